// Assembly of the structural matrices of a scene: linear elasticity per body
// (the pad separately, so that a sweep over its modulus rescales one matrix),
// the support's springs and the friction interface. All matrices share one
// sparsity pattern so that combining them is a cheap MatAXPY.

#include <deal.II/base/qprojector.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_refinement.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <squeal/physics/elastic_law.h>
#include <squeal/physics/interface_coupling.h>
#include <squeal/physics/structural_model.h>

#include <petscmat.h>

#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace squeal
{
  namespace physics
  {
    using namespace dealii;

    StructuralModel::StructuralModel(const parameters::AllParameters &prm,
                                     MPI_Comm                         comm)
      : prm(prm)
      , comm(comm)
      , triangulation(comm,
                      Triangulation<3>::none,
                      false,
                      parallel::shared::Triangulation<3>::partition_metis)
      , fe(FE_Q<3>(prm.mesh.fe_degree), 3)
      , mapping(prm.mesh.fe_degree)
      , dof_handler(triangulation)
    {}

    void
    set_constrained_diagonal(const AffineConstraints<double> &constraints,
                             const IndexSet                  &locally_owned,
                             const double                     value,
                             PETScMatrix                     &matrix)
    {
      for (const auto i : locally_owned)
        if (constraints.is_constrained(i))
          matrix.set(i, i, value);
      matrix.compress(VectorOperation::insert);
    }

    std::pair<std::vector<Point<3>>, std::vector<unsigned int>>
    dof_support_points(const StructuralModel &model)
    {
      const auto                          &fe   = model.fe;
      const auto                          &unit = fe.get_unit_support_points();
      std::vector<Point<3>>                points(model.n_dofs());
      std::vector<unsigned int>            component(model.n_dofs());
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      for (const auto &cell : model.dof_handler.active_cell_iterators())
        {
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            {
              points[dofs[i]] =
                model.mapping.transform_unit_to_real_cell(cell, unit[i]);
              component[dofs[i]] = fe.system_to_component_index(i).first;
            }
        }
      return {points, component};
    }

    namespace
    {
      // Cells whose indicators are within a relative 1e-3 of the smallest
      // one marked are marked too. A symmetric mesh (the disc's rings of
      // equal cells) has groups of cells whose indicators are equal but for
      // rounding, and a marking threshold inside such a group would pick its
      // members by the last bits of the indicator (by the BLAS kernels of
      // the machine). Marking the whole group keeps the mesh symmetric and
      // the refinement the same on every machine.
      void
      mark_ties(Triangulation<3> &triangulation, const Vector<float> &indicator)
      {
        constexpr double tie       = 1e-3;
        float            threshold = std::numeric_limits<float>::max();
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->refine_flag_set())
            threshold =
              std::min(threshold, indicator[cell->active_cell_index()]);
        if (threshold == std::numeric_limits<float>::max())
          return;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (!cell->refine_flag_set() &&
              indicator[cell->active_cell_index()] >= (1. - tie) * threshold)
            cell->set_refine_flag();
      }

      types::global_dof_index largest_size = 0;
    } // namespace

    types::global_dof_index
    largest_model_size()
    {
      return largest_size;
    }

    void
    store_nonzeros_only(PETScMatrix    &A,
                        const IndexSet &owned,
                        const MPI_Comm  comm)
    {
      // the nonzeros in flat arrays (large blocks, returned to the system
      // when freed; a vector per row would stay in the heap)
      DynamicSparsityPattern               dsp(owned);
      std::vector<std::size_t>             start{0};
      std::vector<types::global_dof_index> columns;
      std::vector<PetscScalar>             values;
      start.reserve(owned.n_elements() + 1);
      {
        // room for every stored entry: the pages never written stay
        // virtual, and the arrays are not copied as they grow
        MatInfo info;
        MatGetInfo(A, MAT_LOCAL, &info);
        columns.reserve(static_cast<std::size_t>(info.nz_used));
        values.reserve(static_cast<std::size_t>(info.nz_used));
      }
      for (const auto row : owned)
        {
          PetscInt           n_cols     = 0;
          const PetscInt    *cols       = nullptr;
          const PetscScalar *row_values = nullptr;
          AssertThrow(MatGetRow(A, row, &n_cols, &cols, &row_values) == 0,
                      ExcMessage("store_nonzeros_only: MatGetRow failed"));
          for (PetscInt j = 0; j < n_cols; ++j)
            if (row_values[j] != 0.)
              {
                columns.push_back(cols[j]);
                values.push_back(row_values[j]);
              }
          MatRestoreRow(A, row, &n_cols, &cols, &row_values);
          dsp.add_entries(row, columns.begin() + start.back(), columns.end());
          // An empty row keeps its diagonal (stored as zero): deal.II 9.4's
          // DynamicSparsityPattern::begin(row) of an empty row walks to the
          // next row with entries, so reinit() on a pattern of a few rows
          // (a spring set, an interface) cost O(n^2): 99 % of the braking
          // set-up of a 91 374-DoF brake.
          if (columns.size() == start.back())
            dsp.add(row, row);
          start.push_back(columns.size());
        }
      A.reinit(owned, owned, dsp, comm);
      dsp.reinit(0, 0);
      std::size_t i = 0;
      for (const auto row : owned)
        {
          if (start[i + 1] > start[i])
            A.set(row,
                  start[i + 1] - start[i],
                  columns.data() + start[i],
                  values.data() + start[i]);
          ++i;
        }
      A.compress(VectorOperation::insert);
      // the pattern's rows and the old matrix went back to the heap: give
      // its free pages to the system (a third of a common-pattern matrix,
      // 0.7 GB at a million DoFs, for every matrix stored this way)
      malloc_trim(0);
    }

    void
    copy_to_serial(const PETScMatrix    &K,
                   SparsityPattern      &pattern,
                   SparseMatrix<double> &target)
    {
      const unsigned int     n = K.m();
      DynamicSparsityPattern dsp(n, n);
      // end(i) hoisted: each PETSc row iterator reads its row (MatGetRow)
      for (unsigned int i = 0; i < n; ++i)
        for (auto e = K.begin(i), end = K.end(i); e != end; ++e)
          dsp.add(i, e->column());
      pattern.copy_from(dsp);
      target.reinit(pattern);
      for (unsigned int i = 0; i < n; ++i)
        for (auto e = K.begin(i), end = K.end(i); e != end; ++e)
          target.set(i, e->column(), e->value());
    }

    std::vector<bool>
    dofs_on_boundary(const StructuralModel &model, const types::boundary_id id)
    {
      std::vector<bool>                    on(model.n_dofs(), false);
      std::vector<types::global_dof_index> face_dofs(
        model.fe.n_dofs_per_face());
      for (const auto &cell : model.dof_handler.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() == id)
            {
              cell->face(f)->get_dof_indices(face_dofs);
              for (const auto i : face_dofs)
                on[i] = true;
            }
      return on;
    }

    HeldDofs
    held_dofs(const StructuralModel           &model,
              const std::vector<Point<3>>     &points,
              const std::vector<unsigned int> &component)
    {
      const types::global_dof_index n = model.n_dofs();
      HeldDofs                      held;
      held.on_holds.assign(n, false);
      for (const scene::Hold &hold : model.scene->holds)
        {
          const std::vector<bool> on = dofs_on_boundary(model, hold.id);
          for (types::global_dof_index i = 0; i < n; ++i)
            held.on_holds[i] =
              held.on_holds[i] || (on[i] && hold.components[component[i]]);
        }
      for (const scene::PointHold &hold : model.scene->point_holds)
        {
          types::global_dof_index nearest = numbers::invalid_dof_index;
          double                  best    = 1e300;
          for (types::global_dof_index d = 0; d < points.size(); ++d)
            if (component[d] == hold.component &&
                points[d].distance(hold.point) < best)
              {
                best    = points[d].distance(hold.point);
                nearest = d;
              }
          held.point_held.push_back(nearest);
        }
      return held;
    }

    void
    StructuralModel::setup_and_assemble(ConditionalOStream &pcout)
    {
      setup_and_assemble({}, pcout);
    }

    void
    StructuralModel::setup_and_assemble(
      const std::vector<std::vector<bool>> &history,
      ConditionalOStream                   &pcout)
    {
      auto made = scene::make_scene(prm);
      for (const auto &[name, value] : nominal_overrides)
        made->set_nominal(name, value);
      scene = std::move(made);
      scene->make_mesh(triangulation);
      for (const auto &flags : history)
        {
          // deal.II stores dim bits (the refinement case) per active cell
          if (flags.size() != 3 * triangulation.n_active_cells())
            throw std::runtime_error(
              "refinement history: a step has " + std::to_string(flags.size()) +
              " refine-flag bits for a mesh of " +
              std::to_string(triangulation.n_active_cells()) +
              " cells (3 per cell expected)");
          triangulation.load_refine_flags(flags);
          triangulation.execute_coarsening_and_refinement();
          refinement_history.push_back(flags);
        }
      setup_dofs_and_assemble(pcout);
    }

    void
    StructuralModel::refine(const Vector<float> &indicator,
                            const double         fraction,
                            const bool           by_error,
                            ConditionalOStream  &pcout)
    {
      if (indicator.size() != triangulation.n_active_cells())
        throw std::runtime_error(
          "a refinement indicator needs one value per active cell (" +
          std::to_string(triangulation.n_active_cells()) + "), got " +
          std::to_string(indicator.size()));
      if (by_error)
        GridRefinement::refine_and_coarsen_fixed_fraction(
          triangulation,
          indicator,
          fraction,
          0.,
          std::numeric_limits<unsigned int>::max(),
          VectorTools::L2_norm);
      else
        GridRefinement::refine_and_coarsen_fixed_number(triangulation,
                                                        indicator,
                                                        fraction,
                                                        0.);
      mark_ties(triangulation, indicator);
      std::vector<bool> flags;
      triangulation.save_refine_flags(flags);
      refinement_history.push_back(flags);
      triangulation.execute_coarsening_and_refinement();
      setup_dofs_and_assemble(pcout);
    }

    std::vector<std::complex<double>>
    transfer_field(const StructuralModel                   &from,
                   const std::vector<std::complex<double>> &field,
                   const StructuralModel                   &to)
    {
      if (field.size() != from.n_dofs() ||
          from.triangulation.n_active_cells() !=
            to.triangulation.n_active_cells())
        throw std::runtime_error(
          "transfer_field: the field or the meshes do not match (" +
          std::to_string(field.size()) + " values for " +
          std::to_string(from.n_dofs()) + " DoFs; " +
          std::to_string(from.triangulation.n_active_cells()) + " and " +
          std::to_string(to.triangulation.n_active_cells()) + " cells)");
      const Quadrature<3> at_to_points(to.fe.get_unit_support_points());
      FEValues<3> fe_values(from.mapping, from.fe, at_to_points, update_values);
      std::vector<types::global_dof_index> from_dofs(from.fe.n_dofs_per_cell()),
        to_dofs(to.fe.n_dofs_per_cell());
      std::vector<std::complex<double>> result(to.n_dofs());
      auto                              cell_to = to.dof_handler.begin_active();
      for (const auto &cell : from.dof_handler.active_cell_iterators())
        {
          if (cell->center().distance(cell_to->center()) > 1e-9)
            throw std::runtime_error(
              "transfer_field: the meshes differ (cell " +
              std::to_string(cell->active_cell_index()) + ")");
          fe_values.reinit(cell);
          cell->get_dof_indices(from_dofs);
          cell_to->get_dof_indices(to_dofs);
          for (unsigned int q = 0; q < to_dofs.size(); ++q)
            {
              const unsigned int   c = to.fe.system_to_component_index(q).first;
              std::complex<double> v = 0.;
              for (unsigned int j = 0; j < from_dofs.size(); ++j)
                if (from.fe.system_to_component_index(j).first == c)
                  v += field[from_dofs[j]] * fe_values.shape_value(j, q);
              result[to_dofs[q]] = v;
            }
          ++cell_to;
        }
      return result;
    }

    namespace
    {
      // The model's constraints: hanging nodes, the scene's holds and ties.
      // With ties every rank holds every constraint (a slave node's master
      // nodes need not be among its relevant DoFs; the mesh is whole on
      // every rank).
      void
      make_constraints(StructuralModel &model)
      {
        const scene::Scene &scene       = *model.scene;
        auto               &constraints = model.constraints;
        const bool          tied        = !scene.ties.empty();
        if (tied && !model.tie_constraints)
          throw std::runtime_error(
            "scene " + scene.description() +
            " has ties, and this analysis builds its model without them");
        constraints.clear();
        constraints.reinit(tied ?
                             complete_index_set(model.dof_handler.n_dofs()) :
                             model.locally_relevant_dofs);
        DoFTools::make_hanging_node_constraints(model.dof_handler, constraints);
        for (const scene::Hold &hold : scene.holds)
          VectorTools::interpolate_boundary_values(
            model.mapping,
            model.dof_handler,
            hold.id,
            Functions::ZeroFunction<3>(3),
            constraints,
            ComponentMask(std::vector<bool>(hold.components.begin(),
                                            hold.components.end())));
        if (tied)
          model.tie_constraints(model, constraints);
        constraints.close();
      }

      // The linear interface's quadrature points, one list per contact
      // pair, weighted by the model's interface mask (a preload's contact
      // state) where there is one.
      std::vector<std::vector<CouplingPoint>>
      interface_points(const StructuralModel &model, ConditionalOStream &pcout)
      {
        const auto                             &prm = model.prm;
        std::vector<std::vector<CouplingPoint>> pair_points;
        for (const scene::ContactPair &pair : model.scene->contact_pairs)
          pair_points.push_back(
            interface_quadrature(model.dof_handler,
                                 model.mapping,
                                 pair,
                                 prm.interface.quadrature,
                                 prm.interface.quadrature == "nodal" ?
                                   prm.mesh.fe_degree + 1 :
                                   prm.mesh.fe_degree + 2));
        if (!model.interface_mask)
          return pair_points;
        for (auto &points : pair_points)
          {
            std::vector<CouplingPoint> kept;
            for (CouplingPoint p : points)
              {
                p.weight *= model.interface_mask(
                  model.mapping.transform_unit_to_real_cell(p.pad_cell,
                                                            p.pad_unit));
                if (p.weight != 0.)
                  kept.push_back(p);
              }
            pcout << "Interface: " << kept.size() << " of " << points.size()
                  << " quadrature points with contact (the contact "
                     "state's interface weight above 0)"
                  << std::endl;
            points.swap(kept);
          }
        return pair_points;
      }

      // Constrained rows: K_ii = d, M_ii = d / omega_s^2, all parts else 0;
      // d the mean diagonal over the free rows of the common stiffness part
      // (the bodies no point changes), or of every body's at its nominal
      // values if all vary: it depends on no point. Returns d [N/m].
      double
      set_constrained_rows(StructuralModel   &model,
                           const MatrixParts &parts,
                           const unsigned int fixed_mass,
                           const unsigned int fixed_stiffness)
      {
        const auto &constraints        = model.constraints;
        const auto  mean_free_diagonal = [&](const bool common_only) {
          double trace = 0, n_free = 0;
          for (const auto i : model.locally_owned_dofs)
            if (!constraints.is_constrained(i))
              {
                for (unsigned int k = 0; k < parts.size(); ++k)
                  if ((k == fixed_stiffness || !common_only) &&
                      parts.parts[k].kind == MatrixParts::Kind::stiffness &&
                      !parts.parts[k].springs)
                    trace += parts.matrix(k).diag_element(i);
                n_free += 1;
              }
          return Utilities::MPI::sum(trace, model.comm) /
                 std::max(1., Utilities::MPI::sum(n_free, model.comm));
        };
        double d = mean_free_diagonal(true);
        if (!(d > 0.))
          d = mean_free_diagonal(false);
        const double omega_s =
          2. * numbers::PI * 1e3 * model.prm.eigensolver.f_max;
        for (unsigned int k = 0; k < parts.size(); ++k)
          if (!parts.parts[k].own_pattern) // those are set
            set_constrained_diagonal(constraints,
                                     model.locally_owned_dofs,
                                     k == fixed_stiffness ? d :
                                     k == fixed_mass ? d / (omega_s * omega_s) :
                                                       0.,
                                     *model.part_matrices[k]);
        return d;
      }
    } // namespace

    void
    StructuralModel::setup_dofs_and_assemble(ConditionalOStream &pcout)
    {
      dof_handler.distribute_dofs(fe);
      locally_owned_dofs = dof_handler.locally_owned_dofs();
      DoFTools::extract_locally_relevant_dofs(dof_handler,
                                              locally_relevant_dofs);

      make_constraints(*this);
      const auto pair_points = interface_points(*this, pcout);
      pattern = std::make_unique<DynamicSparsityPattern>(locally_relevant_dofs);
      DoFTools::make_sparsity_pattern(dof_handler,
                                      *pattern,
                                      constraints,
                                      false);
      for (const auto &interface_points : pair_points)
        add_interface_sparsity(interface_points, constraints, *pattern);
      for (const scene::SpringSet &s : scene->springs)
        if (s.to_body)
          for (const auto &dofs : two_body_spring_nodes(s))
            {
              std::vector<types::global_dof_index> d(dofs.begin(), dofs.end());
              constraints.add_entries_local_to_global(d, *pattern, false);
            }
      SparsityTools::distribute_sparsity_pattern(*pattern,
                                                 locally_owned_dofs,
                                                 comm,
                                                 locally_relevant_dofs);
      part_template = std::make_unique<PETScMatrix>();
      part_template->reinit(locally_owned_dofs,
                            locally_owned_dofs,
                            *pattern,
                            comm);

      largest_size = std::max(largest_size, dof_handler.n_dofs());
      pcout << "Mesh: " << triangulation.n_active_cells() << " cells, "
            << dof_handler.n_dofs() << " DoFs (degree " << prm.mesh.fe_degree
            << "), " << constraints.n_constraints() << " constrained"
            << std::endl;

      // The parts: the bodies' (common ones first: they carry the lumped
      // masses and the constrained rows), each spring set's, each pair's
      // K_n and K_t. A scaled part is assembled at the nominal value of its
      // parameter (1 in its unit where that is 0).
      const parameters::ScalarPoint nominal = scene->nominal_point();
      const auto reference_of               = [&](const std::string &name) {
        const double v = nominal.get(name);
        return v == 0. ? 1. : v;
      };
      MatrixParts parts;
      parts.reference    = nominal;
      parts.modal.ratios = prm.damping.modal_ratios;
      parts.modal.cutoff =
        prm.eigensolver.f_max * prm.eigensolver.reduced_band_factor;
      next_part = 0;
      const auto [fixed_mass, fixed_stiffness] =
        assemble_elasticity(nominal, parts);
      // each lumped mass its own part, scaled by its `<mass>.m` [kg]
      point_masses.clear();
      double total = 0.;
      for (const scene::LumpedMass &m : scene->masses)
        {
          const std::string name = m.name + ".m";
          PETScMatrix      &M    = new_part_matrix();
          add_mass(m, M);
          parts.parts.push_back({&M,
                                 MatrixParts::Kind::mass,
                                 "lumped mass " + m.name,
                                 name,
                                 reference_of(name),
                                 "",
                                 "damping.alpha",
                                 false});
          total += m.mass;
        }
      if (!scene->masses.empty())
        pcout << "Masses: " << scene->masses.size() << " lumped, " << total
              << " kg in all" << std::endl;
      // A spring set or an interface part touches a few hundred rows: it is
      // stored on its own nonzeros as soon as it is assembled (with its
      // constrained rows 0), so that at most one part at a time holds the
      // whole pattern (17 spring sets of a 91 374-DoF brake: 3.1 GB)
      const auto compact = [&](PETScMatrix &A) {
        set_constrained_diagonal(constraints, locally_owned_dofs, 0., A);
        store_nonzeros_only(A, locally_owned_dofs, comm);
      };
      for (const scene::SpringSet &springs : scene->springs)
        {
          const std::string k = springs.name + ".k";
          PETScMatrix &K = new_part_matrix([&](DynamicSparsityPattern &dsp) {
            add_spring_sparsity(springs, dsp);
          });
          add_springs(springs, K, reference_of(k), pcout);
          compact(K);
          parts.parts.push_back({&K,
                                 MatrixParts::Kind::stiffness,
                                 "springs " + springs.name,
                                 k,
                                 reference_of(k),
                                 "",
                                 "damping.beta",
                                 true});
          parts.parts.back().own_pattern = true;
        }
      for (unsigned int i = 0; i < pair_points.size(); ++i)
        {
          const scene::ContactPair &pair = scene->contact_pairs[i];
          const std::string k_n = pair.name + ".k_n", k_t = pair.name + ".k_t";
          const auto        own = [&](DynamicSparsityPattern &dsp) {
            add_interface_sparsity(pair_points[i], constraints, dsp);
          };
          PETScMatrix &Kn = new_part_matrix(own), &Kt = new_part_matrix(own);
          // the shear part only where it is or may become nonzero: else it
          // would add an empty term to every product
          PETScMatrix *Kst = pair.tangential_stiffness > 0. || !varied ||
                                 varied->count(k_t) > 0 ?
                               &new_part_matrix(own) :
                               nullptr;
          assemble_interface(pair_points[i],
                             constraints,
                             reference_of(k_n),
                             reference_of(k_t),
                             pair,
                             Kn,
                             Kt,
                             Kst);
          Kn.compress(VectorOperation::add);
          Kt.compress(VectorOperation::add);
          compact(Kn);
          compact(Kt);
          parts.parts.push_back({&Kn,
                                 MatrixParts::Kind::interface_normal,
                                 "normal interface " + pair.name,
                                 k_n,
                                 reference_of(k_n),
                                 "",
                                 "",
                                 false});
          parts.parts.back().own_pattern = true;
          parts.parts.push_back({&Kt,
                                 MatrixParts::Kind::interface_friction,
                                 "friction " + pair.name,
                                 k_n,
                                 reference_of(k_n),
                                 pair.name + ".mu",
                                 "",
                                 false});
          parts.parts.back().own_pattern = true;
          if (Kst)
            {
              Kst->compress(VectorOperation::add);
              compact(*Kst);
              parts.parts.push_back({Kst,
                                     MatrixParts::Kind::interface_normal,
                                     "tangential interface " + pair.name,
                                     k_t,
                                     reference_of(k_t),
                                     "",
                                     "",
                                     false});
              parts.parts.back().own_pattern = true;
            }
        }
      part_matrices.resize(next_part);
      pattern.reset();
      part_template.reset();

      constrained_diagonal =
        set_constrained_rows(*this, parts, fixed_mass, fixed_stiffness);
      // Every part but the common mass and stiffness (which carry the
      // constrained rows) is stored on its own nonzeros: a spring set or an
      // interface touches a few hundred rows, a body a fraction of them, and
      // on the common pattern each would cost a whole matrix in memory and
      // in every product.
      for (unsigned int k = 0; k < parts.size(); ++k)
        if (k != fixed_mass && k != fixed_stiffness &&
            !parts.parts[k].own_pattern)
          {
            const auto it =
              std::find_if(part_matrices.begin(),
                           part_matrices.end(),
                           [&](const auto &m) {
                             return m.get() == parts.parts[k].matrix;
                           });
            Assert(it != part_matrices.end(), ExcInternalError());
            store_nonzeros_only(**it, locally_owned_dofs, comm);
            parts.parts[k].own_pattern = true;
          }
      assembled = parts;
    }

    void
    StructuralModel::release_body_parts()
    {
      MatrixParts kept = assembled;
      kept.parts.clear();
      for (const MatrixParts::Part &part : assembled.parts)
        {
          const bool body = (part.kind == MatrixParts::Kind::mass ||
                             part.kind == MatrixParts::Kind::stiffness) &&
                            !part.springs;
          if (!body)
            kept.parts.push_back(part);
          else
            for (auto &m : part_matrices)
              if (m.get() == part.matrix)
                m->clear();
        }
      kept.bodies_released = true;
      assembled            = kept;
    }

    PETScMatrix &
    StructuralModel::new_part_matrix(
      const std::function<void(DynamicSparsityPattern &)> &own)
    {
      // reused across refinements, so that earlier parts() stay valid
      if (next_part == part_matrices.size())
        part_matrices.push_back(std::make_unique<PETScMatrix>());
      PETScMatrix &m = *part_matrices[next_part++];
      if (!own)
        {
          m.reinit(*part_template);
          return m;
        }
      DynamicSparsityPattern dsp(locally_relevant_dofs);
      own(dsp);
      // every owned row keeps its diagonal (see store_nonzeros_only)
      for (const auto i : locally_owned_dofs)
        dsp.add(i, i);
      SparsityTools::distribute_sparsity_pattern(dsp,
                                                 locally_owned_dofs,
                                                 comm,
                                                 locally_relevant_dofs);
      m.reinit(locally_owned_dofs, locally_owned_dofs, dsp, comm);
      return m;
    }

    std::pair<unsigned int, unsigned int>
    StructuralModel::assemble_elasticity(const parameters::ScalarPoint &nominal,
                                         MatrixParts                   &parts)
    {
      // Group the bodies: one mass part per (scaling density, alpha) and
      // one stiffness part per (scaling modulus, beta); the common parts
      // (no scale, the scene's damping) first.
      const auto is_varied = [&](const std::string &name) {
        return !varied || varied->count(name) > 0;
      };
      using Key = std::pair<std::string, std::string>; // scale, damping
      std::vector<Key> mass_keys{{"", "damping.alpha"}},
        stiffness_keys{{"", "damping.beta"}};
      std::map<types::material_id, std::pair<unsigned int, unsigned int>>
                 group_of; // body -> (mass key, stiffness key)
      const auto index = [](std::vector<Key> &keys, const Key &key) {
        const auto it = std::find(keys.begin(), keys.end(), key);
        if (it != keys.end())
          return static_cast<unsigned int>(it - keys.begin());
        keys.push_back(key);
        return static_cast<unsigned int>(keys.size() - 1);
      };
      for (const scene::Body &b : scene->bodies)
        {
          const std::string E = b.name + ".E", rho = b.name + ".rho";
          const Key         mass_key{is_varied(rho) ? rho : "",
                             b.own_damping ? b.name + ".alpha" :
                                                     "damping.alpha"};
          const Key stiffness_key{is_varied(E) ? E : "",
                                  b.own_damping ? b.name + ".beta" :
                                                  "damping.beta"};
          if (!is_varied(E))
            parts.fixed.emplace_back(E, nominal.get(E));
          if (!is_varied(rho))
            parts.fixed.emplace_back(rho, nominal.get(rho));
          group_of[b.id] = {index(mass_keys, mass_key),
                            index(stiffness_keys, stiffness_key)};
        }
      std::vector<PETScMatrix *> mass_parts, stiffness_parts;
      for (const auto &[scale, damping] : mass_keys)
        {
          mass_parts.push_back(&new_part_matrix());
          parts.parts.push_back(
            {mass_parts.back(),
             MatrixParts::Kind::mass,
             scale.empty() ? "common mass" : "mass, " + scale,
             scale,
             scale.empty() ? 1. : nominal.get(scale),
             "",
             damping});
        }
      for (const auto &[scale, damping] : stiffness_keys)
        {
          stiffness_parts.push_back(&new_part_matrix());
          parts.parts.push_back(
            {stiffness_parts.back(),
             MatrixParts::Kind::stiffness,
             scale.empty() ? "common stiffness" : "stiffness, " + scale,
             scale,
             scale.empty() ? 1. : nominal.get(scale),
             "",
             damping});
        }

      const QGauss<3>                      quadrature(fe.degree + 1);
      FEValues<3>                          fe_values(mapping,
                            fe,
                            quadrature,
                            update_values | update_gradients |
                              update_JxW_values | update_quadrature_points);
      const unsigned int                   n = fe.n_dofs_per_cell();
      FullMatrix<double>                   cell_k(n, n), cell_m(n, n);
      std::vector<SymmetricTensor<4, 3>>   C_q(quadrature.size());
      std::vector<types::global_dof_index> dofs(n);

      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const scene::Body &body = scene->body(cell->material_id());
            const double       E    = scene->youngs_modulus(body.id, nominal);
            const double       nu   = body.material.poisson_ratio;
            const double       density = scene->density(body.id, nominal);
            const auto [lambda, mu]    = lame_constants(E, nu);

            fe_values.reinit(cell);
            cell_k = 0;
            cell_m = 0;
            if (body.law.anisotropic)
              {
                // the law at each quadrature point (a cylindrical frame
                // turns with the point); the mass as for an isotropic body
                for (unsigned int q = 0; q < quadrature.size(); ++q)
                  C_q[q] =
                    scene->stiffness_tensor(body.id,
                                            fe_values.quadrature_point(q),
                                            nominal);
                add_cell_stiffness(fe_values, C_q, cell_k);
                add_cell_elasticity(fe_values, 0., 0., density, cell_k, cell_m);
              }
            else
              add_cell_elasticity(
                fe_values, lambda, mu, density, cell_k, cell_m);
            cell->get_dof_indices(dofs);
            const auto [m, k] = group_of.at(body.id);
            constraints.distribute_local_to_global(cell_k,
                                                   dofs,
                                                   *stiffness_parts[k]);
            constraints.distribute_local_to_global(cell_m,
                                                   dofs,
                                                   *mass_parts[m]);
          }
      for (auto *m : mass_parts)
        m->compress(VectorOperation::add);
      for (auto *k : stiffness_parts)
        k->compress(VectorOperation::add);
      return {0u, static_cast<unsigned int>(mass_keys.size())};
    }
  } // namespace physics
} // namespace squeal
