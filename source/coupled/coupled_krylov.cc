// The coupled system's iterative solver (Contact/Full system solver =
// gmres-amg): the displacement block's AMG, GMRES on the Newton matrix
// with the block preconditioner, and its application. The direct solvers
// and the assembly are in coupled_system.cc.
//
// Its own translation unit outside the unity batches: the members defined
// here are instantiated one by one below, and coupled_system.cc
// instantiates the class, which in one unity file would instantiate these
// members twice.

#include <igabde/coupled/coupled_system.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_vector.h>

#include <sstream>

namespace igabde
{
  namespace coupled
  {
    template <int dim>
    void
    CoupledSystem<dim>::setup_krylov()
    {
      // The displacement block: K of both bodies, held rows scale times
      // identity (as in the Newton matrix); it never changes, so its AMG
      // is set up once. Distributed as the Newton matrix's displacement
      // rows: this rank's [u_begin, u_end).
      displacement_set = IndexSet(n_u);
      displacement_set.add_range(u_begin, u_end);
      displacement_set.compress();
      DynamicSparsityPattern dsp(n_u, n_u, displacement_set);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          const SparseMatrix<double> &K = bodies[b]->stiffness_matrix();
          for (types::global_dof_index i = 0; i < K.m(); ++i)
            {
              const unsigned int gi = offsets[b] + i;
              if (!displacement_set.is_element(gi))
                continue;
              if (held[gi])
                dsp.add(gi, gi);
              else
                for (auto e = K.begin(i); e != K.end(i); ++e)
                  if (!held[offsets[b] + e->column()])
                    dsp.add(gi, offsets[b] + e->column());
            }
        }
      K_matrix.reinit(displacement_set,
                      displacement_set,
                      dsp,
                      this->communicator);
      // D, the diagonal of K on every row (every rank forms the same S~).
      std::vector<double> diagonal(n_u, scale);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          const SparseMatrix<double> &K = bodies[b]->stiffness_matrix();
          for (types::global_dof_index i = 0; i < K.m(); ++i)
            {
              const unsigned int gi = offsets[b] + i;
              if (held[gi])
                {
                  if (displacement_set.is_element(gi))
                    K_matrix.set(gi, gi, scale);
                  continue;
                }
              diagonal[gi] = K.diag_element(i);
              if (!displacement_set.is_element(gi))
                continue;
              for (auto e = K.begin(i); e != K.end(i); ++e)
                if (!held[offsets[b] + e->column()])
                  K_matrix.set(gi, offsets[b] + e->column(), e->value());
            }
        }
      K_matrix.compress(VectorOperation::insert);

