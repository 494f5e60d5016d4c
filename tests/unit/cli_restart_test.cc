// Output/Checkpoint and --restart: a run stopped after a finished step and
// continued from its checkpoint must end where the uninterrupted run ends,
// to 1e-12 relative, on a path whose answer depends on its history:
// partial slip with friction (tutorial 2: the slip of each step is an
// increment from the last, so the friction history is part of the state)
// on the condensed and on the full path, and the F1 elastica at finite
// strain (each step's Newton starts from the last step's displacement),
// and F3, frictional contact at finite strain on the full path (both).
// A checkpoint that dropped either would change every later step.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace cli_restart
{
  /// Every number of @p a equals @p b's at the same place to 1e-12
  /// relative; every key and array of @p a is in @p b.
  void
  expect_same_numbers(const nlohmann::json &a,
                      const nlohmann::json &b,
                      const std::string    &where)
  {
    if (a.is_number())
      {
        ASSERT_TRUE(b.is_number()) << where;
        const double x = a.get<double>(), y = b.get<double>();
        EXPECT_LE(std::abs(x - y), 1e-12 * std::max(std::abs(x), std::abs(y)))
          << where << ": " << x << " against " << y;
      }
    else if (a.is_object())
      for (const auto &[key, value] : a.items())
        {
          ASSERT_TRUE(b.contains(key)) << where << "/" << key;
          expect_same_numbers(value, b.at(key), where + "/" + key);
        }
    else if (a.is_array())
      {
        ASSERT_EQ(a.size(), b.size()) << where;
        for (std::size_t i = 0; i < a.size(); ++i)
          expect_same_numbers(a[i], b[i], where + "/" + std::to_string(i));
      }
    else
      EXPECT_EQ(a, b) << where;
  }

  /**
   * Runs prm/@p scene with checkpoints to the end, then removes the
   * checkpoints after step @p stop (a run interrupted there) and continues
   * it with --restart: the summaries' steps, points and checks agree.
   */
  void
  expect_restart_reproduces(const std::string &scene,
                            const std::string &sets,
                            const unsigned int stop)
  {
    SCOPED_TRACE(scene + " " + sets);
    const cli::ScratchFolder scratch("restart-" +
                                     scene.substr(0, scene.find('.')) +
                                     std::to_string(sets.size()));
    const std::string        checkpoint = " --set 'Output/Checkpoint=true' ";
    const auto whole = cli::run_prm_scene(scratch, scene, checkpoint + sets);
    ASSERT_EQ(whole.status, 0) << whole.output;
    const unsigned int n_steps = whole.summary.at("load_steps").size();
    ASSERT_GT(n_steps, stop);
    for (unsigned int s = stop + 1; s <= n_steps; ++s)
      {
        char name[32];
        std::snprintf(name, sizeof(name), "out/checkpoint-%04u.json", s);
        ASSERT_TRUE(std::filesystem::remove(cli::join(scratch, name))) << name;
      }
    const auto continued =
      cli::run_prm_scene(scratch, scene, checkpoint + sets + " --restart out");
    ASSERT_EQ(continued.status, 0) << continued.output;
    EXPECT_EQ(continued.summary.at("restarted_after_step"), stop);
    EXPECT_EQ(continued.summary.at("status"), "ok");
    for (const std::string key : {"load_steps",
                                  "points",
                                  "point_stresses",
                                  "total_contact_force",
                                  "checks"})
      if (whole.summary.contains(key))
        expect_same_numbers(whole.summary.at(key),
                            continued.summary.at(key),
                            key);
    // steps.csv has every step again.
    const auto table = cli::read_csv(cli::join(scratch, "out/steps.csv"));
    EXPECT_EQ(table.size(), n_steps + 1);
  }
} // namespace cli_restart

using namespace cli_restart;



TEST(CliRestart, PartialSlipContinuesOnTheCondensedPath)
{
  expect_restart_reproduces("tutorial-2-partial-slip.prm", "", 2);
}

TEST(CliRestart, PartialSlipContinuesOnTheFullPath)
{
  expect_restart_reproduces("tutorial-2-partial-slip.prm",
                            "--set 'Contact/Path=full'",
                            3);
}

TEST(CliRestart, ElasticaContinuesAtFiniteStrain)
{
  expect_restart_reproduces("f1-elastica.prm",
                            "--set 'Load path/Number of steps=5'",
                            2);
}

TEST(CliRestart, FrictionalContactContinuesAtFiniteStrain)
{
  // F3 on coarser meshes: the bodies' finite-strain states and the slip
  // history both carry over (stopped in the middle of the shift).
  expect_restart_reproduces("f3-finite-partial-slip.prm",
                            "--set 'Body 1/Subdivisions=58, 8' "
                            "--set 'Body 2/Subdivisions=70, 16'",
                            3);
}

TEST(CliRestart, FiniteSlidingContinuesFromItsLastConfiguration)
{
  // The ring turned on its cylinder: the pairs of the next step are formed
  // on the configuration the last one ended in, with the forces carried
  // over by slave key (the frozen tangent keeps it fast).
  expect_restart_reproduces("ring-turned-on-cylinder.prm",
                            "--set 'Contact/Sliding tangent=frozen'",
                            4);
}

TEST(CliRestart, AnotherSceneOrNoCheckpointIsRefused)
{
  const cli::ScratchFolder scratch("restart-refused");
  const std::string        scene = "'" +
                            cli::join(std::string(IGABDE_SOURCE_DIR),
                                      "prm/tutorial-2-partial-slip.prm") +
                            "' --quiet --set 'Output/Write vtu=false' ";
  cli::expect_refused(scene + "--restart out", scratch, "no checkpoint");
  const auto whole = cli::run_prm_scene(scratch,
                                        "tutorial-2-partial-slip.prm",
                                        "--set 'Output/Checkpoint=true'");
  ASSERT_EQ(whole.status, 0) << whole.output;
  std::filesystem::remove(cli::join(scratch, "out/checkpoint-0005.json"));
  cli::expect_refused(scene +
                        "--set 'Contact/Friction coefficient=0.4' --restart "
                        "out",
                      scratch,
                      "Friction coefficient differs");
}
