#include <igabde/base/utilities.h>
#include <igabde/linear_algebra/sparse_cholesky.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>
#include <igabde/discretization/iga_body.h>
#include <igabde/discretization/lagrange_body.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iomanip>
#include <ostream>
#include <utility>

namespace igabde
{
  namespace discretization
  {
    template <int dim>
    Tensor<1, dim>
    PointOperator<dim>::displacement(const Vector<double> &u) const
    {
      Tensor<1, dim> result;
      for (unsigned int k = 0; k < weights.size(); ++k)
        for (unsigned int c = 0; c < dim; ++c)
          result[c] += weights[k] * u[dofs[k][c]];
      return result;
    }



    template <int dim>
    void
    PointOperator<dim>::distribute(const Tensor<1, dim> &force,
                                   Vector<double>       &f) const
    {
      for (unsigned int k = 0; k < weights.size(); ++k)
        for (unsigned int c = 0; c < dim; ++c)
          f[dofs[k][c]] += weights[k] * force[c];
    }



    /**
     * The factorisation of the constrained stiffness, one of three paths
     * chosen by DiscretizationSettings::linear_solver.
     */
    template <int dim>
    struct Body<dim>::LinearSolver
    {
      /// Direct path (Linear solver = direct): MUMPS LDL^T, with the Schur
      /// complement onto the contact face when asked.
      std::unique_ptr<linear_algebra::SparseCholesky> cholesky;
      /// K with the constrained rows and columns replaced by a scaled
      /// identity (umfpack and cg-amg).
      SparseMatrix<double> constrained_matrix;
      /// LU path (Linear solver = umfpack).
      std::unique_ptr<SparseDirectUMFPACK> direct_solver;
      /// Iterative path (Linear solver = cg-amg): the constrained matrix as
      /// a Trilinos matrix and its ML algebraic multigrid preconditioner.
      std::unique_ptr<TrilinosWrappers::SparseMatrix>    amg_matrix;
      std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    };



    template <int dim>
    Body<dim>::Body(const BodyDescription<dim>   &description,
                    const DiscretizationSettings &settings)
      : settings(settings)
      , body_description(std::make_unique<BodyDescription<dim>>(description))
      , linear_solver(std::make_unique<LinearSolver>())
    {
      description.material.validate("Body '" + description.name + "'");
    }



    template <int dim>
    Body<dim>::~Body() = default;



    template <int dim>
    void
    Body<dim>::setup()
    {
      setup_system();
      factorize();
    }



    template <int dim>
    void
    Body<dim>::setup_system()
    {
      setup_space();
      AssertDimension(dof_locations.size(), n_unknowns);
      AssertDimension(dof_components.size(), n_unknowns);
      assembled       = false;
      assembled_share = false;
      if (shares_assembly())
        assemble_share();
      else if (layout.matrix_everywhere || factorizes_here())
        ensure_assembled();
      find_free_rigid_modes();
      hold_rotations();
    }



    template <int dim>
    void
    Body<dim>::set_parallel_layout(const ParallelLayout &new_layout)
    {
      layout = new_layout;
    }



    template <int dim>
    void
    Body<dim>::ensure_assembled()
    {
      if (assembled && !assembled_share)
        return;
      assemble();
      assembled       = true;
      assembled_share = false;
      matrix_entries  = sparsity.n_nonzero_elements();
    }



    template <int dim>
    bool
    Body<dim>::shares_assembly() const
    {
      return factorizes_here() && !layout.matrix_everywhere &&
             settings.linear_solver == discretization::LinearSolver::direct &&
             Utilities::MPI::n_mpi_processes(layout.group) > 1;
    }



    template <int dim>
    void
    Body<dim>::assemble_share()
    {
      // Contiguous runs of the cells, as the VTU pieces; the share that
      // starts at the first cell also adds the point loads and moments.
      assembly_cells =
        output_cells(Utilities::MPI::this_mpi_process(layout.group),
                     Utilities::MPI::n_mpi_processes(layout.group));
      assemble();
      assembly_cells  = {0, std::numeric_limits<unsigned int>::max()};
      assembled       = true;
      assembled_share = true;
      matrix_entries  = sparsity.n_nonzero_elements();
      for (auto &f : history_rhs)
        Utilities::MPI::sum(ArrayView<const double>(f.data(), f.size()),
                            layout.group,
                            ArrayView<double>(f.data(), f.size()));
      if (!history_rhs.empty())
        load_rhs = history_rhs[0];
    }



    template <int dim>
    Vector<double>
    Body<dim>::stiffness_times(const Vector<double> &u) const
    {
      Vector<double> Ku(n_unknowns);
      system_matrix.vmult(Ku, u);
      if (assembled_share)
        Utilities::MPI::sum(ArrayView<const double>(Ku.data(), Ku.size()),
                            layout.group,
                            ArrayView<double>(Ku.data(), Ku.size()));
      return Ku;
    }



    template <int dim>
    std::size_t
    Body<dim>::n_matrix_entries() const
    {
      return matrix_entries;
    }



    template <int dim>
    void
    Body<dim>::share_assembly()
    {
      if (Utilities::MPI::n_mpi_processes(layout.world) == 1)
        return;
      unsigned int n_h = history_rhs.size();
      Utilities::MPI::broadcast(&n_h, 1, layout.root, layout.world);
      history_rhs.resize(n_h, Vector<double>(n_unknowns));
      for (auto &f : history_rhs)
        Utilities::MPI::broadcast(f.data(),
                                  f.size(),
                                  layout.root,
                                  layout.world);
      if (n_h > 0)
        load_rhs = history_rhs[0];
      unsigned long long entries = matrix_entries;
      Utilities::MPI::broadcast(&entries, 1, layout.root, layout.world);
      matrix_entries = entries;
    }



