// The 3D Hertz check (postprocess::HertzPointCheck) on pair sets built from
// Hertz's closed form, so that every figure it reports has a known value:
// a = (3 P R / (4 E*))^(1/3), p(r) = p0 sqrt(1 - r^2/a^2),
// p0 = 3 P / (2 pi a^2) (Johnson, Contact Mechanics sec. 4.2).

#include <igabde/postprocess/contact_checks.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

// Named, not anonymous: the unity build puts several test files in one
// translation unit, where anonymous-namespace names (R, E, nu, ...) of
// different files would clash.
namespace hertz_point_test
{
  using namespace dealii;
  using igabde::contact::PairState;
  using igabde::postprocess::HertzPointCheck;

  const Tensor<1, 3> ex({1., 0., 0.}), ey({0., 1., 0.});

  HertzPointCheck
  check_for(const Point<3> &axis_point, const Tensor<1, 3> &axis_direction)
  {
    HertzPointCheck check;
    check.load              = 0.75;
    check.radius            = 1.;
    check.effective_modulus = 1000. / (2. * (1. - 0.09));
    check.axis_point        = axis_point;
    check.axis_direction    = axis_direction;
    return check;
  }

  /// Pairs at the centres of an n x n grid of squares of side h over
  /// [0, n h]^2 (a quarter model) or [-n h, n h]^2 (a full model), in the
  /// plane through @p origin spanned by @p e1, @p e2, each carrying Hertz's
  /// pressure at its centre times its area.
  std::vector<PairState<3>>
  grid_pairs(const HertzPointCheck &check,
             const unsigned int     n,
             const double           h,
             const bool             full,
             const Point<3>        &origin,
             const Tensor<1, 3>    &e1,
             const Tensor<1, 3>    &e2)
  {
    const double              a  = std::cbrt(3. * check.load * check.radius /
                               (4. * check.effective_modulus));
    const double              p0 = 3. * check.load / (2. * M_PI * a * a);
    std::vector<PairState<3>> pairs;
    const int                 first = (full ? -int(n) : 0);
    for (int i = first; i < int(n); ++i)
      for (int j = first; j < int(n); ++j)
        {
          const double x = (i + 0.5) * h, y = (j + 0.5) * h;
          const double r = std::hypot(x, y);
          PairState<3> pair;
          pair.location    = origin + x * e1 + y * e2;
          pair.area        = h * h;
          pair.force_local = {
            (r < a ? p0 * std::sqrt(1. - r * r / (a * a)) : 0.) * h * h};
          pairs.push_back(pair);
        }
    return pairs;
  }



  // Point values of Hertz's profile: the ellipse fit is exact (p^2 is linear
  // in r^2), the peak is the profile at the pair nearest the axis, and the
  // profile errors vanish; the moment estimate is a midpoint sum of
  // int p r^2 / int p, whose error is dominated by the square-root edge,
  // O((h/a)^(3/2)) relative: at h = a/100, 1e-3 times a constant of order
  // one, so 1 % is a safe bound and 1e-6 an impossible one.
  TEST(HertzPointCheck, PointValuesOfHertzGiveItsRadiusAndPeak)
  {
    const HertzPointCheck check =
      check_for(Point<3>(), Tensor<1, 3>({0., 0., 1.}));
    const double a     = std::cbrt(3. * 0.75 / (4. * check.effective_modulus));
    const double h     = a / 100.;
    const auto   pairs = grid_pairs(check, 150, h, false, Point<3>(), ex, ey);
    const auto   r     = check.evaluate(pairs);

    EXPECT_NEAR(r.contact_radius_exact, a, 1e-15);
    EXPECT_NEAR(r.contact_radius / a, 1., 1e-10);
    const double p0 = 3. * 0.75 / (2. * M_PI * a * a);
    EXPECT_NEAR(r.peak_pressure_exact / p0, 1., 1e-14);
    EXPECT_NEAR(r.peak_pressure / (p0 * std::sqrt(1. - 0.5 * h * h / (a * a))),
                1.,
                1e-12);
    EXPECT_LT(r.profile_l2_error, 1e-13);
    EXPECT_LT(r.max_pair_deviation, 1e-13);
    EXPECT_NEAR(r.contact_radius_moment / a, 1., 1e-2);
    EXPECT_GT(std::abs(r.contact_radius_moment / a - 1.), 1e-6);
    EXPECT_GT(r.n_fitted, 1000u);
    EXPECT_TRUE(r.warnings.empty());
  }



