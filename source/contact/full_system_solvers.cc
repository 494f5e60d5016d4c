#include <igabde/base/utilities.h>

#include <igabde/contact/contact_law.h>
#include <igabde/contact/full_system_solvers.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

namespace igabde
{
  namespace contact
  {
    namespace
    {
      using Vec = Eigen::VectorXd;

      // Unknowns of the coupled system.
      struct Iterate
      {
        Vec w, p, alpha;
      };



      Iterate
      starting_iterate(const ContactProblem &problem,
                       const Vec            &p0,
                       const Vec            &alpha0)
      {
        AssertThrow(problem.coupled,
                    dealii::ExcMessage(
                      "a full-system contact solver needs the coupled "
                      "system (ContactProblem::coupled)"));
        Iterate x;
        x.w     = problem.w0.size() > 0 ? problem.w0 :
                                          Vec::Zero(problem.coupled->n_dofs());
        x.p     = p0.size() > 0 ? p0 : Vec::Zero(problem.n_rows());
        x.alpha = alpha0.size() > 0 ? alpha0 : Vec::Zero(problem.n_alpha());
        AssertDimension(x.w.size(), problem.coupled->n_dofs());
        AssertDimension(x.p.size(), problem.n_rows());
        AssertDimension(x.alpha.size(), problem.n_alpha());
        return x;
      }



      // u = C w + G alpha + q.
      Vec
      relative_displacement(const ContactProblem &problem, const Iterate &x)
      {
        Vec u = problem.coupled->apply_C(x.w) + problem.q;
        if (problem.n_alpha() > 0)
          u += problem.G * x.alpha;
        return u;
      }



      // G^T p - b (empty without floating bodies).
      Vec
      equilibrium_rows(const ContactProblem &problem, const Vec &p)
      {
        if (problem.n_alpha() == 0)
          return Vec();
        return problem.G.transpose() * p - problem.b;
      }



      // The accuracy of an iterative solve of the Newton system (an
      // inexact Newton method, Eisenstat and Walker's forcing term
      // eta = c |F_k| / |F_0|): the linear residual at most eta times the
      // Newton residual |F_k|, with eta = 1e-2 min(1, |F_k| / |F_0|) and
      // not below 1e-12. Far from the solution a rough direction is
      // enough (the pair states still change); near it eta falls with the
      // residual, so the Newton residual falls as |F_k|^2 / |F_0| per
      // iteration once the states are settled (1 -> 1e-2 -> 1e-6 ->
      // 1e-14), the direct path's answer to the same stopping test.
      double
      krylov_tolerance(const double norm, const double first_norm)
      {
        const double ratio = first_norm > 0. ? norm / first_norm : 1.;
        return std::max(1e-12, 1e-2 * std::min(1., ratio));
      }



      // Newton increment for the per-pair blocks A, B and the residuals;
      // the iterations of an iterative solver go into @p rec.
      bool
      newton_increment(const ContactProblem               &problem,
                       const std::vector<Eigen::Matrix3d> &A,
                       const std::vector<Eigen::Matrix3d> &B,
                       const Vec                          &r_w,
                       const Vec                          &H,
                       const Vec                          &e,
                       const double                        tolerance,
                       Iterate                            &dx,
                       std::string                        &why,
                       ContactIterationRecord             &rec)
      {
        problem.coupled->factorize(A, B);
        const Vec  e_rhs = (e.size() > 0 ? Vec(-e) : Vec());
        const bool ok =
          problem.coupled
            ->solve(-r_w, -H, e_rhs, dx.w, dx.p, dx.alpha, why, tolerance);
        rec.linear_iterations = problem.coupled->linear_iterations();
        if (ok &&
            !(dx.w.allFinite() && dx.p.allFinite() && dx.alpha.allFinite()))
          {
            why = "the Newton system gave a non-finite increment "
                  "(singular matrix)";
            return false;
          }
        return ok;
      }



      void
      count_status(ContactSolverResult &result)
      {
        result.n_open = result.n_stick = result.n_slip = 0;
        for (const ContactStatus s : result.status)
          {
            if (s == ContactStatus::open)
              ++result.n_open;
            else if (s == ContactStatus::stick)
              ++result.n_stick;
            else
              ++result.n_slip;
          }
      }



