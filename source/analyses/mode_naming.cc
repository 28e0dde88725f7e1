// (n,m+-) names of disc modes: the dominant angular harmonic and the radial
// sign changes of the axial displacement on the disc's naming face, and the
// pad's position on a node or an antinode.

#include <deal.II/base/utilities.h>

#include <squeal/analyses/mode_naming.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <sstream>
#include <vector>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;

    // The name of a disc mode from the axial displacement of the disc's
    // top face: (s, n) with n the dominant angular harmonic on the outer
    // rim and s the sign changes along the radius through the rim's
    // largest amplitude; "+" when the pad (at theta = 0) sits on an
    // antinode, "-" on a node; "in-plane" when the axial motion is small
    // against the in-plane motion.
    std::string
    disc_mode_name(const physics::StructuralModel &model,
                   const scene::Body              &disc,
                   const physics::PETScVector     &re,
                   const physics::PETScVector     &im)
    {
      // (r, theta, u_axial_re, u_axial_im, |u_inplane|^2) at the owned
      // vertices of the disc's naming face, in the disc's frame
      std::vector<std::array<double, 5>> local;
      for (const auto &cell : model.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() && cell->material_id() == disc.id)
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == disc.naming_face)
              for (const auto v : cell->face(f)->vertex_indices())
                {
                  const Point<3> x = cell->face(f)->vertex(v);
                  std::array<types::global_dof_index, 3> d;
                  bool                                   owned = true;
                  for (unsigned int c = 0; c < 3; ++c)
                    {
                      d[c] = cell->face(f)->vertex_dof_index(v, c);
                      owned =
                        owned && model.locally_owned_dofs.is_element(d[c]);
                    }
                  if (!owned)
                    continue;
                  Tensor<1, 3> u_re, u_im;
                  for (unsigned int c = 0; c < 3; ++c)
                    {
                      u_re[c] = re(d[c]);
                      u_im[c] = im(d[c]);
                    }
                  const double a_re = u_re * disc.axis, a_im = u_im * disc.axis;
                  const double inplane =
                    (u_re - a_re * disc.axis).norm_square() +
                    (u_im - a_im * disc.axis).norm_square();
                  const auto [r, theta] = disc.polar(x);
                  local.push_back({{r, theta, a_re, a_im, inplane}});
                }
      std::vector<std::array<double, 5>> all;
      for (const auto &part : Utilities::MPI::all_gather(model.comm, local))
        all.insert(all.end(), part.begin(), part.end());
      double axial = 0, inplane = 0;
      for (const auto &a : all)
        {
          axial += a[2] * a[2] + a[3] * a[3];
          inplane += a[4];
        }
      if (all.empty())
        return "";
      if (axial < 0.25 * inplane)
        return "in-plane";
      // rim: the vertices at the outer radius
      const double                       tol = 1e-6 * disc.outer_radius;
      std::vector<std::array<double, 5>> rim;
      for (const auto &a : all)
        if (std::abs(a[0] - disc.outer_radius) < tol)
          rim.push_back(a);
      unsigned int best_n = 0;
      double       best   = -1;
      for (unsigned int n = 0; n <= rim.size() / 4; ++n)
        {
          std::complex<double> cp = 0, cm = 0;
          for (const auto &a : rim)
            {
              const std::complex<double> w(a[2], a[3]);
              cp += w * std::exp(std::complex<double>(0, -double(n) * a[1]));
              cm += w * std::exp(std::complex<double>(0, double(n) * a[1]));
            }
          const double power = std::norm(cp) + (n > 0 ? std::norm(cm) : 0.);
          if (power > best * (1 + 1e-9))
            {
              best   = power;
              best_n = n;
            }
        }
      // the rim point of largest amplitude and its phase
      const auto                 peak = *std::max_element(rim.begin(),
                                          rim.end(),
                                          [](const auto &a, const auto &b) {
                                            return std::hypot(a[2], a[3]) <
                                                   std::hypot(b[2], b[3]);
                                          });
      const std::complex<double> phase =
        std::conj(std::complex<double>(peak[2], peak[3])) /
        std::abs(std::complex<double>(peak[2], peak[3]));
      // nodal circles: sign changes along the radius at the peak's angle
      std::vector<std::pair<double, double>> line;
      for (const auto &a : all)
        if (std::abs(std::remainder(a[1] - peak[1], 2 * M_PI)) < 1e-6)
          line.emplace_back(a[0],
                            (std::complex<double>(a[2], a[3]) * phase).real());
      std::sort(line.begin(), line.end());
      const double amax    = std::abs(peak[2]) + std::abs(peak[3]);
      unsigned int circles = 0;
      double       last    = 0;
      for (const auto &[r, w] : line)
        if (std::abs(w) > 1e-3 * amax)
          {
            if (last != 0 && (w > 0) != (last > 0))
              ++circles;
            last = w;
          }
      std::string name =
        "(" + std::to_string(circles) + "," + std::to_string(best_n);
      if (best_n > 0)
        {
          // amplitude at the pad (theta = 0) against a quarter wave away
          const auto amplitude = [&](const double theta) {
            double a = 0, d = 1e300;
            for (const auto &x : rim)
              {
                const double dt =
                  std::abs(std::remainder(x[1] - theta, 2 * M_PI));
                if (dt < d)
                  {
                    d = dt;
                    a = std::hypot(x[2], x[3]);
                  }
              }
            return a;
          };
          name += amplitude(0.) >= amplitude(M_PI / (2 * best_n)) ? "+" : "-";
        }
      return name + ")";
    }

    std::string
    mode_name(const physics::StructuralModel &model,
              const parameters::ScalarPoint  &values,
              const physics::PETScVector     &re,
              const physics::PETScVector     &im,
              std::vector<double>            *shares,
              const bool                      with_direction,
              const std::vector<double>      *energy)
    {
      // kinetic-energy shares with the whole mass of the point (every body
      // at its density)
      const std::vector<double> e =
        energy != nullptr ?
          *energy :
          physics::kinetic_energy_by_body(model, values, re, im);
      const auto &bodies = model.scene->bodies;
      const auto  share  = [&](const scene::Body &b) {
        return b.id < e.size() ? e[b.id] : 0.;
      };
      double total = 0.;
      for (const scene::Body &b : bodies)
        total += share(b);
      if (shares != nullptr)
        {
          shares->clear();
          for (const scene::Body &b : bodies)
            shares->push_back(share(b) / total);
        }
      // a disc carrying more than half the energy names the mode (s,n+-);
      // otherwise the body carrying most besides the disc
      const scene::Body *disc = model.scene->disc();
      if (disc != nullptr && share(*disc) > 0.5 * total)
        return disc_mode_name(model, *disc, re, im);
      const scene::Body *carrier = nullptr;
      for (const scene::Body &b : bodies)
        if (&b != disc && (carrier == nullptr || share(b) > share(*carrier)))
          carrier = &b;
      if (carrier == nullptr)
        return "";
      if (!with_direction)
        return carrier->name;
      // the axis along which the body's DoFs move most
      std::array<double, 3>                sum{{0., 0., 0.}};
      std::vector<bool>                    seen(model.n_dofs(), false);
      std::vector<types::global_dof_index> dofs(model.fe.n_dofs_per_cell());
      for (const auto &cell : model.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() && cell->material_id() == carrier->id)
          {
            cell->get_dof_indices(dofs);
            for (unsigned int k = 0; k < dofs.size(); ++k)
              if (!seen[dofs[k]] &&
                  model.locally_owned_dofs.is_element(dofs[k]))
                {
                  seen[dofs[k]] = true;
                  sum[model.fe.system_to_component_index(k).first] +=
                    re[dofs[k]] * re[dofs[k]] + im[dofs[k]] * im[dofs[k]];
                }
          }
      for (double &s : sum)
        s = Utilities::MPI::sum(s, model.comm);
      const auto axis = std::max_element(sum.begin(), sum.end()) - sum.begin();
      return carrier->name + " " + "xyz"[axis];
    }
  } // namespace analyses
} // namespace squeal
