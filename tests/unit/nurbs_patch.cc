// Unit tests of NURBS patches: rational basis, refinement invariance, exact
// geometries of the builders, closest points and normals, parametric mesh.
#include <igabde/nurbs/geometry_builders.h>
#include <igabde/nurbs/nurbs_patch.h>
#include <igabde/nurbs/parametric_mesh.h>

#include <deal.II/grid/tria.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace dealii;
using namespace igabde::nurbs;

namespace
{
  template <int dim>
  std::vector<Point<dim>>
  random_parametric_points(const NurbsPatch<dim> &patch,
                           const unsigned int     n,
                           const unsigned int     seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> unit(0., 1.);
    std::vector<Point<dim>>                xi(n);
    for (auto &x : xi)
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = patch.parametric_lower()[d] +
               unit(rng) *
                 (patch.parametric_upper()[d] - patch.parametric_lower()[d]);
    // The corners and edges too.
    xi.push_back(patch.parametric_lower());
    xi.push_back(patch.parametric_upper());
    return xi;
  }

  // A curved 2D patch with unequal weights and an interior knot.
  NurbsPatch<2>
  wavy_patch()
  {
    NurbsPatch<2> p = make_plate_with_hole(1., 4.);
    return p;
  }

  template <int dim>
  void
  expect_same_map(const NurbsPatch<dim> &a,
                  const NurbsPatch<dim> &b,
                  const double           tol)
  {
    for (const auto &xi : random_parametric_points(a, 100, 3))
      {
        const Point<dim> xa = a.value(xi), xb = b.value(xi);
        EXPECT_LT((xa - xb).norm(), tol) << "at xi = " << xi;
        EXPECT_LT((a.jacobian(xi) - b.jacobian(xi)).norm(),
                  1e3 * tol * (1. + a.jacobian(xi).norm()))
          << "at xi = " << xi;
      }
  }
} // namespace



TEST(NurbsPatch, RationalBasisPartitionOfUnityAndGradients)
{
  const NurbsPatch<2> plate = wavy_patch();
  NurbsPatch<3>       beam  = make_curved_beam(4., 5., 1.);
  elevate_to_degree(beam, 2);
  beam.refine_uniformly(1);

  auto check = [](const auto &patch) {
    constexpr int dim = std::decay_t<decltype(patch)>::dimension;
    for (const auto &xi : random_parametric_points(patch, 50, 11))
      {
        std::vector<unsigned int>   idx;
        std::vector<double>         R;
        std::vector<Tensor<1, dim>> dR;
        patch.basis(xi, idx, R, &dR);
        double         sum = 0.;
        Tensor<1, dim> dsum;
        for (unsigned int l = 0; l < R.size(); ++l)
          {
            EXPECT_GE(R[l], -1e-15);
            sum += R[l];
            dsum += dR[l];
          }
        EXPECT_NEAR(sum, 1., 1e-14);
        EXPECT_LT(dsum.norm(), 1e-11);

        // Finite differences of the map x(xi) against the Jacobian.
        const Tensor<2, dim> J = patch.jacobian(xi);
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double h  = 1e-6;
            Point<dim>   xp = xi, xm = xi;
            xp[d] = std::min(xi[d] + h, patch.parametric_upper()[d]);
            xm[d] = std::max(xi[d] - h, patch.parametric_lower()[d]);
            const Tensor<1, dim> fd =
              (patch.value(xp) - patch.value(xm)) / (xp[d] - xm[d]);
            for (unsigned int i = 0; i < dim; ++i)
              EXPECT_NEAR(J[i][d], fd[i], 1e-5 * (1. + std::abs(fd[i])));
          }
      }
  };
  check(plate);
  check(beam);
}



