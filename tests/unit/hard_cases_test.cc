// The hard cases of the reference scenes (stiff contrasts, nu = 0.49, high
// friction, loads and the BDE radius scaled by 1e+-6 and 1e+-4, initial
// gaps, reversal, pairs held on both sides, a load no contact can carry),
// each run by the executable and judged against an independent reference:
// the closed form of the contact patch (uniform pressure, no tangential
// force), Coulomb's bound |F_t| <= mu |F_n|, the exact scaling of linear
// elasticity with a homogeneous contact law (forces proportional to the
// load, displacements unchanged when E and the load scale together), and
// the invariance of the solution under the BDE radius r. A case that has no
// solution must stop with a diagnosis, exit status non-zero and a failed
// summary. `ctest -L hard`.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  using nlohmann::json;

  /// Tolerance on quantities the solver meets to its stopping test (a
  /// relative natural-map residual of 1e-10, amplified by the conditioning
  /// of the condensed system, at most 1e2 on these scenes).
  constexpr double solver_tolerance = 1e-8;

  using cli::SceneRun;

  /// Runs @p scene (a file of prm/) with the overrides @p sets in a
  /// scratch folder named after @p name.
  SceneRun
  run_scene(const std::string &name,
            const std::string &scene,
            const std::string &sets)
  {
    const cli::ScratchFolder scratch(name, "hard");
    return cli::run_prm_scene(scratch.path, scene, sets);
  }

  std::vector<double>
  total_force(const json &summary)
  {
    return summary.at("total_contact_force").get<std::vector<double>>();
  }

  /// Converged, the post-solve condition check met at every step.
  void
  expect_converged(const SceneRun &run)
  {
    ASSERT_EQ(run.status, 0) << run.output;
    ASSERT_EQ(run.summary.at("status"), "ok") << run.output;
    for (const auto &step : run.summary.at("load_steps"))
      EXPECT_LE(step.at("condition_check_max_violation").get<double>(),
                solver_tolerance)
        << "step " << step.at("step");
  }


  /// Converged (expect_converged()), and its warnings as one text (empty
  /// when there are none).
  std::string
  warnings(const SceneRun &run)
  {
    expect_converged(run);
    return run.summary.contains("warnings") ?
             run.summary.at("warnings").dump() :
             std::string();
  }


  /// The contact patch's closed form: pressure 1 at every pair, no
  /// tangential force.
  void
  expect_patch_test(const SceneRun &run)
  {
    expect_converged(run);
    EXPECT_LE(run.summary.at("checks").at("pressure_uniformity").get<double>(),
              solver_tolerance);
    const auto f = total_force(run.summary);
    for (unsigned int c = 0; c + 1 < f.size(); ++c)
      EXPECT_LE(std::abs(f[c]), solver_tolerance * std::abs(f.back()));
  }

  /// The block slides as a whole in the steps @p sliding (0-based) of
  /// @p run: no pair sticks there, and since every pair slips the same way
  /// with p_t = -mu p_n s (s = +1 or -1 the slip direction), the
  /// resultant lies on Coulomb's cone, F_t = -s mu F_n (normal along the
  /// last coordinate, 2D), to the solver's tolerance. That the resultant
  /// never leaves the cone needs no check of its own: it follows from the
  /// per-pair law, which expect_converged() holds at every step.
  void
  expect_sliding_on_the_cone(const SceneRun                  &run,
                             const double                     mu,
                             const std::vector<unsigned int> &sliding,
                             const double                     slip_direction)
  {
    const auto &steps = run.summary.at("load_steps");
    for (const unsigned int s : sliding)
      {
        ASSERT_LT(s, steps.size());
        EXPECT_EQ(steps[s].at("n_stick").get<int>(), 0) << "step " << s + 1;
        const auto f =
          steps[s].at("total_contact_force").get<std::vector<double>>();
        ASSERT_EQ(f.size(), 2u);
        EXPECT_NEAR(f[0],
                    -slip_direction * mu * std::abs(f[1]),
                    solver_tolerance * mu * std::abs(f[1]))
          << "step " << s + 1;
      }
  }

  /// @p scaled holds @p factor times the forces of @p base, with the same
  /// open/stick/slip sets in every step.
  void
  expect_forces_scale(const SceneRun &base,
                      const SceneRun &scaled,
                      const double    factor)
  {
    const auto &a = base.summary.at("load_steps");
    const auto &b = scaled.summary.at("load_steps");
    ASSERT_EQ(a.size(), b.size());
    for (unsigned int s = 0; s < a.size(); ++s)
      {
        for (const char *set : {"n_open", "n_stick", "n_slip"})
          EXPECT_EQ(a[s].at(set), b[s].at(set)) << set << ", step " << s + 1;
        const auto fa =
          a[s].at("total_contact_force").get<std::vector<double>>();
        const auto fb =
          b[s].at("total_contact_force").get<std::vector<double>>();
        double norm = 0.;
        for (const double v : fa)
          norm = std::max(norm, std::abs(v));
        for (unsigned int c = 0; c < fa.size(); ++c)
          EXPECT_NEAR(fb[c] / factor, fa[c], solver_tolerance * norm)
            << "component " << c << ", step " << s + 1;
      }
  }
} // namespace