    template <int dim>
    bool
    Body<dim>::factorizes_here() const
    {
      return layout.group != MPI_COMM_NULL;
    }



    template <int dim>
    void
    Body<dim>::share_factorization()
    {
      if (Utilities::MPI::n_mpi_processes(layout.world) == 1)
        return;
      if (!linear_solver->cholesky)
        linear_solver->cholesky =
          std::make_unique<linear_algebra::SparseCholesky>();
      linear_solver->cholesky->share(layout.world, layout.root);
      unsigned int n_h = u_history.size();
      Utilities::MPI::broadcast(&n_h, 1, layout.root, layout.world);
      u_history.resize(n_h, Vector<double>(n_unknowns));
      for (auto &u : u_history)
        Utilities::MPI::broadcast(u.data(),
                                  u.size(),
                                  layout.root,
                                  layout.world);
    }



    template <int dim>
    void
    Body<dim>::release_factorization()
    {
      if (linear_solver->cholesky)
        linear_solver->cholesky->release();
      linear_solver->direct_solver.reset();
      linear_solver->amg.reset();
      linear_solver->amg_matrix.reset();
      linear_solver->constrained_matrix.clear();
    }



    template <int dim>
    void
    Body<dim>::keep_reaction_rows_only()
    {
      if (!assembled || reduced_to_reaction_rows ||
          settings.linear_solver != discretization::LinearSolver::direct)
        return;
      // The rows support_reaction() and face_motion_reaction() read.
      std::vector<bool> keep(n_unknowns, false);
      for (types::global_dof_index i = 0; i < n_unknowns; ++i)
        keep[i] = constraints.is_constrained(i);
      for (const auto &dofs : dirichlet_dofs)
        for (const auto i : dofs)
          keep[i] = true;
      DynamicSparsityPattern rows(n_unknowns, n_unknowns);
      for (types::global_dof_index i = 0; i < n_unknowns; ++i)
        if (keep[i])
          for (auto entry = sparsity.begin(i); entry != sparsity.end(i);
               ++entry)
            rows.add(i, entry->column());
      reaction_sparsity = std::make_unique<SparsityPattern>();
      reaction_sparsity->copy_from(rows);
      SparseMatrix<double> reduced(*reaction_sparsity);
      for (types::global_dof_index i = 0; i < n_unknowns; ++i)
        if (keep[i])
          for (auto entry = system_matrix.begin(i);
               entry != system_matrix.end(i);
               ++entry)
            reduced.set(i, entry->column(), entry->value());
      system_matrix = std::move(reduced);
      sparsity.reinit(0, 0, 0);
      reduced_to_reaction_rows = true;
    }



    template <int dim>
    void
    Body<dim>::factorize(const std::vector<PointOperator<dim>> &interface,
                         const bool keep_reaction_rows)
    {
      if (!factorizes_here())
        return;
      // The unknowns the contact points touch, less those held at zero.
      std::vector<types::global_dof_index> interface_dofs;
      if (settings.linear_solver == discretization::LinearSolver::direct)
        {
          std::vector<bool> touched(n_unknowns, false);
          // A volume operator at a surface point lists every basis function
          // of the cell; those that vanish on the face carry nothing.
          for (const auto &op : interface)
            for (unsigned int k = 0; k < op.weights.size(); ++k)
              if (op.weights[k] != 0.)
                for (const auto i : op.dofs[k])
                  touched[i] = true;
          for (types::global_dof_index i = 0; i < n_unknowns; ++i)
            if (touched[i] && !solve_constraints.is_constrained(i))
              interface_dofs.push_back(i);
        }
      // Superposition: one load case per load history (history 0 the
      // external loads of the load factors, 1 the prescribed displacements
      // of the displacement factors, 2.. named histories), each scaled by
      // its own factor along the load path. Their right-hand sides first:
      // K lift is the last product with the whole K, whose other rows may
      // then go as soon as the factorisation has read it.
      const unsigned int          n_h = history_rhs.size();
      std::vector<Vector<double>> columns(history_rhs);
      std::vector<Vector<double>> lifts(n_h, Vector<double>(n_unknowns));
      for (types::global_dof_index i = 0; i < n_unknowns; ++i)
        if (prescribed_constraints.is_constrained(i))
          {
            const auto         it = prescribed_history.find(i);
            const unsigned int h =
              (it != prescribed_history.end() ? it->second : 1u);
            AssertIndexRange(h, n_h);
            lifts[h][i] = prescribed_constraints.get_inhomogeneity(i);
          }
      for (unsigned int h = 0; h < n_h; ++h)
        columns[h] -= stiffness_times(lifts[h]);

      factorize_matrix(interface_dofs,
                       keep_reaction_rows ? std::function<void()>([this]() {
                         keep_reaction_rows_only();
                       }) :
                                            std::function<void()>());
      // The pinned responses K^+ C_h serve the Schur-complement
      // flexibility's correction only (correct_for_held_modes()).
      held_response.clear();
      if (has_schur_complement() && !rigid_modes.held_loads().empty())
        {
          held_response = rigid_modes.held_loads();
          solve_pinned(held_response);
        }

      solve_in_group(columns);
      u_history = columns;
      for (unsigned int h = 0; h < n_h; ++h)
        u_history[h] += lifts[h];
    }



