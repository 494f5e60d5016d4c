// The free and held rigid modes of a body (discretization/rigid_modes.h),
// each against what the rule guarantees, on unknowns laid out by hand: the
// free modes are the rigid motions the constraints allow (a rigid motion
// projects onto their span with no residue, a constrained one does not),
// the pins remove them (no free mode survives the pins), and holding a
// face's rotation gives the projectors their defining properties
// (C_h^T P u = 0, R_h^T P^T f = 0) and the reaction that cancels a pure
// moment.

#include <igabde/discretization/rigid_modes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace igabde;
using namespace igabde::discretization;

namespace
{
  /// The unknowns of @p points, each with dim components (unknown
  /// dim * p + c is component c at point p).
  template <int dim>
  std::pair<std::vector<Point<dim>>, std::vector<unsigned int>>
  unknowns_at(const std::vector<Point<dim>> &points)
  {
    std::vector<Point<dim>>   locations;
    std::vector<unsigned int> components;
    for (const auto &p : points)
      for (unsigned int c = 0; c < dim; ++c)
        {
          locations.push_back(p);
          components.push_back(c);
        }
    return {locations, components};
  }

  /// Constraints u_i = 0 for each i of @p held.
  AffineConstraints<double>
  held_at(const std::vector<types::global_dof_index> &held)
  {
    AffineConstraints<double> constraints;
    for (const auto i : held)
      constraints.add_line(i);
    constraints.close();
    return constraints;
  }

  /// The rigid motion a + w x x at @p locations (w about z in 2D: w[0]).
  template <int dim>
  Vector<double>
  rigid_motion(const std::vector<Point<dim>>   &locations,
               const std::vector<unsigned int> &components,
               const Tensor<1, dim>            &a,
               const Tensor<1, 3>              &w)
  {
    Vector<double> u(locations.size());
    for (unsigned int i = 0; i < locations.size(); ++i)
      {
        const Point<dim> &x = locations[i];
        Tensor<1, 3>      x3;
        for (unsigned int d = 0; d < dim; ++d)
          x3[d] = x[d];
        const Tensor<1, 3> r = cross_product_3d(w, x3);
        u[i]                 = a[components[i]] + r[components[i]];
      }
    return u;
  }

  /// |v - projection of v on span(modes)| / |v| (modes: any basis).
  double
  residue_off_span(const std::vector<Vector<double>> &modes,
                   const Vector<double>              &v)
  {
    // Gram-Schmidt on copies, then subtract the projections.
    std::vector<Vector<double>> basis;
    for (Vector<double> m : modes)
      {
        for (const auto &b : basis)
          m.add(-(m * b), b);
        const double norm = m.l2_norm();
        if (norm > 0)
          {
            m /= norm;
            basis.push_back(m);
          }
      }
    Vector<double> r = v;
    for (const auto &b : basis)
      r.add(-(r * b), b);
    return r.l2_norm() / v.l2_norm();
  }

  std::vector<Point<2>>
  unit_square_nodes()
  {
    return {Point<2>(0, 0), Point<2>(1, 0), Point<2>(0, 1), Point<2>(1, 1)};
  }

  Vector<double>
  random_vector(const unsigned int n, const unsigned int seed)
  {
    std::mt19937                           engine(seed);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    Vector<double>                         v(n);
    for (auto &x : v)
      x = uniform(engine);
    return v;
  }
} // namespace



TEST(RigidModes, AnUnheldBodyHasEveryRigidMotionFree)
{
  const auto [x, c] = unknowns_at<2>(unit_square_nodes());
  const RigidModes<2> modes(x, c, held_at({}));
  ASSERT_EQ(modes.free_modes().size(), 3u);
  EXPECT_TRUE(modes.free_translation(0));
  EXPECT_TRUE(modes.free_translation(1));
  // Any rigid motion lies in their span; a stretch does not.
  EXPECT_LT(residue_off_span(modes.free_modes(),
                             rigid_motion<2>(x,
                                             c,
                                             Tensor<1, 2>({0.3, -0.7}),
                                             Tensor<1, 3>({0., 0., 1.3}))),
            1e-12);
  Vector<double> stretch(x.size());
  for (unsigned int i = 0; i < x.size(); ++i)
    stretch[i] = (c[i] == 0 ? x[i][0] : 0.);
  EXPECT_GT(residue_off_span(modes.free_modes(), stretch), 0.1);
}



TEST(RigidModes, APinnedPointLeavesTheRotationAboutIt)
{
  // u = 0 at node (0, 0): the rotation about that node is the only rigid
  // motion left, so neither translation is free.
  const auto [x, c] = unknowns_at<2>(unit_square_nodes());
  const RigidModes<2> modes(x, c, held_at({0, 1}));
  ASSERT_EQ(modes.free_modes().size(), 1u);
  EXPECT_FALSE(modes.free_translation(0));
  EXPECT_FALSE(modes.free_translation(1));
  EXPECT_LT(residue_off_span(modes.free_modes(),
                             rigid_motion<2>(x,
                                             c,
                                             Tensor<1, 2>(),
                                             Tensor<1, 3>({0., 0., 1.}))),
            1e-12);
}



