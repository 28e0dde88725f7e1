// The tribology analysis' outputs: the damage, image, map and correlation
// tables, the verdict and the pad face's maps (pad_face_maps.vtu), written
// into the work folder and published at the end. PNG plots are made from them
// by scripts/plot_tribology.py.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <squeal/io/output_directory.h>
#include <squeal/tribology/tribology_analysis.h>

#include "text_input.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

namespace squeal
{
  namespace tribology
  {
    namespace fs = std::filesystem;
    using internal::nan;

    namespace
    {
      // The maps @p named, all on the grid of @p g, as cell data of a
      // deal.II mesh of that grid in the .vtu @p file (NaN where a map has
      // no value).
      void
      write_face_maps(
        const fs::path                                             &file,
        const GridMap                                              &g,
        const std::vector<std::pair<const GridMap *, std::string>> &named)
      {
        dealii::Triangulation<2> tria;
        dealii::GridGenerator::subdivided_hyper_rectangle(
          tria,
          {g.nx, g.ny},
          dealii::Point<2>(g.x0, g.y0),
          dealii::Point<2>(g.x0 + g.nx * g.h, g.y0 + g.ny * g.h));
        dealii::DataOut<2> data_out;
        data_out.attach_triangulation(tria);
        std::vector<dealii::Vector<double>> fields;
        fields.reserve(named.size());
        for (const auto &[m, name] : named)
          {
            fields.emplace_back(tria.n_active_cells());
            for (const auto &cell : tria.active_cell_iterators())
              {
                const auto c = cell->center();
                const long k = g.cell_of(c[0], c[1]);
                fields.back()[cell->active_cell_index()] =
                  (k >= 0 && !m->values.empty()) ? m->values[k] : nan;
              }
            data_out.add_data_vector(fields.back(),
                                     name,
                                     dealii::DataOut<2>::type_cell_data);
          }
        data_out.build_patches();
        io::OutputFile vtu(file);
        data_out.write_vtu(vtu);
        if (!vtu)
          throw std::runtime_error("cannot write " + file.string());
      }
    } // namespace

