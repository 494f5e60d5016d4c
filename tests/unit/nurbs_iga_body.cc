// Unit tests of the NURBS body: measure, point operators, surface points,
// patch tests and the Lamé cylinder.
#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/iga_body.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

using namespace dealii;
using namespace igabde;
using namespace igabde::discretization;

namespace
{
  template <int dim>
  BodyDescription<dim>
  describe(const nurbs::NurbsPatch<dim> &geometry,
           const double                  E  = 1000.,
           const double                  nu = 0.3)
  {
    BodyDescription<dim> d;
    d.name                    = "test body";
    d.geometry                = geometry;
    d.material.youngs_modulus = E;
    d.material.poisson_ratio  = nu;
    d.material.plane_model    = elasticity::PlaneModel::plane_strain;
    return d;
  }

  DiscretizationSettings
  settings(const unsigned int degree, const unsigned int refinements)
  {
    DiscretizationSettings s;
    s.type        = discretization::Type::nurbs;
    s.degree      = degree;
    s.refinements = refinements;
    return s;
  }

  template <int dim>
  DirichletCondition<dim>
  roller(const types::boundary_id face, const unsigned int component)
  {
    DirichletCondition<dim> bc;
    bc.boundary_id           = face;
    bc.components[component] = true;
    return bc;
  }
} // namespace



TEST(NurbsIgaBody, MeasureIsExactOnCurvedGeometry)
{
  const double r0 = 1., r1 = 2.;
  const double exact_area = M_PI * (r1 * r1 - r0 * r0) / 4.;
  for (unsigned int p = 2; p <= 3; ++p)
    for (unsigned int ref = 0; ref <= 4; ++ref)
      {
        IgaBody<2> body(describe<2>(nurbs::make_quarter_annulus(r0, r1)),
                        settings(p, ref));
        EXPECT_EQ(body.n_elements(), 1u << (2 * ref));
        EXPECT_NEAR(body.measure(), exact_area, 1e-12 * exact_area)
          << "degree " << p << " refinements " << ref;
      }
  const double exact_volume = M_PI * (25. - 16.) / 4. * 1.;
  for (unsigned int ref = 0; ref <= 2; ++ref)
    {
      IgaBody<3> beam(describe<3>(nurbs::make_curved_beam(4., 5., 1.)),
                      settings(2, ref));
      EXPECT_NEAR(beam.measure(), exact_volume, 1e-12 * exact_volume);
    }
  IgaBody<2> plate(describe<2>(nurbs::make_plate_with_hole(1., 4.)),
                   settings(2, 2));
  EXPECT_NEAR(plate.measure(), 16. - M_PI / 4., 1e-12 * 16.);
  IgaBody<2> disc(describe<2>(nurbs::make_hertz_quarter_disc(8.)),
                  settings(2, 2));
  EXPECT_NEAR(disc.measure(), M_PI * 64. / 4., 1e-12 * 64.);
}



TEST(NurbsIgaBody, PolynomialGeometryTakesTheGaussRuleOfItsDegree)
{
  // A box is a polynomial map: p+1 Gauss points per direction integrate
  // its stiffness exactly; only rational geometries take p+2.
  for (unsigned int p = 2; p <= 3; ++p)
    {
      IgaBody<3> box(describe<3>(nurbs::make_box(Point<3>(0., 0., 0.),
                                                 Point<3>(2., 1., 0.5))),
                     settings(p, 2));
      EXPECT_EQ(box.n_quadrature_points_1d(), p + 1);
      // Round-off of a sum of 64 cells times (p+1)^3 points: n eps.
      EXPECT_NEAR(box.measure(), 1., 64. * 64. * 1e-16);
      IgaBody<3> beam(describe<3>(nurbs::make_curved_beam(4., 5., 1.)),
                      settings(p, 2));
      EXPECT_EQ(beam.n_quadrature_points_1d(), p + 2);
    }
}



