// Von Mises and the out-of-plane stress against closed forms, and the
// stresses both discretisations recover through the one elasticity room:
// homogeneous states to round-off, the Lamé cylinder (V2) at its inner wall
// within 1 %.
#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <igabde/elasticity/stress_measures.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

namespace
{
  using namespace igabde;
  using namespace dealii;

  template <int dim>
  elasticity::IsotropicMaterial<dim>
  material(const elasticity::PlaneModel model)
  {
    elasticity::IsotropicMaterial<dim> m;
    m.youngs_modulus = 1000.;
    m.poisson_ratio  = 0.3;
    m.plane_model    = model;
    return m;
  }

  const auto plane_stress = elasticity::PlaneModel::plane_stress;
  const auto plane_strain = elasticity::PlaneModel::plane_strain;

  discretization::DirichletCondition<2>
  support(const types::boundary_id face,
          const unsigned int       component,
          const double             value = 0.)
  {
    discretization::DirichletCondition<2> bc;
    bc.boundary_id           = face;
    bc.components[component] = true;
    bc.value[component]      = value;
    return bc;
  }

  std::unique_ptr<discretization::Body<2>>
  make_body(const discretization::BodyDescription<2> &description,
            const discretization::Type                type,
            const unsigned int                        refinements)
  {
    discretization::DiscretizationSettings settings;
    settings.type        = type;
    settings.degree      = 2;
    settings.refinements = refinements;
    auto body = discretization::create_body<2>(description, settings);
    body->setup();
    return body;
  }
} // namespace



TEST(ElasticityStressMeasures, UniaxialIsSigma)
{
  const double          s = 7.5;
  SymmetricTensor<2, 3> sigma3;
  sigma3[0][0] = s;
  EXPECT_NEAR(elasticity::von_mises(sigma3, material<3>(plane_strain)),
              s,
              1e-14 * s);
  SymmetricTensor<2, 2> sigma2;
  sigma2[1][1] = s;
  EXPECT_NEAR(elasticity::von_mises(sigma2, material<2>(plane_stress)),
              s,
              1e-14 * s);
  EXPECT_EQ(elasticity::out_of_plane_stress(sigma2, material<2>(plane_stress)),
            0.);
  EXPECT_EQ(elasticity::out_of_plane_stress(sigma3, material<3>(plane_strain)),
            0.);
}



TEST(ElasticityStressMeasures, EquibiaxialPlaneStressIsSigma)
{
  // The 2D deviator of the first landing gave 0 here.
  const double          s = 3.;
  SymmetricTensor<2, 2> sigma;
  sigma[0][0] = sigma[1][1] = s;
  EXPECT_NEAR(elasticity::von_mises(sigma, material<2>(plane_stress)),
              s,
              1e-14 * s);
}



TEST(ElasticityStressMeasures, PureShearIsSqrt3Tau)
{
  const double          tau = 2.;
  SymmetricTensor<2, 2> sigma2;
  sigma2[0][1] = tau;
  EXPECT_NEAR(elasticity::von_mises(sigma2, material<2>(plane_stress)),
              std::sqrt(3.) * tau,
              1e-14 * tau);
  // Plane strain: sigma_zz = nu (0 + 0) = 0, the same value.
  EXPECT_NEAR(elasticity::von_mises(sigma2, material<2>(plane_strain)),
              std::sqrt(3.) * tau,
              1e-14 * tau);
  SymmetricTensor<2, 3> sigma3;
  sigma3[1][2] = tau;
  EXPECT_NEAR(elasticity::von_mises(sigma3, material<3>(plane_strain)),
              std::sqrt(3.) * tau,
              1e-14 * tau);
}



TEST(ElasticityStressMeasures, PlaneStrainUniaxialStrain)
{
  // eps = e e_x e_x, eps_zz = 0: sigma_xx = (lambda + 2 mu) e,
  // sigma_yy = sigma_zz = lambda e, and indeed nu (sigma_xx + sigma_yy) =
  // 2 nu (lambda + mu) e = lambda e. Von Mises = |sigma_xx - sigma_yy| =
  // 2 mu e.
  const auto   m      = material<2>(plane_strain);
  const double E      = m.youngs_modulus;
  const double nu     = m.poisson_ratio;
  const double lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
  const double mu     = E / (2. * (1. + nu));
  const double e      = 1e-3;

  SymmetricTensor<2, 2> eps;
  eps[0][0]                         = e;
  const SymmetricTensor<2, 2> sigma = elasticity::stress(eps, m);
  EXPECT_NEAR(sigma[0][0], (lambda + 2. * mu) * e, 1e-13 * mu * e);
  EXPECT_NEAR(sigma[1][1], lambda * e, 1e-13 * mu * e);
  EXPECT_NEAR(elasticity::out_of_plane_stress(sigma, m),
              lambda * e,
              1e-13 * mu * e);
  EXPECT_NEAR(elasticity::von_mises(sigma, m), 2. * mu * e, 1e-13 * mu * e);
}



