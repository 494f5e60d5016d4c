// Unit tests of the damped B-Newton contact solver on hand-checkable
// problems.

#include <igabde/contact/bnewton.h>
#include <igabde/contact/condition_check.h>
#include <igabde/contact/contact_law.h>
#include <igabde/contact/contact_problem.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace igabde::contact;

namespace
{
  ContactProblem
  make_problem(const unsigned int         n_components,
               const Eigen::MatrixXd     &W,
               const Eigen::VectorXd     &q,
               const std::vector<double> &mu)
  {
    ContactProblem problem;
    problem.n_components = n_components;
    problem.n_contacts   = q.size() / n_components;
    problem.W            = W;
    problem.q            = q;
    problem.mu           = mu;
    return problem;
  }



  // A random symmetric positive definite flexibility with a dominant
  // diagonal, n_contacts pairs.
  Eigen::MatrixXd
  random_spd(const unsigned int n, const unsigned int seed)
  {
    std::mt19937                           gen(seed);
    std::uniform_real_distribution<double> dist(-1., 1.);
    Eigen::MatrixXd                        A(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        A(i, j) = dist(gen);
    return A * A.transpose() / n + Eigen::MatrixXd::Identity(n, n);
  }



  // A floating 3D body on one frictional support with all three
  // translations free (FloatingBody3DStick).
  ContactProblem
  floating_body_on_one_support()
  {
    ContactProblem problem;
    problem.n_components = 3;
    problem.n_contacts   = 1;
    problem.W            = Eigen::Matrix3d::Identity() * 0.01;
    problem.W(0, 1) = problem.W(1, 0) = 0.002;
    problem.q                         = Eigen::Vector3d(0.02, 0., 0.);
    problem.mu                        = {0.5};
    problem.G                         = Eigen::Matrix3d::Identity();
    problem.b                         = Eigen::Vector3d(50., 10., -5.);
    return problem;
  }



  // A floating body on two supports of the same springs, gaps 0.01 and
  // 0.03, pressed by 50 (FloatingBodyOnSpringsInSeries).
  ContactProblem
  floating_body_on_two_supports()
  {
    ContactProblem problem;
    problem.n_components = 1;
    problem.n_contacts   = 2;
    problem.W            = 0.0125 * Eigen::MatrixXd::Identity(2, 2);
    problem.q            = Eigen::Vector2d(0.01, 0.03);
    problem.G            = Eigen::MatrixXd::Ones(2, 1);
    problem.b            = Eigen::VectorXd::Constant(1, 50.);
    return problem;
  }



  /// Gaps of @p n_contacts 3D pairs: every third pair open (q_n = 0.2),
  /// the others pressed (q_n = -1), tangential parts of either sign.
  Eigen::VectorXd
  mixed_gaps(const unsigned int n_contacts)
  {
    Eigen::VectorXd q(3 * n_contacts);
    for (unsigned int k = 0; k < n_contacts; ++k)
      q.segment<3>(3 * k) << (k % 3 == 0 ? 0.2 : -1.), 0.4 * std::sin(1. + k),
        0.3 * std::cos(2. + k);
    return q;
  }



  /// The two ways the closed forms below are solved: the default (nonsmooth
  /// Gauss-Seidel sweeps first, which solve a one-pair problem outright)
  /// and Newton alone (the sweeps off), so that each closed form tests the
  /// B-Newton phases and not only the sweeps.
  std::vector<std::pair<std::string, BNewtonSolver::Settings>>
  sweeps_and_newton_only(BNewtonSolver::Settings settings = {})
  {
    BNewtonSolver::Settings newton_only   = settings;
    newton_only.gauss_seidel_first_sweeps = 0;
    return {{"sweeps first", settings}, {"Newton only", newton_only}};
  }



  /// Newton alone (@p settings without sweeps) took at least one
  /// iteration, every iteration was the first Newton phase's (with
  /// settings.radius) and took the Newton direction: the answer is
  /// Newton's, not a fallback's (which would hide a broken Newton rule).
  void
  expect_solved_by_first_newton_phase(const BNewtonSolver::Result   &result,
                                      const BNewtonSolver::Settings &settings)
  {
    const std::string phase =
      settings.radius == FrictionRadius::christensen_pang ? "newton-cp" :
                                                            "newton-ac";
    EXPECT_GE(result.iterations, 1u);
    EXPECT_EQ(result.sweeps, 0u);
    ASSERT_FALSE(result.history.empty());
    for (const auto &record : result.history)
      {
        EXPECT_EQ(record.phase, phase) << "iteration " << record.iteration;
        // The Newton direction taken, not the driver's steepest-descent
        // fallback (which reaches these well-conditioned answers too).
        EXPECT_EQ(record.note.find("gradient"), std::string::npos)
          << "iteration " << record.iteration << ": " << record.note;
      }
  }



  void
  expect_solution_ok(const ContactProblem        &problem,
                     const BNewtonSolver::Result &result)
  {
    EXPECT_TRUE(result.converged) << result.summary();
    EXPECT_LE(result.residual, 1e-10);
    const ConditionReport report =
      check_contact_conditions(problem, result.p, result.u, 1e-8);
    EXPECT_TRUE(report.passed()) << report.first_violation();
  }
} // namespace



// One 3D pair with a positive gap: p = 0, u = q, open.
TEST(ContactBNewton, SingleContactOpen)
{
  const ContactProblem problem = make_problem(3,
                                              Eigen::Matrix3d::Identity(),
                                              Eigen::Vector3d(1., 0.2, 0.),
                                              {0.5});
  for (const auto &[phases, settings] : sweeps_and_newton_only())
    {
      SCOPED_TRACE(phases);
      const BNewtonSolver::Result result =
        BNewtonSolver(settings).solve(problem);
      expect_solution_ok(problem, result);
      EXPECT_EQ(result.p.norm(), 0.);
      EXPECT_EQ(result.status[0], ContactStatus::open);
      EXPECT_EQ(result.n_open, 1u);
    }
}



// W = I, q = (-1, -0.1, 0), mu = 0.5. Normal: u_n = p_n - 1 = 0, p_n = 1.
// Stick: u_t = p_t + q_t = 0, p_t = (0.1, 0), |p_t| = 0.1 < mu p_n = 0.5.
// Newton alone starts at p = 0, where the pair is not solved: it iterates.
TEST(ContactBNewton, SingleContactStick)
{
  const ContactProblem problem = make_problem(3,
                                              Eigen::Matrix3d::Identity(),
                                              Eigen::Vector3d(-1., -0.1, 0.),
                                              {0.5});
  for (const auto &[phases, settings] : sweeps_and_newton_only())
    {
      SCOPED_TRACE(phases);
      const BNewtonSolver::Result result =
        BNewtonSolver(settings).solve(problem);
      expect_solution_ok(problem, result);
      EXPECT_NEAR(result.p[0], 1., 1e-12);
      EXPECT_NEAR(result.p[1], 0.1, 1e-12);
      EXPECT_NEAR(result.p[2], 0., 1e-12);
      EXPECT_EQ(result.status[0], ContactStatus::stick);
      if (settings.gauss_seidel_first_sweeps == 0)
        {
          expect_solved_by_first_newton_phase(result, settings);
        }
    }
}



// W = I, q = (-1, -0.8, -0.6), mu = 0.5: sticking would need |p_t| = 1 >
// 0.5, so the pair slips. p_n = 1 (uncoupled), p_t = mu p_n (0.8, 0.6) =
// (0.4, 0.3), u_t = p_t + q_t = (-0.4, -0.3) = -|u_t| p_t / |p_t|.
TEST(ContactBNewton, SingleContactSlip3D)
{
  const ContactProblem problem = make_problem(3,
                                              Eigen::Matrix3d::Identity(),
                                              Eigen::Vector3d(-1., -0.8, -0.6),
                                              {0.5});
  for (const FrictionRadius radius :
       {FrictionRadius::christensen_pang, FrictionRadius::alart_curnier})
    {
      BNewtonSolver::Settings with_radius;
      with_radius.radius = radius;
      for (const auto &[phases, settings] : sweeps_and_newton_only(with_radius))
        {
          SCOPED_TRACE(phases);
          const BNewtonSolver::Result result =
            BNewtonSolver(settings).solve(problem);
          expect_solution_ok(problem, result);
          EXPECT_NEAR(result.p[0], 1., 1e-12);
          EXPECT_NEAR(result.p[1], 0.4, 1e-12);
          EXPECT_NEAR(result.p[2], 0.3, 1e-12);
          EXPECT_NEAR(result.u[1], -0.4, 1e-12);
          EXPECT_EQ(result.status[0], ContactStatus::slip);
          if (settings.gauss_seidel_first_sweeps == 0)
            {
              expect_solved_by_first_newton_phase(result, settings);
            }
        }
    }
}



// 2D, coupled: W = [[2, 0.5], [0.5, 1]], q = (-2, -3), mu = 0.3. With slip
// and p_t = mu p_n: u_n = 2 p_n + 0.5 mu p_n - 2 = 0, p_n = 2/2.15;
// u_t = 0.5 p_n + mu p_n - 3 = -2.2558 < 0, opposite to p_t > 0.
TEST(ContactBNewton, SingleContactSlip2D)
{
  Eigen::Matrix2d W;
  W << 2., 0.5, 0.5, 1.;
  const ContactProblem problem =
    make_problem(2, W, Eigen::Vector2d(-2., -3.), {0.3});
  for (const auto &[phases, settings] : sweeps_and_newton_only())
    {
      SCOPED_TRACE(phases);
      const BNewtonSolver::Result result =
        BNewtonSolver(settings).solve(problem);
      expect_solution_ok(problem, result);
      const double pn = 2. / 2.15;
      EXPECT_NEAR(result.p[0], pn, 1e-12);
      EXPECT_NEAR(result.p[1], 0.3 * pn, 1e-12);
      EXPECT_NEAR(result.u[1], 0.8 * pn - 3., 1e-12);
      EXPECT_EQ(result.status[0], ContactStatus::slip);
      if (settings.gauss_seidel_first_sweeps == 0)
        {
          expect_solved_by_first_newton_phase(result, settings);
        }
    }
}



// Frictionless, two pairs, W = [[2, 1], [1, 2]]. q = (-1, 0.5): pair 0
// closes with 2 p_0 = 1, pair 1 stays open with u_1 = p_0 + 0.5 = 1.
// q = (-1, -1): both close, 3 p = 1.
TEST(ContactBNewton, FrictionlessNormalOnly)
{
  Eigen::Matrix2d W;
  W << 2., 1., 1., 2.;
  {
    const ContactProblem problem =
      make_problem(1, W, Eigen::Vector2d(-1., 0.5), {});
    for (const auto &[phases, settings] : sweeps_and_newton_only())
      {
        SCOPED_TRACE(phases);
        const BNewtonSolver::Result result =
          BNewtonSolver(settings).solve(problem);
        expect_solution_ok(problem, result);
        EXPECT_EQ(result.p.size(), 2);
        EXPECT_NEAR(result.p[0], 0.5, 1e-14);
        EXPECT_EQ(result.p[1], 0.);
        EXPECT_NEAR(result.u[1], 1., 1e-14);
        EXPECT_EQ(result.status[0], ContactStatus::closed);
        EXPECT_EQ(result.status[1], ContactStatus::open);
        if (settings.gauss_seidel_first_sweeps == 0)
          {
            expect_solved_by_first_newton_phase(result, settings);
          }
      }
  }
  {
    // Both closed: p* = (1/3, 1/3). Newton alone ends exactly on this
    // piecewise linear problem. The default solve tries Gauss-Seidel sweeps
    // first (Newton goes on from their iterate where they stop early), so
    // it is held to the tolerance only: FCLIB's error is |min(p, u)| / |q|
    // and near p* it is |W (p - p*)| / |q|, so |p - p*| <= tol |q| /
    // lambda_min(W) with lambda_min(W) = 1.
    const ContactProblem problem =
      make_problem(1, W, Eigen::Vector2d(-1., -1.), {});
    BNewtonSolver::Settings newton_only;
    newton_only.gauss_seidel_first_sweeps = 0;
    const BNewtonSolver::Result result =
      BNewtonSolver(newton_only).solve(problem);
    expect_solution_ok(problem, result);
    EXPECT_NEAR(result.p[0], 1. / 3., 1e-14);
    EXPECT_NEAR(result.p[1], 1. / 3., 1e-14);
    const BNewtonSolver::Result swept = BNewtonSolver().solve(problem);
    expect_solution_ok(problem, swept);
    EXPECT_LE((swept.p - Eigen::Vector2d(1. / 3., 1. / 3.)).norm(),
              newton_only.tolerance * problem.q.norm());
  }
}



// Grazing contacts: q_n = 0 gives the tie r u_n = p_n = 0 at p = 0 and the
// zero radius. The solution is p = 0 (with q_t = -0.1 the pair slides with
// zero force); the tie rules must not move it.
TEST(ContactBNewton, GrazingTies)
{
  for (const auto &[phases, settings] : sweeps_and_newton_only())
    {
      SCOPED_TRACE(phases);
      for (const double qt : {0., -0.1})
        {
          const ContactProblem problem =
            make_problem(3,
                         Eigen::Matrix3d::Identity(),
                         Eigen::Vector3d(0., qt, 0.),
                         {0.5});
          const BNewtonSolver::Result result =
            BNewtonSolver(settings).solve(problem, Eigen::VectorXd());
          EXPECT_TRUE(result.converged) << result.summary();
          EXPECT_EQ(result.p.norm(), 0.);
          EXPECT_EQ(result.status[0], ContactStatus::open);
          const ConditionReport report =
            check_contact_conditions(problem, result.p, result.u, 1e-8);
          EXPECT_TRUE(report.passed()) << report.first_violation();
        }
      // A grazing pair next to a closed one: W = I (3 pairs), pair 1
      // grazing. Newton alone iterates on the closed pair with the grazing
      // one tied at every iteration.
      Eigen::VectorXd q(9);
      q << -1., -0.3, 0.2, 0., 0., 0., 0.5, 0., 0.;
      const ContactProblem problem =
        make_problem(3, Eigen::MatrixXd::Identity(9, 9), q, {0.5, 0.5, 0.5});
      const BNewtonSolver::Result result =
        BNewtonSolver(settings).solve(problem);
      expect_solution_ok(problem, result);
      EXPECT_NEAR(result.p[0], 1., 1e-14);
      EXPECT_NEAR(result.p[1], 0.3, 1e-14);
      EXPECT_NEAR(result.p[2], -0.2, 1e-14);
      EXPECT_EQ(result.p.segment(3, 6).norm(), 0.);
      if (settings.gauss_seidel_first_sweeps == 0)
        {
          expect_solved_by_first_newton_phase(result, settings);
        }
    }
}



// High friction (mu = 2) on a coupled random problem with mixed states;
// the answer is checked by the natural map and the condition check, and
// both radii must reach it.
TEST(ContactBNewton, HighFriction)
{
  const unsigned int                     nc = 8;
  const Eigen::MatrixXd                  W  = random_spd(3 * nc, 7);
  std::mt19937                           gen(11);
  std::uniform_real_distribution<double> dist(-1., 1.);
  Eigen::VectorXd                        q(3 * nc);
  for (unsigned int i = 0; i < 3 * nc; ++i)
    q[i] = (i % 3 == 0) ? dist(gen) - 0.3 : 3. * dist(gen);
  const ContactProblem problem =
    make_problem(3, W, q, std::vector<double>(nc, 2.));
  for (const FrictionRadius radius :
       {FrictionRadius::christensen_pang, FrictionRadius::alart_curnier})
    {
      BNewtonSolver::Settings settings;
      settings.radius = radius;
      const BNewtonSolver::Result result =
        BNewtonSolver(settings).solve(problem);
      expect_solution_ok(problem, result);
      EXPECT_GT(result.n_open + result.n_stick + result.n_slip, 0u);
    }
}



// W and q scaled: force factor f and displacement factor d give p -> f p,
// u -> d u exactly (r is per contact, so the iterates scale too).
TEST(ContactBNewton, ScaledProblems)
{
  const unsigned int                     nc = 6;
  const Eigen::MatrixXd                  W  = random_spd(3 * nc, 3);
  std::mt19937                           gen(5);
  std::uniform_real_distribution<double> dist(-1., 1.);
  Eigen::VectorXd                        q(3 * nc);
  for (unsigned int i = 0; i < 3 * nc; ++i)
    q[i] = dist(gen);
  const ContactProblem problem =
    make_problem(3, W, q, std::vector<double>(nc, 0.3));
  const BNewtonSolver         solver;
  const BNewtonSolver::Result reference = solver.solve(problem);
  expect_solution_ok(problem, reference);
  for (const double f : {1e-6, 1., 1e6})
    for (const double dsp : {1e-6, 1e6})
      {
        const ContactProblem        scaled = problem.scaled(f, dsp);
        const BNewtonSolver::Result result = solver.solve(scaled);
        EXPECT_TRUE(result.converged) << result.summary();
        EXPECT_LE((result.p - f * reference.p).norm(),
                  1e-9 * f * reference.p.norm());
        EXPECT_LE((result.u - dsp * reference.u).norm(),
                  1e-9 * dsp * reference.u.norm());
        // The iterates scale exactly: the same balanced errors (a scale-
        // invariant measure) at every iteration of the reference. Only the
        // FCLIB part of the stopping test (not scale invariant) may ask for
        // more iterations: where it is out of reach (forces 1e6, W 1e-12
        // here) the driver stops when no step reduces |H| any more or
        // Newton has stopped converging quadratically, which rounding
        // decides, at the latest after its stall window.
        ASSERT_GE(result.history.size(), reference.iterations);
        for (unsigned int k = 0; k < reference.iterations; ++k)
          EXPECT_NEAR(result.history[k].balanced_residual,
                      reference.history[k].balanced_residual,
                      1e-6 * reference.history[k].balanced_residual)
            << "iteration " << k + 1 << ", f = " << f << ", dsp = " << dsp;
        EXPECT_LE(result.iterations,
                  reference.iterations +
                    solver.get_settings().stall_iterations);
        EXPECT_LE(result.balanced_residual, 1e-10);
        const ConditionReport report =
          check_contact_conditions(scaled, result.p, result.u, 1e-8);
        EXPECT_TRUE(report.passed()) << report.first_violation();
      }
}



// Warm start: from the solution, no iteration is needed; from a nearby
// point only a few.
TEST(ContactBNewton, WarmStart)
{
  const unsigned int                     nc = 5;
  const Eigen::MatrixXd                  W  = random_spd(3 * nc, 9);
  std::mt19937                           gen(2);
  std::uniform_real_distribution<double> dist(-1., 1.);
  Eigen::VectorXd                        q(3 * nc);
  for (unsigned int i = 0; i < 3 * nc; ++i)
    q[i] = dist(gen);
  const ContactProblem problem =
    make_problem(3, W, q, std::vector<double>(nc, 0.4));
  const BNewtonSolver         solver;
  const BNewtonSolver::Result cold = solver.solve(problem);
  expect_solution_ok(problem, cold);
  const BNewtonSolver::Result warm = solver.solve(problem, cold.p);
  EXPECT_TRUE(warm.converged);
  EXPECT_EQ(warm.iterations, 0u);
  // Next load step: q changes a little.
  ContactProblem next = problem;
  next.q *= 1.05;
  const BNewtonSolver::Result step = solver.solve(next, cold.p);
  expect_solution_ok(next, step);
  EXPECT_LE(step.iterations, cold.iterations + 1);
}



// A rigid circle of radius 1 over the plane, its pairs at
// x_i = -0.35 + 0.1 i (i = 0..7) with the exact gaps g_i = 1 - sqrt(1 - x_i^2),
// loaded by a unit vertical force along the line x = 0.12. Modes: a vertical
// translation and a small rotation theta about the point x = c, so
// u_i = g_i + t + theta (x_i - c) and b = (1, 0.12 - c). By hand: the circle
// rests on the two pairs that bracket the load line, x_a = 0.05 and
// x_b = 0.15 (g convex: every other pair lies above the chord through
// them), with theta = (g_a - g_b) / (x_b - x_a) and t + theta (x_a - c) =
// -g_a; their forces 0.3 and 0.7 balance the load. The rest position does
// not depend on where the rotation is taken (c = 0 or c = 0.3), unlike the
// first touch along -b; a load pulling the circle away has no rest.
TEST(ContactBNewton, RestingAlphaFindsTheRigidRestPositionByHand)
{
  for (const double c : {0., 0.3})
    {
      SCOPED_TRACE("rotation about x = " + std::to_string(c));
      ContactData problem;
      problem.n_components = 1;
      problem.n_contacts   = 8;
      problem.q.resize(8);
      problem.G.resize(8, 2);
      problem.mu.assign(8, 0.);
      for (unsigned int i = 0; i < 8; ++i)
        {
          const double x  = -0.35 + 0.1 * i;
          problem.q(i)    = 1. - std::sqrt(1. - x * x);
          problem.G(i, 0) = 1.;
          problem.G(i, 1) = x - c;
        }
      problem.b = Eigen::Vector2d(1., 0.12 - c);

      Eigen::VectorXd           alpha;
      std::vector<unsigned int> active;
      ASSERT_TRUE(resting_alpha(problem, alpha, active));
      EXPECT_EQ(active, (std::vector<unsigned int>{4, 5}));
      const double ga    = 1. - std::sqrt(1. - 0.05 * 0.05);
      const double gb    = 1. - std::sqrt(1. - 0.15 * 0.15);
      const double theta = (ga - gb) / 0.1;
      EXPECT_NEAR(alpha(1), theta, 1e-12);
      EXPECT_NEAR(alpha(0), -ga - theta * (0.05 - c), 1e-12);
      const Eigen::VectorXd u = problem.q + problem.G * alpha;
      EXPECT_GE(u.minCoeff(), -1e-14);

      problem.b            = Eigen::Vector2d(-1., 0.);
      Eigen::VectorXd away = alpha;
      EXPECT_FALSE(resting_alpha(problem, away, active));
      EXPECT_EQ(away, alpha);
    }
}



// A floating body pressed by the force b = 50 against two springs in
// series (k1 = 100 for the body, k2 = 400 for the support), initial gap
// g0 = 0.01, its rigid translation alpha along +n (opening). Flexibility
// W = 1/k1 + 1/k2 = 0.0125. Equilibrium G^T p = b with G = 1: p = 50.
// Contact u_n = W p + g0 + alpha = 0: alpha = -(0.625 + 0.01) = -0.635.
TEST(ContactBNewton, FloatingBodyOnSpringsInSeries)
{
  ContactProblem problem;
  problem.n_components = 1;
  problem.n_contacts   = 1;
  problem.W            = Eigen::MatrixXd::Constant(1, 1, 1. / 100. + 1. / 400.);
  problem.q            = Eigen::VectorXd::Constant(1, 0.01);
  problem.G            = Eigen::MatrixXd::Constant(1, 1, 1.);
  problem.b            = Eigen::VectorXd::Constant(1, 50.);
  const Eigen::VectorXd alpha0 = touching_alpha(problem);
  EXPECT_NEAR(alpha0[0], -0.01, 1e-15);
  const BNewtonSolver::Result result = BNewtonSolver().solve(problem);
  EXPECT_TRUE(result.converged) << result.summary();
  EXPECT_NEAR(result.p[0], 50., 1e-12);
  EXPECT_NEAR(result.alpha[0], -0.635, 1e-12);
  EXPECT_NEAR(result.u[0], 0., 1e-12);
  const ConditionReport report =
    check_contact_conditions(problem, result.p, result.u, 1e-10);
  EXPECT_TRUE(report.passed()) << report.first_violation();

  // The same body on two such supports (gaps 0.01 and 0.03, same springs),
  // alpha = vertical translation: the first support takes the load alone
  // while alpha > -0.03 - W p_2; with b = 50 the body sinks to
  // alpha = -0.635, so both touch: W p_1 + 0.01 + alpha = 0,
  // W p_2 + 0.03 + alpha = 0, p_1 + p_2 = 50. Then
  // p_1 - p_2 = 0.02 / W = 1.6, p_1 = 25.8, p_2 = 24.2,
  // alpha = -(0.0125 * 25.8 + 0.01) = -0.3325.
  const BNewtonSolver::Result r2 =
    BNewtonSolver().solve(floating_body_on_two_supports());
  EXPECT_TRUE(r2.converged) << r2.summary();
  EXPECT_NEAR(r2.p[0], 25.8, 1e-11);
  EXPECT_NEAR(r2.p[1], 24.2, 1e-11);
  EXPECT_NEAR(r2.alpha[0], -0.3325, 1e-12);
}



// A floating 3D body on one frictional support with all three
// translations free: p = b exactly, the pair sticks, alpha closes the
// relative displacement: alpha = -(W b + q).
TEST(ContactBNewton, FloatingBody3DStick)
{
  const ContactProblem        problem = floating_body_on_one_support();
  const BNewtonSolver::Result result  = BNewtonSolver().solve(problem);
  EXPECT_TRUE(result.converged) << result.summary();
  EXPECT_LE((result.p - problem.b).norm(), 1e-11);
  const Eigen::Vector3d expected_alpha = -(problem.W * problem.b + problem.q);
  EXPECT_LE((result.alpha - expected_alpha).norm(), 1e-12);
  EXPECT_EQ(result.status[0], ContactStatus::stick);
}



// Ill-posed problems must say so: (a) a floating body pulled away from its
// support (G^T p = b < 0 with p_n >= 0 has no solution); (b) W = 0 with a
// negative gap (u_n = q_n < 0 whatever p).
TEST(ContactBNewton, IllPosedReportsNotConverged)
{
  {
    ContactProblem problem;
    problem.n_components = 1;
    problem.n_contacts   = 1;
    problem.W            = Eigen::MatrixXd::Constant(1, 1, 0.01);
    problem.q            = Eigen::VectorXd::Constant(1, 0.01);
    problem.G            = Eigen::MatrixXd::Constant(1, 1, 1.);
    problem.b            = Eigen::VectorXd::Constant(1, -50.);
    const BNewtonSolver::Result result =
      BNewtonSolver().solve(problem,
                            Eigen::VectorXd(),
                            Eigen::VectorXd::Zero(1));
    EXPECT_FALSE(result.converged);
    EXPECT_FALSE(result.diagnosis.empty());
    EXPECT_NE(result.diagnosis.find("not converged"), std::string::npos)
      << result.diagnosis;
    EXPECT_TRUE(result.p.allFinite());
  }
  {
    ContactProblem problem;
    problem.n_components = 3;
    problem.n_contacts   = 2;
    problem.W            = Eigen::MatrixXd::Zero(6, 6);
    problem.q.setZero(6);
    problem.q[0] = -1.;
    problem.q[3] = -2.;
    problem.mu   = {0.3, 0.3};
    BNewtonSolver::Settings settings;
    settings.max_iterations            = 60;
    const BNewtonSolver::Result result = BNewtonSolver(settings).solve(problem);
    EXPECT_FALSE(result.converged);
    EXPECT_NE(result.diagnosis.find("not converged"), std::string::npos)
      << result.diagnosis;
    EXPECT_TRUE(result.p.allFinite());
    const ConditionReport report =
      check_contact_conditions(problem, result.p, result.u, 1e-6);
    EXPECT_FALSE(report.passed());
  }
}



// A problem of one contact is its own local problem: the first Gauss-Seidel
// sweep solves it exactly, without a Newton iteration, and gives Newton's
// answer (the same solver without the sweep), on a coupled W, in every
// state of the pair.
TEST(ContactBNewton, OneContactIsSolvedByOneSweep)
{
  const Eigen::MatrixXd W = random_spd(3, 11);
  // Each gap and load with the state it puts the pair in (mu = 0.5).
  const std::vector<std::pair<Eigen::Vector3d, ContactStatus>> cases = {
    {Eigen::Vector3d(-1., -0.8, -0.6), ContactStatus::slip},
    {Eigen::Vector3d(-1., -0.05, 0.02), ContactStatus::stick},
    {Eigen::Vector3d(0.5, -0.3, 0.1), ContactStatus::open}};
  for (const auto &[q, state] : cases)
    {
      SCOPED_TRACE("q = " + std::to_string(q[0]) + ", " + std::to_string(q[1]) +
                   ", " + std::to_string(q[2]));
      const ContactProblem        problem = make_problem(3, W, q, {0.5});
      const BNewtonSolver::Result swept   = BNewtonSolver().solve(problem);
      expect_solution_ok(problem, swept);
      EXPECT_EQ(swept.iterations, 0u);
      EXPECT_EQ(swept.sweeps, 1u);
      BNewtonSolver::Settings newton_only;
      newton_only.gauss_seidel_first_sweeps = 0;
      const BNewtonSolver::Result newton =
        BNewtonSolver(newton_only).solve(problem);
      expect_solution_ok(problem, newton);
      EXPECT_LE((swept.p - newton.p).norm(), 1e-10 * (1. + newton.p.norm()));
      EXPECT_EQ(swept.status[0], state);
      EXPECT_EQ(newton.status[0], state);
    }
}



// The history is printed with the column header and one line per
// iteration.
TEST(ContactBNewton, HistoryPrinting)
{
  const ContactProblem    problem = make_problem(3,
                                              Eigen::Matrix3d::Identity(),
                                              Eigen::Vector3d(-1., -0.8, -0.6),
                                              {0.5});
  std::ostringstream      log;
  BNewtonSolver::Settings settings;
  settings.log        = true;
  settings.log_stream = &log;
  // Newton's history: one contact is solved by a first Gauss-Seidel sweep
  // (its own local problem) without a Newton iteration.
  settings.gauss_seidel_first_sweeps = 0;
  const BNewtonSolver::Result result = BNewtonSolver(settings).solve(problem);
  EXPECT_TRUE(result.converged);
  // One line per iteration and a last one with the final residual.
  ASSERT_EQ(result.history.size(), result.iterations + 1);
  EXPECT_LE(result.history.back().residual, settings.tolerance);
  std::ostringstream out;
  result.print_history(out);
  EXPECT_NE(out.str().find("residual"), std::string::npos);
  EXPECT_NE(out.str().find("converged"), std::string::npos);
  EXPECT_NE(log.str().find("newton-cp"), std::string::npos);
}



// Bad input is rejected with a clear message.
TEST(ContactBNewton, BadInputThrows)
{
  ContactProblem problem =
    make_problem(3, Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 0, 0), {});
  EXPECT_ANY_THROW(BNewtonSolver().solve(problem));
  problem.mu = {-1.};
  EXPECT_ANY_THROW(BNewtonSolver().solve(problem));
  problem.mu = {0.3};
  EXPECT_NO_THROW(BNewtonSolver().solve(problem));
  EXPECT_ANY_THROW(BNewtonSolver().solve(problem, Eigen::VectorXd::Zero(2)));
}



