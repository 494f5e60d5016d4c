// Finite-strain elasticity (elasticity/hyperelastic.h, finite_strain.h),
// each part against an independent reference:
// - the stress is the energy's derivative and the tangent the stress's
//   (central differences, error O(h^2) of order 1e-9 of the values here);
// - both laws are Hooke's law at small strain (the linear code's
//   stiffness);
// - a rigid rotation by 90 degrees stores no energy and leaves no internal
//   force (frame indifference);
// - on a distorted element of each discretisation (a FE_Q(2) cell with a
//   moved vertex, a NURBS span of a quarter annulus), the internal force is
//   the derivative of the cell's energy and the tangent the derivative of
//   the internal force, at a displacement with 20 % strain and a rotation.

#include <igabde/nurbs/geometry_builders.h>
#include <igabde/nurbs/nurbs_values.h>

#include <igabde/elasticity/fe_values_evaluator.h>
#include <igabde/elasticity/finite_strain.h>
#include <igabde/elasticity/hyperelastic.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace igabde;
using namespace igabde::elasticity;

namespace
{
  constexpr MaterialModel laws[] = {MaterialModel::saint_venant_kirchhoff,
                                    MaterialModel::neo_hookean};

  template <int dim>
  IsotropicMaterial<dim>
  steel_like()
  {
    IsotropicMaterial<dim> m;
    m.youngs_modulus = 210.;
    m.poisson_ratio  = 0.3;
    return m;
  }

  /// A symmetric C = F^T F of a stretched, sheared F (det F > 0).
  template <int dim>
  SymmetricTensor<2, dim>
  some_strain()
  {
    Tensor<2, dim> F;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        F[i][j] = (i == j ? 1. + 0.1 * (i + 1) : 0.05 * (i + 2 * j + 1));
    return right_cauchy_green(F);
  }

  /// A symmetric direction with entries of order one.
  template <int dim>
  SymmetricTensor<2, dim>
  some_direction()
  {
    SymmetricTensor<2, dim> d;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        d[i][j] = 0.3 + 0.2 * i - 0.4 * j;
    return d;
  }

  /// Largest |entry| of the difference, over the largest |entry| of a.
  double
  relative_difference(const Vector<double> &a, const Vector<double> &b)
  {
    Vector<double> d = a;
    d -= b;
    return d.linfty_norm() / a.linfty_norm();
  }

  /// A stretch with shear and a rotation of 0.3 rad.
  template <int dim>
  Tensor<2, dim>
  stretched_rotation()
  {
    Tensor<2, dim> R, U;
    for (unsigned int d = 0; d < dim; ++d)
      {
        R[d][d] = 1.;
        U[d][d] = 1. + 0.2 * (d == 0) - 0.05 * (d == 1);
      }
    R[0][0] = R[1][1] = std::cos(0.3);
    R[0][1]           = -std::sin(0.3);
    R[1][0]           = std::sin(0.3);
    U[0][1] = U[1][0] = 0.04;
    return R * U;
  }
  /**
   * The checks on one cell of evaluator @p values (reinitialised): at the
   * displacement of a 20 % stretch with a 0.3 rad rotation (through the
   * cell's own basis: u = (R U - I) X at the coefficients' locations
   * @p locations) plus a random part of 2 %, the internal force against central
   * differences of the cell energy, and the tangent against central differences
   * of the internal force, along random directions.
   */
  template <int dim, typename Values>
  void
  expect_consistent_cell(const Values                  &values,
                         const std::vector<Point<dim>> &locations)
  {
    const unsigned int   n = values.dofs_per_cell();
    const Tensor<2, dim> G = stretched_rotation<dim>();
    std::vector<double>  u(n);
    for (unsigned int l = 0; l < values.n_basis(); ++l)
      {
        const Tensor<1, dim> x = locations[l];
        const Tensor<1, dim> y = G * x - x;
        for (unsigned int c = 0; c < dim; ++c)
          u[values.local_dof(l, c)] = y[c];
      }
    std::mt19937                           engine(7);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    // Not homogeneous: a smaller random part on every coefficient.
    for (auto &v : u)
      v += 0.02 * uniform(engine);

    for (const MaterialModel law : laws)
      {
        SCOPED_TRACE(to_string(law));
        const HyperelasticMaterial<dim> material(law, steel_like<dim>());
        Vector<double>                  r(n);
        FullMatrix<double>              K(n, n);
        const double                    min_J =
          add_cell_internal_force<dim>(values, u, material, r, &K);
        ASSERT_GT(min_J, 0.5);
        // The tangent of a hyperelastic law is symmetric.
        double asymmetry = 0., largest = 0.;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            {
              asymmetry = std::max(asymmetry, std::abs(K(i, j) - K(j, i)));
              largest   = std::max(largest, std::abs(K(i, j)));
            }
        EXPECT_LT(asymmetry, 1e-12 * largest);

        for (unsigned int trial = 0; trial < 3; ++trial)
          {
            std::vector<double> du(n);
            for (auto &v : du)
              v = 0.01 * uniform(engine);
            const double h       = 1e-4;
            const auto   shifted = [&](const double s) {
              std::vector<double> w = u;
              for (unsigned int i = 0; i < n; ++i)
                w[i] += s * du[i];
              return w;
            };
            // Internal force: the directional derivative of the energy.
            const double dW =
              (cell_energy<dim>(values, shifted(h), material) -
               cell_energy<dim>(values, shifted(-h), material)) /
              (2 * h);
            double r_du = 0.;
            for (unsigned int i = 0; i < n; ++i)
              r_du += r[i] * du[i];
            EXPECT_NEAR(dW, r_du, 1e-7 * r.linfty_norm());

            // Tangent: the directional derivative of the internal force.
            Vector<double> r_plus(n), r_minus(n), K_du(n), fd(n);
            add_cell_internal_force<dim>(values,
                                         shifted(h),
                                         material,
                                         r_plus,
                                         nullptr);
            add_cell_internal_force<dim>(values,
                                         shifted(-h),
                                         material,
                                         r_minus,
                                         nullptr);
            for (unsigned int i = 0; i < n; ++i)
              {
                fd[i] = (r_plus[i] - r_minus[i]) / (2 * h);
                for (unsigned int j = 0; j < n; ++j)
                  K_du[i] += K(i, j) * du[j];
              }
            EXPECT_LT(relative_difference(K_du, fd), 1e-6);
          }
      }
  }
} // namespace



