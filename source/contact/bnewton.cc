#include <igabde/contact/bnewton.h>
#include <igabde/contact/gauss_seidel.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <utility>

namespace igabde
{
  namespace contact
  {
    namespace
    {
      using Vec = Eigen::VectorXd;

      std::string
      phase_name(const std::string &prefix, const FrictionRadius radius)
      {
        return prefix +
               (radius == FrictionRadius::christensen_pang ? "-cp" : "-ac");
      }



      FrictionRadius
      other(const FrictionRadius radius)
      {
        return radius == FrictionRadius::christensen_pang ?
                 FrictionRadius::alart_curnier :
                 FrictionRadius::christensen_pang;
      }



      // The law of the B-differentiable equations on @p op at factor c.
      BdeLaw
      bde_law(const ContactOperator &op,
              const ContactData     &data,
              const double           r_factor,
              const FrictionRadius   radius)
      {
        // At the default scale 1 the law's weights are the unit ones, formed
        // and held once (on a problem of a few contacts each allocation is
        // a part of the solve's time).
        if (r_factor == 1.)
          return BdeLaw(op.weights(data, 1.), radius);
        return BdeLaw(op.weights(data, r_factor), op.weights(data, 1.), radius);
      }
    } // namespace



    BNewtonSolver::BNewtonSolver(const Settings &settings)
      : settings(settings)
    {
      AssertThrow(settings.tolerance > 0.,
                  dealii::ExcMessage("BNewtonSolver: tolerance must be > 0"));
      AssertThrow(settings.armijo_sigma > 0. && settings.armijo_sigma < 0.5,
                  dealii::ExcMessage(
                    "BNewtonSolver: armijo_sigma must be in (0, 1/2)"));
      AssertThrow(settings.armijo_beta > 0. && settings.armijo_beta < 1.,
                  dealii::ExcMessage(
                    "BNewtonSolver: armijo_beta must be in (0, 1)"));
      AssertThrow(settings.min_step > 0. && settings.min_step < 1.,
                  dealii::ExcMessage(
                    "BNewtonSolver: min_step must be in (0, 1)"));
      AssertThrow(settings.r_factor > 0.,
                  dealii::ExcMessage("BNewtonSolver: r_factor must be > 0"));
    }



    std::string
    BNewtonSolver::name() const
    {
      return "bde";
    }



    const BNewtonSolver::Settings &
    BNewtonSolver::get_settings() const
    {
      return settings;
    }



    BNewtonSolver::Result
    BNewtonSolver::solve(const ContactProblem &problem) const
    {
      return solve(problem, Eigen::VectorXd(), Eigen::VectorXd());
    }



    BNewtonSolver::Result
    BNewtonSolver::solve(const ContactProblem  &problem,
                         const Eigen::VectorXd &p0,
                         const Eigen::VectorXd &alpha0) const
    {
      problem.check_consistency();
      CondensedOperator op(problem.W,
                           settings.linear_algebra,
                           settings.sparse_fill,
                           settings.use_symmetry);
      ContactIterate    start;
      start.p     = p0;
      start.alpha = alpha0;
      return solve(problem, op, start);
    }