namespace
{
  // A sparse symmetric positive definite flexibility in 3D: pairs on a
  // chain, each coupled with its two neighbours (block tridiagonal, as
  // the W of a stack of rigid bodies), plus a dominant diagonal.
  Eigen::MatrixXd
  chain_flexibility(const unsigned int nc, const unsigned int seed)
  {
    std::mt19937                           gen(seed);
    std::uniform_real_distribution<double> dist(-1., 1.);
    const unsigned int                     n = 3 * nc;
    Eigen::MatrixXd                        A = Eigen::MatrixXd::Zero(n, n);
    for (unsigned int c = 0; c < nc; ++c)
      for (unsigned int e = c; e < std::min(nc, c + 2); ++e)
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            A(3 * c + i, 3 * e + j) = dist(gen);
    return A * A.transpose() / 6. + Eigen::MatrixXd::Identity(n, n);
  }



  BNewtonSolver::Settings
  path_settings(const NewtonLinearAlgebra linear_algebra,
                const bool                use_symmetry)
  {
    BNewtonSolver::Settings settings;
    settings.linear_algebra = linear_algebra;
    settings.use_symmetry   = use_symmetry;
    return settings;
  }
} // namespace



// Every pair sticks at a force p* chosen strictly inside its cone, with
// q = -W p*: the exact solution is p = p*, u = 0, and the reduced Newton
// matrix is diag(r) W (the Cholesky path). Each storage and factorisation
// (dense/sparse, Cholesky/LU) must find p* to the conditioning of W.
TEST(ContactBNewton, LinearAlgebraPathsFindStickSolution)
{
  const unsigned int                     nc = 120;
  const Eigen::MatrixXd                  W  = chain_flexibility(nc, 7);
  std::mt19937                           gen(11);
  std::uniform_real_distribution<double> dist(-1., 1.);
  Eigen::VectorXd                        p_star(3 * nc);
  for (unsigned int c = 0; c < nc; ++c)
    {
      p_star[3 * c]     = 1. + 0.5 * dist(gen);
      p_star[3 * c + 1] = 0.1 * p_star[3 * c] * dist(gen);
      p_star[3 * c + 2] = 0.1 * p_star[3 * c] * dist(gen);
    }
  const Eigen::VectorXd q = -W * p_star;
  const ContactProblem  problem =
    make_problem(3, W, q, std::vector<double>(nc, 0.5));
  // 2-norm condition of W, from its eigenvalues.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(W);
  const double                                         cond =
    eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
  for (const auto la :
       {NewtonLinearAlgebra::dense, NewtonLinearAlgebra::sparse})
    for (const bool symmetric : {true, false})
      {
        SCOPED_TRACE(
          std::string(la == NewtonLinearAlgebra::dense ? "dense" : "sparse") +
          (symmetric ? ", Cholesky" : ", LU"));
        const BNewtonSolver::Result result =
          BNewtonSolver(path_settings(la, symmetric)).solve(problem);
        expect_solution_ok(problem, result);
        EXPECT_EQ(result.n_stick, nc);
        EXPECT_LE((result.p - p_star).norm(), 1e-12 * cond * p_star.norm());
      }
}



