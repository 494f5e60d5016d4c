#include <igabde/contact/bnewton.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <iomanip>
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
      using Mat = Eigen::MatrixXd;

      double
      equilibrium_error(const ContactProblem &problem,
                        const Vec            &p,
                        double               &absolute)
      {
        return relative_equilibrium_error(problem, p, absolute);
      }



      using Weights = PairWeights;
      using Branch  = PairPiece;



      // H(x) and the branches for one problem, one radius, one r.
      class System
      {
      public:
        System(const ContactProblem &problem,
               const Weights        &weights,
               const FrictionRadius  radius)
          : problem(problem)
          , w(weights)
          , radius(radius)
          , d(problem.n_components)
          , m(problem.n_rows())
          , na(problem.n_alpha())
        {}

        Vec
        displacement(const Vec &x) const
        {
          Vec u = problem.W * x.head(m) + problem.q;
          if (na > 0)
            u += problem.G * x.tail(na);
          return u;
        }

        // Fills H (size m + na); branches if non-null.
        void
        residual(const Vec           &x,
                 const Vec           &u,
                 Vec                 &H,
                 std::vector<Branch> *branches) const
        {
          H.resize(m + na);
          if (branches)
            branches->resize(problem.n_contacts);
          for (unsigned int c = 0; c < problem.n_contacts; ++c)
            {
              const unsigned int o = c * d;
              pair_law(d,
                       d > 1 ? problem.mu[c] : 0.,
                       w.r_n[c],
                       w.r_t[c],
                       radius,
                       x.data() + o,
                       u.data() + o,
                       H.data() + o,
                       branches ? &(*branches)[c] : nullptr);
            }
          if (na > 0)
            H.tail(na) = problem.G.transpose() * x.head(m) - problem.b;
        }

        // Floating-body tie rule: activate the closest contact if none is
        // closed (else the alpha columns of J vanish).
        void
        apply_floating_tie_rule(const Vec           &x,
                                const Vec           &u,
                                std::vector<Branch> &branches) const
        {
          if (na == 0 || problem.n_contacts == 0)
            return;
          for (const Branch &br : branches)
            if (br.closed)
              return;
          unsigned int best = 0;
          double       gap  = std::numeric_limits<double>::infinity();
          for (unsigned int c = 0; c < problem.n_contacts; ++c)
            {
              const double g = w.r_n[c] * u[c * d] - x[c * d];
              if (g < gap)
                {
                  gap  = g;
                  best = c;
                }
            }
          Branch &br = branches[best];
          br.closed  = true;
          br.A(0, 0) = w.r_n[best];
          br.B(0, 0) = 0.;
        }

        const ContactProblem &problem;
        const Weights        &w;
        const FrictionRadius  radius;
        const unsigned int    d, m, na;
      };



      // The Newton matrix in reduced form: trivial rows (d_i = -H_i) and
      // the dense rows J_N.
      struct ReducedJacobian
      {
        std::vector<int>  trivial, others;
        std::vector<char> is_trivial;
        Mat               JN; // others.size() x n

        Vec
        apply(const Vec &v) const
        {
          Vec out(v.size());
          for (const int i : trivial)
            out[i] = v[i];
          const Vec y = JN * v;
          for (unsigned int k = 0; k < others.size(); ++k)
            out[others[k]] = y[k];
          return out;
        }

        Vec
        apply_transpose(const Vec &h) const
        {
          Vec hN(others.size());
          for (unsigned int k = 0; k < others.size(); ++k)
            hN[k] = h[others[k]];
          Vec out = JN.transpose() * hN;
          for (const int i : trivial)
            out[i] += h[i];
          return out;
        }
      };



      ReducedJacobian
      build_jacobian(const System &sys, const std::vector<Branch> &branches)
      {
        const ContactProblem &pb = sys.problem;
        const unsigned int    d = sys.d, m = sys.m, na = sys.na, n = m + na;
        ReducedJacobian       J;
        J.is_trivial.assign(n, 0);
        for (unsigned int c = 0; c < pb.n_contacts; ++c)
          for (unsigned int k = 0; k < d; ++k)
            {
              const Branch &br      = branches[c];
              bool          trivial = br.B(k, k) == 1.;
              for (unsigned int l = 0; l < d && trivial; ++l)
                trivial = br.A(k, l) == 0. && (l == k || br.B(k, l) == 0.);
              J.is_trivial[c * d + k] = trivial;
            }
        for (unsigned int i = 0; i < n; ++i)
          (J.is_trivial[i] ? J.trivial : J.others).push_back(i);

        J.JN.setZero(J.others.size(), n);
        for (unsigned int r = 0; r < J.others.size(); ++r)
          {
            const unsigned int i = J.others[r];
            if (i < m)
              {
                const unsigned int c = i / d, k = i % d, o = c * d;
                const Branch      &br = branches[c];
                for (unsigned int l = 0; l < d; ++l)
                  {
                    const double a = br.A(k, l);
                    if (a != 0.)
                      {
                        J.JN.row(r).head(m) += a * pb.W.row(o + l);
                        if (na > 0)
                          J.JN.row(r).tail(na) += a * pb.G.row(o + l);
                      }
                    J.JN(r, o + l) += br.B(k, l);
                  }
              }
            else
              J.JN.row(r).head(m) = pb.G.col(i - m).transpose();
          }
        return J;
      }



      void
      count_status(const std::vector<Branch> &branches,
                   unsigned int              &n_open,
                   unsigned int              &n_stick,
                   unsigned int              &n_slip)
      {
        n_open = n_stick = n_slip = 0;
        for (const Branch &br : branches)
          switch (br.status)
            {
              case ContactStatus::open:
                ++n_open;
                break;
              case ContactStatus::stick:
                ++n_stick;
                break;
              case ContactStatus::slip:
                ++n_slip;
                break;
            }
      }



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



      // The stopping test (see the class documentation).
      bool
      stopping_test(const ContactProblem &problem,
                    const Vec            &x,
                    const Vec            &u,
                    const double          tolerance,
                    double               &err,
                    double               &balanced,
                    double               &eq_err,
                    const bool            at_rounding_floor)
      {
        const unsigned int m = problem.n_rows();
        err      = relative_natural_map_error(problem, x.head(m), u);
        balanced = balanced_natural_map_error(problem, x.head(m), u);
        double abs_eq;
        eq_err = equilibrium_error(problem, x.head(m), abs_eq);
        return balanced <= tolerance &&
               (err <= tolerance ||
                (at_rounding_floor && balanced <= 1e-3 * tolerance)) &&
               eq_err <= tolerance;
      }



      struct PhaseOutcome
      {
        bool        converged = false;
        std::string reason;
      };



      class Driver
      {
      public:
        Driver(const ContactProblem          &original,
               const BNewtonSolver::Settings &settings,
               BNewtonSolver::Result         &result)
          : original(original)
          , settings(settings)
          , result(result)
          , start(std::chrono::steady_clock::now())
          , m(original.n_rows())
          , na(original.n_alpha())
        {
          out = settings.log_stream ? settings.log_stream : &std::cout;
        }

        bool
        out_of_time() const
        {
          if (settings.max_wall_seconds <= 0.)
            return false;
          const double elapsed = std::chrono::duration<double>(
                                   std::chrono::steady_clock::now() - start)
                                   .count();
          return elapsed > settings.max_wall_seconds;
        }

        bool
        out_of_iterations() const
        {
          return result.iterations >= settings.max_iterations;
        }

        // Record x as a candidate for the returned iterate (original
        // problem only).
        void
        offer_best(const Vec &x, const double err, const double eq_err)
        {
          const double score = std::max(err, eq_err);
          if (!std::isfinite(score))
            return;
          if (!have_best || score < best_score)
            {
              have_best  = true;
              best_score = score;
              best_x     = x;
            }
        }

        PhaseOutcome
        newton(const ContactProblem &problem,
               const FrictionRadius  radius,
               Vec                  &x,
               const double          tolerance,
               const std::string    &phase,
               const bool            on_original,
               const unsigned int    budget);

        void
        log_record(const BNewtonSolver::IterationRecord &rec)
        {
          if (!settings.log)
            return;
          rec.print(*out);
        }

        const ContactProblem                 &original;
        const BNewtonSolver::Settings        &settings;
        BNewtonSolver::Result                &result;
        std::chrono::steady_clock::time_point start;
        const unsigned int                    m, na;
        std::ostream                         *out;
        bool                                  have_best  = false;
        double                                best_score = 0.;
        Vec                                   best_x;
        Vec                                   converged_x;
      };



      PhaseOutcome
      Driver::newton(const ContactProblem &problem,
                     const FrictionRadius  radius,
                     Vec                  &x,
                     const double          tolerance,
                     const std::string    &phase,
                     const bool            on_original,
                     const unsigned int    budget)
      {
        const Weights w = pair_weights(problem, settings.r_factor);
        const System  sys(problem, w, radius);
        const double  sigma = settings.armijo_sigma;
        const double  beta  = settings.armijo_beta;

        std::deque<double>  theta_memory;
        std::vector<Branch> branches;
        Vec                 H, H_trial;
        double              best_theta    = std::numeric_limits<double>::max();
        unsigned int        last_progress = 0;
        unsigned int        local_it      = 0;
        double              last_theta    = 0.;

        Vec u = sys.displacement(x);
        sys.residual(x, u, H, &branches);
        for (;;)
          {
            const double theta = 0.5 * H.squaredNorm();
            if (!std::isfinite(theta) || !x.allFinite())
              return {false, "non-finite values (NaN/inf) in H"};
            double err, balanced, eq_err;
            // The FCLIB error may be out of reach in floating point when
            // forces and displacements have very different scales: accept
            // the balanced error alone once Newton stops converging
            // quadratically (|H| decreased less than 2x in the last step).
            const bool at_floor = local_it > 0 && theta > 0.25 * last_theta;
            last_theta          = theta;
            const bool done     = stopping_test(problem,
                                            x,
                                            u,
                                            tolerance,
                                            err,
                                            balanced,
                                            eq_err,
                                            at_floor);
            if (on_original)
              offer_best(x, balanced, eq_err);

            BNewtonSolver::IterationRecord rec;
            rec.phase             = phase;
            rec.h_norm            = std::sqrt(2. * theta);
            rec.residual          = err;
            rec.balanced_residual = balanced;
            count_status(branches, rec.n_open, rec.n_stick, rec.n_slip);

            if (done)
              {
                if (on_original)
                  converged_x = x;
                return {true, "converged"};
              }
            if (local_it >= budget || out_of_iterations())
              return {false, "iteration limit"};
            if (out_of_time())
              return {false, "time limit"};
            if (theta < best_theta * (1. - 1e-3))
              {
                best_theta    = theta;
                last_progress = local_it;
              }
            else if (local_it - last_progress >= settings.stall_iterations)
              return {false,
                      "stall (no decrease of |H| in " +
                        std::to_string(settings.stall_iterations) +
                        " iterations)"};

            ++local_it;
            ++result.iterations;
            rec.iteration = result.iterations;

            // --- direction
            sys.apply_floating_tie_rule(x, u, branches);
            const ReducedJacobian J = build_jacobian(sys, branches);
            rec.n_reduced           = J.others.size();
            const unsigned int n    = x.size();
            Vec                dx(n);
            for (const int i : J.trivial)
              dx[i] = -H[i];
            if (!J.others.empty())
              {
                const unsigned int nN = J.others.size();
                Mat                K(nN, nN);
                Vec                rhs(nN);
                for (unsigned int a = 0; a < nN; ++a)
                  {
                    rhs[a] = -H[J.others[a]];
                    for (const int i : J.trivial)
                      rhs[a] -= J.JN(a, i) * dx[i];
                  }
                for (unsigned int b = 0; b < nN; ++b)
                  K.col(b) = J.JN.col(J.others[b]);
                Eigen::PartialPivLU<Mat> lu(K);
                Vec                      dN = lu.solve(rhs);
                const double             rc = lu.rcond();
                if (!(rc > 1e-14) || !dN.allFinite())
                  {
                    // Levenberg-Marquardt on the reduced system
                    const Mat    KtK = K.transpose() * K;
                    const double lm =
                      1e-10 * std::max(KtK.diagonal().maxCoeff(), 1e-300);
                    dN = (KtK + lm * Mat::Identity(nN, nN))
                           .ldlt()
                           .solve(K.transpose() * rhs);
                    rec.note += "lm ";
                  }
                for (unsigned int a = 0; a < nN; ++a)
                  dx[J.others[a]] = dN[a];
              }

            const Vec grad          = J.apply_transpose(H);
            double    slope         = grad.dot(J.apply(dx));
            bool      gradient_step = false;
            if (!dx.allFinite() || !(slope < -1e-8 * grad.norm() * dx.norm()))
              {
                dx            = -grad;
                slope         = -grad.squaredNorm();
                gradient_step = true;
                rec.note += "gradient ";
              }

            // --- line search (non-monotone Armijo)
            theta_memory.push_back(theta);
            while (theta_memory.size() >
                   std::max(1u, settings.nonmonotone_memory))
              theta_memory.pop_front();
            const double theta_ref =
              *std::max_element(theta_memory.begin(), theta_memory.end());

            bool   accepted = false;
            double step     = 0.;
            for (int attempt = 0; attempt < 2 && !accepted; ++attempt)
              {
                Vec du = problem.W * dx.head(m);
                if (na > 0)
                  du += problem.G * dx.tail(na);
                double t = 1., best_t = 0.,
                       best_trial = std::numeric_limits<double>::max();
                while (t >= settings.min_step)
                  {
                    const Vec xt = x + t * dx;
                    const Vec ut = u + t * du;
                    sys.residual(xt, ut, H_trial, nullptr);
                    const double th = 0.5 * H_trial.squaredNorm();
                    if (std::isfinite(th) && th < best_trial)
                      {
                        best_trial = th;
                        best_t     = t;
                      }
                    if (std::isfinite(th) &&
                        th <= theta_ref + sigma * t * slope)
                      {
                        accepted = true;
                        step     = t;
                        break;
                      }
                    t *= beta;
                  }
                if (!accepted && best_t > 0. && best_trial < theta)
                  {
                    accepted = true;
                    step     = best_t;
                    rec.note += "best-trial ";
                  }
                if (!accepted && !gradient_step)
                  {
                    dx            = -grad;
                    slope         = -grad.squaredNorm();
                    gradient_step = true;
                    rec.note += "gradient ";
                  }
                else
                  break;
              }
            rec.step = step;
            result.history.push_back(rec);
            log_record(rec);
            if (!accepted)
              return {false,
                      "line-search failure (no decrease along the "
                      "Newton and the steepest-descent directions)"};

            x += step * dx;
            u = sys.displacement(x);
            sys.residual(x, u, H, &branches);
          }
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
      const unsigned int m = problem.n_rows(), na = problem.n_alpha();
      AssertThrow(p0.size() == 0 || p0.size() == m,
                  dealii::ExcMessage("BNewtonSolver::solve: p0 has size " +
                                     std::to_string(p0.size()) + ", expected " +
                                     std::to_string(m)));
      AssertThrow(alpha0.size() == 0 || alpha0.size() == na,
                  dealii::ExcMessage("BNewtonSolver::solve: alpha0 has size " +
                                     std::to_string(alpha0.size()) +
                                     ", expected " + std::to_string(na)));
      Result result;
      Vec    x(m + na);
      x.head(m) = p0.size() > 0 ? p0 : Vec::Zero(m);
      if (na > 0)
        {
          if (alpha0.size() > 0)
            x.tail(na) = alpha0;
          else
            {
              // No pair closes along -b (e.g. b = 0): start from zero.
              try
                {
                  x.tail(na) = touching_alpha(problem);
                }
              catch (const std::exception &)
                {
                  x.tail(na).setZero();
                }
            }
        }

      Driver driver(problem, settings, result);
      if (settings.log)
        *driver.out
          << "B-Newton on " << (problem.name.empty() ? "problem" : problem.name)
          << ": " << problem.n_contacts << " contacts, " << problem.n_components
          << " components, " << na << " floating modes\n"
          << "   it     phase        |H|    residual    balanced        step"
             "  open stick  slip   red note\n";

      PhaseOutcome outcome;
      std::string  reasons;
      if (m + na == 0)
        outcome.converged = true;
      else
        {
          // Phase 1: Newton with the chosen radius.
          const FrictionRadius radius = settings.radius;
          Vec                  x1     = x;
          outcome                     = driver.newton(problem,
                                  radius,
                                  x1,
                                  settings.tolerance,
                                  phase_name("newton", radius),
                                  true,
                                  settings.max_iterations);
          reasons = phase_name("newton", radius) + ": " + outcome.reason;
          // Phase 2: the other radius, from the best iterate.
          if (!outcome.converged && problem.has_friction() &&
              settings.switch_radius && !driver.out_of_iterations() &&
              !driver.out_of_time())
            {
              Vec x2  = driver.have_best ? driver.best_x : x;
              outcome = driver.newton(problem,
                                      other(radius),
                                      x2,
                                      settings.tolerance,
                                      phase_name("newton", other(radius)),
                                      true,
                                      settings.max_iterations);
              reasons += "; " + phase_name("newton", other(radius)) + ": " +
                         outcome.reason;
            }
          // Phase 3: proximal point.
          if (!outcome.converged && settings.proximal &&
              !driver.out_of_iterations() && !driver.out_of_time())
            {
              Vec          xk = driver.have_best ? driver.best_x : x;
              const double max_diag =
                m > 0 ? std::max(problem.W.diagonal().maxCoeff(), 0.) : 0.;
              const double   eps_ref = max_diag > 0. ? max_diag : 1.;
              double         eps     = eps_ref;
              double         err    = driver.have_best ? driver.best_score : 1.;
              unsigned int   n_fail = 0;
              std::string    prox_reason = "iteration limit";
              ContactProblem sub         = problem;
              while (!driver.out_of_iterations() && !driver.out_of_time())
                {
                  sub.W = problem.W;
                  sub.W.diagonal().array() += eps;
                  sub.q                  = problem.q - eps * xk.head(m);
                  const double inner_tol = std::max(0.1 * settings.tolerance,
                                                    std::min(1e-6, 0.1 * err));
                  Vec          xi        = xk;
                  PhaseOutcome in        = driver.newton(sub,
                                                  radius,
                                                  xi,
                                                  inner_tol,
                                                  phase_name("prox", radius),
                                                  false,
                                                  50);
                  if (!in.converged && !driver.out_of_iterations())
                    {
                      xi = xk;
                      in = driver.newton(sub,
                                         other(radius),
                                         xi,
                                         inner_tol,
                                         phase_name("prox", other(radius)),
                                         false,
                                         50);
                    }
                  if (in.converged)
                    {
                      xk = xi;
                      const Vec uk =
                        problem.relative_displacement(xk.head(m), xk.tail(na));
                      double       e_fclib, e_bal, eq;
                      const bool   done = stopping_test(problem,
                                                      xk,
                                                      uk,
                                                      settings.tolerance,
                                                      e_fclib,
                                                      e_bal,
                                                      eq,
                                                      false);
                      const double e    = e_bal;
                      driver.offer_best(xk, e, eq);
                      if (done)
                        {
                          driver.converged_x = xk;
                          outcome.converged  = true;
                          prox_reason        = "converged";
                          break;
                        }
                      if (e < 0.5 * err)
                        eps = std::max(eps * 0.1, 1e-12 * eps_ref);
                      err    = std::min(err, e);
                      n_fail = 0;
                    }
                  else
                    {
                      eps *= 10.;
                      if (++n_fail > 6 || eps > 1e12 * eps_ref)
                        {
                          prox_reason =
                            "stall (inner solves fail: " + in.reason + ")";
                          break;
                        }
                    }
                }
              if (!outcome.converged)
                outcome.reason = prox_reason;
              reasons += "; proximal: " + prox_reason;
            }
        }

      // The returned iterate: the converged one, else the best one seen on
      // the original problem.
      Vec xr   = outcome.converged ? driver.converged_x :
                 driver.have_best  ? driver.best_x :
                                     x;
      result.p = xr.head(m);
      if (na > 0)
        result.alpha = xr.tail(na);
      result.u          = problem.relative_displacement(result.p, result.alpha);
      const bool strict = stopping_test(problem,
                                        xr,
                                        result.u,
                                        settings.tolerance,
                                        result.residual,
                                        result.balanced_residual,
                                        result.equilibrium_residual,
                                        false);
      result.converged  = (strict || outcome.converged) &&
                         result.p.allFinite() &&
                         result.balanced_residual <= settings.tolerance;
      if (result.converged)
        result.diagnosis = "converged (" + reasons + ")";
      else if (!result.p.allFinite() || !std::isfinite(result.residual))
        result.diagnosis = "non-finite result (" + reasons + ")";
      else
        result.diagnosis =
          "not converged: " + outcome.reason + " [" + reasons + "]";

      // Final per-contact status at (p, u), with the phase-1 radius.
      {
        const Weights       w = pair_weights(problem, settings.r_factor);
        const System        sys(problem, w, settings.radius);
        std::vector<Branch> branches;
        Vec                 H;
        if (m + na > 0)
          sys.residual(xr, result.u, H, &branches);
        result.status.clear();
        for (const Branch &br : branches)
          result.status.push_back(br.status);
        count_status(branches, result.n_open, result.n_stick, result.n_slip);
      }
      if (settings.log)
        *driver.out << result.summary() << '\n';
      return result;
    }

  } // namespace contact
} // namespace igabde
