// The tribology analysis: contact-stress histories -> fatigue-damage indices
// per pad node; SEM images -> crack and exfoliation maps; both on one grid
// of the pad face -> correlation with honest (toroidal-shift) significance.
//
// The parameters follow the rest of squeal: one struct per subsection, every
// entry with a default, a range and help with SI units. Results go into
// DIRECTORY.partial, renamed at the end, so an interrupted run never looks
// like a finished one and never replaces an earlier result.
#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <squeal/io/output_directory.h>
#include <squeal/parameters/parameters.h>
#include <squeal/tribology/tribology_analysis.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "text_input.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <tuple>

namespace squeal
{
  namespace tribology
  {
    namespace fs = std::filesystem;

    using internal::nan;
    using internal::resolve;

    namespace
    {
      // Cells of the correlation grid over an extent of @p wx x @p wy [m]
      // at cells of @p h [m]; a dozen maps of doubles share the grid.
      // @throws std::runtime_error naming Correlation/Cell size if they
      // would not fit in memory (more than 1e8 cells: about 10 GB)
      std::pair<unsigned int, unsigned int>
      grid_cells(const double wx, const double wy, const double h)
      {
        const double nx = std::max(1., std::ceil(wx / h - 1e-6)),
                     ny = std::max(1., std::ceil(wy / h - 1e-6));
        if (!(nx * ny <= 1e8))
          {
            std::ostringstream m;
            m << "Correlation/Cell size = " << h << " m gives " << nx << " x "
              << ny << " cells over the " << wx << " x " << wy
              << " m pad face: more than the 1e8 (about 10 GB of maps) a run "
                 "can hold; take a larger cell";
            throw std::runtime_error(m.str());
          }
        return {static_cast<unsigned int>(nx), static_cast<unsigned int>(ny)};
      }
    } // namespace

    // ---------------------------------------------------------------------
    // The analysis

    TribologyAnalysis::TribologyAnalysis(const TribologyParameters &prm,
                                         const ParameterHandler    &handler)
      : prm(prm)
      , handler(handler)
    {}

    void
    TribologyAnalysis::setup()
    {
      work_dir =
        io::partial_directory(prm.output.directory, prm.output.overwrite);
      io::fresh_directory(work_dir, "images");
      io::OutputFile out(fs::path(work_dir) / "parameters.prm");
      handler.print_parameters(out, ParameterHandler::PRM);

      if (prm.history.file == "synthetic")
        {
          const SyntheticHistory &s = prm.synthetic_history;
          history                   = synthetic_squeal_history(s.nodes_per_side,
                                             s.samples,
                                             s.sampling_rate,
                                             s.frequency,
                                             s.mean_pressure,
                                             s.friction_coefficient,
                                             s.pad_size,
                                             s.pad_radius,
                                             s.trailing_amplitude);
          io::write_contact_history(
            (fs::path(work_dir) / "contact_history.h5").string(), history);
          std::cout << "Synthetic contact history: " << history.n_nodes()
                    << " nodes x " << history.n_samples() << " samples at "
                    << history.sampling_rate << " Hz (written to "
                    << "contact_history.h5)" << std::endl;
        }
      else if (!prm.history.file.empty())
        {
          history = io::read_contact_history(
            resolve(prm.base_directory, prm.history.file));
          std::cout << "Contact history " << prm.history.file << ": "
                    << history.n_nodes() << " nodes x " << history.n_samples()
                    << " samples at " << history.sampling_rate << " Hz"
                    << std::endl;
        }
      if (history.n_nodes() > 0)
        {
          const std::string where =
            "Contact history/File '" + prm.history.file + "'";
          if (prm.history.face.empty() && history.face_names.size() > 1)
            throw std::runtime_error(
              where + " holds " + std::to_string(history.face_names.size()) +
              " pad faces (" + history.face_list() +
              "): set Contact history/Face to one of them");
          if (!prm.history.face.empty())
            try
              {
                history.keep_face(prm.history.face);
              }
            catch (const std::exception &e)
              {
                throw std::runtime_error(where +
                                         ", Contact history/Face: " + e.what());
              }
          if (!history.face_names.empty())
            std::cout << "Pad face '" << history.face_names.front()
                      << "': " << history.n_nodes() << " nodes" << std::endl;
        }
      if (history.n_nodes() > 0 && prm.history.start_time > 0.)
        {
          const std::size_t first = std::lower_bound(history.time.begin(),
                                                     history.time.end(),
                                                     prm.history.start_time) -
                                    history.time.begin();
          if (first + 2 > history.n_samples())
            throw std::runtime_error(
              "Contact history/Start time leaves fewer than 2 samples");
          const auto cut = [first](auto &rows) {
            for (auto &r : rows)
              r.erase(r.begin(), r.begin() + first);
          };
          history.time.erase(history.time.begin(),
                             history.time.begin() + first);
          cut(history.p_N);
          cut(history.t_T1);
          cut(history.t_T2);
          cut(history.slip_velocity);
          cut(history.status);
        }

      // The grid of the pad face: the nodes' bounding box.
      if (history.n_nodes() > 0)
        {
          double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
          for (std::size_t i = 0; i < history.n_nodes(); ++i)
            {
              const auto uv = history.face_coordinates(i);
              for (int d = 0; d < 2; ++d)
                {
                  lo[d] = std::min(lo[d], uv[d]);
                  hi[d] = std::max(hi[d], uv[d]);
                }
            }
          const double h   = prm.correlation.cell_size;
          const double eps = 1e-9 * h;
          // Centre the grid on the face.
          const auto [nx, ny] = grid_cells(hi[0] - lo[0], hi[1] - lo[1], h);
          log_damage          = GridMap(nx,
                               ny,
                               0.5 * (lo[0] + hi[0]) - 0.5 * nx * h - eps,
                               0.5 * (lo[1] + hi[1]) - 0.5 * ny * h - eps,
                               h + 2. * eps / std::max(nx, ny));
        }
    }