// A problem with open, stick and slip pairs: the four paths solve it and
// agree with each other (the solution of this strongly monotone problem,
// W positive definite and mu small, is unique).
TEST(ContactBNewton, LinearAlgebraPathsAgreeWithFriction)
{
  const unsigned int                     nc = 120;
  const Eigen::MatrixXd                  W  = chain_flexibility(nc, 3);
  std::mt19937                           gen(5);
  std::uniform_real_distribution<double> dist(-1., 1.);
  Eigen::VectorXd                        q(3 * nc);
  for (unsigned int i = 0; i < 3 * nc; ++i)
    q[i] = (i % 3 == 0 ? 1. : 0.1) * dist(gen);
  const ContactProblem problem =
    make_problem(3, W, q, std::vector<double>(nc, 0.3));
  const BNewtonSolver::Result reference =
    BNewtonSolver(path_settings(NewtonLinearAlgebra::dense, false))
      .solve(problem);
  expect_solution_ok(problem, reference);
  EXPECT_GT(reference.n_open, 0u);
  EXPECT_GT(reference.n_slip, 0u);
  EXPECT_GT(reference.n_stick, 0u);
  for (const auto la :
       {NewtonLinearAlgebra::dense, NewtonLinearAlgebra::sparse})
    for (const bool symmetric : {true, false})
      {
        const BNewtonSolver::Result result =
          BNewtonSolver(path_settings(la, symmetric)).solve(problem);
        expect_solution_ok(problem, result);
        EXPECT_LE((result.p - reference.p).norm(), 1e-8 * reference.p.norm());
      }
}



