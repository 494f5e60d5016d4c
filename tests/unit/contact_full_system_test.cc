// The full-system contact algorithms against the condensed B-Newton, run by
// the executable on the reference scenes: the uncondensed BDE and the
// augmented Lagrangian must reach the condensed answer (a second method on
// the same equations), the penalty answer must approach it as FKN grows.

#include <igabde/base/utilities.h>

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  struct SceneRun
  {
    nlohmann::json summary;
    // What the executable printed.
    std::string output;
    // Pair states of every step (from contact-NNNN.csv).
    std::vector<std::vector<std::string>> status;
  };

  SceneRun
  run_scene(const std::string &scene,
            const std::string &settings,
            const std::string &folder)
  {
    const std::string out = cli::join(folder, "out");
    const auto        r =
      cli::run_igabde(cli::join(std::string(IGABDE_SOURCE_DIR),
                                "prm/" + scene + ".prm") +
                        " --set " + "'Output/Directory=" + out +
                        "' --set 'Output/Write vtu=false' " +
                        "--set Contact/Tolerance=1e-12 " + settings,
                      folder);
    EXPECT_EQ(r.status, 0) << scene << " " << settings << "\n" << r.output;
    SceneRun run;
    run.output = r.output;
    std::ifstream in(cli::join(out, "summary.json"));
    if (!in)
      return run;
    run.summary = nlohmann::json::parse(in);
    for (unsigned int s = 1; s <= run.summary["load_steps"].size(); ++s)
      {
        std::ostringstream name;
        name << "contact-" << std::setw(4) << std::setfill('0') << s << ".csv";
        std::ifstream            csv(std::filesystem::path(out) / name.str());
        std::string              line;
        std::vector<std::string> states;
        std::getline(csv, line); // header
        while (std::getline(csv, line))
          states.push_back(line.substr(line.rfind(',') + 1));
        run.status.push_back(states);
      }
    return run;
  }

  double
  norm(const nlohmann::json &v)
  {
    double s = 0.;
    for (const auto &x : v)
      s += x.get<double>() * x.get<double>();
    return std::sqrt(s);
  }

  double
  difference(const nlohmann::json &a, const nlohmann::json &b)
  {
    double s = 0.;
    for (unsigned int i = 0; i < a.size(); ++i)
      s += std::pow(a[i].get<double>() - b[i].get<double>(), 2);
    return std::sqrt(s);
  }

  // Largest relative difference of the step contact forces and of the probe
  // displacements (relative to the largest probe displacement).
  double
  deviation(const SceneRun &a, const SceneRun &b)
  {
    double d = 0.;
    for (unsigned int s = 0; s < a.summary["load_steps"].size(); ++s)
      {
        const auto &fa = a.summary["load_steps"][s]["total_contact_force"];
        const auto &fb = b.summary["load_steps"][s]["total_contact_force"];
        d = std::max(d, difference(fa, fb) / std::max(norm(fa), 1e-300));
      }
    double scale = 0.;
    for (const auto &[name, value] : a.summary["points"].items())
      scale = std::max(scale, norm(value));
    for (const auto &[name, value] : a.summary["points"].items())
      d = std::max(d, difference(value, b.summary["points"][name]) / scale);
    return d;
  }

  // Two runs of @p scene answer alike: as many steps, the contact forces
  // and probe displacements within 1e-8 (deviation()), every pair's state
  // equal in every step.
  void
  expect_same_answer(const SceneRun    &a,
                     const SceneRun    &b,
                     const std::string &scene)
  {
    ASSERT_EQ(a.status.size(), b.status.size()) << scene;
    EXPECT_LT(deviation(a, b), 1e-8) << scene;
    for (unsigned int s = 0; s < b.status.size(); ++s)
      EXPECT_EQ(a.status[s], b.status[s]) << scene << ", step " << s + 1;
  }

  const char *scenes[] = {"v3-contact-patch-2d",
                          "v3-contact-patch-3d",
                          "v4-sliding-block",
                          "v5-hertz-2d",
                          "b2-curved-beams"};
} // namespace



// Both paths solve the same B-differentiable equations to 1e-12: the
// contact forces must agree to 1e-8 and every pair's state must match.
TEST(FullSystem, AgreesWithTheCondensedPath)
{
  for (const std::string scene : scenes)
    {
      cli::ScratchFolder folder(scene, "full");
      const SceneRun     condensed = run_scene(scene,
                                           "--set Contact/Path=condensed",
                                           cli::join(folder.path, "c"));
      const SceneRun     full      = run_scene(scene,
                                      "--set Contact/Path=full",
                                      cli::join(folder.path, "f"));
      ASSERT_EQ(full.summary["contact_path"], "full");
      ASSERT_EQ(condensed.summary["contact_path"], "condensed");
      expect_same_answer(condensed, full, scene);
    }
}