TEST(FiniteStrain, TheStressIsTheEnergysDerivativeAndTheTangentTheStresss)
{
  const auto check = [](auto dimension) {
    constexpr int                 dim = decltype(dimension)::value;
    const SymmetricTensor<2, dim> C   = some_strain<dim>();
    const SymmetricTensor<2, dim> dC  = some_direction<dim>();
    for (const MaterialModel law : laws)
      {
        SCOPED_TRACE(to_string(law) + " " + std::to_string(dim) + "D");
        const HyperelasticMaterial<dim> material(law, steel_like<dim>());
        const double                    h = 1e-5;
        // dW[dC] = S : dC / 2.
        const double dW =
          (material.energy(C + h * dC) - material.energy(C - h * dC)) / (2 * h);
        const SymmetricTensor<2, dim> S = material.second_piola_kirchhoff(C);
        EXPECT_NEAR(dW, 0.5 * (S * dC), 1e-8 * S.norm());
        // dS[dC] = D : dC / 2 (D = dS/dE, dE = dC / 2).
        const SymmetricTensor<2, dim> dS =
          (material.second_piola_kirchhoff(C + h * dC) -
           material.second_piola_kirchhoff(C - h * dC)) /
          (2 * h);
        const SymmetricTensor<2, dim> D_dC = material.tangent(C) * dC;
        EXPECT_LT((dS - 0.5 * D_dC).norm(), 1e-8 * D_dC.norm());
      }
  };
  check(std::integral_constant<int, 2>());
  check(std::integral_constant<int, 3>());
}



TEST(FiniteStrain, BothLawsAreHookesLawAtSmallStrain)
{
  const auto check = [](auto dimension, const PlaneModel plane) {
    constexpr int          dim          = decltype(dimension)::value;
    IsotropicMaterial<dim> material     = steel_like<dim>();
    material.plane_model                = plane;
    const SymmetricTensor<4, dim> hooke = material.stiffness();
    for (const MaterialModel law : laws)
      {
        if (dim == 2 && plane == PlaneModel::plane_stress &&
            !HyperelasticMaterial<dim>::supports_plane_stress(law))
          continue;
        SCOPED_TRACE(to_string(law) + " " + std::to_string(dim) + "D");
        const HyperelasticMaterial<dim> hyperelastic(law, material);
        const SymmetricTensor<2, dim>   I = unit_symmetric_tensor<dim>();
        EXPECT_LT((hyperelastic.tangent(I) - hooke).norm(),
                  1e-13 * hooke.norm());
        EXPECT_LT(hyperelastic.second_piola_kirchhoff(I).norm(), 1e-13);
        EXPECT_NEAR(hyperelastic.energy(I), 0., 1e-13);
      }
  };
  check(std::integral_constant<int, 2>(), PlaneModel::plane_strain);
  check(std::integral_constant<int, 2>(), PlaneModel::plane_stress);
  check(std::integral_constant<int, 3>(), PlaneModel::plane_strain);
}



