// The nonsmooth Gauss-Seidel phase: its exact local solver against hand-
// derived pairs (each branch of the 2D Coulomb law and the frictionless
// case), and the phase inside BNewtonSolver against the Newton answer of the
// same problem.

#include <igabde/contact/bnewton.h>
#include <igabde/contact/condition_check.h>
#include <igabde/contact/contact_problem.h>
#include <igabde/contact/gauss_seidel.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

using namespace igabde::contact;

namespace
{
  // u = A p + c of one 2D pair, and whether (p, u) obey the law: u_n >= 0,
  // p_n >= 0, u_n p_n = 0, |p_t| <= mu p_n, p_t = -mu p_n sign(u_t) where
  // u_t != 0.
  void
  expect_law(const double *A,
             const double *c,
             const double  mu,
             const double *p,
             const double  tol = 1e-12)
  {
    const double un = A[0] * p[0] + A[1] * p[1] + c[0];
    const double ut = A[2] * p[0] + A[3] * p[1] + c[1];
    EXPECT_GE(un, -tol);
    EXPECT_GE(p[0], -tol);
    EXPECT_NEAR(un * p[0], 0., tol);
    EXPECT_LE(std::abs(p[1]), mu * p[0] + tol);
    if (std::abs(ut) > tol)
      {
        EXPECT_NEAR(p[1], -mu * p[0] * (ut > 0. ? 1. : -1.), tol);
      }
  }
} // namespace



// A = [2 0.5; 0.5 1], mu = 0.5. Each c below is built from the answer:
//  - open: c_n = 0.1 >= 0, so p = 0;
//  - stick: p* = (1, 0.2), |0.2| <= 0.5, c = -A p* = (-2.1, -0.7);
//  - slip, u_t > 0: p* = (1, -0.5); c_n = -(2 - 0.25) = -1.75 gives u_n = 0,
//    c_t = 0.3 gives u_t = 0.5 - 0.5 + 0.3 = 0.3 > 0; the stick candidate
//    -A^-1 c = (0.914, -0.843) is outside the cone (0.843 > 0.457);
//  - slip, u_t < 0: p* = (1, 0.5); c_n = -(2 + 0.25) = -2.25 gives u_n = 0,
//    c_t = -1.3 gives u_t = 0.5 + 0.5 - 1.3 = -0.3 < 0.
// Each answer is also checked against the law itself (expect_law()).
TEST(ContactGaussSeidel, LocalPairSolvesEachBranchByHand)
{
  const double A[4] = {2., 0.5, 0.5, 1.};
  const double mu   = 0.5;
  double       p[2] = {7., 7.};

  const double open[2] = {0.1, 3.};
  ASSERT_TRUE(solve_local_pair(2, A, open, mu, p));
  EXPECT_EQ(p[0], 0.);
  EXPECT_EQ(p[1], 0.);

  const double stick[2] = {-2.1, -0.7};
  ASSERT_TRUE(solve_local_pair(2, A, stick, mu, p));
  EXPECT_NEAR(p[0], 1., 1e-14);
  EXPECT_NEAR(p[1], 0.2, 1e-14);
  expect_law(A, stick, mu, p);

  const double slip[2] = {-1.75, 0.3};
  ASSERT_TRUE(solve_local_pair(2, A, slip, mu, p));
  EXPECT_NEAR(p[0], 1., 1e-14);
  EXPECT_NEAR(p[1], -0.5, 1e-14);
  expect_law(A, slip, mu, p);

  const double back[2] = {-2.25, -1.3};
  ASSERT_TRUE(solve_local_pair(2, A, back, mu, p));
  EXPECT_NEAR(p[0], 1., 1e-14);
  EXPECT_NEAR(p[1], 0.5, 1e-14);
  expect_law(A, back, mu, p);

  // Frictionless: p = -c / A where c < 0.
  const double a1 = 3., c1 = -1.5;
  double       p1 = 0.;
  ASSERT_TRUE(solve_local_pair(1, &a1, &c1, 0., &p1));
  EXPECT_NEAR(p1, 0.5, 1e-15);

  // No branch holds for a pair whose normal flexibility is not positive.
  const double bad[4] = {-1., 0., 0., 1.};
  EXPECT_FALSE(solve_local_pair(2, bad, stick, mu, p));
}



