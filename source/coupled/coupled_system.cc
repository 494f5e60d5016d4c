#include <igabde/base/memory_record.h>
#include <igabde/base/utilities.h>
#include <igabde/linear_algebra/sparse_cholesky.h>

#include <igabde/coupled/coupled_system.h>
#include <igabde/coupled/mumps_pivot_order.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_CrsMatrix.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace igabde
{
  namespace coupled
  {
    template <int dim>
    CoupledSystem<dim>::CoupledSystem(
      const std::vector<const discretization::Body<dim> *> &bodies,
      const std::vector<contact::ContactPair<dim>>         &pairs,
      const unsigned int                                    n_components,
      const Eigen::MatrixXd                                &G,
      const Solver                                          solver,
      const unsigned int krylov_max_iterations,
      const MPI_Comm     communicator)
      : bodies(bodies)
      , d(n_components)
      , n_pairs(pairs.size())
      , n_alpha(G.cols())
      , G(G)
      , solver_type(solver == Solver::klu       ? "Amesos_Klu" :
                    solver == Solver::gmres_amg ? "gmres-amg" :
                                                  "Amesos_Mumps")
      , communicator(communicator)
      , mumps(solver == Solver::mumps)
      , krylov(solver == Solver::gmres_amg)
      , krylov_max_iterations(krylov_max_iterations)
    {
      for (const auto *body : bodies)
        {
          offsets.push_back(n_u);
          n_u += body->n_dofs();
        }
      n_total = n_u + d * n_pairs + n_alpha;
      finite.assign(bodies.size(), false);
      reference.resize(bodies.size());
      support_moves.resize(bodies.size());
      loads.resize(bodies.size());
      tangents.resize(bodies.size());
      residuals.resize(bodies.size());
      force_norms.assign(bodies.size(), 0.);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        if (bodies[b]->finite_strain())
          {
            AssertThrow(bodies[b]->free_rigid_modes().empty(),
                        base::ExcInput(
                          bodies[b]->name() +
                          " at Kinematics = finite is held by contact alone "
                          "against " +
                          bodies[b]->free_rigid_mode_names().front() +
                          ", which is modelled at small strain only; add "
                          "Supports or Face motions that hold it."));
            AssertThrow(!krylov,
                        ExcMessage("the full path at finite strain "
                                   "factorises its Newton matrix (Contact/"
                                   "Full system solver = mumps or klu)"));
            finite[b]  = true;
            any_finite = true;
            tangents[b].reinit(bodies[b]->sparsity_pattern());
            residuals[b].reinit(bodies[b]->n_dofs());
          }
      held.assign(n_u, false);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        for (types::global_dof_index i = 0; i < bodies[b]->n_dofs(); ++i)
          held[offsets[b] + i] = bodies[b]->is_held(i);
      AssertDimension(G.rows(), d * n_pairs);

      set_C_rows(pairs);

      // Pair stiffness E A / h from the elements of the pair's bodies (E
      // of the two in series, the larger element size).
      double mean_area = 0.;
      for (const auto &pair : pairs)
        mean_area += pair.area / std::max<double>(n_pairs, 1);
      stiffness.resize(n_pairs);
      // Each body's mean element size once: measure() integrates over the
      // body.
      for (const auto *body : bodies)
        element_size.push_back(
          std::pow(body->measure() / body->n_elements(), 1. / dim));
      for (unsigned int i = 0; i < n_pairs; ++i)
        {
          double h = 0., inverse_modulus = 0.;
          for (const unsigned int b :
               {pairs[i].slave_body, pairs[i].master_body})
            if (b < bodies.size())
              {
                h = std::max(h, element_size[b]);
                inverse_modulus += 1. / bodies[b]->material().youngs_modulus;
              }
          const double area = pairs[i].area > 0. ? pairs[i].area :
                              mean_area > 0.     ? mean_area :
                                                   std::pow(h, dim - 1);
          stiffness[i]      = area / (inverse_modulus * h);
        }

      // Rows split among the ranks: each a contiguous share of the
      // displacement rows (cut between control points or nodes, so that
      // the AMG's blocks of dim unknowns stay on one rank) and of the pair
      // and rigid-mode rows. Each rank builds the sparsity of its own rows
      // only.
      all = complete_index_set(n_total);
      {
        const std::size_t n_ranks =
                            Utilities::MPI::n_mpi_processes(this->communicator),
                          rank = Utilities::MPI::this_mpi_process(
                            this->communicator);
        const std::size_t n_nodes = n_u / dim, n_rest = n_total - n_u;
        u_begin = dim * (n_nodes * rank / n_ranks);
        u_end   = dim * (n_nodes * (rank + 1) / n_ranks);
        owned   = IndexSet(n_total);
        owned.add_range(u_begin, u_end);
        owned.add_range(n_u + n_rest * rank / n_ranks,
                        n_u + n_rest * (rank + 1) / n_ranks);
        owned.compress();
      }

      // Column scale of the force unknowns: p = scale p~ with scale the
      // mean stiffness diagonal, so that every block of the Newton matrix
      // has entries of one magnitude (K ~ scale, C^T scale ~ scale); the
      // held rows get the same diagonal.
      double       sum = 0.;
      unsigned int n   = 0;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        for (types::global_dof_index i = 0; i < bodies[b]->n_dofs(); ++i)
          if (!held[offsets[b] + i])
            {
              sum += std::abs(bodies[b]->stiffness_matrix().diag_element(i));
              ++n;
            }
      scale = (n > 0 && sum > 0.) ? sum / n : 1.;

      build_pattern();
      if (krylov)
        setup_krylov();
    }



    template <int dim>
    void
    CoupledSystem<dim>::set_C_rows(
      const std::vector<contact::ContactPair<dim>> &pairs)
    {
      // C: per pair row, the unknowns of the two points in the local frame
      // (the master body's with the opposite sign).
      C_rows.assign(d * n_pairs, {});
      for (unsigned int i = 0; i < n_pairs; ++i)
        for (const unsigned int b : {pairs[i].slave_body, pairs[i].master_body})
          {
            if (b >= bodies.size())
              continue;
            double      sign = 0.;
            const auto &op   = *pairs[i].operator_on(b, sign);
            for (unsigned int k = 0; k < op.weights.size(); ++k)
              for (unsigned int c = 0; c < dim; ++c)
                {
                  const unsigned int g = offsets[b] + op.dofs[k][c];
                  if (held[g])
                    continue;
                  for (unsigned int s = 0; s < d; ++s)
                    {
                      // A frame component of round-off size (a tangent
                      // along an axis, from a mean of normals) is zero:
                      // else a direction whose unknowns the supports hold
                      // keeps a row of rounding and the glued Newton
                      // matrix of that row is singular.
                      if (std::abs(pairs[i].frame[s][c]) <= 1e-12)
                        continue;
                      const double v =
                        sign * op.weights[k] * pairs[i].frame[s][c];
                      if (v != 0.)
                        C_rows[d * i + s].emplace_back(g, v);
                    }
                }
          }
    }



    template <int dim>
    void
    CoupledSystem<dim>::build_pattern()
    {
      // Sparsity of the Newton matrix.
      DynamicSparsityPattern dsp(n_total, n_total, owned);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          const SparseMatrix<double> &K = bodies[b]->stiffness_matrix();
          for (types::global_dof_index i = 0; i < K.m(); ++i)
            {
              const unsigned int gi = offsets[b] + i;
              if (held[gi])
                {
                  dsp.add(gi, gi);
                  continue;
                }
              // At finite strain the free rows depend on the held
              // unknowns too, which move during the solve.
              for (auto e = K.begin(i); e != K.end(i); ++e)
                if (finite[b] || !held[offsets[b] + e->column()])
                  dsp.add(gi, offsets[b] + e->column());
            }
        }
      for (unsigned int i = 0; i < n_pairs; ++i)
        for (unsigned int s = 0; s < d; ++s)
          {
            const unsigned int r = n_u + d * i + s;
            for (unsigned int t = 0; t < d; ++t)
              {
                dsp.add(r, n_u + d * i + t);
                for (const auto &[g, v] : C_rows[d * i + t])
                  {
                    dsp.add(r, g);
                    dsp.add(g, r);
                  }
              }
            for (unsigned int a = 0; a < n_alpha; ++a)
              {
                dsp.add(r, n_u + d * n_pairs + a);
                dsp.add(n_u + d * n_pairs + a, r);
              }
          }
      for (unsigned int a = 0; a < n_alpha; ++a)
        dsp.add(n_u + d * n_pairs + a, n_u + d * n_pairs + a);
      // Finite sliding's geometric tangent (linearize_geometry()).
      for (const auto &[row, column] : extra_pattern)
        if (owned.is_element(row))
          dsp.add(row, column);
      matrix.reinit(owned, owned, dsp, this->communicator);
    }



    template <int dim>
    unsigned int
    CoupledSystem<dim>::n_dofs() const
    {
      return n_u;
    }



    template <int dim>
    unsigned int
    CoupledSystem<dim>::n_rows() const
    {
      return d * n_pairs;
    }



    template <int dim>
    const Eigen::VectorXd &
    CoupledSystem<dim>::element_pair_stiffness() const
    {
      return stiffness;
    }



    template <int dim>
    bool
    CoupledSystem<dim>::pair_row_is_held(const unsigned int row) const
    {
      AssertIndexRange(row, C_rows.size());
      return C_rows[row].empty();
    }



    template <int dim>
    double
    CoupledSystem<dim>::n_nonzeros() const
    {
      return matrix.n_nonzero_elements();
    }



    template <int dim>
    Eigen::VectorXd
    CoupledSystem<dim>::apply_C(const Eigen::VectorXd &w) const
    {
      AssertDimension(w.size(), n_u);
      return apply_rows(C_rows, w);
    }



    template <int dim>
    Eigen::VectorXd
    CoupledSystem<dim>::apply_rows(
      const std::vector<std::vector<std::pair<unsigned int, double>>> &rows,
      const Eigen::VectorXd                                           &v)
    {
      Eigen::VectorXd u(rows.size());
      for (unsigned int r = 0; r < rows.size(); ++r)
        {
          double sum = 0.;
          for (const auto &[g, value] : rows[r])
            sum += value * v[g];
          u[r] = sum;
        }
      return u;
    }



    template <int dim>
    Eigen::VectorXd
    CoupledSystem<dim>::displacement_equations(const Eigen::VectorXd &w,
                                               const Eigen::VectorXd &p) const
    {
      Eigen::VectorXd r = frozen_equations(w, p);
      // With the geometric tangent of linearize_geometry(): the pairs'
      // change from its iterate to w, to first order (zero there).
      if (geometric_valid)
        add_geometric_term(w - geometric_at, r);
      return r;
    }



    template <int dim>
    Eigen::VectorXd
    CoupledSystem<dim>::frozen_equations(const Eigen::VectorXd &w,
                                         const Eigen::VectorXd &p) const
    {
      AssertDimension(w.size(), n_u);
      AssertDimension(p.size(), d * n_pairs);
      Eigen::VectorXd r(n_u);
      // Bodies at finite strain: f_int(u_ref + w) - f_ext (not a number
      // where an element inverts: no step may go there).
      const bool finite_ok = !any_finite || evaluate_bodies(w, false);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          if (finite[b])
            {
              for (unsigned int i = 0; i < bodies[b]->n_dofs(); ++i)
                r[offsets[b] + i] = finite_ok ?
                                      residuals[b][i] :
                                      std::numeric_limits<double>::quiet_NaN();
              continue;
            }
          const SparseMatrix<double> &K = bodies[b]->stiffness_matrix();
          Vector<double>              wb(K.m()), rb(K.m());
          for (unsigned int i = 0; i < K.m(); ++i)
            wb[i] = held[offsets[b] + i] ? 0. : w[offsets[b] + i];
          K.vmult(rb, wb);
          for (unsigned int i = 0; i < K.m(); ++i)
            r[offsets[b] + i] = rb[i];
        }
      for (unsigned int row = 0; row < d * n_pairs; ++row)
        for (const auto &[g, v] : C_rows[row])
          r[g] -= v * p[row];
      for (unsigned int g = 0; g < n_u; ++g)
        if (held[g])
          r[g] = w[g];
      // At finite strain the held unknowns move to the supports' values.
      for (unsigned int b = 0; b < bodies.size(); ++b)
        if (finite[b])
          for (unsigned int i = 0; i < bodies[b]->n_dofs(); ++i)
            if (held[offsets[b] + i])
              r[offsets[b] + i] -= support_moves[b][i];
      return r;
    }



    template <int dim>
    bool
    CoupledSystem<dim>::finite_strain() const
    {
      return any_finite;
    }



    template <int dim>
    double
    CoupledSystem<dim>::displacement_equations_scale(
      const Eigen::VectorXd &w,
      const Eigen::VectorXd &p) const
    {
      Eigen::VectorXd r = Eigen::VectorXd::Zero(n_u);
      // A body at finite strain: the size of its internal forces (with the
      // reactions) and of its loads, and the moves of its held unknowns.
      double finite_terms = 0.;
      if (any_finite)
        evaluate_bodies(w, false);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          if (finite[b])
            {
              finite_terms += force_norms[b] * force_norms[b];
              for (unsigned int i = 0; i < bodies[b]->n_dofs(); ++i)
                if (held[offsets[b] + i])
                  r[offsets[b] + i] =
                    std::abs(w[offsets[b] + i]) + std::abs(support_moves[b][i]);
              continue;
            }
          const SparseMatrix<double> &K = bodies[b]->stiffness_matrix();
          for (types::global_dof_index i = 0; i < K.m(); ++i)
            {
              const unsigned int gi = offsets[b] + i;
              if (held[gi])
                {
                  r[gi] = std::abs(w[gi]);
                  continue;
                }
              for (auto e = K.begin(i); e != K.end(i); ++e)
                if (!held[offsets[b] + e->column()])
                  r[gi] += std::abs(e->value() * w[offsets[b] + e->column()]);
            }
        }
      for (unsigned int row = 0; row < d * n_pairs; ++row)
        for (const auto &[g, v] : C_rows[row])
          r[g] += std::abs(v * p[row]);
      if (!any_finite)
        return r.norm();
      return std::sqrt(r.squaredNorm() + finite_terms);
    }



    template <int dim>
    void
    CoupledSystem<dim>::factorize(const std::vector<Eigen::Matrix3d> &A,
                                  const std::vector<Eigen::Matrix3d> &B)
    {
      AssertDimension(A.size(), n_pairs);
      AssertDimension(B.size(), n_pairs);
      matrix = 0.;
      // Each rank adds its own rows only (every rank builds the same
      // system; added twice, an entry would count twice).
      const auto add = [this](const types::global_dof_index row,
                              const types::global_dof_index column,
                              const double                  value) {
        if (owned.is_element(row))
          matrix.add(row, column, value);
      };
      std::vector<types::global_dof_index> columns;
      std::vector<double>                  values;
      Assert(!any_finite || linearized, ExcMessage("linearize_bodies() first"));
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          // A body at finite strain: its tangent at the last linearisation.
          const SparseMatrix<double> &K =
            finite[b] ? tangents[b] : bodies[b]->stiffness_matrix();
          for (types::global_dof_index i = 0; i < K.m(); ++i)
            {
              const types::global_dof_index gi = offsets[b] + i;
              if (!owned.is_element(gi))
                continue;
              if (held[gi])
                {
                  matrix.add(gi, gi, scale);
                  continue;
                }
              columns.clear();
              values.clear();
              for (auto e = K.begin(i); e != K.end(i); ++e)
                if (finite[b] || !held[offsets[b] + e->column()])
                  {
                    columns.push_back(offsets[b] + e->column());
                    values.push_back(e->value());
                  }
              matrix.add(gi, columns, values);
            }
        }
      // The law's rows differentiate u: C, or with the geometric tangent
      // the pairs' derivatives, whose forces' derivative the displacement
      // rows add.
      const auto &law_rows = geometric_valid ? J_rows : C_rows;
      if (geometric_valid)
        for (const auto &[row, column, value] : geometric_entries)
          if (!held[row])
            add(row, column, value);
      const unsigned int alpha0 = n_u + d * n_pairs;
      for (unsigned int i = 0; i < n_pairs; ++i)
        for (unsigned int s = 0; s < d; ++s)
          {
            const unsigned int row = d * i + s, r = n_u + row;
            for (const auto &[g, v] : C_rows[row])
              add(g, r, -v * scale);
            for (unsigned int t = 0; t < d; ++t)
              {
                if (B[i](s, t) != 0.)
                  add(r, n_u + d * i + t, B[i](s, t) * scale);
                if (A[i](s, t) != 0.)
                  for (const auto &[g, v] : law_rows[d * i + t])
                    add(r, g, A[i](s, t) * v);
              }
            for (unsigned int a = 0; a < n_alpha; ++a)
              {
                double ag = 0.;
                for (unsigned int t = 0; t < d; ++t)
                  ag += A[i](s, t) * G(d * i + t, a);
                if (ag != 0.)
                  add(r, alpha0 + a, ag);
                if (G(row, a) != 0.)
                  add(alpha0 + a, r, G(row, a) * scale);
              }
          }
      matrix.compress(VectorOperation::add);
      factorization_error.clear();
      if (krylov)
        {
          // S~ = [(B + A C D^-1 C^T) s, A G; G^T s, 0].
          const unsigned int                  m = d * n_pairs;
          std::vector<Eigen::Triplet<double>> entries;
          for (unsigned int i = 0; i < n_pairs; ++i)
            for (unsigned int s = 0; s < d; ++s)
              {
                const unsigned int row = d * i + s;
                for (unsigned int t = 0; t < d; ++t)
                  {
                    if (B[i](s, t) != 0.)
                      entries.emplace_back(row, d * i + t, B[i](s, t) * scale);
                    if (A[i](s, t) != 0.)
                      for (Eigen::SparseMatrix<double>::InnerIterator
                             e(local_flexibility, d * i + t);
                           e;
                           ++e)
                        entries.emplace_back(row,
                                             e.row(),
                                             A[i](s, t) * e.value() * scale);
                  }
                for (unsigned int a = 0; a < n_alpha; ++a)
                  {
                    double ag = 0.;
                    for (unsigned int t = 0; t < d; ++t)
                      ag += A[i](s, t) * G(d * i + t, a);
                    if (ag != 0.)
                      entries.emplace_back(row, m + a, ag);
                    if (G(row, a) != 0.)
                      entries.emplace_back(m + a, row, G(row, a) * scale);
                  }
              }
          Eigen::SparseMatrix<double> S(m + n_alpha, m + n_alpha);
          S.setFromTriplets(entries.begin(), entries.end());
          S.makeCompressed();
          schur_lu.analyzePattern(S);
          schur_lu.factorize(S);
          if (schur_lu.info() != Eigen::Success)
            factorization_error = "the Schur-complement approximation of "
                                  "the preconditioner is singular";
          return;
        }
      // Amesos prints its solver's error codes to the terminal itself;
      // they are caught here and their code joins the one message the
      // contact solver gives.
      // A factorisation that may take more than a second says so first
      // (about 2e6 nonzeros on this project's machine).
      const bool report =
        progress != nullptr && matrix.n_nonzero_elements() > 2000000;
      Timer clock;
      if (report)
        *progress << "  [progress] coupled system: " << solver_type
                  << (direct ? " factorisation" : " analysis and factorisation")
                  << " of " << n_total << " unknowns ("
                  << matrix.n_nonzero_elements() << " nonzeros) ..."
                  << std::flush;
      std::ostringstream captured;
      std::streambuf    *out = std::cout.rdbuf(captured.rdbuf());
      std::streambuf    *err = std::cerr.rdbuf(captured.rdbuf());
      factorization_error.clear();
      // The symbolic factorisation depends on the pattern only, which is
      // the same at every Newton iteration: it is made once. A numeric
      // factorisation that fails after a reused analysis (MUMPS' workspace,
      // estimated at the analysis, can fall short when the pivots change
      // with the values) is tried once more from a fresh analysis. A fresh
      // one that runs out of workspace (MUMPS' INFOG(1) = -8, -9, -11, -14,
      // -15, -17, -20: the estimate fell short of the delayed pivots; V7 on
      // NURBS, full path, 3 ranks) is tried again with the workspace
      // relaxation ICNTL(14) raised from MUMPS' 20 % to 100 % and 400 %
      // before the matrix is called singular.
      // The raised relaxation stays for the later analyses of this matrix.
      const std::array<int, 3> relaxations = {{0, 100, 400}};
      int                      mumps_code  = 0;
      for (unsigned int attempt = 0; attempt < 4; ++attempt)
        {
          const bool fresh  = !direct;
          int        status = 0;
          try
            {
              if (fresh)
                {
                  direct_problem = std::make_unique<Epetra_LinearProblem>();
                  direct_problem->SetOperator(
                    const_cast<Epetra_CrsMatrix *>(&matrix.trilinos_matrix()));
                  Amesos factory;
                  direct.reset(
                    factory.Create(solver_type.c_str(), *direct_problem));
                  AssertThrow(direct != nullptr,
                              ExcMessage("Amesos has no solver " +
                                         solver_type));
                  // Left to itself through Amesos, MUMPS chose PORD for
                  // the 3D contact-patch plates (its analysis at 20 449
                  // pairs had not ended after 6 minutes); the Newton
                  // matrix takes the nested dissection the bodies'
                  // factorisations take. One process only: under mpirun
                  // the pattern's rows are spread over the ranks.
                  if (mumps &&
                      Utilities::MPI::n_mpi_processes(communicator) == 1)
                    {
                      pivot_order = fill_reducing_order();
                      internal::give_mumps_pivot_order(*direct, pivot_order);
                    }
                  if (relaxations[workspace_relaxation] > 0)
                    internal::set_mumps_workspace_relaxation(
                      *direct,
                      relaxations[workspace_relaxation]);
                  status = direct->SymbolicFactorization();
                }
              if (status == 0)
                status = direct->NumericFactorization();
            }
          catch (const std::exception &)
            {
              status = -1;
            }
          if (status == 0)
            break;
          mumps_code = direct ? internal::mumps_error(*direct) : 0;
          direct.reset();
          direct_problem.reset();
          const bool short_of_workspace =
            mumps_code == -8 || mumps_code == -9 || mumps_code == -11 ||
            mumps_code == -14 || mumps_code == -15 || mumps_code == -17 ||
            mumps_code == -20;
          if (fresh && short_of_workspace &&
              workspace_relaxation + 1 < relaxations.size())
            {
              ++workspace_relaxation;
              continue;
            }
          if (fresh)
            {
              // A singular Newton matrix (e.g. a floating body whose pairs
              // are all open): solve() reports it, the contact solver says
              // why.
              factorization_error =
                short_of_workspace ?
                  "out of workspace with ICNTL(14) = " +
                    std::to_string(relaxations[workspace_relaxation]) + " %" :
                  "singular";
              if (mumps_code != 0)
                factorization_error +=
                  ", MUMPS INFOG(1) = " + std::to_string(mumps_code);
              break;
            }
        }
      std::cout.rdbuf(out);
      std::cerr.rdbuf(err);
      if (report)
        {
          const double seconds = clock.wall_time();
          const double flops =
            direct ? internal::mumps_factorization_flops(*direct) : 0.;
          *progress << " " << std::setprecision(3) << seconds << " s";
          // MUMPS' count: with the seconds, the factorisation's rate.
          if (flops > 0.)
            *progress << " (" << flops << " flops, " << std::setprecision(2)
                      << flops / seconds / 1e9 << " GFlop/s)";
          *progress << std::setprecision(6) << std::endl;
        }
    }



    template <int dim>
    std::vector<int>
    CoupledSystem<dim>::fill_reducing_order() const
    {
      const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
      const unsigned int      n = A.NumMyRows();
      AssertDimension(n, n_total);
      // A + A^T with every diagonal: count, fill, then sort and drop the
      // repeats of each row.
      std::vector<std::size_t> row_start(n + 1, 0);
      for (unsigned int i = 0; i < n; ++i)
        {
          int  length  = 0;
          int *indices = nullptr;
          A.Graph().ExtractMyRowView(i, length, indices);
          row_start[A.GRID(i) + 1] += length + 1;
          for (int k = 0; k < length; ++k)
            ++row_start[A.GCID(indices[k]) + 1];
        }
      for (unsigned int i = 0; i < n; ++i)
        row_start[i + 1] += row_start[i];
      std::vector<unsigned int> columns(row_start[n]);
      std::vector<std::size_t>  next(row_start.begin(), row_start.end() - 1);
      for (unsigned int i = 0; i < n; ++i)
        {
          int  length  = 0;
          int *indices = nullptr;
          A.Graph().ExtractMyRowView(i, length, indices);
          const unsigned int gi = A.GRID(i);
          columns[next[gi]++]   = gi;
          for (int k = 0; k < length; ++k)
            {
              const unsigned int gj = A.GCID(indices[k]);
              columns[next[gi]++]   = gj;
              columns[next[gj]++]   = gi;
            }
        }
      std::size_t kept = 0, begin = 0;
      for (unsigned int i = 0; i < n; ++i)
        {
          const auto first = columns.begin() + begin,
                     last  = columns.begin() + row_start[i + 1];
          std::sort(first, last);
          const auto end = std::unique(first, last);
          begin          = row_start[i + 1];
          row_start[i]   = kept;
          kept =
            std::copy(first, end, columns.begin() + kept) - columns.begin();
        }
      row_start[n] = kept;
      columns.resize(kept);
      return linear_algebra::nested_dissection_order(n, row_start, columns, {});
    }



    template <int dim>
    std::vector<base::MemoryItem>
    CoupledSystem<dim>::memory_record() const
    {
      std::vector<base::MemoryItem> items;
      items.push_back({"coupled system: matrix (this rank's rows)",
                       double(matrix.memory_consumption()),
                       true});
      if (krylov)
        items.push_back({"coupled system: displacement block and its AMG",
                         double(K_matrix.memory_consumption()) +
                           double(amg.memory_consumption()),
                         true});
      // The factor's reals and integers on this rank (MUMPS' INFO(9, 10));
      // KLU reports no size.
      if (direct)
        items.push_back({"coupled system: factorisation",
                         internal::mumps_local_bytes(*direct),
                         true});
      double whole =
        base::vector_bytes(offsets) + double(held.capacity()) / 8. +
        base::vector_bytes(C_rows) + double(G.size()) * sizeof(double) +
        double(stiffness.size()) * sizeof(double) +
        base::vector_bytes(pivot_order) +
        double(linearized_at.size() + residual_at.size()) * sizeof(double);
      for (const auto &row : C_rows)
        whole += base::vector_bytes(row);
      const std::array<const std::vector<Vector<double>> *, 4> sets = {
        {&reference, &support_moves, &loads, &residuals}};
      for (const auto *set : sets)
        for (const auto &v : *set)
          whole += v.memory_consumption();
      for (const auto &tangent : tangents)
        whole += tangent.memory_consumption();
      items.push_back(
        {"coupled system: rows of C, body tangents and vectors", whole, false});
      return items;
    }



    template <int dim>
    void
    CoupledSystem<dim>::report_progress_to(std::ostream *stream)
    {
      progress = stream;
    }



    template <int dim>
    bool
    CoupledSystem<dim>::solve(const Eigen::VectorXd &r_w,
                              const Eigen::VectorXd &r_p,
                              const Eigen::VectorXd &r_alpha,
                              Eigen::VectorXd       &dw,
                              Eigen::VectorXd       &dp,
                              Eigen::VectorXd       &dalpha,
                              std::string           &why,
                              const double           relative_tolerance) const
    {
      Assert(direct || krylov, ExcMessage("factorize() first"));
      last_iterations = 0;
      if (krylov && !factorization_error.empty())
        {
          why = "the Newton matrix of the coupled system cannot be solved "
                "by gmres-amg: " +
                factorization_error +
                " (a floating body whose pairs are all open is held by "
                "nothing)";
          return false;
        }
      if (!factorization_error.empty())
        {
          if (factorization_error.rfind("out of workspace", 0) == 0)
            why = "the Newton matrix of the coupled system could not be "
                  "factorised (" +
                  solver_type + " ran " + factorization_error +
                  "; fewer ranks, or Contact/Full system solver = "
                  "gmres-amg)";
          else
            why = "the Newton matrix of the coupled system is singular (" +
                  solver_type +
                  " failed to factorise it: " + factorization_error +
                  "; a floating body whose pairs are all open is held by "
                  "nothing)";
          return false;
        }
      TrilinosWrappers::MPI::Vector rhs(owned, communicator),
        x(owned, communicator);
      for (const auto i : owned)
        rhs[i] = i < n_u               ? (held[i] ? scale * r_w[i] : r_w[i]) :
                 i < n_u + d * n_pairs ? r_p[i - n_u] :
                                         r_alpha[i - n_u - d * n_pairs];
      rhs.compress(VectorOperation::insert);
      if (krylov)
        {
          if (!solve_krylov(rhs, x, relative_tolerance, why))
            return false;
        }
      else
        try
          {
            // One step of iterative refinement against the assembled matrix
            // (Amesos does not refine; near the solution the Newton
            // direction must be accurate to the rounding of the residual).
            const auto direct_solve =
              [this](TrilinosWrappers::MPI::Vector       &solution,
                     const TrilinosWrappers::MPI::Vector &right_hand_side) {
                direct_problem->SetLHS(&solution.trilinos_vector());
                direct_problem->SetRHS(const_cast<Epetra_MultiVector *>(
                  static_cast<const Epetra_MultiVector *>(
                    &right_hand_side.trilinos_vector())));
                AssertThrow(direct->Solve() == 0,
                            ExcMessage(solver_type + "'s solve failed"));
              };
            direct_solve(x, rhs);
            TrilinosWrappers::MPI::Vector residual(owned, communicator),
              correction(owned, communicator);
            matrix.vmult(residual, x);
            residual.sadd(-1., rhs);
            direct_solve(correction, residual);
            x += correction;
          }
        catch (const std::exception &e)
          {
            why = std::string("the sparse direct solver failed on the Newton "
                              "matrix: ") +
                  e.what();
            return false;
          }
      // Every rank continues with the whole solution.
      TrilinosWrappers::MPI::Vector whole(owned, all, communicator);
      whole = x;
      dw.resize(n_u);
      dp.resize(d * n_pairs);
      dalpha.resize(n_alpha);
      for (unsigned int i = 0; i < n_u; ++i)
        dw[i] = whole[i];
      for (unsigned int i = 0; i < d * n_pairs; ++i)
        dp[i] = scale * whole[n_u + i];
      for (unsigned int a = 0; a < n_alpha; ++a)
        dalpha[a] = whole[n_u + d * n_pairs + a];
      return true;
    }



    template <int dim>
    contact::CoupledFactory<dim>
    coupled_factory(const Solver       solver,
                    const unsigned int krylov_max_iterations,
                    std::ostream      *progress,
                    const MPI_Comm     communicator)
    {
      return [solver, krylov_max_iterations, progress, communicator](
               const std::vector<const discretization::Body<dim> *> &bodies,
               const std::vector<contact::ContactPair<dim>>         &pairs,
               const unsigned int                 n_components,
               const Eigen::MatrixXd             &G,
               const contact::FiniteSliding<dim> &sliding) {
        auto system =
          std::make_unique<CoupledSystem<dim>>(bodies,
                                               pairs,
                                               n_components,
                                               G,
                                               solver,
                                               krylov_max_iterations,
                                               communicator);
        system->report_progress_to(progress);
        if (sliding.pairs_at)
          system->set_finite_sliding(sliding);
        return system;
      };
    }



    template contact::CoupledFactory<2>
    coupled_factory<2>(const Solver,
                       const unsigned int,
                       std::ostream *,
                       const MPI_Comm);
    template contact::CoupledFactory<3>
    coupled_factory<3>(const Solver,
                       const unsigned int,
                       std::ostream *,
                       const MPI_Comm);
    template class CoupledSystem<2>;
    template class CoupledSystem<3>;
  } // namespace coupled
} // namespace igabde
