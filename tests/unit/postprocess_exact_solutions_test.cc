// The closed-form solutions the error norms are measured against: their
// displacement and stress fields are written separately, so each must
// agree with the other through Hooke's law of the scene's plane model
// (written out here by hand), or the reported errors measure the
// reference's mistake. Strains from the displacement by central
// differences (step h = 1e-4 times the radius: truncation about 1e-8
// relative, rounding about 1e-12).

#include <igabde/postprocess/contact_checks.h>
#include <igabde/postprocess/exact_solutions.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace
{
  using namespace dealii;
  using igabde::elasticity::IsotropicMaterial;
  using igabde::elasticity::PlaneModel;

  /// In-plane strains (xx, yy, xy) of @p u at @p x by central differences.
  template <int dim, typename Displacement>
  std::array<double, 3>
  strain(const Displacement &u, const Point<dim> &x, const double h)
  {
    Point<dim> xp = x, xm = x, yp = x, ym = x;
    xp[0] += h;
    xm[0] -= h;
    yp[1] += h;
    ym[1] -= h;
    const Tensor<1, dim> dx = (u(xp) - u(xm)) / (2. * h);
    const Tensor<1, dim> dy = (u(yp) - u(ym)) / (2. * h);
    return {{dx[0], dy[1], 0.5 * (dx[1] + dy[0])}};
  }

  /// Hooke's law for the in-plane strains of in-plane stresses @p s
  /// (xx, yy, xy): plane stress, or plane strain (eps_zz = 0).
  std::array<double, 3>
  hooke(const std::array<double, 3> &s,
        const double                 E,
        const double                 nu,
        const bool                   plane_stress)
  {
    if (plane_stress)
      return {
        {(s[0] - nu * s[1]) / E, (s[1] - nu * s[0]) / E, (1. + nu) / E * s[2]}};
    return {{(1. + nu) / E * ((1. - nu) * s[0] - nu * s[1]),
             (1. + nu) / E * ((1. - nu) * s[1] - nu * s[0]),
             (1. + nu) / E * s[2]}};
  }

  template <int dim>
  void
  expect_hooke(const igabde::elasticity::ExactSolution<dim> &exact,
               const IsotropicMaterial<dim>                 &material,
               const Point<dim>                             &x,
               const double                                  radius)
  {
    const auto e     = strain<dim>(exact.displacement, x, 1e-4 * radius);
    const auto sigma = exact.stress(x);
    const auto expected =
      hooke({{sigma[0][0], sigma[1][1], sigma[0][1]}},
            material.youngs_modulus,
            material.poisson_ratio,
            dim == 2 && material.plane_model == PlaneModel::plane_stress);
    const double scale = std::max(
      {std::abs(expected[0]), std::abs(expected[1]), std::abs(expected[2])});
    for (unsigned int c = 0; c < 3; ++c)
      EXPECT_NEAR(e[c], expected[c], 1e-6 * scale)
        << "component " << c << " at " << x;
    if (dim == 3)
      {
        // Ends held: eps_zz = 0, so sigma_zz = nu (sigma_xx + sigma_yy).
        EXPECT_NEAR(sigma[dim - 1][dim - 1],
                    material.poisson_ratio * (sigma[0][0] + sigma[1][1]),
                    1e-12 * std::abs(sigma[0][0] + sigma[1][1]));
      }
  }
} // namespace



