#include <igabde/contact/contact_problem.h>

#include <deal.II/base/exceptions.h>

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace igabde
{
  namespace contact
  {
    unsigned int
    ContactData::n_rows() const
    {
      return n_contacts * n_components;
    }



    unsigned int
    ContactData::n_alpha() const
    {
      return static_cast<unsigned int>(G.cols());
    }



    bool
    ContactData::has_friction() const
    {
      return n_components > 1;
    }



    void
    ContactData::check_consistency() const
    {
      // Built only when a check fails (AssertThrow evaluates its message
      // then): a solve of a few contacts takes microseconds.
      const auto where = [this]() {
        return "ContactProblem" +
               (name.empty() ? std::string() : " '" + name + "'");
      };
      AssertThrow(n_components >= 1 && n_components <= 3,
                  dealii::ExcMessage(where() +
                                     ": n_components must be 1, 2 or "
                                     "3, not " +
                                     std::to_string(n_components)));
      const Eigen::Index m = n_rows();
      AssertThrow(q.size() == m,
                  dealii::ExcMessage(where() + ": q must have " +
                                     std::to_string(m) + " entries, has " +
                                     std::to_string(q.size())));
      AssertThrow(q.allFinite(),
                  dealii::ExcMessage(where() + ": q has non-finite entries"));
      if (has_friction())
        {
          AssertThrow(mu.size() == n_contacts,
                      dealii::ExcMessage(
                        where() + ": mu must have one entry per contact (" +
                        std::to_string(n_contacts) + "), has " +
                        std::to_string(mu.size())));
          for (unsigned int i = 0; i < mu.size(); ++i)
            AssertThrow(std::isfinite(mu[i]) && mu[i] >= 0.,
                        dealii::ExcMessage(where() + ": mu[" +
                                           std::to_string(i) +
                                           "] must be finite and >= 0"));
        }
      else
        AssertThrow(mu.empty() || mu.size() == n_contacts,
                    dealii::ExcMessage(where() + ": mu has the wrong size"));
      if (G.size() > 0 || b.size() > 0)
        {
          AssertThrow(G.rows() == m,
                      dealii::ExcMessage(where() + ": G must have " +
                                         std::to_string(m) + " rows, has " +
                                         std::to_string(G.rows())));
          AssertThrow(b.size() == G.cols(),
                      dealii::ExcMessage(
                        where() + ": b must have one entry per column of G (" +
                        std::to_string(G.cols()) + "), has " +
                        std::to_string(b.size())));
          AssertThrow(G.allFinite() && b.allFinite(),
                      dealii::ExcMessage(where() +
                                         ": G or b has non-finite entries"));
        }
    }



    void
    ContactProblem::check_consistency() const
    {
      ContactData::check_consistency();
      // Built only when a check fails (AssertThrow evaluates its message
      // then): a solve of a few contacts takes microseconds.
      const auto where = [this]() {
        return "ContactProblem" +
               (name.empty() ? std::string() : " '" + name + "'");
      };
      const Eigen::Index m = n_rows();
      AssertThrow(W.rows() == m && W.cols() == m,
                  dealii::ExcMessage(
                    where() + ": W must be " + std::to_string(m) + " x " +
                    std::to_string(m) + ", is " + std::to_string(W.rows()) +
                    " x " + std::to_string(W.cols())));
      AssertThrow(W.allFinite(),
                  dealii::ExcMessage(where() + ": W has non-finite entries"));
    }



    Eigen::VectorXd
    ContactProblem::relative_displacement(const Eigen::VectorXd &p,
                                          const Eigen::VectorXd &alpha) const
    {
      AssertThrow(p.size() == static_cast<Eigen::Index>(n_rows()),
                  dealii::ExcMessage("relative_displacement: p has size " +
                                     std::to_string(p.size()) + ", expected " +
                                     std::to_string(n_rows())));
      Eigen::VectorXd u = W * p + q;
      if (n_alpha() > 0 && alpha.size() > 0)
        {
          AssertThrow(alpha.size() == static_cast<Eigen::Index>(n_alpha()),
                      dealii::ExcMessage(
                        "relative_displacement: alpha has the wrong size"));
          u += G * alpha;
        }
      return u;
    }



    ContactProblem
    ContactProblem::scaled(const double force_factor,
                           const double displacement_factor) const
    {
      AssertThrow(force_factor > 0. && displacement_factor > 0.,
                  dealii::ExcMessage("scaled: factors must be positive"));
      ContactProblem copy = *this;
      copy.W *= displacement_factor / force_factor;
      copy.q *= displacement_factor;
      copy.G *= displacement_factor;
      copy.b *= force_factor;
      return copy;
    }



    Eigen::VectorXd
    touching_alpha(const ContactData &problem)
    {
      const unsigned int n_alpha = problem.n_alpha();
      AssertThrow(n_alpha > 0,
                  dealii::ExcMessage(
                    "touching_alpha: the problem has no floating bodies"));
      Eigen::VectorXd       alpha = Eigen::VectorXd::Zero(n_alpha);
      const Eigen::VectorXd s     = -problem.b;
      // No load on the rigid modes (a body driven by prescribed
      // displacements whose free modes are unloaded): zero is the start.
      if (!(s.norm() > 0.))
        return alpha;

      const unsigned int     nc          = problem.n_components;
      const Eigen::VectorXd &u0          = problem.q; // u at p = 0, alpha = 0
      const Eigen::VectorXd  slope       = problem.G * s;
      const double           slope_scale = slope.cwiseAbs().maxCoeff();
      double                 t = std::numeric_limits<double>::infinity();
      for (unsigned int i = 0; i < problem.n_contacts; ++i)
        {
          const double g = slope[i * nc];
          if (g < -1e-14 * slope_scale)
            t = std::min(t, u0[i * nc] / (-g));
        }
      // No pair closes along the direction: zero is the start too.
      if (std::isfinite(t))
        alpha += t * s;
      return alpha;
    }



    bool
    resting_alpha(const ContactData         &problem,
                  Eigen::VectorXd           &alpha,
                  std::vector<unsigned int> &active)
    {
      using Mat             = Eigen::MatrixXd;
      using Vec             = Eigen::VectorXd;
      const unsigned int na = problem.n_alpha();
      const unsigned int nc = problem.n_components;
      const unsigned int n  = problem.n_contacts;
      AssertThrow(na > 0,
                  dealii::ExcMessage(
                    "resting_alpha: the problem has no floating bodies"));
      const Vec &b = problem.b;
      if (!(b.norm() > 0.) || n == 0)
        return false;
      Vec x = Vec::Zero(na);

      // Constraint rows a_i = G_n row i, values c_i = q_n + a_i^T x, bounds.
      Mat A(n, na);
      Vec c(n), lower(n), row_norm(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          A.row(i)    = problem.G.row(i * nc);
          row_norm(i) = A.row(i).norm();
        }
      c = A * x;
      for (unsigned int i = 0; i < n; ++i)
        {
          c(i) += problem.q(i * nc);
          lower(i) = std::min(0., c(i));
        }

      std::vector<unsigned int> set;
      std::vector<bool>         in_set(n, false);
      // A curved surface rolls over one pair per entering constraint
      // (observed: a half disc whose first touch is 136 pairs from its
      // rest position takes 272 iterations).
      const unsigned int limit = 50 + 10 * na + 2 * n;
      for (unsigned int it = 0; it < limit; ++it)
        {
          // The steepest descent of b^T alpha along the active constraints.
          Mat As(set.size(), na);
          for (unsigned int k = 0; k < set.size(); ++k)
            As.row(k) = A.row(set[k]);
          Vec d = -b;
          if (!set.empty())
            {
              const Eigen::HouseholderQR<Mat> qr(As.transpose());
              const Mat                       Q =
                qr.householderQ() *
                Mat::Identity(na, static_cast<Eigen::Index>(set.size()));
              d -= Q * (Q.transpose() * d);
            }
          if (d.norm() <= 1e-10 * b.norm())
            {
              // Nothing active and the descent negligible: b is not a load
              // the norms can measure (zero or overflowing).
              if (set.empty())
                return false;
              // b in the span of the active rows: the multipliers (the
              // rigid contact forces) decide.
              const Vec lambda = As.transpose().colPivHouseholderQr().solve(b);
              Eigen::Index k;
              const double smallest = lambda.minCoeff(&k);
              if (smallest >= -1e-10 * lambda.cwiseAbs().maxCoeff())
                {
                  alpha  = x;
                  active = set;
                  std::sort(active.begin(), active.end());
                  return x.allFinite();
                }
              in_set[set[k]] = false;
              set.erase(set.begin() + k);
              continue;
            }
          // The ratio test: the first pair that the move closes.
          const Vec    s      = A * d;
          double       t      = std::numeric_limits<double>::infinity();
          unsigned int enter  = n;
          const double d_norm = d.norm();
          for (unsigned int i = 0; i < n; ++i)
            if (!in_set[i] && s(i) < -1e-12 * row_norm(i) * d_norm)
              {
                const double ti = std::max(0., c(i) - lower(i)) / -s(i);
                if (ti < t)
                  {
                    t     = ti;
                    enter = i;
                  }
              }
          if (enter == n || set.size() >= na)
            return false; // unbounded: the normal rows do not hold b
          x += t * d;
          c += t * s;
          set.push_back(enter);
          in_set[enter] = true;
        }
      return false;
    }


  } // namespace contact
} // namespace igabde