    void
    TribologyAnalysis::output_results()
    {
      const fs::path dir(work_dir);
      const auto     write_csv =
        [&](const std::string                         &name,
            const std::string                         &header,
            const std::function<void(std::ostream &)> &body) {
          io::OutputFile out(dir / name);
          out << std::setprecision(10) << header << '\n';
          body(out);
          if (!out)
            throw std::runtime_error("cannot write " + (dir / name).string());
        };
      if (history.n_nodes() > 0)
        {
          write_csv(
            "damage.csv",
            "node,x_m,y_m,z_m,s_m,r_m,D_star_Pa_pow_m,D_miner,max_tau_eq_Pa,"
            "n_cycles,crossland_Pa,sqrt_J2a_Pa,sigma_H_max_Pa,mean_p_Pa,"
            "max_p_Pa,p_range_rel,separated_fraction,stick_fraction,"
            "slip_fraction,cycles_per_s",
            [&](std::ostream &o) {
              for (std::size_t i = 0; i < history.n_nodes(); ++i)
                {
                  const auto &x  = history.coordinates[i];
                  const auto  uv = history.face_coordinates(i);
                  const auto &s  = statistics[i];
                  o << i << ',' << x[0] << ',' << x[1] << ',' << x[2] << ','
                    << uv[0] << ',' << uv[1] << ',' << findley[i].relative
                    << ',' << findley[i].miner << ',' << findley[i].max_tau_eq
                    << ',' << findley[i].n_cycles << ',' << crossland[i].index
                    << ',' << crossland[i].sqrt_j2_amplitude << ','
                    << crossland[i].hydrostatic_max << ',' << s.mean_pressure
                    << ',' << s.max_pressure << ',' << s.relative_oscillation
                    << ',' << s.separated_fraction << ',' << s.stick_fraction
                    << ',' << s.slip_fraction << ',' << s.cycles_per_second
                    << '\n';
                }
            });
          // Sensitivity of the damage map's ranking to k and m.
          std::vector<double> reference(history.n_nodes());
          for (std::size_t i = 0; i < history.n_nodes(); ++i)
            reference[i] = findley[i].relative;
          write_csv("damage_sensitivity.csv",
                    "k,m,spearman_to_default,max_over_min",
                    [&](std::ostream &o) {
                      FindleyParameters f = prm.damage.findley;
                      std::vector<std::pair<double, double>> cases;
                      for (double k : prm.damage.sensitivity_k)
                        cases.emplace_back(k, f.m);
                      for (double m : prm.damage.sensitivity_m)
                        cases.emplace_back(f.k, m);
                      for (const auto &[k, m] : cases)
                        {
                          f.k = k;
                          f.m = m;
                          std::vector<double> d(history.n_nodes());
                          for (std::size_t i = 0; i < d.size(); ++i)
                            d[i] =
                              findley_damage(history.p_N[i], history.t_T1[i], f)
                                .relative;
                          const auto [lo, hi] =
                            std::minmax_element(d.begin(), d.end());
                          o << k << ',' << m << ',' << spearman(reference, d)
                            << ',' << (*lo > 0. ? *hi / *lo : INFINITY) << '\n';
                        }
                    });
        }
      if (!images.empty())
        write_csv("images.csv",
                  "file,pixel_size_m,width_px,height_px,cracks,"
                  "crack_length_mm,crack_length_per_area_mm_per_mm2,"
                  "cracks_per_mm2,exfoliated_fraction,micro,meso,macro,"
                  "micro_area_mm2,meso_area_mm2,macro_area_mm2",
                  [&](std::ostream &o) {
                    for (const auto &r : images)
                      {
                        const double px = r.placement.pixel_size;
                        const double mm2 =
                          r.cracks.mask.total() * px * px * 1e6;
                        o << fs::path(r.file).filename().string() << ',' << px
                          << ',' << r.cracks.mask.cols << ','
                          << r.cracks.mask.rows << ','
                          << r.cracks.lengths.size() << ','
                          << r.cracks.total_length * px * 1e3 << ','
                          << r.cracks.total_length * px * 1e3 / mm2 << ','
                          << r.cracks.lengths.size() / mm2 << ','
                          << r.exfoliations.area_fraction << ',' << r.micro
                          << ',' << r.meso << ',' << r.macro << ','
                          << r.micro_area * 1e6 << ',' << r.meso_area * 1e6
                          << ',' << r.macro_area * 1e6 << '\n';
                      }
                  });
      const GridMap &g     = log_damage;
      const auto     value = [](const GridMap &m, std::size_t c) {
        return m.values.empty() ? nan : m.values[c];
      };
      write_csv("maps.csv",
                "i,j,s_m,r_m,log10_damage,p_range_rel,separated_fraction,"
                "crack_length_per_area_mm_per_mm2,cracks_per_mm2,"
                "exfoliated_fraction,coverage",
                [&](std::ostream &o) {
                  for (unsigned int j = 0; j < g.ny; ++j)
                    for (unsigned int i = 0; i < g.nx; ++i)
                      {
                        const std::size_t c = i + g.nx * j;
                        o << i << ',' << j << ',' << g.x0 + (i + 0.5) * g.h
                          << ',' << g.y0 + (j + 0.5) * g.h << ',' << value(g, c)
                          << ',' << value(p_oscillation, c) << ','
                          << value(separated, c) << ','
                          << value(crack_density, c) << ','
                          << value(crack_count, c) << ','
                          << value(exfoliated, c) << ',' << value(coverage, c)
                          << '\n';
                      }
                });
      if (!correlation_rows.empty())
        {
          write_csv("correlation.csv",
                    "statistic,value,p_value,cells,shifts",
                    [&](std::ostream &o) {
                      for (const auto &r : correlation_rows)
                        o << r[0] << ',' << r[1] << ',' << r[2] << ',' << r[3]
                          << ',' << r[4] << '\n';
                    });
          write_csv("roc.csv",
                    "false_positive_rate,true_positive_rate",
                    [&](std::ostream &o) {
                      for (const auto &[f, t] : roc)
                        o << f << ',' << t << '\n';
                    });
          io::OutputFile(dir / "verdict.txt") << verdict << '\n';
        }

      // ParaView: the maps as cell data on the pad-face grid.
      write_face_maps(dir / "pad_face_maps.vtu",
                      g,
                      {{&log_damage, "log10_damage_Findley"},
                       {&p_oscillation, "pressure_range_relative"},
                       {&separated, "separated_fraction"},
                       {&crack_density, "crack_length_per_area_mm_per_mm2"},
                       {&crack_count, "cracks_per_mm2"},
                       {&exfoliated, "exfoliated_fraction"}});

      io::check_writes(MPI_COMM_SELF);
      io::publish_directory(work_dir, prm.output.directory);
      std::cout << "Results in " << prm.output.directory << std::endl;
    }
  } // namespace tribology
} // namespace squeal