TEST(FiniteStrain, ARigidRotationBy90DegreesIsStressFree)
{
  // F = R (90 degrees about z): C = I, so S = 0 and W = 0 for both laws,
  // where the small-strain measure would see a strain of -1 on the
  // diagonal.
  Tensor<2, 3> grad_u;
  grad_u[0][0] = grad_u[1][1] = -1.;
  grad_u[0][1]                = -1.;
  grad_u[1][0]                = 1.;
  const Tensor<2, 3> F        = deformation_gradient<3>(grad_u);
  EXPECT_NEAR(determinant(F), 1., 1e-15);
  const SymmetricTensor<2, 3> C = right_cauchy_green(F);
  for (const MaterialModel law : laws)
    {
      const HyperelasticMaterial<3> material(law, steel_like<3>());
      EXPECT_LT(material.second_piola_kirchhoff(C).norm(), 1e-12);
      EXPECT_NEAR(material.energy(C), 0., 1e-12);
      EXPECT_LT(cauchy_stress(F, material.second_piola_kirchhoff(C)).norm(),
                1e-12);
    }
}



TEST(FiniteStrain, TheTangentOfADistortedLagrangeCellIsConsistent)
{
  const auto check = [](auto dimension) {
    constexpr int      dim = decltype(dimension)::value;
    Triangulation<dim> mesh;
    GridGenerator::hyper_cube(mesh, 0., 1.);
    // One vertex moved: the cell is no longer affine.
    Point<dim> &v = mesh.begin_active()->vertex(dim == 2 ? 3 : 7);
    for (unsigned int d = 0; d < dim; ++d)
      v[d] += 0.3 - 0.1 * d;
    const FESystem<dim> fe(FE_Q<dim>(2), dim);
    DoFHandler<dim>     dofs(mesh);
    dofs.distribute_dofs(fe);
    const MappingQ<dim>    mapping(1);
    FEValuesEvaluator<dim> values(mapping,
                                  fe,
                                  QGauss<dim>(4),
                                  update_values | update_gradients |
                                    update_JxW_values |
                                    update_quadrature_points);
    values.reinit(dofs.begin_active());
    // The support points of the basis functions, through the mapping.
    std::vector<Point<dim>> locations(values.n_basis());
    const auto &unit_points = fe.base_element(0).get_unit_support_points();
    for (unsigned int l = 0; l < values.n_basis(); ++l)
      locations[l] = mapping.transform_unit_to_real_cell(dofs.begin_active(),
                                                         unit_points[l]);
    expect_consistent_cell<dim>(values, locations);
  };
  check(std::integral_constant<int, 2>());
  check(std::integral_constant<int, 3>());
}



TEST(FiniteStrain, TheTangentOfANurbsSpanIsConsistent)
{
  const auto check = [](auto dimension) {
    constexpr int          dim = decltype(dimension)::value;
    nurbs::NurbsPatch<dim> patch =
      nurbs::make_thick_cylinder_quarter<dim>(1., 2., 1.);
    patch.elevate_degree(0, 1);
    nurbs::NurbsValues<dim>       values(patch,
                                   QGauss<dim>(5),
                                   update_values | update_gradients |
                                     update_JxW_values |
                                     update_quadrature_points);
    std::array<unsigned int, dim> span;
    span.fill(0);
    values.reinit(span);
    // The control points of the span's basis functions: any point per
    // function serves to lay out a smooth displacement.
    std::vector<Point<dim>> locations;
    for (const unsigned int a : values.control_points())
      locations.push_back(patch.control_point(a));
    expect_consistent_cell<dim>(values, locations);
  };
  check(std::integral_constant<int, 2>());
  check(std::integral_constant<int, 3>());
}



