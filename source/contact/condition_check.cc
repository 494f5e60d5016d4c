#include <igabde/contact/condition_check.h>

#include <deal.II/base/exceptions.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace igabde
{
  namespace contact
  {
    namespace
    {
      std::string
      format(const double v)
      {
        std::ostringstream s;
        s << std::setprecision(5) << v;
        return s.str();
      }



      void
      update(ConditionViolation &cv,
             const double        violation,
             const unsigned int  contact,
             const std::string  &detail)
      {
        if (violation > cv.max_violation)
          {
            cv.max_violation = violation;
            cv.contact       = contact;
            cv.detail        = detail;
          }
      }
    } // namespace



    bool
    ConditionReport::passed() const
    {
      for (const ConditionViolation &cv : conditions)
        if (!(cv.max_violation <= tolerance))
          return false;
      return true;
    }



    std::string
    ConditionReport::first_violation() const
    {
      for (const ConditionViolation &cv : conditions)
        if (!(cv.max_violation <= tolerance))
          return cv.name + " violated at contact " +
                 std::to_string(cv.contact) + ": " + cv.detail +
                 " (scaled violation " + format(cv.max_violation) +
                 " > tolerance " + format(tolerance) + ")";
      return "all contact conditions hold";
    }



    std::string
    ConditionReport::describe() const
    {
      std::ostringstream s;
      s << "contact conditions (force scale " << format(force_scale)
        << ", displacement scale " << format(displacement_scale)
        << ", tolerance " << format(tolerance) << "):\n";
      for (const ConditionViolation &cv : conditions)
        s << "  " << std::left << std::setw(36) << cv.name << std::right
          << std::setw(12) << format(cv.max_violation)
          << (cv.max_violation <= tolerance ? "  ok" : "  VIOLATED") << '\n';
      return s.str();
    }



    ConditionReport
    check_contact_conditions(const ContactData     &problem,
                             const Eigen::VectorXd &p,
                             const Eigen::VectorXd &u,
                             const double           tolerance)
    {
      const unsigned int m = problem.n_rows(), d = problem.n_components;
      AssertThrow(p.size() == m && u.size() == m,
                  dealii::ExcMessage(
                    "check_contact_conditions: p and u must have " +
                    std::to_string(m) + " entries"));
      AssertThrow(tolerance >= 0.,
                  dealii::ExcMessage(
                    "check_contact_conditions: negative tolerance"));
      ConditionReport report;
      report.tolerance = tolerance;
      double F         = m > 0 ? p.cwiseAbs().maxCoeff() : 0.;
      if (!(F > 0.))
        F = 1.;
      double D = m > 0 ? problem.q.cwiseAbs().maxCoeff() : 0.;
      if (problem.displacement_scale > 0. && problem.n_contacts > 0)
        D = std::max(D,
                     problem.displacement_scale /
                       std::sqrt(double(problem.n_contacts)));
      if (!(D > 0.))
        D = m > 0 ? u.cwiseAbs().maxCoeff() : 0.;
      if (!(D > 0.))
        D = 1.;
      report.force_scale        = F;
      report.displacement_scale = D;

      ConditionViolation pen, comp, compl_, cone, slip, equil;
      pen.name    = "non-penetration u_n >= 0";
      comp.name   = "compression p_n >= 0";
      compl_.name = "complementarity p_n u_n = 0";
      cone.name   = "Coulomb cone |p_t| <= mu p_n";
      slip.name   = "slip direction p_t = -mu p_n u_t/|u_t|";
      equil.name  = "equilibrium G^T p = b";

      for (unsigned int c = 0; c < problem.n_contacts; ++c)
        {
          const unsigned int o  = c * d;
          const double       pn = p[o], un = u[o];
          const std::string  nvals =
            "p_n = " + format(pn) + ", u_n = " + format(un);
          update(pen, std::max(-un, 0.) / D, c, nvals);
          update(comp, std::max(-pn, 0.) / F, c, nvals);
          update(compl_,
                 std::min(std::abs(pn) / F, std::abs(un) / D),
                 c,
                 nvals);
          if (!std::isfinite(pn) || !std::isfinite(un))
            update(pen, std::numeric_limits<double>::infinity(), c, nvals);
          if (d == 1)
            continue;
          const double mu = problem.mu[c];
          double       pt = 0., ut = 0.;
          for (unsigned int k = 1; k < d; ++k)
            {
              pt += p[o + k] * p[o + k];
              ut += u[o + k] * u[o + k];
            }
          pt = std::sqrt(pt);
          ut = std::sqrt(ut);
          update(cone,
                 std::max(pt - mu * pn, 0.) / F,
                 c,
                 "|p_t| = " + format(pt) + ", mu p_n = " + format(mu * pn));
          // Where the pair slips: p_t = -mu p_n u_t/|u_t|. Measured, like
          // the complementarity, as the smaller of its force form
          // |p_t + mu p_n u_t/|u_t||/F and its displacement form
          // |u_t + |u_t| p_t/(mu p_n)|/D: the direction of a slip lost in
          // the rounding of u_t changes the answer by that slip only.
          // (mu p_n <= 0 leaves p_t = 0 to the cone condition.)
          if (ut > 0. && mu * pn > 0.)
            {
              double ef = 0., ed = 0.;
              for (unsigned int k = 1; k < d; ++k)
                {
                  const double fk = p[o + k] + mu * pn * u[o + k] / ut;
                  const double dk = u[o + k] + ut * p[o + k] / (mu * pn);
                  ef += fk * fk;
                  ed += dk * dk;
                }
              std::string pts = "p_t = (", uts = "u_t = (";
              for (unsigned int k = 1; k < d; ++k)
                {
                  pts += format(p[o + k]) + (k + 1 < d ? ", " : ")");
                  uts += format(u[o + k]) + (k + 1 < d ? ", " : ")");
                }
              update(slip,
                     std::min(std::sqrt(ef) / F, std::sqrt(ed) / D),
                     c,
                     pts + ", " + uts + ", mu p_n = " + format(mu * pn));
            }
        }
      report.conditions = {pen, comp, compl_};
      if (d > 1)
        {
          report.conditions.push_back(cone);
          report.conditions.push_back(slip);
        }
      if (problem.n_alpha() > 0)
        {
          const Eigen::VectorXd res = problem.G.transpose() * p - problem.b;
          const double          den = std::max(problem.b.cwiseAbs().maxCoeff(),
                                      F * problem.G.cwiseAbs().maxCoeff());
          Eigen::Index          j   = 0;
          const double          worst =
            res.size() > 0 ? res.cwiseAbs().maxCoeff(&j) : 0.;
          update(equil,
                 den > 0. ? worst / den : worst,
                 static_cast<unsigned int>(j),
                 "rigid mode " + std::to_string(j) +
                   ": G^T p - b = " + format(res.size() > 0 ? res[j] : 0.));
          report.conditions.push_back(equil);
        }
      return report;
    }

  } // namespace contact
} // namespace igabde