TEST(NurbsIgaBody, PointLoadDistribution)
{
  auto desc = describe<2>(nurbs::make_quarter_annulus(1., 2.));
  desc.dirichlet.push_back(roller<2>(2, 1));
  desc.dirichlet.push_back(roller<2>(3, 0));
  IgaBody<2> body(desc, settings(2, 2));
  body.setup();

  const Point<2>     X(1.3 * std::cos(0.6), 1.3 * std::sin(0.6));
  const auto         op = body.point_operator(X);
  const Tensor<1, 2> P({3., -7.});
  Vector<double>     f(body.n_dofs());
  op.distribute(P, f);

  double       weight_sum = 0.;
  Tensor<1, 2> force_sum;
  double       moment = 0.;
  Point<2>     image;
  for (unsigned int k = 0; k < op.weights.size(); ++k)
    {
      EXPECT_GE(op.weights[k], -1e-15);
      weight_sum += op.weights[k];
      const unsigned int a = op.dofs[k][0] / 2;
      EXPECT_EQ(op.dofs[k][1], op.dofs[k][0] + 1);
      image += op.weights[k] * body.patch().control_point(a);
    }
  for (unsigned int a = 0; a < body.patch().n_control_points(); ++a)
    {
      const Tensor<1, 2> Pa({f[2 * a], f[2 * a + 1]});
      force_sum += Pa;
      const Point<2> &x = body.patch().control_point(a);
      moment += x[0] * Pa[1] - x[1] * Pa[0];
    }
  EXPECT_NEAR(weight_sum, 1., 1e-14);
  EXPECT_NEAR((force_sum - P).norm(), 0., 1e-13);
  EXPECT_NEAR(moment, X[0] * P[1] - X[1] * P[0], 1e-12);
  EXPECT_NEAR((image - X).norm(), 0., 1e-12);

  // The weights are R_A at the inverted parametric point.
  const Point<2>            xi = body.parametric_point(X);
  std::vector<unsigned int> idx;
  std::vector<double>       R;
  body.patch().basis(xi, idx, R);
  ASSERT_EQ(idx.size(), op.weights.size());
  for (unsigned int k = 0; k < idx.size(); ++k)
    {
      EXPECT_EQ(2 * idx[k], op.dofs[k][0]);
      EXPECT_NEAR(R[k], op.weights[k], 1e-15);
    }

  // A point outside the body is refused with a clear error.
  EXPECT_THROW(body.point_operator(Point<2>(3., 3.)), std::exception);
  // Boundary points are accepted.
  EXPECT_NO_THROW(body.point_operator(Point<2>(0., 2.)));
  EXPECT_NO_THROW(body.point_operator(Point<2>(1.5, 0.)));
}



TEST(NurbsIgaBody, SurfacePointsAndTributaryAreas)
{
  IgaBody<2> body(describe<2>(nurbs::make_quarter_annulus(1., 2.)),
                  settings(2, 3));
  body.setup();
  const double inner_length = M_PI / 2.;
  for (const auto placement :
       {PairPlacement::greville, PairPlacement::knots, PairPlacement::gauss})
    {
      const auto points = body.surface_points(0, placement);
      double     total  = 0.;
      for (const auto &sp : points)
        {
          EXPECT_NEAR(sp.location.norm(), 1., 1e-14);
          EXPECT_NEAR((sp.normal + sp.location / sp.location.norm()).norm(),
                      0.,
                      1e-13);
          EXPECT_NEAR((body.patch().value(sp.parametric) - sp.location).norm(),
                      0.,
                      1e-15);
          EXPECT_NEAR(sp.op.weights.size(), 9u, 0);
          total += sp.tributary_area;
        }
      EXPECT_NEAR(total, inner_length, 1e-9)
        << "placement " << static_cast<int>(placement);
      if (placement == PairPlacement::greville)
        {
          EXPECT_EQ(points.size(), body.patch().n_control_points(1));
        }
      else if (placement == PairPlacement::knots)
        {
          EXPECT_EQ(points.size(), 9u);
        }
      else
        {
          EXPECT_EQ(points.size(), 8u * 3u);
        }
    }

  // Greville areas reproduce a uniform pressure exactly: the pair forces of
  // a unit pressure, distributed to the control points, equal int R_A n
  // (checked on the flat face 2, where n is constant).
  const auto     points = body.surface_points(2, PairPlacement::greville);
  Vector<double> f(body.n_dofs());
  for (const auto &sp : points)
    sp.op.distribute(sp.tributary_area * sp.normal, f);
  // Compare with a traction assembly of the same unit pressure.
  auto                desc = describe<2>(nurbs::make_quarter_annulus(1., 2.));
  NeumannCondition<2> pressure;
  pressure.boundary_id = 2;
  pressure.traction    = [](const Point<2> &, const Tensor<1, 2> &n) {
    return n;
  };
  desc.tractions.push_back(pressure);
  desc.dirichlet.push_back(roller<2>(2, 1));
  desc.dirichlet.push_back(roller<2>(3, 0));
  IgaBody<2> loaded(desc, settings(2, 3));
  loaded.setup();
  Vector<double> diff = loaded.load_vector();
  diff -= f;
  EXPECT_LT(diff.linfty_norm(), 1e-13 * loaded.load_vector().linfty_norm());
}



