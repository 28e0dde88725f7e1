// Assembly shared by the contact tests: linear elasticity of an FE_Q^3
// field with one material per material id, and uniform tractions on
// boundary faces, each into its own load vector.
#ifndef squeal_tests_contact_assembly_h
#define squeal_tests_contact_assembly_h

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <squeal/physics/structural_model.h>

#include <functional>
#include <utility>
#include <vector>

/** A uniform traction [Pa] on the faces with boundary id `id`, into `f`. */
struct TractionLoad
{
  dealii::types::boundary_id id;
  dealii::Tensor<1, 3>       traction;
  dealii::Vector<double>    *f;
};

/**
 * K (with @p constraints) and the loads; E_nu(material id) gives (E, nu).
 * If @p K_free is given it receives the unconstrained stiffness, and
 * @p f_free the unconstrained first load.
 */
inline void
assemble_elastic_system(
  const dealii::DoFHandler<3>                                  &dofs,
  const dealii::Mapping<3>                                     &mapping,
  const dealii::AffineConstraints<double>                      &constraints,
  const std::function<std::pair<double, double>(unsigned int)> &E_nu,
  const std::vector<TractionLoad>                              &loads,
  dealii::SparseMatrix<double>                                 &K,
  dealii::SparseMatrix<double> *K_free = nullptr,
  dealii::Vector<double>       *f_free = nullptr)
{
  using namespace dealii;
  const FiniteElement<3> &fe = dofs.get_fe();
  const QGauss<3>         q(fe.degree + 1);
  const QGauss<2>         qf(fe.degree + 1);
  FEValues<3>             fv(mapping,
                 fe,
                 q,
                 update_values | update_gradients | update_JxW_values);
  FEFaceValues<3>    ffv(mapping, fe, qf, update_values | update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  FullMatrix<double> ck(n, n), cm(n, n), none(n, n);
  std::vector<Vector<double>>          cf(loads.size(), Vector<double>(n));
  std::vector<types::global_dof_index> ids(n);
  for (const auto &cell : dofs.active_cell_iterators())
    {
      const auto [E, nu] = E_nu(cell->material_id());
      fv.reinit(cell);
      ck = 0;
      cm = 0;
      squeal::physics::add_cell_elasticity(
        fv, E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu)), 1., ck, cm);
      for (unsigned int l = 0; l < loads.size(); ++l)
        {
          cf[l] = 0;
          for (const auto fn : cell->face_indices())
            if (cell->face(fn)->at_boundary() &&
                cell->face(fn)->boundary_id() == loads[l].id)
              {
                ffv.reinit(cell, fn);
                for (unsigned int k = 0; k < qf.size(); ++k)
                  for (unsigned int i = 0; i < n; ++i)
                    cf[l][i] +=
                      loads[l].traction[fe.system_to_component_index(i).first] *
                      ffv.shape_value(i, k) * ffv.JxW(k);
              }
        }
      cell->get_dof_indices(ids);
      for (unsigned int l = 0; l < loads.size(); ++l)
        constraints.distribute_local_to_global(
          l == 0 ? ck : none, cf[l], ids, K, *loads[l].f);
      if (loads.empty())
        constraints.distribute_local_to_global(ck, ids, K);
      if (K_free)
        K_free->add(ids, ck);
      if (f_free && !loads.empty())
        f_free->add(ids, cf[0]);
    }
}

#endif
