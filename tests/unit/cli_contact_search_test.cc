// Slave points left out at set-up (#72 Deliver 2, 3): a contact face may
// reach past the part that faces the master. Points whose normal turns
// away from the master, and points beyond the master's extent, are left
// out and counted (summary.json contact_points_left_out) instead of
// refusing the scene. The references are second runs of the same scene
// whose slave face is only the part that faces the master, and the
// master's extent computed by hand from its geometry.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

namespace contact_search_test
{
  struct SearchRun
  {
    nlohmann::json summary;
    cli::CsvTable  pairs; ///< contact-0001.csv
  };

  SearchRun
  run_scene(const std::string &name,
            const std::string &scene_file,
            const std::string &sets)
  {
    const cli::ScratchFolder scratch(name, "contact-search");
    const cli::SceneRun      scene =
      cli::run_prm_scene(scratch.path, scene_file, sets);
    EXPECT_EQ(scene.status, 0) << scene.output;
    SearchRun run;
    run.summary = scene.summary;
    run.pairs =
      cli::read_table(cli::join(scratch.path, "out/contact-0001.csv"));
    return run;
  }



  /// The closed pairs (pressure above 1e-9 of the peak) of @p run, as
  /// (x, pressure) sorted by x.
  std::vector<std::pair<double, double>>
  closed_pairs(const SearchRun &run)
  {
    double peak = 0.;
    for (std::size_t r = 0; r < run.pairs.rows.size(); ++r)
      peak = std::max(peak, run.pairs.number(r, "pressure"));
    std::vector<std::pair<double, double>> closed;
    for (std::size_t r = 0; r < run.pairs.rows.size(); ++r)
      if (run.pairs.number(r, "pressure") > 1e-9 * peak)
        closed.emplace_back(run.pairs.number(r, "x"),
                            run.pairs.number(r, "pressure"));
    std::sort(closed.begin(), closed.end());
    return closed;
  }



  /// A full disc R = 8 on the rigid plane (tutorial 1's load and mesh)
  /// with its whole boundary as the slave surface (faces 0+1+2+3): the
  /// upper half turns away from the plane and is left out; the closed
  /// pairs and the contact force are those of the bottom arc alone
  /// (face 2), whose every point faces the plane.
  void
  expect_wrap_round_pairs_its_facing_part(const std::string &pairing)
  {
    const std::string disc =
      "--set 'Body 1/Geometry=full disc' --set 'Body 1/Subdivisions=100, 8' "
      "--set 'Body 1/Grading=' --set 'Checks/Hertz line load=0' "
      "--set 'Contact/Pairing=" +
      pairing + "' ";
    const SearchRun whole =
      run_scene("wrap-" + pairing,
                "tutorial-1-disc-on-plane.prm",
                disc + "--set 'Contact/Slave face=0+1+2+3'");
    const SearchRun arc = run_scene("arc-" + pairing,
                                    "tutorial-1-disc-on-plane.prm",
                                    disc + "--set 'Contact/Slave face=2'");
    ASSERT_EQ(whole.summary.at("status"), "ok");
    ASSERT_EQ(arc.summary.at("status"), "ok");

    // The whole boundary leaves its upper half out: turned away, not
    // beyond the plane (which has no edge); the bottom arc leaves nothing
    // out.
    const auto &left_out = whole.summary.at("contact_points_left_out");
    EXPECT_GT(left_out.at("not_facing").get<unsigned int>(), 0u);
    EXPECT_EQ(left_out.at("outside_master").get<unsigned int>(), 0u);
    EXPECT_EQ(left_out.at("unprojected").get<unsigned int>(), 0u);
    EXPECT_FALSE(arc.summary.contains("contact_points_left_out"));
    // Every pair kept faces the plane: its point lies in the lower half.
    for (std::size_t r = 0; r < whole.pairs.rows.size(); ++r)
      EXPECT_LT(whole.pairs.number(r, "y"), 8.) << r;

    // The same contact: the disc is held by it alone, so the force is the
    // traction's resultant in both, and the closed pairs coincide.
    const double f_whole = whole.summary.at("load_steps")[0]
                             .at("total_contact_force")[1]
                             .get<double>(),
                 f_arc = arc.summary.at("load_steps")[0]
                           .at("total_contact_force")[1]
                           .get<double>();
    EXPECT_NEAR(f_whole, f_arc, 1e-8 * std::abs(f_arc));
    const auto closed_whole = closed_pairs(whole),
               closed_arc   = closed_pairs(arc);
    ASSERT_EQ(closed_whole.size(), closed_arc.size());
    ASSERT_GT(closed_arc.size(), 3u);
    double peak = 0.;
    for (const auto &[x, p] : closed_arc)
      peak = std::max(peak, p);
    for (std::size_t k = 0; k < closed_arc.size(); ++k)
      {
        EXPECT_NEAR(closed_whole[k].first, closed_arc[k].first, 1e-10) << k;
        EXPECT_NEAR(closed_whole[k].second, closed_arc[k].second, 1e-7 * peak)
          << k;
      }
  }



  TEST(ContactSearch, FaceThatWrapsRoundPairsOnlyItsFacingPartPointwise)
  {
    expect_wrap_round_pairs_its_facing_part("node-to-surface");
  }



  TEST(ContactSearch, FaceThatWrapsRoundPairsOnlyItsFacingPartWeightedGap)
  {
    expect_wrap_round_pairs_its_facing_part("weighted-gap");
  }



  TEST(ContactSearch, SlavePointsBeyondTheMasterAreLeftOut)
  {
    // The block's top face reaches to x = 20; the rounded punch of
    // prm/geometry/rounded-punch.xml ends at x = 0.5 + 16 sin(10 deg) =
    // 3.2784: the Greville points beyond project onto its end, and are
    // left out, every one counted; no pair lies beyond the end.
    const double    reach = 0.5 + 16. * std::sin(10. * M_PI / 180.);
    const SearchRun run   = run_scene("beyond", "rigid-punch-on-block.prm", "");
    ASSERT_EQ(run.summary.at("status"), "ok");
    const auto        &left_out = run.summary.at("contact_points_left_out");
    const unsigned int kept     = run.pairs.rows.size();
    // 160 spans of degree 2: 162 Greville points on the top face.
    EXPECT_EQ(left_out.at("candidates").get<unsigned int>(), 162u);
    EXPECT_EQ(left_out.at("not_facing").get<unsigned int>(), 0u);
    EXPECT_EQ(left_out.at("outside_master").get<unsigned int>(), 162u - kept);
    double farthest = 0.;
    for (std::size_t r = 0; r < run.pairs.rows.size(); ++r)
      farthest = std::max(farthest, run.pairs.number(r, "x"));
    EXPECT_LE(farthest, reach);
  }
} // namespace contact_search_test
