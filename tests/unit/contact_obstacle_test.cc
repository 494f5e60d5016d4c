// Rigid obstacles (include/igabde/contact/obstacle.h): the closest point
// and outward normal of a circle, a cylinder, a sphere and a NURBS rigid
// surface against points placed by hand, and a prescribed rigid motion
// against its hand evaluation u(x) = sum_k f_k (d_k + r_k x (x - c)).
// The rounded punch's closed form (postprocess::RoundedPunchCheck) against
// Hertz (its b = 0 limit), equilibrium, and the inversion integral
// evaluated by quadrature.

#include <igabde/base/utilities.h>

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/nurbs_surface.h>

#include <igabde/contact/obstacle.h>

#include <igabde/postprocess/contact_checks.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <gtest/gtest.h>

#include <cmath>

namespace obstacle_test
{
  using namespace dealii;
  using namespace igabde;

  template <int dim>
  void
  expect_point(const Point<dim> &actual, const Point<dim> &expected)
  {
    for (unsigned int d = 0; d < dim; ++d)
      EXPECT_NEAR(actual[d], expected[d], 1e-14) << d;
  }



  template <int dim>
  void
  expect_tensor(const Tensor<1, dim> &actual, const Tensor<1, dim> &expected)
  {
    for (unsigned int d = 0; d < dim; ++d)
      EXPECT_NEAR(actual[d], expected[d], 1e-14) << d;
  }



  TEST(RigidObstacle, CircleClosestPointLiesOnTheRayFromItsCentre)
  {
    // Circle R = 2 about (1, 3); the point (4, 7) is at distance 5 along
    // (3, 4)/5: the closest point is (1, 3) + 2 (0.6, 0.8).
    const contact::RigidCylinder<2> circle(Point<2>(1., 3.),
                                           2.,
                                           Tensor<1, 2>());
    const auto p = circle.closest_point(Point<2>(4., 7.), nullptr);
    expect_point(p.location, Point<2>(2.2, 4.6));
    expect_tensor(p.normal, Tensor<1, 2>({0.6, 0.8}));
    // A point inside (distance 1 < R) projects outward along the same ray:
    // the gap (x - y) . n is then -1, the penetration.
    const auto q = circle.closest_point(Point<2>(1.6, 3.8), nullptr);
    expect_point(q.location, Point<2>(2.2, 4.6));
    EXPECT_NEAR((Point<2>(1.6, 3.8) - q.location) * q.normal, -1., 1e-14);
    EXPECT_FALSE(circle.flat());
    EXPECT_EQ(circle.kind(), "rigid circle");
  }



  TEST(RigidObstacle, CylinderProjectsAlongTheAxisFirst)
  {
    // Axis through (0, 0, 1) along (0, 2, 0) (not unit), R = 0.5: the point
    // (3, 7, 5) has its foot (0, 7, 1) on the axis, radial (3, 0, 4)/5.
    const contact::RigidCylinder<3> cylinder(Point<3>(0., 0., 1.),
                                             0.5,
                                             Tensor<1, 3>({0., 2., 0.}));
    const auto p = cylinder.closest_point(Point<3>(3., 7., 5.), nullptr);
    expect_point(p.location, Point<3>(0.3, 7., 1.4));
    expect_tensor(p.normal, Tensor<1, 3>({0.6, 0., 0.8}));
    EXPECT_EQ(cylinder.kind(), "rigid cylinder");
  }



  TEST(RigidObstacle, SphereClosestPointAndItsCentreRefused)
  {
    const contact::RigidSphere<3> sphere(Point<3>(1., 1., 1.), 3.);
    // (1, 1, 1) + (2, 3, 6) is at distance 7: the closest point is at 3/7.
    const auto p = sphere.closest_point(Point<3>(3., 4., 7.), nullptr);
    expect_point(p.location,
                 Point<3>(1. + 6. / 7., 1. + 9. / 7., 1. + 18. / 7.));
    expect_tensor(p.normal, Tensor<1, 3>({2. / 7., 3. / 7., 6. / 7.}));
    // No normal exists at the centre: an input error, not a NaN normal.
    EXPECT_THROW(sphere.closest_point(Point<3>(1., 1., 1.), nullptr),
                 base::ExcInput);
  }