  // A quarter model and the whole contact give the same figures, in any
  // orientation of the axis: every figure is pointwise or a ratio of sums.
  TEST(HertzPointCheck, QuarterAndFullModelsAgreeInAnyOrientation)
  {
    const double a = std::cbrt(3. * 0.75 / (4. * 1000. / (2. * (1. - 0.09))));
    const double h = a / 20.;

    const HertzPointCheck upright =
      check_for(Point<3>(), Tensor<1, 3>({0., 0., 1.}));
    const auto quarter =
      upright.evaluate(grid_pairs(upright, 30, h, false, Point<3>(), ex, ey));

    // The whole contact, about an axis through (1, 2, 3) along (1, 1, 1).
    const Point<3>     origin(1., 2., 3.);
    const Tensor<1, 3> n(
      {1. / std::sqrt(3.), 1. / std::sqrt(3.), 1. / std::sqrt(3.)});
    const Tensor<1, 3>    e1({1. / std::sqrt(2.), -1. / std::sqrt(2.), 0.});
    const Tensor<1, 3>    e2     = cross_product_3d(n, e1);
    const HertzPointCheck tilted = check_for(origin, 2. * n);
    const auto            full =
      tilted.evaluate(grid_pairs(tilted, 30, h, true, origin, e1, e2));

    EXPECT_NEAR(full.contact_radius, quarter.contact_radius, 1e-12 * a);
    EXPECT_NEAR(full.contact_radius_moment,
                quarter.contact_radius_moment,
                1e-12 * a);
    EXPECT_NEAR(full.peak_pressure,
                quarter.peak_pressure,
                1e-12 * quarter.peak_pressure);
    EXPECT_NEAR(full.profile_l2_error, quarter.profile_l2_error, 1e-12);
    EXPECT_EQ(full.n_fitted, 4 * quarter.n_fitted);
    EXPECT_EQ(full.n_inner_pairs, 4 * quarter.n_inner_pairs);
  }



  // A profile that is not Hertz's is measured as such: pressures 10 % above
  // Hertz's everywhere give a peak 10 % high, the same radius (a scaled
  // ellipse has the same zero), and profile errors of 10 %.
  TEST(HertzPointCheck, ScaledProfileIsMeasuredAsScaled)
  {
    const HertzPointCheck check =
      check_for(Point<3>(), Tensor<1, 3>({0., 0., 1.}));
    const double a = check.evaluate({}).contact_radius_exact;
    auto pairs     = grid_pairs(check, 40, a / 25., false, Point<3>(), ex, ey);
    for (auto &pair : pairs)
      pair.force_local[0] *= 1.1;
    const auto r = check.evaluate(pairs);
    EXPECT_NEAR(r.contact_radius / a, 1., 1e-10);
    EXPECT_NEAR(r.profile_l2_error, 0.1, 1e-12);
    const double p_first = r.peak_pressure / 1.1;
    EXPECT_NEAR(r.max_pair_deviation,
                0.1 * p_first / r.peak_pressure_exact,
                1e-12);
  }



  // Too few pairs in the contact zone, or elements deeper than twice the
  // contact radius, are said: the figures then measure the mesh.
  TEST(HertzPointCheck, UnresolvedZoneAndDeepElementsAreSaid)
  {
    HertzPointCheck check = check_for(Point<3>(), Tensor<1, 3>({0., 0., 1.}));
    const double    a     = check.evaluate({}).contact_radius_exact;
    const auto      coarse =
      check.evaluate(grid_pairs(check, 4, 0.4 * a, false, Point<3>(), ex, ey));
    ASSERT_EQ(coarse.warnings.size(), 1u);
    EXPECT_NE(coarse.warnings[0].find("not resolved by the pairs"),
              std::string::npos);

    check.element_depth = 3. * a;
    const auto deep =
      check.evaluate(grid_pairs(check, 40, a / 20., false, Point<3>(), ex, ey));
    ASSERT_EQ(deep.warnings.size(), 1u);
    EXPECT_NE(deep.warnings[0].find("more than twice the contact radius"),
              std::string::npos);
  }


