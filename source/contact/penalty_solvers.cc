#include <igabde/base/utilities.h>

#include <igabde/contact/penalty_solvers.h>

#include <deal.II/base/exceptions.h>

#include <limits>
#include <sstream>

namespace igabde
{
  namespace contact
  {
    namespace
    {
      using Vec = Eigen::VectorXd;

      // The starting iterate: p and w from the start (zero when empty),
      // alpha likewise.
      ContactIterate
      starting_iterate(const ContactData     &data,
                       const ContactOperator &op,
                       const ContactIterate  &start)
      {
        ContactIterate x;
        x.p = start.p.size() > 0 ? start.p : Vec::Zero(data.n_rows());
        x.alpha =
          start.alpha.size() > 0 ? start.alpha : Vec::Zero(data.n_alpha());
        x.w = start.w.size() > 0 ? start.w : Vec::Zero(op.n_dofs());
        AssertDimension(x.p.size(), data.n_rows());
        AssertDimension(x.alpha.size(), data.n_alpha());
        AssertDimension(x.w.size(), op.n_dofs());
        return x;
      }



      // Penalty stiffnesses per pair.
      void
      penalty_stiffness(const ContactOperator       &op,
                        const ContactSolverSettings &settings,
                        Vec                         &k_n,
                        Vec                         &k_t)
      {
        AssertThrow(settings.penalty.normal_factor > 0. &&
                      settings.penalty.tangential_factor > 0.,
                    base::ExcInput("the penalty factors FKN and FKT must be "
                                   "positive"));
        k_n = settings.penalty.normal_factor * op.pair_stiffness();
        k_t = settings.penalty.tangential_factor * k_n;
      }



      // The driver settings of a penalty solve: its iteration limit, the
      // line search as the scene asks (monotone Armijo).
      BNewtonSettings
      penalty_newton_settings(const ContactSolverSettings &settings)
      {
        BNewtonSettings s    = settings.bnewton;
        s.nonmonotone_memory = 1;
        s.line_search        = settings.penalty.line_search;
        // The limits are per penalty solve (Penalty settings), not over
        // the multiplier updates.
        s.max_iterations = std::numeric_limits<unsigned int>::max();
        return s;
      }



    } // namespace



    PenaltySolver::PenaltySolver(const ContactSolverSettings &settings)
      : settings(settings)
    {}



    std::string
    PenaltySolver::name() const
    {
      return "penalty";
    }



    bool
    PenaltySolver::exact() const
    {
      return false;
    }



    ContactSolverResult
    PenaltySolver::solve(const ContactData     &data,
                         ContactOperator       &op,
                         const ContactIterate  &start,
                         const Eigen::VectorXd &p_previous) const
    {
      ContactIterate x = starting_iterate(data, op, start);
      Vec            k_n, k_t;
      penalty_stiffness(op, settings, k_n, k_t);
      // Pure penalty: no normal multiplier; the tangential base is the
      // force at the end of the previous step (friction is incremental).
      const unsigned int d      = data.n_components;
      Vec                lambda = Vec::Zero(data.n_rows());
      if (p_previous.size() == data.n_rows())
        for (unsigned int c = 0; c < data.n_contacts; ++c)
          for (unsigned int k = 1; k < d; ++k)
            lambda[c * d + k] = p_previous[c * d + k];

      ContactSolverResult   result;
      const BNewtonSettings newton = penalty_newton_settings(settings);
      NewtonDriver          driver(data, op, newton, result);
      const PenaltyLaw      law(k_n, k_t, lambda);
      const PhaseOutcome    outcome =
        driver.newton(data,
                      law,
                      x,
                      settings.bnewton.tolerance,
                      "penalty",
                      false,
                      settings.penalty.max_iterations);
      result.converged = outcome.converged;
      std::ostringstream s;
      if (outcome.converged)
        s << "converged (penalty, FKN = " << settings.penalty.normal_factor
          << ")";
      else
        s << "no convergence of the penalty Newton: " << outcome.reason
          << " (a smaller penalty factor converges more easily)";
      result.diagnosis = s.str();
      driver.finish(data, law, x);
      if (settings.bnewton.log)
        result.print_history(driver.log());
      return result;
    }



    AugmentedLagrangeSolver::AugmentedLagrangeSolver(
      const ContactSolverSettings &settings)
      : settings(settings)
    {}



    std::string
    AugmentedLagrangeSolver::name() const
    {
      return "augmented-lagrange";
    }



    ContactSolverResult
    AugmentedLagrangeSolver::solve(const ContactData    &data,
                                   ContactOperator      &op,
                                   const ContactIterate &start,
                                   const Eigen::VectorXd &) const
    {
      ContactIterate x = starting_iterate(data, op, start);
      Vec            k_n, k_t;
      penalty_stiffness(op, settings, k_n, k_t);
      // Multipliers start at the warm-start forces.
      Vec lambda = x.p;

      ContactSolverResult   result;
      const BNewtonSettings newton = penalty_newton_settings(settings);
      NewtonDriver          driver(data, op, newton, result);
      const BdeLaw          exact_law(op.weights(data, 1.),
                             op.weights(data, 1.),
                             newton.radius);
      const double          tol = settings.bnewton.tolerance;
      // The method of multipliers with penalty increase (Bertsekas; Nocedal
      // and Wright, Framework 17.3): when an update does not reduce the
      // residual by the factor 1/4, the penalty doubles, up to 1000 times
      // FKN. The contraction per update is about 1 / (1 + k lambda_min(W))
      // on the closed pairs, slow for a soft penalty.
      double       factor = 1., previous_error = 0.;
      const double max_factor = 1000.;
      for (unsigned int k = 0;; ++k)
        {
          const PenaltyLaw   law(k_n, k_t, lambda);
          const PhaseOutcome outcome =
            driver.newton(data,
                          law,
                          x,
                          tol,
                          "al-newton",
                          false,
                          settings.penalty.max_iterations);
          if (!outcome.converged)
            {
              result.diagnosis = "augmented Lagrange update " +
                                 std::to_string(k) + ": " + outcome.reason;
              break;
            }
          // The stopping test of the B-differentiable equations (with its
          // rounding-floor clause: a balanced residual 1000 times below the
          // tolerance) on the multipliers' answer.
          StopMeasures measures;
          const bool   done =
            driver.stopping_test(data, exact_law, x, tol, true, measures);
          const double err = measures.err, bal = measures.balanced;
          if (!result.history.empty())
            {
              result.history.back().residual          = err;
              result.history.back().balanced_residual = bal;
              result.history.back().note = "update " + std::to_string(k);
            }
          if (done && (err <= tol || bal <= 1e-3 * tol))
            {
              result.converged = true;
              std::ostringstream s;
              s << "converged (augmented Lagrange, FKN = "
                << settings.penalty.normal_factor * factor << ", " << k
                << " multiplier updates)";
              result.diagnosis = s.str();
              break;
            }
          if (k >= settings.penalty.max_updates)
            {
              std::ostringstream s;
              s << "no convergence in " << k
                << " multiplier updates (natural-map residual " << err
                << "); a larger penalty factor contracts faster";
              result.diagnosis = s.str();
              break;
            }
          lambda = x.p;
          ++result.updates;
          if (k > 0 && err > 0.25 * previous_error && factor < max_factor)
            {
              factor *= 2.;
              k_n *= 2.;
              k_t *= 2.;
            }
          previous_error = err;
        }
      const PenaltyLaw final_law(k_n, k_t, lambda);
      driver.finish(data, final_law, x);
      if (settings.bnewton.log)
        result.print_history(driver.log());
      return result;
    }
  } // namespace contact
} // namespace igabde