    template <int dim>
    FullMatrix<double>
    Body<dim>::flexibility(const std::vector<PointOperator<dim>> &operators,
                           const std::vector<Tensor<1, dim>> &directions) const
    {
      FullMatrix<double> F;
      if (factorizes_here())
        F = flexibility_in_group(operators, directions);
      share_flexibility(F);
      return F;
    }



    template <int dim>
    void
    Body<dim>::share_flexibility(FullMatrix<double> &F) const
    {
      if (Utilities::MPI::n_mpi_processes(layout.world) == 1)
        return;
      unsigned int n = F.m();
      Utilities::MPI::broadcast(&n, 1, layout.root, layout.world);
      if (F.m() != n)
        F.reinit(n, n);
      if (n > 0)
        Utilities::MPI::broadcast(&F(0, 0),
                                  std::size_t(n) * n,
                                  layout.root,
                                  layout.world);
    }



    template <int dim>
    FullMatrix<double>
    Body<dim>::flexibility_in_group(
      const std::vector<PointOperator<dim>> &operators,
      const std::vector<Tensor<1, dim>>     &directions) const
    {
      AssertDimension(operators.size(), directions.size());
      const unsigned int n = operators.size();
      FullMatrix<double> F(n, n);
      if (n == 0)
        return F;
      if (has_schur_complement())
        {
          // Dense work on the root alone (every rank of the group holds the
          // factor of S; the others would only repeat it).
          if (Utilities::MPI::this_mpi_process(layout.world) != layout.root)
            return FullMatrix<double>();
          // Columns of point forces on the interface unknowns: F = C^T S^-1 C
          // (the readout of a point displacement is the transpose of the
          // point-force distribution).
          const auto      &dofs = linear_solver->cholesky->interface_dofs();
          std::vector<int> position(n_unknowns, -1);
          for (unsigned int a = 0; a < dofs.size(); ++a)
            position[dofs[a]] = a;
          FullMatrix<double> C(dofs.size(), n);
          for (unsigned int j = 0; j < n; ++j)
            {
              const auto &op = operators[j];
              for (unsigned int k = 0; k < op.weights.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const auto i = op.dofs[k][c];
                    if (position[i] >= 0)
                      C(position[i], j) += op.weights[k] * directions[j][c];
                    else
                      // Dropping it would give a wrong F silently.
                      AssertThrow(op.weights[k] == 0. ||
                                    solve_constraints.is_constrained(i),
                                  ExcMessage("A point operator touches an "
                                             "unknown outside the Schur "
                                             "interface; factorize() must "
                                             "be given these operators."));
                  }
            }
          FullMatrix<double> F0 =
            linear_solver->cholesky->interface_flexibility(std::move(C));
          correct_for_held_modes(operators, directions, F0);
          return F0;
        }

      // One solve per column on the shared factorisation (the group's;
      // the root's columns hold the solutions).
      std::vector<Vector<double>> columns(n, Vector<double>(n_unknowns));
      for (unsigned int j = 0; j < n; ++j)
        operators[j].distribute(directions[j], columns[j]);
      solve_in_group(columns);
      if (Utilities::MPI::this_mpi_process(layout.world) != layout.root)
        return FullMatrix<double>();
      for (unsigned int j = 0; j < n; ++j)
        for (unsigned int i = 0; i < n; ++i)
          F(i, j) = directions[i] * operators[i].displacement(columns[j]);
      return F;
    }



    template <int dim>
    bool
    Body<dim>::has_schur_complement() const
    {
      return linear_solver->cholesky &&
             linear_solver->cholesky->n_interface() > 0;
    }



    template <int dim>
    unsigned int
    Body<dim>::n_interface_dofs() const
    {
      return (linear_solver->cholesky ? linear_solver->cholesky->n_interface() :
                                        0);
    }



    template <int dim>
    double
    Body<dim>::factor_entries() const
    {
      return (linear_solver->cholesky ?
                linear_solver->cholesky->factor_entries() :
                0.);
    }



    template <int dim>
    double
    Body<dim>::factor_flops() const
    {
      return (
        linear_solver->cholesky ? linear_solver->cholesky->factor_flops() : 0.);
    }



    template <int dim>
    bool
    Body<dim>::contains(const Point<dim> &location) const
    {
      try
        {
          point_operator(location);
          return true;
        }
      catch (const ExceptionBase &)
        {
          return false;
        }
    }



    template <int dim>
    unsigned int
    Body<dim>::dof_component(const types::global_dof_index i) const
    {
      AssertIndexRange(i, dof_components.size());
      return dof_components[i];
    }



    template <int dim>
    const Point<dim> &
    Body<dim>::dof_location(const types::global_dof_index i) const
    {
      AssertIndexRange(i, dof_locations.size());
      return dof_locations[i];
    }



    template <int dim>
    Tensor<1, dim>
    Body<dim>::support_reaction(const Vector<double> &u,
                                const Vector<double> &f) const
    {
      AssertDimension(u.size(), n_unknowns);
      AssertDimension(f.size(), n_unknowns);
      // Under a parallel layout the root computes it (every rank has the
      // same u and f) and hands it to all; K u comes from the root's K, or
      // from the group's shares when the group divided the assembly.
      std::array<double, dim> reaction{};
      const bool              root =
        (Utilities::MPI::this_mpi_process(layout.world) == layout.root);
      if (root || assembled_share)
        {
          AssertThrow(assembled, ExcInternalError());
          Vector<double> r = stiffness_times(u);
          r -= f;
          if (root)
            for (types::global_dof_index i = 0; i < n_unknowns; ++i)
              if (constraints.is_constrained(i))
                reaction[dof_components[i]] += r[i];
        }
      if (Utilities::MPI::n_mpi_processes(layout.world) > 1)
        Utilities::MPI::broadcast(reaction.data(),
                                  dim,
                                  layout.root,
                                  layout.world);
      Tensor<1, dim> result;
      for (unsigned int c = 0; c < dim; ++c)
        result[c] = reaction[c];
      return result;
    }