TEST(NurbsPatch, KnotInsertionAndElevationKeepTheMap)
{
  {
    const NurbsPatch<2> original = make_plate_with_hole(1., 4.);
    NurbsPatch<2>       refined  = original;
    refined.insert_knots(0, {0.25, 0.6, 0.6});
    refined.insert_knots(1, {0.1, 0.5, 0.77});
    EXPECT_EQ(refined.n_control_points(0), 6u);
    EXPECT_EQ(refined.n_control_points(1), 7u);
    expect_same_map(original, refined, 1e-13);

    NurbsPatch<2> elevated = original;
    elevated.elevate_degree(0, 1);
    elevated.elevate_degree(1, 2);
    EXPECT_EQ(elevated.degree(0), 3u);
    EXPECT_EQ(elevated.degree(1), 4u);
    // Continuity kept: the interior knot now has multiplicity 3 (C1).
    EXPECT_EQ(elevated.knot_vector(1).multiplicities(),
              (std::vector<unsigned int>{5, 3, 5}));
    expect_same_map(original, elevated, 1e-13);

    NurbsPatch<2> k = original;
    elevate_to_degree(k, 3);
    k.refine_uniformly(2);
    expect_same_map(original, k, 1e-13);
  }
  {
    const NurbsPatch<3> original = make_curved_beam(4., 5., 1.);
    NurbsPatch<3>       k        = original;
    elevate_to_degree(k, 3);
    subdivide(k, {{2, 3, 2}});
    EXPECT_EQ(k.knot_vector(1).n_spans(), 3u);
    k.refine_uniformly(1);
    expect_same_map(original, k, 1e-13);
  }
}



TEST(NurbsPatch, PolynomialPatchStaysPolynomial)
{
  // Elevation and knot insertion act on the homogeneous points (w P, w);
  // the new weights are sums of old ones with coefficients that add up to
  // one only to round-off. A patch whose weights are all equal must keep
  // them exactly equal: a weight of 1 - 1e-16 makes a box count as
  // rational, with its p+2 Gauss points per direction in every cell and
  // its 12-point measure rule.
  NurbsPatch<3> box = make_box(Point<3>(0., 0., 0.), Point<3>(1., 1., 0.1));
  elevate_to_degree(box, 3);
  subdivide(box, {{7, 5, 3}});
  box.refine_uniformly(2);
  for (unsigned int a = 0; a < box.n_control_points(); ++a)
    ASSERT_EQ(box.weight(a), 1.) << "control point " << a;
  expect_same_map(make_box(Point<3>(0., 0., 0.), Point<3>(1., 1., 0.1)),
                  box,
                  1e-13);

  // A rational patch keeps its varying weights.
  NurbsPatch<2> plate = make_plate_with_hole(1., 4.);
  elevate_to_degree(plate, 3);
  plate.refine_uniformly(1);
  bool varying = false;
  for (unsigned int a = 1; a < plate.n_control_points(); ++a)
    varying = varying || std::abs(plate.weight(a) - plate.weight(0)) > 1e-3;
  EXPECT_TRUE(varying);
}



TEST(NurbsPatch, GradedSubdivisionIsGeometricAndKeepsTheMap)
{
  // Four parts graded 8 toward the low end: q = 8^(1/3) = 2, parts h, 2h,
  // 4h, 8h with 15 h = 1, breakpoints 0, 1/15, 3/15, 7/15, 1; toward the
  // high end the mirror image 0, 8/15, 12/15, 14/15, 1 (hand derivation).
  NurbsPatch<2> box = make_box<2>(Point<2>(0., 0.), Point<2>(1., 1.));
  elevate_to_degree(box, 2);
  const NurbsPatch<2> original = box;
  subdivide(box, {{4, 4}}, {{8., 8.}}, {{false, true}});
  const std::vector<double> low = box.breakpoints(0), high = box.breakpoints(1);
  const std::vector<double> expected_low  = {0., 1., 3., 7., 15.};
  const std::vector<double> expected_high = {0., 8., 12., 14., 15.};
  ASSERT_EQ(low.size(), 5u);
  ASSERT_EQ(high.size(), 5u);
  for (unsigned int j = 0; j < 5; ++j)
    {
      EXPECT_NEAR(low[j], expected_low[j] / 15., 1e-14);
      EXPECT_NEAR(high[j], expected_high[j] / 15., 1e-14);
    }
  expect_same_map(original, box, 1e-13);

  // On the plate with a hole (two base spans around the hole, direction 1)
  // the base
  // breakpoint 0.5 stays and the graded knots are laid over the whole
  // direction: 2 x 3 = 6 graded parts, plus the base breakpoint where no
  // graded knot falls.
  const NurbsPatch<2> plate  = make_plate_with_hole(1., 4.);
  NurbsPatch<2>       graded = plate;
  subdivide(graded, {{1, 3}}, {{1., 4.}});
  const std::vector<double> b = graded.breakpoints(1);
  EXPECT_NE(std::find(b.begin(), b.end(), 0.5), b.end());
  EXPECT_EQ(b.size(), 8u);
  expect_same_map(plate, graded, 1e-13);
}