  TEST(RigidObstacle, FixedObstacleDoesNotMove)
  {
    const contact::RigidPlane<2> plane(Point<2>(0., 0.),
                                       Tensor<1, 2>({0., 1.}));
    EXPECT_FALSE(plane.moves());
    EXPECT_TRUE(plane.flat());
    expect_tensor(plane.displacement(Point<2>(3., 0.), {1., 1., 1.}),
                  Tensor<1, 2>());
  }



  TEST(RigidObstacle, MotionAddsTranslationAndRotationPerHistory)
  {
    // 2D: circle about c = (1, 2); term 0 (history 1) translates by
    // (0, -0.1) and turns by 0.02 rad about z; term 1 (history 2)
    // translates by (0.3, 0). At x = (4, 6), x - c = (3, 4) and
    // r x (x - c) = 0.02 (-4, 3) = (-0.08, 0.06). With factors f1 = 0.5,
    // f2 = 2: u = 0.5 ((0, -0.1) + (-0.08, 0.06)) + 2 (0.3, 0)
    //           = (0.56, -0.02).
    contact::RigidCylinder<2> circle(Point<2>(1., 2.), 1., Tensor<1, 2>());
    std::vector<contact::RigidMotion<2>> motion(2);
    motion[0].history     = 1;
    motion[0].translation = Tensor<1, 2>({0., -0.1});
    motion[0].rotation[2] = 0.02;
    motion[1].history     = 2;
    motion[1].translation = Tensor<1, 2>({0.3, 0.});
    circle.set_motion(motion);
    EXPECT_TRUE(circle.moves());
    expect_tensor(circle.displacement(Point<2>(4., 6.), {1., 0.5, 2.}),
                  Tensor<1, 2>({0.56, -0.02}));
    // A history past the step's factors contributes nothing.
    expect_tensor(circle.displacement(Point<2>(4., 6.), {1., 0.5}),
                  Tensor<1, 2>({-0.04, -0.02}));

    // 3D: sphere about c = (0, 0, 1), rotation (0.1, 0, 0.2) rad, no
    // translation, factor 1; at x = (1, 2, 1): x - c = (1, 2, 0),
    // r x (x - c) = (0 * 0 - 0.2 * 2, 0.2 * 1 - 0.1 * 0, 0.1 * 2 - 0 * 1)
    //             = (-0.4, 0.2, 0.2).
    contact::RigidSphere<3>              sphere(Point<3>(0., 0., 1.), 1.);
    std::vector<contact::RigidMotion<3>> turn(1);
    turn[0].rotation = Tensor<1, 3>({0.1, 0., 0.2});
    sphere.set_motion(turn);
    expect_tensor(sphere.displacement(Point<3>(1., 2., 1.), {0., 1.}),
                  Tensor<1, 3>({-0.4, 0.2, 0.2}));
  }


  TEST(RigidObstacle, FiniteMotionIsExactAndLinearisesToTheDisplacement)
  {
    // 2D: the circle about c = (1, 2) turned by a quarter turn and moved
    // by (0.3, 0): x = (4, 6), x - c = (3, 4), goes to c + (0.3, 0) +
    // (-4, 3) = (-2.7, 5).
    contact::RigidCylinder<2> circle(Point<2>(1., 2.), 1., Tensor<1, 2>());
    std::vector<contact::RigidMotion<2>> motion(1);
    motion[0].history     = 1;
    motion[0].translation = Tensor<1, 2>({0.3, 0.});
    motion[0].rotation[2] = M_PI / 2.;
    circle.set_motion(motion);
    expect_tensor(circle.placed(Point<2>(4., 6.), {0., 1.}) - Point<2>(),
                  Tensor<1, 2>({-2.7, 5.}));
    // 3D: a sphere about c = (0, 0, 1) turned by 120 degrees about
    // (1, 1, 1) / sqrt(3), which cycles the axes: x - c = (1, 2, 0) goes to
    // (0, 1, 2).
    contact::RigidSphere<3>              sphere(Point<3>(0., 0., 1.), 1.);
    std::vector<contact::RigidMotion<3>> turn(1);
    turn[0].rotation =
      (2. * M_PI / 3. / std::sqrt(3.)) * Tensor<1, 3>({1., 1., 1.});
    sphere.set_motion(turn);
    expect_tensor(sphere.placed(Point<3>(1., 2., 1.), {0., 1.}) - Point<3>(),
                  Tensor<1, 3>({0., 1., 3.}));
    // Small factors: placed() - x is displacement() to second order; the
    // second-order term of a turn by the angle a is a / 2 of the first.
    const std::vector<double> small = {0., 1e-4};
    const Tensor<1, 3>        exact =
      sphere.placed(Point<3>(1., 2., 1.), small) - Point<3>(1., 2., 1.);
    const Tensor<1, 3> linear =
      sphere.displacement(Point<3>(1., 2., 1.), small);
    const double angle = 1e-4 * turn[0].rotation.norm();
    EXPECT_LT((exact - linear).norm(), angle * linear.norm());
    EXPECT_GT((exact - linear).norm(), 0.25 * angle * linear.norm());

    // The plane y = 0 (normal +y) turned by a quarter turn about (0, 0)
    // and moved by (0.3, 0) is the plane x = 0.3 with normal (-1, 0): the
    // closest point to (3, 5) is (0.3, 5).
    contact::RigidPlane<2> plane(Point<2>(0., 0.), Tensor<1, 2>({0., 1.}));
    plane.set_motion(motion);
    const contact::PlacedObstacle<2> placed(plane, {0., 1.});
    const auto point = placed.closest_point(Point<2>(3., 5.), nullptr);
    expect_tensor(point.location - Point<2>(), Tensor<1, 2>({0.3, 5.}));
    expect_tensor(point.normal, Tensor<1, 2>({-1., 0.}));
  }


