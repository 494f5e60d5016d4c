#ifndef igabde_coupled_coupled_system_h
#define igabde_coupled_coupled_system_h

#include <igabde/base/retain_freed_memory.h>

#include <igabde/discretization/body.h>

#include <igabde/contact/contact_path.h>
#include <igabde/contact/coupled_operator.h>
#include <igabde/contact/pairing.h>

#include <igabde/coupled/solver.h>

#include <deal.II/base/index_set.h>

#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Eigen/Dense>
#include <Eigen/SparseLU>

#include <Amesos_BaseSolver.h>
#include <Epetra_LinearProblem.h>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace igabde
{
  namespace coupled
  {
    using namespace dealii;

    /**
     * @brief The uncondensed contact system of the deformable bodies (the
     * CoupledOperator of the full-system contact path): both bodies'
     * stiffness, the pair operator C from each pair's PointOperators and
     * local frame, and the rigid-mode columns G, in one Trilinos sparse
     * matrix factorised by a sparse direct solver through Amesos (MUMPS by
     * default, KLU on request), or solved by GMRES with a block
     * preconditioner ("gmres-amg"; see factorize()). With a communicator
     * of several ranks the matrix is distributed by rows (each rank a
     * contiguous share of the displacement rows and one of the pair rows,
     * assembled by its owner only); the direct solver factorises it on all
     * ranks together, or GMRES runs on the distributed matrix with the
     * AMG of the distributed displacement block. The solution is then
     * gathered on every rank, which all run the same Newton iteration.
     *
     * Unknown order: Body 1's unknowns, Body 2's, then the pair forces
     * (pair by pair, normal first) and the rigid-mode amplitudes. Held
     * unknowns (supports and the pins of free rigid modes) keep an identity
     * row and no coupling.
     */
    template <int dim>
    class CoupledSystem : public contact::CoupledOperator
    {
    public:
      /**
       * @param bodies The deformable bodies (Body 1 first), set up.
       * @param pairs The contact pairs; each couples the bodies its indices
       * name (op2 unused against an obstacle).
       * @param n_components Components per pair (1 frictionless, else dim).
       * @param G The rigid-mode columns of the contact problem.
       * @param solver The linear solver.
       * @param krylov_max_iterations GMRES iteration limit per solve
       * (gmres-amg).
       * @param communicator The ranks that factorise or iterate on the
       * matrix together (each of them builds this system alike);
       * MPI_COMM_SELF: this process alone.
       */
      CoupledSystem(
        const std::vector<const discretization::Body<dim> *> &bodies,
        const std::vector<contact::ContactPair<dim>>         &pairs,
        const unsigned int                                    n_components,
        const Eigen::MatrixXd                                &G,
        const Solver                                          solver,
        const unsigned int krylov_max_iterations = 1000,
        const MPI_Comm     communicator          = MPI_COMM_SELF);

      unsigned int
      n_dofs() const override;

      unsigned int
      n_rows() const override;

      Eigen::VectorXd
      apply_C(const Eigen::VectorXd &w) const override;

      Eigen::VectorXd
      displacement_equations(const Eigen::VectorXd &w,
                             const Eigen::VectorXd &p) const override;

      double
      displacement_equations_scale(const Eigen::VectorXd &w,
                                   const Eigen::VectorXd &p) const override;

      /**
       * Direct solvers factorise the assembled matrix. gmres-amg builds
       * instead the block upper-triangular preconditioner
       * @code
       *   P = [ K   U ]    U = [-C^T s  0],
       *       [ 0   S~]    S~ = [ (B + A C D^-1 C^T) s   A G ]
       *                         [  G^T s                  0  ]
       * @endcode
       * (s the force scale, D the diagonal of K): one V-cycle of smoothed
       * aggregation AMG (Trilinos ML, the bodies' rigid-body modes as near
       * null space; set up once, K does not change) for K, and a sparse LU
       * of S~, the Schur complement of the Newton matrix with K^-1
       * replaced by D^-1 (pairs couple only through shared unknowns, so S~
       * is sparse). With the exact K^-1 in S~, GMRES would converge in two
       * iterations (Murphy, Golub and Wathen); D^-1 leaves the long-range
       * part of the flexibility to the iteration.
       */
      void
      factorize(const std::vector<Eigen::Matrix3d> &A,
                const std::vector<Eigen::Matrix3d> &B) override;

      bool
      solve(const Eigen::VectorXd &r_w,
            const Eigen::VectorXd &r_p,
            const Eigen::VectorXd &r_alpha,
            Eigen::VectorXd       &dw,
            Eigen::VectorXd       &dp,
            Eigen::VectorXd       &dalpha,
            std::string           &why,
            const double           relative_tolerance) const override;

      unsigned int
      linear_iterations() const override;

      const Eigen::VectorXd &
      element_pair_stiffness() const override;

      bool
      pair_row_is_held(const unsigned int row) const override;

      double
      n_nonzeros() const override;

      bool
      finite_strain() const override;

      /**
       * At finite strain the held unknowns of a body at finite strain move
       * from their values in @p u to the supports' values at @p factors
       * during the solve: their rows are w_i = g_i - u_i, so that the
       * first Newton step moves the supports and predicts the inside and
       * the contact with them (moving the supports alone would distort
       * the elements next to them).
       */
      void
      set_reference(const Eigen::VectorXd     &u,
                    const std::vector<double> &factors) override;

      void
      linearize_bodies(const Eigen::VectorXd &w) override;

      Eigen::VectorXd
      tangent_equations(const Eigen::VectorXd &v_w,
                        const Eigen::VectorXd &v_p) const override;

      Eigen::VectorXd
      tangent_transpose(const Eigen::VectorXd &h) const override;

      /**
       * @brief Progress lines of factorisations that may take more than a
       * second go to @p stream (nullptr: none).
       */
      /**
       * @brief This rank's rows of the coupled matrix and of the
       * displacement block with its AMG (divided), MUMPS' factor on this
       * rank (divided), and the bodies' tangents, the vectors and the
       * rows of C every rank holds whole.
       */
      std::vector<base::MemoryItem>
      memory_record() const override;

      void
      report_progress_to(std::ostream *stream);

      /**
       * @brief Finite sliding: the pairs are formed again at every iterate
       * by @p sliding (update_geometry()); the number of pairs and their
       * order stay. Direct solvers only, every body held.
       */
      void
      set_finite_sliding(const contact::FiniteSliding<dim> &sliding);

      /**
       * @brief The pairs at the iterate @p x (set_finite_sliding()): C's
       * rows from their operators and frames, the Newton matrix's pattern
       * again where they moved into other elements, and the offset that
       * makes the normal rows of C w + q + offset their gaps at @p x.
       * Nothing without finite sliding or at the last iterate.
       */
      void
      update_geometry(const contact::ContactIterate &x) override;

      const Eigen::VectorXd *
      displacement_offset() const override;

      void
      forget_geometry() override;

      /**
       * @brief With the full sliding tangent (FiniteSliding::full_tangent):
       * the derivatives of every pair's gap, slip (the law's rows of u) and
       * force -C^T p (at x.p) by the unknowns it reads, by forward
       * differences of the pairing at @p x, one pairing per colour of
       * unknowns no pair reads together. The law's rows of the Newton
       * matrix then take them in place of C's rows, and the displacement
       * rows add the forces' derivative (the geometric stiffness of the
       * contact: the force directions turning with the master's normal,
       * the master points moving over its elements). Kept until the pairs
       * are formed again (update_geometry()).
       */
      void
      linearize_geometry(const contact::ContactIterate &x) override;

      /**
       * @brief Contact/Sliding tangent = auto: whether the next
       * linearize_geometry() takes the pairs' derivatives (the Newton
       * iteration asks once the frozen tangent contracts slowly).
       */
      void
      want_exact_tangent(const bool wanted) override
      {
        exact_tangent_wanted = wanted;
      }

      Eigen::VectorXd
      apply_C_derivative(const Eigen::VectorXd &v) const override;

    private:
      /// r += (d(-C^T p)/dw) v with the derivative of linearize_geometry()
      /// (nothing without it).
      void
      add_geometric_term(const Eigen::VectorXd &v, Eigen::VectorXd &r) const;

      /// K w - C^T p with the held rows (displacement_equations() at the
      /// pairs of the last update, without the geometric model).
      Eigen::VectorXd
      frozen_equations(const Eigen::VectorXd &w,
                       const Eigen::VectorXd &p) const;

      /// C's rows from the pairs' operators and frames.
      void
      set_C_rows(const std::vector<contact::ContactPair<dim>> &pairs);

      /// The Newton matrix's sparsity from the bodies' K and C's rows, and
      /// the matrix on it.
      void
      build_pattern();

      /**
       * linearize_geometry() in closed form: J_rows of the pairs @p active
       * and the forces' derivative @p K (row, column) from their
       * linearisations @p linearized (FiniteSliding::linearization_of).
       */
      void
      add_closed_form_tangent(
        const contact::ContactIterate                           &x,
        const std::vector<unsigned int>                         &active,
        const std::vector<contact::PairLinearization<dim>>      &linearized,
        std::map<std::pair<unsigned int, unsigned int>, double> &K);

      /**
       * linearize_geometry() by differences: the pairs @p active formed
       * again (FiniteSliding::pairs_of) at one step per colour of the
       * unknowns they read (Curtis, Powell and Reid), @p pairs those at
       * the iterate.
       */
      void
      add_difference_tangent(
        const contact::ContactIterate                           &x,
        const std::vector<contact::ContactPair<dim>>            &pairs,
        const std::vector<unsigned int>                         &active,
        std::map<std::pair<unsigned int, unsigned int>, double> &K);

      /// set_finite_sliding(); the iterate of the last update_geometry()
      /// and its offset.
      contact::FiniteSliding<dim> sliding;
      Eigen::VectorXd             geometry_at, offset;
      /// How far (m, any unknown) the bodies move before the pairs are
      /// formed again.
      double geometry_tolerance = 0.;
      /// Each body's mean element size (measure / elements)^(1/dim).
      std::vector<double> element_size;
      /// The pairs of the last update_geometry().
      std::vector<contact::ContactPair<dim>> pairs_now;
      /// linearize_geometry(): whether its derivatives hold (until the
      /// next update_geometry()), the law rows' derivative by w, the
      /// forces' derivative as (row, column, value), the iterate's w, and
      /// the entries beyond K's and C's pattern that the pattern holds.
      bool geometric_valid = false;
      /// want_exact_tangent(): the adaptive tangent's choice.
      bool exact_tangent_wanted = false;
      std::vector<std::vector<std::pair<unsigned int, double>>> J_rows;
      std::vector<std::tuple<unsigned int, unsigned int, double>>
                                                         geometric_entries;
      Eigen::VectorXd                                    geometric_at;
      std::vector<std::pair<unsigned int, unsigned int>> extra_pattern;

      /// Freed pages stay with the process while the system lives: every
      /// Newton iteration's factorisation frees MUMPS' workspace and takes
      /// it again (first member: made before, released after the rest).
      base::RetainFreedMemory retain_freed_memory;
      /// The bodies (not owned).
      std::vector<const discretization::Body<dim> *> bodies;
      /// Components per pair, pairs, rigid modes.
      const unsigned int d;
      unsigned int       n_pairs = 0, n_alpha = 0;
      /// Unknowns of the bodies, and of the whole system.
      unsigned int n_u = 0, n_total = 0;
      /// First unknown of each body.
      std::vector<unsigned int> offsets;
      /// Whether each displacement unknown is held at zero.
      std::vector<bool> held;
      /// Rows of C: (unknown, coefficient) lists, held unknowns left out.
      std::vector<std::vector<std::pair<unsigned int, double>>> C_rows;
      /// The rows @p rows ((unknown, coefficient) lists, as C_rows and
      /// J_rows) applied to @p v.
      static Eigen::VectorXd
      apply_rows(
        const std::vector<std::vector<std::pair<unsigned int, double>>> &rows,
        const Eigen::VectorXd                                           &v);
      /// The rigid-mode columns.
      Eigen::MatrixXd G;
      /// Column scale of the force unknowns (mean stiffness diagonal).
      double scale = 1.;
      /// Pair stiffness from the underlying elements.
      Eigen::VectorXd stiffness;
      /// Amesos solver name.
      std::string solver_type;
      /// The ranks that factorise the Newton matrix together.
      MPI_Comm communicator;
      /// The Newton matrix and its factorisation: all unknowns, and the
      /// rows this rank owns (all of them on one rank): the displacement
      /// rows [u_begin, u_end) and a share of the pair and rigid-mode rows.
      IndexSet                       all, owned;
      types::global_dof_index        u_begin = 0, u_end = 0;
      TrilinosWrappers::SparseMatrix matrix;
      /// The direct solver (Amesos) on the Newton matrix: the pattern never
      /// changes, so its symbolic factorisation (MUMPS' analysis: the pivot
      /// order) is made once and every Newton iteration factorises the new
      /// values only.
      std::unique_ptr<Epetra_LinearProblem> direct_problem;
      std::unique_ptr<Amesos_BaseSolver>    direct;
      /// MUMPS' pivot order (PERM_IN) in one process: nested dissection of
      /// the pattern (fill_reducing_order()); kept while MUMPS may read it.
      std::vector<int> pivot_order;
      /// Index into the workspace relaxations MUMPS' analyses take (0: its
      /// default; raised when a fresh factorisation ran out of workspace).
      std::size_t workspace_relaxation = 0;
      /// Why the last factorisation failed (empty if it did not).
      std::string factorization_error;
      /// Where progress lines go (nullptr: nowhere).
      std::ostream *progress = nullptr;

      /// The bodies at finite strain: per body whether it is, its
      /// reference displacement u_ref (set_reference()), the held unknowns'
      /// moves g - u_ref, the external loads at the step's factors and the
      /// factors (follower pressures), its tangent at the last
      /// linearize_bodies() and the correction w it was taken at.
      std::vector<bool>                         finite;
      bool                                      any_finite = false;
      std::vector<Vector<double>>               reference, support_moves, loads;
      std::vector<double>                       factors;
      mutable std::vector<SparseMatrix<double>> tangents;
      mutable Eigen::VectorXd                   linearized_at;
      mutable bool                              linearized = false;
      /// The residual f_int - f_ext (follower pressures included) of each
      /// body at finite strain at the correction residual_at, and the
      /// norms of f_int and f_ext there (the scale of the equations).
      mutable std::vector<Vector<double>> residuals;
      mutable Eigen::VectorXd             residual_at;
      mutable bool                        have_residual   = false;
      mutable bool                        residual_finite = true;
      mutable std::vector<double>         force_norms;

      /// The residuals at @p w (cached for the last w); with @p tangent
      /// also the tangents. False where an element inverts (det F <= 0).
      bool
      evaluate_bodies(const Eigen::VectorXd &w, const bool tangent) const;

      /// gmres-amg: the iteration limit, the displacement block K (held
      /// rows: scale times identity) and its AMG, D^-1 C^T of the Schur
      /// approximation (n_u x rows of C), the LU of S~, the last count.
      /// The direct solver is MUMPS (not KLU).
      bool                                         mumps  = false;
      bool                                         krylov = false;
      unsigned int                                 krylov_max_iterations = 1000;
      IndexSet                                     displacement_set;
      TrilinosWrappers::SparseMatrix               K_matrix;
      TrilinosWrappers::PreconditionAMG            amg;
      std::vector<double>                          null_space;
      Eigen::SparseMatrix<double>                  local_flexibility;
      Eigen::SparseLU<Eigen::SparseMatrix<double>> schur_lu;
      mutable unsigned int                         last_iterations = 0;

      /// Builds K_matrix, the AMG and the local flexibility C D^-1 C^T.
      void
      setup_krylov();

      /// METIS nested dissection of the Newton matrix's pattern made
      /// symmetric (one process: every row is this rank's); empty if METIS
      /// fails.
      std::vector<int>
      fill_reducing_order() const;

      /// Applies P^-1 (gmres-amg).
      void
      apply_preconditioner(TrilinosWrappers::MPI::Vector       &dst,
                           const TrilinosWrappers::MPI::Vector &src) const;

      /// GMRES with P on the Newton matrix to @p relative_tolerance of
      /// |rhs|; false with the reason in @p why if it does not converge.
      bool
      solve_krylov(const TrilinosWrappers::MPI::Vector &rhs,
                   TrilinosWrappers::MPI::Vector       &x,
                   const double                         relative_tolerance,
                   std::string                         &why) const;
    };

    /**
     * @brief The factory of the full contact path's coupled system that
     * the contact stage calls once the pairs are formed: CoupledSystem
     * with the linear solver @p solver and
     * the GMRES iteration limit @p krylov_max_iterations, its progress
     * lines to @p progress (nullptr: none), a direct solver's matrix
     * distributed over the ranks of @p communicator.
     */
    template <int dim>
    contact::CoupledFactory<dim>
    coupled_factory(const Solver       solver,
                    const unsigned int krylov_max_iterations,
                    std::ostream      *progress     = nullptr,
                    const MPI_Comm     communicator = MPI_COMM_SELF);
  } // namespace coupled
} // namespace igabde

#endif