      // Fills the result's answer and its error measures at x.
      void
      finish(const ContactProblem &problem,
             const Iterate        &x,
             ContactSolverResult  &result)
      {
        result.p     = x.p;
        result.w     = x.w;
        result.alpha = x.alpha;
        result.u     = relative_displacement(problem, x);
        result.residual =
          relative_natural_map_error(problem, result.p, result.u);
        result.balanced_residual =
          balanced_natural_map_error(problem, result.p, result.u);
        double absolute;
        result.equilibrium_residual =
          relative_equilibrium_error(problem, result.p, absolute);
        result.max_penetration = 0.;
        for (unsigned int c = 0; c < problem.n_contacts; ++c)
          result.max_penetration =
            std::max(result.max_penetration,
                     -result.u[c * problem.n_components]);
        count_status(result);
      }



      // The iteration table, when the settings ask for it.
      void
      print_history(const BNewtonSettings     &settings,
                    const ContactSolverResult &result)
      {
        if (settings.log)
          result.print_history(settings.log_stream ? *settings.log_stream :
                                                     std::cout);
      }



      // Force scale of the residuals of the coupled system.
      double
      force_scale(const ContactProblem &problem, const Vec &p)
      {
        double s = p.norm();
        if (problem.n_alpha() > 0)
          s = std::max(s, problem.b.norm());
        return s > 0. ? s : 1.;
      }



      struct PenaltyOutcome
      {
        bool        converged = false;
        std::string reason;
      };



