#ifndef igabde_contact_newton_driver_h
#define igabde_contact_newton_driver_h

#include <igabde/contact/contact_law.h>
#include <igabde/contact/contact_operator.h>
#include <igabde/contact/contact_solver.h>

#include <Eigen/Dense>

#include <chrono>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief The per-pair law that the Newton driver linearises: the
     * residual H_i(p_i, u_i) of pair i, its piece (status and the blocks
     * A = dH/du, B = dH/dp), the law's error measures and how a kink that
     * would leave the Newton matrix singular is resolved.
     */
    class PairLawModel
    {
    public:
      virtual ~PairLawModel() = default;

      /** @brief H of pair @p c at (p, u), and its piece if @p piece. */
      virtual void
      evaluate(const ContactData &data,
               const unsigned int c,
               const double      *p,
               const double      *u,
               double            *H,
               PairPiece         *piece) const = 0;

      /**
       * @brief Moves pieces off a kink where the Newton matrix would be
       * singular (nothing by default).
       */
      virtual void
      tie_rule(const ContactData     &data,
               const Eigen::VectorXd &p,
               const Eigen::VectorXd &u,
               NewtonBlocks          &pieces) const
      {
        (void)data;
        (void)p;
        (void)u;
        (void)pieces;
      }

      /**
       * @brief The law's error at (p, u) with residual H: @p err the
       * measure reported (the FCLIB error for the exact law), @p balanced
       * the scale-invariant one the stopping test requires.
       */
      virtual void
      errors(const ContactData     &data,
             const Eigen::VectorXd &p,
             const Eigen::VectorXd &u,
             const Eigen::VectorXd &H,
             double                &err,
             double                &balanced) const = 0;

      /**
       * @brief The rounding-floor clause of the stopping test: once the
       * Newton iterations stop converging quadratically, the balanced
       * error alone is accepted below this factor times the tolerance.
       */
      virtual double
      floor_factor() const
      {
        return 1e-3;
      }

      /**
       * @brief Whether a failed line search takes the full step instead of
       * ending the phase (penalty: full Newton steps as ANSYS takes them).
       */
      virtual bool
      full_step_on_failure() const
      {
        return false;
      }
    };



    /**
     * @brief The B-differentiable equations of the seed (pair_law()) with
     * weights r and a friction radius, and the floating-body tie rule:
     * with floating bodies the alpha columns of the Newton matrix are tied
     * down only by the rows of G of closed (normal) and sticking
     * (tangential) pairs; while these do not span every column, the pairs
     * with the smallest r_n u_n - p_n take the closed branch, then closed
     * pairs the stick branch (the first is exactly a tie after
     * touching_alpha()).
     */
    class BdeLaw : public PairLawModel
    {
    public:
      /// The law at @p weights; the balanced error at @p unit_weights (the
      /// weights at the unit scale).
      BdeLaw(PairWeights          weights,
             PairWeights          unit_weights,
             const FrictionRadius radius);

      /// The law at the unit scale: @p unit_weights for both (held once).
      BdeLaw(PairWeights unit_weights, const FrictionRadius radius);

      void
      evaluate(const ContactData &data,
               const unsigned int c,
               const double      *p,
               const double      *u,
               double            *H,
               PairPiece         *piece) const override;

      void
      tie_rule(const ContactData     &data,
               const Eigen::VectorXd &p,
               const Eigen::VectorXd &u,
               NewtonBlocks          &pieces) const override;

      void
      errors(const ContactData     &data,
             const Eigen::VectorXd &p,
             const Eigen::VectorXd &u,
             const Eigen::VectorXd &H,
             double                &err,
             double                &balanced) const override;

    private:
      /// The balanced error's weights: unit, or w where they are the same.
      const PairWeights &
      unit_weights() const;

      const PairWeights    w, unit;
      const bool           unit_is_w;
      const FrictionRadius radius;
    };



    /**
     * @brief Penalty with Coulomb return mapping (penalty_law()): H = p -
     * P(u) with P the penalty force, k_n and k_t per pair, base forces
     * lambda (the multipliers of the augmented Lagrangian, the previous
     * step's tangential force of the pure penalty). Its error is |H|
     * relative to the force scale; the answer penetrates by about p / k_n
     * and is not measured against the exact conditions.
     */
    class PenaltyLaw : public PairLawModel
    {
    public:
      PenaltyLaw(const Eigen::VectorXd &k_n,
                 const Eigen::VectorXd &k_t,
                 const Eigen::VectorXd &lambda);

      void
      evaluate(const ContactData &data,
               const unsigned int c,
               const double      *p,
               const double      *u,
               double            *H,
               PairPiece         *piece) const override;

      void
      tie_rule(const ContactData     &data,
               const Eigen::VectorXd &p,
               const Eigen::VectorXd &u,
               NewtonBlocks          &pieces) const override;

      void
      errors(const ContactData     &data,
             const Eigen::VectorXd &p,
             const Eigen::VectorXd &u,
             const Eigen::VectorXd &H,
             double                &err,
             double                &balanced) const override;

      double
      floor_factor() const override;

      bool
      full_step_on_failure() const override;

    private:
      const Eigen::VectorXd k_n, k_t, lambda;
    };



    /** @brief The stopping test's measures of the error at one iterate. */
    struct StopMeasures
    {
      /// The law's reported error (the FCLIB error for the exact law).
      double err = 0.;
      /// The law's scale-invariant error.
      double balanced = 0.;
      /// The relative equilibrium error of floating bodies.
      double eq = 0.;
      /// The componentwise backward error of the displacement equations.
      double disp = 0.;
    };



    /**
     * @brief The buffers of the Newton driver and of the phases around it,
     * kept by a solver between its solves and lent to each solve's driver:
     * on a problem of a few contacts their allocation and release are a
     * part of the solve's time. A workspace serves one solve at a time;
     * what it holds between solves is storage, never read as a result
     * (NewtonDriver's constructor forgets the accepted answer).
     */
    struct NewtonWorkspace
    {
      /// The solver's start and the first sweeps' iterate.
      ContactIterate x, x_sweeps;
      /// The best iterate seen on the original problem, and the accepted
      /// one (NewtonDriver::best_x, NewtonDriver::converged_x).
      ContactIterate best_x, converged_x;
      /// Directions held by supports on both sides (pair rows).
      std::vector<bool> held;
      /// u, the law's residual and the pieces of the stopping test and of
      /// the answer.
      Eigen::VectorXd u_scratch;
      ContactIterate  F_scratch;
      NewtonBlocks    pieces_scratch;
      /// The Gauss-Seidel phase's running u, and u and the law's residual
      /// at its checks.
      Eigen::VectorXd sweep_u, check_u;
      ContactIterate  check_F;

      /// The evaluation of converged_x by the stopping test that accepted
      /// it (NewtonDriver::accept(); law null: none). law and data name the
      /// accepting test's objects by address only, to be compared with
      /// answer()'s, never read through: a phase's law may be a temporary
      /// that has ended (phases 2 and 2b), and then no live law has its
      /// address.
      struct Accepted
      {
        const PairLawModel *law  = nullptr;
        const ContactData  *data = nullptr;
        Eigen::VectorXd     u;
        ContactIterate      F;
        StopMeasures        measures;
      };
      Accepted accepted;
    };



    /** @brief How a Newton phase ended. */
    struct PhaseOutcome
    {
      bool        converged = false;
      std::string reason;
    };



    /**
     * @brief The one damped semismooth (B-)Newton driver of the contact
     * layer, over any ContactOperator (the path) and any PairLawModel (the
     * law). Unknowns x = (p, alpha, w), residual F = (H, G^T p - b, E) with
     * E the operator's displacement equations, merit theta = |F|^2 / 2.
     *
     *  - Direction: the operator's Newton step for the law's pieces; if it
     *    fails, or is not a descent direction (grad^T d > -1e-8 |grad||d|),
     *    the steepest descent -J^T F.
     *  - Line search: Armijo backtracking t = beta^m on theta, accepted if
     *    theta(x + t d) <= theta_ref + sigma t grad^T d, theta_ref the max
     *    of the last BNewtonSettings::nonmonotone_memory values
     *    (Grippo-Lampariello-Lucidi; 1 is monotone); when t < min_step
     *    the best trial point is taken if it decreases theta, else the
     *    steepest descent is tried; if that fails too the phase ends
     *    ("line-search failure"), unless the stopping test holds at the
     *    rounding floor.
     *  - Stopping test (stopping_test()): the law's balanced error and its
     *    reported error below the tolerance (or, once Newton stops
     *    converging quadratically, the balanced error below the law's
     *    floor_factor() times it), the equilibrium of floating bodies and
     *    the componentwise backward error of the displacement equations
     *    below the tolerance.
     *  - Failure diagnosis: iteration limit, stall (no 0.1 % decrease of
     *    the best theta in BNewtonSettings::stall_iterations iterations),
     *    line-search failure, non-finite values, time limit; with the
     *    pairs involved (cycling between active sets, non-finite values,
     *    or the largest residuals).
     *
     * The proximal phase and the radius switch of the BDE are phases built
     * on newton() (BNewtonSolver); the augmented Lagrangian is an outer
     * loop around it.
     */
    class NewtonDriver
    {
    public:
      /**
       * @param original The problem whose pair directions held by supports
       * on both sides are found once (held).
       * @param op The path (its proximal shift may be changed by phases).
       * @param settings Tolerances, limits, line search, log.
       * @param result Receives the history and iteration count.
       * @param workspace The buffers to use (a solver's, kept between its
       * solves); null: the driver's own.
       */
      NewtonDriver(const ContactData     &original,
                   ContactOperator       &op,
                   const BNewtonSettings &settings,
                   ContactSolverResult   &result,
                   NewtonWorkspace       *workspace = nullptr);

      /**
       * @brief One Newton phase on @p data (the original, or a proximal
       * subproblem) from @p x, to @p tolerance, at most @p budget
       * iterations; @p on_original: iterates are candidates for the
       * answer. With @p leave_when_singular_at_start the phase ends before
       * any step when its first Newton matrix is singular and the operator
       * prefers the proximal phase then
       * (ContactOperator::proximal_for_singular_start();
       * left_singular_at_start is set). With @p leave_when_cycling (a
       * phase that another follows) the phase also ends as a stall when
       * ten iterations bring no progress while the active sets cycle
       * among at most five (FCLIB: spheres-in-a-box 103 -> 69 iterations,
       * Capsules-i100-1090 56 -> 50); the last phases keep the full
       * stall window, since one of them may still converge after such a
       * stretch (a radius-switch hard case does).
       * With @p leave_when_crawling (a phase at a user's r scale far from
       * 1, which the scale 1 follows) it ends when the best theta fell by
       * less than 10 % in those ten iterations.
       */
      PhaseOutcome
      newton(const ContactData  &data,
             const PairLawModel &law,
             ContactIterate     &x,
             const double        tolerance,
             const std::string  &phase,
             const bool          on_original,
             const unsigned int  budget,
             const bool          leave_when_singular_at_start = false,
             const bool          leave_when_cycling           = false,
             const bool          leave_when_crawling          = false);

      /**
       * @brief The stopping test at x (see the class documentation); its
       * measures go to @p measures. @p u_at_x and @p F_at_x, when given,
       * are u and the law's residual at @p x as evaluate() returns them
       * (the Newton loop has them: evaluating again would cost a product
       * with W per iteration).
       */
      bool
      stopping_test(const ContactData     &data,
                    const PairLawModel    &law,
                    const ContactIterate  &x,
                    const double           tolerance,
                    const bool             at_rounding_floor,
                    StopMeasures          &measures,
                    const Eigen::VectorXd *u_at_x = nullptr,
                    const ContactIterate  *F_at_x = nullptr) const;

      /**
       * @brief u, the law's residual F and (if @p pieces) the pieces at
       * @p x, with the directions held by supports on both sides taken
       * out of the law (p = 0 there); returns theta = |F|^2 / 2.
       */
      double
      evaluate(const ContactData    &data,
               const PairLawModel   &law,
               const ContactIterate &x,
               Eigen::VectorXd      &u,
               ContactIterate       &F,
               NewtonBlocks         *pieces) const;

      /**
       * @brief As evaluate(), from @p u = M(p, w) + G alpha + q and
       * F.w = E(p, w) given (zeroed in the held directions on return).
       */
      double
      residual(const ContactData    &data,
               const PairLawModel   &law,
               const ContactIterate &x,
               Eigen::VectorXd      &u,
               ContactIterate       &F,
               NewtonBlocks         *pieces) const;

      /**
       * @brief The answer @p x into the result: p, alpha, w, u, the status
       * of every pair under @p law, the largest penetration and, with
       * @p measures, the exact conditions' measures (FCLIB natural map,
       * balanced, equilibrium; a caller whose stopping test at the answer
       * writes them passes false). Returns the residual of @p law at @p x
       * (for a stopping test at the answer without evaluating it again).
       */
      ContactIterate
      finish(const ContactData    &data,
             const PairLawModel   &law,
             const ContactIterate &x,
             const bool            measures = true) const;

      /**
       * @brief Records @p x as the answer of the problem (converged_x),
       * accepted by a stopping test on @p data under @p law that had @p u
       * and the law's residual @p F at @p x (taken over) and measured
       * @p measures: answer() then reads them
       * instead of evaluating the answer again (a product with W and the
       * law's errors, on a problem of a few contacts a sixth of the
       * solve).
       */
      void
      accept(const ContactData    &data,
             const PairLawModel   &law,
             const ContactIterate &x,
             Eigen::VectorXd     &&u,
             ContactIterate      &&F,
             const StopMeasures   &measures);

      /**
       * @brief Records @p x as the answer of the problem (converged_x),
       * without the evaluation that accepted it.
       */
      void
      accept(const ContactIterate &x);

      /**
       * @brief finish() and the stopping test at the answer @p x under
       * @p law: its measures into the result (residual, balanced,
       * equilibrium); returns whether the test passes. Where
       * @p x is converged_x, accepted on @p data under @p law with its
       * evaluation (accept()), that evaluation and its measures are the
       * answer's (the same values: the test passed there).
       */
      bool
      answer(const ContactData    &data,
             const PairLawModel   &law,
             const ContactIterate &x,
             const double          tolerance) const;

      /** @brief Whether the iteration budget is used up. */
      bool
      out_of_iterations() const;

      /** @brief Whether the wall-time limit is passed. */
      bool
      out_of_time() const;

      /**
       * @brief Offers @p x as the answer if its error (the larger of the
       * balanced and the equilibrium one) is the smallest.
       */
      void
      offer_best(const ContactIterate &x, const StopMeasures &measures);

      /** @brief The stream of the iteration log. */
      std::ostream &
      log() const;

    private:
      /// The buffers when no workspace is lent. Declared before ws, which
      /// refers to it: members are initialised in declaration order.
      std::optional<NewtonWorkspace> own;

    public:
      ContactOperator                      &op;
      const BNewtonSettings                &settings;
      ContactSolverResult                  &result;
      std::chrono::steady_clock::time_point start;
      /// The buffers in use (lent, or own).
      NewtonWorkspace &ws;
      /// Directions held by supports on both sides (pair rows), and
      /// whether there is any.
      std::vector<bool> &held;
      bool               any_held;
      bool               have_best  = false;
      double             best_score = 0.;
      /// Iterations whose Newton matrix was singular (Levenberg-Marquardt
      /// or steepest-descent steps).
      unsigned int singular_iterations = 0;
      /// Set when a phase asked to leave when its first Newton matrix is
      /// singular ended so (newton()).
      bool            left_singular_at_start = false;
      ContactIterate &best_x, &converged_x;

    private:
      /// p, alpha, w, the status of every pair (from pieces_scratch) and
      /// the largest penetration (from result.u) of the answer @p x.
      void
      record_answer(const ContactData &data, const ContactIterate &x) const;
    };



    /**
     * @brief The tangential pair directions held by supports on both sides
     * (an empty row of the operator, and of G with floating bodies): no
     * displacement moves them and their force enters no body's equations,
     * so they carry p = 0 and u = 0 (the supports take whatever friction
     * would carry there). Left to the contact law, a stick piece there is a
     * zero row of the Newton matrix. The rule for every path and solver.
     * Into @p held (one entry per pair row); returns whether any is held.
     */
    bool
    held_pair_directions(const ContactData     &data,
                         const ContactOperator &op,
                         std::vector<bool>     &held);

    /** @brief Status counts of @p status into the result. */
    void
    count_status(ContactSolverResult &result);
  } // namespace contact
} // namespace igabde

#endif
