// The FE_Q geometry of the Lagrange path must be a valid mesh: a positive
// Jacobian at every point where it is evaluated, the VTU sample points
// (cell vertices included) as much as the quadrature points. The curved
// builders have points where the NURBS map itself is singular (det J = 0):
// the 180-degree corner where the two arcs of the Hertz quarter disc meet at
// -45 degrees, and the corner (L, L) of the plate with hole (a doubled
// control point, zero speed). Interpolating the map there gave a folded
// sliver (Hertz, FE_Q(2) and FE_Q(3): det J < 0 at the corner vertex, which
// stopped a Debug build in DataOut::build_patches) or det J = 0 (plate).
// The references are the exact NURBS geometry and closed forms.

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body_description.h>
#include <igabde/discretization/lagrange_body.h>

#include <deal.II/base/quadrature_lib.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
  using namespace igabde;
  using namespace dealii;

  /// The points where the body is evaluated: the VTU sample grid of
  /// write_vtu() (n subdivisions, cell vertices included) and the Gauss
  /// points of the assembly.
  template <int dim>
  std::vector<Point<dim>>
  evaluation_points(const unsigned int degree, const unsigned int n_sub)
  {
    std::vector<Point<dim>> points =
      QIterated<dim>(QTrapezoid<1>(), std::max(degree, n_sub)).get_points();
    const auto gauss = QGauss<dim>(degree + 1).get_points();
    points.insert(points.end(), gauss.begin(), gauss.end());
    return points;
  }

  /// V5's disc (prm/v5-hertz-2d.prm): R = 8, @p n0 x @p n1 knot spans.
  nurbs::NurbsPatch<2>
  hertz_disc(const unsigned int degree,
             const unsigned int n0,
             const unsigned int n1)
  {
    nurbs::NurbsPatch<2> patch = nurbs::make_hertz_quarter_disc(8.);
    nurbs::elevate_to_degree(patch, degree);
    nurbs::subdivide(patch, std::array<unsigned int, 2>{{n0, n1}});
    return patch;
  }

  template <int dim>
  discretization::BodyDescription<dim>
  description(const nurbs::NurbsPatch<dim> &patch)
  {
    discretization::BodyDescription<dim> d;
    d.geometry = patch;
    return d;
  }

  discretization::DiscretizationSettings
  lagrange(const unsigned int degree)
  {
    discretization::DiscretizationSettings settings;
    settings.type   = discretization::Type::lagrange;
    settings.degree = degree;
    return settings;
  }

  /// Area of the circular segment of radius @p R cut off by the chord
  /// from @p a to @p b (both on the circle).
  double
  segment_area(const double R, const Point<2> &a, const Point<2> &b)
  {
    const double phi = 2. * std::asin(a.distance(b) / (2. * R));
    return R * R / 2. * (phi - std::sin(phi));
  }
} // namespace



TEST(HardCase, LagrangeHertzDiscIsValidAtTheOutputPoints)
{
  // The V5 mesh as the scene builds it (64 x 16 spans, FE_Q(2), 4 output
  // subdivisions). A valid element has det J > 0 on the closed cell; the
  // exact map has det J = 0 at the -45 degree corner, where the plain
  // interpolant gave det J(corner) / det J(centre) = -1.6e-3.
  const double                    R     = 8.;
  const auto                      patch = hertz_disc(2, 64, 16);
  discretization::LagrangeBody<2> body(description(patch), lagrange(2));
  body.setup_system();
  const auto [ratio, where] =
    body.min_jacobian_ratio(evaluation_points<2>(2, 4));
  EXPECT_GT(ratio, 0.) << "inverted near " << where;

  // The corner cell's two boundary edges are chords instead of arcs; what
  // the area loses is the two circular segments over them (from the exact
  // end points). The rest is the FE_Q(2) interpolation error of the other
  // arc edges: with the normal error R theta (theta^2 - alpha^2) theta / 6
  // on an edge of angle phi = 2 alpha, R^2 phi^5 / 720 per edge, summed
  // below R^2 (pi / 2) phi_max^4 / 720; the rational parametrisation's
  // speed varies by a few per cent over a 45-degree arc (weight
  // cos 22.5 deg), so phi_max <= 1.2 (pi / 4) / 16 with room to spare.
  const Point<2> corner = patch.value(Point<2>(1., 0.));
  const double   segments =
    segment_area(R, patch.value(Point<2>(63. / 64., 0.)), corner) +
    segment_area(R, corner, patch.value(Point<2>(1., 1. / 16.)));
  const double phi_max   = 1.2 * M_PI / 4. / 16.;
  const double remainder = R * R * M_PI / 2. * std::pow(phi_max, 4) / 720.;
  EXPECT_NEAR(M_PI * R * R / 4. - body.measure(), segments, remainder);
  // The segments are what the fix costs: 1.2e-5 of the area, over 300
  // times the remainder bound, so a geometry without the chords fails the
  // check above too.
  EXPECT_GT(segments, 5. * remainder);
}