TEST(NurbsPatch, BandGradedSubdivisionRefinesTheBandAndKeepsTheMap)
{
  // 40 parts toward the band [0.45, 0.55] with ratio 8: parts of one size
  // h inside the band, growing by the factor 1.25 per part away from it
  // (the size law h + (2/9) dist: a part D centred at distance t has
  // D = h + (2/9) t, its neighbour D' = D + (2/9)(D + D') / 2, so
  // D' / D = (1 + 1/9) / (1 - 1/9) = 1.25 exactly), capped at 8 h. The
  // density integral is evaluated on a grid of 1/20000 (trapezoids on a
  // smooth density), well under 1e-3 of the smallest part (about 0.01);
  // the ratios of neighbours within 1e-2. The part that straddles the cap
  // or the band's edge grows less.
  const std::vector<double> f = band_graded_fractions(40, 0.45, 0.55, 8.);
  ASSERT_EQ(f.size(), 39u);
  std::vector<double> parts;
  double              previous = 0.;
  for (const double x : f)
    {
      parts.push_back(x - previous);
      previous = x;
    }
  parts.push_back(1. - previous);
  const double smallest = *std::min_element(parts.begin(), parts.end());
  const double largest  = *std::max_element(parts.begin(), parts.end());
  EXPECT_NEAR(largest / smallest, 8., 0.01 * 8.);
  double start = 0.;
  for (unsigned int k = 0; k < parts.size(); ++k)
    {
      const double end = start + parts[k];
      if (start >= 0.45 && end <= 0.55)
        {
          EXPECT_NEAR(parts[k], smallest, 1e-3 * smallest);
        }
      if (k + 1 < parts.size())
        {
          const double ratio = parts[k + 1] / parts[k];
          EXPECT_LE(std::max(ratio, 1. / ratio), 1.25 + 1e-2);
        }
      start = end;
    }
  // Symmetric band, symmetric parts.
  for (unsigned int k = 0; k < parts.size(); ++k)
    EXPECT_NEAR(parts[k], parts[parts.size() - 1 - k], 1e-3 * smallest);

  // On the half disc along its arc: the map stays, the band's spans are
  // the smallest.
  NurbsPatch<2> disc = make_half_disc(Point<2>(0., 8.), 8.);
  elevate_to_degree(disc, 2);
  NurbsPatch<2> graded = disc;
  subdivide(graded,
            {{40, 4}},
            {{8., 1.}},
            {{false, false}},
            {{{{0.45, 0.55}}, {{0., 0.}}}});
  expect_same_map(disc, graded, 1e-12);
  const std::vector<double> b = graded.breakpoints(0);
  EXPECT_EQ(b.size(), 41u);
}