  TEST(RigidObstacle, NurbsSurfaceIsItsExactCircle)
  {
    // The quarter annulus 1 <= r <= 2 as a rigid surface of its outer arc
    // (face 1): the closest point of (3, 4) is 2 (0.6, 0.8), the normal
    // (0.6, 0.8), the radius of curvature 2 (the rational arc is exact).
    const std::vector<nurbs::NurbsPatch<2>> patches = {
      nurbs::make_quarter_annulus(1., 2.)};
    const contact::RigidSurface<2> arc(
      discretization::make_nurbs_surface(patches, {1}),
      "a quarter annulus");
    const auto p = arc.closest_point(Point<2>(3., 4.), nullptr);
    for (unsigned int d = 0; d < 2; ++d)
      {
        EXPECT_NEAR(p.location[d], (d == 0 ? 1.2 : 1.6), 1e-12) << d;
        EXPECT_NEAR(p.normal[d], (d == 0 ? 0.6 : 0.8), 1e-12) << d;
      }
    EXPECT_NEAR(arc.curvature_radius(), 2., 1e-10);
    EXPECT_FALSE(arc.flat());
    EXPECT_EQ(arc.kind(), "rigid surface");
    EXPECT_EQ(arc.description(), "the rigid surface of a quarter annulus");

    // Its inner arc (face 0) is touched from the hole: the outward normal
    // points to the centre.
    const contact::RigidSurface<2> hole(
      discretization::make_nurbs_surface(patches, {0}),
      "a quarter annulus");
    const auto q = hole.closest_point(Point<2>(0.3, 0.4), nullptr);
    EXPECT_NEAR(q.location[0], 0.6, 1e-12);
    EXPECT_NEAR(q.normal[1], -0.8, 1e-12);
    EXPECT_NEAR(hole.curvature_radius(), 1., 1e-10);
  }



  TEST(RigidObstacle, NurbsSurfaceOfTwoFacesKeepsTheNearest)
  {
    // The box [0, 2] x [0, 1], faces 2 (bottom) and 1 (right): (3, 0.5) is
    // nearest to the right face at (2, 0.5), (1, -1) to the bottom at
    // (1, 0); both flat. The pivot is the mean of the faces' centroids,
    // ((1, 0) + (2, 0.5)) / 2.
    const std::vector<nurbs::NurbsPatch<2>> patches = {
      nurbs::make_box(Point<2>(0., 0.), Point<2>(2., 1.))};
    const contact::RigidSurface<2> box(
      discretization::make_nurbs_surface(patches, {2, 1}),
      "a box");
    const auto right = box.closest_point(Point<2>(3., 0.5), nullptr);
    EXPECT_NEAR(right.location[0], 2., 1e-12);
    EXPECT_NEAR(right.location[1], 0.5, 1e-12);
    EXPECT_NEAR(right.normal[0], 1., 1e-12);
    const auto bottom = box.closest_point(Point<2>(1., -1.), nullptr);
    EXPECT_NEAR(bottom.location[0], 1., 1e-12);
    EXPECT_NEAR(bottom.location[1], 0., 1e-12);
    EXPECT_NEAR(bottom.normal[1], -1., 1e-12);
    EXPECT_TRUE(box.flat());
    EXPECT_NEAR(box.pivot()[0], 1.5, 1e-12);
    EXPECT_NEAR(box.pivot()[1], 0.25, 1e-12);
  }