namespace
{
  // Uniaxial stress sigma_xx = s under rollers: exact in any NURBS space.
  template <int dim>
  void
  run_patch_test(
    const nurbs::NurbsPatch<dim>                             &geometry,
    const std::vector<std::pair<unsigned int, unsigned int>> &rollers,
    const std::vector<unsigned int>                          &loaded_faces,
    const unsigned int                                        degree,
    const unsigned int                                        refinements,
    const double                                              tolerance)
  {
    const double E = 1000., nu = 0.3, s = 7.;
    auto         desc = describe<dim>(geometry, E, nu);
    for (const auto &[face, c] : rollers)
      desc.dirichlet.push_back(roller<dim>(face, c));
    for (const unsigned int face : loaded_faces)
      {
        NeumannCondition<dim> t;
        t.boundary_id = face;
        t.traction    = [s](const Point<dim> &, const Tensor<1, dim> &n) {
          Tensor<1, dim> r;
          r[0] = s * n[0];
          return r;
        };
        desc.tractions.push_back(t);
      }
    // Plane strain in 2D: eps_xx = (1 - nu^2) s / E, eps_yy = -nu (1 + nu)
    // s / E; 3D: eps_xx = s / E, eps_yy = eps_zz = -nu s / E.
    const double       exx = (dim == 2 ? (1. - nu * nu) : 1.) * s / E;
    const double       eyy = (dim == 2 ? -nu * (1. + nu) : -nu) * s / E;
    ExactSolution<dim> exact;
    exact.displacement = [=](const Point<dim> &x) {
      Tensor<1, dim> u;
      u[0] = exx * x[0];
      for (unsigned int d = 1; d < dim; ++d)
        u[d] = eyy * x[d];
      return u;
    };
    exact.stress = [=](const Point<dim> &) {
      SymmetricTensor<2, dim> sigma;
      sigma[0][0] = s;
      return sigma;
    };

    IgaBody<dim> body(desc, settings(degree, refinements));
    body.setup();
    EXPECT_TRUE(body.free_rigid_modes().empty());
    const Vector<double> &u       = body.load_solution();
    double                max_err = 0.;
    for (unsigned int a = 0; a < body.patch().n_control_points(); ++a)
      {
        const Tensor<1, dim> ue =
          exact.displacement(body.patch().control_point(a));
        for (unsigned int c = 0; c < dim; ++c)
          max_err = std::max(max_err, std::abs(u[dim * a + c] - ue[c]));
      }
    EXPECT_LT(max_err, tolerance * exx * 4.);
    const ErrorNorms errors = body.compute_errors(u, exact);
    EXPECT_LT(errors.l2_relative, tolerance);
    EXPECT_LT(errors.energy_relative, tolerance);

    Point<dim> probe =
      body.patch().value(0.5 * (body.patch().parametric_lower() +
                                body.patch().parametric_upper()));
    const SymmetricTensor<2, dim> sigma = body.stress(u, probe);
    EXPECT_NEAR(sigma[0][0], s, tolerance * s);
    EXPECT_NEAR(sigma[1][1], 0., tolerance * s);
  }
} // namespace



