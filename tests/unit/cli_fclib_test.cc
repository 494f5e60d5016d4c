// igabde --fclib FILE: a published contact problem solved from the command
// line. A problem written with libfclib whose answer is known in closed form
// (one contact sliding, one open, W block-diagonal) must come back with
// that answer; a problem of the FCLIB corpus must meet FCLIB's measure and,
// where its file stores a reference solution computed by another solver,
// agree with it; bad input ends with status 2 and one line, an unsolved
// problem with status 1 and summary.json saying why.

#include <igabde/contact/contact_problem.h>

#include <igabde/postprocess/fclib_writer.h>

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  std::string
  fclib_dir()
  {
    const char *env = std::getenv("IGABDE_FCLIB_DIR");
    return env ? std::string(env) :
                 (std::filesystem::path(IGABDE_SOURCE_DIR) / ".." / "shared" /
                  "fclib" / "data")
                   .string();
  }

  nlohmann::json
  read_summary(const std::string &folder)
  {
    std::ifstream  in(cli::join(folder, "out/summary.json"));
    nlohmann::json summary;
    in >> summary;
    return summary;
  }

  /// The rows of solution.csv after its header, as numbers (the status
  /// column as its text in @p statuses).
  std::vector<std::vector<double>>
  read_solution(const std::string &folder, std::vector<std::string> &statuses)
  {
    std::ifstream                    in(cli::join(folder, "out/solution.csv"));
    std::string                      line;
    std::vector<std::vector<double>> rows;
    std::getline(in, line);
    while (std::getline(in, line))
      {
        std::stringstream   cells(line);
        std::string         cell;
        std::vector<double> row;
        for (unsigned int k = 0; std::getline(cells, cell, ','); ++k)
          if (k == 1)
            statuses.push_back(cell);
          else
            row.push_back(std::stod(cell));
        rows.push_back(row);
      }
    return rows;
  }
  /// Solves the exported FCLIB problem @p file from zero with igabde --fclib
  /// in @p folder: its answer must meet FCLIB's measure, the stored
  /// solution (the scene's answer) too, and the two must agree.
  void
  expect_solves_to_its_reference(const std::string        &file,
                                 const cli::ScratchFolder &folder)
  {
    const auto run = cli::run_igabde("--fclib '" + file +
                                       "' --quiet --set Output/Directory=out",
                                     folder);
    ASSERT_EQ(run.status, 0) << run.output;
    const nlohmann::json summary = read_summary(folder.path);
    const auto          &checks  = summary.at("checks");
    EXPECT_LE(checks.at("fclib_error").get<double>(), 1e-8);
    ASSERT_TRUE(checks.contains("reference_fclib_error")) << checks.dump();
    EXPECT_LE(checks.at("reference_fclib_error").get<double>(), 1e-8);
    EXPECT_LE(checks.at("reference_relative_difference").get<double>(), 1e-6);
  }
} // namespace



