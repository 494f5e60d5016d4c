// Body::move_surfaces(): the surface queries on the configuration
// x = X + u, what finite sliding pairs on. Checked against closed forms:
//  - a rigid motion x = R X + c is represented exactly by both
//    discretisations (NURBS are invariant under affine maps of their
//    control points; isoparametric FE_Q(2) elements under those of their
//    nodes), so every face point, surface point and closest point of the
//    moved body is the rigid image of the reference one: locations
//    R X + c, normals and tangents R n and R t, measures and tributary
//    areas unchanged, operators unchanged (the same material points);
//  - the weighted-gap pairs of two blocks moved by one rigid motion are
//    those of the reference blocks, moved: same gaps and areas, normals
//    rotated;
//  - a slave block slid by t along a flat master (and pressed 0.01 into
//    it): every pair's master side is the master's material at the slave's
//    moved position: sum_k w_k X_k over op2 is x1 + t, and the gap is
//    -0.01 (the tolerances: round-off, 1e-12 of the block size, and for
//    the slid pairs the 1e-10 of an element to which the weighted gap
//    brackets its element cuts).
// And against a second method: the face points' basis gradients and
// second derivatives on a curved configuration, by central differences
// of the face points themselves.

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <igabde/contact/contact_surface.h>
#include <igabde/contact/pairing.h>

#include <gtest/gtest.h>

#include "test_blocks.h"
#include <algorithm>
#include <cmath>

namespace
{
  using namespace igabde;
  using namespace dealii;
  using test_blocks::block;

  /// A rotation by 0.3 rad (about the axis (1, 2, 2) / 3 in 3D).
  template <int dim>
  Tensor<2, dim>
  rotation()
  {
    const double   a = 0.3;
    Tensor<2, dim> R;
    if constexpr (dim == 2)
      {
        R[0][0] = R[1][1] = std::cos(a);
        R[0][1]           = -std::sin(a);
        R[1][0]           = std::sin(a);
      }
    else
      {
        const Tensor<1, 3> k({1. / 3., 2. / 3., 2. / 3.});
        Tensor<2, 3>       K;
        K[0][1] = -k[2];
        K[0][2] = k[1];
        K[1][0] = k[2];
        K[1][2] = -k[0];
        K[2][0] = -k[1];
        K[2][1] = k[0];
        R       = Tensor<2, 3>(unit_symmetric_tensor<3>()) + std::sin(a) * K +
            (1. - std::cos(a)) * K * K;
      }
    return R;
  }

  /// The unknowns of the motion x = R X + c (u = (R - I) X + c at every
  /// control point or node).
  template <int dim>
  Vector<double>
  rigid_motion(const discretization::Body<dim> &body,
               const Tensor<2, dim>            &R,
               const Tensor<1, dim>            &c)
  {
    Vector<double> u(body.n_dofs());
    for (types::global_dof_index i = 0; i < body.n_dofs(); ++i)
      {
        const Point<dim>  &X = body.dof_location(i);
        const unsigned int k = body.dof_component(i);
        u[i]                 = (R * X)[k] + c[k] - X[k];
      }
    return u;
  }

  template <int dim>
  Tensor<1, dim>
  offset()
  {
    Tensor<1, dim> c;
    for (unsigned int k = 0; k < dim; ++k)
      c[k] = 0.7 - 0.4 * k;
    return c;
  }

