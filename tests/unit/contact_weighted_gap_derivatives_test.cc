// The weighted-gap pairs' derivatives in closed form
// (WeightedGapPairing::make_pairs_with_derivatives(), finite sliding's
// full tangent) against central differences of the pairing itself: the
// pairs formed again on the configurations u +- eps v (make_pairs_of(),
// which finds the element cuts and the closest points anew), for the gap,
// the unit normal and every weight of op1 and op2, along a random
// direction v of both bodies' unknowns. The configurations are random
// control-point displacements (amplitude 0.02 on blocks of size 1), so
// that the faces are curved and overlap in places; the master covers the
// slave face.
//
// The closed form holds the quadrature's pieces where they are: exact
// where the master's knot lines fall on the pieces' ends, which they do in
// 2D (the cuts are the crossings) and in 3D while the grids stay aligned
// (displacements normal to the faces). Its tolerance: the central
// differences err by eps^2 times the third derivatives (1e-8 at eps =
// 1e-4) and by the pairing's noise over eps (the cuts bracketed to 1e-10
// of an element move the Gauss points: measured 2e-10 / eps relative).
// The bound 1e-5 leaves a margin of 5. Where the
// master's knot lines cross a 3D slave element obliquely, the pairing cuts
// along the element's centre lines only, kinks of the integrand lie inside
// pieces, and the discrete pairing's derivative has a term from the
// pieces' motion that the closed form leaves out: of the order of the
// square of the crossing angle (the angle times its change), so it must
// fall about fourfold when the displacements halve. Against a faceted
// master (a bent FE_Q face, whose normal jumps at the element edges) the
// closed form is refused, and the full tangent takes differences.

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <igabde/contact/contact_surface.h>
#include <igabde/contact/obstacle.h>
#include <igabde/contact/pairing.h>

#include <gtest/gtest.h>

#include "test_blocks.h"
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <utility>

namespace
{
  using namespace igabde;
  using namespace dealii;
  using test_blocks::block;

  /// The 2D pair: a unit slave block of 3 x 2 spans (top face 3) under a
  /// wider master block of 4 x 2 (bottom face 2, held on its top).
  std::pair<std::unique_ptr<discretization::Body<2>>,
            std::unique_ptr<discretization::Body<2>>>
  blocks_2d(const discretization::Type slave, const discretization::Type master)
  {
    return {
      block<2>(slave, Point<2>(0., 0.), Point<2>(1., 1.), {{3, 2}}, 2),
      block<2>(master, Point<2>(-0.15, 1.), Point<2>(1.2, 1.6), {{4, 2}}, 3)};
  }

  /// The 3D pair: a unit slave block of 2 x 2 x 1 spans (top face 5) under
  /// a master block of 3 x 3 x 1 that covers it (bottom face 4).
  std::pair<std::unique_ptr<discretization::Body<3>>,
            std::unique_ptr<discretization::Body<3>>>
  blocks_3d()
  {
    return {block<3>(discretization::Type::nurbs,
                     Point<3>(0., 0., 0.),
                     Point<3>(1., 1., 1.),
                     {{2, 2, 1}},
                     4),
            block<3>(discretization::Type::nurbs,
                     Point<3>(-0.1, -0.15, 1.),
                     Point<3>(1.2, 1.1, 1.5),
                     {{3, 3, 1}},
                     5)};
  }

  /// Random unknowns of @p body, of amplitude @p amplitude; only in the
  /// last component (normal to the blocks' faces) where @p normal_only.
  template <int dim>
  Vector<double>
  random_vector(const discretization::Body<dim> &body,
                const double                     amplitude,
                const bool                       normal_only,
                std::mt19937                    &g)
  {
    std::uniform_real_distribution<> uniform(-1., 1.);
    Vector<double>                   v(body.n_dofs());
    for (unsigned int i = 0; i < v.size(); ++i)
      {
        const double value = amplitude * uniform(g);
        v[i] = !normal_only || body.dof_component(i) == dim - 1 ? value : 0.;
      }
    return v;
  }

  /// What the comparison reads of a pair, by name: gap, normal, and the
  /// operators' weights by their first unknowns.
  template <int dim>
  std::map<std::string, double>
  values(const contact::ContactPair<dim> &pair)
  {
    std::map<std::string, double> v;
    const std::string             key = std::to_string(pair.slave_key) + ":";
    v[key + "gap"]                    = pair.gap;
    for (unsigned int c = 0; c < dim; ++c)
      v[key + "n" + std::to_string(c)] = pair.frame[0][c];
    for (unsigned int k = 0; k < pair.op1.weights.size(); ++k)
      v[key + "s" + std::to_string(pair.op1.dofs[k][0])] = pair.op1.weights[k];
    for (unsigned int k = 0; k < pair.op2.weights.size(); ++k)
      v[key + "m" + std::to_string(pair.op2.dofs[k][0])] = pair.op2.weights[k];
    return v;
  }

