// The size guard (doc/robustness.md): the estimate a scene is checked
// against before anything is built, compared with what the built scene
// really holds (deal.II's DoFHandler and sparsity pattern, MUMPS' factor),
// and the refinement it names as the largest that fits.

#include <igabde/scene/simulator.h>
#include <igabde/scene/size_estimate.h>

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace
{
  std::string
  scene_path(const std::string &name)
  {
    return cli::join(cli::join(std::string(IGABDE_SOURCE_DIR), "prm"), name);
  }

  struct Case
  {
    std::string name;
    std::string scene;
    std::string settings;
    int         dim;
  };
} // namespace



TEST(SizeGuard, EstimateAgainstTheBuiltScene)
{
  // Unknowns: exact (the knot vectors and the FE_Q node count are closed
  // forms). Matrix entries: an upper bound (every row is counted with the
  // couplings of an interior node). Factor entries: never below MUMPS' own
  // count (a guard that underestimates lets a run start that cannot
  // finish), and over by less than one uniform refinement multiplies the
  // factor (at least 4 in 2D, n log n with n x 4; 16 in 3D, n^{4/3} with
  // n x 8), so the refinement the guard names is off by at most one.
  const std::vector<Case> cases = {
    {"v3-nurbs",
     "v3-contact-patch-2d.prm",
     "--set Discretization/Refinements=2",
     2},
    {"v3-lagrange",
     "v3-contact-patch-2d.prm",
     "--set Discretization/Refinements=1 --set Discretization/Type=lagrange",
     2},
    {"v5-nurbs-p2", "v5-hertz-2d.prm", "--set Discretization/Refinements=1", 2},
    {"v5-nurbs-p3",
     "v5-hertz-2d.prm",
     "--set Discretization/Degree=3 --set Discretization/Refinements=1",
     2},
    {"v5-q1",
     "v5-hertz-2d.prm",
     "--set Discretization/Type=lagrange --set Discretization/Degree=1 "
     "--set Discretization/Refinements=1",
     2},
    {"v5-q2", "v5-hertz-2d.prm", "--set Discretization/Type=lagrange", 2},
    {"v1-nurbs", "v1-plate-with-hole.prm", "", 2},
    {"v3-3d-lagrange",
     "v3-contact-patch-3d.prm",
     "--set Discretization/Type=lagrange --set Discretization/Refinements=0",
     3},
    {"v3-3d-nurbs-slab",
     "v3-contact-patch-3d.prm",
     "--set Discretization/Refinements=0 "
     "--set 'Body 1/Subdivisions=24,24,1' --set 'Body 2/Subdivisions=24,24,1' "
     "--set 'Body 1/Upper corner=1,1,0.1' --set 'Body 2/Lower corner=0,0,-0.1'",
     3},
    {"v3-3d-lagrange-slab",
     "v3-contact-patch-3d.prm",
     "--set Discretization/Type=lagrange --set Discretization/Refinements=0 "
     "--set 'Body 1/Subdivisions=12,12,1' --set 'Body 2/Subdivisions=12,12,1' "
     "--set 'Body 1/Upper corner=1,1,0.1' --set 'Body 2/Lower corner=0,0,-0.1'",
     3},
    {"b2-nurbs", "b2-curved-beams.prm", "", 3},
    {"b2-lagrange",
     "b2-curved-beams.prm",
     "--set Discretization/Type=lagrange --set 'Body 1/Subdivisions=2,2,2' "
     "--set 'Body 2/Subdivisions=2,2,2'",
     3}};
  for (const Case &c : cases)
    {
      SCOPED_TRACE(c.name);
      const cli::ScratchFolder folder(c.name, "size");
      const auto               result =
        cli::run_igabde("'" + scene_path(c.scene) + "' " + c.settings +
                          " --quiet --set 'Output/Write vtu=false'"
                          " --set 'Output/Directory=out'",
                        folder);
      ASSERT_EQ(result.status, 0) << result.output;
      const nlohmann::json summary = nlohmann::json::parse(
        cli::read_file(cli::join(folder.path, "out/summary.json")));
      const auto &built     = summary.at("bodies");
      const auto &estimated = summary.at("size_estimate").at("bodies");
      ASSERT_EQ(built.size(), estimated.size());
      const double growth = (c.dim == 2 ? 4. : 16.);
      for (unsigned int b = 0; b < built.size(); ++b)
        {
          SCOPED_TRACE(b);
          EXPECT_EQ(estimated[b].at("n_unknowns").get<double>(),
                    built[b].at("n_dofs").get<double>());
          EXPECT_GE(estimated[b].at("matrix_entries").get<double>(),
                    built[b].at("matrix_entries").get<double>());
          ASSERT_TRUE(built[b].contains("factor_entries"));
          const double ratio = estimated[b].at("factor_entries").get<double>() /
                               built[b].at("factor_entries").get<double>();
          EXPECT_GE(ratio, 1.);
          EXPECT_LT(ratio, growth);
        }
    }
}