    template <int dim>
    std::vector<double>
    Body<dim>::face_motion_reaction(const Vector<double> &u,
                                    const Vector<double> &f,
                                    const unsigned int    k) const
    {
      AssertIndexRange(k, description().face_motions.size());
      const FaceMotion<dim> &motion = description().face_motions[k];
      const unsigned int     n_axes = (dim == 2 ? 1 : 3);
      std::vector<double>    result(dim + n_axes, 0.);
      const bool             root =
        (Utilities::MPI::this_mpi_process(layout.world) == layout.root);
      if (root || assembled_share)
        {
          AssertThrow(assembled, ExcInternalError());
          // K u: collective on the group when it divided the assembly; the
          // root alone sums the reactions.
          Vector<double> r = stiffness_times(u);
          r -= f;
          if (root)
            for (const types::global_dof_index i :
                 dirichlet_dofs.at(motion.condition))
              {
                const unsigned int   c = dof_components[i];
                const Tensor<1, dim> y = dof_locations[i] - motion.centre;
                result[c] += r[i];
                // The moment of the force r_i e_c at y: (y x e_c) r_i.
                if (dim == 2)
                  result[dim] += (c == 1 ? y[0] : -y[1]) * r[i];
                else
                  for (unsigned int a = 0; a < 3; ++a)
                    if (a != c)
                      result[dim + a] +=
                        ((c == (a + 2) % 3) ? y[(a + 1) % 3] :
                                              -y[(a + 2) % 3]) *
                        r[i];
              }
        }
      if (Utilities::MPI::n_mpi_processes(layout.world) > 1)
        Utilities::MPI::broadcast(result.data(),
                                  result.size(),
                                  layout.root,
                                  layout.world);
      return result;
    }



    template <int dim>
    const SparseMatrix<double> &
    Body<dim>::stiffness_matrix() const
    {
      Assert(assembled && !assembled_share,
             ExcMessage("K is not assembled on this rank."));
      AssertThrow(!reduced_to_reaction_rows,
                  ExcMessage("K was reduced to its reaction rows "
                             "(keep_reaction_rows_only())."));
      return system_matrix;
    }



    template <int dim>
    bool
    Body<dim>::is_held(const types::global_dof_index i) const
    {
      return solve_constraints.is_constrained(i);
    }



    template <int dim>
    bool
    Body<dim>::is_supported(const types::global_dof_index i) const
    {
      return constraints.is_constrained(i);
    }



    template <int dim>
    types::global_dof_index
    Body<dim>::n_dofs() const
    {
      return n_unknowns;
    }



    template <int dim>
    const BodyDescription<dim> &
    Body<dim>::description() const
    {
      return *body_description;
    }



    template <int dim>
    const std::string &
    Body<dim>::name() const
    {
      return body_description->name;
    }



    template <int dim>
    const elasticity::IsotropicMaterial<dim> &
    Body<dim>::material() const
    {
      return body_description->material;
    }



    template <int dim>
    const Vector<double> &
    Body<dim>::load_solution() const
    {
      return u_history[0];
    }



    template <int dim>
    const Vector<double> &
    Body<dim>::prescribed_solution() const
    {
      return u_history[1];
    }



    template <int dim>
    const Vector<double> &
    Body<dim>::load_vector() const
    {
      return load_rhs;
    }



    template <int dim>
    unsigned int
    Body<dim>::n_histories() const
    {
      return history_rhs.size();
    }



    template <int dim>
    const Vector<double> &
    Body<dim>::history_solution(const unsigned int h) const
    {
      AssertIndexRange(h, u_history.size());
      return u_history[h];
    }



    template <int dim>
    const Vector<double> &
    Body<dim>::history_load_vector(const unsigned int h) const
    {
      AssertIndexRange(h, history_rhs.size());
      return history_rhs[h];
    }



    template <int dim>
    Vector<double>
    Body<dim>::external_solution(const std::vector<double> &factors) const
    {
      Vector<double> u(n_unknowns);
      for (unsigned int h = 0; h < u_history.size() && h < factors.size(); ++h)
        u.add(factors[h], u_history[h]);
      return u;
    }



    template <int dim>
    Vector<double>
    Body<dim>::external_load_vector(const std::vector<double> &factors) const
    {
      Vector<double> f(n_unknowns);
      for (unsigned int h = 0; h < history_rhs.size() && h < factors.size();
           ++h)
        f.add(factors[h], history_rhs[h]);
      return f;
    }



