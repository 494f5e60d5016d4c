// A body at finite strain (Body::internal_force, solve_finite_strain) on
// the homogeneous deformations both discretisations contain exactly, each
// against its closed form: a uniaxial stretch to twice the length of a
// neo-Hookean block (the lateral stretch from S_22 = 0, solved here by
// bisection; the end force P_11), a simple shear of gamma = 1 and a rigid
// rotation by 90 degrees imposed on the whole boundary (no stress, no
// force); the Cauchy stress read at a point of the stretched block. Newton
// converges quadratically once close (Newton's theorem with an exact tangent):
// r_k <= C r_k-1^2 is checked.

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>
#include <igabde/discretization/finite_strain_solver.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <sstream>

using namespace igabde;
using namespace igabde::discretization;

namespace
{
  constexpr Type discretizations[] = {Type::nurbs, Type::lagrange};

  std::string
  name_of(const Type type)
  {
    return type == Type::nurbs ? "NURBS" : "FE_Q";
  }

  /// The unit square, 3 x 2 spans of degree 2, E = 1000, nu = 0.3.
  BodyDescription<2>
  unit_square()
  {
    BodyDescription<2> d;
    d.geometry = nurbs::make_box<2>(Point<2>(0., 0.), Point<2>(1., 1.));
    nurbs::elevate_to_degree(d.geometry, 2);
    nurbs::subdivide(d.geometry, std::array<unsigned int, 2>{{3, 2}});
    d.material.youngs_modulus = 1000.;
    d.material.poisson_ratio  = 0.3;
    return d;
  }

  /// Component @p c of @p face held at @p value times the displacement
  /// factor, or at @p field(x).
  DirichletCondition<2>
  held(const unsigned int                      face,
       const unsigned int                      c,
       const double                            value,
       std::function<double(const Point<2> &)> field = {})
  {
    DirichletCondition<2> condition;
    condition.boundary_id   = face;
    condition.components[c] = true;
    condition.value[c]      = value;
    condition.field[c]      = field;
    return condition;
  }

  /**
   * Solves @p body at displacement factors 1/n, 2/n, ..., 1 (no loads),
   * each step from the last; returns the solution and every step's result.
   */
  std::pair<Vector<double>, std::vector<NewtonResult>>
  solve_in_steps(const Body<2>                             &body,
                 const elasticity::HyperelasticMaterial<2> &material,
                 const unsigned int                         n)
  {
    Vector<double>            u(body.n_dofs());
    std::vector<NewtonResult> results;
    for (unsigned int s = 1; s <= n; ++s)
      {
        results.push_back(solve_finite_strain<2>(body,
                                                 material,
                                                 {0., double(s) / n},
                                                 NewtonSettings(),
                                                 u,
                                                 nullptr));
        EXPECT_TRUE(results.back().converged)
          << "step " << s << ": " << results.back().diagnosis;
      }
    return {u, results};
  }

  /// Largest |u_i - exact(x_i)_c| over the unknowns.
  double
  largest_error(const Body<2>                                       &body,
                const Vector<double>                                &u,
                const std::function<Tensor<1, 2>(const Point<2> &)> &exact)
  {
    double error = 0.;
    for (types::global_dof_index i = 0; i < body.n_dofs(); ++i)
      error =
        std::max(error,
                 std::abs(u[i] -
                          exact(body.dof_location(i))[body.dof_component(i)]));
    return error;
  }
} // namespace



