// PairingStrategy::make_pairs_of(): the weighted-gap pairs of some slave
// basis functions, formed from only the slave elements those functions
// live on (finite sliding's full tangent forms the pairs in contact again
// at every group of unknowns it differentiates by). Each must be the pair
// make_pairs() forms for the same function, to the last bit: a function's
// integrals are sums over its own elements, which both visit in the same
// order. The case: a half disc (the slave, its curved face cut by the
// master's element edges) pressed into a block on non-matching meshes,
// on a moved configuration (both surfaces displaced by a smooth field, as
// finite sliding pairs them), NURBS p = 2 and FE_Q(2), the dual and the
// standard weights; the keys asked for are every third pair's, and the
// test also asks for a key that no pair has. Where supports hold one of
// the slave face's functions in every component, make_pairs_of() forms
// every pair and keeps those asked for: the same numbers again.

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <igabde/contact/contact_surface.h>
#include <igabde/contact/pairing.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace
{
  using namespace igabde;
  using namespace dealii;

  /// Whether @p a and @p b are the same pair to the last bit.
  void
  expect_identical(const contact::ContactPair<2> &a,
                   const contact::ContactPair<2> &b)
  {
    EXPECT_EQ(a.gap, b.gap);
    EXPECT_EQ(a.area, b.area);
    EXPECT_EQ(a.x1, b.x1);
    EXPECT_EQ(a.x2, b.x2);
    EXPECT_EQ(a.frame, b.frame);
    for (const auto &[p, q] :
         {std::make_pair(&a.op1, &b.op1), std::make_pair(&a.op2, &b.op2)})
      {
        ASSERT_EQ(p->weights.size(), q->weights.size());
        for (unsigned int k = 0; k < p->weights.size(); ++k)
          {
            EXPECT_EQ(p->weights[k], q->weights[k]);
            EXPECT_EQ(p->dofs[k], q->dofs[k]);
          }
      }
  }

  void
  check_pairs_of(const discretization::Type type,
                 const contact::Pairing     pairing,
                 const bool                 hold_slave_face_end)
  {
    discretization::DiscretizationSettings settings;
    settings.type   = type;
    settings.degree = 2;

    discretization::BodyDescription<2> disc;
    disc.geometry = nurbs::make_half_disc(Point<2>(0.1, 1.), 1.);
    nurbs::subdivide(disc.geometry, std::array<unsigned int, 2>{{12, 3}});
    disc.material.youngs_modulus = 1.;
    disc.material.poisson_ratio  = 0.3;
    discretization::DirichletCondition<2> top;
    top.boundary_id = 3;
    top.components  = {{true, true}};
    disc.dirichlet.push_back(top);
    if (hold_slave_face_end)
      {
        // The disc's left side: its end functions on the curved face too.
        discretization::DirichletCondition<2> side;
        side.boundary_id = 0;
        side.components  = {{true, true}};
        disc.dirichlet.push_back(side);
      }

    discretization::BodyDescription<2> block;
    block.geometry = nurbs::make_box<2>(Point<2>(-1.5, -1.), Point<2>(1.5, 0.));
    nurbs::elevate_to_degree(block.geometry, 2);
    nurbs::subdivide(block.geometry, std::array<unsigned int, 2>{{17, 4}});
    block.material = disc.material;
    discretization::DirichletCondition<2> bottom;
    bottom.boundary_id = 2;
    bottom.components  = {{true, true}};
    block.dirichlet.push_back(bottom);

    auto slave  = discretization::create_body<2>(disc, settings);
    auto master = discretization::create_body<2>(block, settings);
    slave->setup();
    master->setup();

    // A smooth displacement of both: the disc 0.05 down into the block
    // and sheared, the block's top waved.
    const auto field =
      [](const discretization::Body<2> &body, const double a, const double b) {
        Vector<double> u(body.n_dofs());
        for (unsigned int i = 0; i < body.n_dofs(); ++i)
          {
            const Point<2> X = body.dof_location(i);
            u[i]             = body.dof_component(i) == 0 ?
                                 a * std::sin(1.3 * X[1] + 0.4) :
                                 b * (1. + 0.3 * std::cos(2.1 * X[0]));
          }
        return u;
      };
    const Vector<double> u_slave  = field(*slave, 0.02, -0.05);
    const Vector<double> u_master = field(*master, 0.01, 0.01);
    slave->move_surfaces(u_slave);
    master->move_surfaces(u_master);

    const contact::BodyFace<2> face(*master, {3});
    const auto strategy = contact::create_pairing_strategy<2>(pairing);
    const std::vector<contact::ContactPair<2>> all =
      strategy->make_pairs(*slave, {2}, face, "test");
    ASSERT_GT(all.size(), 6u);
    std::vector<types::global_dof_index>            keys;
    std::map<types::global_dof_index, unsigned int> index;
    for (unsigned int i = 0; i < all.size(); ++i)
      {
        index[all[i].slave_key] = i;
        if (i % 3 == 1)
          keys.push_back(all[i].slave_key);
      }
    keys.push_back(numbers::invalid_dof_index - 1);
    std::sort(keys.begin(), keys.end());
    const std::vector<contact::ContactPair<2>> some =
      strategy->make_pairs_of(*slave, {2}, face, "test", keys);
    slave->reset_surfaces();
    master->reset_surfaces();

    ASSERT_EQ(some.size(), keys.size() - 1);
    for (unsigned int j = 0; j < some.size(); ++j)
      {
        EXPECT_TRUE(
          std::binary_search(keys.begin(), keys.end(), some[j].slave_key));
        if (j > 0)
          {
            EXPECT_LT(some[j - 1].slave_key, some[j].slave_key);
          }
        expect_identical(some[j], all[index.at(some[j].slave_key)]);
      }
  }
} // namespace

TEST(ContactPairsOf, SomePairsAreThoseOfAllPairsToTheBit)
{
  for (const auto type :
       {discretization::Type::nurbs, discretization::Type::lagrange})
    for (const auto pairing : {contact::Pairing::weighted_gap,
                               contact::Pairing::weighted_gap_standard})
      for (const bool held : {false, true})
        {
          SCOPED_TRACE(std::string(type == discretization::Type::nurbs ?
                                     "nurbs" :
                                     "lagrange") +
                       " " + contact::to_string(pairing) +
                       (held ? ", face end held" : ""));
          check_pairs_of(type, pairing, held);
        }
}
