// The per-pair law of the penalty methods (penalty_law) against hand-derived
// forces and tangents, and its tangent against central differences of the
// forces (a second, independent method).

#include <igabde/contact/contact_law.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace
{
  using namespace igabde::contact;

  // -dP/du by central differences (the law is piecewise linear or smooth
  // away from its kinks, so the difference is exact to rounding there).
  Eigen::Matrix3d
  finite_difference_tangent(const unsigned int d,
                            const double       mu,
                            const double       k_n,
                            const double       k_t,
                            const double      *lambda,
                            const double      *u)
  {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    const double    h = 1e-7;
    for (unsigned int j = 0; j < d; ++j)
      {
        std::array<double, 3> up{{u[0], d > 1 ? u[1] : 0., d > 2 ? u[2] : 0.}},
          um = up, pp, pm;
        up[j] += h;
        um[j] -= h;
        penalty_law(d, mu, k_n, k_t, lambda, up.data(), pp.data());
        penalty_law(d, mu, k_n, k_t, lambda, um.data(), pm.data());
        for (unsigned int i = 0; i < d; ++i)
          A(i, j) = -(pp[i] - pm[i]) / (2. * h);
      }
    return A;
  }
} // namespace



TEST(PenaltyLaw, OpenPairCarriesNothing)
{
  const double lambda[2] = {0., 0.3}, u[2] = {0.1, 0.02};
  double       p[2];
  const auto   piece = penalty_law(2, 0.5, 100., 50., lambda, u, p);
  EXPECT_EQ(piece.status, ContactStatus::open);
  EXPECT_FALSE(piece.closed);
  EXPECT_EQ(p[0], 0.);
  EXPECT_EQ(p[1], 0.);
  EXPECT_EQ(piece.A.norm(), 0.);
  EXPECT_EQ(piece.B, Eigen::Matrix3d::Identity());
}



TEST(PenaltyLaw, FrictionlessPenetration)
{
  // p_n = k_n * penetration = 100 * 0.01.
  const double lambda[1] = {0.}, u[1] = {-0.01};
  double       p[1];
  const auto   piece = penalty_law(1, 0., 100., 1., lambda, u, p);
  EXPECT_TRUE(piece.closed);
  EXPECT_NEAR(p[0], 1., 1e-14);
  EXPECT_EQ(piece.A(0, 0), 100.);
}



TEST(PenaltyLaw, AugmentedMultiplierHoldsAnOpenGap)
{
  // lambda_n = 2, gap 0.01, k_n = 100: p_n = 2 - 1 = 1 > 0, closed.
  const double lambda[1] = {2.}, u[1] = {0.01};
  double       p[1];
  const auto   piece = penalty_law(1, 0., 100., 1., lambda, u, p);
  EXPECT_TRUE(piece.closed);
  EXPECT_NEAR(p[0], 1., 1e-14);
}



TEST(PenaltyLaw, Stick2D)
{
  // p_n = 100 * 0.01 = 1; trial p_t = 0.1 - 50 * 0.001 = 0.05 <= 0.5 * 1.
  const double lambda[2] = {0., 0.1}, u[2] = {-0.01, 0.001};
  double       p[2];
  const auto   piece = penalty_law(2, 0.5, 100., 50., lambda, u, p);
  EXPECT_EQ(piece.status, ContactStatus::stick);
  EXPECT_NEAR(p[0], 1., 1e-14);
  EXPECT_NEAR(p[1], 0.05, 1e-14);
  EXPECT_EQ(piece.A(0, 0), 100.);
  EXPECT_EQ(piece.A(1, 1), 50.);
  EXPECT_EQ(piece.A(1, 0), 0.);
}



TEST(PenaltyLaw, Slip3DReturnMapping)
{
  // p_n = 10 * 0.1 = 1; trial p_t = -20 (0.03, -0.04) = (-0.6, 0.8), |.| = 1
  // > mu p_n = 0.3: p_t = 0.3 (-0.6, 0.8). Tangent: A_tn = mu k_n t =
  // (-1.8, 2.4); A_tt = k_t (R/|trial|) (I - t t^T) = 6 [[0.64, 0.48],
  // [0.48, 0.36]].
  const double lambda[3] = {0., 0., 0.}, u[3] = {-0.1, 0.03, -0.04};
  double       p[3];
  const auto   piece = penalty_law(3, 0.3, 10., 20., lambda, u, p);
  EXPECT_EQ(piece.status, ContactStatus::slip);
  EXPECT_NEAR(p[0], 1., 1e-14);
  EXPECT_NEAR(p[1], -0.18, 1e-14);
  EXPECT_NEAR(p[2], 0.24, 1e-14);
  Eigen::Matrix3d expected;
  expected << 10., 0., 0., -1.8, 3.84, 2.88, 2.4, 2.88, 2.16;
  EXPECT_LT((piece.A - expected).norm(), 1e-13);
}



TEST(PenaltyLaw, TangentMatchesCentralDifferences)
{
  // Points on every piece, in 2D and 3D, away from the kinks.
  struct Case
  {
    unsigned int          d;
    double                mu;
    std::array<double, 3> lambda, u;
  };
  const Case cases[] = {{2, 0.4, {{0., 0.2, 0.}}, {{-0.02, 0.001, 0.}}},
                        {2, 0.4, {{0., 0.2, 0.}}, {{-0.02, -0.03, 0.}}},
                        {3, 0.3, {{1., 0.1, -0.2}}, {{0.005, 0.01, 0.02}}},
                        {3, 0.3, {{0., 0.05, 0.}}, {{-0.01, 0.0001, 0.0002}}},
                        {3, 0.8, {{0.5, 0., 0.}}, {{0.005, 0.0, 0.0}}}};
  for (const Case &c : cases)
    {
      double     p[3];
      const auto piece =
        penalty_law(c.d, c.mu, 50., 30., c.lambda.data(), c.u.data(), p);
      const Eigen::Matrix3d fd = finite_difference_tangent(c.d,
                                                           c.mu,
                                                           50.,
                                                           30.,
                                                           c.lambda.data(),
                                                           c.u.data());
      EXPECT_LT(
        (piece.A.topLeftCorner(c.d, c.d) - fd.topLeftCorner(c.d, c.d)).norm(),
        1e-6 * (1. + fd.norm()))
        << "d = " << c.d << ", status " << to_string(piece.status);
      // Coulomb: the force lies in the cone.
      double pt = 0.;
      for (unsigned int k = 1; k < c.d; ++k)
        pt += p[k] * p[k];
      EXPECT_LE(std::sqrt(pt), c.mu * p[0] * (1. + 1e-14));
    }
}