    PhaseOutcome
    BNewtonSolver::proximal_phase(NewtonDriver         &driver,
                                  const ContactData    &data,
                                  const ContactIterate &x,
                                  const double          r_factor) const
    {
      const FrictionRadius radius  = settings.radius;
      ContactIterate       xk      = driver.have_best ? driver.best_x : x;
      const double         scale   = driver.op.flexibility_scale();
      const double         eps_ref = scale > 0. ? scale : 1.;
      double               eps     = eps_ref;
      double               err     = driver.have_best ? driver.best_score : 1.;
      unsigned int         n_fail = 0, n_idle = 0;
      PhaseOutcome         outcome;
      outcome.reason            = "iteration limit";
      const BdeLaw original_law = bde_law(driver.op, data, r_factor, radius);
      ContactData  sub          = data;
      while (!driver.out_of_iterations() && !driver.out_of_time())
        {
          driver.op.set_proximal_shift(eps);
          sub.q = data.q - eps * xk.p;
          const double inner_tol =
            std::max(0.1 * settings.tolerance, std::min(1e-6, 0.1 * err));
          ContactIterate xi = xk;
          PhaseOutcome   in =
            driver.newton(sub,
                          bde_law(driver.op, sub, r_factor, radius),
                          xi,
                          inner_tol,
                          phase_name("prox", radius),
                          false,
                          50);
          if (!in.converged && !driver.out_of_iterations())
            {
              xi = xk;
              in =
                driver.newton(sub,
                              bde_law(driver.op, sub, r_factor, other(radius)),
                              xi,
                              inner_tol,
                              phase_name("prox", other(radius)),
                              false,
                              50);
            }
          driver.op.set_proximal_shift(0.);
          const bool idle = in.converged && xi.p == xk.p &&
                            xi.alpha == xk.alpha && xi.w == xk.w;
          if (idle)
            {
              // The subproblem is solved where it starts (its relative
              // residual is measured against q - eps x_k, which a large
              // eps makes large): a smaller eps brings it nearer the
              // original problem; without that the loop would turn
              // without iterating.
              eps = std::max(eps * 0.1, 1e-12 * eps_ref);
              if (++n_idle > 12)
                {
                  outcome.reason = "stall (every proximal subproblem is "
                                   "solved at the current iterate)";
                  break;
                }
            }
          else if (in.converged)
            {
              n_idle = 0;
              xk     = xi;
              StopMeasures measures;
              const bool   done = driver.stopping_test(data,
                                                     original_law,
                                                     xk,
                                                     settings.tolerance,
                                                     false,
                                                     measures);
              driver.offer_best(xk, measures);
              if (done)
                {
                  driver.accept(xk);
                  outcome.converged = true;
                  outcome.reason    = "converged";
                  break;
                }
              // A solved subproblem allows a smaller shift: the nearer
              // eps is to 0, the faster the outer iterations converge
              // (their rate is about eps / (eps + the smallest non-zero
              // eigenvalue of W)). Kept while the error halved only,
              // the outer iterations crawled at a constant eps
              // (fc2d_granularflowonwall_02020: 300 iterations at 3e-7;
              // reduced at every solved subproblem, 96 iterations to
              // 5e-11).
              eps    = std::max(eps * 0.1, 1e-12 * eps_ref);
              err    = std::min(err, measures.balanced);
              n_fail = 0;
            }
          else
            {
              eps *= 10.;
              if (++n_fail > 6 || eps > 1e12 * eps_ref)
                {
                  outcome.reason =
                    "stall (inner solves fail: " + in.reason + ")";
                  break;
                }
            }
        }
      driver.op.set_proximal_shift(0.);
      return outcome;
    }