TEST(HardCase, ContactPatchWithStiffnessContrast)
{
  // E2/E1 = 1e6, frictionless: the patch test's state is uniaxial stress
  // whatever the moduli, so the pressure stays exactly uniform.
  expect_patch_test(run_scene("contrast2d",
                              "v3-contact-patch-2d.prm",
                              "--set 'Body 2/Young'\"'\"'s modulus=1e9'"));
  expect_patch_test(run_scene("contrast3d",
                              "v3-contact-patch-3d.prm",
                              "--set 'Body 2/Young'\"'\"'s modulus=1e9'"));

  // With friction the two blocks' different lateral (Poisson) expansion is
  // resisted at the interface: no closed form, so a second method is the
  // reference, the augmented Lagrangian on the full system.
  const std::string contrast = "--set 'Body 2/Young'\"'\"'s modulus=1e9' "
                               "--set 'Contact/Friction coefficient=2' ";
  const SceneRun    bde =
    run_scene("contrastbde", "v3-contact-patch-2d.prm", contrast);
  const SceneRun al =
    run_scene("contrastal",
              "v3-contact-patch-2d.prm",
              contrast + "--set 'Contact/Algorithm=augmented-lagrange'");
  expect_converged(bde);
  expect_converged(al);
  expect_forces_scale(bde, al, 1.);
}



TEST(HardCase, ContactPatchOnGradedMeshes)
{
  // The patch test on meshes graded toward the contact face (ratio 8 in
  // depth) and along it (ratio 4, the same for both blocks, so that the
  // pairs coincide): the uniform closed-form pressure holds on any mesh,
  // for both discretisations.
  for (const std::string type : {"nurbs", "lagrange"})
    {
      SCOPED_TRACE(type);
      expect_patch_test(run_scene("graded" + type,
                                  "v3-contact-patch-2d.prm",
                                  "--set 'Discretization/Type=" + type +
                                    "' "
                                    "--set 'Discretization/Refinements=0' "
                                    "--set 'Body 1/Subdivisions=8' "
                                    "--set 'Body 2/Subdivisions=8' "
                                    "--set 'Body 1/Grading=0: 4; 2: 8' "
                                    "--set 'Body 2/Grading=0: 4; 3: 8'"));
    }
}



TEST(HardCase, FloatingPlatePatchKeepsEveryPairUniform)
{
  // The upper plate of the 3D patch test (FE_Q(2), 20 x 20 x 1 cells, 0.2
  // thick, 1 681 pairs) is held only through contact: its z translation is
  // pinned at one unknown, and in floating point the pin carries the
  // rounding of the whole plate's balance. The discrete answer is exactly
  // uniform, so every pair's pressure is rounding: about kappa * eps with
  // kappa ~ (L/h)^2 L/t = 8e3 (h = 0.025 between nodes, t = 0.2), 1e-12;
  // the bound allows a thousand times that. A pin on the contact face puts
  // the balance's rounding into one pair's force, divided by the smallest
  // pair area of the face (the corner's, 1/14 400 of the plate): 1.8e-8
  // when the pin sat at the corner node.
  const SceneRun run = run_scene("floatingplate",
                                 "v3-contact-patch-3d.prm",
                                 "--set 'Discretization/Type=lagrange' "
                                 "--set 'Discretization/Refinements=0' "
                                 "--set 'Body 1/Subdivisions=20,20,1' "
                                 "--set 'Body 2/Subdivisions=20,20,1' "
                                 "--set 'Body 1/Upper corner=1,1,0.2' "
                                 "--set 'Body 2/Lower corner=0,0,-0.2' "
                                 "--set 'Contact/Path=full'");
  expect_converged(run);
  EXPECT_LE(run.summary.at("checks").at("pressure_uniformity").get<double>(),
            1e-9);
}



TEST(HardCase, ContactPatchNearlyIncompressible)
{
  expect_patch_test(run_scene("nu049",
                              "v3-contact-patch-2d.prm",
                              "--set 'Body 1/Poisson'\"'\"'s ratio=0.49' "
                              "--set 'Body 2/Poisson'\"'\"'s ratio=0.49' "
                              "--set 'Contact/Friction coefficient=0.3'"));
}



