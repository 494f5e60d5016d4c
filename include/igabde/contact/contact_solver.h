#ifndef igabde_contact_contact_solver_h
#define igabde_contact_contact_solver_h

#include <igabde/base/choice_names.h>

#include <igabde/contact/contact_law.h>
#include <igabde/contact/contact_operator.h>
#include <igabde/contact/contact_problem.h>
#include <igabde/contact/path_cost.h>

#include <Eigen/Dense>

#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /** @brief One line of a contact solver's iteration history. */
    struct ContactIterationRecord
    {
      /** @brief Global iteration counter (1-based). */
      unsigned int iteration = 0;
      /** @brief Phase, e.g. "newton-cp", "newton-ac", "prox-cp". */
      std::string phase;
      /** @brief |H| at the start of the iteration (force units). */
      double h_norm = 0.;
      /** @brief Relative natural-map error of the problem solved. */
      double residual = 0.;
      /** @brief Balanced natural-map error of the problem solved. */
      double balanced_residual = 0.;
      /** @brief Accepted step length (0 if none). */
      double step = 0.;
      /** @brief Contact counts at the start of the iteration. */
      unsigned int n_open = 0, n_stick = 0, n_slip = 0, n_closed = 0;
      /** @brief Size of the reduced linear system. */
      unsigned int n_reduced = 0;
      /** @brief Iterations of the iterative linear solve of this Newton
       * step (full path with gmres-amg; 0 otherwise). */
      unsigned int linear_iterations = 0;
      /** @brief Remarks: "lm", "gradient", "best-trial", ... */
      std::string note;

      /** @brief One line of the history table (5 significant digits). */
      void
      print(std::ostream &out) const;
    };

    /** @brief Outcome of a contact solve, whatever the algorithm. */
    struct ContactSolverResult
    {
      /** @brief Contact forces (best iterate), n_rows(). */
      Eigen::VectorXd p;
      /**
       * @brief Relative displacements: W p + q + G alpha on the condensed
       * path, C w + q + G alpha on the full path.
       */
      Eigen::VectorXd u;
      /** @brief Floating-body amplitudes (empty without G). */
      Eigen::VectorXd alpha;
      /** @brief Iterations done (all phases). */
      unsigned int iterations = 0;
      /**
       * @brief Nonsmooth Gauss-Seidel sweeps done (all phases; not counted
       * in @p iterations).
       */
      unsigned int sweeps = 0;
      /** @brief Final relative natural-map error (FCLIB, /|q|). */
      double residual = 0.;
      /** @brief Final balanced_natural_map_error(). */
      double balanced_residual = 0.;
      /** @brief Final relative equilibrium error |G^T p - b| (0 w/o G). */
      double equilibrium_residual = 0.;
      /** @brief True if the stopping test was met. */
      bool converged = false;
      /** @brief "converged (...)" or why not. */
      std::string diagnosis;
      /** @brief Per-contact status at p, u. */
      std::vector<ContactStatus> status;
      /** @brief Status counts. */
      unsigned int n_open = 0, n_stick = 0, n_slip = 0, n_closed = 0;
      /** @brief Per-iteration history. */
      std::vector<ContactIterationRecord> history;
      /** @brief Coupled displacement unknowns w (full path; else empty). */
      Eigen::VectorXd w;
      /** @brief Largest penetration max(0, -u_n) over the pairs (length). */
      double max_penetration = 0.;
      /** @brief Multiplier updates (augmented Lagrangian; else 0). */
      unsigned int updates = 0;
      /**
       * @brief When not converged: the pairs (indices into the problem's
       * contacts) the failure involves, as the diagnosis names them: those
       * that change state in a cycle, those with non-finite values, else
       * those with the largest residual.
       */
      std::vector<unsigned int> pairs_involved;

      /** @brief Print the history table with 5 significant digits. */
      void
      print_history(std::ostream &out) const;

      /** @brief One-line summary: converged, iterations, residual. */
      std::string
      summary() const;
    };

    /**
     * @brief A contact solver: the law's data of one load step, the path
     * (ContactOperator) and a warm start in, the contact forces and the
     * contact state out. Every implementation runs the one Newton driver
     * (newton_driver.h) with its law: BNewtonSolver the B-differentiable
     * equations (pair_law()), PenaltySolver and AugmentedLagrangeSolver
     * the penalty law (penalty_law()), the latter in an outer loop of
     * multiplier updates. The post-solve condition check
     * (check_contact_conditions()) judges the exact ones the same way.
     * A new algorithm is one class deriving from this one plus one line
     * in create_contact_solver().
     */
    class ContactSolver
    {
    public:
      virtual ~ContactSolver() = default;

      /** @brief The name for logs and summary.json. */
      virtual std::string
      name() const = 0;

      /**
       * @brief Whether the answer satisfies the exact contact conditions
       * (and is checked against them); the penalty answer penetrates by
       * design.
       */
      virtual bool
      exact() const
      {
        return true;
      }

      /**
       * @brief Solves the problem @p data on the path @p op from @p start
       * (p, alpha, w; an empty p counts as zero, an empty alpha as the
       * solver's choice, an empty w as zero); @p p_previous holds the
       * pair forces at the end of the previous load step (the base of the
       * incremental friction of the penalty methods; empty for zero).
       */
      virtual ContactSolverResult
      solve(const ContactData     &data,
            ContactOperator       &op,
            const ContactIterate  &start,
            const Eigen::VectorXd &p_previous = {}) const = 0;
    };

    /** @brief How the condensed Newton matrix is stored and factorised. */
    using NewtonLinearAlgebra = CondensedOperator::LinearAlgebra;

    /** @brief Settings of the BDE (damped B-Newton) solver. */
    struct BNewtonSettings
    {
      /** @brief Tolerance on the relative natural-map error. */
      double tolerance = 1e-10;

      /** @brief Iteration budget over all phases. */
      unsigned int max_iterations = 100;

      /**
       * @brief Stop as soon as the FCLIB error (with the equilibrium
       * rows) meets the tolerance, without asking the balanced error to
       * meet it too: the measure FCLIB problems are judged by, for which
       * Siconos' solvers are stopped the same way in the comparisons.
       * False (scenes): both errors must meet it.
       */
      bool fclib_stopping = false;

      /** @brief Armijo sufficient-decrease constant sigma. */
      double armijo_sigma = 1e-4;

      /** @brief Backtracking factor beta. */
      double armijo_beta = 0.5;

      /** @brief Smallest step tried in the line search. */
      double min_step = 1e-10;

      /** @brief Factor c multiplying the per-contact r (pair_weights()). */
      double r_factor = 1.;

      /** @brief Line search on the Newton steps (false: full steps). */
      bool line_search = true;

      /** @brief Non-monotone (GLL) memory M; 1 = monotone Armijo. */
      unsigned int nonmonotone_memory = 5;

      /** @brief Iterations without 0.1 % progress that count as stall. */
      unsigned int stall_iterations = 20;

      /** @brief Radius of the first phase. */
      FrictionRadius radius = FrictionRadius::christensen_pang;

      /** @brief Retry with the other radius after a failed phase. */
      bool switch_radius = true;

      /** @brief Proximal-point phase after failed Newton phases. */
      bool proximal = true;

      /**
       * @brief Sweeps of the nonsmooth Gauss-Seidel phase after the failed
       * Newton phases, before the proximal one (condensed path, 2D or
       * frictionless, no floating bodies; 0: no such phase).
       */
      unsigned int gauss_seidel_sweeps = 2000;

      /**
       * @brief Sweeps of the nonsmooth Gauss-Seidel phase tried before
       * the Newton phases where W is small, or kept sparse and the pairs
       * are 3D with friction (no floating bodies; 0: no such phase on any
       * problem). The phase ends as soon as the error's rate per sweep would
       * not reach the tolerance within these sweeps; if the sweeps do not
       * solve the problem, Newton starts from the start as without them (on
       * a small W from the sweeps' iterate). A 3D sweep solves each slipping
       * pair by a local Newton: ten cost less than one sparse factorisation
       * of the Newton matrix on the FCLIB rigid-body problems, and where more
       * sweeps solve such a problem they cost more than Newton (as on
       * Box_Stacks-i0122; doc/contact-solver.md).
       */
      unsigned int gauss_seidel_first_sweeps = 10;

      /**
       * @brief The same on a sparse W where each pair's local problem is
       * solved in closed form (2D friction, or frictionless; the phase runs
       * where gauss_seidel_first_sweeps is not 0; a small W keeps
       * gauss_seidel_first_sweeps, a Newton iteration costing there about as
       * much as a few sweeps): a sweep is about one pass over W's non-zeros,
       * and on the FCLIB 2D problems the sweeps that reach the tolerance
       * within a thousand cost less than the Newton phases they replace
       * (FrictionContactProblem00727: 679 sweeps against 81 Newton
       * iterations and 482 sweeps; doc/contact-solver.md).
       */
      unsigned int gauss_seidel_first_sweeps_exact = 1000;

      /** @brief Storage and factorisation of the Newton matrix. */
      NewtonLinearAlgebra linear_algebra = NewtonLinearAlgebra::automatic;

      /**
       * @brief With NewtonLinearAlgebra::automatic, W (n_rows() >= 48) is
       * treated as sparse when its share of non-zero entries is at most
       * this fraction.
       */
      double sparse_fill = 0.1;

      /**
       * @brief Factorise the reduced Newton matrix by Cholesky (LDL^T) when
       * the pieces make it a positive scaling of a principal block of a
       * symmetric W (every remaining row closed-normal or stick, no
       * floating bodies); LU otherwise.
       */
      bool use_symmetry = true;

      /** @brief Wall-time limit in seconds (0: none). */
      double max_wall_seconds = 0.;

      /** @brief Print the iterations while solving. */
      bool log = false;

      /** @brief Stream for the log (nullptr: std::cout). */
      std::ostream *log_stream = nullptr;

      /**
       * @brief Called after every iteration with the iterations so far
       * (all phases) and the relative natural-map residual: a caller's
       * progress report (empty: none).
       */
      std::function<void(unsigned int, double)> on_iteration;
    };

    /**
     * @brief Settings of the penalty and augmented-Lagrange solvers.
     */
    struct PenaltySettings
    {
      /// Normal stiffness factor FKN: k_n = FKN k_i per pair.
      double normal_factor = 1.;
      /// Tangential (stick) stiffness factor FKT: k_t = FKT k_n.
      double tangential_factor = 1.;
      /// Newton iteration limit of one penalty solve.
      unsigned int max_iterations = 50;
      /// Multiplier-update limit of the augmented Lagrangian.
      unsigned int max_updates = 200;
      /// Armijo line search on the penalty Newton steps (false: full
      /// steps, as ANSYS takes them by default).
      bool line_search = true;
    };

    /** @brief Contact/Algorithm. */
    enum class Algorithm
    {
      /// The B-differentiable equations (damped B-Newton).
      bde,
      /// Node-to-node penalty (ANSYS' default contact).
      penalty,
      /// The method of multipliers around the penalty solve.
      augmented_lagrange
    };

    /** @brief The names of Algorithm as the scene writes them. */
    inline constexpr base::ChoiceNames<Algorithm, 3> algorithm_names = {
      {{Algorithm::bde, "bde"},
       {Algorithm::penalty, "penalty"},
       {Algorithm::augmented_lagrange, "augmented-lagrange"}}};

    /** @brief The name of @p algorithm as the scene writes it. */
    inline std::string
    to_string(const Algorithm algorithm)
    {
      return base::name_of(algorithm_names, algorithm);
    }

    /** @brief What create_contact_solver() needs. */
    struct ContactSolverSettings
    {
      /// Contact/Algorithm.
      Algorithm algorithm = Algorithm::bde;
      /// Contact/Path of the BDE (penalty and augmented Lagrange always
      /// solve the full system).
      Path path = Path::condensed;
      /// Settings of the BDE solver (tolerance and iteration limits are
      /// shared by all algorithms).
      BNewtonSettings bnewton;
      /// Settings of the penalty methods.
      PenaltySettings penalty;
    };

    /** @brief The solver @p settings.algorithm names. */
    std::unique_ptr<ContactSolver>
    create_contact_solver(const ContactSolverSettings &settings);
  } // namespace contact
} // namespace igabde

#endif