// A floating body on the sparse path: the equilibrium rows G^T p = b join
// the sparse LU. Two springs in series hold a body pressed by b, as in
// FloatingBodyOnSpringsInSeries, but with 300 further open pairs so that
// the automatic choice takes the sparse path; exact p = b on the closed
// pair, zero elsewhere.
TEST(ContactBNewton, SparsePathWithFloatingBody)
{
  const unsigned int nc  = 301;
  Eigen::MatrixXd    W   = Eigen::MatrixXd::Identity(nc, nc);
  W(0, 0)                = 2.;
  Eigen::VectorXd q      = Eigen::VectorXd::Constant(nc, 1.);
  q[0]                   = 0.5;
  ContactProblem problem = make_problem(1, W, q, {});
  problem.G              = Eigen::MatrixXd::Zero(nc, 1);
  problem.G(0, 0)        = -1.;
  problem.b              = Eigen::VectorXd::Constant(1, -3.);
  for (const auto la :
       {NewtonLinearAlgebra::automatic, NewtonLinearAlgebra::dense})
    {
      const BNewtonSolver::Result result =
        BNewtonSolver(path_settings(la, true)).solve(problem);
      expect_solution_ok(problem, result);
      ASSERT_EQ(result.alpha.size(), 1);
      EXPECT_NEAR(result.p[0], 3., 1e-12);
      EXPECT_NEAR(result.u[0], 0., 1e-12);
      // u_0 = 2 p_0 + 0.5 - alpha = 0
      EXPECT_NEAR(result.alpha[0], 6.5, 1e-12);
      EXPECT_EQ(result.p.tail(nc - 1).norm(), 0.);
    }
}



