// Scenes of more than two bodies (prm/three-block-stack.prm): three blocks
// stacked on non-matching meshes, two contact interactions, the middle block
// held vertically by the two contacts alone. The references are closed
// forms, not earlier runs: the weighted gap transmits a uniform pressure
// exactly, and the stack is in uniaxial stress sigma_yy = -p (plane strain),
// so u_y = -(1 - nu^2) p / E (y + 1) and u_x = nu (1 + nu) p / E x at every
// point. A wrong sign of the middle body's share in the condensed
// flexibility, in the rigid-mode columns or in the coupled system's rows
// (it is the master of one interaction and the slave of the other) moves
// its probe and the lower interface's pressures.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <array>
#include <cmath>
#include <string>

namespace
{
  // The stack's material and load (names of their own: the unity batches
  // join test files).
  constexpr double stack_E = 1000., stack_nu = 0.3, stack_pressure = 1.;

  /// The closed-form displacement of the stack at (x, y).
  std::vector<double>
  uniaxial_displacement(const double x, const double y)
  {
    return {stack_nu * (1. + stack_nu) * stack_pressure / stack_E * x,
            -(1. - stack_nu * stack_nu) * stack_pressure / stack_E * (y + 1.)};
  }

  void
  expect_exact_stack(const cli::SceneTable &run, const bool friction)
  {
    const auto &summary = run.summary;
    ASSERT_EQ(summary["status"], "ok");
    ASSERT_EQ(summary["contact_interactions"].size(), 2u);
    EXPECT_EQ(summary["contact_interactions"][0]["slave_body"], 1);
    EXPECT_EQ(summary["contact_interactions"][1]["slave_body"], 2);
    EXPECT_EQ(summary["contact_interactions"][1]["master_body"], 3);
    // Both interfaces carry pairs, and each pair the uniform pressure: the
    // upper interface at y = 1, the lower at y = 0.
    const auto        &table = run.table;
    const unsigned int n     = table.rows.size();
    ASSERT_EQ(n, summary["n_contact_pairs"].get<unsigned int>());
    double on_interface[2] = {0., 0.};
    for (unsigned int i = 0; i < n; ++i)
      {
        const int k = static_cast<int>(table.number(i, "interaction")) - 1;
        ASSERT_TRUE(k == 0 || k == 1);
        EXPECT_NEAR(table.number(i, "y"), k == 0 ? 1. : 0., 1e-12);
        EXPECT_NEAR(table.number(i, "pressure"), stack_pressure, 1e-8)
          << "pair " << i << " at x = " << table.number(i, "x");
        if (friction)
          {
            EXPECT_NEAR(table.number(i, "p_t1"),
                        0.,
                        1e-8 * table.number(i, "p_n"));
          }
        on_interface[k] += table.number(i, "p_n");
      }
    // Each interface carries the whole load p times the width 1.
    EXPECT_NEAR(on_interface[0], stack_pressure, 1e-10);
    EXPECT_NEAR(on_interface[1], stack_pressure, 1e-10);
    const std::vector<std::pair<std::string, std::array<double, 2>>> probes = {
      {"top", {{0.5, 2.}}},
      {"middle", {{0.5, 0.5}}},
      {"bottom", {{0.5, -0.5}}}};
    for (const auto &[name, x] : probes)
      {
        const std::vector<double> exact = uniaxial_displacement(x[0], x[1]);
        for (unsigned int c = 0; c < 2; ++c)
          EXPECT_NEAR(summary["points"][name][c].get<double>(),
                      exact[c],
                      1e-10 * std::abs(exact[1]))
            << name << " component " << c;
      }
  }
} // namespace



TEST(NBodies, ThreeBlockStackTransmitsTheUniformPressureThroughBothInterfaces)
{
  for (const std::string type : {"nurbs", "lagrange"})
    for (const std::string path : {"condensed", "full"})
      {
        SCOPED_TRACE(type + ", " + path);
        const cli::SceneTable run =
          cli::run_prm_scene_table("stack-" + type + "-" + path,
                                   "n-bodies",
                                   "three-block-stack.prm",
                                   "--set 'Discretization/Type=" + type +
                                     "' --set 'Contact/Path=" + path + "'");
        EXPECT_EQ(run.summary["contact_path"], path);
        expect_exact_stack(run, false);
      }
}



// With friction the blocks, of one material, expand alike under the
// pressure: nothing slips and no tangential force arises, on either path
// (the full path's glued start needs the rows of the corner pairs, whose
// unknowns the supports hold along the tangent, to be held rows).
TEST(NBodies, ThreeBlockStackWithFrictionSticksWithoutTangentialForce)
{
  for (const std::string path : {"condensed", "full"})
    {
      SCOPED_TRACE(path);
      const cli::SceneTable run = cli::run_prm_scene_table(
        "stack-friction-" + path,
        "n-bodies",
        "three-block-stack.prm",
        "--set 'Contact/Friction coefficient=0.3' --set 'Contact/Path=" + path +
          "'");
      expect_exact_stack(run, true);
    }
}