// A thin frictional strip (V3 2D, 100 x 2 spans per body, 0.02 thick,
// mu = 0.3) whose first pair has its tangential direction held by the
// x supports of both bodies: that direction is an empty row of C, and the
// full path stopped with a singular Newton matrix there (a stick piece is
// a zero row; Body 1 then started with every pair open, held by nothing).
// Such a direction carries no force (the supports take it); the full path
// now gives the condensed answer and every pair's state, and its Newton
// matrix stays regular. Without the rule the proximal phase still reaches
// an answer within the tolerance, after 40 iterations and with the
// patch's pressure off uniform by 2.5e-7: matching meshes carry the
// uniform pressure to the solver's tolerance (the other patch tests'
// 1e-8).
TEST(FullSystem, PairDirectionsHeldOnBothSidesCarryNoForce)
{
  const std::string  scene = "v3-contact-patch-2d";
  const std::string  strip = "--set Discretization/Refinements=0 "
                             "--set 'Body 1/Subdivisions=100, 2' "
                             "--set 'Body 2/Subdivisions=100, 2' "
                             "--set 'Body 1/Upper corner=1, 0.02' "
                             "--set 'Body 2/Lower corner=0, -0.02' "
                             "--set 'Contact/Friction coefficient=0.3' ";
  cli::ScratchFolder folder(scene, "held");
  const SceneRun     condensed = run_scene(scene,
                                       strip + "--set Contact/Path=condensed",
                                       cli::join(folder.path, "c"));
  const SceneRun     full      = run_scene(scene,
                                  strip + "--set Contact/Path=full",
                                  cli::join(folder.path, "f"));
  ASSERT_EQ(full.summary["status"], "ok");
  ASSERT_EQ(condensed.summary["status"], "ok");
  EXPECT_LT(deviation(condensed, full), 1e-8);
  ASSERT_EQ(condensed.status.size(), full.status.size());
  for (unsigned int s = 0; s < full.status.size(); ++s)
    EXPECT_EQ(condensed.status[s], full.status[s]) << "step " << s + 1;
  for (const SceneRun *run : {&condensed, &full})
    {
      EXPECT_LT(run->summary["checks"]["pressure_uniformity"].get<double>(),
                1e-8)
        << run->summary["contact_path"];
      EXPECT_EQ(run->output.find("singular"), std::string::npos) << run->output;
    }
}



// The augmented Lagrangian stops on the natural-map test of the BDE: its
// answer is the BDE answer (1e-6 with the 1e-12 tolerance).
TEST(FullSystem, AugmentedLagrangeReachesTheBdeAnswer)
{
  for (const std::string scene : scenes)
    {
      cli::ScratchFolder folder(scene, "al");
      const SceneRun     bde = run_scene(scene,
                                     "--set Contact/Path=condensed",
                                     cli::join(folder.path, "c"));
      const SceneRun     al =
        run_scene(scene,
                  "--set Contact/Algorithm=augmented-lagrange",
                  cli::join(folder.path, "a"));
      EXPECT_LT(deviation(bde, al), 1e-6) << scene;
    }
}



// V6 on its coarsest study mesh (disc 29 x 4 spans, block 35 x 8): the disc
// is held by contact alone. Penalty and augmented Lagrange stopped at their
// first Newton step there (every pair open, the coupled matrix singular);
// they start now, like the BDE, from the pairs on which the rigid disc
// rests. The augmented Lagrangian must reach the condensed BDE's pressure
// profile (peak and half-width of the pair pressures; the resultant equals
// the load for any answer of a floating body), the penalty must converge.
TEST(FullSystem, FloatingDiscStartsFromItsRestingPairsOnEveryAlgorithm)
{
  const std::string  scene  = "v6-cylinder-on-block";
  const std::string  coarse = "--set 'Body 1/Subdivisions=29, 4' "
                              "--set 'Body 2/Subdivisions=35, 8' ";
  cli::ScratchFolder folder(scene, "floating");
  const SceneRun     bde = run_scene(scene,
                                 coarse + "--set Contact/Path=condensed",
                                 cli::join(folder.path, "c"));
  const SceneRun     al =
    run_scene(scene,
              coarse + "--set Contact/Algorithm=augmented-lagrange",
              cli::join(folder.path, "a"));
  const SceneRun penalty = run_scene(scene,
                                     coarse + "--set Contact/Algorithm=penalty",
                                     cli::join(folder.path, "p"));
  ASSERT_EQ(bde.summary["status"], "ok");
  ASSERT_EQ(al.summary["status"], "ok");
  EXPECT_EQ(penalty.summary["status"], "ok");
  for (const char *check : {"hertz_peak_pressure", "hertz_half_width_moment"})
    {
      const double b = bde.summary["checks"][check];
      const double a = al.summary["checks"][check];
      EXPECT_NEAR(a, b, 1e-6 * std::abs(b)) << check;
    }
}



