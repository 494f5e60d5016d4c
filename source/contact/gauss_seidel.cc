#include <igabde/contact/gauss_seidel.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace igabde
{
  namespace contact
  {
    bool
    solve_local_pair(const unsigned int n_components,
                     const double      *A,
                     const double      *c,
                     const double       mu,
                     double            *p)
    {
      if (c[0] >= 0.)
        {
          // Open: no force, the pair does not touch.
          for (unsigned int k = 0; k < n_components; ++k)
            p[k] = 0.;
          return true;
        }
      if (n_components == 1)
        {
          if (!(A[0] > 0.))
            return false;
          p[0] = -c[0] / A[0];
          return true;
        }
      const double a00 = A[0], a01 = A[1], a10 = A[2], a11 = A[3];
      // Stick: u = 0.
      const double det = a00 * a11 - a01 * a10;
      if (det > 0.)
        {
          const double pn = (-c[0] * a11 + c[1] * a01) / det;
          const double pt = (-c[1] * a00 + c[0] * a10) / det;
          if (pn >= 0. && std::abs(pt) <= mu * pn)
            {
              p[0] = pn;
              p[1] = pt;
              return true;
            }
        }
      // Slip with u_t in direction s: u_n = 0, p_t = -s mu p_n.
      for (const double s : {1., -1.})
        {
          const double d = a00 - s * mu * a01;
          if (!(d > 0.))
            continue;
          const double pn = -c[0] / d;
          const double ut = (a10 - s * mu * a11) * pn + c[1];
          if (pn >= 0. && s * ut >= 0.)
            {
              p[0] = pn;
              p[1] = -s * mu * pn;
              return true;
            }
        }
      return false;
    }



    PhaseOutcome
    gauss_seidel_phase(NewtonDriver          &driver,
                       const ContactData     &data,
                       const PairLawModel    &law,
                       const Eigen::MatrixXd &W,
                       ContactIterate        &x,
                       const unsigned int     max_sweeps,
                       unsigned int          &sweeps)
    {
      const unsigned int d = data.n_components;
      PhaseOutcome       outcome;
      outcome.reason    = "sweep limit (" + std::to_string(max_sweeps) + ")";
      sweeps            = 0;
      Eigen::VectorXd u = W * x.p + data.q;
      double          A[4], c[2], p_new[2];
      // The error at the last check, and the best one at the last mark (every
      // 100 sweeps).
      double       best         = std::numeric_limits<double>::infinity();
      double       best_at_mark = best;
      unsigned int mark         = 0;
      while (sweeps < max_sweeps)
        {
          for (unsigned int i = 0; i < data.n_contacts; ++i)
            {
              const unsigned int r = i * d;
              for (unsigned int a = 0; a < d; ++a)
                {
                  c[a] = u(r + a);
                  for (unsigned int b = 0; b < d; ++b)
                    {
                      A[a * d + b] = W(r + a, r + b);
                      c[a] -= W(r + a, r + b) * x.p(r + b);
                    }
                }
              const double mu = data.has_friction() ? data.mu[i] : 0.;
              if (!solve_local_pair(d, A, c, mu, p_new))
                continue;
              for (unsigned int b = 0; b < d; ++b)
                {
                  const double dp = p_new[b] - x.p(r + b);
                  if (dp != 0.)
                    {
                      u.noalias() += W.col(r + b) * dp;
                      x.p(r + b) = p_new[b];
                    }
                }
            }
          ++sweeps;
          if (sweeps % 10 != 0 && sweeps != max_sweeps)
            continue;
          // The error of the exact law, from u = W p + q recomputed by the
          // stopping test. The running u is not re-synchronised with it:
          // its updates' round-off grows by about one unit of W p per
          // sweep, 1e-13 relative after 2 000 sweeps, far below any
          // tolerance, and a second product with W would cost a tenth of
          // a sweep per check.
          double     err, balanced, eq, disp;
          const bool done = driver.stopping_test(data,
                                                 law,
                                                 x,
                                                 driver.settings.tolerance,
                                                 false,
                                                 err,
                                                 balanced,
                                                 eq,
                                                 disp);
          driver.offer_best(x, balanced, eq);
          if (driver.settings.log)
            driver.log() << "  nsgs sweep " << sweeps << ": error " << err
                         << ", balanced " << balanced << '\n';
          if (done)
            {
              driver.converged_x = x;
              outcome.converged  = true;
              outcome.reason =
                "converged in " + std::to_string(sweeps) + " sweeps";
              break;
            }
          if (!std::isfinite(balanced))
            {
              outcome.reason = "non-finite error";
              break;
            }
          best = std::min(best, balanced);
          if (sweeps - mark >= 100)
            {
              if (best > 0.5 * best_at_mark)
                {
                  outcome.reason = "stall (the error did not halve in 100 "
                                   "sweeps; " +
                                   std::to_string(sweeps) + " sweeps)";
                  break;
                }
              best_at_mark = best;
              mark         = sweeps;
            }
          if (driver.out_of_time())
            {
              outcome.reason = "time limit";
              break;
            }
        }
      return outcome;
    }
  } // namespace contact
} // namespace igabde