// A frictionless upper interface and a frictional lower one: each
// interaction takes its own coefficient (the summary lists them).
TEST(NBodies, EachInteractionHasItsOwnFrictionCoefficient)
{
  const cli::SceneTable run = cli::run_prm_scene_table(
    "stack-mixed-friction",
    "n-bodies",
    "three-block-stack.prm",
    "--set 'Contact/Interaction 2/Friction coefficient=0.4'");
  const auto &list = run.summary["contact_interactions"];
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0]["friction_coefficient"].get<double>(), 0.);
  EXPECT_EQ(list[1]["friction_coefficient"].get<double>(), 0.4);
  EXPECT_EQ(run.summary["effects"]["tangential_unknowns"], true);
  expect_exact_stack(run, true);
}



// prm/roller-between-plates.prm: a roller (R = 8) held by nothing but its
// two contacts with an elastic plate below and one above, P = 60 per unit
// thickness through both. Each contact is Hertz's with E* of the roller
// and that plate (Johnson, Contact Mechanics, 4.3): a = sqrt(4 P R /
// (pi E*)), p0 = 2 P / (pi a), recomputed here from the closed form. The
// half-width comes from the second moment of each contact's pair forces
// (int p x^2 = P a^2 / 4 for Hertz's profile), the peak from the largest
// pair pressure; the 1 % on both, and on every pair inside 0.9 a.
// The plates are 8 deep against a = 1.05: the half-space's error is
// smaller than that.
TEST(NBodies, RollerBetweenTwoPlatesMeetsHertzAtBothContacts)
{
  const cli::SceneTable run =
    cli::run_prm_scene_table("roller",
                             "n-bodies",
                             "roller-between-plates.prm",
                             "");
  ASSERT_EQ(run.summary["status"], "ok");
  const double P = 60., R = 8.;
  const double E_star = 1. / (2. * (1. - stack_nu * stack_nu) / stack_E);
  const double a      = std::sqrt(4. * P * R / (M_PI * E_star));
  const double p0     = 2. * P / (M_PI * a);
  const auto  &table  = run.table;
  // Each contact's resultant on the roller: the lower plate pushes it up
  // by P, the upper one down by P (the upper plate's load), per unit
  // thickness.
  const auto &forces = run.summary["load_steps"][0]["interaction_forces"];
  ASSERT_EQ(forces.size(), 2u);
  EXPECT_NEAR(forces[0][1].get<double>(), P, 1e-8 * P);
  EXPECT_NEAR(forces[1][1].get<double>(), -P, 1e-8 * P);
  EXPECT_NEAR(forces[0][0].get<double>(), 0., 1e-8 * P);
  for (const int k : {1, 2})
    {
      SCOPED_TRACE("interaction " + std::to_string(k));
      double       force = 0., moment = 0., peak = 0., worst = 0.;
      unsigned int inner = 0;
      for (std::size_t i = 0; i < table.rows.size(); ++i)
        {
          if (static_cast<int>(table.number(i, "interaction")) != k)
            continue;
          const double x = table.number(i, "x"), f = table.number(i, "p_n"),
                       p = table.number(i, "pressure");
          // The lower contact at y = 0, the upper one at y = 16.
          if (f > 0.)
            {
              EXPECT_NEAR(table.number(i, "y"), k == 1 ? 0. : 16., 0.1);
            }
          force += f;
          moment += f * x * x;
          peak = std::max(peak, p);
          if (std::abs(x) < 0.9 * a)
            {
              worst =
                std::max(worst,
                         std::abs(p - p0 * std::sqrt(1. - x * x / (a * a))) /
                           p0);
              ++inner;
            }
        }
      EXPECT_NEAR(force, P, 1e-8 * P);
      EXPECT_NEAR(2. * std::sqrt(moment / force) / a, 1., 0.01);
      EXPECT_NEAR(peak / p0, 1., 0.01);
      EXPECT_GE(inner, 10u);
      EXPECT_LT(worst, 0.01);
      // The scene's own check of this interaction says the same.
      const auto &checks = run.summary["checks"]["interactions"][k - 1];
      EXPECT_NEAR(checks["hertz_half_width_exact"].get<double>(), a, 1e-12 * a);
      EXPECT_NEAR(checks["hertz_half_width_moment"].get<double>(),
                  2. * std::sqrt(moment / force),
                  1e-8 * a);
    }
}