    template <int dim>
    void
    Body<dim>::assemble_history_loads(
      const std::function<void(const elasticity::BodyForce<dim> &,
                               const std::vector<NeumannCondition<dim>> &,
                               SparseMatrix<double> &,
                               Vector<double> &)> &assemble,
      const std::function<void(const PointLoad<dim> &, Vector<double> &)>
        &point_load)
    {
      const BodyDescription<dim> &d   = description();
      const unsigned int          n_h = d.n_histories();
      history_rhs.assign(n_h, Vector<double>(n_unknowns));
      SparseMatrix<double> scratch;
      for (unsigned int h = 0; h < n_h; ++h)
        {
          std::vector<NeumannCondition<dim>> tractions;
          for (const auto &t : d.tractions)
            if (t.history == h)
              tractions.push_back(t);
          if (h == 0)
            {
              system_matrix.reinit(sparsity);
              assemble(elasticity::BodyForce<dim>{d.body_force,
                                                  d.body_force_field},
                       tractions,
                       system_matrix,
                       history_rhs[h]);
            }
          else if (!tractions.empty())
            {
              // The tractions' loads only (an empty matrix: no stiffness).
              assemble(elasticity::BodyForce<dim>(),
                       tractions,
                       scratch,
                       history_rhs[h]);
            }
          // Point loads and moments once: by the rank whose cells start at
          // the first (all of them unless the group divides the assembly).
          if (assembly_cells.first > 0)
            continue;
          for (const auto &load : d.point_loads)
            if (load.history == h)
              point_load(load, history_rhs[h]);
          // A moment M on a face: the loads sum_a alpha_a c_a of the
          // tractions alpha_a e_a x (x - x_c), whose moment J alpha is M.
          for (const auto &moment : d.moments)
            if (moment.history == h)
              {
                std::vector<Vector<double>> c;
                FullMatrix<double>          J, J_inverse;
                face_rotation_loads(moment.boundary_id, c, J);
                AssertDimension(moment.moment.size(), c.size());
                J_inverse.reinit(J.m(), J.n());
                J_inverse.invert(J);
                for (unsigned int a = 0; a < c.size(); ++a)
                  {
                    double alpha = 0.;
                    for (unsigned int b = 0; b < c.size(); ++b)
                      alpha += J_inverse(a, b) * moment.moment[b];
                    history_rhs[h].add(alpha, c[a]);
                  }
              }
        }
      load_rhs = history_rhs[0];
    }



    template <int dim>
    const std::vector<Vector<double>> &
    Body<dim>::free_rigid_modes() const
    {
      return rigid_modes.free_modes();
    }



    template <int dim>
    const std::vector<std::string> &
    Body<dim>::free_rigid_mode_names() const
    {
      return rigid_modes.free_mode_names();
    }



    template <int dim>
    bool
    Body<dim>::free_translation(const unsigned int c) const
    {
      return rigid_modes.free_translation(c);
    }



    template <int dim>
    void
    Body<dim>::find_free_rigid_modes()
    {
      rigid_modes = RigidModes<dim>(dof_locations, dof_components, constraints);

      // Pins: one unknown per free mode, independent there (RigidModes::
      // pins()). With balanced loads the pins carry no reaction, so the
      // pinned solve is a generalised inverse K^+ (method.md, "Bodies held
      // only through contact"). A rotation held later (hold_rotations())
      // keeps its pin: the pinned solve of loads balanced in that mode,
      // projected.
      //
      // In floating point a pin does carry a reaction: the round-off of the
      // whole body's balance, about 1e-12 of the load. On a contact pair
      // that reaction is one pair's force error, and divided by the pair's
      // area a pressure error (the corner pair of the 3D contact patch at
      // 20 000 pairs: 1.2e-6). The pins' choice therefore sees boundary
      // unknowns weighted by 1e-3 and interior ones by pin_preference()
      // (deepest first, then nearest the centroid), so that pins sit inside
      // the body, where their reaction spreads before it reaches a surface;
      // a body without interior unknowns keeps the plain choice.
      solve_constraints.clear();
      solve_constraints.copy_from(constraints);
      if (!rigid_modes.free_modes().empty())
        {
          AffineConstraints<double> pins;
          for (const auto i : rigid_modes.pins(pin_preference()))
            pins.add_line(i);
          pins.close();
          solve_constraints.merge(pins);
        }
      solve_constraints.close();
    }



    template <int dim>
    std::vector<double>
    Body<dim>::pin_preference() const
    {
      std::vector<double> weights(n_unknowns, 1.);
      if (on_boundary.size() != n_unknowns)
        return weights;
      // Breadth-first search from the boundary through K's pattern.
      constexpr unsigned int    unreached = static_cast<unsigned>(-1);
      std::vector<unsigned int> depth(n_unknowns, unreached);
      std::vector<types::global_dof_index> front, next;
      for (types::global_dof_index i = 0; i < n_unknowns; ++i)
        if (on_boundary[i])
          {
            depth[i] = 0;
            front.push_back(i);
          }
      unsigned int max_depth = 0;
      while (!front.empty())
        {
          next.clear();
          for (const auto i : front)
            for (auto entry = sparsity.begin(i); entry != sparsity.end(i);
                 ++entry)
              if (depth[entry->column()] == unreached)
                {
                  depth[entry->column()] = depth[i] + 1;
                  max_depth              = depth[i] + 1;
                  next.push_back(entry->column());
                }
          front.swap(next);
        }
      if (max_depth == 0)
        return weights;
      // Among equally deep unknowns (a plate one cell thick has one interior
      // layer), the one nearest the centroid: half a depth step at most.
      for (types::global_dof_index i = 0; i < n_unknowns; ++i)
        if (depth[i] == 0)
          weights[i] = 1e-3;
        else
          {
            const double closeness =
              1. - (dof_locations[i] - rigid_modes.centre()).norm() /
                     rigid_modes.size();
            weights[i] =
              1. + (std::min(depth[i], max_depth) + 0.5 * closeness) /
                     (max_depth + 1.);
          }
      return weights;
    }