      // Newton on the penalty system with base forces lambda, from x;
      // iterations are appended to result.history and counted there.
      PenaltyOutcome
      penalty_newton(const ContactProblem        &problem,
                     const ContactSolverSettings &settings,
                     const Vec                   &k_n,
                     const Vec                   &k_t,
                     const Vec                   &lambda,
                     const std::string           &phase,
                     Iterate                     &x,
                     ContactSolverResult         &result)
      {
        const unsigned int d = problem.n_components, nc = problem.n_contacts;
        const double       tolerance = settings.bnewton.tolerance;
        std::vector<Eigen::Matrix3d> A(nc), B(nc, Eigen::Matrix3d::Identity());
        Vec                          P(problem.n_rows());
        result.status.assign(nc, ContactStatus::open);
        PenaltyOutcome outcome;
        double         last_residual = 0., first_norm = 0.;
        for (unsigned int it = 0;; ++it)
          {
            Vec u = relative_displacement(problem, x);
            // The start (a bilateral solve, or the previous step) glues the
            // pairs it expects closed at u_n = 0 up to rounding: a pair
            // that carries compression there starts on the closed piece
            // (the tie), else a floating body could start with every pair
            // open and a singular Newton matrix.
            if (it == 0)
              for (unsigned int c = 0; c < nc; ++c)
                if (x.p[c * d] > 0. && u[c * d] > 0. &&
                    k_n[c] * u[c * d] <= 1e-8 * x.p[c * d])
                  u[c * d] = 0.;
            for (unsigned int c = 0; c < nc; ++c)
              {
                const PairPiece piece = penalty_law(d,
                                                    d > 1 ? problem.mu[c] : 0.,
                                                    k_n[c],
                                                    k_t[c],
                                                    lambda.data() + c * d,
                                                    u.data() + c * d,
                                                    P.data() + c * d);
                A[c]                  = piece.A;
                result.status[c]      = piece.status;
              }
            const Vec H   = x.p - P;
            const Vec r_w = problem.coupled->equilibrium_residual(x.w, x.p);
            const Vec e   = equilibrium_rows(problem, x.p);
            // The largest of the relative residuals of the penalty law,
            // of the displacement equations (componentwise backward error)
            // and of the equilibrium of floating bodies.
            const double w_scale = problem.coupled->equilibrium_scale(x.w, x.p);
            double       absolute;
            const double residual =
              std::max({H.norm() / force_scale(problem, P),
                        w_scale > 0. ? r_w.norm() / w_scale : 0.,
                        relative_equilibrium_error(problem, x.p, absolute)});

            ContactIterationRecord rec;
            rec.iteration = result.iterations + 1;
            rec.phase     = phase;
            rec.h_norm    = H.norm();
            rec.residual  = residual;
            rec.n_reduced =
              problem.coupled->n_dofs() + problem.n_rows() + problem.n_alpha();
            count_status(result);
            rec.n_open  = result.n_open;
            rec.n_stick = result.n_stick;
            rec.n_slip  = result.n_slip;
            if (!std::isfinite(residual))
              {
                outcome.reason = "non-finite residual";
                result.history.push_back(rec);
                return outcome;
              }
            // Converged at the tolerance, or at the rounding floor: no
            // halving of the residual in an iteration while within 1000
            // times the tolerance (the floor grows with the condition of
            // K; the outer test of the augmented Lagrangian still
            // measures the natural map).
            const bool at_floor = it > 1 && residual > 0.5 * last_residual &&
                                  residual <= 1e3 * tolerance;
            last_residual = residual;
            if (residual <= tolerance || at_floor)
              {
                rec.note = at_floor ? "rounding floor" : "states settled";
                result.history.push_back(rec);
                outcome.converged = true;
                return outcome;
              }
            if (it >= settings.penalty.max_iterations)
              {
                result.history.push_back(rec);
                outcome.reason = "no convergence in " + std::to_string(it) +
                                 " Newton iterations: the pair states "
                                 "still change (chattering; a smaller "
                                 "penalty factor converges more easily)";
                return outcome;
              }
            Iterate      dx;
            std::string  why;
            const double F_norm =
              std::sqrt(H.squaredNorm() + r_w.squaredNorm() +
                        (e.size() > 0 ? e.squaredNorm() : 0.));
            if (it == 0)
              first_norm = F_norm;
            if (!newton_increment(problem,
                                  A,
                                  B,
                                  r_w,
                                  H,
                                  e,
                                  krylov_tolerance(F_norm, first_norm),
                                  dx,
                                  why,
                                  rec))
              {
                result.history.push_back(rec);
                outcome.reason = why;
                return outcome;
              }
            // Armijo backtracking on theta = |H|^2/2 + |r_w|^2/2 + |e|^2/2
            // (the Newton direction has slope -2 theta); without line
            // search full Newton steps, as ANSYS takes them by default.
            double t = 1.;
            if (settings.penalty.line_search)
              {
                const double theta =
                  0.5 * (H.squaredNorm() + r_w.squaredNorm() +
                         (e.size() > 0 ? e.squaredNorm() : 0.));
                double  best_t = 0., best_theta = theta;
                Iterate trial;
                Vec     Pt(problem.n_rows());
                for (t = 1.; t >= settings.bnewton.min_step;
                     t *= settings.bnewton.armijo_beta)
                  {
                    trial.w      = x.w + t * dx.w;
                    trial.p      = x.p + t * dx.p;
                    trial.alpha  = x.alpha + t * dx.alpha;
                    const Vec ut = relative_displacement(problem, trial);
                    for (unsigned int c = 0; c < nc; ++c)
                      penalty_law(d,
                                  d > 1 ? problem.mu[c] : 0.,
                                  k_n[c],
                                  k_t[c],
                                  lambda.data() + c * d,
                                  ut.data() + c * d,
                                  Pt.data() + c * d);
                    const Vec    et = equilibrium_rows(problem, trial.p);
                    const double th =
                      0.5 *
                      ((trial.p - Pt).squaredNorm() +
                       problem.coupled->equilibrium_residual(trial.w, trial.p)
                         .squaredNorm() +
                       (et.size() > 0 ? et.squaredNorm() : 0.));
                    if (th <=
                        (1. - 2. * settings.bnewton.armijo_sigma * t) * theta)
                      {
                        best_t = t;
                        break;
                      }
                    if (th < best_theta)
                      {
                        best_theta = th;
                        best_t     = t;
                      }
                  }
                t = best_t > 0. ? best_t : 1.;
              }
            rec.step = t;
            result.history.push_back(rec);
            ++result.iterations;
            x.w += t * dx.w;
            x.p += t * dx.p;
            x.alpha += t * dx.alpha;
          }
      }