  // Elliptical contact (HertzEllipticCheck). Its closed form is checked by
  // the property that defines it, independently of the elliptic-integral
  // relations it uses: Hertz's pressure p0 sqrt(1 - x^2/a_x^2 - y^2/a_y^2)
  // on a half-space (Boussinesq: w = 1/(pi E*) int p / rho dA, E* the
  // check's combined modulus) must indent the surface by w(0) - A x^2 -
  // B y^2 inside the ellipse, and carry P. w is integrated in polar
  // coordinates about the point: along each ray p is p0 sqrt(alpha
  // (rho_max - rho)(rho - rho_min)), whose integral is a circular segment
  // in closed form; the angle by the trapezoidal rule, exponentially
  // convergent for a smooth periodic integrand (2000 angles: round-off).
  double
  boussinesq_deflection(const igabde::postprocess::HertzEllipticCheck &check,
                        const double                                   x0,
                        const double                                   y0)
  {
    const auto         exact = check.exact();
    const double       a = exact.semi_axis_x, b = exact.semi_axis_y;
    const unsigned int n   = 2000;
    double             sum = 0.;
    for (unsigned int k = 0; k < n; ++k)
      {
        const double theta = 2. * M_PI * k / n;
        const double c = std::cos(theta), s = std::sin(theta);
        const double alpha = c * c / (a * a) + s * s / (b * b);
        const double beta  = x0 * c / (a * a) + y0 * s / (b * b);
        const double gamma = x0 * x0 / (a * a) + y0 * y0 / (b * b) - 1.;
        const double root  = std::sqrt(beta * beta - alpha * gamma);
        const double hi = (-beta + root) / alpha, lo = (-beta - root) / alpha;
        // int_0^hi sqrt(h^2 - (rho - m)^2) drho, m the middle, h the half.
        const double m = 0.5 * (hi + lo), h = 0.5 * (hi - lo);
        const auto   F = [&](const double u) {
          const double v = std::clamp(u / h, -1., 1.);
          return 0.5 * (u * std::sqrt(std::max(h * h - u * u, 0.)) +
                        h * h * std::asin(v));
        };
        sum += std::sqrt(alpha) * (F(h) - F(-m));
      }
    return exact.peak_pressure * sum * (2. * M_PI / n) /
           (M_PI * check.effective_modulus);
  }

  igabde::postprocess::HertzEllipticCheck
  elliptic_check(const double A, const double B)
  {
    igabde::postprocess::HertzEllipticCheck check;
    check.load                = 0.75;
    check.curvature_x         = A;
    check.curvature_y         = B;
    check.effective_modulus   = 1000. / (2. * (1. - 0.09));
    check.axis_direction      = Tensor<1, 3>({0., 0., 1.});
    check.principal_direction = ex;
    return check;
  }