TEST(NurbsIgaBody, GrevilleAreasReproduceAUniformPressureIn3D)
{
  // The Greville areas of a 3D face are found direction by direction (the
  // collocation matrix is a Kronecker product scaled by the weights). On
  // the flat, rational end face 4 of the curved beam, a unit pressure
  // spread by the pair points with those areas must equal the consistent
  // load of the same pressure assembled by quadrature.
  for (unsigned int p = 2; p <= 3; ++p)
    {
      auto       desc = describe<3>(nurbs::make_curved_beam(4., 5., 1.));
      IgaBody<3> body(desc, settings(p, 2));
      body.setup();
      const auto points = body.surface_points(4, PairPlacement::greville);
      ASSERT_EQ(points.size(),
                body.patch().n_control_points(0) *
                  body.patch().n_control_points(1));
      Vector<double> f(body.n_dofs());
      for (const auto &sp : points)
        sp.op.distribute(sp.tributary_area * sp.normal, f);

      NeumannCondition<3> pressure;
      pressure.boundary_id = 4;
      pressure.traction    = [](const Point<3> &, const Tensor<1, 3> &n) {
        return n;
      };
      desc.tractions.push_back(pressure);
      IgaBody<3> loaded(desc, settings(p, 2));
      loaded.setup();
      Vector<double> diff = loaded.load_vector();
      diff -= f;
      EXPECT_LT(diff.linfty_norm(), 1e-13 * loaded.load_vector().linfty_norm())
        << "degree " << p;
    }
}



TEST(NurbsIgaBody, PatchTestBox)
{
  run_patch_test<2>(nurbs::make_box(Point<2>(0., 0.), Point<2>(2., 1.)),
                    {{0, 0}, {2, 1}},
                    {1},
                    2,
                    2,
                    1e-10);
  run_patch_test<2>(nurbs::make_box(Point<2>(0., 0.), Point<2>(2., 1.)),
                    {{0, 0}, {2, 1}},
                    {1},
                    3,
                    1,
                    1e-10);
  run_patch_test<3>(nurbs::make_box(Point<3>(0., 0., 0.), Point<3>(2., 1., 1.)),
                    {{0, 0}, {2, 1}, {4, 2}},
                    {1},
                    2,
                    1,
                    1e-10);
}



TEST(NurbsIgaBody, PatchTestCurved)
{
  // The rational space reproduces affine fields, so a uniform stress on the
  // plate with hole is exact up to the face quadrature of the tractions.
  run_patch_test<2>(nurbs::make_plate_with_hole(1., 4.),
                    {{2, 1}, {3, 0}},
                    {0, 1},
                    2,
                    2,
                    1e-8);
}