  /// The relative deviation of the closed-form directional derivatives
  /// from central differences of the pairing, @p slave against @p master
  /// (a body's face, or an obstacle where @p master_body is nullptr).
  template <int dim>
  double
  derivative_error(const discretization::Body<dim>    &slave,
                   const types::boundary_id            slave_face,
                   const discretization::Body<dim>    *master_body,
                   const types::boundary_id            master_face,
                   const contact::ContactSurface<dim> *obstacle,
                   const bool                          dual,
                   const double                        amplitude   = 0.02,
                   const bool                          normal_only = false)
  {
    std::mt19937         g(7);
    const Vector<double> u1 = random_vector(slave, amplitude, normal_only, g);
    const Vector<double> v1 = random_vector(slave, 1., false, g);
    Vector<double>       u2, v2;
    if (master_body != nullptr)
      {
        u2 = random_vector(*master_body, amplitude, normal_only, g);
        v2 = random_vector(*master_body, 1., false, g);
      }
    const contact::WeightedGapPairing<dim> pairing(dual);
    const auto                             pairs_on = [&](const double                                t,
                              std::vector<types::global_dof_index>       *keys,
                              std::vector<contact::PairDerivatives<dim>> *d) {
      Vector<double> a = u1, b = u2;
      a.add(t, v1);
      if (master_body != nullptr)
        b.add(t, v2);
      slave.move_surfaces(a);
      if (master_body != nullptr)
        master_body->move_surfaces(b);
      std::unique_ptr<contact::ContactSurface<dim>> face;
      if (master_body != nullptr)
        face = std::make_unique<contact::BodyFace<dim>>(
          *master_body,
          std::vector<types::boundary_id>{master_face});
      const contact::ContactSurface<dim> &master =
        master_body != nullptr ? *face : *obstacle;
      std::vector<contact::ContactPair<dim>> pairs;
      if (d != nullptr)
        {
          const bool closed_form =
            pairing.make_pairs_with_derivatives(slave,
                                                {slave_face},
                                                master,
                                                "test",
                                                *keys,
                                                pairs,
                                                *d);
          EXPECT_TRUE(closed_form);
        }
      else if (keys->empty())
        {
          pairs = pairing.make_pairs(slave, {slave_face}, master, "test");
          for (const auto &pair : pairs)
            keys->push_back(pair.slave_key);
        }
      else
        pairs =
          pairing.make_pairs_of(slave, {slave_face}, master, "test", *keys);
      slave.reset_surfaces();
      if (master_body != nullptr)
        master_body->reset_surfaces();
      return pairs;
    };
    std::vector<types::global_dof_index> keys;
    pairs_on(0., &keys, nullptr);
    EXPECT_GT(keys.size(), 3u);
    std::vector<contact::PairDerivatives<dim>> derivatives;
    const auto   base  = pairs_on(0., &keys, &derivatives);
    const double eps   = 1e-4;
    const auto   plus  = pairs_on(eps, &keys, nullptr);
    const auto   minus = pairs_on(-eps, &keys, nullptr);
    EXPECT_EQ(base.size(), keys.size());
    EXPECT_EQ(plus.size(), base.size());
    EXPECT_EQ(minus.size(), base.size());

    // d X . v by the closed form, by name.
    const auto along =
      [&](const typename contact::PairDerivatives<dim>::Gradient &gradient) {
        double sum = 0.;
        for (const auto &[u, value] : gradient)
          sum += value * (u.first == 0 ? v1[u.second] : v2[u.second]);
        return sum;
      };
    double error = 0., size = 0.;
    for (unsigned int i = 0; i < base.size(); ++i)
      {
        const auto       &pair = base[i];
        const auto       &d    = derivatives[i];
        const std::string key  = std::to_string(pair.slave_key) + ":";
        std::map<std::string, double> closed;
        closed[key + "gap"] = along(d.gap);
        for (unsigned int c = 0; c < dim; ++c)
          closed[key + "n" + std::to_string(c)] = along(d.normal[c]);
        EXPECT_EQ(d.op1.size(), pair.op1.weights.size());
        EXPECT_EQ(d.op2.size(), pair.op2.weights.size());
        for (unsigned int k = 0; k < d.op1.size(); ++k)
          closed[key + "s" + std::to_string(pair.op1.dofs[k][0])] =
            along(d.op1[k]);
        for (unsigned int k = 0; k < d.op2.size(); ++k)
          closed[key + "m" + std::to_string(pair.op2.dofs[k][0])] =
            along(d.op2[k]);
        auto vp = values(plus[i]), vm = values(minus[i]);
        for (const auto &[name, value] : closed)
          {
            const double difference = (vp[name] - vm[name]) / (2. * eps);
            error += std::pow(value - difference, 2);
            size += std::pow(difference, 2);
          }
      }
    return std::sqrt(error / size);
  }
} // namespace