      // Near null space of the AMG: the rigid-body modes of each body
      // (translations and rotations about its centre, from the control
      // points or nodes: exact rigid motions of the discrete space).
      // Smoothed aggregation with translations only coarsens the bending
      // of slender bodies badly.
      // ML reads this rank's rows, mode by mode.
      const unsigned int n_modes = (dim == 2 ? 3 : 6);
      const std::size_t  n_local = u_end - u_begin;
      null_space.assign(std::size_t(n_modes) * n_local, 0.);
      bool node_blocks = true;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          Point<dim>   centre;
          const auto  &body = *bodies[b];
          const double n    = std::max<double>(body.n_dofs(), 1.);
          for (types::global_dof_index i = 0; i < body.n_dofs(); ++i)
            centre += body.dof_location(i) / n;
          double size = 0.;
          for (types::global_dof_index i = 0; i < body.n_dofs(); ++i)
            size = std::max(size, body.dof_location(i).distance(centre));
          size = size > 0. ? size : 1.;
          for (types::global_dof_index i = 0; i < body.n_dofs(); ++i)
            {
              const std::size_t  g = offsets[b] + i;
              const unsigned int c = body.dof_component(i);
              node_blocks          = node_blocks && (g % dim == c);
              if (g < u_begin || g >= u_end)
                continue;
              const std::size_t    l = g - u_begin;
              const Tensor<1, dim> x = (body.dof_location(i) - centre) / size;
              null_space[c * n_local + l] = 1.;
              if (dim == 2)
                null_space[2 * n_local + l] = (c == 0 ? -x[1] : x[0]);
              else
                {
                  // Rotations about x, y, z: (0,-z,y), (z,0,-x), (-y,x,0).
                  const double rx[3]          = {0., -x[dim - 1], x[1]};
                  const double ry[3]          = {x[dim - 1], 0., -x[0]};
                  const double rz[3]          = {-x[1], x[0], 0.};
                  null_space[3 * n_local + l] = rx[c];
                  null_space[4 * n_local + l] = ry[c];
                  null_space[5 * n_local + l] = rz[c];
                }
            }
        }
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.higher_order_elements = true;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 1e-4;
      Teuchos::ParameterList              list;
      std::unique_ptr<Epetra_MultiVector> unused;
      data.set_parameters(list, unused, K_matrix);
      list.set("null space: type", "pre-computed");
      list.set("null space: dimension", static_cast<int>(n_modes));
      list.set("null space: vectors", null_space.data());
      // ML aggregates blocks of "PDE equations" consecutive unknowns: the
      // components of one control point or node when they are numbered
      // together, else one unknown at a time.
      list.set("PDE equations", node_blocks ? dim : 1);
      amg.initialize(K_matrix, list);

      // C D^-1 C^T, the flexibility of the pairs if each unknown were held
      // by its own diagonal stiffness (sparse: pairs that share no unknown
      // do not couple).
      std::vector<Eigen::Triplet<double>> entries;
      for (unsigned int r = 0; r < d * n_pairs; ++r)
        for (const auto &[g, v] : C_rows[r])
          entries.emplace_back(r, g, v / std::sqrt(diagonal[g]));
      Eigen::SparseMatrix<double> C_scaled(d * n_pairs, n_u);
      C_scaled.setFromTriplets(entries.begin(), entries.end());
      local_flexibility = C_scaled * C_scaled.transpose();
    }



    template <int dim>
    bool
    CoupledSystem<dim>::solve_krylov(const TrilinosWrappers::MPI::Vector &rhs,
                                     TrilinosWrappers::MPI::Vector       &x,
                                     const double relative_tolerance,
                                     std::string &why) const
    {
      // Right preconditioning: GMRES measures the residual of the
      // Newton system itself (rows in force units), not a
      // preconditioned one.
      const double  target = relative_tolerance * rhs.l2_norm();
      SolverControl gmres_control(krylov_max_iterations, target, false, false);
      SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
        gmres_control,
        SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(102, true));
      struct Preconditioner
      {
        const CoupledSystem<dim> *system;
        void
        vmult(TrilinosWrappers::MPI::Vector       &dst,
              const TrilinosWrappers::MPI::Vector &src) const
        {
          system->apply_preconditioner(dst, src);
        }
      } preconditioner{this};
      try
        {
          if (target > 0.)
            gmres.solve(matrix, x, rhs, preconditioner);
          last_iterations = gmres_control.last_step();
        }
      catch (const SolverControl::NoConvergence &e)
        {
          last_iterations = e.last_step;
          std::ostringstream message;
          message << "GMRES (AMG and Schur-complement preconditioner) "
                     "did not converge on the Newton matrix of the "
                     "coupled system: "
                  << e.last_step << " iterations, residual "
                  << e.last_residual / rhs.l2_norm()
                  << " relative to the right-hand side, required "
                  << relative_tolerance
                  << " (raise Contact/Krylov max iterations, or use "
                     "Contact/Full system solver = mumps)";
          why = message.str();
          return false;
        }
      return true;
    }



    template <int dim>
    void
    CoupledSystem<dim>::apply_preconditioner(
      TrilinosWrappers::MPI::Vector       &dst,
      const TrilinosWrappers::MPI::Vector &src) const
    {
      // Block back substitution with P = [K U; 0 S~]: y = S~^-1 g, then
      // x = AMG(f - U y) = AMG(f + C^T s y_p). The pair and rigid-mode
      // rows g are few: every rank gathers them all and solves with S~;
      // the displacement rows stay distributed. A vector's local entries
      // are this rank's displacement rows, then its pair rows.
      const unsigned int m       = d * n_pairs;
      const std::size_t  n_local = u_end - u_begin;
      const std::size_t  g_local = owned.n_elements() - n_local;
      const std::size_t  g_begin =
        (g_local > 0 ? owned.nth_index_in_set(n_local) - n_u : 0);
      Eigen::VectorXd g  = Eigen::VectorXd::Zero(m + n_alpha);
      const double   *in = src.begin();
      for (std::size_t k = 0; k < g_local; ++k)
        g[g_begin + k] = in[n_local + k];
      if (Utilities::MPI::n_mpi_processes(communicator) > 1)
        Utilities::MPI::sum(ArrayView<const double>(g.data(), g.size()),
                            communicator,
                            ArrayView<double>(g.data(), g.size()));
      const Eigen::VectorXd         y = schur_lu.solve(g);
      TrilinosWrappers::MPI::Vector f(displacement_set, communicator),
        x(displacement_set, communicator);
      double *out = f.begin();
      for (std::size_t k = 0; k < n_local; ++k)
        out[k] = in[k];
      for (unsigned int r = 0; r < m; ++r)
        for (const auto &[j, v] : C_rows[r])
          if (j >= u_begin && j < u_end)
            out[j - u_begin] += v * scale * y[r];
      amg.vmult(x, f);
      double       *result = dst.begin();
      const double *xs     = x.begin();
      for (std::size_t k = 0; k < n_local; ++k)
        result[k] = xs[k];
      for (std::size_t k = 0; k < g_local; ++k)
        result[n_local + k] = y[g_begin + k];
    }



    template <int dim>
    unsigned int
    CoupledSystem<dim>::linear_iterations() const
    {
      return last_iterations;
    }



    template void
    CoupledSystem<2>::setup_krylov();
    template bool
    CoupledSystem<2>::solve_krylov(const TrilinosWrappers::MPI::Vector &,
                                   TrilinosWrappers::MPI::Vector &,
                                   const double,
                                   std::string &) const;
    template void
    CoupledSystem<2>::apply_preconditioner(
      TrilinosWrappers::MPI::Vector &,
      const TrilinosWrappers::MPI::Vector &) const;
    template unsigned int
    CoupledSystem<2>::linear_iterations() const;
    template void
    CoupledSystem<3>::setup_krylov();
    template bool
    CoupledSystem<3>::solve_krylov(const TrilinosWrappers::MPI::Vector &,
                                   TrilinosWrappers::MPI::Vector &,
                                   const double,
                                   std::string &) const;
    template void
    CoupledSystem<3>::apply_preconditioner(
      TrilinosWrappers::MPI::Vector &,
      const TrilinosWrappers::MPI::Vector &) const;
    template unsigned int
    CoupledSystem<3>::linear_iterations() const;
  } // namespace coupled
} // namespace igabde
