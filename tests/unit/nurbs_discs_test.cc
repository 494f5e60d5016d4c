// The full and half disc and cylinder builders (issue #12, item 4): every
// arc face on the circle of the given centre and radius with the radial
// outward normal, the flat faces where they belong, the faces spanning the
// angles the header documents, det J > 0 inside the patch, and areas and
// volumes equal to pi R^2, pi R^2 / 2 and those times the height (Gauss
// quadrature of det J, exponentially convergent for this analytic map).

#include <igabde/nurbs/geometry_builders.h>
#include <igabde/nurbs/nurbs_patch.h>

#include <deal.II/base/quadrature_lib.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace dealii;
using namespace igabde::nurbs;

namespace
{
  /// Polar angle of @p x about @p c in degrees, in [0, 360).
  double
  angle(const Point<2> &x, const Point<2> &c)
  {
    const double t = std::atan2(x[1] - c[1], x[0] - c[0]) * 180. / M_PI;
    return t < 0. ? t + 360. : t;
  }

  /// The angle from @p b to @p a in degrees, in [-180, 180).
  double
  turn(const double a, const double b)
  {
    return std::fmod(a - b + 540., 360.) - 180.;
  }

  /// int det J over the parametric box.
  template <int dim>
  double
  measure(const NurbsPatch<dim> &patch)
  {
    const QGauss<dim> rule(40);
    double            sum = 0.;
    for (unsigned int q = 0; q < rule.size(); ++q)
      sum += determinant(patch.jacobian(rule.point(q))) * rule.weight(q);
    return sum;
  }

  /**
   * Checks a 2D disc patch: face f (0 left, 1 right, 2 bottom, 3 top) runs
   * along the circle from angle from[f] to to[f] (face 3 of the half disc
   * is the diameter, flat == true).
   */
  void
  check_disc(const NurbsPatch<2> &disc,
             const Point<2>      &c,
             const double         R,
             const double (&from)[4],
             const double (&to)[4],
             const bool flat_top)
  {
    EXPECT_EQ(disc.orientation(), 1.);
    for (unsigned int f = 0; f < 4; ++f)
      {
        SCOPED_TRACE("face " + std::to_string(f));
        const unsigned int d = f / 2;
        // Ends of the face: parameter 0 and 1 along the other direction.
        Point<2> start, end;
        start[d] = end[d] = (f % 2 == 0 ? 0. : 1.);
        start[1 - d]      = 0.;
        end[1 - d]        = 1.;
        if (f == 3 && flat_top)
          {
            EXPECT_NEAR((disc.value(start) - (c + Point<2>(-R, 0.))).norm(),
                        0.,
                        1e-13 * R);
            EXPECT_NEAR((disc.value(end) - (c + Point<2>(R, 0.))).norm(),
                        0.,
                        1e-13 * R);
          }
        else
          {
            EXPECT_NEAR(turn(angle(disc.value(start), c), from[f]), 0., 1e-12);
            EXPECT_NEAR(turn(angle(disc.value(end), c), to[f]), 0., 1e-12);
          }
        for (unsigned int s = 0; s <= 50; ++s)
          {
            Point<2> xi          = start;
            xi[1 - d]            = s / 50.;
            const Point<2>     x = disc.value(xi);
            const Tensor<1, 2> n = disc.outward_normal(f, xi);
            if (f == 3 && flat_top)
              {
                EXPECT_NEAR(x[1], c[1], 1e-13 * R);
                EXPECT_NEAR(n[1], 1., 1e-13);
              }
            else
              {
                EXPECT_NEAR((x - c).norm(), R, 1e-13 * R);
                EXPECT_NEAR((n - (x - c) / R).norm(), 0., 1e-12);
              }
          }
      }
    // det J > 0 inside (it vanishes only at the corners where two arcs
    // meet at a straight angle).
    for (unsigned int i = 1; i < 40; ++i)
      for (unsigned int j = 1; j < 40; ++j)
        EXPECT_GT(determinant(disc.jacobian(Point<2>(i / 40., j / 40.))), 0.)
          << "at (" << i / 40. << ", " << j / 40. << ")";
  }
} // namespace



TEST(NurbsBuilders, HalfDiscIsExact)
{
  const Point<2>      c(0.5, 8.);
  const double        R       = 8.;
  const NurbsPatch<2> disc    = make_half_disc(c, R);
  const double        from[4] = {225., 315., 225., 0.};
  const double        to[4]   = {180., 360., 315., 0.};
  check_disc(disc, c, R, from, to, true);
  // The lowest point at the middle of the bottom face.
  EXPECT_NEAR((disc.value(Point<2>(0.5, 0.)) - (c + Point<2>(0., -R))).norm(),
              0.,
              1e-13 * R);
  EXPECT_NEAR(measure(disc), M_PI * R * R / 2., 1e-10 * R * R);

  // Refinement keeps the map: the same area after elevation and splits.
  NurbsPatch<2> refined = disc;
  elevate_to_degree(refined, 3);
  subdivide(refined, {{5, 3}});
  EXPECT_NEAR(measure(refined), M_PI * R * R / 2., 1e-10 * R * R);
}



TEST(NurbsBuilders, FullDiscIsExact)
{
  const Point<2>      c(-1., 2.);
  const double        R       = 3.;
  const NurbsPatch<2> disc    = make_full_disc(c, R);
  const double        from[4] = {225., 315., 225., 135.};
  const double        to[4]   = {135., 45., 315., 45.};
  check_disc(disc, c, R, from, to, false);
  EXPECT_NEAR(measure(disc), M_PI * R * R, 1e-10 * R * R);
  // The nine-point disc: the middle control point is the centre.
  EXPECT_NEAR((disc.control_point(4) - c).norm(), 0., 1e-14 * R);
  EXPECT_NEAR(disc.weight(4), std::sqrt(2.) - 1., 1e-14);
}



TEST(NurbsBuilders, CylindersAreExtrudedDiscs)
{
  const Point<3> c(1., 2., -0.5);
  const double   R = 2., height = 3.;
  for (const bool full : {false, true})
    {
      SCOPED_TRACE(full ? "full cylinder" : "half cylinder");
      const NurbsPatch<3> cylinder = make_cylinder(c, R, height, full);
      EXPECT_EQ(cylinder.orientation(), 1.);
      EXPECT_NEAR(measure(cylinder),
                  (full ? 1. : 0.5) * M_PI * R * R * height,
                  1e-10 * R * R * height);
      for (unsigned int s = 0; s <= 10; ++s)
        for (unsigned int k = 0; k <= 4; ++k)
          {
            const Point<3> x = cylinder.value(Point<3>(s / 10., 0., k / 4.));
            EXPECT_NEAR(std::hypot(x[0] - c[0], x[1] - c[1]), R, 1e-13 * R);
            EXPECT_NEAR(x[2], c[2] + height * k / 4., 1e-13 * height);
          }
      EXPECT_NEAR(cylinder.outward_normal(4, Point<3>(0.3, 0.6, 0.))[2],
                  -1.,
                  1e-13);
      EXPECT_NEAR(cylinder.outward_normal(5, Point<3>(0.3, 0.6, 1.))[2],
                  1.,
                  1e-13);
    }
}