    BNewtonSolver::Result
    BNewtonSolver::solve(const ContactData    &data,
                         ContactOperator      &op,
                         const ContactIterate &start,
                         const Eigen::VectorXd &) const
    {
      data.check_consistency();
      const unsigned int m = data.n_rows(), na = data.n_alpha();
      AssertThrow(op.n_rows() == m,
                  dealii::ExcMessage("BNewtonSolver::solve: the operator has " +
                                     std::to_string(op.n_rows()) +
                                     " rows, the problem " +
                                     std::to_string(m)));
      AssertThrow(start.p.size() == 0 || start.p.size() == m,
                  dealii::ExcMessage("BNewtonSolver::solve: p0 has size " +
                                     std::to_string(start.p.size()) +
                                     ", expected " + std::to_string(m)));
      AssertThrow(start.alpha.size() == 0 || start.alpha.size() == na,
                  dealii::ExcMessage("BNewtonSolver::solve: alpha0 has size " +
                                     std::to_string(start.alpha.size()) +
                                     ", expected " + std::to_string(na)));
      Result result;
      // The start, in the workspace's storage (assigned, not built: the
      // storage of an earlier solve of the same size is reused).
      ContactIterate &x = workspace.x;
      if (start.p.size() > 0)
        x.p = start.p;
      else
        x.p.setZero(m);
      if (start.w.size() > 0)
        x.w = start.w;
      else
        x.w.setZero(op.n_dofs());
      if (na > 0 && start.alpha.size() > 0)
        x.alpha = start.alpha;
      else if (na > 0)
        x.alpha = touching_alpha(data);
      else
        x.alpha.resize(0);

      op.set_proximal_shift(0.);
      NewtonDriver driver(data, op, settings, result, &workspace);
      if (settings.log)
        driver.log()
          << "B-Newton on " << (data.name.empty() ? "problem" : data.name)
          << " (" << op.path_name() << " path): " << data.n_contacts
          << " contacts, " << data.n_components << " components, " << na
          << " floating modes\n"
          << "   it     phase        |H|    residual    balanced        step"
             "  open stick  slip closed   red note\n";

      PhaseOutcome outcome;
      // The phases' reasons, the diagnosis' text (reserved once: on a
      // problem of one contact each allocation is a part of the time).
      std::string reasons;
      reasons.reserve(160);
      double r_factor = settings.r_factor;
      // The law of phases 0 and 1 and of the answer's measures (its
      // weights are formed once: on a problem of a few contacts they are
      // a part of the solve's time worth keeping).
      const BdeLaw law = bde_law(op, data, settings.r_factor, settings.radius);
      if (m + na == 0)
        {
          outcome.converged = true;
          driver.accept(x);
        }
      else
        {
          // Phase 1: Newton with the chosen radius; on a path that
          // prefers it, a singular first Newton matrix hands over to the
          // proximal phase (phase 4) at once.
          const FrictionRadius radius = settings.radius;
          // Phase 0: a few Gauss-Seidel sweeps where W is sparse (rigid
          // bodies: each contact coupled to the few that share its
          // bodies), each a pass over W's non-zeros, far cheaper than one
          // Newton factorisation; where they do not solve the problem, the
          // Newton phases start from the start as without them (from the
          // sweeps' iterate, Capsules-i122-1617 and spheres-in-a-box did
          // not converge in 300 iterations; doc/contact-solver.md). Up to a
          // thousand sweeps where the local problems are solved in closed
          // form (2D, frictionless), ten in 3D with friction (Settings).
          // Ten sweeps where W is small (fewer than min_sparse_rows rows: a
          // few contacts, where a Newton iteration costs a few sweeps; with
          // a budget of a thousand, FC2D_SliderCrankLagrangian's 367 sweeps
          // cost more than 1 sweep and 1 Newton iteration): a problem of
          // one contact is its own local problem, solved exactly by one
          // sweep, and on a few weakly coupled contacts one sweep solves it
          // too, in less time than Newton's 2-3 iterations (CubeH8,
          // Confeti-ex13-4contact, FC3D_Example1), a few more sweeps on
          // others (Rover4396: 4 sweeps, in less time than 1 sweep and 3
          // Newton iterations; doc/contact-solver.md); where they do not,
          // Newton starts from the sweeps' iterate, nearer the solution
          // than the start (the Rover problems, 4-5 contacts: 5-8
          // iterations -> 2-3).
          const auto *Ws   = op.sparse_flexibility(data);
          const bool small = data.n_rows() < CondensedOperator::min_sparse_rows;
          // Newton's start: x, or the first sweeps' iterate (copied only
          // where Newton runs).
          ContactIterate       &x_sweeps = workspace.x_sweeps;
          const ContactIterate *x_newton = &x;
          if (settings.gauss_seidel_first_sweeps > 0 &&
              (Ws != nullptr || small) && na == 0 &&
              op.dense_flexibility() != nullptr)
            {
              x_sweeps                  = x;
              unsigned int       sweeps = 0;
              GaussSeidelOptions first;
              first.max_sweeps =
                Ws != nullptr && local_problems_in_closed_form(data) ?
                  settings.gauss_seidel_first_sweeps_exact :
                  settings.gauss_seidel_first_sweeps;
              first.check_every        = 1;
              first.offer_best         = false;
              first.quit_when_too_slow = true;
              outcome                  = gauss_seidel_phase(driver,
                                           data,
                                           law,
                                           *op.dense_flexibility(),
                                           Ws,
                                           x_sweeps,
                                           first,
                                           sweeps);
              result.sweeps += sweeps;
              reasons = "gauss-seidel first: ";
              reasons += outcome.reason;
              if (Ws == nullptr && x_sweeps.p.allFinite())
                x_newton = &x_sweeps;
            }
          // Whether phase 2 (r at the scale 1) will run, when phase 1
          // fails: a phase another follows ends early when it cycles.
          const bool r_far = std::abs(std::log10(settings.r_factor)) > 1.;
          if (!outcome.converged)
            {
              ContactIterate x1 = *x_newton;
              outcome           = driver.newton(data,
                                      law,
                                      x1,
                                      settings.tolerance,
                                      phase_name("newton", radius),
                                      true,
                                      settings.max_iterations,
                                      settings.proximal,
                                      settings.switch_radius &&
                                        (data.has_friction() || r_far),
                                      settings.switch_radius && r_far);
              reasons += (reasons.empty() ? "" : "; ") +
                         phase_name("newton", radius) + ": " + outcome.reason;
            }
          const bool proximal_now = driver.left_singular_at_start;
          // Phase 2: r from the flexibility alone (c = 1), when the
          // chosen factor is far from it. The solution does not depend on
          // r, but the merit |H|^2 weighs the displacement rows by r: with
          // c = 1e-4 (B1) the line search hardly sees the penetration and
          // the active sets cycle; c = 1 balances force and displacement.
          // Before the other radius, which cycles as the first did at the
          // same c (V4 with r scale 1e6: 109 iterations of the other
          // radius without progress, then 2 at c = 1).
          if (!outcome.converged && !proximal_now && settings.switch_radius &&
              r_far && !driver.out_of_iterations() && !driver.out_of_time())
            {
              r_factor          = 1.;
              ContactIterate x3 = driver.have_best ? driver.best_x : x;
              outcome           = driver.newton(data,
                                      bde_law(op, data, r_factor, radius),
                                      x3,
                                      settings.tolerance,
                                      phase_name("newton-r1", radius),
                                      true,
                                      settings.max_iterations);
              reasons +=
                "; " + phase_name("newton-r1", radius) + ": " + outcome.reason;
            }
          // Phase 2b: the other radius, from the best iterate (at c = 1
          // when phase 2 ran).
          if (!outcome.converged && !proximal_now && data.has_friction() &&
              settings.switch_radius && !driver.out_of_iterations() &&
              !driver.out_of_time())
            {
              const std::string name =
                phase_name(r_factor == settings.r_factor ? "newton" :
                                                           "newton-r1",
                           other(radius));
              ContactIterate x2 = driver.have_best ? driver.best_x : x;
              outcome =
                driver.newton(data,
                              bde_law(op, data, r_factor, other(radius)),
                              x2,
                              settings.tolerance,
                              name,
                              true,
                              settings.max_iterations);
              reasons += "; " + name + ": " + outcome.reason;
            }
          // Phase 3: nonsmooth Gauss-Seidel, where its local problems are
          // solved exactly (condensed path, 2D or frictionless, no
          // floating bodies); before the proximal phase, which costs more
          // where both apply (as on FrictionContactProblem00727;
          // doc/contact-solver.md). On a sparse W each pair's u is read
          // from its rows of the sparse copy, which costs less than the
          // dense W's columns.
          const Eigen::MatrixXd *W = op.dense_flexibility();
          if (!outcome.converged && !proximal_now &&
              settings.gauss_seidel_sweeps > 0 && W != nullptr && na == 0 &&
              local_problems_in_closed_form(data) && !driver.out_of_time())
            {
              op.set_proximal_shift(0.);
              ContactIterate     xg     = driver.have_best ? driver.best_x : x;
              unsigned int       sweeps = 0;
              GaussSeidelOptions options;
              options.max_sweeps    = settings.gauss_seidel_sweeps;
              const PhaseOutcome gs = gauss_seidel_phase(driver,
                                                         data,
                                                         law,
                                                         *W,
                                                         Ws,
                                                         xg,
                                                         options,
                                                         sweeps);
              result.sweeps += sweeps;
              outcome = gs;
              reasons += "; gauss-seidel: " + gs.reason;
            }
          // Phase 4: proximal point.
          if (!outcome.converged && settings.proximal &&
              !driver.out_of_iterations() && !driver.out_of_time())
            {
              outcome = proximal_phase(driver, data, x, r_factor);
              reasons += "; proximal: " + outcome.reason;
            }
        }

      // The returned iterate: the converged one, else the best one seen on
      // the original problem.
      const ContactIterate &xr = outcome.converged ? driver.converged_x :
                                 driver.have_best  ? driver.best_x :
                                                     x;
      // The answer and the status of every pair with the phase-1 radius;
      // its measures from the stopping test (the law's errors are the
      // exact conditions' measures: FCLIB's, balanced at the unit scale),
      // those of the test that accepted it where that was under this law.
      const bool strict = driver.answer(data, law, xr, settings.tolerance);
      // With fclib_stopping the FCLIB error alone is the test (as the
      // stopping test); else the balanced error must meet it too.
      result.converged = (strict || outcome.converged) &&
                         result.p.allFinite() &&
                         (settings.fclib_stopping ?
                            result.residual <= settings.tolerance :
                            result.balanced_residual <= settings.tolerance);
      if (result.converged)
        {
          reasons.insert(0, "converged (");
          reasons += ')';
          result.diagnosis = std::move(reasons);
        }
      else if (!result.p.allFinite() || !std::isfinite(result.residual))
        result.diagnosis = "non-finite result (" + reasons + ")";
      else
        result.diagnosis =
          "not converged: " + outcome.reason + " [" + reasons + "]";
      if (result.converged)
        result.pairs_involved.clear();
      else if (driver.singular_iterations > 0)
        result.diagnosis +=
          "; the Newton matrix was singular in " +
          std::to_string(driver.singular_iterations) + " of " +
          std::to_string(result.iterations) +
          " iterations (Levenberg-Marquardt steps): redundant pairs, or a "
          "body held only through contact";

      if (settings.log)
        driver.log() << result.summary() << '\n';
      return result;
    }

  } // namespace contact
} // namespace igabde