  /// The rounded punch's pressure by quadrature of the inversion of the
  /// half-plane's integral equation, p(x) = E* / (2 pi) sqrt(a^2 - x^2)
  /// PV int h'(s) / (sqrt(a^2 - s^2) (s - x)) ds, written with
  /// s = a sin(theta) over the two corners, the principal value's pole
  /// subtracted and integrated in closed form: an evaluation independent
  /// of the check's closed form.
  double
  punch_pressure_by_quadrature(const double x,
                               const double a,
                               const double b,
                               const double R,
                               const double e_star)
  {
    const double phi0 = std::asin(b / a), phi = std::asin(x / a);
    const auto   g = [&](const double theta) {
      return (a * std::sin(theta) - b) / R;
    };
    // int over (phi0, pi/2) of g / (a sin - c) for c = x and of
    // g / (a sin + x); 20000 midpoints.
    const unsigned int n     = 20000;
    const double       h     = (M_PI / 2. - phi0) / n;
    double             right = 0., left = 0.;
    const bool         pole = (phi > phi0);
    for (unsigned int k = 0; k < n; ++k)
      {
        const double theta = phi0 + (k + 0.5) * h;
        left += h * g(theta) / (a * std::sin(theta) + x);
        double f = g(theta) / (a * std::sin(theta) - x);
        if (pole)
          f -= g(phi) / (a * std::cos(phi) * (theta - phi));
        right += h * f;
      }
    if (pole)
      right += g(phi) / (a * std::cos(phi)) *
               std::log((M_PI / 2. - phi) / (phi - phi0));
    return e_star / (2. * M_PI) * std::sqrt(a * a - x * x) * (right + left);
  }



  TEST(RoundedPunch, ClosedFormMeetsHertzEquilibriumAndTheInversion)
  {
    const double e_star = 1000. / 0.91;
    // b = 0: Hertz's cylinder of radius R, a = sqrt(4 P R / (pi E*)),
    // p = p0 sqrt(1 - x^2 / a^2), p0 = 2 P / (pi a).
    postprocess::RoundedPunchCheck hertz;
    hertz.line_load         = 20.;
    hertz.corner_radius     = 16.;
    hertz.effective_modulus = e_star;
    const double a_hertz    = std::sqrt(4. * 20. * 16. / (M_PI * e_star));
    EXPECT_NEAR(hertz.half_width(), a_hertz, 1e-12 * a_hertz);
    for (const double x : {0., 0.3, 0.7, 0.95})
      EXPECT_NEAR(hertz.pressure(x * a_hertz),
                  2. * 20. / (M_PI * a_hertz) * std::sqrt(1. - x * x),
                  1e-10)
        << x;

    // b = 0.5: the load relation, and the pressure against the quadrature
    // on the flat, at the knot x = b and in the corners; the force
    // int p dx = P by Simpson's rule (p ~ sqrt(a - x) at the edge: 1e-4).
    postprocess::RoundedPunchCheck punch = hertz;
    punch.flat_half_width                = 0.5;
    const double a                       = punch.half_width();
    const double phi0                    = std::asin(0.5 / a);
    EXPECT_NEAR(e_star * a * a * (M_PI - 2. * phi0 - std::sin(2. * phi0)) /
                  (4. * 16.),
                20.,
                1e-10);
    for (const double x : {0., 0.2, 0.45, 0.5, 0.55, 0.7, 0.9, 0.97})
      EXPECT_NEAR(punch.pressure(x),
                  punch_pressure_by_quadrature(x, a, 0.5, 16., e_star),
                  1e-6 * punch.pressure(0.7))
        << x;
    const unsigned int n     = 20000;
    double             force = 0.;
    for (unsigned int k = 0; k <= n; ++k)
      force += (k == 0 || k == n ? 1. : (k % 2 == 1 ? 4. : 2.)) *
               punch.pressure(-a + 2. * a * k / n) * (2. * a / n) / 3.;
    EXPECT_NEAR(force, 20., 1e-4 * 20.);
    EXPECT_EQ(punch.pressure(a), 0.);
    EXPECT_EQ(punch.pressure(-1.01 * a), 0.);
  }
} // namespace obstacle_test