TEST(SizeGuard, NamesTheLargestRefinementThatFits)
{
  // V5 at 3 refinements, against a memory between the estimates at 1 and 2
  // refinements: refused, naming 1; with the memory of the estimate itself:
  // accepted.
  dealii::ParameterHandler prm;
  const auto               parameters =
    igabde::scene::parse_scene(prm,
                               scene_path("v5-hertz-2d.prm"),
                               {{"Discretization/Refinements", "3"}});
  std::vector<double> bytes;
  for (int r = 0; r <= 3; ++r)
    bytes.push_back(
      igabde::scene::estimate_size(parameters, "v5-hertz-2d.prm", r)
        .total_bytes());
  for (int r = 0; r < 3; ++r)
    EXPECT_LT(bytes[r], bytes[r + 1]);

  EXPECT_NO_THROW(
    igabde::scene::check_size(parameters, "v5-hertz-2d.prm", bytes[3]));
  try
    {
      igabde::scene::check_size(parameters,
                                "v5-hertz-2d.prm",
                                0.5 * (bytes[1] + bytes[2]));
      ADD_FAILURE() << "a scene beyond the memory was accepted";
    }
  catch (const dealii::ExceptionBase &e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find("Discretization/Refinements = 1 fits"),
                std::string::npos)
        << what;
      EXPECT_NE(what.find("--force"), std::string::npos) << what;
    }
  // Not even the coarsest mesh: say so.
  try
    {
      igabde::scene::check_size(parameters, "v5-hertz-2d.prm", 0.5 * bytes[0]);
      ADD_FAILURE() << "a scene beyond the memory was accepted";
    }
  catch (const dealii::ExceptionBase &e)
    {
      EXPECT_NE(std::string(e.what()).find("Refinements = 0 does not fit"),
                std::string::npos)
        << e.what();
    }
}