  template <int dim>
  void
  rigid_motion_of_the_surface(const discretization::Type type)
  {
    Point<dim> lo, hi;
    for (unsigned int k = 0; k < dim; ++k)
      hi[k] = 1. + 0.5 * k;
    const auto           body  = block<dim>(type, lo, hi, 3);
    const Tensor<2, dim> R     = rotation<dim>();
    const Tensor<1, dim> c     = offset<dim>();
    const double         tol   = 1e-12;
    const auto           image = [&](const Point<dim> &X) {
      return Point<dim>(R * X + c);
    };

    const types::boundary_id    face = 2 * dim - 1;
    std::vector<Point<dim - 1>> etas;
    for (const double s : {0.1, 0.37, 0.5, 0.93})
      {
        Point<dim - 1> eta;
        for (unsigned int k = 0; k < dim - 1; ++k)
          eta[k] = s * (k + 1) / dim;
        etas.push_back(eta);
      }
    std::vector<discretization::FacePoint<dim>> reference;
    for (const auto &eta : etas)
      reference.push_back(body->face_point(face, eta));
    const auto reference_points = body->surface_points(face);

    EXPECT_FALSE(body->surfaces_moved());
    body->move_surfaces(rigid_motion(*body, R, c));
    EXPECT_TRUE(body->surfaces_moved());
    for (unsigned int i = 0; i < etas.size(); ++i)
      {
        const auto moved = body->face_point(face, etas[i]);
        EXPECT_LT(moved.location.distance(image(reference[i].location)), tol);
        EXPECT_LT((moved.normal - R * reference[i].normal).norm(), tol);
        EXPECT_NEAR(moved.measure, reference[i].measure, tol);
        for (unsigned int k = 0; k < dim - 1; ++k)
          EXPECT_LT((moved.tangents[k] - R * reference[i].tangents[k]).norm(),
                    tol);
        EXPECT_EQ(moved.op.dofs, reference[i].op.dofs);
        for (unsigned int k = 0; k < moved.op.weights.size(); ++k)
          EXPECT_NEAR(moved.op.weights[k], reference[i].op.weights[k], tol);
      }
    const auto moved_points = body->surface_points(face);
    ASSERT_EQ(moved_points.size(), reference_points.size());
    for (unsigned int i = 0; i < moved_points.size(); ++i)
      {
        EXPECT_LT(moved_points[i].location.distance(
                    image(reference_points[i].location)),
                  tol);
        EXPECT_LT(
          (moved_points[i].normal - R * reference_points[i].normal).norm(),
          tol);
        EXPECT_NEAR(moved_points[i].tributary_area,
                    reference_points[i].tributary_area,
                    tol);
      }
    if (type == discretization::Type::nurbs)
      {
        // The exact face's closest point of a point above the face.
        const auto      &near = reference_points[reference_points.size() / 2];
        const Point<dim> y    = near.location + 0.2 * near.normal;
        body->reset_surfaces();
        const auto closest = body->closest_surface_point(face, y, near);
        body->move_surfaces(rigid_motion(*body, R, c));
        const auto moved_closest =
          body->closest_surface_point(face, image(y), moved_points[0]);
        EXPECT_LT(moved_closest.location.distance(image(closest.location)),
                  tol);
        EXPECT_LT((moved_closest.normal - R * closest.normal).norm(), tol);
      }
    body->reset_surfaces();
    EXPECT_FALSE(body->surfaces_moved());
    EXPECT_LT(
      body->face_point(face, etas[1]).location.distance(reference[1].location),
      tol);
  }

  /// The weighted-gap pairs of the slave (upper, 2 spans) on the master
  /// (lower, 3 spans).
  template <int dim>
  std::vector<contact::ContactPair<dim>>
  weighted_gap_pairs(const discretization::Body<dim> &slave,
                     const discretization::Body<dim> &master)
  {
    const contact::BodyFace<dim> master_face(master, {2 * dim - 1});
    return contact::create_pairing_strategy<dim>(contact::Pairing::weighted_gap)
      ->make_pairs(slave, {2 * (dim - 1)}, master_face, "test");
  }

