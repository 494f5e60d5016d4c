// The full contact path at finite strain (coupled::CoupledSystem with a
// body at Kinematics = finite): its linearised displacement equations are
// the derivative of its displacement equations, checked against central
// finite differences of them at a distorted state, with the held unknowns
// away from the supports' values (the free rows then depend on them too)
// and nonzero pair forces; and its transposed product is the adjoint of
// that derivative (h^T (J v) = (J^T h)^T v). Both discretisations. A
// tangent that dropped the coupling to the held unknowns, or that stayed
// the small-strain K, fails by far more than the differences' error
// (O(eps^2) with eps = 1e-6 of the state's size).

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <igabde/contact/pairing.h>

#include <igabde/coupled/coupled_system.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

namespace coupled_finite_strain
{
  using namespace igabde;
  using namespace igabde::discretization;

  /// A neo-Hookean unit square at finite strain, 3 x 2 spans of degree 2,
  /// held at x = 0 (x) and y = 0 (y, moved by 0.1 times the displacement
  /// factor), with one pair at (0.6, 1) against a rigid obstacle.
  void
  expect_consistent_tangent(const Type type)
  {
    BodyDescription<2> d;
    d.geometry = nurbs::make_box<2>(Point<2>(0., 0.), Point<2>(1., 1.));
    nurbs::elevate_to_degree(d.geometry, 2);
    nurbs::subdivide(d.geometry, std::array<unsigned int, 2>{{3, 2}});
    d.material.youngs_modulus = 1000.;
    d.material.poisson_ratio  = 0.3;
    d.kinematics              = elasticity::Kinematics::finite;
    d.model                   = elasticity::MaterialModel::neo_hookean;
    for (const auto &[face, c, value] :
         {std::tuple<unsigned int, unsigned int, double>{0, 0, 0.},
          std::tuple<unsigned int, unsigned int, double>{2, 1, 0.1}})
      {
        DirichletCondition<2> condition;
        condition.boundary_id   = face;
        condition.components[c] = true;
        condition.value[c]      = value;
        d.dirichlet.push_back(condition);
      }
    DiscretizationSettings settings;
    settings.type   = type;
    settings.degree = 2;
    auto body       = create_body<2>(d, settings);
    body->setup();
    body->ensure_assembled();

    contact::ContactPair<2> pair;
    pair.x1                             = Point<2>(0.6, 1.);
    pair.frame                          = unit_symmetric_tensor<2>();
    pair.area                           = 0.3;
    pair.op1                            = body->point_operator(pair.x1);
    pair.master_body                    = dealii::numbers::invalid_unsigned_int;
    pair.obstacle                       = 0;
    std::vector<const Body<2> *> bodies = {body.get()};
    coupled::CoupledSystem<2>    system(bodies,
                                     {pair},
                                     2,
                                     Eigen::MatrixXd(2, 0),
                                     coupled::Solver::mumps);
    ASSERT_TRUE(system.finite_strain());

    // A distorted start: every unknown (held ones too) moved at random by
    // up to 0.05; the supports move by 0.1 at factor 1.
    const unsigned int               n = system.n_dofs();
    std::mt19937                     random(7);
    std::uniform_real_distribution<> uniform(-1., 1.);
    Eigen::VectorXd                  u0(n), w(n), v(n), h(n), p(2), vp(2);
    for (unsigned int i = 0; i < n; ++i)
      {
        u0[i] = 0.05 * uniform(random);
        w[i]  = 0.02 * uniform(random);
        v[i]  = uniform(random);
        h[i]  = uniform(random);
      }
    p << 30., -10.;
    vp << 1., 2.;
    system.set_reference(u0, {1., 1.});
    system.linearize_bodies(w);

    const double          eps = 1e-6 / v.lpNorm<Eigen::Infinity>() * 0.02;
    const Eigen::VectorXd difference =
      (system.displacement_equations(w + eps * v, p + eps * vp) -
       system.displacement_equations(w - eps * v, p - eps * vp)) /
      (2. * eps);
    const Eigen::VectorXd derivative = system.tangent_equations(v, vp);
    ASSERT_TRUE(derivative.allFinite());
    EXPECT_LT((derivative - difference).norm(), 1e-6 * derivative.norm())
      << (derivative - difference).norm() << " of " << derivative.norm();
    // The adjoint of the derivative with respect to w.
    const double forward =
      h.dot(system.tangent_equations(v, Eigen::VectorXd::Zero(2)));
    const double adjoint = system.tangent_transpose(h).dot(v);
    EXPECT_NEAR(adjoint, forward, 1e-10 * std::abs(forward));
  }
} // namespace coupled_finite_strain

TEST(CoupledFiniteStrain, TangentIsTheDerivativeOfTheResidualNurbs)
{
  coupled_finite_strain::expect_consistent_tangent(
    igabde::discretization::Type::nurbs);
}

TEST(CoupledFiniteStrain, TangentIsTheDerivativeOfTheResidualLagrange)
{
  coupled_finite_strain::expect_consistent_tangent(
    igabde::discretization::Type::lagrange);
}