  TEST(HertzEllipticCheck, ClosedFormIndentsTheHalfSpaceByTheGap)
  {
    // B/A from the sphere's neighbourhood (the series branch) to a long
    // ellipse, and with the longer axis along y.
    for (const auto &[A, B] :
         std::vector<std::pair<double, double>>{{0.5, 0.5 * (1. + 1e-4)},
                                                {0.25, 0.5},
                                                {0.05, 0.5},
                                                {0.5, 0.1}})
      {
        SCOPED_TRACE("A = " + std::to_string(A) + ", B = " + std::to_string(B));
        const auto   check = elliptic_check(A, B);
        const auto   exact = check.exact();
        const double w0    = boussinesq_deflection(check, 0., 0.);
        for (const double t : {0.3, 0.7})
          {
            const double x = t * exact.semi_axis_x, y = t * exact.semi_axis_y;
            EXPECT_NEAR(w0 - boussinesq_deflection(check, x, 0.),
                        A * x * x,
                        1e-8 * A * x * x);
            EXPECT_NEAR(w0 - boussinesq_deflection(check, 0., y),
                        B * y * y,
                        1e-8 * B * y * y);
          }
        // The load: int p dA = 2/3 pi a b p0.
        EXPECT_NEAR(2. / 3. * M_PI * exact.semi_axis_x * exact.semi_axis_y *
                      exact.peak_pressure,
                    0.75,
                    1e-12);
        // The longer semi-axis lies along the smaller curvature.
        EXPECT_EQ(exact.semi_axis_x > exact.semi_axis_y, A < B);
      }
    // A = B is the sphere of radius 1 / (2 A).
    const auto   sphere = elliptic_check(0.5, 0.5).exact();
    const double a      = std::cbrt(3. * 0.75 / (4. * (1000. / 1.82)));
    EXPECT_NEAR(sphere.semi_axis_x, a, 1e-14);
    EXPECT_NEAR(sphere.semi_axis_y, a, 1e-14);
    EXPECT_EQ(sphere.eccentricity, 0.);
  }

  TEST(HertzEllipticCheck, PointValuesOfHertzGiveItsSemiAxesAndPeak)
  {
    // Pairs on a grid carrying Hertz's elliptical pressure at their
    // centres (a quarter model): the peak is the profile at the pair
    // nearest the axis, the profile error vanishes, the force moments give
    // the semi-axes to the midpoint rule's O((h/a)^(3/2)) at the
    // square-root edge (h = a_y / 100: 1 %).
    auto                      check = elliptic_check(0.25, 0.5);
    const auto                exact = check.exact();
    const double              ax = exact.semi_axis_x, ay = exact.semi_axis_y;
    const double              p0 = exact.peak_pressure, h = ay / 100.;
    std::vector<PairState<3>> pairs;
    for (unsigned int i = 0; i < 200; ++i)
      for (unsigned int j = 0; j < 150; ++j)
        {
          const double x = (i + 0.5) * h, y = (j + 0.5) * h;
          const double q = 1. - x * x / (ax * ax) - y * y / (ay * ay);
          PairState<3> pair;
          pair.location    = Point<3>(x, y, 0.);
          pair.area        = h * h;
          pair.force_local = {(q > 0. ? p0 * std::sqrt(q) : 0.) * h * h};
          pairs.push_back(pair);
        }
    const auto r = check.evaluate(pairs);
    EXPECT_NEAR(r.peak_pressure,
                p0 * std::sqrt(1. - 0.25 * h * h *
                                      (1. / (ax * ax) + 1. / (ay * ay))),
                1e-12 * p0);
    EXPECT_LT(r.profile_l2_error, 1e-13);
    EXPECT_NEAR(r.semi_axis_x_moment / ax, 1., 1e-2);
    EXPECT_NEAR(r.semi_axis_y_moment / ay, 1., 1e-2);
    EXPECT_TRUE(r.warnings.empty());
    // The pairs turned by 90 degrees about the axis, (x, y) -> (-y, x):
    // the long axis now lies along y, and the check told so (principal
    // direction y; e_y = z x y = -x) reads the same figures.
    check.principal_direction        = ey;
    std::vector<PairState<3>> turned = pairs;
    for (auto &pair : turned)
      pair.location = Point<3>(-pair.location[1], pair.location[0], 0.);
    const auto q = check.evaluate(turned);
    EXPECT_NEAR(q.semi_axis_x_moment, r.semi_axis_x_moment, 1e-12 * ax);
    EXPECT_NEAR(q.semi_axis_y_moment, r.semi_axis_y_moment, 1e-12 * ay);
    EXPECT_NEAR(q.profile_l2_error, r.profile_l2_error, 1e-12);
  }
} // namespace hertz_point_test
