// Rigid obstacles (include/igabde/contact/obstacle.h): the closest point
// and outward normal of a circle, a cylinder and a sphere against points
// placed by hand, and a prescribed rigid motion against its hand
// evaluation u(x) = sum_k f_k (d_k + r_k x (x - c)).

#include <igabde/base/utilities.h>

#include <igabde/contact/obstacle.h>

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
} // namespace obstacle_test