TEST(FiniteStrainBody, UniaxialStretchToTwiceTheLength)
{
  // Plane strain, lateral faces free: F = diag(2, s) with
  // S_22 = mu (1 - 1/s^2) + lambda ln(2 s) / s^2 = 0, i.e.
  // mu (s^2 - 1) + lambda ln(2 s) = 0, one root in (0, 1).
  const double E = 1000., nu = 0.3;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu     = E / (2 * (1 + nu));
  double       lo = 1e-3, hi = 1.;
  for (unsigned int k = 0; k < 200; ++k)
    {
      const double s = 0.5 * (lo + hi);
      (mu * (s * s - 1) + lambda * std::log(2 * s) > 0 ? hi : lo) = s;
    }
  const double s   = 0.5 * (lo + hi);
  const double S11 = mu * (1 - 1 / 4.) + lambda * std::log(2 * s) / 4.;
  const double P11 = 2. * S11; // per unit reference height (1)

  for (const Type type : discretizations)
    {
      SCOPED_TRACE(name_of(type));
      BodyDescription<2> d = unit_square();
      d.dirichlet          = {held(0, 0, 0.), held(2, 1, 0.), held(1, 0, 1.)};
      DiscretizationSettings settings;
      settings.type   = type;
      settings.degree = 2;
      auto body       = create_body<2>(d, settings);
      body->setup();
      const elasticity::HyperelasticMaterial<2> material(
        elasticity::MaterialModel::neo_hookean,
        d.material);
      const auto [u, results] = solve_in_steps(*body, material, 4);
      EXPECT_LT(largest_error(*body,
                              u,
                              [s](const Point<2> &x) {
                                return Tensor<1, 2>({x[0], (s - 1) * x[1]});
                              }),
                1e-10);
      // The end force: the internal force's x components on the unknowns
      // of the face x = 1 (the lateral faces carry no traction).
      Vector<double> f(body->n_dofs());
      body->internal_force(u, material, f, nullptr);
      double end_force = 0.;
      for (types::global_dof_index i = 0; i < body->n_dofs(); ++i)
        if (body->dof_component(i) == 0 &&
            std::abs(body->dof_location(i)[0] - 1.) < 1e-12)
          end_force += f[i];
      EXPECT_NEAR(end_force, P11, 1e-10 * P11);
      // The Cauchy stress inside: sigma_11 = P_11 F_11 / J = P_11 / s,
      // sigma_22 = 0 (free lateral faces), no shear.
      const SymmetricTensor<2, 2> sigma =
        body->cauchy_stress(u, Point<2>(0.37, 0.61), material);
      EXPECT_NEAR(sigma[0][0], P11 / s, 1e-9 * P11);
      EXPECT_NEAR(sigma[1][1], 0., 1e-9 * P11);
      EXPECT_NEAR(sigma[0][1], 0., 1e-9 * P11);

      // Quadratic convergence once close: r_k <= C r_k-1^2 with C = 100
      // for r_k-1 in (1e-6, 1e-3), above the round-off of r (1e-15); a
      // linear rate of 0.1 breaks it by two orders at r = 1e-5.
      unsigned int checked = 0;
      for (const auto &result : results)
        for (unsigned int k = 1; k < result.residuals.size(); ++k)
          {
            const double previous = result.residuals[k - 1];
            const double current  = result.residuals[k];
            if (previous < 1e-3 && previous > 1e-6)
              {
                EXPECT_LT(current, 100. * previous * previous)
                  << "iteration " << k << ": " << previous << " -> " << current;
                ++checked;
              }
          }
      EXPECT_GT(checked, 0u);
    }
}



TEST(FiniteStrainBody, SimpleShearOfOne)
{
  // u = (gamma y, 0) on the whole boundary: the homogeneous shear is the
  // equilibrium inside (constant stress, div P = 0).
  for (const Type type : discretizations)
    {
      SCOPED_TRACE(name_of(type));
      BodyDescription<2> d = unit_square();
      for (unsigned int face = 0; face < 4; ++face)
        {
          d.dirichlet.push_back(held(face, 0, 0., [](const Point<2> &x) {
            return x[1];
          }));
          d.dirichlet.push_back(held(face, 1, 0.));
        }
      DiscretizationSettings settings;
      settings.type   = type;
      settings.degree = 2;
      auto body       = create_body<2>(d, settings);
      body->setup();
      for (const auto law : {elasticity::MaterialModel::neo_hookean,
                             elasticity::MaterialModel::saint_venant_kirchhoff})
        {
          SCOPED_TRACE(elasticity::to_string(law));
          const elasticity::HyperelasticMaterial<2> material(law, d.material);
          const auto [u, results] = solve_in_steps(*body, material, 2);
          EXPECT_LT(largest_error(*body,
                                  u,
                                  [](const Point<2> &x) {
                                    return Tensor<1, 2>({x[1], 0.});
                                  }),
                    1e-10);
        }
    }
}



TEST(FiniteStrainBody, ARigidRotationBy90DegreesCarriesNoForce)
{
  // u = (R - I) X on the whole boundary, R by 90 degrees: the whole body
  // turns rigidly and stores nothing. Along the way (factor t < 1) the
  // boundary is a rotation with a contraction, F = I + t (R - I), of
  // det F = (1 - t)^2 + t^2 > 0.
  const auto rotation = [](const Point<2> &x) {
    return Tensor<1, 2>({-x[0] - x[1], x[0] - x[1]});
  };
  for (const Type type : discretizations)
    {
      SCOPED_TRACE(name_of(type));
      BodyDescription<2> d = unit_square();
      for (unsigned int face = 0; face < 4; ++face)
        for (unsigned int c = 0; c < 2; ++c)
          d.dirichlet.push_back(
            held(face, c, 0., [rotation, c](const Point<2> &x) {
              return rotation(x)[c];
            }));
      DiscretizationSettings settings;
      settings.type   = type;
      settings.degree = 2;
      auto body       = create_body<2>(d, settings);
      body->setup();
      const elasticity::HyperelasticMaterial<2> material(
        elasticity::MaterialModel::neo_hookean,
        d.material);
      const auto [u, results] = solve_in_steps(*body, material, 4);
      EXPECT_LT(largest_error(*body, u, rotation), 1e-10);
      Vector<double> f(body->n_dofs());
      body->internal_force(u, material, f, nullptr);
      // Against the forces of the first step (a contraction by a quarter
      // of the rotation): round-off of those.
      Vector<double> u1(body->n_dofs()), f1(body->n_dofs());
      solve_finite_strain<2>(*body,
                             material,
                             {0., 0.25},
                             NewtonSettings(),
                             u1,
                             nullptr);
      body->internal_force(u1, material, f1, nullptr);
      EXPECT_LT(f.linfty_norm(), 1e-10 * f1.linfty_norm());
    }
}