TEST(CliFclib, SlidingAndOpenContactsMatchTheirClosedForm)
{
  // Contact 0: W = diag(2, 1, 1), q = (-1, 0.5, 0), mu = 0.3. Closed:
  // p_n = -q_n / W_nn = 0.5. The stick trial p_t = -q_t = (-0.5, 0) leaves
  // the cone (0.5 > mu p_n = 0.15), so it slides: p_t = (-0.15, 0),
  // u_t = p_t + q_t = (0.35, 0), u_n = 0. Contact 1: W = I, q = (0.2, 0.1,
  // 0): open, p = 0, u = q.
  igabde::contact::ContactProblem problem;
  problem.n_contacts   = 2;
  problem.n_components = 3;
  problem.W            = Eigen::MatrixXd::Identity(6, 6);
  problem.W(0, 0)      = 2.;
  problem.q.resize(6);
  problem.q << -1., 0.5, 0., 0.2, 0.1, 0.;
  problem.mu = {0.3, 0.3};
  const cli::ScratchFolder scratch("fclib-closed-form");
  igabde::postprocess::write_fclib_local(problem,
                                         nullptr,
                                         cli::join(scratch.path, "two.hdf5"));

  const auto run =
    cli::run_igabde("--fclib two.hdf5 --quiet --set Output/Directory=out",
                    scratch);
  ASSERT_EQ(run.status, 0) << run.output;
  const nlohmann::json summary = read_summary(scratch.path);
  EXPECT_EQ(summary.at("status"), "ok");
  EXPECT_EQ(summary.at("n_contacts"), 2);
  EXPECT_LE(summary.at("checks").at("fclib_error").get<double>(), 1e-8);
  EXPECT_TRUE(summary.at("checks").at("conditions_passed").get<bool>());
  EXPECT_EQ(summary.at("n_slip"), 1);
  EXPECT_EQ(summary.at("n_open"), 1);

  std::vector<std::string> statuses;
  const auto               rows = read_solution(scratch.path, statuses);
  ASSERT_EQ(rows.size(), 2u);
  // contact, r_n, r_t1, r_t2, u_n, u_t1, u_t2 (the status read apart).
  const double exact[2][7] = {{0, 0.5, -0.15, 0., 0., 0.35, 0.},
                              {1, 0., 0., 0., 0.2, 0.1, 0.}};
  for (unsigned int i = 0; i < 2; ++i)
    {
      ASSERT_EQ(rows[i].size(), 7u);
      for (unsigned int k = 0; k < 7; ++k)
        EXPECT_NEAR(rows[i][k], exact[i][k], 1e-9)
          << "contact " << i << ", " << k;
    }
  EXPECT_EQ(statuses.at(0), "slip");
  EXPECT_EQ(statuses.at(1), "open");
}



TEST(CliFclib, CorpusProblemsMeetFclibsMeasureAndTheStoredReference)
{
  if (!std::filesystem::is_directory(fclib_dir()))
    GTEST_SKIP() << "no FCLIB corpus at " << fclib_dir();
  for (const std::string name : {"hdf5_local/local_problem_test.hdf5",
                                 "hdf5_global/Box_Stacks-i0035-31-0.hdf5",
                                 "siconos_dat/FrictionContact3D_1c.dat"})
    {
      SCOPED_TRACE(name);
      const std::string        file = cli::join(fclib_dir(), name);
      const cli::ScratchFolder scratch("fclib-corpus");
      const auto               run = cli::run_igabde("--fclib '" + file +
                                         "' --quiet --set Output/Directory=out",
                                       scratch);
      ASSERT_EQ(run.status, 0) << run.output;
      const nlohmann::json summary = read_summary(scratch.path);
      const auto          &checks  = summary.at("checks");
      EXPECT_LE(checks.at("fclib_error").get<double>(), 1e-8);
      EXPECT_TRUE(checks.at("conditions_passed").get<bool>());
      // A reference another solver stored: the same forces where the
      // problem's answer is unique to its own accuracy (its FCLIB error
      // bounds the distance, up to the conditioning of W).
      if (checks.contains("reference_relative_difference") &&
          checks.at("reference_fclib_error").get<double>() <= 1e-8)
        {
          EXPECT_LE(checks.at("reference_relative_difference").get<double>(),
                    1e-5);
        }
    }
}



