#ifndef igabde_contact_condition_check_h
#define igabde_contact_condition_check_h

#include <igabde/contact/contact_problem.h>

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief The worst violation of one contact condition.
     */
    struct ConditionViolation
    {
      /** @brief Name of the condition, e.g. "non-penetration u_n >= 0". */
      std::string name;
      /** @brief Largest scaled violation over all contacts (0 if none). */
      double max_violation = 0.;
      /** @brief Contact with the largest violation (-1 if none); for the
       * equilibrium condition the rigid mode. */
      int contact = -1;
      /** @brief Details (values at the worst contact) when violated. */
      std::string detail;
    };

    /**
     * @brief Result of check_contact_conditions().
     *
     * Scaling (so that a solution whose forces are scaled by s_f and whose
     * displacements are scaled by s_d passes or fails identically): forces
     * are divided by the force scale F = max_i |p_i| (1 if p = 0),
     * displacements by D = max_i |q_i| (max_i |u_i| if q = 0, 1 if both are
     * zero). The scaled violations of the conditions are
     *  - non-penetration: max(-u_n, 0) / D;
     *  - compression: max(-p_n, 0) / F;
     *  - complementarity: min(|p_n| / F, |u_n| / D);
     *  - Coulomb cone: max(|p_t| - mu p_n, 0) / F;
     *  - slip direction, where |u_t| > 0 and mu p_n > 0: the smaller of
     *    |p_t + mu p_n u_t / |u_t|| / F (p_t opposes the slip and lies on
     *    the cone boundary) and its displacement form
     *    |u_t + |u_t| p_t / (mu p_n)| / D (a slip lost in the rounding of
     *    u_t changes the answer by that slip only);
     *  - equilibrium of floating bodies: max |G^T p - b| / max(max|b|,
     *    F max|G|).
     * A condition fails when its violation exceeds the tolerance.
     */
    struct ConditionReport
    {
      /** @brief Tolerance used. */
      double tolerance = 0.;
      /** @brief Force scale F. */
      double force_scale = 1.;
      /** @brief Displacement scale D. */
      double displacement_scale = 1.;
      /** @brief One entry per condition, in the order listed above. */
      std::vector<ConditionViolation> conditions;

      /** @brief True if no condition exceeds the tolerance. */
      bool
      passed() const;

      /** @brief Human-readable description of the first violated condition
       * ("all contact conditions hold" if none). */
      std::string
      first_violation() const;

      /** @brief One line per condition with its worst violation. */
      std::string
      describe() const;
    };

    /**
     * @brief Check Signorini and Coulomb conditions on a computed (p, u).
     *
     * @param problem The problem (for mu, q, G, b and the layout).
     * @param p Contact forces, n_rows().
     * @param u Relative displacements, n_rows() (normally W p + q + G alpha;
     * passed separately so that any candidate can be checked).
     * @param tolerance Tolerance on the scaled violations (see
     * ConditionReport).
     */
    ConditionReport
    check_contact_conditions(const ContactData     &problem,
                             const Eigen::VectorXd &p,
                             const Eigen::VectorXd &u,
                             const double           tolerance = 1e-6);

  } // namespace contact
} // namespace igabde

#endif