TEST(NurbsBuilders, CirclesAreExact)
{
  std::mt19937                           rng(5);
  std::uniform_real_distribution<double> unit(0., 1.);

  // Quarter annulus: faces 0 and 1 are arcs.
  {
    NurbsPatch<2> annulus = make_quarter_annulus(1., 2.);
    for (unsigned int level = 0; level < 3; ++level)
      {
        for (unsigned int s = 0; s < 100; ++s)
          {
            const double t = unit(rng);
            EXPECT_NEAR(annulus.value(Point<2>(0., t)).norm(), 1., 1e-14);
            EXPECT_NEAR(annulus.value(Point<2>(1., t)).norm(), 2., 1e-14);
            const Point<2> x = annulus.value(Point<2>(unit(rng), t));
            EXPECT_GE(x.norm(), 1. - 1e-14);
            EXPECT_LE(x.norm(), 2. + 1e-14);
            // Normals: inward on the hole side, outward on the outer arc.
            const Tensor<1, 2> n0 = annulus.outward_normal(0, Point<2>(0., t));
            const Point<2>     x0 = annulus.value(Point<2>(0., t));
            EXPECT_NEAR((n0 + x0 / x0.norm()).norm(), 0., 1e-13);
            const Tensor<1, 2> n1 = annulus.outward_normal(1, Point<2>(1., t));
            const Point<2>     x1 = annulus.value(Point<2>(1., t));
            EXPECT_NEAR((n1 - x1 / x1.norm()).norm(), 0., 1e-13);
          }
        EXPECT_EQ(annulus.orientation(), 1.);
        elevate_to_degree(annulus, 2 + level);
        annulus.refine_uniformly(1);
      }
    // Straight faces.
    const Tensor<1, 2> n2 = annulus.outward_normal(2, Point<2>(0.3, 0.));
    EXPECT_NEAR(n2[1], -1., 1e-14);
    const Tensor<1, 2> n3 = annulus.outward_normal(3, Point<2>(0.3, 1.));
    EXPECT_NEAR(n3[0], -1., 1e-14);
  }

  // Plate with hole: face 0 is the hole, face 1 the outer square edges.
  {
    const NurbsPatch<2> plate = make_plate_with_hole(1., 4.);
    EXPECT_EQ(plate.orientation(), 1.);
    for (unsigned int s = 0; s < 100; ++s)
      {
        const double t = unit(rng);
        EXPECT_NEAR(plate.value(Point<2>(0., t)).norm(), 1., 1e-14);
        const Point<2> x = plate.value(Point<2>(1., t));
        EXPECT_NEAR(std::max(x[0], x[1]), 4., 1e-14);
        EXPECT_NEAR(plate.value(Point<2>(t, 0.))[1], 0., 1e-14);
        EXPECT_NEAR(plate.value(Point<2>(t, 1.))[0], 0., 1e-14);
        const Tensor<1, 2> n0 = plate.outward_normal(0, Point<2>(0., t));
        const Point<2>     x0 = plate.value(Point<2>(0., t));
        EXPECT_NEAR((n0 + x0 / x0.norm()).norm(), 0., 1e-13);
      }
    // The published control net at R = 1, L = 4.
    EXPECT_NEAR(plate.control_point(4)[0], 2.5, 1e-15);
    EXPECT_NEAR(plate.control_point(4)[1], 0.75, 1e-15);
    EXPECT_NEAR(plate.weight(3), (1. + 1. / std::sqrt(2.)) / 2., 1e-15);
  }

  // Hertz quarter disc: faces 1 and 2 are arcs about (0, R).
  {
    const double        R    = 8.;
    const Point<2>      c    = Point<2>(0., R);
    const NurbsPatch<2> disc = make_hertz_quarter_disc(R);
    EXPECT_EQ(disc.orientation(), 1.);
    EXPECT_NEAR(disc.value(Point<2>(0., 0.)).norm(), 0., 1e-14);
    for (unsigned int s = 0; s <= 100; ++s)
      {
        const double   t     = s / 100.;
        const Point<2> lower = disc.value(Point<2>(t, 0.));
        const Point<2> upper = disc.value(Point<2>(1., t));
        EXPECT_NEAR((lower - c).norm(), R, 1e-13);
        EXPECT_NEAR((upper - c).norm(), R, 1e-13);
        EXPECT_LE(lower[0], R / std::sqrt(2.) + 1e-13);
        EXPECT_GE(upper[0], R / std::sqrt(2.) - 1e-13);
        EXPECT_NEAR(disc.value(Point<2>(0., t))[0], 0., 1e-14);
        EXPECT_NEAR(disc.value(Point<2>(t, 1.))[1], R, 1e-14);
        const Tensor<1, 2> n = disc.outward_normal(2, Point<2>(t, 0.));
        EXPECT_NEAR((n - (lower - c) / R).norm(), 0., 1e-13);
        // det J > 0 except at the corner xi = (1, 0), the 45-degree point,
        // where the two arcs meet at a straight angle (J has rank 1 there).
        for (unsigned int r = 0; r <= 20; ++r)
          if (s < 100 || r > 0)
            {
              EXPECT_GT(determinant(disc.jacobian(Point<2>(t, r / 20.))), 0.)
                << "det J <= 0 at (" << t << ", " << r / 20. << ")";
            }
      }
  }

  // Curved beam: arcs in the x-z plane, y along the width.
  {
    const NurbsPatch<3> beam = make_curved_beam(4., 5., 1.);
    EXPECT_EQ(beam.orientation(), -1.);
    for (unsigned int s = 0; s < 50; ++s)
      {
        const double   t = unit(rng), y = unit(rng);
        const Point<3> x = beam.value(Point<3>(1., t, y));
        EXPECT_NEAR(std::hypot(x[0], x[2]), 5., 1e-14);
        EXPECT_NEAR(x[1], y, 1e-14);
        const Tensor<1, 3> n  = beam.outward_normal(0, Point<3>(0., t, y));
        const Point<3>     x0 = beam.value(Point<3>(0., t, y));
        const Tensor<1, 3> radial({x0[0] / 4., 0., x0[2] / 4.});
        EXPECT_NEAR((n + radial).norm(), 0., 1e-13);
        EXPECT_NEAR(beam.outward_normal(2, Point<3>(t, 0., y))[2], -1., 1e-14);
        EXPECT_NEAR(beam.outward_normal(5, Point<3>(t, y, 1.))[1], 1., 1e-14);
      }
    EXPECT_NEAR(beam.value(Point<3>(1., 1., 0.))[2], 5., 1e-14);
  }
}