    template <int dim>
    void
    Body<dim>::face_rotation_loads(const types::boundary_id     face,
                                   std::vector<Vector<double>> &c,
                                   FullMatrix<double>          &J) const
    {
      // Gauss points of the face (two more per direction than its degree:
      // the tractions below are linear in x on a curved face too, up to
      // the geometry's rational factor).
      const FaceGrid<dim>         grid = face_grid(face);
      const QGauss<1>             gauss(grid.degree + 2);
      std::vector<Point<dim - 1>> etas(1);
      std::vector<double>         weights(1, 1.);
      for (unsigned int d = 0; d < dim - 1; ++d)
        {
          std::vector<Point<dim - 1>> next_etas;
          std::vector<double>         next_weights;
          const auto                 &b = grid.breaks[d];
          for (unsigned int k = 0; k < etas.size(); ++k)
            for (unsigned int e = 0; e + 1 < b.size(); ++e)
              for (unsigned int q = 0; q < gauss.size(); ++q)
                {
                  Point<dim - 1> eta = etas[k];
                  const double   h   = b[e + 1] - b[e];
                  eta[d]             = b[e] + h * gauss.point(q)[0];
                  next_etas.push_back(eta);
                  next_weights.push_back(weights[k] * h * gauss.weight(q));
                }
          etas.swap(next_etas);
          weights.swap(next_weights);
        }
      std::vector<FacePoint<dim>> points;
      double                      area = 0.;
      Point<dim>                  centroid;
      for (unsigned int q = 0; q < etas.size(); ++q)
        {
          points.push_back(face_point(face, etas[q]));
          weights[q] *= points.back().measure;
          area += weights[q];
          centroid += weights[q] * points.back().location;
        }
      AssertThrow(area > 0.,
                  ExcMessage("Body '" + description().name + "': face " +
                             std::to_string(face) +
                             " has no area: no rotation or moment can act "
                             "on it."));
      centroid /= area;

      // One traction per rotation axis, t_a = e_a x (x - centroid): a pure
      // moment (zero resultant) whose consistent loads c_a are the
      // constraint's direction; J_ab = int (|y|^2 delta_ab - y_a y_b) is the
      // moment of t_a about axis b.
      const unsigned int n_axes = (dim == 2 ? 1 : 3);
      c.assign(n_axes, Vector<double>(n_unknowns));
      J.reinit(n_axes, n_axes);
      for (unsigned int q = 0; q < points.size(); ++q)
        {
          const Tensor<1, dim> y = points[q].location - centroid;
          for (unsigned int a = 0; a < n_axes; ++a)
            {
              Tensor<1, dim> t;
              if (dim == 2)
                {
                  t[0] = -y[1];
                  t[1] = y[0];
                }
              else
                {
                  const unsigned int b = (a + 1) % 3, d = (a + 2) % 3;
                  t[b] = -y[d];
                  t[d] = y[b];
                }
              points[q].op.distribute(weights[q] * t, c[a]);
              for (unsigned int b = 0; b < n_axes; ++b)
                J(a, b) += weights[q] * ((a == b ? y * y : 0.) -
                                         (dim == 2 ? 0. : y[a] * y[b]));
            }
        }
      for (auto &v : c)
        constraints.set_zero(v);
    }



    template <int dim>
    void
    Body<dim>::hold_rotations()
    {
      held_response.clear();
      const int face = description().hold_rotation_face;
      if (face < 0 || rigid_modes.free_modes().empty())
        return;
      std::vector<Vector<double>> c;
      FullMatrix<double>          J;
      face_rotation_loads(face, c, J);
      rigid_modes.hold(c, J);
    }



    template <int dim>
    std::vector<double>
    Body<dim>::held_moment(const Vector<double> &f) const
    {
      return rigid_modes.held_moment(f);
    }



    template <int dim>
    void
    Body<dim>::correct_for_held_modes(
      const std::vector<PointOperator<dim>> &operators,
      const std::vector<Tensor<1, dim>>     &directions,
      FullMatrix<double>                    &F) const
    {
      const auto        &held_modes   = rigid_modes.held_modes();
      const auto        &held_loads   = rigid_modes.held_loads();
      const auto        &held_inverse = rigid_modes.held_inverse();
      const unsigned int r            = held_modes.size();
      const unsigned int n            = operators.size();
      if (r == 0 || n == 0)
        return;
      AssertDimension(held_response.size(), r);
      Eigen::MatrixXd A(r, n), B(n, r), Gamma(r, r), S_inv(r, r);
      for (unsigned int k = 0; k < r; ++k)
        {
          for (unsigned int j = 0; j < n; ++j)
            {
              A(k, j) =
                directions[j] * operators[j].displacement(held_modes[k]);
              B(j, k) =
                directions[j] * operators[j].displacement(held_response[k]);
            }
          for (unsigned int l = 0; l < r; ++l)
            {
              Gamma(k, l) = held_loads[k] * held_response[l];
              S_inv(k, l) = held_inverse(k, l);
            }
        }
      const Eigen::MatrixXd M  = S_inv * A;
      const Eigen::MatrixXd BM = B * M;
      const Eigen::MatrixXd correction =
        M.transpose() * Gamma * M - BM - BM.transpose();
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          F(i, j) += correction(i, j);
    }



    template <int dim>
    const std::vector<std::string> &
    Body<dim>::held_rigid_mode_names() const
    {
      return rigid_modes.held_mode_names();
    }