// A unit square stretched by delta along x (x = 0 and y = 0 on rollers,
// y = 1 free): sigma = s e_x e_x everywhere, s = E delta in plane stress
// and s = E delta / (1 - nu^2) with sigma_zz = nu s in plane strain, so
// von Mises = s and s sqrt(1 - nu + nu^2). Both spaces hold the linear
// displacement exactly.
TEST(ElasticityStressMeasures, HomogeneousStretchBothDiscretisations)
{
  const double delta = 1e-3;
  for (const auto model : {plane_stress, plane_strain})
    for (const auto type :
         {discretization::Type::nurbs, discretization::Type::lagrange})
      {
        discretization::BodyDescription<2> d;
        d.name     = "square";
        d.geometry = nurbs::make_box<2>(Point<2>(0., 0.), Point<2>(1., 1.));
        d.material = material<2>(model);
        d.dirichlet.push_back(support(0, 0));
        d.dirichlet.push_back(support(1, 0, delta));
        d.dirichlet.push_back(support(2, 1));
        const auto body = make_body(d, type, 2);

        const double E  = d.material.youngs_modulus;
        const double nu = d.material.poisson_ratio;
        const double s =
          (model == plane_stress ? E * delta : E * delta / (1. - nu * nu));
        const double expected =
          (model == plane_stress ? s : s * std::sqrt(1. - nu + nu * nu));
        for (const Point<2> x :
             {Point<2>(0.3, 0.7), Point<2>(0.9, 0.1), Point<2>(0.5, 0.5)})
          {
            const SymmetricTensor<2, 2> sigma =
              body->stress(body->prescribed_solution(), x);
            EXPECT_NEAR(elasticity::von_mises(sigma, body->material()),
                        expected,
                        1e-10 * expected)
              << to_string(type) << ", plane "
              << (model == plane_stress ? "stress" : "strain") << ", at " << x;
            EXPECT_NEAR(sigma[0][0], s, 1e-10 * s);
          }
      }
}



// V2: Lamé cylinder a = 1, b = 2, internal pressure 1, plane strain,
// nu = 0.3. At r = a: sigma_rr = -p, sigma_tt = p (b^2 + a^2) / (b^2 - a^2)
// = 5/3, sigma_zz = nu (sigma_rr + sigma_tt) = 0.2, von Mises 2.31325.
TEST(ElasticityStressMeasures, LameCylinderInnerWallBothDiscretisations)
{
  const double a = 1., b = 2., p = 1., nu = 0.3;
  const double s_rr = -p;
  const double s_tt = p * (b * b + a * a) / (b * b - a * a);
  const double s_zz = nu * (s_rr + s_tt);
  const double lame = std::sqrt(0.5 * ((s_rr - s_tt) * (s_rr - s_tt) +
                                       (s_tt - s_zz) * (s_tt - s_zz) +
                                       (s_zz - s_rr) * (s_zz - s_rr)));
  // 2.31325 exactly: 2.3133 to four significant digits.
  EXPECT_NEAR(lame, 2.3133, 1e-4 * 2.3133);

  for (const auto type :
       {discretization::Type::nurbs, discretization::Type::lagrange})
    {
      discretization::BodyDescription<2> d;
      d.name     = "cylinder";
      d.geometry = nurbs::make_quarter_annulus(a, b);
      d.material = material<2>(plane_strain);
      d.dirichlet.push_back(support(2, 1));
      d.dirichlet.push_back(support(3, 0));
      discretization::NeumannCondition<2> pressure;
      pressure.boundary_id = 0;
      pressure.traction    = [p](const Point<2> &, const Tensor<1, 2> &n) {
        return -p * n;
      };
      d.tractions.push_back(pressure);
      const auto body = make_body(d, type, 3);

      const SymmetricTensor<2, 2> sigma =
        body->stress(body->load_solution(), Point<2>(1., 0.));
      EXPECT_NEAR(elasticity::von_mises(sigma, body->material()),
                  lame,
                  1e-2 * lame)
        << to_string(type);
    }
}