// The 3D open and stick branches in closed form, on a non-symmetric A (each
// cofactor enters; A = W_ii is symmetric in use) with every entry distinct:
// A = [3 0.4 -0.2; 0.1 2 0.3; -0.5 0.2 1.5], mu = 0.5. Each c is built from
// the answer:
//  - stick: p* = (1, 0.2, -0.1), |p_t| = 0.224 <= 0.5, c = -A p*
//    = -(3.1, 0.47, -0.61);
//  - open: c_n = 0.2 >= 0, p = 0;
//  - slip: p* = (1, 0.6, 0) would be the stick solution of c = -A p*, but
//    |p_t| = 0.6 > 0.5: not this function's branch, p is left as it was;
//  - A of determinant -1 (a negative normal flexibility): refused.
TEST(ContactGaussSeidel, LocalPairOpenOrStickIn3DByHand)
{
  const double A[9] = {3., 0.4, -0.2, 0.1, 2., 0.3, -0.5, 0.2, 1.5};
  const double mu   = 0.5;
  double       p[3] = {7., 7., 7.};

  const double stick[3] = {-3.1, -0.47, 0.61};
  ASSERT_TRUE(solve_local_pair_open_or_stick(A, stick, mu, p));
  EXPECT_NEAR(p[0], 1., 1e-14);
  EXPECT_NEAR(p[1], 0.2, 1e-14);
  EXPECT_NEAR(p[2], -0.1, 1e-14);

  const double open[3] = {0.2, -1., 1.};
  ASSERT_TRUE(solve_local_pair_open_or_stick(A, open, mu, p));
  EXPECT_EQ(p[0], 0.);
  EXPECT_EQ(p[1], 0.);
  EXPECT_EQ(p[2], 0.);

  const double slip[3] = {-3.24, -1.3, 0.38};
  double       q[3]    = {7., 8., 9.};
  EXPECT_FALSE(solve_local_pair_open_or_stick(A, slip, mu, q));
  EXPECT_EQ(q[0], 7.);
  EXPECT_EQ(q[1], 8.);
  EXPECT_EQ(q[2], 9.);

  const double negative[9] = {-1., 0., 0., 0., 1., 0., 0., 0., 1.};
  EXPECT_FALSE(solve_local_pair_open_or_stick(negative, stick, mu, q));
}