  template <int dim>
  void
  pairs_of_a_rigid_motion(const discretization::Type type)
  {
    Point<dim> lo, hi, mid;
    for (unsigned int k = 0; k < dim; ++k)
      hi[k] = 1.;
    mid[dim - 1]        = 1.;
    Point<dim> top      = hi;
    top[dim - 1]        = 2.;
    Point<dim> slave_lo = mid, slave_hi = top;
    for (unsigned int k = 0; k + 1 < dim; ++k)
      {
        slave_lo[k] = 0.25;
        slave_hi[k] = 0.75;
      }
    const auto master = block<dim>(type, lo, hi, 3);
    const auto slave  = block<dim>(type, slave_lo, slave_hi, 2);
    const auto pairs  = weighted_gap_pairs(*slave, *master);
    ASSERT_GT(pairs.size(), 0u);
    const double tol = 1e-12;

    // Both moved alike.
    const Tensor<2, dim> R = rotation<dim>();
    const Tensor<1, dim> c = offset<dim>();
    master->move_surfaces(rigid_motion(*master, R, c));
    slave->move_surfaces(rigid_motion(*slave, R, c));
    const auto moved = weighted_gap_pairs(*slave, *master);
    ASSERT_EQ(moved.size(), pairs.size());
    for (const auto &pair : moved)
      {
        // The reference pair whose moved point is this one's.
        const auto same =
          std::min_element(pairs.begin(),
                           pairs.end(),
                           [&](const auto &a, const auto &b) {
                             return pair.x1.distance(Point<dim>(R * a.x1 + c)) <
                                    pair.x1.distance(Point<dim>(R * b.x1 + c));
                           });
        EXPECT_LT(pair.x1.distance(Point<dim>(R * same->x1 + c)), tol);
        EXPECT_NEAR(pair.gap, same->gap, tol);
        EXPECT_NEAR(pair.area, same->area, tol);
        // The normal rotates; the tangents are a basis of its plane that
        // the frame's convention picks (not rotated with it in 3D).
        EXPECT_LT((pair.frame[0] - R * same->frame[0]).norm(), tol);
        for (unsigned int s = 1; s < dim; ++s)
          EXPECT_NEAR(pair.frame[s] * pair.frame[0], 0., tol);
      }

    // The slave slid by t along the master and pressed 0.01 into it.
    master->reset_surfaces();
    Tensor<1, dim> t;
    for (unsigned int k = 0; k + 1 < dim; ++k)
      t[k] = 0.13 + 0.04 * k;
    Tensor<1, dim> press;
    press[dim - 1] = -0.01;
    slave->move_surfaces(
      rigid_motion(*slave,
                   Tensor<2, dim>(unit_symmetric_tensor<dim>()),
                   t + press));
    const auto slid = weighted_gap_pairs(*slave, *master);
    ASSERT_EQ(slid.size(), pairs.size());
    // The master side is the (dual-)weighted mean of the master's points
    // under the slave's moved ones, x_s + t on the plane y = 1, with the
    // slave's weights: what op1 gives on the slave's reference points,
    // plus t. The element cuts are bracketed to 1e-10 of an element.
    const auto mean_location =
      [](const discretization::Body<dim>          &body,
         const discretization::PointOperator<dim> &op) {
        Point<dim> x;
        for (unsigned int k = 0; k < op.weights.size(); ++k)
          for (unsigned int comp = 0; comp < dim; ++comp)
            x[comp] +=
              op.weights[k] * body.dof_location(op.dofs[k][comp])[comp];
        return x;
      };
    for (const auto &pair : slid)
      {
        Point<dim> expected = mean_location(*slave, pair.op1) + t;
        expected[dim - 1]   = 1.;
        EXPECT_LT(mean_location(*master, pair.op2).distance(expected), 1e-10);
        EXPECT_NEAR(pair.gap, -0.01, 1e-10);
      }
    slave->reset_surfaces();
  }

