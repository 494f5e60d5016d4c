// V7 (prm/v7-sphere-on-block.prm): an elastic sphere R = 1 pressed onto an
// elastic block of the same material (E = 1000, nu = 0.3), frictionless,
// quarter model. The reference is Hertz's point contact (Johnson, Contact
// Mechanics sec. 4.2), computed here from the scene's data: P = 4 t A with
// t = 3.75 the traction on the sector's inner face r = 0.3, whose area is
// A = 0.3^2 (pi/4) sin(pi/4); 1/E* = 2 (1 - nu^2)/E,
// a = (3 P R / (4 E*))^(1/3), p0 = 3 P / (2 pi a^2). The criterion is the
// issue's: a and p0 within 2 % on the scene's mesh, for both
// discretisations. It leaves room for what the scene is not: the sector
// reaches 7 a above the contact and the block 10 a below and beside it,
// not half-spaces, and the pairs' pressures are means over their
// supports (weighted-gap).

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

// Named, not anonymous: the unity build puts several test files in one
// translation unit, where anonymous-namespace names (R, E, nu, ...) of
// different files would clash.
namespace v7_hertz_test
{
  constexpr double R = 1., E = 1000., nu = 0.3, traction = 3.75;

  /// Hertz's load, contact radius and peak pressure for the scene.
  std::array<double, 3>
  hertz()
  {
    const double P = 4. * traction * 0.09 * M_PI / 4. * std::sin(M_PI / 4.);
    const double e_star = 1. / (2. * (1. - nu * nu) / E);
    const double a      = std::cbrt(3. * P * R / (4. * e_star));
    return {{P, a, 3. * P / (2. * M_PI * a * a)}};
  }

  struct V7Run
  {
    nlohmann::json summary;
    /// Pair x, y, normal force and pressure (contact-0001.csv).
    std::vector<std::array<double, 4>> pairs;
  };

  V7Run
  run_v7(const std::string &name, const std::string &sets)
  {
    const cli::ScratchFolder scratch(name, "v7");
    const cli::SceneRun      scene =
      cli::run_prm_scene(scratch.path, "v7-sphere-on-block.prm", sets);
    EXPECT_EQ(scene.status, 0) << scene.output;
    V7Run run;
    run.summary = scene.summary;
    const cli::CsvTable table =
      cli::read_table(cli::join(scratch.path, "out/contact-0001.csv"));
    EXPECT_EQ(table.header,
              (std::vector<std::string>{"pair",
                                        "x",
                                        "y",
                                        "z",
                                        "area",
                                        "gap",
                                        "p_n",
                                        "pressure",
                                        "recovered_pressure",
                                        "status"}));
    for (std::size_t r = 0; r < table.rows.size(); ++r)
      run.pairs.push_back(std::array<double, 4>{{table.number(r, "x"),
                                                 table.number(r, "y"),
                                                 table.number(r, "p_n"),
                                                 table.number(r, "pressure")}});
    return run;
  }

  /// Checks one run against Hertz: the summary's own reference values,
  /// and a and p0 recomputed here from the pair table.
  void
  expect_hertz(const V7Run &run, const double area_tolerance)
  {
    const auto [P, a, p0] = hertz();
    ASSERT_EQ(run.summary.at("status"), "ok");
    const auto &checks = run.summary.at("checks");
    EXPECT_NEAR(checks.at("hertz_contact_radius_exact").get<double>(),
                a,
                1e-6 * a);
    EXPECT_NEAR(checks.at("hertz_peak_pressure_exact").get<double>(),
                p0,
                1e-6 * p0);
    EXPECT_LE(checks.at("hertz_contact_radius_error").get<double>(), 0.02);
    EXPECT_LE(checks.at("hertz_peak_pressure_error").get<double>(), 0.02);

    // From the pair table: a from the second moment of the pair forces
    // (int p r^2 dA / int p dA = 2 a^2 / 5 for Hertz's profile), p0 the
    // largest pair pressure.
    double force = 0., moment = 0., peak = 0.;
    for (const auto &[x, y, f, p] : run.pairs)
      {
        force += f;
        moment += f * (x * x + y * y);
        peak = std::max(peak, p);
      }
    const double a_h = std::sqrt(2.5 * moment / force);
    EXPECT_NEAR(a_h / a, 1., 0.02) << "a_h = " << a_h << ", Hertz " << a;
    EXPECT_NEAR(peak / p0, 1., 0.02) << "p0_h = " << peak << ", Hertz " << p0;
    // The pairs carry a quarter of P: the sphere is held vertically by the
    // contact alone, so their sum is the traction integrated over the
    // curved inner face by the body's face quadrature, compared here with
    // the closed-form area.
    EXPECT_NEAR(4. * force / P, 1., area_tolerance);
  }



  TEST(ContactV7Hertz, NurbsContactRadiusAndPeakWithinTwoPercent)
  {
    // The NURBS face is the exact sphere: only quadrature error.
    expect_hertz(run_v7("nurbs", ""), 1e-8);
  }



  TEST(ContactV7Hertz, LagrangeContactRadiusAndPeakWithinTwoPercent)
  {
    // FE_Q(2) interpolates the curved face: its area is off by O(theta^4)
    // for spans of angle theta, at most 0.11 rad here (the coarsest of the
    // graded spans): 1.5e-4 times a small constant (2.3e-7 measured).
    expect_hertz(run_v7("lagrange", "--set 'Discretization/Type=lagrange'"),
                 1e-5);
  }


  // The elliptical contact of prm/hertz-elliptical-contact.prm: V7's
  // sector stretched by sqrt 2 in x (an ellipsoid with principal radii 2
  // and 1 at its lowest point) on the same block and mesh. The load is the
  // traction times the stretched inner face's area (contrib/geometry/
  // sphere-sector --inner-face-area, in closed form), a quarter of
  // P = 1.014283211633063, which the scene gives the check. The semi-axes
  // (force moments) and the peak must meet Johnson's elliptical Hertz
  // within 2 %, the criterion of V7 for the same reasons; its closed form
  // itself is checked against Boussinesq's half-space
  // (HertzEllipticCheck.ClosedFormIndentsTheHalfSpaceByTheGap).
  TEST(ContactV7Hertz, EllipticalContactOfAnEllipsoidMeetsHertz)
  {
    const cli::ScratchFolder scratch("elliptical", "v7");
    const cli::SceneRun      scene =
      cli::run_prm_scene(scratch.path, "hertz-elliptical-contact.prm", "");
    ASSERT_EQ(scene.status, 0) << scene.output;
    const auto &checks = scene.summary.at("checks");
    const auto  exact  = checks.at("hertz_semi_axes_exact");
    const auto  moment = checks.at("hertz_semi_axes_moment");
    // The stretched sector's exact semi-axes, from B/A = 2: the longer
    // along x (the smaller curvature).
    EXPECT_GT(exact[0].get<double>(), 1.5 * exact[1].get<double>());
    for (unsigned int d = 0; d < 2; ++d)
      EXPECT_NEAR(moment[d].get<double>() / exact[d].get<double>(), 1., 0.02)
        << d;
    EXPECT_LE(checks.at("hertz_peak_pressure_error").get<double>(), 0.02);
    // The check's load is the scene's: the contact resultant balances it.
    EXPECT_NEAR(4. * scene.summary.at("load_steps")[0]
                       .at("total_contact_force")[2]
                       .get<double>(),
                1.014283211633063,
                1e-8);
  }
} // namespace v7_hertz_test