TEST(NurbsIgaBody, LameCylinderConverges)
{
  const double     a = 1., b = 2., p = 1., E = 1000., nu = 0.3;
  ExactSolution<2> exact;
  exact.displacement = [=](const Point<2> &x) {
    const double r  = x.norm();
    const double ur = (1. + nu) * a * a * p / (E * (b * b - a * a)) *
                      ((1. - 2. * nu) * r + b * b / r);
    return Tensor<1, 2>(ur * x / r);
  };
  exact.stress = [=](const Point<2> &x) {
    const double          r2  = x.norm_square();
    const double          c   = a * a * p / (b * b - a * a);
    const double          srr = c * (1. - b * b / r2);
    const double          stt = c * (1. + b * b / r2);
    const Tensor<1, 2>    er  = x / std::sqrt(r2);
    SymmetricTensor<2, 2> s;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = i; j < 2; ++j)
        s[i][j] = srr * er[i] * er[j] + stt * ((i == j) - er[i] * er[j]);
    return s;
  };

  auto desc = describe<2>(nurbs::make_quarter_annulus(a, b), E, nu);
  desc.dirichlet.push_back(roller<2>(2, 1));
  desc.dirichlet.push_back(roller<2>(3, 0));
  NeumannCondition<2> inner;
  inner.boundary_id = 0;
  inner.traction    = [p](const Point<2> &, const Tensor<1, 2> &n) {
    return Tensor<1, 2>(-p * n);
  };
  desc.tractions.push_back(inner);

  std::vector<ErrorNorms> errors;
  for (unsigned int ref = 1; ref <= 4; ++ref)
    {
      IgaBody<2> body(desc, settings(2, ref));
      body.setup();
      errors.push_back(body.compute_errors(body.load_solution(), exact));
    }
  for (unsigned int i = 1; i < errors.size(); ++i)
    {
      const double l2_rate =
        std::log2(errors[i - 1].l2_relative / errors[i].l2_relative);
      const double en_rate =
        std::log2(errors[i - 1].energy_relative / errors[i].energy_relative);
      EXPECT_GT(l2_rate, 2.7) << "refinement " << i + 1;
      EXPECT_GT(en_rate, 1.8) << "refinement " << i + 1;
    }
  EXPECT_LT(errors.back().l2_relative, 1e-5);
}



TEST(NurbsIgaBody, WritesVtu)
{
  auto desc = describe<3>(nurbs::make_curved_beam(4., 5., 1.));
  desc.dirichlet.push_back(roller<3>(2, 0));
  desc.dirichlet.push_back(roller<3>(2, 1));
  desc.dirichlet.push_back(roller<3>(2, 2));
  desc.point_loads.push_back(
    {Point<3>(0., 0.5, 5.), Tensor<1, 3>({0., 0., -1.})});
  IgaBody<3> body(desc, settings(2, 1));
  body.setup();
  EXPECT_TRUE(body.free_rigid_modes().empty());
  // The tip moves down.
  const auto tip = body.point_operator(Point<3>(0., 0.5, 5.));
  EXPECT_LT(tip.displacement(body.load_solution())[2], 0.);

  const std::string name = "nurbs_iga_body_test.vtu";
  body.write_vtu(body.load_solution(), name, 0, 1);
  std::ifstream     in(name);
  std::stringstream content;
  content << in.rdbuf();
  EXPECT_NE(content.str().find("displacement"), std::string::npos);
  EXPECT_NE(content.str().find("von_mises"), std::string::npos);
  // Output subdivisions = auto on this coarse mesh (at most 8192 / 64
  // cells): 4 per direction, one patch of 4^3 hexahedra per element.
  ASSERT_LE(body.n_elements() * 64, 8192u);
  EXPECT_NE(content.str().find("NumberOfCells=\"" +
                               std::to_string(body.n_elements() * 64) + "\""),
            std::string::npos)
    << body.n_elements();
  std::remove(name.c_str());
}



TEST(DiscretizationSettings, AutoOutputSubdivisions)
{
  // The largest s <= 4 with n s^dim <= 8192; a set value is kept.
  EXPECT_EQ(output_subdivisions_for<2>(0, 32), 4u);   // 512
  EXPECT_EQ(output_subdivisions_for<2>(0, 1024), 2u); // 9216 > 8192 at 3
  EXPECT_EQ(output_subdivisions_for<2>(0, 2048), 2u); // exactly 8192
  EXPECT_EQ(output_subdivisions_for<2>(0, 2049), 1u);
  EXPECT_EQ(output_subdivisions_for<2>(0, 1e6), 1u);
  EXPECT_EQ(output_subdivisions_for<2>(3, 1e6), 3u);
  EXPECT_EQ(output_subdivisions_for<3>(0, 128), 4u); // exactly 8192
  EXPECT_EQ(output_subdivisions_for<3>(0, 129), 3u);
  EXPECT_EQ(output_subdivisions_for<3>(0, 304), 2u); // 8208 > 8192 at 3
  EXPECT_EQ(output_subdivisions_for<3>(0, 1025), 1u);
  EXPECT_EQ(output_subdivisions_for<3>(16, 8), 16u);
}



