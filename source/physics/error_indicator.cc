// The traction-jump indicator of displacement fields (see
// error_indicator.h).

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_interface_values.h>
#include <deal.II/fe/fe_values_extractors.h>

#include <squeal/physics/error_indicator.h>

#include <cmath>

namespace squeal
{
  namespace physics
  {
    using namespace dealii;

    void
    traction_jump_indicator(
      const Mapping<3>                                      &mapping,
      const DoFHandler<3>                                   &dof_handler,
      const StiffnessOf                                     &stiffness,
      const std::function<double(types::material_id)>       &modulus,
      const std::vector<const PETScWrappers::MPI::Vector *> &solutions,
      std::vector<Vector<float>>                            &eta)
    {
      const unsigned int n_cells =
        dof_handler.get_triangulation().n_active_cells();
      std::vector<Vector<double>> sum(solutions.size(),
                                      Vector<double>(n_cells));
      const QGauss<2>             quadrature(dof_handler.get_fe().degree + 1);
      FEInterfaceValues<3>        interface(mapping,
                                     dof_handler.get_fe(),
                                     quadrature,
                                     update_gradients | update_JxW_values |
                                       update_normal_vectors |
                                       update_quadrature_points);
      const FEValuesExtractors::Vector       u(0);
      const unsigned int                     n_q = quadrature.size();
      std::vector<std::vector<Tensor<2, 3>>> grad(
        2, std::vector<Tensor<2, 3>>(n_q));
      std::vector<std::vector<SymmetricTensor<4, 3>>> C(
        2, std::vector<SymmetricTensor<4, 3>>(n_q));
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int f : cell->face_indices())
            {
              if (cell->at_boundary(f))
                continue;
              const auto neighbor = cell->neighbor(f);
              // each face once: from its finer side, at equal levels from
              // the cell of smaller index
              if (neighbor->has_children())
                continue;
              if (cell->neighbor_is_coarser(f))
                {
                  const auto [nf, nsf] = cell->neighbor_of_coarser_neighbor(f);
                  interface.reinit(
                    cell, f, numbers::invalid_unsigned_int, neighbor, nf, nsf);
                }
              else if (cell->active_cell_index() <
                       neighbor->active_cell_index())
                interface.reinit(cell,
                                 f,
                                 numbers::invalid_unsigned_int,
                                 neighbor,
                                 cell->neighbor_of_neighbor(f),
                                 numbers::invalid_unsigned_int);
              else
                continue;
              const types::material_id ids[2] = {cell->material_id(),
                                                 neighbor->material_id()};
              const double             scale  = cell->diameter() / 24. /
                                   (0.5 * (modulus(ids[0]) + modulus(ids[1])));
              const FEFaceValuesBase<3> &side0 =
                interface.get_fe_face_values(0);
              for (unsigned int side = 0; side < 2; ++side)
                for (unsigned int q = 0; q < n_q; ++q)
                  C[side][q] = stiffness(ids[side], side0.quadrature_point(q));
              for (std::size_t s = 0; s < solutions.size(); ++s)
                {
                  for (unsigned int side = 0; side < 2; ++side)
                    interface.get_fe_face_values(side)[u]
                      .get_function_gradients(*solutions[s], grad[side]);
                  double integral = 0.;
                  for (unsigned int q = 0; q < n_q; ++q)
                    integral += ((C[0][q] * symmetrize(grad[0][q]) -
                                  C[1][q] * symmetrize(grad[1][q])) *
                                 side0.normal_vector(q))
                                  .norm_square() *
                                side0.JxW(q);
                  sum[s][cell->active_cell_index()] += scale * integral;
                  sum[s][neighbor->active_cell_index()] += scale * integral;
                }
            }
      eta.assign(solutions.size(), Vector<float>(n_cells));
      for (std::size_t s = 0; s < solutions.size(); ++s)
        for (unsigned int c = 0; c < n_cells; ++c)
          eta[s][c] = float(std::sqrt(sum[s][c]));
    }
  } // namespace physics
} // namespace squeal