  /// The face points' derivatives by the face coordinates on a curved
  /// configuration (a smooth non-affine displacement): the operator's
  /// gradients (FacePoint::gradients) against central differences of its
  /// weights, and face_second_derivatives() against central differences
  /// of the tangents, at points inside the elements. Steps h = 1e-5 of the
  /// face: the differences err by h^2 times third derivatives (of order
  /// one here) and by round-off 1e-16 / h, so 1e-8 bounds both by a margin
  /// of 100.
  template <int dim>
  void
  face_derivatives_agree_with_differences(const discretization::Type type)
  {
    Point<dim> lo, hi;
    for (unsigned int k = 0; k < dim; ++k)
      hi[k] = 1. + 0.5 * k;
    const auto     body = block<dim>(type, lo, hi, 3);
    Vector<double> u(body->n_dofs());
    for (types::global_dof_index i = 0; i < body->n_dofs(); ++i)
      {
        const Point<dim> &X = body->dof_location(i);
        u[i] = 0.05 * std::sin(2. * X[0] + X[dim - 1] + body->dof_component(i));
      }
    body->move_surfaces(u);
    const types::boundary_id face = 2 * dim - 1;
    const auto               grid = body->face_grid(face);
    const double             h    = 1e-5;
    for (const double s : {0.1, 0.37, 0.55, 0.93})
      {
        Point<dim - 1> eta;
        for (unsigned int k = 0; k < dim - 1; ++k)
          eta[k] =
            grid.breaks[k].front() +
            (s + 0.02 * k) * (grid.breaks[k].back() - grid.breaks[k].front());
        const auto point  = body->face_point(face, eta);
        const auto second = body->face_second_derivatives(face, eta);
        ASSERT_EQ(point.gradients.size(), point.op.weights.size());
        for (unsigned int b = 0; b + 1 < dim; ++b)
          {
            Point<dim - 1> up = eta, down = eta;
            up[b] += h;
            down[b] -= h;
            const auto pu = body->face_point(face, up);
            const auto pd = body->face_point(face, down);
            ASSERT_EQ(pu.op.dofs, point.op.dofs);
            ASSERT_EQ(pd.op.dofs, point.op.dofs);
            for (unsigned int k = 0; k < point.op.weights.size(); ++k)
              EXPECT_NEAR(point.gradients[k][b],
                          (pu.op.weights[k] - pd.op.weights[k]) / (2. * h),
                          1e-8);
            for (unsigned int a = 0; a + 1 < dim; ++a)
              EXPECT_LT((second[a][b] -
                         (pu.tangents[a] - pd.tangents[a]) / (2. * h))
                          .norm(),
                        1e-8);
          }
      }
    body->reset_surfaces();
  }
} // namespace

TEST(MovedSurfaces, RigidMotionOfTheNurbsSurface2D)
{
  rigid_motion_of_the_surface<2>(discretization::Type::nurbs);
}

TEST(MovedSurfaces, RigidMotionOfTheNurbsSurface3D)
{
  rigid_motion_of_the_surface<3>(discretization::Type::nurbs);
}

TEST(MovedSurfaces, RigidMotionOfTheLagrangeSurface2D)
{
  rigid_motion_of_the_surface<2>(discretization::Type::lagrange);
}

TEST(MovedSurfaces, RigidMotionOfTheLagrangeSurface3D)
{
  rigid_motion_of_the_surface<3>(discretization::Type::lagrange);
}

TEST(MovedSurfaces, WeightedGapPairsFollowTheConfigurationNurbs2D)
{
  pairs_of_a_rigid_motion<2>(discretization::Type::nurbs);
}

TEST(MovedSurfaces, WeightedGapPairsFollowTheConfigurationNurbs3D)
{
  pairs_of_a_rigid_motion<3>(discretization::Type::nurbs);
}

TEST(MovedSurfaces, WeightedGapPairsFollowTheConfigurationLagrange2D)
{
  pairs_of_a_rigid_motion<2>(discretization::Type::lagrange);
}

TEST(MovedSurfaces, WeightedGapPairsFollowTheConfigurationLagrange3D)
{
  pairs_of_a_rigid_motion<3>(discretization::Type::lagrange);
}

TEST(MovedSurfaces, FaceDerivativesAgreeWithDifferencesNurbs2D)
{
  face_derivatives_agree_with_differences<2>(discretization::Type::nurbs);
}

TEST(MovedSurfaces, FaceDerivativesAgreeWithDifferencesNurbs3D)
{
  face_derivatives_agree_with_differences<3>(discretization::Type::nurbs);
}

TEST(MovedSurfaces, FaceDerivativesAgreeWithDifferencesLagrange2D)
{
  face_derivatives_agree_with_differences<2>(discretization::Type::lagrange);
}

TEST(MovedSurfaces, FaceDerivativesAgreeWithDifferencesLagrange3D)
{
  face_derivatives_agree_with_differences<3>(discretization::Type::lagrange);
}