    void
    TribologyAnalysis::compute_damage()
    {
      if (history.n_nodes() == 0)
        return;
      const std::size_t n = history.n_nodes();
      findley.resize(n);
      crossland.resize(n);
      statistics.resize(n);
      std::size_t next_report = n / 10;
      for (std::size_t i = 0; i < n; ++i)
        {
          findley[i] =
            findley_damage(history.p_N[i], history.t_T1[i], prm.damage.findley);
          crossland[i]  = crossland_index(history.p_N[i],
                                         history.t_T1[i],
                                         prm.damage.poisson_ratio,
                                         prm.damage.crossland_alpha);
          statistics[i] = node_statistics(history.p_N[i],
                                          history.status[i],
                                          history.sampling_rate);
          if (n >= 1000 && i + 1 >= next_report)
            {
              std::cout << "  damage: " << (100 * (i + 1)) / n << " % of " << n
                        << " nodes" << std::endl;
              next_report += n / 10;
            }
        }
      // Node values onto the grid: the mean over the nodes in a cell; a
      // cell without a node takes its nearest node's value if that lies
      // within 1.5 node spacings (a grid finer than the contact mesh).
      const std::size_t   n_cells = log_damage.values.size();
      std::vector<double> sum(n_cells, 0.), osc(n_cells, 0.), sep(n_cells, 0.),
        count(n_cells, 0.);
      const auto node_log_damage = [&](std::size_t i) {
        return std::log10(std::max(findley[i].relative, 1e-300));
      };
      for (std::size_t i = 0; i < n; ++i)
        {
          const auto uv = history.face_coordinates(i);
          const long c  = log_damage.cell_of(uv[0], uv[1]);
          if (c < 0)
            continue;
          sum[c] += node_log_damage(i);
          osc[c] += statistics[i].relative_oscillation;
          sep[c] += statistics[i].separated_fraction;
          count[c] += 1.;
        }
      const GridMap &g       = log_damage;
      const double   spacing = std::sqrt(g.nx * g.ny * g.h * g.h / n);
      for (unsigned int j = 0; j < g.ny; ++j)
        for (unsigned int i = 0; i < g.nx; ++i)
          {
            const std::size_t c = i + g.nx * j;
            if (count[c] > 0.)
              continue;
            const double x = g.x0 + (i + 0.5) * g.h, y = g.y0 + (j + 0.5) * g.h;
            double       best = 1e300;
            std::size_t  k    = 0;
            for (std::size_t m = 0; m < n; ++m)
              {
                const auto   uv = history.face_coordinates(m);
                const double d2 =
                  (uv[0] - x) * (uv[0] - x) + (uv[1] - y) * (uv[1] - y);
                if (d2 < best)
                  {
                    best = d2;
                    k    = m;
                  }
              }
            if (std::sqrt(best) <= 1.5 * spacing)
              {
                sum[c]   = node_log_damage(k);
                osc[c]   = statistics[k].relative_oscillation;
                sep[c]   = statistics[k].separated_fraction;
                count[c] = 1.;
              }
          }
      p_oscillation = separated = log_damage.empty_like();
      for (std::size_t c = 0; c < n_cells; ++c)
        if (count[c] > 0.)
          {
            log_damage.values[c]    = sum[c] / count[c];
            p_oscillation.values[c] = osc[c] / count[c];
            separated.values[c]     = sep[c] / count[c];
          }
      double      d_max = 0., d_min = 1e300;
      std::size_t i_max = 0;
      for (std::size_t i = 0; i < n; ++i)
        {
          if (findley[i].relative > d_max)
            {
              d_max = findley[i].relative;
              i_max = i;
            }
          d_min = std::min(d_min, findley[i].relative);
        }
      const auto uv = history.face_coordinates(i_max);
      std::cout << "Findley damage D* over " << n << " nodes: max "
                << std::setprecision(4) << d_max << " Pa^m at (s, r) = ("
                << uv[0] * 1e3 << ", " << uv[1] * 1e3 << ") mm, min " << d_min
                << ", max/min " << (d_min > 0. ? d_max / d_min : INFINITY)
                << std::endl;
    }