TEST(ExactSolutions, LameDisplacementAndStressObeyHookesLawOfEachModel)
{
  // V2's cylinder: a = 1, b = 2, p = 1; E = 1000, nu = 0.3.
  for (const PlaneModel model :
       {PlaneModel::plane_strain, PlaneModel::plane_stress})
    {
      SCOPED_TRACE(igabde::elasticity::to_string(model));
      IsotropicMaterial<2> material;
      material.youngs_modulus = 1000.;
      material.poisson_ratio  = 0.3;
      material.plane_model    = model;
      const auto exact =
        igabde::postprocess::lame_solution<2>(1., 2., 1., material);
      for (const double r : {1.1, 1.5, 1.9})
        for (const double t : {0.2, 0.9, 1.4})
          expect_hooke<2>(exact,
                          material,
                          Point<2>(r * std::cos(t), r * std::sin(t)),
                          r);
    }
  IsotropicMaterial<3> material;
  material.youngs_modulus = 1000.;
  material.poisson_ratio  = 0.3;
  const auto exact =
    igabde::postprocess::lame_solution<3>(1., 2., 1., material);
  for (const double r : {1.1, 1.5, 1.9})
    expect_hooke<3>(exact, material, Point<3>(r * 0.6, r * 0.8, 0.5), r);
}



TEST(ExactSolutions, KirschDisplacementAndStressObeyHookesLawOfEachModel)
{
  // V1's plate: hole radius 1, remote tension 10; E = 1e5, nu = 0.3.
  for (const PlaneModel model :
       {PlaneModel::plane_strain, PlaneModel::plane_stress})
    {
      SCOPED_TRACE(igabde::elasticity::to_string(model));
      IsotropicMaterial<2> material;
      material.youngs_modulus = 1e5;
      material.poisson_ratio  = 0.3;
      material.plane_model    = model;
      const auto exact =
        igabde::postprocess::kirsch_solution(10., 1., material);
      for (const double r : {1.2, 2., 4.})
        for (const double t : {0.3, 1., 2.5})
          expect_hooke<2>(exact,
                          material,
                          Point<2>(r * std::cos(t), r * std::sin(t)),
                          r);
    }
}



TEST(HertzReference, DundursBetaVanishesForSimilarBodiesAndMatchesJohnsonsForm)
{
  // Whether friction can change a Hertz contact (the warning beside the
  // Hertz checks): Dundurs' beta, against Johnson's form of it in terms of
  // the compliances, |beta| = |(1 - 2 nu_1) / G_1 - (1 - 2 nu_2) / G_2| /
  // (2 ((1 - nu_1) / G_1 + (1 - nu_2) / G_2)) (plane strain and 3D).
  using igabde::postprocess::dundurs_beta;
  IsotropicMaterial<3> a, b;
  a.youngs_modulus = 1000.;
  a.poisson_ratio  = 0.3;
  b                = a;
  EXPECT_EQ(dundurs_beta<3>(a, &b), 0.);
  b.youngs_modulus = 3000.;
  b.poisson_ratio  = 0.2;
  const auto g     = [](const IsotropicMaterial<3> &m) {
    return m.youngs_modulus / (2. * (1. + m.poisson_ratio));
  };
  const double johnson =
    std::abs((1. - 2. * a.poisson_ratio) / g(a) -
             (1. - 2. * b.poisson_ratio) / g(b)) /
    (2. * ((1. - a.poisson_ratio) / g(a) + (1. - b.poisson_ratio) / g(b)));
  EXPECT_NEAR(std::abs(dundurs_beta<3>(a, &b)), johnson, 1e-14);
  // A rigid obstacle is the limit of an ever stiffer second body:
  // -(1 - 2 nu) / (2 (1 - nu)) = -0.2857 for nu = 0.3.
  b.youngs_modulus = 1e15;
  EXPECT_NEAR(dundurs_beta<3>(a, nullptr), dundurs_beta<3>(a, &b), 1e-10);
  EXPECT_NEAR(dundurs_beta<3>(a, nullptr), -0.4 / 1.4, 1e-14);
  // Plane stress: kappa = (3 - nu) / (1 + nu), beta = -(1 - nu) / 2 against
  // a rigid plane (nu = 0.3: -0.35).
  IsotropicMaterial<2> s;
  s.poisson_ratio = 0.3;
  s.plane_model   = PlaneModel::plane_stress;
  EXPECT_NEAR(dundurs_beta<2>(s, nullptr), -0.35, 1e-14);
}