      // Penalty stiffnesses per pair.
      void
      penalty_stiffness(const ContactProblem        &problem,
                        const ContactSolverSettings &settings,
                        Vec                         &k_n,
                        Vec                         &k_t)
      {
        AssertThrow(settings.penalty.normal_factor > 0. &&
                      settings.penalty.tangential_factor > 0.,
                    base::ExcInput("the penalty factors FKN and FKT must be "
                                   "positive"));
        k_n =
          settings.penalty.normal_factor * problem.coupled->pair_stiffness();
        k_t = settings.penalty.tangential_factor * k_n;
      }
    } // namespace



    FullBNewtonSolver::FullBNewtonSolver(const BNewtonSettings &settings)
      : settings(settings)
    {
      AssertThrow(settings.tolerance > 0.,
                  dealii::ExcMessage("FullBNewtonSolver: tolerance must be "
                                     "> 0"));
    }



    std::string
    FullBNewtonSolver::name() const
    {
      return "bde";
    }



    ContactSolverResult
    FullBNewtonSolver::solve(const ContactProblem  &problem,
                             const Eigen::VectorXd &p0,
                             const Eigen::VectorXd &alpha0) const
    {
      const unsigned int  d = problem.n_components, nc = problem.n_contacts;
      const unsigned int  m       = problem.n_rows();
      Iterate             x       = starting_iterate(problem, p0, alpha0);
      const PairWeights   weights = pair_weights(problem, settings.r_factor);
      ContactSolverResult result;

      std::vector<PairPiece>  pieces(nc);
      const std::vector<bool> held = held_pair_directions(problem);
      // theta and the residuals at y (pieces when asked).
      const auto evaluate = [&](const Iterate &y,
                                Vec           &u,
                                Vec           &H,
                                Vec           &r_w,
                                Vec           &e,
                                const bool     with_pieces) {
        u = relative_displacement(problem, y);
        for (unsigned int row = 0; row < m; ++row)
          if (held[row])
            u[row] = 0.;
        H.resize(m);
        for (unsigned int c = 0; c < nc; ++c)
          pair_law(d,
                   d > 1 ? problem.mu[c] : 0.,
                   weights.r_n[c],
                   weights.r_t[c],
                   settings.radius,
                   y.p.data() + c * d,
                   u.data() + c * d,
                   H.data() + c * d,
                   with_pieces ? &pieces[c] : nullptr);
        for (unsigned int row = 0; row < m; ++row)
          if (held[row])
            {
              H[row] = y.p[row];
              if (with_pieces)
                {
                  const unsigned int c = row / d, k = row % d;
                  pieces[c].A.row(k).setZero();
                  pieces[c].B.row(k).setZero();
                  pieces[c].B(k, k) = 1.;
                }
            }
        r_w = problem.coupled->equilibrium_residual(y.w, y.p);
        e   = equilibrium_rows(problem, y.p);
        return 0.5 * (H.squaredNorm() + r_w.squaredNorm() +
                      (e.size() > 0 ? e.squaredNorm() : 0.));
      };

      std::vector<Eigen::Matrix3d> A(nc), B(nc);
      Vec                          u, H, r_w, e;
      double                       last_theta = 0., first_norm = 0.;
      for (unsigned int it = 0;; ++it)
        {
          const double           theta = evaluate(x, u, H, r_w, e, true);
          ContactIterationRecord rec;
          rec.iteration = it + 1;
          rec.phase     = "full-cp";
          rec.h_norm    = std::sqrt(2. * theta);
          rec.n_reduced = problem.coupled->n_dofs() + m + problem.n_alpha();
          result.status.resize(nc);
          for (unsigned int c = 0; c < nc; ++c)
            result.status[c] = pieces[c].status;
          count_status(result);
          rec.n_open  = result.n_open;
          rec.n_stick = result.n_stick;
          rec.n_slip  = result.n_slip;
          if (!std::isfinite(theta) || !x.p.allFinite())
            {
              result.diagnosis = "non-finite iterate";
              result.history.push_back(rec);
              break;
            }

          // The stopping test of the condensed solver, and the
          // displacement equations (linear: at round-off once met).
          rec.residual          = relative_natural_map_error(problem, x.p, u);
          rec.balanced_residual = balanced_natural_map_error(problem, x.p, u);
          double       absolute;
          const double eq_error =
            relative_equilibrium_error(problem, x.p, absolute);
          const double w_scale  = problem.coupled->equilibrium_scale(x.w, x.p);
          const double w_error  = w_scale > 0. ? r_w.norm() / w_scale : 0.;
          const bool   at_floor = it > 0 && theta > 0.25 * last_theta;
          last_theta            = theta;
          const double tol      = settings.tolerance;
          if (rec.balanced_residual <= tol &&
              (rec.residual <= tol ||
               (at_floor && rec.balanced_residual <= 1e-3 * tol)) &&
              eq_error <= tol && w_error <= tol)
            {
              result.converged = true;
              result.diagnosis = "converged (full system)";
              result.history.push_back(rec);
              break;
            }
          if (it >= settings.max_iterations)
            {
              result.diagnosis = "iteration limit " +
                                 std::to_string(settings.max_iterations) +
                                 " reached on the full system";
              result.history.push_back(rec);
              break;
            }

          for (unsigned int c = 0; c < nc; ++c)
            {
              A[c] = pieces[c].A;
              B[c] = pieces[c].B;
            }
          Iterate     dx;
          std::string why;
          if (it == 0)
            first_norm = rec.h_norm;
          if (!newton_increment(problem,
                                A,
                                B,
                                r_w,
                                H,
                                e,
                                krylov_tolerance(rec.h_norm, first_norm),
                                dx,
                                why,
                                rec))
            {
              result.diagnosis = why;
              result.history.push_back(rec);
              break;
            }

          // Armijo backtracking on theta (the Newton direction has slope
          // -2 theta); the best trial is kept if none is accepted.
          double  t = 1., best_t = 0., best_theta = theta;
          Iterate trial, best;
          Vec     ut, Ht, rt, et;
          bool    accepted = false;
          while (t >= settings.min_step)
            {
              trial.w           = x.w + t * dx.w;
              trial.p           = x.p + t * dx.p;
              trial.alpha       = x.alpha + t * dx.alpha;
              const double th_t = evaluate(trial, ut, Ht, rt, et, false);
              if (std::isfinite(th_t) &&
                  th_t <= (1. - 2. * settings.armijo_sigma * t) * theta)
                {
                  accepted = true;
                  best     = trial;
                  best_t   = t;
                  break;
                }
              if (std::isfinite(th_t) && th_t < best_theta)
                {
                  best_theta = th_t;
                  best       = trial;
                  best_t     = t;
                }
              t *= settings.armijo_beta;
            }
          if (best_t == 0. && rec.balanced_residual <= 1e-3 * tol &&
              eq_error <= tol && w_error <= tol)
            {
              // No step reduces theta: the rounding floor, where the
              // balanced residual already meets the tolerance by far.
              result.converged = true;
              result.diagnosis = "converged (full system, at the rounding "
                                 "floor)";
              result.history.push_back(rec);
              break;
            }
          if (best_t == 0.)
            {
              std::ostringstream why_not;
              why_not << "line search failed: no step reduces |H| (a "
                         "stationary point of the merit function that is "
                         "not a solution; balanced residual "
                      << rec.balanced_residual << ", displacement-equation "
                      << "residual " << w_error << ")";
              result.diagnosis = why_not.str();
              result.history.push_back(rec);
              break;
            }
          rec.step = best_t;
          rec.note = accepted ? "" : "best-trial";
          result.history.push_back(rec);
          x = best;
          ++result.iterations;
        }
      finish(problem, x, result);
      // The pieces at the final iterate decide the status.
      evaluate(x, u, H, r_w, e, true);
      for (unsigned int c = 0; c < nc; ++c)
        result.status[c] = pieces[c].status;
      count_status(result);
      print_history(settings, result);
      return result;
    }



