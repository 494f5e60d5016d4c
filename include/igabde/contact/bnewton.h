#ifndef igabde_contact_bnewton_h
#define igabde_contact_bnewton_h

#include <igabde/contact/contact_problem.h>

#include <Eigen/Dense>

#include <iosfwd>
#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief State of one contact pair at the end of a solve (or iteration).
     *
     * A closed frictionless pair, and a closed pair with a zero friction
     * radius, move freely in the tangential directions and are reported as
     * slip.
     */
    enum class ContactStatus
    {
      open,
      stick,
      slip
    };

    /** @brief "open", "stick" or "slip". */
    std::string
    to_string(const ContactStatus status);

    /**
     * @brief Radius of the friction disc in the B-differentiable equations.
     *
     * Both give the same solution set; Newton behaves differently
     * (research/contact-solvers.md §4, §5.3).
     */
    enum class FrictionRadius
    {
      /** R = mu max(p_n, 0): method.md's H (Christensen-Pang, Siconos JM). */
      christensen_pang,
      /** R = mu max(p_n - r_n u_n, 0): Alart-Curnier (Siconos NSN_AC). */
      alart_curnier
    };

    /**
     * @brief Absolute natural-map (De Saxce/FCLIB) error
     * |p - P_K(p - u_hat)| with u_hat = u + mu |u_t| e_n per contact and K
     * the Coulomb cone {|p_t| <= mu p_n}; for frictionless problems
     * |p - max(0, p - u)|. This is Siconos' fc3d_compute_error before its
     * division.
     */
    double
    natural_map_error(const ContactProblem  &problem,
                      const Eigen::VectorXd &p,
                      const Eigen::VectorXd &u);

    /**
     * @brief natural_map_error() divided by |q|, as in the FCLIB paper.
     *
     * When |q| is about zero (|q| <= 1e-12 |u - q|, or |q| = 0) the
     * division is by the force scale |p| instead (1 if p = 0 too).
     */
    double
    relative_natural_map_error(const ContactProblem  &problem,
                               const Eigen::VectorXd &p,
                               const Eigen::VectorXd &u);

    /**
     * @brief Scale-invariant ("balanced") natural-map error:
     * |p - P_K(p - rho_c u_hat)| / |rho q| with rho_c = 1/W_nn of each
     * contact (a stiffness), so that forces are compared with forces. It
     * vanishes exactly where natural_map_error() does, and is unchanged when
     * forces and displacements are rescaled independently (the FCLIB error
     * is not: with W, q scaled by 1e6 it weights force errors by 1e-6).
     * Falls back to division by |p| when |q| is about zero.
     */
    double
    balanced_natural_map_error(const ContactProblem  &problem,
                               const Eigen::VectorXd &p,
                               const Eigen::VectorXd &u);

    /** @brief Parameters of BNewtonSolver. */
    struct BNewtonSettings
    {
      /** @brief Tolerance on the relative natural-map error. */
      double tolerance = 1e-10;

      /** @brief Iteration budget over all phases. */
      unsigned int max_iterations = 100;

      /** @brief Armijo sufficient-decrease constant sigma. */
      double armijo_sigma = 1e-4;

      /** @brief Backtracking factor beta. */
      double armijo_beta = 0.5;

      /** @brief Smallest step tried in the line search. */
      double min_step = 1e-10;

      /** @brief Factor c multiplying the per-contact r (see class doc). */
      double r_factor = 1.;

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

      /** @brief Wall-time limit in seconds (0: none). */
      double max_wall_seconds = 0.;

      /** @brief Print the iterations while solving. */
      bool log = false;

      /** @brief Stream for the log (nullptr: std::cout). */
      std::ostream *log_stream = nullptr;
    };



    /**
     * @brief Damped B-Newton solver (Pang 1990) for the B-differentiable
     * equations of method.md §3, with robustness guards.
     *
     * <h3>Equations</h3>
     * Per contact, with r_n, r_t > 0 and u = W p + q + G alpha:
     * @code
     *   H_n = min(r_n u_n, p_n)
     *   H_t = p_t - Proj_{D(R)}(z),  z = p_t - r_t u_t,
     *   R   = mu max(p_n, 0)            (FrictionRadius::christensen_pang)
     *     or mu max(p_n - r_n u_n, 0)   (FrictionRadius::alart_curnier)
     * @endcode
     * plus, with floating bodies, the rows G^T p - b. A frictionless problem
     * (n_components = 1) has only the normal rows.
     *
     * <h3>r</h3>
     * Per contact r_n = c / W_nn and r_t = c / lambda_max(W_tt) (W_tt the
     * tangential diagonal block), c = Settings::r_factor. A non-positive
     * diagonal entry falls back to c / max_i W_ii (and to c if W = 0).
     *
     * <h3>Newton matrix and tie rules</h3>
     * The direction solves J d = -H with J = A [W G] + [B 0] (and the rows
     * [G^T 0]), A = dH/du and B = dH/dp one element of the B-subdifferential:
     *  - min, r_n u_n < p_n: closed, A_nn = r_n;
     *  - min, r_n u_n >= p_n (the tie included): open, B_nn = 1 (Siconos'
     *    Heaviside(0) = 0 choice);
     *  - |z| <= R, including z = 0 with R = 0: stick (lambda := 1),
     *    A_tt = r_t I; so the slip tie |z| = R > 0 is stick;
     *  - |z| > R = 0 (p_n <= 0, resp. p_n <= r_n u_n for AC): H_t = p_t,
     *    B_tt = I (the kink of R at p_n = 0 is dropped);
     *  - |z| > R > 0: slip, with zhat = z/|z| and
     *    Gamma = (R/|z|)(I - zhat zhat^T): B_tt = I - Gamma,
     *    A_tt = r_t Gamma, B_tn = -mu zhat, and for AC also
     *    A_tn = mu r_n zhat.
     *  - floating-body tie rule: if n_alpha > 0 and no contact is closed,
     *    the alpha columns of J vanish; the contact with the smallest
     *    r_n u_n - p_n is then taken in the closed branch (exactly a tie
     *    after touching_alpha()).
     * Rows with A = 0 and B = identity (open normals, free tangents) are
     * eliminated, d_i = -H_i, so the dense LU is only as large as the
     * number of remaining rows.
     *
     * <h3>Globalisation</h3>
     *  - Armijo backtracking on theta = |H|^2/2: step t = beta^m, accepted if
     *    theta(x + t d) <= theta_ref + sigma t grad(theta)^T d, with
     *    theta_ref the max of the last Settings::nonmonotone_memory values
     *    (Grippo-Lampariello-Lucidi; memory 1 is the monotone rule);
     *  - if the directional derivative is not sufficiently negative
     *    (grad^T d > -1e-8 |grad| |d|) the direction is replaced by the
     *    steepest descent -J^T H;
     *  - a singular or non-finite LU (reciprocal condition < 1e-14) is
     *    replaced by a Levenberg-Marquardt step (J^T J + lambda I) d = -J^T H;
     *  - when the line search reaches t < Settings::min_step, the best
     *    trial point is taken if it decreases theta (never the full step);
     *    else a steepest-descent line search is tried; if that fails too
     *    the phase ends with "line-search failure";
     *  - a phase also ends on stagnation: no 0.1 % decrease of the best
     *    theta in Settings::stall_iterations iterations.
     * Phases: (1) Newton with Settings::radius; (2) if that ends without
     * convergence and Settings::switch_radius, Newton with the other radius
     * from the best iterate so far; (3) if still not converged and
     * Settings::proximal, proximal-point outer iterations (Acary et al.
     * 2018, PPA-NSN): the subproblem W + eps I, q - eps p_k (centred on the
     * current iterate, strongly monotone) is solved by Newton, eps starting
     * at max_i W_ii and divided by 10 after every outer step that halved
     * the error, multiplied by 10 after a failed inner solve. All phases share
     * the iteration budget Settings::max_iterations (inner iterations count).
     *
     * <h3>Stopping</h3>
     * Converged when balanced_natural_map_error() <= tol and either
     * relative_natural_map_error() <= tol (the FCLIB measure) or the
     * balanced error is <= 1e-3 tol (the FCLIB measure mixes force and
     * displacement units and may be unreachable in floating point when
     * they are scaled very differently), and (with floating bodies)
     * |G^T p - b| <= tol * max(|b|, |G^T| |p|); tol = Settings::tolerance.
     * Otherwise the result says why (Result::diagnosis): iteration limit,
     * stall, line-search failure, non-finite values, time limit. The
     * returned p, u are the best iterate seen, never a diverged one.
     */
    class BNewtonSolver
    {
    public:
      /** @brief Solver parameters (see BNewtonSettings). */
      using Settings = BNewtonSettings;

      /** @brief One line of the iteration history. */
      struct IterationRecord
      {
        /** @brief Global iteration counter (1-based). */
        unsigned int iteration = 0;
        /** @brief Phase: "newton-cp", "newton-ac", "prox-cp", "prox-ac". */
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
        unsigned int n_open = 0, n_stick = 0, n_slip = 0;
        /** @brief Size of the reduced linear system. */
        unsigned int n_reduced = 0;
        /** @brief Remarks: "lm", "gradient", "best-trial", ... */
        std::string note;
      };

      /** @brief Outcome of a solve. */
      struct Result
      {
        /** @brief Contact forces (best iterate), n_rows(). */
        Eigen::VectorXd p;
        /** @brief Relative displacements W p + q + G alpha. */
        Eigen::VectorXd u;
        /** @brief Floating-body amplitudes (empty without G). */
        Eigen::VectorXd alpha;
        /** @brief Newton iterations done (all phases). */
        unsigned int iterations = 0;
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
        unsigned int n_open = 0, n_stick = 0, n_slip = 0;
        /** @brief Per-iteration history. */
        std::vector<IterationRecord> history;

        /** @brief Print the history table with 5 significant digits. */
        void
        print_history(std::ostream &out) const;

        /** @brief One-line summary: converged, iterations, residual. */
        std::string
        summary() const;
      };

      /** @brief Construct with @p settings. */
      explicit BNewtonSolver(const Settings &settings = Settings());

      /** @brief The settings in use. */
      const Settings &
      get_settings() const;

      /**
       * @brief Solve from p = 0 (alpha from touching_alpha() when the
       * problem has floating bodies).
       */
      Result
      solve(const ContactProblem &problem) const;

      /**
       * @brief Solve from an initial guess (warm start from a previous load
       * step).
       * @param problem The problem.
       * @param p0 Initial contact forces, n_rows() (empty: zero).
       * @param alpha0 Initial floating-body amplitudes, n_alpha() (empty:
       * touching_alpha() from zero, or zero if no pair closes along -b).
       */
      Result
      solve(const ContactProblem  &problem,
            const Eigen::VectorXd &p0,
            const Eigen::VectorXd &alpha0 = {}) const;

    private:
      Settings settings;
    };

  } // namespace contact
} // namespace igabde

#endif
