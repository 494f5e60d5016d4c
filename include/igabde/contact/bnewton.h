#ifndef igabde_contact_bnewton_h
#define igabde_contact_bnewton_h

#include <igabde/contact/contact_problem.h>
#include <igabde/contact/contact_solver.h>
#include <igabde/contact/newton_driver.h>

#include <Eigen/Dense>

#include <iosfwd>
#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief Damped B-Newton solver (Pang 1990) for the B-differentiable
     * equations of the seed (contact_law.h), with robustness guards.
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
     *  - floating-body tie rule (BdeLaw::tie_rule()): with n_alpha > 0 the
     *    alpha columns of J are tied down only by the rows of G of closed
     *    and sticking pairs; while these do not span every column, the
     *    pairs with the smallest r_n u_n - p_n take the closed branch, then
     *    closed pairs the stick branch (the first is exactly a tie after
     *    touching_alpha()).
     * The Newton solve is the path's (ContactOperator::newton_step(): on
     * the condensed path the rows with A = 0 and B = identity are
     * eliminated and the rest factorised by Cholesky or LU, densely or
     * sparsely; on the full path the coupled system).
     *
     * <h3>Globalisation</h3>
     * The one driver of the contact layer (NewtonDriver):
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
     *    theta in Settings::stall_iterations iterations, or (phase 1 when
     *    another phase follows) in ten iterations whose active sets cycle,
     *    or (phase 1 when phase 2 follows) less than 10 % decrease in ten
     *    iterations.
     * Phases: (0) where the operator keeps W sparse and no body floats, at
     * most Settings::gauss_seidel_first_sweeps (3D with friction) or
     * Settings::gauss_seidel_first_sweeps_exact (local problems in closed
     * form) nonsmooth Gauss-Seidel sweeps from the start, left as soon as
     * their rate would not reach the tolerance within them; if they do not
     * converge, phase 1 starts from the start; where W is small (fewer than
     * CondensedOperator::min_sparse_rows rows) and no body floats, at most
     * Settings::gauss_seidel_first_sweeps sweeps (the first solves a problem
     * of one contact exactly), and if they do not converge, phase 1 starts
     * from their iterate; (1) Newton with Settings::radius; (2) if that ends
     * without convergence, Settings::switch_radius and r_factor is more than
     * ten times away from 1, Newton with r_factor = 1 (r from the flexibility
     * alone; the solution does not depend on r, the merit function does), from
     * the best iterate so far; (2b) if still not converged and
     * Settings::switch_radius, Newton with the other radius from the best
     * iterate (at r_factor = 1 if phase 2 ran); (3) if still not converged, on
     * the condensed path with 2D friction or none and no floating bodies:
     * nonsmooth Gauss-Seidel sweeps from the best iterate
     * (gauss_seidel_phase(), at most Settings::gauss_seidel_sweeps, a budget of
     * its own), which converge where Newton's active sets cycle (FCLIB's
     * FrictionContactProblem00727); (4) if still not converged and
     * Settings::proximal, proximal-point outer iterations (Acary et al.
     * 2018, PPA-NSN): the subproblem W + eps I, q - eps p_k (centred on the
     * current iterate, strongly monotone) is solved by Newton, eps starting
     * at max_i W_ii, divided by 10 after every solved subproblem and
     * multiplied by 10 after a failed inner solve; on a sparse symmetric W
     * a singular first Newton matrix of phase 1 hands over to it at once
     * (ContactOperator::proximal_for_singular_start()). The Newton
     * phases share the iteration budget Settings::max_iterations (inner
     * iterations count).
     *
     * <h3>Stopping</h3>
     * Converged when balanced_natural_map_error() <= tol and either
     * relative_natural_map_error() <= tol (the FCLIB measure) or the
     * balanced error is <= 1e-3 tol (the FCLIB measure mixes force and
     * displacement units and may be unreachable in floating point when
     * they are scaled very differently), and (with floating bodies)
     * |G^T p - b| <= tol * max(|b|, |G^T| |p|); tol = Settings::tolerance.
     * With Settings::fclib_stopping the FCLIB measure alone decides (the
     * balanced error's rounding-floor clause does not apply).
     * Otherwise the result says why (Result::diagnosis): iteration limit,
     * stall, line-search failure, non-finite values, time limit. The
     * returned p, u are the best iterate seen, never a diverged one.
     *
     * The solver keeps the buffers of a solve between its solves
     * (NewtonWorkspace): one object serves one solve at a time.
     */
    class BNewtonSolver : public ContactSolver
    {
    public:
      /** @brief Solver parameters (see BNewtonSettings). */
      using Settings = BNewtonSettings;

      /** @brief Outcome of a solve. */
      using Result = ContactSolverResult;

      /**
       * @brief Construct with @p settings; throws if a setting is out of
       * range (the scene reader refuses such values first).
       */
      explicit BNewtonSolver(const Settings &settings = Settings());

      /** @brief The settings in use. */
      const Settings &
      get_settings() const;

      /**
       * @brief Solve a condensed problem from p = 0 (alpha from
       * touching_alpha() when the problem has floating bodies).
       */
      Result
      solve(const ContactProblem &problem) const;

      /**
       * @brief Solve a condensed problem (its W through a
       * CondensedOperator) from an initial guess.
       * @param problem The problem.
       * @param p0 Initial contact forces, n_rows() (empty: zero).
       * @param alpha0 Initial floating-body amplitudes, n_alpha() (empty:
       * touching_alpha() from zero, or zero if no pair closes along -b).
       */
      Result
      solve(const ContactProblem  &problem,
            const Eigen::VectorXd &p0,
            const Eigen::VectorXd &alpha0 = {}) const;

      /** @brief Solve on any path (ContactSolver). */
      Result
      solve(const ContactData     &data,
            ContactOperator       &op,
            const ContactIterate  &start,
            const Eigen::VectorXd &p_previous = {}) const override;

      /** @brief "bde". */
      std::string
      name() const override;

    private:
      /**
       * @brief The proximal-point phase (Acary et al. 2018, PPA-NSN) from
       * the best iterate: subproblems with the operator shifted by eps
       * (W + eps I, u + eps p on the full path) and q - eps p_k, centred
       * on the current iterate, solved by Newton.
       */
      PhaseOutcome
      proximal_phase(NewtonDriver         &driver,
                     const ContactData    &data,
                     const ContactIterate &x,
                     const double          r_factor) const;

      Settings settings;

      /// The buffers of a solve, kept between solves (NewtonWorkspace):
      /// one solve at a time per solver object.
      mutable NewtonWorkspace workspace;
    };

  } // namespace contact
} // namespace igabde

#endif