TEST(NurbsIgaBody, HertzContactFace)
{
  const double R    = 8.;
  auto         desc = describe<2>(nurbs::make_hertz_quarter_disc(R));
  desc.dirichlet.push_back(roller<2>(0, 0));
  desc.dirichlet.push_back(roller<2>(2, 1));
  IgaBody<2> body(desc, settings(2, 3));
  body.setup();
  // The contact face 2: the lower arc from (0, 0) to 45 degrees.
  const auto points = body.surface_points(2, PairPlacement::greville);
  EXPECT_EQ(points.size(), body.patch().n_control_points(0));
  double total = 0.;
  for (const auto &sp : points)
    {
      const Tensor<1, 2> radial = (sp.location - Point<2>(0., R)) / R;
      EXPECT_NEAR(radial.norm(), 1., 1e-14);
      EXPECT_NEAR((sp.normal - radial).norm(), 0., 1e-13);
      EXPECT_GT(sp.tributary_area, 0.);
      total += sp.tributary_area;
    }
  EXPECT_NEAR(total, R * M_PI / 4., 1e-9 * R);
  EXPECT_NEAR(points.front().location.norm(), 0., 1e-14);
  EXPECT_NEAR(points.back().location[0], R / std::sqrt(2.), 1e-13);

  // The stress at the singular corner (45 degrees) is finite.
  Vector<double> u(body.n_dofs());
  for (unsigned int a = 0; a < body.patch().n_control_points(); ++a)
    u[2 * a] = 1e-3 * body.patch().control_point(a)[0];
  const auto sigma = body.stress(u, points.back().location);
  EXPECT_TRUE(std::isfinite(sigma.norm()));
  const auto eps = body.strain_at_parametric(u, points.back().parametric);
  EXPECT_NEAR(eps[0][0], 1e-3, 1e-9);
  EXPECT_NEAR(eps[1][1], 0., 1e-9);
}



// On the condensed path a body keeps of K only the rows the support
// reactions read once its load cases are solved. The reaction of a clamped
// block pulled by a uniform traction must be the same from the reduced K
// as from the whole one, and both minus the applied resultant (closed
// form: traction times the loaded face's length); the whole K is refused
// afterwards.
TEST(NurbsIgaBody, ReactionRowsOnlyKeepTheSupportReaction)
{
  const double s = 7., height = 1.5;
  auto         desc =
    describe<2>(nurbs::make_box<2>(Point<2>(0., 0.), Point<2>(4., height)));
  DirichletCondition<2> clamp;
  clamp.boundary_id   = 0;
  clamp.components[0] = clamp.components[1] = true;
  desc.dirichlet.push_back(clamp);
  NeumannCondition<2> pull;
  pull.boundary_id = 1;
  pull.traction    = [s](const Point<2> &, const Tensor<1, 2> &n) {
    Tensor<1, 2> t;
    t[0] = s * n[0];
    return t;
  };
  desc.tractions.push_back(pull);

  IgaBody<2> body(desc, settings(2, 3));
  body.setup();
  const Vector<double> &u      = body.load_solution();
  const Vector<double> &f      = body.load_vector();
  const Tensor<1, 2>    before = body.support_reaction(u, f);
  EXPECT_NEAR(before[0], -s * height, 1e-10 * s * height);
  EXPECT_NEAR(before[1], 0., 1e-10 * s * height);

  body.keep_reaction_rows_only();
  const Tensor<1, 2> after = body.support_reaction(u, f);
  EXPECT_EQ(after[0], before[0]);
  EXPECT_EQ(after[1], before[1]);
  EXPECT_THROW(body.stiffness_matrix(), dealii::ExceptionBase);
}