    template <int dim>
    const SparsityPattern &
    Body<dim>::sparsity_pattern() const
    {
      return sparsity;
    }



    template <int dim>
    const AffineConstraints<double> &
    Body<dim>::support_constraints() const
    {
      return constraints;
    }



    template <int dim>
    SymmetricTensor<2, dim>
    Body<dim>::cauchy_stress(
      const Vector<double>                        &u,
      const Point<dim>                            &location,
      const elasticity::HyperelasticMaterial<dim> &material) const
    {
      const Tensor<2, dim> F = elasticity::deformation_gradient<dim>(
        displacement_gradient(u, location));
      AssertThrow(determinant(F) > 0.,
                  ExcMessage("Body '" + description().name +
                             "': det F <= 0 at (" + base::to_string(location) +
                             "): the element has inverted there."));
      return elasticity::cauchy_stress(F,
                                       material.second_piola_kirchhoff(
                                         elasticity::right_cauchy_green(F)));
    }



    template <int dim>
    Vector<double>
    Body<dim>::prescribed_values(const std::vector<double> &factors) const
    {
      Vector<double> g(n_unknowns);
      for (types::global_dof_index i = 0; i < n_unknowns; ++i)
        if (prescribed_constraints.is_constrained(i))
          {
            const auto         it = prescribed_history.find(i);
            const unsigned int h =
              (it != prescribed_history.end() ? it->second : 1u);
            g[i] = (h < factors.size() ? factors[h] : 0.) *
                   prescribed_constraints.get_inhomogeneity(i);
          }
      return g;
    }



    template <int dim>
    void
    Body<dim>::factorize_matrix(
      const std::vector<types::global_dof_index> &interface_dofs,
      const std::function<void()>                &matrix_read)
    {
      if (settings.linear_solver == discretization::LinearSolver::direct)
        {
          // MUMPS on the free block; constrained unknowns and pins are
          // eliminated (zero in every solution).
          std::vector<bool> eliminated(n_unknowns);
          for (types::global_dof_index i = 0; i < n_unknowns; ++i)
            eliminated[i] = solve_constraints.is_constrained(i);
          linear_solver->cholesky =
            std::make_unique<linear_algebra::SparseCholesky>();
          // Nested dissection in 3D, where it halves the factorisation's
          // flops, minimum degree in 2D, where it is the faster of the two
          // (doc/performance.md, "Cost growth").
          using Order = linear_algebra::SparseCholesky::PivotOrder;
          linear_solver->cholesky->initialize(system_matrix,
                                              eliminated,
                                              interface_dofs,
                                              dim == 3 ?
                                                Order::nested_dissection :
                                                Order::minimum_degree,
                                              layout.group,
                                              assembled_share,
                                              matrix_read);
          return;
        }

      // Zero the constrained rows and columns and keep a positive diagonal:
      // the solution is then zero there and the rest is the reduced system.
      linear_solver->constrained_matrix.reinit(sparsity);
      linear_solver->constrained_matrix.copy_from(system_matrix);
      double diagonal_scale = 0.;
      for (types::global_dof_index i = 0; i < n_unknowns; ++i)
        diagonal_scale += std::abs(system_matrix.diag_element(i));
      diagonal_scale /= std::max<types::global_dof_index>(n_unknowns, 1);

      for (types::global_dof_index row = 0; row < n_unknowns; ++row)
        {
          const bool row_constrained = solve_constraints.is_constrained(row);
          for (auto entry = linear_solver->constrained_matrix.begin(row);
               entry != linear_solver->constrained_matrix.end(row);
               ++entry)
            if (row_constrained ||
                solve_constraints.is_constrained(entry->column()))
              entry->value() = (entry->column() == row ? diagonal_scale : 0.);
        }
      if (settings.linear_solver == discretization::LinearSolver::cg_amg)
        {
          // ML with the displacement components as near-null space (one
          // constant mode per component) and the higher-order smoother
          // setting for p > 1.
          linear_solver->amg_matrix =
            std::make_unique<TrilinosWrappers::SparseMatrix>();
          linear_solver->amg_matrix->reinit(linear_solver->constrained_matrix);
          TrilinosWrappers::PreconditionAMG::AdditionalData data;
          data.elliptic              = true;
          data.higher_order_elements = (settings.degree > 1);
          data.smoother_sweeps       = 2;
          data.aggregation_threshold = 0.02;
          data.constant_modes.assign(dim, std::vector<bool>(n_unknowns));
          for (types::global_dof_index i = 0; i < n_unknowns; ++i)
            data.constant_modes[dof_components[i]][i] = true;
          linear_solver->amg =
            std::make_unique<TrilinosWrappers::PreconditionAMG>();
          linear_solver->amg->initialize(*linear_solver->amg_matrix, data);
        }
      else
        {
          linear_solver->direct_solver =
            std::make_unique<SparseDirectUMFPACK>();
          linear_solver->direct_solver->initialize(
            linear_solver->constrained_matrix);
        }
    }



    template <int dim>
    void
    Body<dim>::solve(std::vector<Vector<double>> &rhs_and_solutions) const
    {
      if (Utilities::MPI::n_mpi_processes(layout.world) == 1)
        {
          solve_in_group(rhs_and_solutions);
          return;
        }
      // The group solves the root's vectors (every rank computed the same
      // right-hand sides); the root hands the solutions to all.
      if (factorizes_here())
        solve_in_group(rhs_and_solutions);
      for (auto &v : rhs_and_solutions)
        Utilities::MPI::broadcast(v.data(),
                                  v.size(),
                                  layout.root,
                                  layout.world);
    }



