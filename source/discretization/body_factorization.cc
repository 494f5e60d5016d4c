#include <igabde/base/utilities.h>
#include <igabde/linear_algebra/sparse_cholesky.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>
#include <igabde/discretization/body_linear_solver.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iomanip>
#include <ostream>
#include <utility>

// The factorisation of a body and the solves with it: its load cases, the
// flexibility at contact points, the Schur interface, and how the ranks of
// a body's group share them.

namespace igabde
{
  namespace discretization
  {
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
        {
          // The group solves; where K is read no more, this rank has no
          // use for its pattern either (the pins were chosen from it).
          if (keep_reaction_rows && !assembled)
            sparsity.reinit(0, 0, 0);
          return;
        }
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
    std::vector<base::MemoryItem>
    Body<dim>::memory_record() const
    {
      const std::string             prefix = name() + ": ";
      std::vector<base::MemoryItem> items;
      items.push_back({prefix + "mesh", mesh_bytes(), false});

      double tables =
        base::vector_bytes(dof_locations) + base::vector_bytes(dof_components) +
        double(on_boundary.capacity()) / 8. + constraints.memory_consumption() +
        prescribed_constraints.memory_consumption() +
        solve_constraints.memory_consumption() +
        base::vector_bytes(dirichlet_dofs);
      for (const auto &dofs : dirichlet_dofs)
        tables += base::vector_bytes(dofs);
      // A std::map node: the entry and three pointers and a colour.
      tables +=
        double(prescribed_history.size()) *
        (sizeof(std::pair<const types::global_dof_index, unsigned int>) +
         4 * sizeof(void *));
      items.push_back({prefix + "unknowns' tables", tables, false});

      // K and its pattern are divided where only the body's group holds
      // them: the other ranks free the pattern once the group has
      // factorised (the condensed path).
      const bool matrix_divided =
        !layout.matrix_everywhere && !assembled_everywhere;
      items.push_back(
        {prefix + "sparsity pattern",
         double(sparsity.memory_consumption()) +
           (reaction_sparsity ? reaction_sparsity->memory_consumption() : 0.),
         matrix_divided});
      // K's values are allocated for the whole pattern also where a rank
      // assembles only its share of the cells.
      items.push_back({prefix + "stiffness matrix",
                       double(system_matrix.memory_consumption()),
                       matrix_divided});

      double vectors = load_rhs.memory_consumption();
      for (const std::vector<Vector<double>> *set :
           {&history_rhs, &u_history, &held_response})
        for (const auto &v : *set)
          vectors += v.memory_consumption();
      items.push_back({prefix + "load vectors and solutions", vectors, false});

      // MUMPS runs on the body's group (each rank a share of the factor,
      // or the body's own ranks alone); UMFPACK and CG with AMG on every
      // rank alike (UMFPACK's own LU is not counted: it reports no size).
      const LinearSolver &ls = *linear_solver;
      if (ls.cholesky)
        items.push_back(
          {prefix + "factorisation", ls.cholesky->local_bytes(), true});
      else
        items.push_back(
          {prefix + "factorisation",
           double(ls.constrained_matrix.memory_consumption()) +
             (ls.amg_matrix ? ls.amg_matrix->memory_consumption() : 0.) +
             (ls.amg ? ls.amg->memory_consumption() : 0.),
           false});
      return items;
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
          linear_solver->cholesky->set_progress(progress_stream, name());
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



    template void
    Body<2>::share_factorization();
    template void
    Body<3>::share_factorization();
    template void
    Body<2>::release_factorization();
    template void
    Body<3>::release_factorization();
    template void
    Body<2>::keep_reaction_rows_only();
    template void
    Body<3>::keep_reaction_rows_only();
    template void
    Body<2>::factorize(const std::vector<PointOperator<2>> &interface,
                       const bool                           keep_reaction_rows);
    template void
    Body<3>::factorize(const std::vector<PointOperator<3>> &interface,
                       const bool                           keep_reaction_rows);
    template FullMatrix<double>
    Body<2>::flexibility(const std::vector<PointOperator<2>> &operators,
                         const std::vector<Tensor<1, 2>>     &directions) const;
    template FullMatrix<double>
    Body<3>::flexibility(const std::vector<PointOperator<3>> &operators,
                         const std::vector<Tensor<1, 3>>     &directions) const;
    template void
    Body<2>::share_flexibility(FullMatrix<double> &F) const;
    template void
    Body<3>::share_flexibility(FullMatrix<double> &F) const;
    template FullMatrix<double>
    Body<2>::flexibility_in_group(
      const std::vector<PointOperator<2>> &operators,
      const std::vector<Tensor<1, 2>>     &directions) const;
    template FullMatrix<double>
    Body<3>::flexibility_in_group(
      const std::vector<PointOperator<3>> &operators,
      const std::vector<Tensor<1, 3>>     &directions) const;
    template bool
    Body<2>::has_schur_complement() const;
    template bool
    Body<3>::has_schur_complement() const;
    template unsigned int
    Body<2>::n_interface_dofs() const;
    template unsigned int
    Body<3>::n_interface_dofs() const;
    template std::vector<base::MemoryItem>
    Body<2>::memory_record() const;
    template std::vector<base::MemoryItem>
    Body<3>::memory_record() const;
    template double
    Body<2>::factor_entries() const;
    template double
    Body<3>::factor_entries() const;
    template double
    Body<2>::factor_flops() const;
    template double
    Body<3>::factor_flops() const;
    template void
    Body<2>::factorize_matrix(
      const std::vector<types::global_dof_index> &interface_dofs,
      const std::function<void()>                &matrix_read);
    template void
    Body<3>::factorize_matrix(
      const std::vector<types::global_dof_index> &interface_dofs,
      const std::function<void()>                &matrix_read);
    template void
    Body<2>::solve(std::vector<Vector<double>> &rhs_and_solutions) const;
    template void
    Body<3>::solve(std::vector<Vector<double>> &rhs_and_solutions) const;
    template void
    Body<2>::solve_in_group(
      std::vector<Vector<double>> &rhs_and_solutions) const;
    template void
    Body<3>::solve_in_group(
      std::vector<Vector<double>> &rhs_and_solutions) const;
    template void
    Body<2>::solve_pinned(std::vector<Vector<double>> &rhs_and_solutions) const;
    template void
    Body<3>::solve_pinned(std::vector<Vector<double>> &rhs_and_solutions) const;
  } // namespace discretization
} // namespace igabde