    PenaltySolver::PenaltySolver(const ContactSolverSettings &settings)
      : settings(settings)
    {}



    std::string
    PenaltySolver::name() const
    {
      return "penalty";
    }



    ContactSolverResult
    PenaltySolver::solve(const ContactProblem  &problem,
                         const Eigen::VectorXd &p0,
                         const Eigen::VectorXd &alpha0) const
    {
      Iterate x = starting_iterate(problem, p0, alpha0);
      Vec     k_n, k_t;
      penalty_stiffness(problem, settings, k_n, k_t);
      // Pure penalty: no normal multiplier; the tangential base is the
      // force at the end of the previous step (friction is incremental).
      Vec lambda = Vec::Zero(problem.n_rows());
      if (problem.p_previous.size() == problem.n_rows())
        for (unsigned int c = 0; c < problem.n_contacts; ++c)
          for (unsigned int k = 1; k < problem.n_components; ++k)
            lambda[c * problem.n_components + k] =
              problem.p_previous[c * problem.n_components + k];

      ContactSolverResult  result;
      const PenaltyOutcome outcome = penalty_newton(problem,
                                                    settings,
                                                    k_n,
                                                    k_t,
                                                    lambda,
                                                    "penalty",
                                                    x,
                                                    result);
      result.converged             = outcome.converged;
      std::ostringstream s;
      if (outcome.converged)
        s << "converged (penalty, FKN = " << settings.penalty.normal_factor
          << ")";
      else
        s << outcome.reason;
      result.diagnosis                  = s.str();
      std::vector<ContactStatus> status = result.status;
      finish(problem, x, result);
      result.status = status;
      count_status(result);
      print_history(settings.bnewton, result);
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
    AugmentedLagrangeSolver::solve(const ContactProblem  &problem,
                                   const Eigen::VectorXd &p0,
                                   const Eigen::VectorXd &alpha0) const
    {
      Iterate x = starting_iterate(problem, p0, alpha0);
      Vec     k_n, k_t;
      penalty_stiffness(problem, settings, k_n, k_t);
      // Multipliers start at the warm-start forces.
      Vec lambda = x.p;

      ContactSolverResult        result;
      std::vector<ContactStatus> status;
      const double               tol = settings.bnewton.tolerance;
      // The method of multipliers with penalty increase (Bertsekas; Nocedal
      // and Wright, Framework 17.3): when an update does not reduce the
      // residual by the factor 1/4, the penalty doubles, up to 1000 times
      // FKN. The contraction per update is about 1 / (1 + k lambda_min(W))
      // on the closed pairs, slow for a soft penalty.
      double       factor = 1., previous_error = 0.;
      const double max_factor = 1000.;
      for (unsigned int k = 0;; ++k)
        {
          const PenaltyOutcome outcome = penalty_newton(problem,
                                                        settings,
                                                        k_n,
                                                        k_t,
                                                        lambda,
                                                        "al-newton",
                                                        x,
                                                        result);
          status                       = result.status;
          if (!outcome.converged)
            {
              result.diagnosis = "augmented Lagrange update " +
                                 std::to_string(k) + ": " + outcome.reason;
              break;
            }
          const Vec    u   = relative_displacement(problem, x);
          const double err = relative_natural_map_error(problem, x.p, u);
          const double bal = balanced_natural_map_error(problem, x.p, u);
          double       absolute;
          const double eq = relative_equilibrium_error(problem, x.p, absolute);
          result.history.back().residual          = err;
          result.history.back().balanced_residual = bal;
          result.history.back().note = "update " + std::to_string(k);
          // The stopping test of the B-differentiable equations (with its
          // rounding-floor clause: a balanced residual 1000 times below the
          // tolerance).
          if (bal <= tol && (err <= tol || bal <= 1e-3 * tol) && eq <= tol)
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
      finish(problem, x, result);
      result.status = status;
      count_status(result);
      print_history(settings.bnewton, result);
      return result;
    }
  } // namespace contact
} // namespace igabde