TEST(HardCase, LoadsScaledBy1e6And1em6ScaleTheForces)
{
  // Linear elasticity, zero gaps and a positively homogeneous contact law:
  // forces are proportional to the load, the contact sets unchanged. V4
  // (sliding block, a prescribed displacement) scales its displacement
  // factors with the pressure.
  const SceneRun base = run_scene("v3base",
                                  "v3-contact-patch-2d.prm",
                                  "--set 'Contact/Friction coefficient=0.3'");
  expect_patch_test(base);
  for (const double factor : {1e-6, 1e6})
    {
      SCOPED_TRACE("factor " + std::to_string(factor));
      const std::string p = (factor < 1. ? "1e-6" : "1e6");
      const SceneRun    scaled =
        run_scene("v3scaled" + p,
                  "v3-contact-patch-2d.prm",
                  "--set 'Contact/Friction coefficient=0.3' "
                  "--set 'Body 1/Tractions=3: pressure " +
                    p + "' --set 'Checks/Uniform pressure=" + p + "'");
      expect_patch_test(scaled);
      expect_forces_scale(base, scaled, factor);
    }

  const SceneRun hertz = run_scene("v5base", "v5-hertz-2d.prm", "");
  expect_converged(hertz);
  for (const std::string p : {"1e-6", "1e6"})
    {
      SCOPED_TRACE("Hertz, E and load x " + p);
      // E and the load scaled together: the same displacements, forces
      // scaled by the factor.
      const double   factor = std::stod(p);
      const SceneRun scaled =
        run_scene("v5scaled" + p,
                  "v5-hertz-2d.prm",
                  "--set 'Body 1/Tractions=3: vector 0, " +
                    std::to_string(-15. * factor) +
                    "' --set 'Body 1/Young'\"'\"'s modulus=" +
                    std::to_string(1000. * factor) +
                    "' --set 'Checks/Hertz line load=" +
                    std::to_string(240. * factor) + "'");
      expect_converged(scaled);
      expect_forces_scale(hertz, scaled, factor);
      EXPECT_NEAR(
        scaled.summary.at("checks").at("hertz_half_width").get<double>(),
        hertz.summary.at("checks").at("hertz_half_width").get<double>(),
        solver_tolerance);
    }
}



TEST(HardCase, BdeRadiusScaledBy1e4And1em4GivesTheSameSolution)
{
  // r only weights the two sides of each natural-map equation: the
  // solution of the contact problem does not depend on it.
  for (const char *scene : {"v3-contact-patch-2d.prm", "v5-hertz-2d.prm"})
    {
      const std::string friction =
        std::string(scene).find("v3") == 0 ?
          "--set 'Contact/Friction coefficient=0.3' " :
          "";
      const SceneRun base = run_scene("rbase", scene, friction);
      expect_converged(base);
      for (const char *scale : {"1e-4", "1e4"})
        {
          SCOPED_TRACE(std::string(scene) + ", r x " + scale);
          const SceneRun scaled =
            run_scene(std::string("r") + scale,
                      scene,
                      friction + "--set 'Contact/r scale=" + scale + "'");
          expect_converged(scaled);
          expect_forces_scale(base, scaled, 1.);
        }
    }
}



TEST(HardCase, BdeRadiusScaledBy1e6ConvergesToTheSameSolution)
{
  // At r x 1e6 the merit |H|^2 weighs the displacement rows 1e12 times the
  // force rows: Newton's line search crawls (steps of 1e-3 to 1e-6) or
  // the active sets cycle, in the first radius and in the other alike.
  // The phase at r from the flexibility alone must follow the first one
  // before the budget is spent. Sliding block (mu = 0.4, condensed path,
  // eleven steps: the first radius cycles) and the load-history block
  // (mu = 0.4, Lagrange, full path: the first radius crawls): each step
  // the same forces and sets as at r x 1.
  struct Case
  {
    const char *scene;
    const char *sets;
  };
  for (const Case &c : {Case{"v4-sliding-block.prm", ""},
                        Case{"load-histories-block.prm",
                             "--set 'Discretization/Type=lagrange' "
                             "--set 'Contact/Path=full' "}})
    {
      SCOPED_TRACE(c.scene);
      const SceneRun base = run_scene("r1e6base", c.scene, c.sets);
      expect_converged(base);
      const SceneRun scaled =
        run_scene("r1e6",
                  c.scene,
                  std::string(c.sets) + "--set 'Contact/r scale=1e6'");
      expect_converged(scaled);
      expect_forces_scale(base, scaled, 1.);
    }
}



