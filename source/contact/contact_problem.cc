#include <igabde/contact/contact_problem.h>

#include <deal.II/base/exceptions.h>

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
      const std::string where =
        "ContactProblem" + (name.empty() ? std::string() : " '" + name + "'");
      AssertThrow(n_components >= 1 && n_components <= 3,
                  dealii::ExcMessage(where +
                                     ": n_components must be 1, 2 or "
                                     "3, not " +
                                     std::to_string(n_components)));
      const Eigen::Index m = n_rows();
      AssertThrow(q.size() == m,
                  dealii::ExcMessage(where + ": q must have " +
                                     std::to_string(m) + " entries, has " +
                                     std::to_string(q.size())));
      AssertThrow(q.allFinite(),
                  dealii::ExcMessage(where + ": q has non-finite entries"));
      if (has_friction())
        {
          AssertThrow(mu.size() == n_contacts,
                      dealii::ExcMessage(
                        where + ": mu must have one entry per contact (" +
                        std::to_string(n_contacts) + "), has " +
                        std::to_string(mu.size())));
          for (unsigned int i = 0; i < mu.size(); ++i)
            AssertThrow(std::isfinite(mu[i]) && mu[i] >= 0.,
                        dealii::ExcMessage(where + ": mu[" + std::to_string(i) +
                                           "] must be finite and >= 0"));
        }
      else
        AssertThrow(mu.empty() || mu.size() == n_contacts,
                    dealii::ExcMessage(where + ": mu has the wrong size"));
      if (G.size() > 0 || b.size() > 0)
        {
          AssertThrow(G.rows() == m,
                      dealii::ExcMessage(where + ": G must have " +
                                         std::to_string(m) + " rows, has " +
                                         std::to_string(G.rows())));
          AssertThrow(b.size() == G.cols(),
                      dealii::ExcMessage(
                        where + ": b must have one entry per column of G (" +
                        std::to_string(G.cols()) + "), has " +
                        std::to_string(b.size())));
          AssertThrow(G.allFinite() && b.allFinite(),
                      dealii::ExcMessage(where +
                                         ": G or b has non-finite entries"));
        }
    }



    void
    ContactProblem::check_consistency() const
    {
      ContactData::check_consistency();
      const std::string where =
        "ContactProblem" + (name.empty() ? std::string() : " '" + name + "'");
      const Eigen::Index m = n_rows();
      AssertThrow(W.rows() == m && W.cols() == m,
                  dealii::ExcMessage(
                    where + ": W must be " + std::to_string(m) + " x " +
                    std::to_string(m) + ", is " + std::to_string(W.rows()) +
                    " x " + std::to_string(W.cols())));
      AssertThrow(W.allFinite(),
                  dealii::ExcMessage(where + ": W has non-finite entries"));
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
    ContactProblem::with_friction(const double new_mu) const
    {
      ContactProblem copy = *this;
      copy.mu.assign(n_contacts, new_mu);
      return copy;
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
    touching_alpha(const ContactData     &problem,
                   const Eigen::VectorXd &alpha0,
                   const Eigen::VectorXd &direction)
    {
      const unsigned int n_alpha = problem.n_alpha();
      AssertThrow(n_alpha > 0,
                  dealii::ExcMessage(
                    "touching_alpha: the problem has no floating bodies"));
      Eigen::VectorXd alpha =
        alpha0.size() > 0 ? alpha0 : Eigen::VectorXd::Zero(n_alpha);
      Eigen::VectorXd s = direction.size() > 0 ? direction : -problem.b;
      AssertThrow(alpha.size() == n_alpha && s.size() == n_alpha,
                  dealii::ExcMessage("touching_alpha: alpha0 or direction "
                                     "has the wrong size"));
      // No load on the rigid modes (a body driven by prescribed
      // displacements whose free modes are unloaded): alpha0 is the start.
      if (!(s.norm() > 0.))
        return alpha;

      const unsigned int    nc    = problem.n_components;
      const Eigen::VectorXd u0    = problem.q + problem.G * alpha; // u at p = 0
      const Eigen::VectorXd slope = problem.G * s;
      const double          slope_scale = slope.cwiseAbs().maxCoeff();
      double                t = std::numeric_limits<double>::infinity();
      for (unsigned int i = 0; i < problem.n_contacts; ++i)
        {
          const double g = slope[i * nc];
          if (g < -1e-14 * slope_scale)
            t = std::min(t, u0[i * nc] / (-g));
        }
      // No pair closes along the direction: alpha0 is the start too.
      if (std::isfinite(t))
        alpha += t * s;
      return alpha;
    }



  } // namespace contact
} // namespace igabde