TEST(SizeGuard, AutoTakesTheFullPathWhenTheCondensedDoesNotFit)
{
  // A 3D contact patch of 2 704 pairs (plates of 50x50x1 spans): the
  // condensed path's dense blocks (Schur complements of 8 112 face
  // unknowns per plate) outweigh the full path's sparse LU (estimates of
  // 2.56 and 1.85 GiB; the two cross near 35x35 spans). With Contact/Path =
  // full the estimate counts no dense block; with auto and a memory between the
  // two paths' needs, the run takes the full path and says why; below both, it
  // is refused.
  dealii::ParameterHandler                               prm;
  const std::vector<std::pair<std::string, std::string>> slab = {
    {"Discretization/Refinements", "0"},
    {"Body 1/Subdivisions", "50,50,1"},
    {"Body 2/Subdivisions", "50,50,1"},
    {"Body 1/Upper corner", "1,1,0.2"},
    {"Body 2/Lower corner", "0,0,-0.2"}};
  const auto parameters =
    igabde::scene::parse_scene(prm,
                               scene_path("v3-contact-patch-3d.prm"),
                               slab);
  const auto e =
    igabde::scene::estimate_size(parameters, "v3-contact-patch-3d.prm");
  EXPECT_EQ(e.path, igabde::contact::Path::condensed);
  const double condensed = e.total_bytes(igabde::contact::Path::condensed);
  const double full      = e.total_bytes(igabde::contact::Path::full);
  ASSERT_LT(full, condensed);
  EXPECT_GT(e.bytes_dense, 0.);
  EXPECT_GT(e.bytes_coupled, 0.);

  auto full_only = slab;
  full_only.emplace_back("Contact/Path", "full");
  dealii::ParameterHandler prm_full;
  const auto               parameters_full =
    igabde::scene::parse_scene(prm_full,
                               scene_path("v3-contact-patch-3d.prm"),
                               full_only);
  const auto f =
    igabde::scene::estimate_size(parameters_full, "v3-contact-patch-3d.prm");
  EXPECT_EQ(f.path, igabde::contact::Path::full);
  EXPECT_DOUBLE_EQ(f.total_bytes(), full);

  // Between the two: accepted, on the full path, in the run too.
  const double between = 0.5 * (full + condensed);
  EXPECT_EQ(igabde::scene::check_size(parameters,
                                      "v3-contact-patch-3d.prm",
                                      between)
              .path,
            igabde::contact::Path::full);
  EXPECT_THROW(igabde::scene::check_size(parameters,
                                         "v3-contact-patch-3d.prm",
                                         0.9 * full),
               dealii::ExceptionBase);
  const cli::ScratchFolder folder("auto-full", "size");
  std::string              sets;
  for (const auto &[key, value] : slab)
    sets += " --set '" + key + "=" + value + "'";
  const auto result =
    cli::run_in(folder,
                "IGABDE_MEMORY_LIMIT=" +
                  std::to_string(between / std::pow(2., 30)) + " " +
                  cli::executable() + " '" +
                  scene_path("v3-contact-patch-3d.prm") + "'" + sets +
                  " --quiet --set 'Output/Write vtu=false'"
                  " --set 'Output/Directory=out'");
  ASSERT_EQ(result.status, 0) << result.output;
  const nlohmann::json summary = nlohmann::json::parse(
    cli::read_file(cli::join(folder.path, "out/summary.json")));
  EXPECT_EQ(summary.at("contact_path"), "full");
  EXPECT_NE(summary.at("contact_path_reason")
              .get<std::string>()
              .find("the condensed path needs about"),
            std::string::npos)
    << summary.at("contact_path_reason");
  // The exact answer of the patch test: pressure 1 on every pair, to the
  // 1e-6 that the 3D contact-patch family is held to (doc/performance.md).
  EXPECT_LT(summary.at("checks").at("pressure_uniformity").get<double>(), 1e-6);
}



TEST(SizeGuard, MemoryLimitAndForce)
{
  // IGABDE_MEMORY_LIMIT below what any process needs: V3 is refused at
  // parse time; --force runs it past the guard (and only past the guard).
  const cli::ScratchFolder folder("force", "size");
  const std::string        run =
    "IGABDE_MEMORY_LIMIT=0.01 " + cli::executable() + " '" +
    scene_path("v3-contact-patch-2d.prm") +
    "' --quiet --set 'Output/Write vtu=false' --set 'Output/Directory=out'";
  const auto refused = cli::run_in(folder, run);
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("Even Discretization/Refinements = 0 does "
                                "not fit"),
            std::string::npos)
    << refused.output;
  EXPECT_FALSE(std::filesystem::exists(cli::join(folder.path, "out")));
  const auto forced = cli::run_in(folder, run + " --force");
  EXPECT_EQ(forced.status, 0) << forced.output;
  const auto forced_bad =
    cli::run_in(folder, run + " --force --set \"Body 1/Young's modulus=0\"");
  EXPECT_EQ(forced_bad.status, 2) << forced_bad.output;
  const auto bad_limit =
    cli::run_in(folder,
                "IGABDE_MEMORY_LIMIT=lots " + cli::executable() + " '" +
                  scene_path("v3-contact-patch-2d.prm") + "' --quiet");
  EXPECT_EQ(bad_limit.status, 2) << bad_limit.output;
  EXPECT_NE(bad_limit.output.find("IGABDE_MEMORY_LIMIT"), std::string::npos)
    << bad_limit.output;
}