TEST(NurbsPatch, ClosestPoints)
{
  NurbsPatch<2> annulus = make_quarter_annulus(1., 2.);
  elevate_to_degree(annulus, 2);
  annulus.refine_uniformly(2);
  // A point outside the outer arc projects radially.
  const Point<2> x(2.5 * std::cos(0.4), 2.5 * std::sin(0.4));
  const Point<2> xi = annulus.closest_point_on_face(1, x);
  EXPECT_EQ(xi[0], 1.);
  const Point<2> y = annulus.value(xi);
  EXPECT_NEAR(y[0], 2. * std::cos(0.4), 1e-12);
  EXPECT_NEAR(y[1], 2. * std::sin(0.4), 1e-12);
  // Inversion of the map at an interior point.
  const Point<2> target = annulus.value(Point<2>(0.37, 0.81));
  double         dist   = 1.;
  const Point<2> back =
    annulus.closest_parametric_point(target, nullptr, &dist);
  EXPECT_LT(dist, 1e-13);
  EXPECT_NEAR(back[0], 0.37, 1e-12);
  EXPECT_NEAR(back[1], 0.81, 1e-12);
  // A boundary point and a point outside.
  const Point<2> on_edge =
    annulus.closest_parametric_point(Point<2>(1.5, 0.), nullptr, &dist);
  EXPECT_LT(dist, 1e-13);
  EXPECT_NEAR(on_edge[1], 0., 1e-14);
  annulus.closest_parametric_point(Point<2>(3., 3.), nullptr, &dist);
  EXPECT_NEAR(dist, 3. * std::sqrt(2.) - 2., 1e-10);

  // 3D: a point above the contact face r = 5 of the curved beam.
  const NurbsPatch<3> beam = make_curved_beam(5., 6., 1.);
  const Point<3>      z(4.9 * std::cos(0.7), 0.3, 4.9 * std::sin(0.7));
  const Point<3>      zeta = beam.closest_point_on_face(0, z);
  const Point<3>      w    = beam.value(zeta);
  EXPECT_NEAR(w[0], 5. * std::cos(0.7), 1e-11);
  EXPECT_NEAR(w[1], 0.3, 1e-11);
  EXPECT_NEAR(w[2], 5. * std::sin(0.7), 1e-11);
}