TEST(WeightedGapDerivatives, NurbsMasterAgreesWithDifferences2D)
{
  const auto [slave, master] =
    blocks_2d(discretization::Type::nurbs, discretization::Type::nurbs);
  for (const bool dual : {true, false})
    EXPECT_LT(derivative_error<2>(*slave, 3, master.get(), 2, nullptr, dual),
              1e-5)
      << "dual " << dual;
}

TEST(WeightedGapDerivatives, LagrangeSlaveOnNurbsMaster2D)
{
  const auto [slave, master] =
    blocks_2d(discretization::Type::lagrange, discretization::Type::nurbs);
  EXPECT_LT(derivative_error<2>(*slave, 3, master.get(), 2, nullptr, true),
            1e-5);
}

TEST(WeightedGapDerivatives, RigidCylinderAgreesWithDifferences2D)
{
  auto                            slave = block<2>(discretization::Type::nurbs,
                        Point<2>(0., 0.),
                        Point<2>(1., 1.),
                        {{4, 2}},
                        2);
  const contact::RigidCylinder<2> cylinder(Point<2>(0.5, 2.4),
                                           1.45,
                                           Tensor<1, 2>());
  for (const bool dual : {true, false})
    EXPECT_LT(derivative_error<2>(*slave, 3, nullptr, 0, &cylinder, dual), 1e-5)
      << "dual " << dual;
}

TEST(WeightedGapDerivatives, NurbsMasterAgreesWithDifferences3D)
{
  const auto [slave, master] = blocks_3d();
  for (const bool dual : {true, false})
    EXPECT_LT(derivative_error<
                3>(*slave, 5, master.get(), 4, nullptr, dual, 0.02, true),
              1e-5)
      << "dual " << dual;
}

TEST(WeightedGapDerivatives, ObliqueKnotLinesLeaveASecondOrderTerm3D)
{
  const auto [slave, master] = blocks_3d();
  const double large =
    derivative_error<3>(*slave, 5, master.get(), 4, nullptr, true, 0.02);
  const double small =
    derivative_error<3>(*slave, 5, master.get(), 4, nullptr, true, 0.01);
  EXPECT_GT(large / small, 3.);
  EXPECT_LT(large, 1e-3);
}

TEST(WeightedGapDerivatives, FacetedMasterIsLeftToDifferences)
{
  // Both blocks bent by random node and control-point displacements of
  // 0.05 (the elements are 0.34 and 0.5 long): FE_Q's faces then kink at
  // the element edges by about 0.1, NURBS' stay C^1.
  const auto [slave, master] =
    blocks_2d(discretization::Type::nurbs, discretization::Type::lagrange);
  std::mt19937 g(3);
  slave->move_surfaces(random_vector(*slave, 0.05, false, g));
  master->move_surfaces(random_vector(*master, 0.05, false, g));
  const contact::BodyFace<2> face(*master, {2});
  EXPECT_FALSE(face.normal_continuous());
  const contact::BodyFace<2> nurbs_face(*slave, {3});
  EXPECT_TRUE(nurbs_face.normal_continuous());
  std::vector<contact::ContactPair<2>>     pairs;
  std::vector<contact::PairDerivatives<2>> derivatives;
  const contact::WeightedGapPairing<2>     pairing;
  EXPECT_FALSE(pairing.make_pairs_with_derivatives(*slave,
                                                   {3},
                                                   face,
                                                   "test",
                                                   {0},
                                                   pairs,
                                                   derivatives));
  slave->reset_surfaces();
  master->reset_surfaces();
  // Unbent, FE_Q's flat face has a continuous normal too.
  EXPECT_TRUE(contact::BodyFace<2>(*master, {2}).normal_continuous());
}