TEST(SizeGuard, InterruptedRunKeepsTheFinishedSteps)
{
  // SIGTERM during a 200-step V4 run, once two steps are written: exit status
  // 128 + 15, summary.json 'interrupted' naming the step, the finished
  // steps in summary.json and steps.csv, their fields on disk.
  const cli::ScratchFolder folder("interrupt", "size");
  std::string              loads, displacements;
  for (int i = 0; i < 200; ++i)
    {
      loads += std::string(i ? ", " : "") + "1";
      displacements +=
        std::string(i ? ", " : "") + std::to_string(i / 199.).substr(0, 8);
    }
  const std::string command =
    cli::executable() + " '" + scene_path("v4-sliding-block.prm") +
    "' --set Discretization/Refinements=3 --set 'Load path/Load factors=" +
    loads + "' --set 'Load path/Displacement factors=" + displacements +
    "' --set 'Output/Directory=out' > screen.txt 2>&1 & pid=$!;"
    " for i in $(seq 1200); do"
    " [ -f out/steps.csv ] && [ $(wc -l < out/steps.csv) -ge 3 ] && break;"
    " sleep 0.05; done; kill -TERM $pid; wait $pid; echo \"exit $?\"";
  const auto result = cli::run_in(folder, command);
  EXPECT_NE(result.output.find("exit 143"), std::string::npos) << result.output;
  const nlohmann::json summary = nlohmann::json::parse(
    cli::read_file(cli::join(folder.path, "out/summary.json")));
  EXPECT_EQ(summary.at("status"), "interrupted");
  const std::size_t finished = summary.at("load_steps").size();
  EXPECT_GE(finished, 2u);
  EXPECT_LT(finished, 200u);
  const std::string error = summary.at("error");
  // The step it was in, and the steps whose files were all written (the
  // fields of the last one or two finished steps may still have been
  // being written in the background: those are not counted).
  EXPECT_NE(error.find("interrupted by SIGTERM during load step "),
            std::string::npos)
    << error;
  EXPECT_NE(error.find(" of 200 (steps 1.." + std::to_string(finished) +
                       " finished and written)"),
            std::string::npos)
    << error;
  // One row per finished step (and the header).
  const std::string steps =
    cli::read_file(cli::join(folder.path, "out/steps.csv"));
  EXPECT_EQ(static_cast<std::size_t>(
              std::count(steps.begin(), steps.end(), '\n')),
            finished + 1)
    << steps;
  for (std::size_t s = 1; s <= finished; ++s)
    {
      char number[8];
      std::snprintf(number, sizeof(number), "%04zu", s);
      EXPECT_TRUE(std::filesystem::exists(
        cli::join(folder.path, std::string("out/contact-") + number + ".csv")));
      EXPECT_TRUE(std::filesystem::exists(
        cli::join(folder.path,
                  std::string("out/solution-body1-") + number + ".vtu")));
    }
  // The reason reaches the screen and the log.
  const std::string screen =
    cli::read_file(cli::join(folder.path, "screen.txt"));
  EXPECT_NE(screen.find("igabde: interrupted by SIGTERM"), std::string::npos);
  const std::string log = cli::read_file(cli::join(folder.path, "out/log.txt"));
  EXPECT_NE(log.find("interrupted by SIGTERM"), std::string::npos);
}