// A start near the answer (the nearest of a face's pair points) searches
// only the spans around it; the answer is the whole face's, and a start on
// the wrong side of the face still finds it (the whole face is searched
// when Newton leaves the spans around the start).
TEST(NurbsPatch, ClosestPointOnFaceFromANearStart)
{
  NurbsPatch<3> beam = make_curved_beam(5., 6., 1.);
  elevate_to_degree(beam, 2);
  subdivide(beam, std::array<unsigned int, 3>{{2, 16, 6}});
  std::mt19937                           random(7);
  std::uniform_real_distribution<double> unit(0., 1.);
  for (unsigned int k = 0; k < 20; ++k)
    {
      const double   t = 0.05 + 1.4 * unit(random), y = unit(random);
      const Point<3> x(4.8 * std::cos(t), y, 4.8 * std::sin(t));
      const Point<3> whole = beam.closest_point_on_face(0, x);
      // Near: a point of the face about one span away.
      Point<3> near        = whole;
      near[1]              = std::min(1., whole[1] + 0.06);
      near[2]              = std::max(0., whole[2] - 0.1);
      const Point<3> local = beam.closest_point_on_face(0, x, &near);
      EXPECT_LT((beam.value(local) - beam.value(whole)).norm(), 1e-11) << k;
      // A start at the far end of the face.
      Point<3> far            = whole;
      far[1]                  = (whole[1] < 0.5 ? 1. : 0.);
      far[2]                  = (whole[2] < 0.5 ? 1. : 0.);
      const Point<3> from_far = beam.closest_point_on_face(0, x, &far);
      EXPECT_LT((beam.value(from_far) - beam.value(whole)).norm(), 1e-11) << k;
      EXPECT_NEAR((beam.value(whole) - x).norm(), 0.2, 1e-11);
    }
}



TEST(NurbsParametricMesh, CellsAreKnotSpans)
{
  NurbsPatch<2> plate = make_plate_with_hole(1., 4.);
  plate.insert_knots(0, {0.2, 0.2});
  Triangulation<2> tria;
  make_parametric_triangulation(plate, tria);
  EXPECT_EQ(tria.n_active_cells(), 2u * 2u);
  std::set<std::pair<unsigned int, unsigned int>> seen;
  for (const auto &cell : tria.active_cell_iterators())
    {
      const auto span = span_of_cell(plate, cell);
      seen.insert({span[0], span[1]});
      const auto b0 = plate.breakpoints(0), b1 = plate.breakpoints(1);
      EXPECT_NEAR(cell->vertex(0)[0], b0[span[0]], 1e-15);
      EXPECT_NEAR(cell->vertex(3)[1], b1[span[1] + 1], 1e-15);
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            EXPECT_EQ(cell->face(f)->boundary_id(), f);
          }
    }
  EXPECT_EQ(seen.size(), 4u);
}



// The tensor-grid evaluation against value() point by point, on rational
// patches of both dimensions (the plate with a hole, the curved beam) and
// at knots, span midpoints and the ends (where the spans switch): the same
// sums in another order, so equal to round-off.
TEST(NurbsPatch, ValuesOnGridEqualPointwiseValues)
{
  const auto check = [](const auto &patch) {
    constexpr int dim = std::decay_t<decltype(patch)>::dimension;
    std::array<std::vector<double>, dim> coordinates;
    for (int d = 0; d < dim; ++d)
      {
        const auto breaks = patch.breakpoints(d);
        for (unsigned int e = 0; e + 1 < breaks.size(); ++e)
          {
            coordinates[d].push_back(breaks[e]);
            coordinates[d].push_back(0.3 * breaks[e] + 0.7 * breaks[e + 1]);
          }
        coordinates[d].push_back(breaks.back());
      }
    const auto grid = patch.values_on_grid(coordinates);
    double     size = 0.;
    for (const auto &x : grid)
      size = std::max(size, x.norm());
    std::size_t q = 0;
    for (std::size_t k = 0; k < (dim == 3 ? coordinates[2].size() : 1); ++k)
      for (std::size_t j = 0; j < coordinates[1].size(); ++j)
        for (std::size_t i = 0; i < coordinates[0].size(); ++i, ++q)
          {
            Point<dim> xi;
            xi[0] = coordinates[0][i];
            xi[1] = coordinates[1][j];
            if constexpr (dim == 3)
              xi[2] = coordinates[2][k];
            EXPECT_LE(grid[q].distance(patch.value(xi)), 1e-14 * size);
          }
    EXPECT_EQ(q, grid.size());
  };
  NurbsPatch<2> plate = make_plate_with_hole(1., 4.);
  plate.refine_uniformly(2);
  check(plate);
  check(make_curved_beam(4., 5., 1.));
}