    template <int dim>
    void
    Body<dim>::solve_in_group(
      std::vector<Vector<double>> &rhs_and_solutions) const
    {
      if (rigid_modes.held_modes().empty())
        {
          solve_pinned(rhs_and_solutions);
          return;
        }
      for (auto &v : rhs_and_solutions)
        rigid_modes.balance(v);
      solve_pinned(rhs_and_solutions);
      for (auto &v : rhs_and_solutions)
        rigid_modes.fix(v);
    }



    template <int dim>
    void
    Body<dim>::solve_pinned(
      std::vector<Vector<double>> &rhs_and_solutions) const
    {
      // The factorisation is shared; the columns are independent and are
      // solved in parallel chunks (UMFPACK's solve phase only reads it).
      auto solve_range = [&](const std::size_t begin, const std::size_t end) {
        for (std::size_t k = begin; k < end; ++k)
          {
            Vector<double> &v = rhs_and_solutions[k];
            AssertDimension(v.size(), n_unknowns);
            solve_constraints.set_zero(v);
            linear_solver->direct_solver->solve(v);
            solve_constraints.set_zero(v);
          }
      };
      const std::size_t n = rhs_and_solutions.size();
      if (linear_solver->cholesky)
        {
          // All columns in one multi-right-hand-side solve (BLAS-3).
          for (auto &v : rhs_and_solutions)
            solve_constraints.set_zero(v);
          linear_solver->cholesky->solve(rhs_and_solutions);
          for (auto &v : rhs_and_solutions)
            solve_constraints.set_zero(v);
          return;
        }
      if (linear_solver->amg)
        {
          // CG to a relative residual of Linear tolerance; one column after
          // the other (the ML preconditioner is not shared across threads).
          const bool   report = progress_stream != nullptr && n >= 100;
          Timer        clock;
          unsigned int tenths = 0;
          for (std::size_t k = 0; k < n; ++k)
            {
              if (report && 10 * k >= (tenths + 1) * n)
                {
                  ++tenths;
                  *progress_stream
                    << "  [progress] " << name() << ": CG with AMG, " << k
                    << " of " << n << " columns, " << std::setprecision(3)
                    << clock.wall_time() << " s" << std::setprecision(6)
                    << std::endl;
                }
              Vector<double> &v = rhs_and_solutions[k];
              AssertDimension(v.size(), n_unknowns);
              solve_constraints.set_zero(v);
              const Vector<double> rhs = v;
              v                        = 0.;
              if (rhs.l2_norm() == 0.)
                continue;
              SolverControl control(
                std::max<types::global_dof_index>(1000, n_unknowns),
                settings.linear_tolerance * rhs.l2_norm());
              SolverCG<Vector<double>> cg(control);
              cg.solve(*linear_solver->amg_matrix, v, rhs, *linear_solver->amg);
              solve_constraints.set_zero(v);
            }
          return;
        }
      const std::size_t n_chunks =
        std::min<std::size_t>(MultithreadInfo::n_threads(), n);
      if (n_chunks <= 1)
        {
          solve_range(0, n);
          return;
        }
      // What a chunk throws is kept here: deal.II 9.4's join() does not
      // rethrow a void task's exception.
      std::vector<std::exception_ptr> errors(n_chunks);
      Threads::TaskGroup<void>        tasks;
      for (std::size_t c = 0; c < n_chunks; ++c)
        {
          const std::size_t begin = c * n / n_chunks;
          const std::size_t end   = (c + 1) * n / n_chunks;
          tasks += Threads::new_task([&solve_range, &errors, c, begin, end]() {
            try
              {
                solve_range(begin, end);
              }
            catch (...)
              {
                errors[c] = std::current_exception();
              }
          });
        }
      tasks.join_all();
      for (const auto &error : errors)
        if (error)
          std::rethrow_exception(error);
    }



    template <int dim>
    void
    Body<dim>::set_progress_stream(std::ostream *stream)
    {
      progress_stream = stream;
    }



    template <int dim>
    SurfacePoint<dim>
    Body<dim>::closest_surface_point(const types::boundary_id,
                                     const Point<dim>        &location,
                                     const SurfacePoint<dim> &nearest) const
    {
      SurfacePoint<dim> result = nearest;
      result.tributary_area    = 0.;
      const Point<dim> projected =
        location -
        ((location - nearest.location) * nearest.normal) * nearest.normal;
      try
        {
          result.op       = point_operator(projected);
          result.location = projected;
        }
      catch (const ExceptionBase &)
        {
          // The projection left a curved face: keep the nearest point.
        }
      return result;
    }



    template <int dim>
    std::unique_ptr<Body<dim>>
    create_body(const BodyDescription<dim>   &description,
                const DiscretizationSettings &settings)
    {
      if (settings.type == Type::nurbs)
        return std::make_unique<IgaBody<dim>>(description, settings);
      return std::make_unique<LagrangeBody<dim>>(description, settings);
    }



    template struct PointOperator<2>;
    template struct PointOperator<3>;
    template class Body<2>;
    template class Body<3>;
    template std::unique_ptr<Body<2>>
    create_body(const BodyDescription<2> &, const DiscretizationSettings &);
    template std::unique_ptr<Body<3>>
    create_body(const BodyDescription<3> &, const DiscretizationSettings &);
  } // namespace discretization
} // namespace igabde