// Penalty: the answer penetrates by about p / k_n, so the deviation from
// the BDE answer and the penetration both fall as FKN grows (B2, where the
// contact force itself depends on the compliance of the interface; V4,
// the sliding block).
TEST(FullSystem, PenaltyApproachesTheBdeAnswerAsFknGrows)
{
  for (const std::string scene : {"b2-curved-beams", "v4-sliding-block"})
    {
      cli::ScratchFolder folder(scene, "penalty");
      const SceneRun     bde            = run_scene(scene,
                                     "--set Contact/Path=condensed",
                                     cli::join(folder.path, "c"));
      double             last_deviation = 1e300, last_penetration = 1e300;
      for (const std::string fkn : {"0.01", "0.1", "1", "10"})
        {
          const SceneRun penalty = run_scene(scene,
                                             "--set Contact/Algorithm=penalty "
                                             "--set 'Contact/Penalty factor=" +
                                               fkn + "'",
                                             cli::join(folder.path, "p") + fkn);
          const double   dev     = deviation(bde, penalty);
          const double   pen =
            penalty.summary["load_steps"].back()["max_penetration"];
          EXPECT_LT(dev, last_deviation) << scene << ", FKN = " << fkn;
          EXPECT_GT(pen, 0.) << scene << ", FKN = " << fkn;
          // Stiffer springs penetrate less (not ten times less: the
          // forces redistribute as the interface stiffens).
          EXPECT_LT(pen, last_penetration) << scene << ", FKN = " << fkn;
          last_deviation   = dev;
          last_penetration = pen;
        }
    }
}



// GMRES with the block preconditioner solves the same Newton systems as
// MUMPS, each to 1e-2 min(1, |F_k|/|F_0|) of the Newton residual: the
// Newton stops on the same test (Contact/Tolerance = 1e-12), so the answers
// agree as the two paths do (1e-8, the states exactly), and every Newton
// step reports its GMRES iterations.
TEST(FullSystem, KrylovAgreesWithTheDirectSolver)
{
  for (const std::string scene :
       {"v3-contact-patch-2d", "v3-contact-patch-3d", "b2-curved-beams"})
    {
      cli::ScratchFolder folder(scene, "krylov");
      const SceneRun     direct = run_scene(scene,
                                        "--set Contact/Path=full",
                                        cli::join(folder.path, "d"));
      const SceneRun     krylov =
        run_scene(scene,
                  "--set Contact/Path=full "
                  "--set 'Contact/Full system solver=gmres-amg'",
                  cli::join(folder.path, "k"));
      ASSERT_EQ(krylov.summary["contact_path"], "full") << scene;
      ASSERT_EQ(krylov.summary["full_system_solver"], "gmres-amg") << scene;
      expect_same_answer(direct, krylov, scene);
      for (unsigned int s = 0; s < krylov.status.size(); ++s)
        {
          // (V3's bilateral start is already the answer: no Newton step.)
          const auto &step = krylov.summary["load_steps"][s];
          if (step["newton_iterations"].get<int>() > 0)
            {
              ASSERT_TRUE(step.contains("krylov_iterations")) << scene;
              EXPECT_GE(step["krylov_iterations"].size(), 1u) << scene;
            }
        }
    }
}



// The two direct solvers of the coupled system (MUMPS, KLU) solve the same
// equations; both keep their symbolic factorisation over the Newton
// iterations and factorise the new values only, so a value they did not
// re-read would show here (V4: friction, ten load steps, the active set
// changing; B2: two 3D bodies). Same bound as the paths' agreement.
TEST(FullSystem, KluAgreesWithMumps)
{
  for (const std::string scene : {"v4-sliding-block", "b2-curved-beams"})
    {
      cli::ScratchFolder folder(scene, "klu");
      const SceneRun     mumps = run_scene(scene,
                                       "--set Contact/Path=full",
                                       cli::join(folder.path, "m"));
      const SceneRun     klu   = run_scene(scene,
                                     "--set Contact/Path=full "
                                           "--set 'Contact/Full system solver=klu'",
                                     cli::join(folder.path, "k"));
      ASSERT_EQ(klu.summary["full_system_solver"], "klu") << scene;
      expect_same_answer(mumps, klu, scene);
    }
}



// A GMRES that stops at its iteration limit fails the step with the
// iterations and the residual in one line, and the run fails (exit status,
// summary.json): never a silent wrong answer.
TEST(FullSystem, KrylovFailureIsReported)
{
  cli::ScratchFolder folder("b2", "krylov-fail");
  const std::string  out = cli::join(folder.path, "out");
  const auto         r   = cli::run_igabde(
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/b2-curved-beams.prm") +
      " --set 'Output/Directory=" + out +
      "' --set 'Output/Write vtu=false' --set Contact/Path=full "
                "--set 'Contact/Full system solver=gmres-amg' "
                "--set 'Contact/Krylov max iterations=1' "
                "--set 'Contact/Max step cuts=0'",
    folder.path);
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("GMRES (AMG and Schur-complement preconditioner) "
                          "did not converge"),
            std::string::npos)
    << r.output;
  EXPECT_NE(r.output.find(": 1 iterations, residual "), std::string::npos)
    << r.output;
  std::ifstream in(cli::join(out, "summary.json"));
  ASSERT_TRUE(in);
  const auto summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["status"], "failed");
}