TEST(HardCase, LagrangeHertzDiscIsValidOnEveryMesh)
{
  // The sign of the plain interpolant's det J at the corner is
  // interpolation error: negative for FE_Q(2) and FE_Q(3) from 4 spans
  // along the lower arc on, for FE_Q(4) on the coarsest meshes. Making the
  // whole corner cell bilinear instead folds the cubic and quartic
  // neighbours (the first cell row is a fan of slivers there, whose
  // thickness grows like the square of the distance to the corner, and a
  // straight shared edge with equally spaced nodes does not fit their
  // exact interior nodes). The transfinite corner cell is valid for every
  // degree and mesh; FE_Q(1) was always valid.
  for (unsigned int degree = 1; degree <= 4; ++degree)
    for (const auto &n : std::vector<std::array<unsigned int, 2>>{{{1, 1}},
                                                                  {{4, 1}},
                                                                  {{4, 4}},
                                                                  {{16, 4}},
                                                                  {{64, 16}},
                                                                  {{128, 32}}})
      {
        if (degree > 2 && n[0] > 64)
          continue; // 64 x 16 already has the sliver fan; keep Debug quick
        discretization::LagrangeBody<2> body(description(
                                               hertz_disc(degree, n[0], n[1])),
                                             lagrange(degree));
        body.setup_system();
        const auto [ratio, where] =
          body.min_jacobian_ratio(evaluation_points<2>(degree, 8));
        EXPECT_GT(ratio, 0.) << "FE_Q(" << degree << "), " << n[0] << " x "
                             << n[1] << " spans: inverted near " << where;
      }
}



TEST(HardCase, LagrangeHertzDiscNodesOnTheExactArc)
{
  // Against the exact geometry: every node of the two arc faces (1, 2)
  // lies on the circle of radius R around (0, R), except the inner nodes of
  // the two chords at the -45 degree corner (degree - 1 each), which lie
  // inside it by less than the chord's sagitta R (1 - cos(phi / 2)).
  const double R = 8.;
  for (const unsigned int degree : {2u, 3u})
    {
      const auto                      patch = hertz_disc(degree, 64, 16);
      discretization::LagrangeBody<2> body(description(patch),
                                           lagrange(degree));
      body.setup_system();
      const Point<2>                centre(0., R);
      const Point<2>                corner = patch.value(Point<2>(1., 0.));
      const std::array<Point<2>, 2> far_ends{
        {patch.value(Point<2>(63. / 64., 0.)),
         patch.value(Point<2>(1., 1. / 16.))}};
      for (const unsigned int face : {2u, 1u})
        {
          const Point<2> &far_end = far_ends[face == 2 ? 0 : 1];
          const double    phi =
            2. * std::asin(far_end.distance(corner) / (2. * R));
          const double sagitta  = R * (1. - std::cos(phi / 2.));
          unsigned int n_inside = 0;
          for (const auto &p : body.surface_points(face))
            {
              const double depth = R - p.location.distance(centre);
              if (std::abs(depth) <= 1e-12 * R)
                continue;
              ++n_inside;
              EXPECT_GT(depth, 0.) << "node " << p.location << " outside";
              EXPECT_LE(depth, sagitta + 1e-12 * R) << "node " << p.location;
              // On the chord: between its end points.
              EXPECT_NEAR(p.location.distance(corner) +
                            p.location.distance(far_end),
                          corner.distance(far_end),
                          1e-12 * R);
            }
          EXPECT_EQ(n_inside, degree - 1) << "face " << face;
        }
    }
}



