// The Lagrange path on the geometries of the scenes, including the
// left-handed curved-beam patch (which the FE_Q mesh must use reflected):
// positive Jacobians, the right volume, faces that keep their patch ids;
// points outside a body are not in it.

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
  using namespace igabde;
  using namespace dealii;
} // namespace



TEST(LagrangeBody, CurvedBeamVolumeAndFaces)
{
  // Quarter annulus 5 <= r <= 6 in the x-z plane, extruded by 1 in y.
  discretization::BodyDescription<3> d;
  d.geometry = nurbs::make_curved_beam(5., 6., 1.);
  nurbs::elevate_to_degree(d.geometry, 2);
  nurbs::subdivide(d.geometry, std::array<unsigned int, 3>{{2, 4, 2}});
  discretization::DirichletCondition<3> clamp; // theta = 0, the z = 0 end
  clamp.boundary_id   = 2;
  clamp.components[0] = clamp.components[1] = clamp.components[2] = true;
  d.dirichlet.push_back(clamp);

  discretization::DiscretizationSettings settings;
  settings.type   = discretization::Type::lagrange;
  settings.degree = 2;
  auto body       = discretization::create_body<3>(d, settings);
  body->setup();

  // Quadratic interpolation of 22.5-degree arcs: relative volume error of
  // order (pi/8)^4 / 100, about 2e-4; the sign would flip for a mesh with
  // negative Jacobians.
  const double exact = M_PI * (36. - 25.) / 4.;
  EXPECT_NEAR(body->measure(), exact, 1e-3 * exact);

  // Face ids keep their patch meaning: face 4 is y = 0, face 5 is y = 1,
  // face 0 is r = 5 with the outward normal pointing to the axis.
  for (const unsigned int face : {4u, 5u})
    for (const auto &p : body->surface_points(face))
      {
        EXPECT_NEAR(p.location[1], face == 4 ? 0. : 1., 1e-12);
        EXPECT_NEAR(p.normal[1], face == 4 ? -1. : 1., 1e-8);
      }
  for (const auto &p : body->surface_points(0))
    {
      const double r = std::hypot(p.location[0], p.location[2]);
      EXPECT_NEAR(r, 5., 1e-12);
      EXPECT_LT(p.normal[0] * p.location[0] + p.normal[2] * p.location[2], 0.);
    }
}



TEST(LagrangeBody, ContainsOnlyItsOwnPoints)
{
  // The probes of a two-body scene are looked for body by body: a point of
  // Body 2 must be "not contained" in Body 1 on both discretisations (the
  // FE_Q path used to dereference deal.II's invalid "not found" iterator).
  discretization::BodyDescription<3> d;
  d.geometry = nurbs::make_box<3>(Point<3>(0., 0., 1.), Point<3>(6., 1., 2.));
  nurbs::elevate_to_degree(d.geometry, 2);
  nurbs::subdivide(d.geometry, std::array<unsigned int, 3>{{4, 2, 2}});
  for (const auto type :
       {discretization::Type::lagrange, discretization::Type::nurbs})
    {
      discretization::DiscretizationSettings settings;
      settings.type   = type;
      settings.degree = 2;
      auto body       = discretization::create_body<3>(d, settings);
      body->setup();
      EXPECT_TRUE(body->contains(Point<3>(0., 0., 2.))) << to_string(type);
      EXPECT_TRUE(body->contains(Point<3>(3., 0.5, 1.5))) << to_string(type);
      EXPECT_FALSE(body->contains(Point<3>(6., 0., 0.))) << to_string(type);
      EXPECT_FALSE(body->contains(Point<3>(3., 0.5, 0.5))) << to_string(type);
    }
}



// The curved beam is left-handed, so the FE_Q mesh runs its last direction
// (y) backwards. With that direction graded (4 spans, ratio 8, toward
// y = 0), the mesh's cells must still be the patch's spans: the nodes'
// y values are the breakpoints and span midpoints of the patch, not their
// mirror images 1 - y (which the mesh had before 2026-11-26: the grading
// landed at y = 1 and a face point in a span the mirrored lookup did not
// know crashed).
TEST(LagrangeBody, ReflectedMeshKeepsTheGradedSpans)
{
  discretization::BodyDescription<3> d;
  d.geometry = nurbs::make_curved_beam(5., 6., 1.);
  nurbs::elevate_to_degree(d.geometry, 2);
  nurbs::subdivide(d.geometry,
                   std::array<unsigned int, 3>{{2, 4, 4}},
                   std::array<double, 3>{{1., 1., 8.}});
  const std::vector<double> breaks = d.geometry.breakpoints(2);
  ASSERT_EQ(breaks.size(), 5u);
  ASSERT_GT(breaks[4] - breaks[3], 4. * (breaks[1] - breaks[0]));

  discretization::DiscretizationSettings settings;
  settings.type   = discretization::Type::lagrange;
  settings.degree = 2;
  auto body       = discretization::create_body<3>(d, settings);
  body->setup();

  // The extrusion is linear in the parameter: y = xi_2.
  std::vector<double> expected;
  for (unsigned int k = 0; k + 1 < breaks.size(); ++k)
    expected.insert(expected.end(),
                    {breaks[k], 0.5 * (breaks[k] + breaks[k + 1])});
  expected.push_back(breaks.back());
  std::vector<double> ys;
  for (types::global_dof_index i = 0; i < body->n_dofs(); ++i)
    ys.push_back(body->dof_location(i)[1]);
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(),
                       ys.end(),
                       [](const double a, const double b) {
                         return std::abs(a - b) < 1e-12;
                       }),
           ys.end());
  ASSERT_EQ(ys.size(), expected.size());
  for (unsigned int k = 0; k < ys.size(); ++k)
    EXPECT_NEAR(ys[k], expected[k], 1e-12) << k;

  // A face point in every span of the r = 5 face along y lies on that
  // face at the parametric y asked for.
  for (unsigned int k = 0; k + 1 < breaks.size(); ++k)
    {
      const double y = 0.5 * (breaks[k] + breaks[k + 1]);
      const auto   p = body->face_point(0, Point<2>(0.3, y));
      EXPECT_NEAR(p.location[1], y, 1e-12);
      EXPECT_NEAR(std::hypot(p.location[0], p.location[2]), 5., 1e-3);
    }
}
