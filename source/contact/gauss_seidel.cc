#include <igabde/contact/flexibility_structure.h>
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



    bool
    solve_local_pair_open_or_stick(const double *A,
                                   const double *c,
                                   const double  mu,
                                   double       *p)
    {
      if (c[0] >= 0.)
        {
          p[0] = p[1] = p[2] = 0.;
          return true;
        }
      // A p = -c by cofactors (A = W_ii, symmetric positive definite where
      // the pair moves its bodies).
      const double m00 = A[4] * A[8] - A[5] * A[7];
      const double m01 = A[2] * A[7] - A[1] * A[8];
      const double m02 = A[1] * A[5] - A[2] * A[4];
      const double det = A[0] * m00 + A[3] * m01 + A[6] * m02;
      if (!(det > 0.))
        return false;
      const double m10 = A[5] * A[6] - A[3] * A[8];
      const double m11 = A[0] * A[8] - A[2] * A[6];
      const double m12 = A[2] * A[3] - A[0] * A[5];
      const double m20 = A[3] * A[7] - A[4] * A[6];
      const double m21 = A[1] * A[6] - A[0] * A[7];
      const double m22 = A[0] * A[4] - A[1] * A[3];
      const double pn  = -(m00 * c[0] + m01 * c[1] + m02 * c[2]) / det;
      const double pt1 = -(m10 * c[0] + m11 * c[1] + m12 * c[2]) / det;
      const double pt2 = -(m20 * c[0] + m21 * c[1] + m22 * c[2]) / det;
      if (!(pn >= 0.) || !(std::hypot(pt1, pt2) <= mu * pn))
        return false;
      p[0] = pn;
      p[1] = pt1;
      p[2] = pt2;
      return true;
    }



    bool
    solve_local_pair_law(const PairLawModel &law,
                         const ContactData  &data,
                         const unsigned int  c,
                         const double       *A,
                         const double       *c_u,
                         double             *p)
    {
      const unsigned int d = data.n_components;
      Eigen::Vector3d    x = Eigen::Vector3d::Zero(), u, H, x_try, u_try, H_try;
      Eigen::Matrix3d    Aw = Eigen::Matrix3d::Identity();
      for (unsigned int a = 0; a < d; ++a)
        {
          x[a] = p[a];
          for (unsigned int b = 0; b < d; ++b)
            Aw(a, b) = A[a * d + b];
        }
      PairPiece  piece;
      const auto evaluate = [&](const Eigen::Vector3d &y,
                                Eigen::Vector3d       &uy,
                                Eigen::Vector3d       &Hy,
                                PairPiece             *py) {
        uy.setZero();
        Hy.setZero();
        for (unsigned int a = 0; a < d; ++a)
          {
            uy[a] = c_u[a];
            for (unsigned int b = 0; b < d; ++b)
              uy[a] += Aw(a, b) * y[b];
          }
        law.evaluate(data, c, y.data(), uy.data(), Hy.data(), py);
        return Hy.head(d).squaredNorm();
      };
      double theta = evaluate(x, u, H, &piece);
      // H is exactly 0 on a solution of the piecewise linear branches
      // (open, stick, closed) and to rounding on a slip one: stop at the
      // rounding of H's terms, forces (p, and A u with A = dH/du in force
      // per displacement), so that the test does not change when forces or
      // displacements are scaled.
      const auto small = [&](const double th) {
        const double scale = std::max(x.head(d).cwiseAbs().maxCoeff(),
                                      u.head(d).cwiseAbs().maxCoeff() *
                                        piece.A.cwiseAbs().maxCoeff());
        return std::sqrt(th) <= 1e-14 * scale;
      };
      for (unsigned int it = 0; it < 30; ++it)
        {
          if (theta == 0. || small(theta))
            {
              for (unsigned int a = 0; a < d; ++a)
                p[a] = x[a];
              return true;
            }
          Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
          J.topLeftCorner(d, d) =
            piece.A.topLeftCorner(d, d) * Aw.topLeftCorner(d, d) +
            piece.B.topLeftCorner(d, d);
          const Eigen::FullPivLU<Eigen::Matrix3d> lu(J);
          if (!lu.isInvertible())
            return false;
          Eigen::Vector3d rhs      = Eigen::Vector3d::Zero();
          rhs.head(d)              = -H.head(d);
          const Eigen::Vector3d dx = lu.solve(rhs);
          // Armijo backtracking on |H|^2.
          double    t = 1., theta_try = 0.;
          PairPiece piece_try;
          bool      accepted = false;
          for (unsigned int k = 0; k < 20 && !accepted; ++k, t *= 0.5)
            {
              x_try     = x + t * dx;
              theta_try = evaluate(x_try, u_try, H_try, &piece_try);
              accepted  = theta_try <= (1. - 1e-4 * t) * theta;
            }
          if (!accepted)
            return false;
          x     = x_try;
          u     = u_try;
          H     = H_try;
          piece = piece_try;
          theta = theta_try;
        }
      if (!small(theta))
        return false;
      for (unsigned int a = 0; a < d; ++a)
        p[a] = x[a];
      return true;
    }



    PhaseOutcome
    gauss_seidel_phase(NewtonDriver          &driver,
                       const ContactData     &data,
                       const PairLawModel    &law,
                       const Eigen::MatrixXd &W,
                       const Eigen::SparseMatrix<double, Eigen::RowMajor> *Ws,
                       ContactIterate                                     &x,
                       const GaussSeidelOptions &options,
                       unsigned int             &sweeps)
    {
      const unsigned int d          = data.n_components;
      const unsigned int max_sweeps = options.max_sweeps;
      PhaseOutcome       outcome;
      sweeps = 0;
      // With a dense W the running u = W p + q, updated by columns; with a
      // sparse W each pair's u is read from its rows when it is visited.
      Eigen::VectorXd u;
      if (Ws == nullptr &&
          W.rows() <= internal::FlexibilityStructure::tiny_rows)
        {
          u = internal::FlexibilityStructure::dense_times(W, x.p);
          u += data.q;
        }
      else if (Ws == nullptr)
        u = W * x.p + data.q;
      double A[9], c[3], p_new[3];
      // The error at the last check, and the best one at the last mark (every
      // 100 sweeps).
      double       best         = std::numeric_limits<double>::infinity();
      double       best_at_mark = best;
      unsigned int mark         = 0;
      double       last_wanted  = best;
      while (sweeps < max_sweeps)
        {
          for (unsigned int i = 0; i < data.n_contacts; ++i)
            {
              const unsigned int r = i * d;
              for (unsigned int a = 0; a < d; ++a)
                {
                  if (Ws == nullptr)
                    c[a] = u(r + a);
                  else
                    {
                      c[a] = data.q(r + a);
                      for (Eigen::SparseMatrix<double,
                                               Eigen::RowMajor>::InnerIterator
                             it(*Ws, r + a);
                           it;
                           ++it)
                        c[a] += it.value() * x.p(it.col());
                    }
                  for (unsigned int b = 0; b < d; ++b)
                    {
                      A[a * d + b] = W(r + a, r + b);
                      c[a] -= W(r + a, r + b) * x.p(r + b);
                    }
                }
              const double mu = data.has_friction() ? data.mu[i] : 0.;
              for (unsigned int b = 0; b < d; ++b)
                p_new[b] = x.p(r + b);
              const bool solved =
                d <= 2 ? solve_local_pair(d, A, c, mu, p_new) :
                         solve_local_pair_open_or_stick(A, c, mu, p_new) ||
                           solve_local_pair_law(law, data, i, A, c, p_new);
              if (!solved)
                continue;
              for (unsigned int b = 0; b < d; ++b)
                {
                  const double dp = p_new[b] - x.p(r + b);
                  if (dp != 0.)
                    {
                      if (Ws == nullptr)
                        u.noalias() += W.col(r + b) * dp;
                      x.p(r + b) = p_new[b];
                    }
                }
            }
          ++sweeps;
          if (sweeps % options.check_every != 0 && sweeps != max_sweeps)
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
          if (options.offer_best)
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
          // The error the stopping test asks for.
          const double wanted =
            driver.settings.fclib_stopping ? err : std::max(err, balanced);
          if (options.quit_when_too_slow && sweeps > options.check_every)
            {
              const double rate = wanted / last_wanted;
              if (!(rate < 1.) || wanted * std::pow(rate, max_sweeps - sweeps) >
                                    driver.settings.tolerance)
                {
                  outcome.reason = "too slow (the error fell by " +
                                   std::to_string(rate) + " per check)";
                  break;
                }
            }
          last_wanted = wanted;
          best        = std::min(best, balanced);
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
      // Every other end names its reason (the string only where the phase
      // ends: on a problem of one contact it is a part of the solve's time).
      if (outcome.reason.empty())
        outcome.reason = "sweep limit (" + std::to_string(max_sweeps) + ")";
      return outcome;
    }
  } // namespace contact
} // namespace igabde