    void
    TribologyAnalysis::make_synthetic_images()
    {
      // Fields of view tiling the grid; cracks and exfoliations drawn with a
      // density that follows the rank of the cell's damage.
      const SyntheticImages &s  = prm.synthetic_images;
      const GridMap         &g  = log_damage;
      const double           wx = g.nx * g.h / s.fields_per_side,
                   wy           = g.ny * g.h / s.fields_per_side;
      const double        pixel = std::max(wx, wy) / s.image_size;
      std::vector<double> finite;
      for (double v : g.values)
        if (std::isfinite(v))
          finite.push_back(v);
      std::sort(finite.begin(), finite.end());
      const auto rank = [&](double v) {
        if (!std::isfinite(v) || finite.size() < 2)
          return 0.;
        return double(std::lower_bound(finite.begin(), finite.end(), v) -
                      finite.begin()) /
               (finite.size() - 1);
      };
      std::mt19937                           rng(s.seed);
      std::uniform_real_distribution<double> U(0., 1.);
      for (unsigned int fy = 0; fy < s.fields_per_side; ++fy)
        for (unsigned int fx = 0; fx < s.fields_per_side; ++fx)
          {
            const double s0 = g.x0 + fx * wx, r1 = g.y0 + (fy + 1) * wy;
            // pixel (x, y) -> face (s0 + x p, r1 - y p): displayed upright
            const cv::Matx23d A(
              pixel, 0., s0 + 0.5 * pixel, 0., -pixel, r1 - 0.5 * pixel);
            const cv::Size size(cvRound(wx / pixel), cvRound(wy / pixel));
            std::vector<SyntheticCrack> cracks;
            std::vector<SyntheticBlob>  blobs;
            const double                cell_px = g.h / pixel;
            for (unsigned int j = 0; j < g.ny; ++j)
              for (unsigned int i = 0; i < g.nx; ++i)
                {
                  const double cx = (g.x0 + (i + 0.5) * g.h - s0) / pixel - 0.5,
                               cy =
                                 (r1 - (g.y0 + (j + 0.5) * g.h)) / pixel - 0.5;
                  if (cx < 0 || cy < 0 || cx >= size.width || cy >= size.height)
                    continue;
                  const double                   q = rank(g(i, j));
                  std::poisson_distribution<int> nc(
                    std::max(1e-9, s.cracks_per_cell * q * q)),
                    nb(std::max(1e-9, s.blobs_per_cell * q));
                  for (int k = nc(rng); k > 0; --k)
                    {
                      const double len = (0.3 + 0.4 * U(rng)) * cell_px,
                                   ang = M_PI * U(rng);
                      const cv::Point2d mid(cx + (U(rng) - 0.5) * 0.5 * cell_px,
                                            cy +
                                              (U(rng) - 0.5) * 0.5 * cell_px);
                      const cv::Point2d d(0.5 * len * std::cos(ang),
                                          0.5 * len * std::sin(ang));
                      cracks.push_back(
                        {{mid - d,
                          mid,
                          mid + d + cv::Point2d(0.1 * len * std::sin(ang), 0.)},
                         2. + U(rng)});
                    }
                  for (int k = nb(rng); k > 0; --k)
                    blobs.push_back(
                      {cv::Point2d(cx + (U(rng) - 0.5) * 0.4 * cell_px,
                                   cy + (U(rng) - 0.5) * 0.4 * cell_px),
                       cv::Size2d((0.15 + 0.1 * U(rng)) * cell_px,
                                  (0.12 + 0.05 * U(rng)) * cell_px),
                       180. * U(rng)});
                }
            const SyntheticSurface surf =
              draw_synthetic_surface(size,
                                     cracks,
                                     blobs,
                                     0.3,
                                     0.2,
                                     1.0,
                                     0.02,
                                     s.seed + fx + s.fields_per_side * fy);
            const std::string name =
              "field_" + std::to_string(fx) + "_" + std::to_string(fy);
            const fs::path png =
              fs::path(work_dir) / "images" / (name + ".png");
            cv::Mat u8;
            surf.image.convertTo(u8, CV_8U, 255.);
            if (!cv::imwrite(png.string(), u8))
              throw std::runtime_error("cannot write " + png.string());
            io::OutputFile side(fs::path(png).replace_extension(".prm"));
            side << std::setprecision(17) << "# synthetic field of view\n"
                 << "set Pixel size = " << pixel << "\n"
                 << "set Placement = affine\n"
                 << "set Affine = " << A(0, 0) << ", " << A(0, 1) << ", "
                 << A(0, 2) << "; " << A(1, 0) << ", " << A(1, 1) << ", "
                 << A(1, 2) << "\n";
            image_files.push_back(png.string());
          }
      std::cout << "Synthetic SEM fields: " << image_files.size() << " of "
                << cvRound(wx / pixel) << " x " << cvRound(wy / pixel)
                << " px at " << pixel * 1e6 << " um/px" << std::endl;
    }