TEST(HardCase, NewtonResidualExactlyZeroAtTheRoundingFloorConverges)
{
  // B1 with degree-1 NURBS: forces of 1e5 N against gaps of 1e-6 m hold
  // the FCLIB error at 1.4e-9 (the forces' rounding), above the 1e-10
  // tolerance, while the Newton residual H reaches exactly zero. The
  // rounding-floor clause of the stopping test was entered only when |H|
  // fell by less than 2x in a step, which zero after zero never does: the
  // run stalled in every phase and step cut, and failed. Degree-1 NURBS on
  // uniform knots are the trilinear hexahedra, so the Lagrange FE_Q(1) run
  // of the same mesh (whose |H| stays above zero at its floor) is the same
  // discrete problem solved by another discretisation's code: the same
  // displacements and contact force within the solver tolerance amplified
  // as above (1e2) times the larger of the two runs' FCLIB errors.
  const std::string degree_one = "--set Discretization/Degree=1 ";
  const SceneRun    nurbs =
    run_scene("b1q1nurbs", "b1-cantilever-beams.prm", degree_one);
  const SceneRun lagrange =
    run_scene("b1q1lagrange",
              "b1-cantilever-beams.prm",
              degree_one + "--set Discretization/Type=lagrange");
  expect_converged(nurbs);
  expect_converged(lagrange);
  const double error =
    std::max(nurbs.summary.at("load_steps")[0].at("residual").get<double>(),
             lagrange.summary.at("load_steps")[0].at("residual").get<double>());
  const double tolerance   = 1e2 * std::max(error, 1e-10);
  const auto   expect_same = [&](const std::vector<double> &a,
                               const std::vector<double> &b) {
    ASSERT_EQ(a.size(), b.size());
    double norm = 0.;
    for (const double v : b)
      norm = std::max(norm, std::abs(v));
    for (unsigned int c = 0; c < a.size(); ++c)
      EXPECT_NEAR(a[c], b[c], tolerance * norm) << "component " << c;
  };
  expect_same(total_force(nurbs.summary), total_force(lagrange.summary));
  for (const std::string probe : {"A", "C"})
    {
      SCOPED_TRACE("probe " + probe);
      expect_same(
        nurbs.summary.at("points").at(probe).get<std::vector<double>>(),
        lagrange.summary.at("points").at(probe).get<std::vector<double>>());
    }
}



TEST(HardCase, HighFrictionTipsTheBlockAndSlidingStaysOnTheCone)
{
  // V4's block (E = 1000, nu = 0.3: G = 385, width w = 1, height h = 0.5)
  // under the pressure 10, N = 10, with its top moved by 0.05 in x. At
  // mu = 0.4 it slides as a whole once the top has moved past what a
  // uniform shear of mu N needs, mu 10 0.5 / G = 0.005, so at the last step,
  // and the friction force then opposes the slip (+x) on the cone. At
  // mu = 2 it cannot slide: the moment of the friction force about the toe
  // reaches the pressure's, F_t h = N w / 2, at F_t = 10 < mu N = 20, so
  // the block tips: the heel lifts (pairs open) and the toe sticks.
  {
    SCOPED_TRACE("V4, mu = 2");
    const SceneRun run = run_scene("v4mu2",
                                   "v4-sliding-block.prm",
                                   "--set 'Contact/Friction coefficient=2'");
    expect_converged(run);
    const auto &last = run.summary.at("load_steps").back();
    EXPECT_GT(last.at("n_open").get<int>(), 0);
    EXPECT_GT(last.at("n_stick").get<int>(), 0);
  }
  {
    // The gap closes under the pressure before the top moves.
    SCOPED_TRACE("V4, initial gap 1e-3");
    const SceneRun run = run_scene("v4gap",
                                   "v4-sliding-block.prm",
                                   "--set 'Body 2/Plane point=0, -0.001'");
    expect_converged(run);
    expect_sliding_on_the_cone(run, 0.4, {10}, 1.);
  }
  {
    // Top displaced to +0.5 of its final value (0.025, past the 0.005 that
    // sliding needs at mu = 0.4), to +1, back to 0 and to -0.5, then half
    // the pressure: the block slides forward at steps 2 and 3, back at
    // steps 4 and 5 (0.05 of travel back from +0.05 against the 0.01 that
    // reversing the shear needs) and after the pressure is halved.
    SCOPED_TRACE("V4, reversal and unloading");
    const SceneRun run =
      run_scene("v4reversal",
                "v4-sliding-block.prm",
                "--set 'Load path/Load factors=1, 1, 1, 1, 1, 0.5' "
                "--set 'Load path/Displacement factors=0, 0.5, 1, 0, -0.5, "
                "-0.5'");
    expect_converged(run);
    ASSERT_EQ(run.summary.at("load_steps").size(), 6u);
    expect_sliding_on_the_cone(run, 0.4, {1, 2}, 1.);
    expect_sliding_on_the_cone(run, 0.4, {3, 4, 5}, -1.);
  }
}



TEST(HardCase, PairsHeldOnBothSidesAreLeftOutAndCounted)
{
  // B2's clamped theta = 0 edge lies in the contact surface of both beams.
  for (const std::string mu : {"0", "2"})
    {
      SCOPED_TRACE("mu = " + mu);
      const SceneRun run = run_scene("b2mu" + mu,
                                     "b2-curved-beams.prm",
                                     "--set 'Body 1/Subdivisions=2, 2, 2' "
                                     "--set 'Body 2/Subdivisions=2, 2, 2' "
                                     "--set 'Contact/Friction coefficient=" +
                                       mu + "'");
      expect_converged(run);
      EXPECT_GT(
        run.summary.at("effects").at("pairs_left_out_supported").get<int>(),
        0);
    }
}



