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
    namespace
    {
      // x = M^-1 b for a d x d matrix M (row-major, d <= 3) by cofactors
      // (the adjugate over the determinant); returns det M, x untouched
      // where it is 0.
      double
      solve_by_cofactors(const unsigned int d,
                         const double      *M,
                         const double      *b,
                         double            *x)
      {
        if (d == 1)
          {
            if (M[0] != 0.)
              x[0] = b[0] / M[0];
            return M[0];
          }
        if (d == 2)
          {
            const double det = M[0] * M[3] - M[1] * M[2];
            if (det != 0.)
              {
                x[0] = (M[3] * b[0] - M[1] * b[1]) / det;
                x[1] = (M[0] * b[1] - M[2] * b[0]) / det;
              }
            return det;
          }
        const double m00 = M[4] * M[8] - M[5] * M[7];
        const double m01 = M[2] * M[7] - M[1] * M[8];
        const double m02 = M[1] * M[5] - M[2] * M[4];
        const double det = M[0] * m00 + M[3] * m01 + M[6] * m02;
        if (det == 0.)
          return det;
        const double m10 = M[5] * M[6] - M[3] * M[8];
        const double m11 = M[0] * M[8] - M[2] * M[6];
        const double m12 = M[2] * M[3] - M[0] * M[5];
        const double m20 = M[3] * M[7] - M[4] * M[6];
        const double m21 = M[1] * M[6] - M[0] * M[7];
        const double m22 = M[0] * M[4] - M[1] * M[3];
        x[0]             = (m00 * b[0] + m01 * b[1] + m02 * b[2]) / det;
        x[1]             = (m10 * b[0] + m11 * b[1] + m12 * b[2]) / det;
        x[2]             = (m20 * b[0] + m21 * b[1] + m22 * b[2]) / det;
        return det;
      }
    } // namespace



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
      double y[3];
      if (!(solve_by_cofactors(3, A, c, y) > 0.))
        return false;
      const double pn = -y[0], pt1 = -y[1], pt2 = -y[2];
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
          // The step from J dx = -H, J = A_piece A + B_piece, by cofactors
          // (a tenth of a pivoted LU's cost at this size); J counts as
          // singular where |det J| is below 1e-14 of Hadamard's bound, the
          // product of its row norms.
          double J[9], rhs[3], step[3], bound = 1.;
          for (unsigned int a = 0; a < d; ++a)
            {
              double row = 0.;
              for (unsigned int b = 0; b < d; ++b)
                {
                  double sum = 0.;
                  for (unsigned int k = 0; k < d; ++k)
                    sum += piece.A(a, k) * Aw(k, b);
                  J[a * d + b] = sum + piece.B(a, b);
                  row += J[a * d + b] * J[a * d + b];
                }
              bound *= std::sqrt(row);
              rhs[a] = -H[a];
            }
          if (!(std::abs(solve_by_cofactors(d, J, rhs, step)) > 1e-14 * bound))
            return false;
          Eigen::Vector3d dx = Eigen::Vector3d::Zero();
          for (unsigned int a = 0; a < d; ++a)
            dx[a] = step[a];
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
      const unsigned int d           = data.n_components;
      const unsigned int max_sweeps  = options.max_sweeps;
      const bool         closed_form = local_problems_in_closed_form(data);
      PhaseOutcome       outcome;
      sweeps = 0;
      // With a dense W the running u = W p + q, updated by columns; with a
      // sparse W each pair's u is read from its rows when it is visited.
      // In the driver's workspace, as the two below.
      Eigen::VectorXd &u = driver.ws.sweep_u;
      if (Ws == nullptr &&
          W.rows() <= internal::FlexibilityStructure::tiny_rows)
        {
          u = internal::FlexibilityStructure::dense_times(W, x.p);
          u += data.q;
        }
      else if (Ws == nullptr)
        u = W * x.p + data.q;
      double A[9], c[3], p_new[3];
      // u = W p + q and the law's residual at a check (handed to the driver
      // with the answer they accept, which is then not evaluated again).
      Eigen::VectorXd &u_check = driver.ws.check_u;
      ContactIterate  &F_check = driver.ws.check_F;
      // The error at the last check, and the best one at the last mark (every
      // 100 sweeps).
      double       best         = std::numeric_limits<double>::infinity();
      double       best_at_mark = best;
      unsigned int mark         = 0;
      double       last_wanted  = best;
      // The sweep of the next check, and of the last one.
      unsigned int next_check = options.check_every;
      unsigned int last_check = 0;
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
                closed_form ? solve_local_pair(d, A, c, mu, p_new) :
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
          if (sweeps < next_check && sweeps != max_sweeps)
            continue;
          // The error of the exact law, from u = W p + q recomputed. The
          // running u is not re-synchronised with it: its updates'
          // round-off grows by about one unit of W p per sweep, 1e-13
          // relative after 2 000 sweeps, far below any tolerance.
          StopMeasures measures;
          driver.evaluate(data, law, x, u_check, F_check, nullptr);
          const bool   done = driver.stopping_test(data,
                                                 law,
                                                 x,
                                                 driver.settings.tolerance,
                                                 false,
                                                 measures,
                                                 &u_check,
                                                 &F_check);
          const double err = measures.err, balanced = measures.balanced;
          if (options.offer_best)
            driver.offer_best(x, measures);
          if (driver.settings.log)
            driver.log() << "  nsgs sweep " << sweeps << ": error " << err
                         << ", balanced " << balanced << '\n';
          if (done)
            {
              driver.accept(data,
                            law,
                            x,
                            std::move(u_check),
                            std::move(F_check),
                            measures);
              outcome.converged = true;
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
          next_check = sweeps + options.check_every;
          if (options.quit_when_too_slow && last_check > 0)
            {
              // The error's rate per sweep since the last check.
              const double rate =
                std::pow(wanted / last_wanted, 1. / (sweeps - last_check));
              if (!(rate < 1.) || wanted * std::pow(rate, max_sweeps - sweeps) >
                                    driver.settings.tolerance)
                {
                  outcome.reason = "too slow (the error fell by " +
                                   std::to_string(rate) + " per sweep)";
                  break;
                }
              // At this rate the tolerance is reached after this many more
              // sweeps: no check before (a check, a product with W and the
              // law's errors over every pair, costs more than a sweep).
              const double to_go = std::ceil(
                std::log(driver.settings.tolerance / wanted) / std::log(rate));
              // At most as many sweeps as done so far: the rate of the
              // first sweeps is often not kept (fast first sweeps, then a
              // slower linear rate), and a phase that will not reach the
              // tolerance is to end after a bounded share of its sweeps.
              if (to_go > options.check_every)
                next_check =
                  sweeps +
                  static_cast<unsigned int>(std::min(
                    {to_go, double(sweeps), double(max_sweeps - sweeps)}));
            }
          last_check  = sweeps;
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