// A heap of rigid bodies: 80 contacts among 30 bodies, W = H H^T of rank
// 90 in 240 rows, sparse (contacts couple where they share a body). Every
// reduced Newton matrix is singular, so both storages take
// Levenberg-Marquardt steps, (K^T K + lambda I) d = K^T rhs: the dense one
// forms K^T K by BLAS (syrk), the sparse one column by column from K's
// compressed rows. The two are the same step, so the first iterations'
// residuals must agree to rounding (amplified by 1/lambda, at most 1e10 of
// max diag K^T K: 1e-5 relative), and both must solve the problem.
TEST(ContactBNewton, SparseAndDenseLevenbergMarquardtStepsAgree)
{
  const unsigned int                     nc = 80, n_bodies = 30;
  std::mt19937                           gen(3);
  std::uniform_real_distribution<double> dist(-1., 1.);
  std::uniform_int_distribution<int>     body(0, n_bodies - 1);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(3 * nc, 3 * n_bodies);
  for (unsigned int c = 0; c < nc; ++c)
    {
      const int b1 = c % n_bodies;
      int       b2 = body(gen);
      if (b2 == b1)
        b2 = (b1 + 1) % n_bodies;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            H(3 * c + i, 3 * b1 + j) = (i == j ? 1. : 0.) + 0.3 * dist(gen);
            H(3 * c + i, 3 * b2 + j) = -((i == j ? 1. : 0.) + 0.3 * dist(gen));
          }
    }
  const Eigen::MatrixXd W = H * H.transpose();
  Eigen::VectorXd       p_star(3 * nc);
  for (unsigned int c = 0; c < nc; ++c)
    {
      p_star[3 * c]     = 1. + 0.5 * dist(gen);
      p_star[3 * c + 1] = 0.2 * p_star[3 * c] * dist(gen);
      p_star[3 * c + 2] = 0.2 * p_star[3 * c] * dist(gen);
    }
  const ContactProblem problem =
    make_problem(3, W, -W * p_star, std::vector<double>(nc, 0.5));

  std::vector<BNewtonSolver::Result> results;
  for (const auto la :
       {NewtonLinearAlgebra::dense, NewtonLinearAlgebra::sparse})
    {
      BNewtonSolver::Settings settings = path_settings(la, false);
      settings.fclib_stopping          = true;
      results.push_back(BNewtonSolver(settings).solve(problem));
      const BNewtonSolver::Result &result = results.back();
      SCOPED_TRACE(la == NewtonLinearAlgebra::dense ? "dense" : "sparse");
      EXPECT_TRUE(result.converged) << result.summary();
      EXPECT_LE(relative_natural_map_error(problem, result.p, result.u), 1e-8);
      unsigned int lm_steps = 0;
      for (const auto &record : result.history)
        lm_steps += record.note.find("lm") != std::string::npos;
      EXPECT_GT(lm_steps, 0u) << "no Levenberg-Marquardt step taken";
    }
  const auto &dense = results[0].history, &sparse = results[1].history;
  ASSERT_GE(std::min(dense.size(), sparse.size()), 3u);
  for (unsigned int k = 1; k < 3; ++k)
    EXPECT_NEAR(sparse[k].residual, dense[k].residual, 1e-5 * dense[k].residual)
      << "iteration " << k;
}