namespace
{
  /// A half disc R = 8 (centre (0, 8)) pressed onto the plane y = 0 by the
  /// traction 3.75 on its cut (P = 60 per unit length), held by the contact
  /// alone: no support, three free rigid modes; @p arc spans along the arc.
  SceneRun
  floating_half_disc(const std::string &name,
                     const unsigned int arc,
                     const std::string &sets = "")
  {
    return run_scene(name,
                     "v5-hertz-2d.prm",
                     "--set 'Body 1/Geometry=half disc' "
                     "--set 'Body 1/Centre=0, 8' "
                     "--set 'Body 1/Supports=' "
                     "--set 'Body 1/Tractions=3: vector 0, -3.75' "
                     "--set 'Body 1/Subdivisions=" +
                       std::to_string(arc) +
                       ", 8' "
                       "--set 'Checks/Hertz line load=60' " +
                       sets);
  }

  /// Converged in one contact solve per step: started from where the rigid
  /// disc comes to rest (the pairs either side of the load line), the
  /// Newton needs no cut of the load (before, the full path stalled at
  /// full load on every span count from 400 and only the halved
  /// increments converged).
  void
  expect_converged_at_once(const SceneRun &run)
  {
    expect_converged(run);
    for (const auto &step : run.summary.at("load_steps"))
      EXPECT_EQ(step.at("step_cuts").get<int>(), 0)
        << "step " << step.at("step");
  }

  /// Converged, and Johnson's half-space solution met within what the
  /// finite disc allows: the converged models of the quarter disc V5 stay
  /// about 1 % from it (doc/studies.md); 2 % on the peak pressure and 3 %
  /// on the half-width from the pressure's second moment leave room for
  /// the coarse radial mesh (8 spans over R).
  void
  expect_hertz(const SceneRun &run)
  {
    expect_converged_at_once(run);
    const json &checks = run.summary.at("checks");
    EXPECT_NEAR(checks.at("hertz_peak_pressure").get<double>(),
                checks.at("hertz_peak_pressure_exact").get<double>(),
                0.02 * checks.at("hertz_peak_pressure_exact").get<double>());
    EXPECT_LE(checks.at("hertz_half_width_moment_error").get<double>(), 0.03);
  }
} // namespace



TEST(HardCase, FloatingHalfDiscRunsForEverySpanCount)
{
  // Whether a pair sits at the lowest point depends on the parity of the
  // span count; the start of a body held only by contact must not: the
  // closed pairs are chosen until they hold every rigid mode (one pair
  // beside the lowest point lets the disc roll about it). Frictionless:
  // the sideways translation moves no pair along its normal and carries
  // no load, so it is held at zero.
  for (const unsigned int arc :
       {100u, 101u, 200u, 201u, 400u, 401u, 800u, 801u, 1600u, 1601u})
    {
      SCOPED_TRACE("arc spans " + std::to_string(arc));
      expect_hertz(floating_half_disc("halfdisc", arc));
    }
}



TEST(HardCase, FloatingHalfDiscOnTheFullPathAndWithFriction)
{
  // Both parities from 400 spans, where the full path once stalled at full
  // load (the condensed path runs 800 and 1600 above).
  for (const unsigned int arc : {400u, 401u})
    {
      SCOPED_TRACE("full path, arc spans " + std::to_string(arc));
      expect_hertz(
        floating_half_disc("halfdiscfull", arc, "--set 'Contact/Path=full'"));
    }
  // With friction the sideways translation is held by the tangential rows
  // of the closed pairs (the stick branch at the start). Friction on the
  // rigid plane resists the disc's Poisson spreading, so Johnson's
  // frictionless solution is no longer the reference (Spence's problem):
  // the two paths are (equilibrium holds by construction for a floating
  // body, so the resultant is not a check).
  for (const unsigned int arc : {400u, 401u})
    {
      SCOPED_TRACE("friction 0.3, arc spans " + std::to_string(arc));
      std::vector<double> peak;
      for (const std::string path : {"condensed", "full"})
        {
          const SceneRun run = floating_half_disc(
            "halfdiscmu",
            arc,
            "--set 'Contact/Friction coefficient=0.3' --set 'Contact/Path=" +
              path + "'");
          expect_converged_at_once(run);
          peak.push_back(
            run.summary.at("checks").at("hertz_peak_pressure").get<double>());
        }
      EXPECT_NEAR(peak[0], peak[1], 1e-8 * peak[0]);
    }
  // Driven by a displacement of its cut instead of a force, the disc's only
  // free mode is the unloaded sideways translation (b = 0): frictionless it
  // is held at zero, with friction the closed pairs stick. The cut moves
  // down by 0.05; the contact force then follows from the disc's
  // compliance, the same on both paths.
  for (const std::string mu : {"0", "0.3"})
    {
      SCOPED_TRACE("displacement-driven, friction " + mu);
      std::vector<double> force;
      for (const std::string path : {"condensed", "full"})
        {
          const SceneRun run = floating_half_disc(
            "halfdiscu",
            400,
            "--set 'Body 1/Supports=3: y=-0.05' --set 'Body 1/Tractions=' "
            "--set 'Checks/Hertz line load=0' "
            "--set 'Contact/Friction coefficient=" +
              mu + "' --set 'Contact/Path=" + path + "'");
          expect_converged_at_once(run);
          const auto f = total_force(run.summary);
          EXPECT_GT(f[1], 0.);
          force.push_back(f[1]);
        }
      EXPECT_NEAR(force[0], force[1], 1e-8 * force[0]);
    }
}



