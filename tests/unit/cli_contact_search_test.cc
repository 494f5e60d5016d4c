// Slave points left out at set-up (#72 Deliver 2, 3): a contact face may
// reach past the part that faces the master. Points whose normal turns
// away from the master, and points beyond the master's extent, are left
// out and counted (summary.json contact_points_left_out) instead of
// refusing the scene. The references are second runs of the same scene
// whose slave face is only the part that faces the master, the master's
// extent computed by hand from its geometry, and for a contact at a patch
// corner the same ring parametrised so that the contact lies inside a
// patch.

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
    auto run =
      cli::run_prm_scene_table(name, "contact-search", scene_file, sets);
    return {std::move(run.summary), std::move(run.table)};
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


  /// The ring 1 <= r <= 2 of @p patches exact NURBS patches (written by
  /// contrib/geometry/annulus-patches into @p folder) under its own weight
  /// (body force 1 per unit volume) on the rigid plane y = -2, held by
  /// the contact alone; the outer arcs @p slave_faces touch the plane.
  cli::SceneRun
  run_ring(const std::string &folder,
           const unsigned int patches,
           const unsigned int angular_spans,
           const std::string &slave_faces)
  {
    const cli::RunResult written =
      cli::run_in(folder,
                  "'" +
                    cli::join(std::string(IGABDE_SOURCE_DIR),
                              "contrib/geometry/annulus-patches") +
                    "' --inner-radius 1 --radius 2 --angle 360 --patches " +
                    std::to_string(patches) + " > ring.xml");
    EXPECT_EQ(written.status, 0) << written.output;
    const std::string scene =
      "set Dimension = 2\n"
      "subsection Discretization\n  set Type = nurbs\n  set Degree = 2\n"
      "end\n"
      "subsection Body 1\n  set Geometry = file\n"
      "  set Geometry file = ring.xml\n  set Subdivisions = 4, " +
      std::to_string(angular_spans) +
      "\n  set Young's modulus = 1000\n  set Poisson's ratio = 0.3\n"
      "  set Body force = 0, -1\nend\n"
      "subsection Body 2\n  set Type = rigid plane\n"
      "  set Plane point = 0, -2\n  set Plane normal = 0, 1\nend\n"
      "subsection Contact\n  set Enabled = true\n  set Slave face = " +
      slave_faces + "\nend\n";
    cli::SceneRun run;
    run.summary = cli::run_scene_text(folder, scene);
    return run;
  }



  /// The contact's half-width from the second moment of the pair forces
  /// about x = 0 (Hertz's profile: 2 sqrt(sum F x^2 / sum F)), and the
  /// largest pair pressure.
  std::pair<double, double>
  moment_width_and_peak(const cli::CsvTable &pairs)
  {
    double force = 0., moment = 0., peak = 0.;
    for (std::size_t r = 0; r < pairs.rows.size(); ++r)
      {
        const double x = pairs.number(r, "x"), f = pairs.number(r, "p_n");
        force += f;
        moment += f * x * x;
        peak = std::max(peak, pairs.number(r, "pressure"));
      }
    return {2. * std::sqrt(moment / force), peak};
  }



  TEST(ContactSearch, ContactAtAPatchCornerMeetsTheSameContactInsideAPatch)
  {
    // Four patches of 90 degrees: the lowest point (270 degrees) is the
    // corner between patches 2 and 3, whose outer arcs (face 1) together
    // are the slave surface; each reaches up to the ring's equator, whose
    // points turn away from the plane. Three patches of 120 degrees: the
    // lowest point lies inside patch 2. The same angular spacing (200 and
    // 267 spans a patch, 0.45 degrees); the ring's weight is 3 pi.
    const cli::ScratchFolder corner_folder("corner", "contact-search");
    const cli::ScratchFolder inside_folder("inside", "contact-search");
    const cli::SceneRun      corner =
      run_ring(corner_folder.path, 4, 200, "2.1+3.1");
    const cli::SceneRun inside = run_ring(inside_folder.path, 3, 267, "2.1");
    ASSERT_EQ(corner.summary.at("status"), "ok");
    ASSERT_EQ(inside.summary.at("status"), "ok");
    EXPECT_GT(corner.summary.at("contact_points_left_out")
                .at("not_facing")
                .get<unsigned int>(),
              0u);
    const double weight = 3. * M_PI;
    for (const auto *run : {&corner, &inside})
      EXPECT_NEAR(run->summary.at("load_steps")[0]
                    .at("total_contact_force")[1]
                    .get<double>(),
                  weight,
                  1e-8 * weight);

    const auto corner_pairs =
      cli::read_table(cli::join(corner_folder.path, "out/contact-0001.csv"));
    const auto inside_pairs =
      cli::read_table(cli::join(inside_folder.path, "out/contact-0001.csv"));
    // The corner's pairs are mirror images about x = 0: the pressure is
    // symmetric to the solver's accuracy.
    std::vector<std::pair<double, double>> profile;
    for (std::size_t r = 0; r < corner_pairs.rows.size(); ++r)
      profile.emplace_back(corner_pairs.number(r, "x"),
                           corner_pairs.number(r, "pressure"));
    std::sort(profile.begin(), profile.end());
    const auto [a_corner, peak_corner] = moment_width_and_peak(corner_pairs);
    const auto [a_inside, peak_inside] = moment_width_and_peak(inside_pairs);
    for (std::size_t k = 0; k < profile.size(); ++k)
      {
        const auto &mirror = profile[profile.size() - 1 - k];
        EXPECT_NEAR(profile[k].first, -mirror.first, 1e-10) << k;
        EXPECT_NEAR(profile[k].second, mirror.second, 1e-8 * peak_corner) << k;
      }
    // Two discretisations of one contact: each within the 0.5 % that the
    // rigid-cylinder scenes show for moment radius and peak at about ten
    // pairs per half-width, so within 1 % of each other.
    EXPECT_NEAR(a_corner / a_inside, 1., 0.01);
    EXPECT_NEAR(peak_corner / peak_inside, 1., 0.01);
  }


  TEST(ContactSearch, LargerCylinderAsSlaveTouchesOnlyWhereItTouches)
  {
    // A half disc R = 8 (the slave) pressed by P = 8 per unit length onto
    // the top arc of a disc R = 2 (the master, 45 to 135 degrees, so
    // |x| <= 1.41): the slave face reaches far beyond the master, whose
    // projection clamps there; those points are left out. Hertz for two
    // cylinders (R = 1 / (1/8 + 1/2), E* = E / (2 (1 - nu^2))) puts the
    // contact's half-width at a = 0.172: every pair farther than 3 a from
    // the axis must be open, for the point-wise and the weighted-gap
    // pairs alike (the weighted gap's cut elements weight the gap with
    // the face basis, not the dual one, whose lobes there made a
    // penetration out of nothing), and both carry the load.
    const std::string   scene = "set Dimension = 2\n"
                                "subsection Discretization\n"
                                "  set Type = nurbs\n  set Degree = 2\nend\n"
                                "subsection Body 1\n"
                                "  set Geometry = half disc\n"
                                "  set Centre = 0, 8\n  set Radius = 8\n"
                                "  set Subdivisions = 200, 8\n"
                                "  set Grading = band 0: 0.45, 0.55, 8; 2: 4\n"
                                "  set Young's modulus = 1000\n"
                                "  set Poisson's ratio = 0.3\n"
                                "  set Supports = 3: x\n"
                                "  set Tractions = 3: vector 0, -0.5\nend\n"
                                "subsection Body 2\n"
                                "  set Type = deformable\n"
                                "  set Geometry = full disc\n"
                                "  set Centre = 0, -2\n  set Radius = 2\n"
                                "  set Subdivisions = 64, 16\n"
                                "  set Young's modulus = 1000\n"
                                "  set Poisson's ratio = 0.3\n"
                                "  set Supports = 2: x y\nend\n"
                                "subsection Contact\n  set Enabled = true\n"
                                "  set Slave face = 2\n"
                                "  set Master face = 3\nend\n";
    const double        a = std::sqrt(4. * 8. * 1.6 / (M_PI * 1000. / 1.82));
    std::vector<double> widths;
    for (const std::string pairing : {"node-to-surface", "weighted-gap"})
      {
        SCOPED_TRACE(pairing);
        const cli::ScratchFolder folder("larger-slave-" + pairing,
                                        "contact-search");
        const auto               summary =
          cli::run_scene_text(folder.path,
                              scene + "subsection Contact\n  set Pairing = " +
                                pairing + "\nend\n");
        ASSERT_EQ(summary.at("status"), "ok");
        EXPECT_FALSE(summary.contains("warnings")) << summary.at("warnings");
        EXPECT_GT(summary.at("contact_points_left_out")
                    .at("outside_master")
                    .get<unsigned int>(),
                  0u);
        EXPECT_NEAR(summary.at("load_steps")[0]
                      .at("total_contact_force")[1]
                      .get<double>(),
                    8.,
                    1e-8 * 8.);
        const auto pairs =
          cli::read_table(cli::join(folder.path, "out/contact-0001.csv"));
        for (std::size_t r = 0; r < pairs.rows.size(); ++r)
          {
            if (std::abs(pairs.number(r, "x")) > 3. * a)
              {
                EXPECT_EQ(pairs.number(r, "p_n"), 0.) << pairs.number(r, "x");
              }
          }
        widths.push_back(moment_width_and_peak(pairs).first);
      }
    // The two pairings' contact widths agree as their discretisations do
    // (the rigid-cylinder tables: within 1 %), and with Hertz's a to the
    // 10 a/R % that the discs' tilted normals and finite size allow (a/R
    // = 0.15 on the small disc: well inside 5 %).
    EXPECT_NEAR(widths[0] / widths[1], 1., 0.01);
    for (const double w : widths)
      EXPECT_NEAR(w / a, 1., 0.05);
  }



  // Contact/Search distance cuts the slave surface to the part within that
  // distance of the master: tutorial 1's half disc on the plane, cut at
  // 0.5. The points kept are exactly those of the uncut run whose
  // reference gap (their height over the plane y = 0, from its pair table)
  // is at most 0.5; the others are counted as beyond the search distance, and
  // the contact (closed pairs and their pressures) is the same: the far points
  // carry nothing.
  TEST(ContactSearch, SearchDistanceCutsTheSlaveSurface)
  {
    const SearchRun whole =
      run_scene("search-whole", "tutorial-1-disc-on-plane.prm", "");
    const SearchRun cut = run_scene("search-cut",
                                    "tutorial-1-disc-on-plane.prm",
                                    "--set 'Contact/Search distance=0.5'");
    ASSERT_EQ(whole.summary.at("status"), "ok");
    ASSERT_EQ(cut.summary.at("status"), "ok");
    unsigned int near = 0;
    for (std::size_t r = 0; r < whole.pairs.rows.size(); ++r)
      near += whole.pairs.number(r, "y") <= 0.5;
    ASSERT_GT(near, 0u);
    ASSERT_LT(near, whole.pairs.rows.size());
    EXPECT_EQ(cut.pairs.rows.size(), near);
    const auto &left_out = cut.summary.at("contact_points_left_out");
    EXPECT_EQ(left_out.at("beyond_search_distance").get<std::size_t>(),
              whole.pairs.rows.size() - near);
    const auto closed_whole = closed_pairs(whole);
    const auto closed_cut   = closed_pairs(cut);
    ASSERT_EQ(closed_whole.size(), closed_cut.size());
    for (std::size_t i = 0; i < closed_cut.size(); ++i)
      {
        EXPECT_NEAR(closed_cut[i].first, closed_whole[i].first, 1e-12);
        EXPECT_NEAR(closed_cut[i].second,
                    closed_whole[i].second,
                    1e-8 * closed_whole[i].second);
      }
  }
} // namespace contact_search_test