    void
    TribologyAnalysis::analyse_images()
    {
      if (prm.images.files.size() == 1 && prm.images.files[0] == "synthetic")
        make_synthetic_images();
      else
        for (const auto &f : prm.images.files)
          image_files.push_back(resolve(prm.base_directory, f));

      const std::string folder =
        prm.images.sidecar_folder.empty() ?
          "" :
          resolve(prm.base_directory, prm.images.sidecar_folder);
      for (const std::string &file : image_files)
        {
          // OpenCV's and the allocator's failures named with the image
          try
            {
              ImageResult r;
              r.file                    = file;
              const std::string sidecar = sidecar_of(file, folder);
              if (!fs::exists(sidecar))
                throw std::runtime_error(
                  "image '" + file + "' has no sidecar '" + sidecar +
                  "' (pixel size and placement on the pad face)");
              const cv::Mat img = load_grey_image(file);
              r.placement       = read_image_placement(sidecar, img);
              if (!r.placement.reference_image.empty())
                {
                  // Refine: reference pixels -> image pixels by ECC, starting
                  // from the two sidecars' placements.
                  const cv::Mat ref =
                    load_grey_image(r.placement.reference_image);
                  const ImagePlacement rp = read_image_placement(
                    sidecar_of(r.placement.reference_image, folder), ref);
                  r.placement = refine_placement(img, r.placement, ref, rp);
                  std::cout
                    << "  " << fs::path(file).filename().string()
                    << ": placement refined by ECC against "
                    << fs::path(r.placement.reference_image).filename().string()
                    << std::endl;
                }
              r.exfoliations =
                detect_exfoliations(img, prm.images.exfoliations);
              cv::Mat exclude;
              // the ridge filter answers up to about its largest scale outside
              // a blob's edge
              const int grow =
                cvCeil(*std::max_element(prm.images.cracks.scales.begin(),
                                         prm.images.cracks.scales.end())) +
                2;
              cv::dilate(r.exfoliations.mask,
                         exclude,
                         cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                                   cv::Size(2 * grow + 1,
                                                            2 * grow + 1)));
              r.cracks = detect_cracks(img, prm.images.cracks, exclude);
              const double px2 =
                r.placement.pixel_size * r.placement.pixel_size;
              for (double a : r.exfoliations.areas)
                {
                  const double m2 = a * px2;
                  if (m2 < prm.images.micro_max_area)
                    {
                      ++r.micro;
                      r.micro_area += m2;
                    }
                  else if (m2 > prm.images.macro_min_area)
                    {
                      ++r.macro;
                      r.macro_area += m2;
                    }
                  else
                    {
                      ++r.meso;
                      r.meso_area += m2;
                    }
                }
              const double area_mm2 = img.total() * px2 * 1e6;
              std::cout << "  " << fs::path(file).filename().string() << ": "
                        << img.cols << " x " << img.rows << " px at "
                        << r.placement.pixel_size * 1e6 << " um/px; "
                        << r.cracks.lengths.size() << " cracks, "
                        << r.cracks.total_length * r.placement.pixel_size * 1e3
                        << " mm, L_A = "
                        << r.cracks.total_length * r.placement.pixel_size *
                             1e3 / area_mm2
                        << " mm/mm^2; exfoliated " << std::setprecision(3)
                        << 100. * r.exfoliations.area_fraction << " % ("
                        << r.micro << " micro, " << r.meso << " meso, "
                        << r.macro << " macro)" << std::setprecision(6)
                        << std::endl;
              write_overlay((fs::path(work_dir) / "images" /
                             (fs::path(file).stem().string() + "_overlay.png"))
                              .string(),
                            img,
                            r.cracks,
                            r.exfoliations);
              images.push_back(std::move(r));
            }
          catch (const cv::Exception &e)
            {
              throw std::runtime_error("image '" + file +
                                       "': OpenCV failed in " + e.func + ": " +
                                       e.err);
            }
          catch (const std::bad_alloc &)
            {
              throw std::runtime_error(
                "image '" + file +
                "': out of memory; the image is too large for this machine "
                "(crop or downscale it, and adjust its Pixel size)");
            }
        }
    }