TEST(HardCase, LagrangeExtrudedHertzDiscIsValid)
{
  // The same disc extruded along z (degree 1, height 2): the singular
  // vertex becomes a singular edge, and the corner cells' faces and lines
  // that touch it take the transfinite interpolation in 3D. The volume is
  // the 2D FE_Q area times the height (the map is linear in z).
  const double height = 2.;
  for (const unsigned int degree : {2u, 3u})
    {
      const auto            disc = hertz_disc(degree, 16, 4);
      std::vector<Point<3>> points;
      std::vector<double>   weights;
      for (unsigned int k = 0; k < 2; ++k)
        for (unsigned int a = 0; a < disc.n_control_points(); ++a)
          {
            const Point<2> &p = disc.control_point(a);
            points.emplace_back(p[0], p[1], k * height);
            weights.push_back(disc.weight(a));
          }
      const nurbs::NurbsPatch<3> cylinder(
        {{disc.knot_vector(0),
          disc.knot_vector(1),
          nurbs::KnotVector(1, {0., 0., 1., 1.})}},
        points,
        weights);
      discretization::LagrangeBody<3> body(description(cylinder),
                                           lagrange(degree));
      body.setup_system();
      const auto [ratio, where] =
        body.min_jacobian_ratio(evaluation_points<3>(degree, 4));
      EXPECT_GT(ratio, 0.) << "FE_Q(" << degree << "): inverted near " << where;

      discretization::LagrangeBody<2> section(description(disc),
                                              lagrange(degree));
      section.setup_system();
      EXPECT_NEAR(body.measure(),
                  height * section.measure(),
                  1e-12 * body.measure());
    }
}



TEST(HardCase, LagrangeMinJacobianRatioOfBilinearCells)
{
  // The measure itself, against a closed form: for FE_Q(1) on the one-cell
  // disc the geometry is the bilinear map of the four exact corners, whose
  // det J is affine in the unit coordinates: smallest at a vertex, where
  // it is the cross product of the two edges, and at the centre the mean of
  // the four vertex values.
  const auto                      patch = hertz_disc(1, 1, 1);
  discretization::LagrangeBody<2> body(description(patch), lagrange(1));
  body.setup_system();
  std::array<Point<2>, 4> x;
  for (unsigned int v = 0; v < 4; ++v)
    x[v] = patch.value(Point<2>(v % 2, v / 2));
  const auto cross = [](const Tensor<1, 2> &a, const Tensor<1, 2> &b) {
    return a[0] * b[1] - a[1] * b[0];
  };
  const std::array<double, 4> det{{cross(x[1] - x[0], x[2] - x[0]),
                                   cross(x[1] - x[0], x[3] - x[1]),
                                   cross(x[3] - x[2], x[2] - x[0]),
                                   cross(x[3] - x[2], x[3] - x[1])}};
  const double                mean = (det[0] + det[1] + det[2] + det[3]) / 4.;
  const double expected = *std::min_element(det.begin(), det.end()) / mean;
  EXPECT_NEAR(body.min_jacobian_ratio(evaluation_points<2>(1, 4)).first,
              expected,
              1e-12);
}



TEST(HardCase, LagrangePlateWithHoleIsValidAtItsCorner)
{
  // V1's geometry (prm/v1-plate-with-hole.prm: hole radius 1, L = 4): the
  // map has zero speed at the corner (L, L), a cell vertex; the plain
  // interpolant had det J = 0 exactly there. The lines touching the corner
  // are straight in the exact geometry (the outer edges, the diagonal), so
  // the transfinite cells keep it; the hole is an interpolated arc of
  // relative area error far below 1e-6.
  for (const unsigned int degree : {2u, 3u, 4u})
    {
      nurbs::NurbsPatch<2> patch = nurbs::make_plate_with_hole(1., 4.);
      nurbs::elevate_to_degree(patch, degree);
      nurbs::subdivide(patch, std::array<unsigned int, 2>{{8, 8}});
      discretization::LagrangeBody<2> body(description(patch),
                                           lagrange(degree));
      body.setup_system();
      const auto [ratio, where] =
        body.min_jacobian_ratio(evaluation_points<2>(degree, 4));
      EXPECT_GT(ratio, 0.) << "FE_Q(" << degree << "): inverted near " << where;
      const double exact = 16. - M_PI / 4.;
      EXPECT_NEAR(body.measure(), exact, 1e-6 * exact);
    }
}
