// Command-line behaviour of the igabde executable: help, parameter listing,
// clear one-line errors for bad input, --set overrides.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace
{
  using cli::read_file;
  using cli::run_igabde;

  void
  write_file(const std::string &path, const std::string &text)
  {
    std::ofstream(path) << text;
  }

} // namespace



TEST(Cli, HelpAndParameterListing)
{
  const auto help = run_igabde("--help", cli::ScratchFolder("help"));
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.output.find("Usage: igabde SCENE.prm"), std::string::npos);

  const auto prm = run_igabde("--print-parameters", cli::ScratchFolder("prm"));
  EXPECT_EQ(prm.status, 0);
  for (const char *name : {"Friction coefficient",
                           "Refinements",
                           "Degree",
                           "Directory",
                           "Algorithm",
                           "Path"})
    EXPECT_NE(prm.output.find(name), std::string::npos) << name;

  const auto json =
    run_igabde("--print-parameters json", cli::ScratchFolder("json"));
  EXPECT_EQ(json.status, 0);
  EXPECT_NE(json.output.find("\"Discretization\""), std::string::npos);
}



TEST(Cli, MisspelledParameterIsOneClearError)
{
  const cli::ScratchFolder scratch("misspelled");
  const std::string       &folder = scratch.path;
  std::filesystem::create_directories(folder);
  write_file(cli::join(folder, "bad.prm"),
             "set Dimension = 2\nsubsection Body 1\n"
             "  set Youngs modulus = 1000\nend\n");
  const auto result = run_igabde("bad.prm", folder);
  EXPECT_NE(result.status, 0);
  EXPECT_NE(result.output.find("bad.prm"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("Youngs modulus"), std::string::npos)
    << result.output;
  EXPECT_NE(result.output.find("Line <3>"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("Did you mean 'Young's modulus'"),
            std::string::npos)
    << result.output;
  // One line, no stack trace and no result files presented as a result.
  EXPECT_EQ(result.output.find("Stacktrace"), std::string::npos);
  EXPECT_FALSE(
    std::filesystem::exists(cli::join(folder, "output/bad/summary.json")));
}



TEST(Cli, MalformedValueAndMissingFile)
{
  const cli::ScratchFolder scratch("malformed");
  const std::string       &folder = scratch.path;
  std::filesystem::create_directories(folder);
  write_file(cli::join(folder, "bad.prm"),
             "subsection Discretization\n  set Degree = two\nend\n");
  const auto bad = run_igabde("bad.prm", folder);
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.output.find("Degree"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("two"), std::string::npos) << bad.output;

  const auto missing = run_igabde("nowhere.prm", folder);
  EXPECT_NE(missing.status, 0);
  EXPECT_NE(missing.output.find("nowhere.prm"), std::string::npos);

  write_file(cli::join(folder, "nu.prm"),
             "subsection Body 1\n  set Poisson's ratio = 0.5\nend\n");
  const auto nu = run_igabde("nu.prm", folder);
  EXPECT_NE(nu.status, 0);
  EXPECT_NE(nu.output.find("Poisson"), std::string::npos) << nu.output;

  write_file(cli::join(folder, "mu.prm"),
             "subsection Contact\n  set Friction coefficient = -0.1\nend\n");
  const auto mu = run_igabde("mu.prm", folder);
  EXPECT_NE(mu.status, 0);
  EXPECT_NE(mu.output.find("Friction coefficient"), std::string::npos)
    << mu.output;
}



TEST(Cli, SetOverridesAValue)
{
  const cli::ScratchFolder scratch("set");
  const std::string       &folder = scratch.path;
  const std::string        scene =
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/v2-lame-cylinder.prm");
  const auto result =
    run_igabde("'" + scene +
                 "' --set 'Discretization/Refinements=0' --set "
                 "'Output/Directory=out' --set 'Output/Write vtu=false'",
               folder);
  ASSERT_EQ(result.status, 0) << result.output;
  const std::string summary = read_file(cli::join(folder, "out/summary.json"));
  EXPECT_NE(summary.find("\"refinements\": 0"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"status\": \"ok\""), std::string::npos) << summary;

  const auto wrong =
    run_igabde("'" + scene + "' --set 'Discretization/Refinementz=1'", folder);
  EXPECT_NE(wrong.status, 0);
  EXPECT_NE(wrong.output.find("Refinementz"), std::string::npos)
    << wrong.output;
}



TEST(Cli, LateFailureKeepsFinishedResults)
{
  // Two B-Newton iterations are too few for the stick phase of V4's second
  // step: the run must fail loudly, keep step 1 and say why in summary.json.
  const cli::ScratchFolder scratch("late");
  const std::string       &folder = scratch.path;
  const std::string        scene =
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/v4-sliding-block.prm");
  const auto result = run_igabde("'" + scene +
                                   "' --set 'Contact/Max iterations=2' "
                                   "--set 'Contact/Max step cuts=0' "
                                   "--set 'Output/Directory=out'",
                                 folder);
  EXPECT_NE(result.status, 0);
  EXPECT_NE(result.output.find("did not converge"), std::string::npos)
    << result.output;
  const std::string summary = read_file(cli::join(folder, "out/summary.json"));
  EXPECT_NE(summary.find("\"status\": \"failed\""), std::string::npos);
  EXPECT_NE(summary.find("load step 2"), std::string::npos) << summary;
  EXPECT_TRUE(
    std::filesystem::exists(cli::join(folder, "out/contact-0001.csv")));
  EXPECT_TRUE(
    std::filesystem::exists(cli::join(folder, "out/solution-body1-0001.vtu")));
  EXPECT_FALSE(
    std::filesystem::exists(cli::join(folder, "out/contact-0002.csv")));
  // The series are written when the run ends, failed or not, and name the
  // finished step's files only.
  for (const std::string series : {"solution-body1", "contact"})
    {
      const std::string pvd =
        read_file(cli::join(folder, "out/" + series + ".pvd"));
      EXPECT_NE(pvd.find(series + "-0001.vtu"), std::string::npos) << pvd;
      EXPECT_EQ(pvd.find("-0002.vtu"), std::string::npos) << pvd;
    }
  // The failed step is recorded with its iterations and residual.
  EXPECT_NE(summary.find("\"status\": \"failed\"", summary.find("load_steps")),
            std::string::npos);
}



TEST(Cli, SurfacesThatDoNotFaceEachOther)
{
  const cli::ScratchFolder scratch("facing");
  const std::string       &folder = scratch.path;
  const std::string        scene =
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/v5-hertz-2d.prm");
  const auto result = run_igabde("'" + scene +
                                   "' --set 'Body 2/Plane normal=0,-1' "
                                   "--set 'Output/Directory=out'",
                                 folder);
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find("do not face each other"), std::string::npos)
    << result.output;
  EXPECT_NE(result.output.find("Plane normal"), std::string::npos)
    << result.output;
}



TEST(Cli, MinimalScenesRunWithDefaults)
{
  // A unit box with rollers and a pressure, everything else at its default,
  // in 2D and 3D; and a support on a face the patch does not have.
  const cli::ScratchFolder scratch("defaults");
  const std::string       &folder = scratch.path;
  std::filesystem::create_directories(folder);
  write_file(cli::join(folder, "box2.prm"),
             "set Dimension = 2\nsubsection Body 1\n"
             "  set Supports = 0: x; 2: y\n  set Tractions = 3: pressure 1\n"
             "end\n");
  write_file(cli::join(folder, "box3.prm"),
             "set Dimension = 3\nsubsection Body 1\n"
             "  set Supports = 0: x; 2: y; 4: z\n"
             "  set Tractions = 5: pressure 1\nend\n");
  write_file(cli::join(folder, "face.prm"),
             "set Dimension = 2\nsubsection Body 1\n"
             "  set Supports = 7: x\nend\n");
  for (const std::string scene : {"box2.prm", "box3.prm"})
    {
      const auto result = run_igabde(scene, folder);
      EXPECT_EQ(result.status, 0) << scene << "\n" << result.output;
    }
  const auto face = run_igabde("face.prm", folder);
  EXPECT_NE(face.status, 0);
  EXPECT_NE(face.output.find("Supports"), std::string::npos) << face.output;
  EXPECT_NE(face.output.find("patch face 0..3"), std::string::npos)
    << face.output;
}



TEST(Cli, SummaryNamesTheAllocatorTheBuildLinked)
{
  // The executable links jemalloc on transparent huge pages unless the
  // build was configured without it (CMake IGABDE_JEMALLOC, or the
  // sanitizers); summary.json says which one served the run.
  const cli::ScratchFolder scratch("allocator");
  const std::string        scene =
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/v3-contact-patch-2d.prm");
  const auto result = run_igabde("'" + scene +
                                   "' --quiet --set 'Output/Directory=out' "
                                   "--set 'Output/Write vtu=false'",
                                 scratch.path);
  ASSERT_EQ(result.status, 0) << result.output;
  const std::string summary =
    read_file(cli::join(scratch.path, "out/summary.json"));
  const bool linked = (IGABDE_EXPECT_JEMALLOC != 0) &&
                      std::getenv("IGABDE_EXECUTABLE") == nullptr;
  if (linked)
    EXPECT_NE(summary.find("\"memory_allocator\": \"jemalloc"),
              std::string::npos)
      << summary;
  else
    EXPECT_NE(summary.find("\"memory_allocator\":"), std::string::npos)
      << summary;
}



TEST(Cli, QuietLeavesTheScreenToWarningsAndErrors)
{
  // V6's partial-slip load path warns at its last step (paired points
  // past one pair spacing): with --quiet that warning is all the screen
  // shows, the log keeps every line; without it the steps print too.
  const cli::ScratchFolder scratch("quiet");
  const std::string        scene =
    "'" +
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/v6-partial-slip-force.prm") +
    "' --set 'Output/Write vtu=false'";
  const auto quiet =
    run_igabde(scene + " --quiet --set 'Output/Directory=quiet'", scratch.path);
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  std::istringstream lines(quiet.output);
  unsigned int       n_lines = 0;
  for (std::string line; std::getline(lines, line); ++n_lines)
    EXPECT_NE(line.find("warning:"), std::string::npos) << line;
  EXPECT_GE(n_lines, 1u) << quiet.output;
  const std::string log = read_file(cli::join(scratch.path, "quiet/log.txt"));
  EXPECT_NE(log.find("Load step 1/"), std::string::npos) << log;
  EXPECT_NE(log.find("warning:"), std::string::npos) << log;

  const auto loud =
    run_igabde(scene + " --set 'Output/Directory=loud'", scratch.path);
  ASSERT_EQ(loud.status, 0) << loud.output;
  EXPECT_NE(loud.output.find("Load step 1/"), std::string::npos);
  EXPECT_NE(loud.output.find("wallclock"), std::string::npos);
}