    void
    TribologyAnalysis::build_maps()
    {
      if (images.empty())
        return;
      if (log_damage.nx == 0)
        {
          // No history: the grid covers the images' footprints.
          double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
          for (const auto &r : images)
            {
              const cv::Mat &m = r.cracks.mask;
              for (const cv::Point2d p : {cv::Point2d(0, 0),
                                          cv::Point2d(m.cols, 0),
                                          cv::Point2d(0, m.rows),
                                          cv::Point2d(m.cols, m.rows)})
                {
                  const cv::Matx23d &A = r.placement.pixel_to_face;
                  const double s = A(0, 0) * p.x + A(0, 1) * p.y + A(0, 2),
                               t = A(1, 0) * p.x + A(1, 1) * p.y + A(1, 2);
                  lo[0]          = std::min(lo[0], s);
                  hi[0]          = std::max(hi[0], s);
                  lo[1]          = std::min(lo[1], t);
                  hi[1]          = std::max(hi[1], t);
                }
            }
          const double h      = prm.correlation.cell_size;
          const auto [nx, ny] = grid_cells(hi[0] - lo[0], hi[1] - lo[1], h);
          log_damage          = GridMap(nx, ny, lo[0], lo[1], h);
          p_oscillation = separated = log_damage.empty_like();
        }
      GridMap length = log_damage.empty_like(), count = length, blob = length,
              covered = length;
      for (GridMap *m : {&length, &count, &blob, &covered})
        std::fill(m->values.begin(), m->values.end(), 0.);
      for (const auto &r : images)
        {
          const cv::Matx23d &A  = r.placement.pixel_to_face;
          const double       px = r.placement.pixel_size;
          const cv::Mat     &L  = r.cracks.length_per_pixel;
          for (int y = 0; y < L.rows; ++y)
            for (int x = 0; x < L.cols; ++x)
              {
                const long c =
                  log_damage.cell_of(A(0, 0) * x + A(0, 1) * y + A(0, 2),
                                     A(1, 0) * x + A(1, 1) * y + A(1, 2));
                if (c < 0)
                  continue;
                covered.values[c] += px * px;
                length.values[c] += L.at<float>(y, x) * px;
                blob.values[c] +=
                  r.exfoliations.mask.at<uchar>(y, x) ? px * px : 0.;
              }
          for (const cv::Point2d &p : r.cracks.centroids)
            {
              const long c =
                log_damage.cell_of(A(0, 0) * p.x + A(0, 1) * p.y + A(0, 2),
                                   A(1, 0) * p.x + A(1, 1) * p.y + A(1, 2));
              if (c >= 0)
                count.values[c] += 1.;
            }
        }
      crack_density = crack_count = exfoliated = coverage =
        log_damage.empty_like();
      const double cell_area = log_damage.h * log_damage.h;
      for (std::size_t c = 0; c < covered.values.size(); ++c)
        {
          coverage.values[c] = std::min(1., covered.values[c] / cell_area);
          // a cell counts when at least half of it was imaged
          if (covered.values[c] < 0.5 * cell_area)
            continue;
          const double mm2        = covered.values[c] * 1e6;
          crack_density.values[c] = length.values[c] * 1e3 / mm2;
          crack_count.values[c]   = count.values[c] / mm2;
          exfoliated.values[c]    = blob.values[c] / covered.values[c];
        }
    }