TEST(RigidModes, A3DBodyOnThreeVerticalSupportsSlidesAndTurnsInItsPlane)
{
  // u_z = 0 at three points of the plane z = 0 (not on a line): the
  // translations x, y and the rotation about z stay free.
  const std::vector<Point<3>> points = {Point<3>(0, 0, 0),
                                        Point<3>(1, 0, 0),
                                        Point<3>(0, 1, 0),
                                        Point<3>(0.4, 0.3, 1)};
  const auto [x, c]                  = unknowns_at<3>(points);
  const RigidModes<3> modes(x, c, held_at({2, 5, 8}));
  ASSERT_EQ(modes.free_modes().size(), 3u);
  EXPECT_TRUE(modes.free_translation(0));
  EXPECT_TRUE(modes.free_translation(1));
  EXPECT_FALSE(modes.free_translation(2));
  EXPECT_LT(residue_off_span(modes.free_modes(),
                             rigid_motion<3>(x,
                                             c,
                                             Tensor<1, 3>({1., 2., 0.}),
                                             Tensor<1, 3>({0., 0., -0.5}))),
            1e-12);
  EXPECT_GT(residue_off_span(modes.free_modes(),
                             rigid_motion<3>(x,
                                             c,
                                             Tensor<1, 3>(),
                                             Tensor<1, 3>({1., 0., 0.}))),
            0.1);
}



TEST(RigidModes, ThePinsLeaveNoFreeMode)
{
  // With the pins added to the constraints, nothing is free any more: the
  // guarantee that makes the pinned matrix regular. The weights steer the
  // choice away from the unknowns weighted down.
  const auto [x, c] = unknowns_at<2>(unit_square_nodes());
  const RigidModes<2> modes(x, c, held_at({}));
  std::vector<double> weights(x.size(), 1.);
  weights[0]      = 1e-3;
  weights[1]      = 1e-3;
  const auto pins = modes.pins(weights);
  ASSERT_EQ(pins.size(), 3u);
  for (const auto i : pins)
    EXPECT_GT(i, 1u) << "pin on an unknown weighted down";
  const RigidModes<2> pinned(x, c, held_at(pins));
  EXPECT_TRUE(pinned.free_modes().empty());
}



TEST(RigidModes, AHeldRotationsProjectorsMeetTheirDefinitions)
{
  // A free 2D body; constraint c^T u = 0 with c a pure moment on the face
  // x = 1: +0.5 along x at node (1, 0), -0.5 along x at node (1, 1). Its
  // moment about z about the face's centroid (1, 0.5) is
  // sum -(y - 0.5) F_x = -(-0.5)(0.5) - (0.5)(-0.5) = 0.5. The constraint
  // holds the rotation: the two translations stay free, one mode is held.
  const auto [x, c] = unknowns_at<2>(unit_square_nodes());
  RigidModes<2>  modes(x, c, held_at({}));
  Vector<double> load(x.size());
  load[2 * 1 + 0] = 0.5;
  load[2 * 3 + 0] = -0.5;
  FullMatrix<double> J(1, 1);
  J(0, 0) = 0.5;
  modes.hold({load}, J);
  ASSERT_EQ(modes.held_modes().size(), 1u);
  EXPECT_EQ(modes.held_mode_names()[0], "rotation z");
  ASSERT_EQ(modes.free_modes().size(), 2u);
  EXPECT_TRUE(modes.free_translation(0));
  EXPECT_TRUE(modes.free_translation(1));

  // P u meets the constraint: C_h^T P u = 0.
  Vector<double> u = random_vector(x.size(), 1);
  modes.fix(u);
  EXPECT_LT(std::abs(modes.held_loads()[0] * u), 1e-14);
  // P^T f is balanced in the held mode: R_h^T P^T f = 0.
  Vector<double> f = random_vector(x.size(), 2);
  modes.balance(f);
  EXPECT_LT(std::abs(modes.held_modes()[0] * f), 1e-14);
  // The hold's reaction to the pure moment load cancels its moment.
  const std::vector<double> reaction = modes.held_moment(load);
  ASSERT_EQ(reaction.size(), 1u);
  EXPECT_NEAR(reaction[0], -0.5, 1e-14);
  // A translation load needs no reaction.
  Vector<double> push(x.size());
  for (unsigned int i = 0; i < x.size(); ++i)
    push[i] = (c[i] == 1 ? 1. : 0.);
  EXPECT_NEAR(modes.held_moment(push)[0], 0., 1e-14);
}



TEST(RigidModes, ARotationTheSupportsHoldIsNotHeldAgain)
{
  // Both x and y held at node (0, 0) and x at node (0, 1): fixed. Holding
  // the rotation has nothing left to hold.
  const auto [x, c] = unknowns_at<2>(unit_square_nodes());
  RigidModes<2> modes(x, c, held_at({0, 1, 4}));
  ASSERT_TRUE(modes.free_modes().empty());
  Vector<double> load(x.size());
  load[2] = 1.;
  FullMatrix<double> J(1, 1);
  J(0, 0) = 1.;
  modes.hold({load}, J);
  EXPECT_TRUE(modes.held_modes().empty());
  EXPECT_TRUE(modes.free_modes().empty());
}
