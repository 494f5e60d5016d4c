// Unit tests of the post-solve contact condition check: a correct solution
// passes, each condition violated in turn is caught, and the result does
// not depend on the units.

#include <igabde/contact/condition_check.h>
#include <igabde/contact/contact_problem.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace igabde::contact;

namespace
{
  // Two 3D pairs, W = I, mu = 0.5. Pair 0: q = (-1, -0.8, -0.6) slips with
  // p = (1, 0.4, 0.3), u = (0, -0.4, -0.3). Pair 1: q = (0.5, 0.1, 0) is
  // open, p = 0, u = q.
  ContactProblem
  slip_problem()
  {
    ContactProblem problem;
    problem.n_components = 3;
    problem.n_contacts   = 2;
    problem.W            = Eigen::MatrixXd::Identity(6, 6);
    problem.q.resize(6);
    problem.q << -1., -0.8, -0.6, 0.5, 0.1, 0.;
    problem.mu = {0.5, 0.5};
    return problem;
  }

  Eigen::VectorXd
  exact_p()
  {
    Eigen::VectorXd p(6);
    p << 1., 0.4, 0.3, 0., 0., 0.;
    return p;
  }

  // Expect exactly the condition whose name starts with @p name to fail.
  void
  expect_only_violation(const ConditionReport &report,
                        const std::string     &name,
                        const int              contact)
  {
    EXPECT_FALSE(report.passed());
    bool found = false;
    for (const ConditionViolation &cv : report.conditions)
      if (cv.name.rfind(name, 0) == 0)
        {
          found = true;
          EXPECT_GT(cv.max_violation, report.tolerance) << cv.name;
          EXPECT_EQ(cv.contact, contact) << cv.name;
        }
    EXPECT_TRUE(found) << name;
    EXPECT_EQ(report.first_violation().rfind(name, 0), 0u)
      << report.first_violation();
  }
} // namespace



TEST(ContactConditionCheck, CorrectSolutionPasses)
{
  const ContactProblem  problem = slip_problem();
  const Eigen::VectorXd p       = exact_p();
  const Eigen::VectorXd u       = problem.relative_displacement(p);
  const ConditionReport report  = check_contact_conditions(problem, p, u);
  EXPECT_TRUE(report.passed()) << report.first_violation();
  EXPECT_EQ(report.first_violation(), "all contact conditions hold");
  EXPECT_EQ(report.conditions.size(), 5u);
  EXPECT_FALSE(report.describe().empty());
}



TEST(ContactConditionCheck, EachViolationIsCaught)
{
  const ContactProblem  problem = slip_problem();
  const Eigen::VectorXd p0      = exact_p();
  const Eigen::VectorXd u0      = problem.relative_displacement(p0);
  {
    // penetration at the open pair
    Eigen::VectorXd u = u0;
    u[3]              = -0.1;
    expect_only_violation(check_contact_conditions(problem, p0, u),
                          "non-penetration",
                          1);
  }
  {
    // tension at the open pair (cone also fails: |p_t| = 0 > mu p_n < 0 is
    // not counted, the cone needs |p_t| > mu p_n)
    Eigen::VectorXd p            = p0;
    p[3]                         = -0.2;
    const ConditionReport report = check_contact_conditions(problem, p, u0);
    EXPECT_FALSE(report.passed());
    EXPECT_EQ(report.first_violation().rfind("compression", 0), 0u)
      << report.first_violation();
  }
  {
    // force on an open pair: complementarity
    Eigen::VectorXd p = p0;
    p[3]              = 0.2;
    expect_only_violation(check_contact_conditions(problem, p, u0),
                          "complementarity",
                          1);
  }
  {
    // outside the cone: |p_t| = 1 > mu p_n = 0.5 (direction kept)
    Eigen::VectorXd p            = p0;
    p[1]                         = 0.8;
    p[2]                         = 0.6;
    const ConditionReport report = check_contact_conditions(problem, p, u0);
    EXPECT_FALSE(report.passed());
    EXPECT_EQ(report.first_violation().rfind("Coulomb cone", 0), 0u)
      << report.first_violation();
  }
  {
    // on the cone but not opposite to the slip
    Eigen::VectorXd p = p0;
    p[1]              = 0.3;
    p[2]              = 0.4;
    expect_only_violation(check_contact_conditions(problem, p, u0),
                          "slip direction",
                          0);
  }
  {
    // inside the cone while slipping
    Eigen::VectorXd p = p0;
    p[1]              = 0.2;
    p[2]              = 0.15;
    expect_only_violation(check_contact_conditions(problem, p, u0),
                          "slip direction",
                          0);
  }
  {
    // floating-body equilibrium
    ContactProblem floating = problem;
    floating.G              = Eigen::MatrixXd::Zero(6, 1);
    floating.G(0, 0)        = 1.;
    floating.b              = Eigen::VectorXd::Constant(1, 2.);
    expect_only_violation(check_contact_conditions(floating, p0, u0),
                          "equilibrium",
                          0);
    floating.b[0] = 1.;
    EXPECT_TRUE(check_contact_conditions(floating, p0, u0).passed());
  }
}



// Forces scaled by f and displacements by d: the same verdicts.
TEST(ContactConditionCheck, ScaleAware)
{
  const ContactProblem  problem = slip_problem();
  const Eigen::VectorXd p0      = exact_p();
  const Eigen::VectorXd u0      = problem.relative_displacement(p0);
  Eigen::VectorXd       p_bad   = p0;
  p_bad[1]                      = 0.3;
  p_bad[2]                      = 0.4;
  Eigen::VectorXd p_small       = p0; // tiny error, below tolerance
  p_small[1] += 1e-9;
  for (const double f : {1e-6, 1., 1e6})
    for (const double d : {1e-6, 1., 1e6})
      {
        const ContactProblem scaled = problem.scaled(f, d);
        EXPECT_TRUE(
          check_contact_conditions(scaled, f * p0, d * u0, 1e-6).passed());
        EXPECT_TRUE(
          check_contact_conditions(scaled, f * p_small, d * u0, 1e-6).passed());
        const ConditionReport bad =
          check_contact_conditions(scaled, f * p_bad, d * u0, 1e-6);
        EXPECT_FALSE(bad.passed());
        EXPECT_EQ(bad.first_violation().rfind("slip direction", 0), 0u);
      }
}



// The slip direction is measured, like the complementarity, as the smaller
// of its force and displacement forms: a slip turned 90 degrees from its
// force has force form |p_t + mu p_n u_t/|u_t||/F = |(0.7, -0.1)| = 0.707
// and displacement form |u_t + |u_t| p_t/(mu p_n)|/D = sqrt(2) s for a slip
// of length s (D = 1). A slip of 1e-9 whose direction is lost passes; the
// same mismatch on a slip of 1e-3 is reported, with the hand-derived size.
TEST(ContactConditionCheck, SlipDirectionWeightedByTheSlip)
{
  const ContactProblem  problem = slip_problem();
  const Eigen::VectorXd p0      = exact_p();
  for (const double s : {1e-9, 1e-3})
    {
      Eigen::VectorXd u = problem.relative_displacement(p0);
      u[1]              = 0.6 * s;
      u[2]              = -0.8 * s;
      const ConditionReport report =
        check_contact_conditions(problem, p0, u, 1e-6);
      double slip = -1.;
      for (const ConditionViolation &cv : report.conditions)
        if (cv.name.rfind("slip direction", 0) == 0)
          slip = cv.max_violation;
      EXPECT_NEAR(slip, std::sqrt(2.) * s, 1e-12 * s);
      EXPECT_EQ(report.passed(), s < 1e-6) << report.describe();
    }
}