// The answer's u, FCLIB error and pair counts are those of the answer p,
// whichever test accepted it: the first sweeps on a small W, Newton on a
// dense one (the accepting test's evaluation is reused for the answer).
// References written here: u = W p + q, and FCLIB's measure
// |p - P_K(p - (u + mu |u_t| e_n))| / |q| with the cone's projection in
// closed form.
TEST(ContactBNewton, TheAnswerIsMeasuredAtTheAnswer)
{
  const auto fclib_measure = [](const ContactProblem  &problem,
                                const Eigen::VectorXd &p,
                                const Eigen::VectorXd &u) {
    double sum = 0.;
    for (unsigned int c = 0; c < problem.n_contacts; ++c)
      {
        const double          mu = problem.mu[c];
        const Eigen::Vector3d pc = p.segment<3>(3 * c);
        const Eigen::Vector3d uc = u.segment<3>(3 * c);
        Eigen::Vector3d       z =
          pc - uc - mu * uc.tail<2>().norm() * Eigen::Vector3d::UnitX();
        const double zt = z.tail<2>().norm(), zn = z[0];
        if (zt <= mu * zn)
          ; // inside the cone
        else if (mu * zt <= -zn)
          z.setZero(); // inside the polar cone
        else
          {
            const double n = (zn + mu * zt) / (1. + mu * mu);
            z.tail<2>() *= mu * n / zt;
            z[0] = n;
          }
        sum += (pc - z).squaredNorm();
      }
    return std::sqrt(sum) / problem.q.norm();
  };

  struct Case
  {
    unsigned int n_contacts;
    double       coupling;
    const char  *accepted_by;
  };
  for (const Case &c :
       {Case{3, 0.05, "gauss-seidel first: converged"}, Case{20, 1., "newton"}})
    {
      SCOPED_TRACE(c.accepted_by);
      const unsigned int m = 3 * c.n_contacts;
      Eigen::MatrixXd    W =
        Eigen::MatrixXd::Identity(m, m) +
        c.coupling * (random_spd(m, 7) - Eigen::MatrixXd::Identity(m, m));
      const Eigen::VectorXd q = mixed_gaps(c.n_contacts);
      const ContactProblem  problem =
        make_problem(3, W, q, std::vector<double>(c.n_contacts, 0.3));
      BNewtonSolver::Settings settings;
      // A tolerance the answers' errors meet well above rounding, so that
      // measures of another iterate would show.
      settings.tolerance            = 1e-5;
      settings.fclib_stopping       = true;
      const BNewtonSolver::Result r = BNewtonSolver(settings).solve(problem);
      ASSERT_TRUE(r.converged) << r.diagnosis;
      EXPECT_NE(r.diagnosis.find(c.accepted_by), std::string::npos)
        << r.diagnosis;

      const Eigen::VectorXd u = W * r.p + q;
      EXPECT_LE((r.u - u).norm(), 1e-14 * (u.norm() + q.norm()));
      const double reference = fclib_measure(problem, r.p, u);
      EXPECT_NEAR(r.residual, reference, 1e-8 * reference + 1e-15);
      EXPECT_LE(r.residual, 1e-5);
      unsigned int open = 0;
      for (unsigned int k = 0; k < c.n_contacts; ++k)
        open += r.p[3 * k] == 0.;
      EXPECT_EQ(r.n_open, open);
      EXPECT_EQ(r.n_open + r.n_stick + r.n_slip + r.n_closed, c.n_contacts);
    }
}