TEST(HardCase, DraggedBlocksEndWithAWarning)
{
  // V3's block (1 x 1 on a second block, 4 spans per side after two
  // refinements, pressure 1, mu = 0.3) with its top dragged by 0.3: it
  // slides by about 0.3 against a frictional resistance of 0.3, more than
  // the pair spacing (at most 1/4 of the face), so pairs formed in the
  // reference configuration no longer face each other. V4's block (on a
  // rigid plane, where sliding is exact) dragged by 0.5 with mu = 10
  // sticks and shears by about its own height 0.5 (strain of order 1,
  // beyond the small-strain model). Each converges and says that it left
  // the model's range; V3 and V4 as given (no slide; slip 0.05, strain
  // about 3 %) do not.
  const SceneRun slides = run_scene("dragslide",
                                    "v3-contact-patch-2d.prm",
                                    "--set 'Body 1/Supports=3: x=0.3' "
                                    "--set 'Contact/Friction coefficient=0.3' "
                                    "--set 'Checks/Uniform pressure=0'");
  EXPECT_NE(warnings(slides).find("pair spacings apart"), std::string::npos)
    << slides.output;
  // About 0.3 over a spacing of at most 1/4.
  EXPECT_GT(
    slides.summary.at("load_steps").back().at("largest_sliding").get<double>(),
    0.3 / 0.25 * 0.9);
  const SceneRun sticks = run_scene("dragstick",
                                    "v4-sliding-block.prm",
                                    "--set 'Body 1/Supports=3: x=0.5' "
                                    "--set 'Contact/Friction coefficient=10'");
  EXPECT_NE(warnings(sticks).find("the largest strain"), std::string::npos)
    << sticks.output;
  EXPECT_EQ(warnings(run_scene("v3base", "v3-contact-patch-2d.prm", "")), "");
  EXPECT_EQ(warnings(run_scene("v4base", "v4-sliding-block.prm", "")), "");
}



TEST(HardCase, LoadNoContactCanCarryStopsWithADiagnosis)
{
  // The quarter disc without its symmetry support, frictionless, with a
  // sideways load: the frictionless pairs on the plane y = 0 push along y
  // only, so nothing holds the disc horizontally and no solution exists.
  // Found when the contact problem is formed (the sideways translation
  // moves no pair along its normal), before any Newton iteration: an
  // input error naming the mode and the fix.
  const SceneRun run = run_scene("nosolution",
                                 "v5-hertz-2d.prm",
                                 "--set 'Body 1/Supports=' "
                                 "--set 'Body 1/Tractions=3: vector 1, -15'");
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.summary.at("status"), "failed");
  EXPECT_NE(run.output.find("translation x' carries a load that no contact "
                            "pair can balance"),
            std::string::npos)
    << run.output;
  EXPECT_NE(run.output.find("Supports"), std::string::npos) << run.output;
}



TEST(HardCase, LoadPullingAFloatingBodyOffStopsWithADiagnosis)
{
  // Tutorial 1's half disc rests on the rigid plane y = 0 held by contact
  // alone; its load, (0, -3.75) on the cut, at factor -1 pulls it up, the
  // direction the plane pushes it too: the translation y's equilibrium
  // sum p_n + 3.75 * 16 = 0 has no solution with p_n >= 0 (friction adds
  // nothing along y on a flat plane). Found before the step's Newton, with
  // the step before kept; no step cut is tried.
  for (const std::string &sets :
       {std::string("--set 'Load path/Load factors=1, -1'"),
        std::string("--set 'Load path/Load factors=1, -1' "
                    "--set 'Contact/Friction coefficient=0.3' "
                    "--set 'Contact/Path=full'")})
    {
      SCOPED_TRACE(sets);
      const SceneRun run =
        run_scene("pulloff", "tutorial-1-disc-on-plane.prm", sets);
      EXPECT_EQ(run.status, 2) << run.output;
      EXPECT_EQ(run.summary.at("status"), "failed");
      EXPECT_NE(run.output.find("load step 2: the load drives Body 1's free "
                                "rigid mode 'translation y' in a direction "
                                "no contact pair can resist"),
                std::string::npos)
        << run.output;
      EXPECT_EQ(run.output.find("halving the increment"), std::string::npos)
        << run.output;
      ASSERT_EQ(run.summary.at("load_steps").size(), 1u) << run.summary;
      const json &step = run.summary.at("load_steps")[0];
      EXPECT_EQ(step.at("step"), 1);
      // The first step balanced the downward load on the cut, 3.75 * 16.
      EXPECT_NEAR(step.at("total_contact_force")[1].get<double>(),
                  60.,
                  1e-6 * 60.);
    }
}