// A 2D problem of 40 pairs (W = I + 0.5 B B^T / n with B uniform in
// [-1, 1]: symmetric, eigenvalues between 1 and about 1.7; half the pairs
// pressed in; mu = 0.3): BNewtonSolver with a budget of one Newton iteration
// fails its Newton phases and goes on to the Gauss-Seidel phase (before the
// proximal one, which finds no iteration left), which must converge to the
// tolerance and give the answer of the unrestricted Newton solve, an
// independent method. Both stop at a natural- map error of 1e-10 relative; with
// W this well conditioned and mu this small the solution is unique and the two
// answers can differ by a small multiple of that; 1e-7 relative leaves three
// orders of margin.
TEST(ContactGaussSeidel, PhaseGivesTheNewtonAnswerOnA2DProblem)
{
  const unsigned int                     nc = 40, n = 2 * nc;
  std::mt19937                           gen(7);
  std::uniform_real_distribution<double> dist(-1., 1.);
  Eigen::MatrixXd                        B(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      B(i, j) = dist(gen);
  ContactProblem problem;
  problem.n_components = 2;
  problem.n_contacts   = nc;
  problem.W = Eigen::MatrixXd::Identity(n, n) + 0.5 * B * B.transpose() / n;
  problem.q.resize(n);
  for (unsigned int i = 0; i < nc; ++i)
    {
      problem.q(2 * i)     = (i % 2 == 0 ? -1. : 0.2) + 0.1 * dist(gen);
      problem.q(2 * i + 1) = dist(gen);
    }
  problem.mu.assign(nc, 0.3);

  BNewtonSolver::Settings settings;
  settings.tolerance            = 1e-10;
  const BNewtonSolver::Result r = BNewtonSolver(settings).solve(problem);
  ASSERT_TRUE(r.converged) << r.diagnosis;

  settings.max_iterations       = 1;
  const BNewtonSolver::Result g = BNewtonSolver(settings).solve(problem);
  ASSERT_TRUE(g.converged) << g.diagnosis;
  EXPECT_NE(g.diagnosis.find("gauss-seidel: converged"), std::string::npos)
    << g.diagnosis;
  EXPECT_LE(g.residual, 1e-10);
  const ConditionReport report =
    check_contact_conditions(problem, g.p, g.u, 1e-8);
  EXPECT_TRUE(report.passed()) << report.first_violation();
  EXPECT_LE((g.p - r.p).norm(), 1e-7 * r.p.norm());

  // Without the phase the same budget fails: the phase is what solved it.
  settings.gauss_seidel_sweeps   = 0;
  const BNewtonSolver::Result no = BNewtonSolver(settings).solve(problem);
  EXPECT_FALSE(no.converged) << no.diagnosis;
}



namespace
{
  // solve_local_pair_law() on one 3D pair u = A p + c with the B-Newton's
  // own law (Christensen-Pang radius), from p = 0.
  std::array<double, 3>
  solve_3d_pair(const Eigen::Matrix3d &A,
                const Eigen::Vector3d &c,
                const double           mu,
                bool                  &solved)
  {
    ContactProblem problem;
    problem.n_components = 3;
    problem.n_contacts   = 1;
    problem.W            = A;
    problem.q            = c;
    problem.mu.assign(1, mu);
    const CondensedOperator op(problem.W);
    const BdeLaw            law(op.weights(problem, 1.),
                     op.weights(problem, 1.),
                     FrictionRadius::christensen_pang);
    std::array<double, 9>   a;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        a[3 * i + j] = A(i, j);
    std::array<double, 3> p = {{0., 0., 0.}};
    solved =
      solve_local_pair_law(law, problem, 0, a.data(), c.data(), p.data());
    return p;
  }

  // Coulomb's law at (p, u = A p + c): u_n >= 0, p_n >= 0, u_n p_n = 0,
  // |p_t| <= mu p_n, and p_t = -mu p_n u_t / |u_t| where u_t != 0.
  void
  expect_law_3d(const Eigen::Matrix3d       &A,
                const Eigen::Vector3d       &c,
                const double                 mu,
                const std::array<double, 3> &p_array,
                const double                 tol)
  {
    const Eigen::Vector3d p(p_array[0], p_array[1], p_array[2]);
    const Eigen::Vector3d u = A * p + c;
    EXPECT_GE(u[0], -tol);
    EXPECT_GE(p[0], -tol);
    EXPECT_NEAR(u[0] * p[0], 0., tol);
    EXPECT_LE(p.tail(2).norm(), mu * p[0] + tol);
    if (u.tail(2).norm() > tol)
      {
        const Eigen::Vector2d slip = -mu * p[0] * u.tail(2).normalized();
        EXPECT_NEAR(p[1], slip[0], tol);
        EXPECT_NEAR(p[2], slip[1], tol);
      }
  }
} // namespace



// The local 3D solver against hand-derived pairs, A = diag(2, 1, 1),
// mu = 0.5, each c built from its answer:
//  - open: c_n = 0.1 >= 0, so p = 0;
//  - stick: p* = (1, 0.2, -0.1), |p_t| = 0.22 <= 0.5, c = -A p*;
//  - slip: p* = (1, -0.3, -0.4) (|p_t| = mu p_n, against u_t = (0.3, 0.4)):
//    c_n = -2 gives u_n = 0, c_t = u_t - p_t = (0.6, 0.8); the stick
//    candidate -A^-1 c = (1, -0.6, -0.8) lies outside the cone.
// Then 200 random pairs (A = I + B B^T / 3 with B uniform in [-1, 1], c
// uniform in [-1, 1]^3, mu in [0.1, 1]) against the law's conditions, and
// the 2D branch of the solver against the exact 2D solver. The local
// Newton stops at rounding (1e-14 of the pair's terms); 1e-10 leaves
// margin for A's conditioning (eigenvalues between 1 and 3).
TEST(ContactGaussSeidel, LocalPairLawSolves3DPairs)
{
  const Eigen::Matrix3d A    = Eigen::Vector3d(2., 1., 1.).asDiagonal();
  const double          mu   = 0.5;
  bool                  done = false;

  const auto open = solve_3d_pair(A, Eigen::Vector3d(0.1, 3., -1.), mu, done);
  ASSERT_TRUE(done);
  EXPECT_EQ(open[0], 0.);
  EXPECT_EQ(open[1], 0.);
  EXPECT_EQ(open[2], 0.);

  const auto stick =
    solve_3d_pair(A, Eigen::Vector3d(-2., -0.2, 0.1), mu, done);
  ASSERT_TRUE(done);
  EXPECT_NEAR(stick[0], 1., 1e-13);
  EXPECT_NEAR(stick[1], 0.2, 1e-13);
  EXPECT_NEAR(stick[2], -0.1, 1e-13);

  const Eigen::Vector3d c_slip(-2., 0.6, 0.8);
  const auto            slip = solve_3d_pair(A, c_slip, mu, done);
  ASSERT_TRUE(done);
  EXPECT_NEAR(slip[0], 1., 1e-12);
  EXPECT_NEAR(slip[1], -0.3, 1e-12);
  EXPECT_NEAR(slip[2], -0.4, 1e-12);
  expect_law_3d(A, c_slip, mu, slip, 1e-12);

  std::mt19937                           gen(11);
  std::uniform_real_distribution<double> dist(-1., 1.);
  unsigned int                           n_solved = 0;
  for (unsigned int k = 0; k < 200; ++k)
    {
      Eigen::Matrix3d B;
      for (unsigned int i = 0; i < 9; ++i)
        B(i / 3, i % 3) = dist(gen);
      const Eigen::Matrix3d Ak =
        Eigen::Matrix3d::Identity() + B * B.transpose() / 3.;
      const Eigen::Vector3d ck(dist(gen), dist(gen), dist(gen));
      const double          muk = 0.55 + 0.45 * dist(gen);
      SCOPED_TRACE(k);
      const auto p = solve_3d_pair(Ak, ck, muk, done);
      if (!done)
        continue;
      ++n_solved;
      expect_law_3d(Ak, ck, muk, p, 1e-10);
    }
  // A local Newton may fail on a kink (the phase then keeps the pair's
  // old force); on well-conditioned pairs that is the exception.
  EXPECT_GE(n_solved, 190u);

  // 2D: the same law's branch against the exact solver (the first test's
  // pairs).
  ContactProblem problem;
  problem.n_components = 2;
  problem.n_contacts   = 1;
  problem.W.resize(2, 2);
  problem.W << 2., 0.5, 0.5, 1.;
  problem.q = Eigen::Vector2d(-1.75, 0.3);
  problem.mu.assign(1, 0.5);
  const CondensedOperator op(problem.W);
  const BdeLaw            law(op.weights(problem, 1.),
                   op.weights(problem, 1.),
                   FrictionRadius::christensen_pang);
  const double            A2[4] = {2., 0.5, 0.5, 1.};
  for (const Eigen::Vector2d &c2 : {Eigen::Vector2d(-2.1, -0.7),
                                    Eigen::Vector2d(-1.75, 0.3),
                                    Eigen::Vector2d(-2.25, -1.3),
                                    Eigen::Vector2d(0.1, 3.)})
    {
      double exact[2] = {0., 0.}, newton[2] = {0., 0.};
      ASSERT_TRUE(solve_local_pair(2, A2, c2.data(), 0.5, exact));
      ASSERT_TRUE(solve_local_pair_law(law, problem, 0, A2, c2.data(), newton));
      EXPECT_NEAR(newton[0], exact[0], 1e-13);
      EXPECT_NEAR(newton[1], exact[1], 1e-13);
    }
}



// Where each pair's local problem is solved in closed form (here
// frictionless), the Gauss-Seidel sweeps tried before Newton on a sparse W
// go on while their rate reaches the tolerance within
// Settings::gauss_seidel_first_sweeps_exact, and are measured only where
// that rate says the tolerance is near. The problem: W = tridiag(-a, 1, -a)
// with a = 0.45 on 60 frictionless contacts (5 % full, kept sparse), q =
// -W p* with p* > 0, so every contact is closed and p* is the one solution
// (W is positive definite). Gauss-Seidel on it is Gauss-Seidel on W p = -q
// while p stays positive, rate (2 a cos(pi / 61))^2 = 0.81 per sweep: about
// 90 sweeps to an FCLIB error of 1e-8, more than the ten sweeps of the 3D
// budget, far fewer than a thousand. The number of sweeps needed, k, is
// counted by a Gauss-Seidel loop written here; the phase stops at a check,
// and a check comes at most as many sweeps after the last as were done
// before it, so it ends between k and 2 k sweeps. FCLIB's error is
// |min(p, u)| / |q| here, and near p* it is |W (p - p*)| / |q|, so
// |p - p*| <= tol |q| / lambda_min(W), lambda_min = 1 - 2 a cos(pi / 61).
TEST(ContactGaussSeidel, FirstSweepsSolveAClosedFormProblemWithFewChecks)
{
  const unsigned int n = 60;
  const double       a = 0.45, tol = 1e-8;
  ContactProblem     problem;
  problem.n_components = 1;
  problem.n_contacts   = n;
  problem.W            = Eigen::MatrixXd::Identity(n, n);
  for (unsigned int i = 0; i + 1 < n; ++i)
    problem.W(i, i + 1) = problem.W(i + 1, i) = -a;
  Eigen::VectorXd p_exact(n);
  for (unsigned int i = 0; i < n; ++i)
    p_exact(i) = 1. + 0.5 * std::sin(1. + i);
  problem.q = -problem.W * p_exact;

  // Gauss-Seidel by hand: the sweeps until FCLIB's error is at most tol.
  unsigned int k = 0;
  {
    Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
    for (; k < 1000; ++k)
      {
        const Eigen::VectorXd u = problem.W * p + problem.q;
        if (u.cwiseMin(p).norm() <= tol * problem.q.norm())
          break;
        for (unsigned int i = 0; i < n; ++i)
          {
            double c = problem.q(i);
            for (unsigned int j = 0; j < n; ++j)
              if (j != i)
                c += problem.W(i, j) * p(j);
            p(i) = std::max(0., -c / problem.W(i, i));
          }
      }
  }
  ASSERT_GT(k, 10u);
  ASSERT_LT(k, 200u);

  BNewtonSolver::Settings settings;
  settings.tolerance      = tol;
  settings.fclib_stopping = true;
  settings.log            = true;
  std::ostringstream log;
  settings.log_stream           = &log;
  const BNewtonSolver::Result r = BNewtonSolver(settings).solve(problem);
  ASSERT_TRUE(r.converged) << r.diagnosis;
  EXPECT_EQ(r.iterations, 0u) << r.diagnosis;
  EXPECT_GE(r.sweeps + 1, k);
  EXPECT_LE(r.sweeps, 2 * k + 1);
  const double lambda_min = 1. - 2. * a * std::cos(M_PI / (n + 1));
  EXPECT_LE((r.p - p_exact).norm(),
            (1. + 1e-6) * tol * problem.q.norm() / lambda_min);

  // The checks: a handful, not one per sweep.
  unsigned int       checks = 0;
  std::istringstream lines(log.str());
  for (std::string line; std::getline(lines, line);)
    checks += line.find("nsgs sweep") != std::string::npos;
  EXPECT_GE(checks, 3u);
  EXPECT_LE(checks, k / 4) << log.str();
}
