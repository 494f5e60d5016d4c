// Contact/Pairing: node-to-node pairs matching surfaces exactly (the V3
// patch test then holds, every pair carries the applied pressure) and
// refuses non-matching ones with a message naming the remedy, where
// node-to-surface still pairs every point by closest point.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace
{
  const std::string scene =
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/v3-contact-patch-2d.prm");

  cli::RunResult
  run(const std::string &folder, const std::string &sets)
  {
    return cli::run_igabde("'" + scene +
                             "' --quiet --set 'Output/Directory=out' --set "
                             "'Output/Write vtu=false' --set "
                             "'Output/Print timing=false' " +
                             sets,
                           folder);
  }
} // namespace



TEST(ContactPairing, NodeToNodeOnMatchingAndNonMatchingSurfaces)
{
  const cli::ScratchFolder scratch("pairing", "unit");
  const std::string       &folder = scratch.path;

  // Matching meshes: the patch test holds to round-off (V3's criterion).
  const auto matching = run(folder, "--set 'Contact/Pairing=node-to-node'");
  ASSERT_EQ(matching.status, 0) << matching.output;
  const auto summary = nlohmann::json::parse(
    cli::read_file(cli::join(folder, "out/summary.json")));
  EXPECT_LE(summary.at("checks").at("pressure_uniformity").get<double>(), 1e-8);

  // Body 2 with 2 spans per direction under Body 1's 1 (8 against 4 face
  // spans after the scene's 2 refinements): Body 1's interior Greville
  // abscissae 1/8, 3/8, ... fall between Body 2's 1/16, 3/16, ...
  const std::string non_matching = "--set 'Body 2/Subdivisions=2' ";
  const auto        refused =
    run(folder, non_matching + "--set 'Contact/Pairing=node-to-node'");
  EXPECT_NE(refused.status, 0);
  EXPECT_NE(refused.output.find("node-to-node needs matching surfaces"),
            std::string::npos)
    << refused.output;
  EXPECT_NE(refused.output.find("use Contact/Pairing = node-to-surface"),
            std::string::npos)
    << refused.output;

  const auto closest =
    run(folder, non_matching + "--set 'Contact/Pairing=node-to-surface'");
  EXPECT_EQ(closest.status, 0) << closest.output;
}