TEST(HardCase, SimilarBodiesWithHighFrictionKeepHertzsSolution)
{
  // V7's sphere and block are of one material (Dundurs' beta = 0): under a
  // normal load their surfaces move alike tangentially, so friction
  // changes nothing and Hertz's solution stays the reference whatever mu
  // (Johnson, Contact Mechanics, 5.2). Weighted-gap pairs on the symmetry
  // planes have a tangent that moves only held unknowns (to the dual
  // basis' round-off): such directions must be held, not left to a
  // Newton matrix that is singular whenever they stick (mu = 100 did not
  // converge in any step cut; mu = 0.3, which converged in 97 iterations,
  // runs in NoSilentWrongAnswer.FrictionalHertzChecksBetween...).
  for (const char *mu : {"100"})
    {
      SCOPED_TRACE(std::string("mu = ") + mu);
      const SceneRun run =
        run_scene(std::string("v7mu") + mu,
                  "v7-sphere-on-block.prm",
                  std::string("--set 'Contact/Friction coefficient=") + mu +
                    "'");
      expect_converged(run);
      EXPECT_EQ(run.summary.at("load_steps")[0].at("step_cuts"), 0);
      // The bounds of the frictionless V7 test (ContactV7Hertz).
      const json &checks = run.summary.at("checks");
      EXPECT_LT(checks.at("hertz_contact_radius_error").get<double>(), 0.02);
      EXPECT_LT(checks.at("hertz_peak_pressure_error").get<double>(), 0.02);
    }
}



TEST(HardCase, ToleranceBelowTheRoundingFloorSaysSo)
{
  // B1 asks for 1e-14: the balanced residual reaches 2e-17, the relative
  // natural-map residual (FCLIB's) stays near 2e-10, held there by
  // rounding (forces of about 1e5 against gaps of 1e-6). Before, every cut
  // of the load repeated the same failure and the run advised more load
  // steps. Now it stops at once and names the tolerance that accepts the
  // solution, which the second run checks.
  const SceneRun run = run_scene("floor",
                                 "b1-cantilever-beams.prm",
                                 "--set 'Contact/Tolerance=1e-14'");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_EQ(run.summary.at("status"), "failed");
  EXPECT_EQ(run.output.find("halving the increment"), std::string::npos)
    << run.output;
  const std::string said = "a Contact/Tolerance above ";
  const auto        at   = run.output.find(said);
  ASSERT_NE(at, std::string::npos) << run.output;
  EXPECT_NE(run.output.find("Contact/Tolerance = 1e-14 is below what "
                            "rounding lets this problem reach"),
            std::string::npos)
    << run.output;
  const double floor = std::stod(run.output.substr(at + said.size()));
  EXPECT_GT(floor, 1e-14);
  std::ostringstream looser_tolerance;
  looser_tolerance << std::setprecision(3) << 2. * floor;
  const SceneRun looser =
    run_scene("floor-looser",
              "b1-cantilever-beams.prm",
              "--set 'Contact/Tolerance=" + looser_tolerance.str() + "'");
  expect_converged(looser);
}