namespace
{
  /**
   * The follower pressure on the face of @p face_values (reinitialised)
   * at a displacement of 20 % strain with a rotation plus a random part:
   * its load stiffness against central differences of its load, and the
   * load's resultant at a homogeneous F against p times the current face
   * vector, -p int cof(F) N dA.
   */
  template <int dim, typename FaceValues>
  void
  expect_consistent_follower_pressure(const FaceValues              &values,
                                      const std::vector<Point<dim>> &locations,
                                      const Tensor<2, dim>          &G)
  {
    const unsigned int  n = values.dofs_per_cell();
    const double        p = 3.;
    std::vector<double> u(n);
    for (unsigned int l = 0; l < values.n_basis(); ++l)
      {
        const Tensor<1, dim> x = locations[l];
        const Tensor<1, dim> y = G * x - x;
        for (unsigned int c = 0; c < dim; ++c)
          u[values.local_dof(l, c)] = y[c];
      }
    // The resultant at the homogeneous F = G: sum over the basis (a
    // partition of unity) of -r.
    {
      Vector<double> r(n);
      add_face_follower_pressure<dim>(values, u, p, r, nullptr);
      Tensor<1, dim> resultant, expected;
      for (unsigned int l = 0; l < values.n_basis(); ++l)
        for (unsigned int c = 0; c < dim; ++c)
          resultant[c] -= r[values.local_dof(l, c)];
      const Tensor<2, dim> cofactor = determinant(G) * transpose(invert(G));
      for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
        expected -= p * values.JxW(q) * (cofactor * values.normal_vector(q));
      EXPECT_LT((resultant - expected).norm(), 1e-12 * expected.norm());
    }
    std::mt19937                           engine(11);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    for (auto &v : u)
      v += 0.02 * uniform(engine);
    Vector<double>     r(n);
    FullMatrix<double> K(n, n);
    add_face_follower_pressure<dim>(values, u, p, r, &K);
    for (unsigned int trial = 0; trial < 3; ++trial)
      {
        std::vector<double> du(n), plus(u), minus(u);
        const double        h = 1e-5;
        for (unsigned int i = 0; i < n; ++i)
          {
            du[i] = uniform(engine);
            plus[i] += h * du[i];
            minus[i] -= h * du[i];
          }
        Vector<double> r_plus(n), r_minus(n), K_du(n), fd(n);
        add_face_follower_pressure<dim>(values, plus, p, r_plus, nullptr);
        add_face_follower_pressure<dim>(values, minus, p, r_minus, nullptr);
        for (unsigned int i = 0; i < n; ++i)
          {
            fd[i] = (r_plus[i] - r_minus[i]) / (2 * h);
            for (unsigned int j = 0; j < n; ++j)
              K_du[i] += K(i, j) * du[j];
          }
        EXPECT_LT(relative_difference(K_du, fd), 1e-7);
      }
  }

} // namespace



TEST(FiniteStrain, TheFollowerPressuresLoadStiffnessIsConsistent)
{
  const auto check = [](auto dimension) {
    constexpr int dim = decltype(dimension)::value;
    // A distorted FE_Q(2) cell, its face x = 1 (face 1, moved vertex).
    Triangulation<dim> mesh;
    GridGenerator::hyper_cube(mesh, 0., 1.);
    Point<dim> &v = mesh.begin_active()->vertex(dim == 2 ? 3 : 7);
    for (unsigned int d = 0; d < dim; ++d)
      v[d] += 0.3 - 0.1 * d;
    const FESystem<dim> fe(FE_Q<dim>(2), dim);
    DoFHandler<dim>     dofs(mesh);
    dofs.distribute_dofs(fe);
    const MappingQ<dim>                       mapping(1);
    FEValuesEvaluator<dim, FEFaceValues<dim>> values(
      mapping,
      fe,
      QGauss<dim - 1>(4),
      update_values | update_gradients | update_JxW_values |
        update_normal_vectors | update_quadrature_points);
    values.reinit(dofs.begin_active(), 1u);
    std::vector<Point<dim>> locations(values.n_basis());
    const auto &unit_points = fe.base_element(0).get_unit_support_points();
    for (unsigned int l = 0; l < values.n_basis(); ++l)
      locations[l] = mapping.transform_unit_to_real_cell(dofs.begin_active(),
                                                         unit_points[l]);
    expect_consistent_follower_pressure<dim>(values,
                                             locations,
                                             stretched_rotation<dim>());

    // A NURBS span's outer face r = 2 (face 1) of the quarter cylinder.
    nurbs::NurbsPatch<dim> patch =
      nurbs::make_thick_cylinder_quarter<dim>(1., 2., 1.);
    patch.elevate_degree(0, 1);
    nurbs::NurbsValues<dim>       face(patch,
                                 QGauss<dim - 1>(6),
                                 update_values | update_gradients |
                                   update_JxW_values | update_normal_vectors |
                                   update_quadrature_points);
    std::array<unsigned int, dim> span;
    span.fill(0);
    face.reinit(span, 1);
    std::vector<Point<dim>> control_points;
    for (const unsigned int a : face.control_points())
      control_points.push_back(patch.control_point(a));
    expect_consistent_follower_pressure<dim>(face,
                                             control_points,
                                             stretched_rotation<dim>());
  };
  check(std::integral_constant<int, 2>());
  check(std::integral_constant<int, 3>());
}