TEST(CliFclib, BadInputEndsWithOneLineAndAnUnsolvedProblemSaysWhy)
{
  const cli::ScratchFolder scratch("fclib-bad");
  {
    const auto run = cli::run_igabde("--fclib no-such.hdf5", scratch);
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("no-such.hdf5: no such file"), std::string::npos)
      << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1)
      << run.output;
  }
  {
    std::ofstream(cli::join(scratch.path, "text.dat")) << "not a problem\n";
    const auto run = cli::run_igabde("--fclib text.dat", scratch);
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1)
      << run.output;
  }

  // A closed-form problem, so the file exists: a scene's parameter is
  // refused, a solver's is read.
  igabde::contact::ContactProblem problem;
  problem.n_contacts   = 2;
  problem.n_components = 3;
  problem.W            = Eigen::MatrixXd::Identity(6, 6);
  problem.W(0, 3) = problem.W(3, 0) = 0.5;
  problem.W(1, 4) = problem.W(4, 1) = 0.5;
  problem.q.resize(6);
  problem.q << -1., 0.5, 0.2, -1., -0.3, 0.4;
  problem.mu = {0.3, 0.6};
  igabde::postprocess::write_fclib_local(problem,
                                         nullptr,
                                         cli::join(scratch.path, "two.hdf5"));
  {
    const auto run =
      cli::run_igabde("--fclib two.hdf5 --set \"Body 1/Young's modulus=2\"",
                      scratch);
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("not a parameter of an FCLIB problem"),
              std::string::npos)
      << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1)
      << run.output;
  }
  {
    // One Gauss-Seidel sweep and one Newton iteration cannot solve two
    // closed pairs coupled in their normal and tangential directions (the
    // sweep leaves the first pair's gap open by W_03 p_1 = 0.25).
    const auto run =
      cli::run_igabde("--fclib two.hdf5 --quiet --set Output/Directory=out "
                      "--set 'Contact/Max iterations=1'",
                      scratch);
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("not solved"), std::string::npos) << run.output;
    const nlohmann::json summary = read_summary(scratch.path);
    EXPECT_EQ(summary.at("status"), "failed");
    EXPECT_FALSE(summary.at("diagnosis").get<std::string>().empty());
    EXPECT_GT(summary.at("checks").at("fclib_error").get<double>(), 1e-8);
  }
}



TEST(CliFclib, ExportedSceneProblemSolvesToTheScenesAnswer)
{
  // B1 (two clamped beams, mu = 0.5) with Output/FCLIB export: the file
  // holds the step's W, q, mu and the run's answer. That answer must meet
  // FCLIB's measure on the written problem (the export is the problem the
  // run solved), and --fclib, solving the file from zero, must find the
  // same forces.
  const cli::ScratchFolder scratch("fclib-export");
  const auto               scene = cli::run_prm_scene(scratch.path,
                                        "b1-cantilever-beams.prm",
                                        "--set 'Output/FCLIB export=true'");
  ASSERT_EQ(scene.status, 0) << scene.output;
  const std::string file = cli::join(scratch.path, "out/fclib-0001.hdf5");
  ASSERT_TRUE(std::filesystem::exists(file));

  const cli::ScratchFolder again("fclib-export-solve");
  expect_solves_to_its_reference(file, again);
}



TEST(CliFclib, ExportWithoutAnFclibProblemIsRefusedWhenRead)
{
  // Frictionless: FCLIB's local problems have 2 or 3 components.
  const cli::ScratchFolder scratch("fclib-export-refused");
  const auto               run = cli::run_prm_scene(scratch.path,
                                      "v3-contact-patch-3d.prm",
                                      "--set 'Output/FCLIB export=true'");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("Output/FCLIB export"), std::string::npos)
    << run.output;
}



TEST(CliFclib, ExportedThreeBodyProblemSolvesToTheScenesAnswer)
{
  // The three-block stack with friction (mu = 0.3), its top pressed down
  // by a prescribed displacement and its middle block held in y on its
  // right side, so that no body floats (FCLIB's local problems have no
  // rigid-mode rows): the condensed W of two interactions over three
  // bodies, the middle one in both. The file must hold the problem the
  // run solved (its answer meets FCLIB's measure on it), and solving the
  // file from zero must find the same forces.
  const cli::ScratchFolder scratch("fclib-export-three");
  const auto               scene =
    cli::run_prm_scene(scratch.path,
                       "three-block-stack.prm",
                       "--set 'Contact/Friction coefficient=0.3' "
                       "--set 'Body 1/Supports=0: x; 3: y=-0.003' "
                       "--set 'Body 1/Tractions=' "
                       "--set 'Body 2/Supports=0: x; 1: y' "
                       "--set 'Checks/Uniform pressure=0' "
                       "--set 'Output/FCLIB export=true'");
  ASSERT_EQ(scene.status, 0) << scene.output;
  ASSERT_EQ(scene.summary.at("contact_interactions").size(), 2u);
  const std::string file = cli::join(scratch.path, "out/fclib-0001.hdf5");
  ASSERT_TRUE(std::filesystem::exists(file)) << scene.output;

  const cli::ScratchFolder again("fclib-export-three-solve");
  expect_solves_to_its_reference(file, again);
}