TEST(HardCase, BeamScenesThroughTheHardList)
{
  // B1 (flat contact z = 1, coarse 12x2x2 per beam) and B2 (curved
  // contact, 2x2x2 per beam) through the list of hard cases: each
  // converges with the exact conditions met at every pair (friction inside
  // Coulomb's cone among them), forces proportional to the load with the
  // same contact sets, the same forces whatever the BDE radius.
  const std::string b2_coarse = "--set 'Body 1/Subdivisions=2, 2, 2' "
                                "--set 'Body 2/Subdivisions=2, 2, 2' ";
  struct Scene
  {
    std::string name, file, coarse, load_point_1, load_point_2;
  };
  for (const Scene &scene :
       {Scene{"b1", "b1-cantilever-beams.prm", "", "0, 0, 2", "0, 1, 2"},
        Scene{"b2", "b2-curved-beams.prm", b2_coarse, "0, 0, 6", "0, 1, 6"}})
    {
      SCOPED_TRACE(scene.name);
      const SceneRun base = run_scene(scene.name, scene.file, scene.coarse);
      expect_converged(base);

      for (const char *mu : {"0", "2"})
        {
          SCOPED_TRACE(std::string("mu = ") + mu);
          const SceneRun run =
            run_scene(scene.name + "mu" + mu,
                      scene.file,
                      scene.coarse +
                        "--set 'Contact/Friction coefficient=" + mu + "'");
          expect_converged(run);
        }
      {
        SCOPED_TRACE("E2/E1 = 1e6, nu = 0.49");
        expect_converged(
          run_scene(scene.name + "contrast",
                    scene.file,
                    scene.coarse +
                      "--set 'Body 2/Young'\"'\"'s modulus=3e16'"));
        expect_converged(
          run_scene(scene.name + "nu049",
                    scene.file,
                    scene.coarse +
                      "--set 'Body 1/Poisson'\"'\"'s ratio=0.49' "
                      "--set 'Body 2/Poisson'\"'\"'s ratio=0.49'"));
      }
      for (const std::string p : {"1e-6", "1e6"})
        {
          SCOPED_TRACE("loads x " + p);
          const double      f     = -1e5 * std::stod(p);
          const std::string force = std::to_string(f) + ", " +
                                    std::to_string(f) + ", " +
                                    std::to_string(f);
          const SceneRun scaled =
            run_scene(scene.name + "load" + p,
                      scene.file,
                      scene.coarse + "--set 'Body 1/Point loads=" +
                        scene.load_point_1 + " : " + force + "; " +
                        scene.load_point_2 + " : " + force + "'");
          expect_converged(scaled);
          expect_forces_scale(base, scaled, std::stod(p));
        }
      for (const char *scale : {"1e-4", "1e4"})
        {
          SCOPED_TRACE(std::string("r x ") + scale);
          const SceneRun scaled =
            run_scene(scene.name + "r" + scale,
                      scene.file,
                      scene.coarse + "--set 'Contact/r scale=" + scale + "'");
          expect_converged(scaled);
          if (scaled.status == 0)
            expect_forces_scale(base, scaled, 1.);
        }
      {
        // Half the load again: the pairs that slipped under the full load
        // hold or slip back.
        SCOPED_TRACE("unloading step");
        const SceneRun run =
          run_scene(scene.name + "unload",
                    scene.file,
                    scene.coarse + "--set 'Load path/Load factors=1, 0.5'");
        expect_converged(run);
        ASSERT_EQ(run.summary.at("load_steps").size(), 2u);
      }
    }

  // B1 with Body 1 lifted by 1e-5 m (the beams' deflection under the load
  // is about 1e-4 m): the free end closes the gap, the clamped end stays
  // open.
  SCOPED_TRACE("B1 initial gap");
  const SceneRun gap = run_scene("b1gap",
                                 "b1-cantilever-beams.prm",
                                 "--set 'Body 1/Lower corner=0, 0, 1.00001' "
                                 "--set 'Body 1/Upper corner=6, 1, 2.00001' "
                                 "--set 'Body 1/Point loads=0, 0, 2.00001 : "
                                 "-1e5, -1e5, -1e5; 0, 1, 2.00001 : -1e5, "
                                 "-1e5, -1e5'");
  expect_converged(gap);
  const auto &step = gap.summary.at("load_steps").back();
  EXPECT_GT(step.at("n_open").get<int>(), 0);
  EXPECT_GT(step.at("n_stick").get<int>() + step.at("n_slip").get<int>(), 0);
}



TEST(HardCase, ContactOnElementsDeeperThanItsZoneWarns)
{
  // V5 with 2 uniform spans across the radius instead of its 16 graded
  // toward the contact face: the elements under the contact are 3.7 deep,
  // 5 times Johnson's half-width 0.746, and the peak pressure comes out
  // several per cent off Johnson (the finite disc's own distance from
  // Johnson is about 1 %); the run converges and says that the depth is
  // under-resolved. V5 as given (elements under 0.5 deep) does not.
  const SceneRun shallow =
    run_scene("deep",
              "v5-hertz-2d.prm",
              "--set 'Body 1/Subdivisions=64, 2' --set 'Body 1/Grading='");
  EXPECT_NE(warnings(shallow).find("elements under the contact are"),
            std::string::npos)
    << shallow.output;
  const json &checks = shallow.summary.at("checks");
  EXPECT_GT(std::abs(checks.at("hertz_peak_pressure").get<double>() /
                       checks.at("hertz_peak_pressure_exact").get<double>() -
                     1.),
            0.03);
  const SceneRun given = run_scene("deep-given", "v5-hertz-2d.prm", "");
  EXPECT_EQ(warnings(given).find("elements under the contact are"),
            std::string::npos)
    << given.output;
}