    void
    TribologyAnalysis::correlate()
    {
      if (images.empty() || history.n_nodes() == 0)
        return;
      std::vector<double> imaged;
      for (double v : crack_density.values)
        if (std::isfinite(v))
          imaged.push_back(v);
      if (imaged.size() < 4)
        throw std::runtime_error(
          "fewer than 4 grid cells are both imaged and in contact: no "
          "correlation (check the images' placement or Correlation/Cell "
          "size)");
      double threshold = prm.correlation.cracked_threshold;
      if (threshold < 0.)
        {
          std::nth_element(imaged.begin(),
                           imaged.begin() + imaged.size() / 2,
                           imaged.end());
          threshold = imaged[imaged.size() / 2];
        }
      GridMap cracked = crack_density.empty_like();
      for (std::size_t c = 0; c < cracked.values.size(); ++c)
        if (std::isfinite(crack_density.values[c]))
          cracked.values[c] = crack_density.values[c] > threshold ? 1. : 0.;

      // A map that does not vary over the paired cells has no ranks: the
      // statistics would be NaN and read as "no link".
      for (const auto &[map, name, advice] :
           {std::tuple(&log_damage,
                       "fatigue-damage map",
                       "the contact history may be too short or the "
                       "load too steady for any damage to differ"),
            std::tuple(&crack_density,
                       "crack-density map",
                       "no crack was found in the images, or every "
                       "cell holds the same; check Images/Crack contrast "
                       "and Crack scales")})
        {
          double      lo = std::numeric_limits<double>::max(), hi = -lo;
          std::size_t n = 0;
          for (std::size_t c = 0; c < map->values.size(); ++c)
            if (std::isfinite(log_damage.values[c]) &&
                std::isfinite(crack_density.values[c]))
              {
                lo = std::min(lo, map->values[c]);
                hi = std::max(hi, map->values[c]);
                ++n;
              }
          if (n > 0 && !(hi > lo))
            {
              std::ostringstream m;
              m << "correlation: the " << name << " is " << lo << " in all "
                << n
                << " cells that are both in contact and imaged; a rank "
                   "correlation needs it to vary ("
                << advice << ")";
              throw std::runtime_error(m.str());
            }
        }
      const auto sp = [](const std::vector<double> &a,
                         const std::vector<double> &b) {
        return spearman(a, b);
      };
      const auto pe = [](const std::vector<double> &a,
                         const std::vector<double> &b) {
        return pearson(a, b);
      };
      const auto au = [](const std::vector<double> &a,
                         const std::vector<double> &b) {
        return roc_auc(a, b);
      };
      const ToroidalTest ts      = toroidal_test(log_damage, crack_density, sp);
      const ToroidalTest tp      = toroidal_test(log_damage, crack_density, pe);
      const ToroidalTest ta      = toroidal_test(log_damage, cracked, au);
      const ToroidalTest te      = toroidal_test(log_damage, exfoliated, sp);
      const double       moran_d = morans_i(log_damage),
                   moran_c       = morans_i(crack_density);
      std::size_t n_pairs        = 0;
      for (std::size_t c = 0; c < cracked.values.size(); ++c)
        n_pairs += std::isfinite(cracked.values[c]) &&
                   std::isfinite(log_damage.values[c]);
      const auto row =
        [&](const std::string &name, double v, double p, unsigned int shifts) {
          std::ostringstream a, b;
          a << std::setprecision(6) << v;
          b << std::setprecision(6) << p;
          correlation_rows.push_back({name,
                                      a.str(),
                                      b.str(),
                                      std::to_string(n_pairs),
                                      std::to_string(shifts)});
        };
      row("spearman_log_damage_vs_crack_density",
          ts.observed,
          ts.p_value,
          ts.n_shifts);
      row("pearson_log_damage_vs_crack_density",
          tp.observed,
          tp.p_value,
          tp.n_shifts);
      row("roc_auc_log_damage_predicts_cracked",
          ta.observed,
          ta.p_value,
          ta.n_shifts);
      row("spearman_log_damage_vs_exfoliated_fraction",
          te.observed,
          te.p_value,
          te.n_shifts);
      row("morans_i_log_damage", moran_d, nan, 0);
      row("morans_i_crack_density", moran_c, nan, 0);
      row("cracked_threshold_mm_per_mm2", threshold, nan, 0);
      roc = roc_curve(log_damage.values, cracked.values);

      std::ostringstream v;
      v << std::setprecision(2) << std::fixed;
      const bool significant = ts.p_value < 0.05 && ts.observed > 0.;
      v << "Verdict: over " << n_pairs << " cells of "
        << prm.correlation.cell_size * 1e3 << " mm that are both in contact "
        << "and imaged, the fatigue-damage map "
        << (significant ? "does" : "does not")
        << " predict where the cracks are: Spearman rho = " << ts.observed
        << " (toroidal-shift p = " << std::setprecision(3) << ts.p_value
        << " over " << ts.n_shifts
        << " shifts), ROC AUC = " << std::setprecision(2) << ta.observed
        << " for cells above " << threshold
        << " mm/mm^2 of cracks (p = " << std::setprecision(3) << ta.p_value
        << ")." << std::setprecision(2)
        << " Both maps are spatially smooth (Moran's I " << moran_d
        << " for damage, " << moran_c
        << " for cracks), so these p-values come from shifting one map "
           "against the other rather than from formulas that assume "
           "independent cells, which would overstate the evidence. "
        << (significant ?
              "The cracks concentrate where the simulated stress "
              "oscillations are largest, as a fatigue reading predicts." :
              "The data do not support a fatigue link at this grid size; "
              "more images, a finer registration or another damage "
              "parameter set (see damage_sensitivity.csv) may change this.");
      verdict = v.str();
    }

    void
    TribologyAnalysis::run()
    {
      // Errors are caught inside the timer's scope and rethrown after it, so
      // that the timer is not destroyed while an exception is in flight.
      std::string failure;
      {
        dealii::TimerOutput timer(std::cout,
                                  dealii::TimerOutput::summary,
                                  dealii::TimerOutput::wall_times);
        const auto          phase = [&](const char *name, auto &&work) {
          if (!failure.empty())
            return;
          dealii::TimerOutput::Scope t(timer, name);
          try
            {
              work();
            }
          catch (const std::exception &e)
            {
              failure = e.what();
            }
        };
        phase("read inputs", [&] { setup(); });
        phase("damage (rainflow, Findley, Crossland)",
              [&] { compute_damage(); });
        phase("images (cracks, exfoliations)", [&] {
          analyse_images();
          build_maps();
        });
        phase("correlation", [&] { correlate(); });
        if (failure.empty() && !verdict.empty())
          std::cout << '\n' << verdict << "\n\n";
        phase("output", [&] { output_results(); });
      }
      if (!failure.empty())
        throw std::runtime_error(failure);
    }
  } // namespace tribology
} // namespace squeal