// One solver object solves problems of different sizes in turn, with and
// without floating bodies and held directions, accepted by the first sweeps
// and by Newton: its workspace, kept between solves, holds storage only.
// Each answer meets its closed form where it has one (the floating bodies
// of the tests above), the contact conditions, and equals a fresh
// solver's.
TEST(ContactBNewton, OneSolverSolvesProblemsInTurn)
{
  const ContactProblem floating_3d  = floating_body_on_one_support();
  const ContactProblem two_supports = floating_body_on_two_supports();

  // Two pairs, the first's first tangential direction held by supports on
  // both sides (a zero row and column of W, no gap): p = 0 there.
  Eigen::MatrixXd held_W = random_spd(6, 5);
  held_W.row(1).setZero();
  held_W.col(1).setZero();
  Eigen::VectorXd held_q(6);
  held_q << -1., 0., 0.1, -0.5, 0.2, -0.1;
  const ContactProblem held = make_problem(3, held_W, held_q, {0.3, 0.3});

  const ContactProblem one_slip =
    make_problem(3, random_spd(3, 11), Eigen::Vector3d(-1., -0.8, -0.6), {0.5});

  const unsigned int   nc     = 20;
  const ContactProblem twenty = make_problem(3,
                                             random_spd(3 * nc, 7),
                                             mixed_gaps(nc),
                                             std::vector<double>(nc, 0.3));

  const auto same_as_fresh = [](const BNewtonSolver::Result &a,
                                const BNewtonSolver::Result &b) {
    EXPECT_EQ(a.converged, b.converged);
    EXPECT_EQ(a.status, b.status);
    ASSERT_EQ(a.p.size(), b.p.size());
    ASSERT_EQ(a.u.size(), b.u.size());
    ASSERT_EQ(a.alpha.size(), b.alpha.size());
    EXPECT_LE((a.p - b.p).norm(), 1e-12 * (1. + b.p.norm()));
    EXPECT_LE((a.u - b.u).norm(), 1e-12 * (1. + b.u.norm()));
    EXPECT_LE((a.alpha - b.alpha).norm(), 1e-12 * (1. + b.alpha.norm()));
  };
  const std::vector<const ContactProblem *> in_turn = {&floating_3d,
                                                       &held,
                                                       &one_slip,
                                                       &twenty,
                                                       &two_supports,
                                                       &one_slip,
                                                       &floating_3d};
  // With the first sweeps, and Newton alone.
  BNewtonSolver::Settings newton_only;
  newton_only.gauss_seidel_first_sweeps = 0;
  for (const BNewtonSolver::Settings &settings :
       {BNewtonSolver::Settings(), newton_only})
    {
      const BNewtonSolver shared(settings);
      for (const ContactProblem *problem : in_turn)
        {
          SCOPED_TRACE(std::to_string(problem->n_contacts) + " contacts, " +
                       std::to_string(problem->n_alpha()) +
                       " floating modes, " +
                       std::to_string(settings.gauss_seidel_first_sweeps) +
                       " first sweeps");
          const BNewtonSolver::Result r = shared.solve(*problem);
          if (problem->n_alpha() == 0)
            {
              expect_solution_ok(*problem, r);
            }
          else
            {
              EXPECT_TRUE(r.converged) << r.summary();
            }
          if (problem == &floating_3d)
            {
              EXPECT_LE((r.p - problem->b).norm(), 1e-11);
              EXPECT_LE((r.alpha + problem->W * problem->b + problem->q).norm(),
                        1e-12);
            }
          if (problem == &held)
            {
              EXPECT_EQ(r.p[1], 0.);
              // The held direction is out of the law (held_pair_directions()),
              // so Newton's matrix stays regular: left to the law, its stick
              // piece is a zero row, and the steps Levenberg-Marquardt's.
              EXPECT_TRUE(settings.gauss_seidel_first_sweeps > 0 ||
                          !r.history.empty());
              for (const ContactIterationRecord &rec : r.history)
                EXPECT_EQ(rec.note.find("lm"), std::string::npos)
                  << rec.iteration;
            }
          if (problem == &two_supports)
            {
              EXPECT_NEAR(r.p[0], 25.8, 1e-11);
              EXPECT_NEAR(r.p[1], 24.2, 1e-11);
              EXPECT_NEAR(r.alpha[0], -0.3325, 1e-12);
            }
          same_as_fresh(r, BNewtonSolver(settings).solve(*problem));
        }
    }
}
