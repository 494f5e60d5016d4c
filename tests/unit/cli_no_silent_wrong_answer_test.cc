// Runs that must not end with "status": "ok" (or leave an old "ok" behind)
// while their answer is wrong or missing, and malformed scene files that
// must give one clear line instead of a crash. Each case failed before the
// fix it guards.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  using cli::read_file;
  using cli::run_igabde;
  using cli::run_in;

  /// A scratch folder removed when the test ends.
  struct Scratch : cli::ScratchFolder
  {
    explicit Scratch(const std::string &name)
      : cli::ScratchFolder(name, "wrong")
    {}
  };

  std::string
  scene(const std::string &name)
  {
    return "'" + cli::join(std::string(IGABDE_SOURCE_DIR), "prm/") + name + "'";
  }

  bool
  contains(const std::string &text, const std::string &what)
  {
    return text.find(what) != std::string::npos;
  }
} // namespace



TEST(NoSilentWrongAnswer, DegreeBelowTheExactGeometryIsRefused)
{
  // The Hertz disc is rational quadratic: a NURBS degree 1 cannot hold it.
  const Scratch s("degree");
  const auto    r =
    run_igabde(scene("v5-hertz-2d.prm") + " --set 'Discretization/Degree=1'"
                                          " --set 'Output/Directory=out'",
               s.path);
  // Bad input, found when the body is built: exit status 2 and the one
  // line names the scene file like the reader's errors.
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "below the degree 2")) << r.output;
  EXPECT_TRUE(contains(r.output,
                       "igabde: error: " +
                         cli::join(std::string(IGABDE_SOURCE_DIR),
                                   "prm/v5-hertz-2d.prm") +
                         ": Discretization/Degree = 1"))
    << r.output;
  EXPECT_FALSE(
    contains(read_file(cli::join(s.path, "out/summary.json")), "\"ok\""));
  // The error line is the last thing on screen: no timing table after it
  // (the timing stays in timing.txt and summary.json).
  EXPECT_FALSE(contains(r.output, "wallclock")) << r.output;
  EXPECT_TRUE(
    contains(read_file(cli::join(s.path, "out/timing.txt")), "wallclock"));
}



TEST(NoSilentWrongAnswer, RedundantPairsAreAWarning)
{
  // V5's quarter disc: 64 spans of degree 2 on the arc, 66 control points
  // with 2 components, of which the symmetry support holds one (x on the
  // axis): 131 face unknowns. Gauss placement puts p + 1 = 3 frictionless
  // pairs in each span, 192 contact unknowns: more rows than the
  // flexibility's rank can reach, so the pair forces are not unique.
  // Greville placement (66 pairs) is not redundant.
  for (const std::string placement : {"gauss", "greville"})
    {
      SCOPED_TRACE(placement);
      const Scratch     s("redundant-" + placement);
      const auto        r = run_igabde(scene("v5-hertz-2d.prm") +
                                  " --quiet --set 'Output/Write vtu=false'"
                                         " --set 'Contact/Pair placement=" +
                                  placement + "' --set 'Output/Directory=out'",
                                s.path);
      const std::string summary =
        read_file(cli::join(s.path, "out/summary.json"));
      const bool warned =
        contains(summary,
                 "192 contact unknowns on 131 face unknowns: the "
                 "contact rows are redundant");
      EXPECT_EQ(warned, placement == "gauss") << summary;
      EXPECT_EQ(contains(r.output, "warning: 192 contact unknowns"),
                placement == "gauss")
        << r.output;
    }
}



namespace
{
  /// Runs prm/@p file with @p sets into a scratch folder; its summary.json.
  nlohmann::json
  run_summary(const std::string &name,
              const std::string &file,
              const std::string &sets)
  {
    const Scratch s(name);
    const auto    r =
      run_igabde(scene(file) + " --quiet --set 'Output/Write vtu=false' " +
                   sets + " --set 'Output/Directory=out'",
                 s.path);
    EXPECT_EQ(r.status, 0) << r.output;
    return nlohmann::json::parse(
      read_file(cli::join(s.path, "out/summary.json")));
  }
} // namespace



TEST(NoSilentWrongAnswer, FrictionalHertzChecksBetweenDissimilarBodiesWarn)
{
  // Friction leaves Hertz's and Johnson's frictionless solutions exact only
  // between similar bodies. V5's disc on a rigid plane (plane strain,
  // nu = 0.3) has Dundurs' beta = -(1 - 2 nu) / (2 (1 - nu)) = -0.2857:
  // with mu = 0.3 its Hertz check must say so. V7's sphere on a block of
  // the same material (beta = 0) keeps its check without the warning.
  // Neither is redundant: V5 with friction has 66 pairs of 2 unknowns on
  // 131 face unknowns, but the tangent of the pair on the symmetry axis
  // moves only the held x unknown (a zero row, left out), so 131 count.
  const std::string note = "Dundurs beta = ";
  {
    const nlohmann::json summary =
      run_summary("dundurs-v5",
                  "v5-hertz-2d.prm",
                  "--set 'Contact/Friction coefficient=0.3'");
    ASSERT_TRUE(summary.contains("warnings")) << summary.dump(1);
    std::vector<std::string> dundurs;
    for (const auto &w : summary["warnings"])
      {
        const std::string text = w.get<std::string>();
        EXPECT_FALSE(contains(text, "redundant")) << text;
        if (contains(text, note))
          dundurs.push_back(text);
      }
    ASSERT_EQ(dundurs.size(), 1u) << summary["warnings"].dump(1);
    const double nu = 0.3;
    const double beta =
      std::stod(dundurs[0].substr(dundurs[0].find(note) + note.size()));
    EXPECT_NEAR(beta, -(1. - 2. * nu) / (2. * (1. - nu)), 1e-3);
  }
  {
    const std::string summary =
      run_summary("dundurs-v7",
                  "v7-sphere-on-block.prm",
                  "--set 'Contact/Friction coefficient=0.3'")
        .dump();
    EXPECT_TRUE(contains(summary, "hertz_contact_radius_error")) << summary;
    EXPECT_FALSE(contains(summary, note)) << summary;
    EXPECT_FALSE(contains(summary, "redundant")) << summary;
  }
}



TEST(NoSilentWrongAnswer, ChecksAtALastFactorOtherThanOneScaleTheirReferences)
{
  // The checks' references are for the loads at factor 1; a load path
  // ending at 0.5 compared the field with them as they were (V2: errors of
  // 50 %, V3: pressure 50 % off uniform, status ok).
  {
    // Linear elasticity: the relative errors at any factor are those at 1.
    const nlohmann::json one = run_summary("lame1", "v2-lame-cylinder.prm", "");
    const nlohmann::json half =
      run_summary("lame05",
                  "v2-lame-cylinder.prm",
                  "--set 'Load path/Load factors=0.5'");
    EXPECT_EQ(half["checks"]["reference_factor"], 0.5) << half.dump(1);
    for (const char *norm : {"l2_error", "energy_error"})
      EXPECT_NEAR(half["checks"][norm].get<double>(),
                  one["checks"][norm].get<double>(),
                  1e-8 * one["checks"][norm].get<double>())
        << norm;
  }
  {
    // The patch test: uniform pressure 0.5 at half the load, to rounding.
    const nlohmann::json half =
      run_summary("patch05",
                  "v3-contact-patch-2d.prm",
                  "--set 'Load path/Load factors=0.5'");
    EXPECT_LT(half["checks"]["pressure_uniformity"].get<double>(), 1e-8)
      << half.dump(1);
  }
  {
    // V5 at half the load, P = 120 N/m (R = 8, E* = E / (1 - nu^2)):
    // Johnson's a = sqrt(4 P R / (pi E*)). The load histories that do not
    // act (the displacement factor: V5 prescribes no displacement) do not
    // count, whatever their factor.
    const nlohmann::json half =
      run_summary("hertz05",
                  "v5-hertz-2d.prm",
                  "--set 'Load path/Load factors=0.5' "
                  "--set 'Load path/Displacement factors=0.2'");
    const double e_star = 1000. / (1. - 0.3 * 0.3);
    const double a      = std::sqrt(4. * 120. * 8. / (M_PI * e_star));
    EXPECT_NEAR(half["checks"]["hertz_half_width_exact"].get<double>(),
                a,
                1e-12 * a)
      << half.dump(1);
    // The moment estimate is within a pair spacing of a.
    EXPECT_LT(half["checks"]["hertz_half_width_moment_error"].get<double>(),
              half["checks"]["hertz_edge_pair_spacing"].get<double>() / a)
      << half.dump(1);
    EXPECT_FALSE(half.contains("warnings")) << half.dump(1);
  }
}



TEST(NoSilentWrongAnswer,
     ChecksAtLoadHistoriesOfDifferentFactorsAreNotEvaluated)
{
  // Tutorial 2 ends with its two acting histories (press, shift) at
  // different factors: no factor scales the check's reference, so the
  // check is left out with a warning instead of a figure against the
  // wrong load. With both ending at 1 the check is evaluated.
  const std::string    check = "--set 'Checks/Hertz line load=60' ";
  const nlohmann::json differ =
    run_summary("histories-differ",
                "tutorial-2-partial-slip.prm",
                check + "--set 'Load path/Histories=press: 1, 1, 1, 1, 1; "
                        "shift: 0, 0.25, 0.5, 0.75, 0.5'");
  EXPECT_FALSE(differ["checks"].contains("hertz_half_width")) << differ.dump(1);
  ASSERT_TRUE(differ.contains("warnings")) << differ.dump(1);
  EXPECT_TRUE(contains(differ["warnings"].dump(),
                       "different factors (Load path), so no check is "
                       "evaluated"))
    << differ["warnings"].dump(1);
  const nlohmann::json same =
    run_summary("histories-same", "tutorial-2-partial-slip.prm", check);
  EXPECT_TRUE(same["checks"].contains("hertz_half_width")) << same.dump(1);
}



TEST(NoSilentWrongAnswer, KilledRunLeavesNoOldOkSummary)
{
  // A finished run, then a second run into the same folder killed while it
  // works: summary.json must not keep saying "ok".
  const Scratch s("stale");
  const auto    first =
    run_igabde(scene("v2-lame-cylinder.prm") + " --set 'Output/Directory=out'",
               s.path);
  ASSERT_EQ(first.status, 0) << first.output;
  ASSERT_TRUE(
    contains(read_file(cli::join(s.path, "out/summary.json")), "\"ok\""));
  const std::string command =
    cli::executable() + " " + scene("b2-curved-beams.prm") +
    " --quiet --set 'Body 1/Subdivisions=8,16,8'"
    " --set 'Body 2/Subdivisions=8,16,8' --set 'Output/Directory=out'"
    " > /dev/null & pid=$!; for i in $(seq 200); do"
    " grep -q running out/summary.json 2>/dev/null && break; sleep 0.05;"
    " done; kill -9 $pid; wait $pid; true";
  run_in(s.path, command);
  const std::string summary = read_file(cli::join(s.path, "out/summary.json"));
  EXPECT_TRUE(contains(summary, "\"status\": \"running\"")) << summary;
  EXPECT_FALSE(contains(summary, "\"status\": \"ok\"")) << summary;
}



TEST(NoSilentWrongAnswer, NonFiniteResultsAreAFailure)
{
  // A load factor of 1e308 overflows the error norms of V2 (they were
  // reported as null next to "status": "ok").
  const Scratch s("finite");
  const auto    r = run_igabde(scene("v2-lame-cylinder.prm") +
                              " --set 'Load path/Load factors=1e308'"
                                 " --set 'Output/Directory=out'",
                            s.path);
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "not finite")) << r.output;
  const std::string summary = read_file(cli::join(s.path, "out/summary.json"));
  EXPECT_TRUE(contains(summary, "\"status\": \"failed\"")) << summary;

  // A modulus below the smallest normal double is refused when read.
  const auto tiny = run_igabde(scene("v2-lame-cylinder.prm") +
                                 " --set \"Body 1/Young's modulus=2.2e-308\""
                                 " --set 'Output/Directory=tiny'",
                               s.path);
  EXPECT_EQ(tiny.status, 2) << tiny.output;
  EXPECT_TRUE(contains(tiny.output, "Young's modulus")) << tiny.output;
}



TEST(NoSilentWrongAnswer, OverflowingLoadsEndWithOneLine)
{
  // Loads whose squares double precision cannot hold (past
  // sqrt(DBL_MAX / n), about 1e150 for these meshes) have no answer: the
  // contact solve's norms overflowed and a QR of an empty matrix crashed
  // with SIGSEGV. The run ends with status 2, one line naming the loads
  // and summary.json 'failed'.
  const Scratch s("overflow");
  for (const std::string pressure : {"1e308", "1e200"})
    {
      SCOPED_TRACE(pressure);
      const std::string out = "out-" + pressure;
      const auto        r =
        run_igabde(scene("v3-contact-patch-2d.prm") +
                     " --set 'Body 1/Tractions=3: pressure " + pressure +
                     "' --set 'Output/Directory=" + out + "'",
                   s.path);
      EXPECT_EQ(r.status, 2) << r.output;
      EXPECT_TRUE(contains(r.output,
                           "Body 1: the loads that follow Load path/Load "
                           "factors"))
        << r.output;
      EXPECT_TRUE(contains(r.output, "Body 1/Tractions")) << r.output;
      const std::string summary =
        read_file(cli::join(s.path, out + "/summary.json"));
      EXPECT_TRUE(contains(summary, "\"status\": \"failed\"")) << summary;
    }

  // A load factor past double arithmetic in the second of V4's steps: the
  // step is named and the first one is kept.
  const auto r =
    run_igabde(scene("v4-sliding-block.prm") +
                 " --set 'Load path/Load factors=1, 1e300, 1'"
                 " --set 'Load path/Displacement factors=0, 0, 0.1'"
                 " --set 'Output/Directory=factor'",
               s.path);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_TRUE(contains(r.output,
                       "load step 2: the contact problem at the history "
                       "factors (1e+300, 0)"))
    << r.output;
  const nlohmann::json summary =
    nlohmann::json::parse(read_file(cli::join(s.path, "factor/summary.json")));
  EXPECT_EQ(summary.at("status"), "failed");
  EXPECT_EQ(summary.at("load_steps").size(), 1u) << summary.dump(2);
}



TEST(NoSilentWrongAnswer, ContactThatNeverClosesIsAWarning)
{
  // Tutorial 2's disc pressed down by 0.2 from 0.5 above the block: no pair
  // closes, and the run says so (before, it ended "ok" with zero forces
  // and nothing else). From the touching position it closes: no warning.
  const Scratch s("never-closes");
  for (const std::string centre : {"8.5", "8"})
    {
      SCOPED_TRACE(centre);
      const std::string out = "out-" + centre;
      const auto        r   = run_igabde(
        scene("tutorial-2-partial-slip.prm") + " --set 'Body 1/Centre=0, " +
          centre +
          "' --set 'Body 1/Subdivisions=24, 4'"
                   " --set 'Body 2/Subdivisions=24, 6'"
                   " --set 'Load path/Number of steps=2'"
                   " --set 'Load path/Histories=press: 0.5, 1; shift: 0, 0'"
                   " --set 'Output/Write vtu=false' --set 'Output/Directory=" +
          out + "'",
        s.path);
      EXPECT_EQ(r.status, 0) << r.output;
      const nlohmann::json summary = nlohmann::json::parse(
        read_file(cli::join(s.path, out + "/summary.json")));
      bool warned = false;
      if (summary.contains("warnings"))
        for (const auto &w : summary.at("warnings"))
          warned =
            warned || contains(w.get<std::string>(),
                               "no contact pair closed in any load "
                               "step: the smallest gap at the end is 0.3");
      EXPECT_EQ(warned, centre == "8.5") << summary.dump(2);
      EXPECT_EQ(contains(r.output,
                         "warning: load step 2: no contact pair closed"),
                centre == "8.5")
        << r.output;
    }
}



TEST(NoSilentWrongAnswer, AnOutputFileThatCannotBeWrittenFailsTheRun)
{
  // The fields' VTU is written by a background job; a folder with a file
  // in it holds its name, so it cannot be opened. The job's error was
  // lost (deal.II 9.4's Task<void>::join() does not rethrow it): the run
  // said "ok" with the file missing.
  const Scratch s("unwritable");
  std::filesystem::create_directories(
    cli::join(s.path, "out/solution-body1-0001.vtu/keep"));
  const auto r =
    run_igabde(scene("v5-hertz-2d.prm") + " --set 'Output/Directory=out'",
               s.path);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "solution-body1-0001.vtu' for writing"))
    << r.output;
  const std::string summary = read_file(cli::join(s.path, "out/summary.json"));
  EXPECT_TRUE(contains(summary, "\"status\": \"failed\"")) << summary;
}



TEST(NoSilentWrongAnswer, MalformedSceneFilesAreOneLineErrors)
{
  const Scratch s("malformed");
  std::ofstream(cli::join(s.path, "self.prm"))
    << "set Dimension = 2\ninclude self.prm\n";
  std::ofstream(cli::join(s.path, "folder.prm"))
    << "include " << s.path << "\n";
  std::ofstream(cli::join(s.path, "truncated.xml"))
    << "<?xml version=\"1.0\"?>\n<Par";
  std::ofstream(cli::join(s.path, "truncated.json")) << "{ \"Dimension\": ";
  const std::array<std::pair<const char *, const char *>, 4> cases = {
    {{"self.prm", "include cycle"},
     {"folder.prm", "is a folder"},
     {"truncated.xml", "not a readable xml parameter file"},
     {"truncated.json", "JSON file is not valid"}}};
  for (const auto &[file, message] : cases)
    {
      const auto r = run_igabde(file, s.path);
      EXPECT_EQ(r.status, 2) << file << "\n" << r.output;
      EXPECT_TRUE(contains(r.output, message)) << file << "\n" << r.output;
      // One line, no backtrace.
      EXPECT_FALSE(contains(r.output, "Stacktrace")) << r.output;
    }
}



TEST(NoSilentWrongAnswer, ParameterSetTwiceInOneFileWarnsWithBothLines)
{
  const Scratch s("twice");
  std::ofstream(cli::join(s.path, "twice.prm"))
    << "set Dimension = 2\nsubsection Body 1\n  set Supports = 0: x; 2: y\n"
       "  set Tractions = 3: pressure 1\nend\nsubsection Output\n"
       "  set Write vtu = false\nend\nsubsection Body 1\n"
       "  set Tractions = 3: pressure 2\nend\n";
  const auto r = run_igabde("twice.prm", s.path);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output,
                       "twice.prm:10: 'Body 1/Tractions' is set "
                       "again (first at line 4)"))
    << r.output;
}



TEST(NoSilentWrongAnswer, HertzZoneBelowThePairSpacingIsAWarning)
{
  // V5: Johnson's half-width a = sqrt(4 P R / (pi E*)) = 1.49 for P = 240,
  // R = 8, E* = 1000 / 0.91, against a pair spacing near the axis of about
  // R (pi / 2) / 64 = 0.2: several pairs inside the zone. With the load
  // x 1e-4, a = 0.0149 is a tenth of one spacing: one pair carries the load
  // and the Hertz figures measure the spacing; the run must say so.
  const Scratch     s("hertz-resolution");
  const std::string quiet   = " --quiet --set 'Output/Write vtu=false'";
  const auto        nominal = run_igabde(scene("v5-hertz-2d.prm") + quiet +
                                    " --set 'Output/Directory=nominal'",
                                  s.path);
  ASSERT_EQ(nominal.status, 0) << nominal.output;
  EXPECT_FALSE(contains(read_file(cli::join(s.path, "nominal/summary.json")),
                        "not resolved by the pairs"));
  const auto tiny = run_igabde(
    scene("v5-hertz-2d.prm") + quiet +
      " --set 'Body 1/Tractions=3: vector 0, -0.0015'"
      " --set 'Checks/Hertz line load=0.024' --set 'Output/Directory=tiny'",
    s.path);
  ASSERT_EQ(tiny.status, 0) << tiny.output;
  const std::string summary = read_file(cli::join(s.path, "tiny/summary.json"));
  EXPECT_TRUE(contains(summary, "not resolved by the pairs")) << summary;
  EXPECT_TRUE(
    contains(tiny.output + read_file(cli::join(s.path, "tiny/log.txt")),
             "Refine the contact face"))
    << tiny.output;
}



TEST(NoSilentWrongAnswer, EachFreeRigidModeGetsOneTrueLine)
{
  // Tutorial 1's disc has no support: frictionless on the plane, its
  // sideways slide moves no pair along a normal and carries no load (held
  // at zero); its vertical translation and its rotation are closed by the
  // contact equilibrium. Each mode is named once, with its fate (before,
  // every mode was first said to be closed by the contact, and the slide
  // then held at zero). Without contact a free mode is refused and no
  // line claims a contact that does not exist.
  const Scratch     s("rigid-modes");
  const std::string coarse = " --set 'Body 1/Subdivisions=40, 4'"
                             " --set 'Output/Write vtu=false'";
  const auto r = run_igabde(scene("tutorial-1-disc-on-plane.prm") + coarse +
                              " --set 'Output/Directory=contact'",
                            s.path);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string log = read_file(cli::join(s.path, "contact/log.txt"));
  const auto        lines_with = [&](const std::string &what) {
    std::vector<std::string> found;
    std::istringstream       in(log);
    for (std::string line; std::getline(in, line);)
      if (contains(line, what))
        found.push_back(line);
    return found;
  };
  EXPECT_EQ(lines_with("rigid mode").size(), 3u) << log;
  const auto slide = lines_with("'translation x'");
  ASSERT_EQ(slide.size(), 1u) << log;
  EXPECT_TRUE(contains(slide[0], "held at zero")) << slide[0];
  const auto lift = lines_with("'translation y'");
  ASSERT_EQ(lift.size(), 1u) << log;
  EXPECT_TRUE(contains(lift[0], "closed by the contact equilibrium"))
    << lift[0];

  // V5's quarter disc is held on its symmetry axis only: without contact
  // its vertical translation is free.
  const auto alone =
    run_igabde(scene("v5-hertz-2d.prm") + " --set 'Output/Write vtu=false'"
                                          " --set 'Contact/Enabled=false'"
                                          " --set 'Output/Directory=none'",
               s.path);
  EXPECT_EQ(alone.status, 2) << alone.output;
  EXPECT_TRUE(contains(alone.output, "has no contact; add Supports"))
    << alone.output;
  EXPECT_FALSE(contains(alone.output, "closed by")) << alone.output;
}



TEST(NoSilentWrongAnswer, StrainsAndContactZonesFarOutOfScaleMentionUnits)
{
  // V5 with E in "Pa" (x 1e6, lengths and loads unchanged): Johnson's
  // half-width shrinks by 10^3 to 1.9e-4 of R, below one pair spacing; the
  // unresolved-zone warning now also says to check the units. The strain
  // falls by 10^6: below 1e-8 for V3's patch test (pressure 1, E = 1000:
  // strain 1e-3, x 1e-6 = 1e-9), a warning of its own. E x 1e-6 on V3
  // makes the strain 1e3: the out-of-range warning says units too. At the
  // scenes' own E none of these appear.
  const Scratch     s("units");
  const std::string quiet       = " --quiet --set 'Output/Write vtu=false'";
  const auto        warnings_of = [&](const std::string &folder) {
    const nlohmann::json summary = nlohmann::json::parse(
      read_file(cli::join(s.path, folder + "/summary.json")));
    std::string all;
    if (summary.contains("warnings"))
      for (const auto &w : summary.at("warnings"))
        all += w.get<std::string>() + "\n";
    return all;
  };
  struct Case
  {
    std::string scene, sets, folder;
    bool        units;
  };
  const std::vector<Case> cases = {
    {"v5-hertz-2d.prm", "", "v5", false},
    {"v5-hertz-2d.prm", " --set \"Body 1/Young's modulus=1e9\"", "v5-pa", true},
    {"v3-contact-patch-2d.prm", "", "v3", false},
    {"v3-contact-patch-2d.prm",
     " --set \"Body 1/Young's modulus=1e9\""
     " --set \"Body 2/Young's modulus=1e9\"",
     "v3-stiff",
     true},
    {"v3-contact-patch-2d.prm",
     " --set \"Body 1/Young's modulus=1e-3\""
     " --set \"Body 2/Young's modulus=1e-3\"",
     "v3-soft",
     true}};
  for (const auto &c : cases)
    {
      SCOPED_TRACE(c.folder);
      const auto r = run_igabde(scene(c.scene) + quiet + c.sets +
                                  " --set 'Output/Directory=" + c.folder + "'",
                                s.path);
      ASSERT_EQ(r.status, 0) << r.output;
      const std::string w = warnings_of(c.folder);
      EXPECT_EQ(contains(w, "check the units") ||
                  contains(w, "inconsistent units"),
                c.units)
        << w;
    }
}



TEST(NoSilentWrongAnswer, ProjectionsOntoACurvedMasterFromAfarConverge)
{
  // A block [0, 1] x [2.5, 3.5] held 1.5 above the outer arc r = 1 of a
  // quarter annulus (weighted-gap pairs, the slave face y = 2.5). Its
  // points lie farther than twice the arc's radius from its centre, where
  // the Gauss-Newton projection without the curvature term diverges: the
  // set-up failed ("did not converge in 100 iterations"). Each pair's
  // gap, the N_j-weighted mean of the pointwise gap g(x) = |x| - 1 over
  // the support of N_j, must meet g at the pair's centroid to within the
  // second-order term: max |g''| (about 1 / 2.5) times half the square of
  // the support's half-width (3 spans of 1/16 over 2): 2e-3. A projection
  // stuck at the arc's end (0, 1) would be off by up to 0.1.
  const Scratch     s("projection");
  const std::string block =
    "set Dimension = 2\n"
    "subsection Discretization\n  set Type = nurbs\n  set Degree = 2\nend\n"
    "subsection Body 1\n  set Geometry = box\n"
    "  set Lower corner = 0, 2.5\n  set Upper corner = 1, 3.5\n"
    "  set Subdivisions = 16, 8\n  set Young's modulus = 1000\n"
    "  set Poisson's ratio = 0.3\n  set Supports = 0: x; 3: y\nend\n"
    "subsection Body 2\n  set Type = deformable\n"
    "  set Geometry = quarter annulus\n  set Inner radius = 0.5\n"
    "  set Outer radius = 1\n  set Subdivisions = 8, 16\n"
    "  set Young's modulus = 1000\n  set Poisson's ratio = 0.3\n"
    "  set Supports = 0: x, y; 3: x\nend\n"
    "subsection Contact\n  set Enabled = true\n"
    "  set Pairing = weighted-gap-standard\n  set Slave face = 2\n"
    "  set Master face = 1\nend\n"
    "subsection Output\n  set Write vtu = false\nend\n";
  std::ofstream(cli::join(s.path, "block.prm")) << block;
  const auto r =
    run_igabde("block.prm --quiet --set 'Output/Directory=out'", s.path);
  ASSERT_EQ(r.status, 0) << r.output;
  std::istringstream csv(read_file(cli::join(s.path, "out/contact-0001.csv")));
  std::string        line;
  std::getline(csv, line);
  ASSERT_EQ(line.rfind("pair,x,y,area,gap,", 0), 0u) << line;
  unsigned int n = 0;
  while (std::getline(csv, line))
    {
      std::array<double, 5> v;
      std::istringstream    fields(line);
      std::string           field;
      for (double &value : v)
        {
          std::getline(fields, field, ',');
          value = std::stod(field);
        }
      EXPECT_NEAR(v[4], std::hypot(v[1], v[2]) - 1., 2e-3) << line;
      ++n;
    }
  EXPECT_EQ(n, 18u);

  // The slave face reaching past the master's extent (the block replaced
  // by a disc of radius 8 touching the arc's end from above): the slave
  // points beyond the arc's end are left out and counted, the others
  // pair. The contact sits on the master's corner, the arc's thin free
  // end: the contact solver does not converge there, and says so and
  // where, with the set-up's figures kept (converge or say why).
  std::ofstream(cli::join(s.path, "disc.prm"))
    << "set Dimension = 2\n"
       "subsection Discretization\n  set Type = nurbs\n  set Degree = 2\nend\n"
       "subsection Body 1\n  set Geometry = half disc\n  set Centre = 0, 9\n"
       "  set Radius = 8\n  set Subdivisions = 40, 8\n"
       "  set Young's modulus = 1000\n  set Poisson's ratio = 0.3\n"
       "  set Supports = 3: x\n  set Tractions = 3: vector 0, -0.1\nend\n"
       "subsection Body 2\n  set Type = deformable\n"
       "  set Geometry = quarter annulus\n  set Inner radius = 0.5\n"
       "  set Outer radius = 1\n  set Subdivisions = 16, 16\n"
       "  set Young's modulus = 1000\n  set Poisson's ratio = 0.3\n"
       "  set Supports = 0: x, y\nend\n"
       "subsection Contact\n  set Enabled = true\n"
       "  set Pairing = weighted-gap\n  set Slave face = 2\n"
       "  set Master face = 1\nend\n"
       "subsection Output\n  set Write vtu = false\nend\n";
  const auto past =
    run_igabde("disc.prm --quiet --set 'Output/Directory=past'", s.path);
  EXPECT_EQ(past.status, 1) << past.output;
  EXPECT_TRUE(contains(past.output, "the contact solver did not converge"))
    << past.output;
  EXPECT_TRUE(contains(past.output, "where: pair")) << past.output;
  std::ifstream        in(cli::join(s.path, "past/summary.json"));
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary.at("status"), "failed");
  EXPECT_GT(summary.at("contact_points_left_out")
              .at("outside_master")
              .get<unsigned int>(),
            0u);
  // No projection failed: each slave point settled or was left out.
  EXPECT_FALSE(contains(past.output, "did not settle")) << past.output;
}



TEST(NoSilentWrongAnswer, NonPositiveTributaryAreasArePairedByTheWeightedGap)
{
  // A block [0, 1]^2 (B-spline, degree 2 x 1, four spans) whose bottom
  // face has its first two control points 1e-4 apart: the parametrisation
  // nearly stops at the corner, and the Greville collocation gives the
  // corner point the tributary area -0.019. Pressed by 1 onto a rigid
  // plane, its node-to-surface pairs ended "ok" with a pressure
  // uniformity error of 1.0 and no warning. The stated rule now: such an
  // interaction is paired by the weighted gap (areas int N_j >= 0), which
  // carries the uniform pressure exactly (to 1e-8, the closed form), and
  // the log and summary.json's warnings say so and why.
  const Scratch      s("tributary");
  std::ostringstream coefs;
  for (const double y : {0., 1.})
    for (const double x : {0., 1e-4, 0.375, 0.625, 0.875, 1.})
      coefs << x << ' ' << y << '\n';
  std::ofstream(cli::join(s.path, "block.xml"))
    << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<xml>\n"
       "<Geometry type=\"TensorBSpline2\" id=\"0\">\n"
       "<Basis type=\"TensorBSplineBasis2\">\n"
       "<Basis type=\"BSplineBasis\" index=\"0\"><KnotVector degree=\"2\">"
       "0 0 0 0.25 0.5 0.75 1 1 1</KnotVector></Basis>\n"
       "<Basis type=\"BSplineBasis\" index=\"1\"><KnotVector degree=\"1\">"
       "0 0 1 1</KnotVector></Basis>\n</Basis>\n<coefs geoDim=\"2\">\n"
    << coefs.str() << "</coefs>\n</Geometry>\n</xml>\n";
  std::ofstream(cli::join(s.path, "block.prm"))
    << "set Dimension = 2\n"
       "subsection Discretization\n  set Type = nurbs\n  set Degree = 2\nend\n"
       "subsection Body 1\n  set Geometry = file\n"
       "  set Geometry file = block.xml\n  set Young's modulus = 1000\n"
       "  set Poisson's ratio = 0.3\n  set Supports = 0.0: x\n"
       "  set Tractions = 0.3: pressure 1\nend\n"
       "subsection Body 2\n  set Type = rigid plane\n"
       "  set Plane point = 0, 0\n  set Plane normal = 0, 1\nend\n"
       "subsection Contact\n  set Enabled = true\n"
       "  set Slave face = 0.2\nend\n"
       "subsection Checks\n  set Uniform pressure = 1\nend\n"
       "subsection Output\n  set Write vtu = false\nend\n";
  const auto repaired =
    run_igabde("block.prm --set 'Output/Directory=points'", s.path);
  ASSERT_EQ(repaired.status, 0) << repaired.output;
  EXPECT_TRUE(contains(repaired.output, "gets the tributary area -0.019"))
    << repaired.output;
  EXPECT_TRUE(contains(repaired.output, "paired by the weighted gap instead"))
    << repaired.output;
  const nlohmann::json summary =
    nlohmann::json::parse(read_file(cli::join(s.path, "points/summary.json")));
  EXPECT_LE(summary.at("checks").at("pressure_uniformity").get<double>(), 1e-8);
  ASSERT_TRUE(summary.contains("warnings"));
  EXPECT_TRUE(contains(summary.at("warnings").dump(), "weighted gap instead"));
}



TEST(NoSilentWrongAnswer, CollapsedEdgeOfTheContactFace)
{
  // A solid whose bottom face (z = 0) is a triangle: a quad with its edge
  // eta = 1 collapsed to the point (0, 1, 0) (a repeated control point in
  // the geometry file); its top (z = 1) is the unit square, so no face
  // collapses as a whole (which the reader refuses: a pole). Pressed by 1
  // onto a rigid plane. The bottom face's contact points on the collapsed
  // edge (its Greville points there: one per control point along xi, 4
  // spans of degree 2, so 6) have no normal, since the face's measure
  // vanishes there: they are left out and counted as degenerate, and the
  // rest of the face carries the load the top pressure puts on it.
  const Scratch      s("collapsed");
  std::ostringstream coefs;
  for (const double z : {0., 1.})
    for (const double y : {0., 1.})
      for (const double x : {0., 1.})
        coefs << (z == 0. && y == 1. ? 0. : x) << ' ' << y << ' ' << z << '\n';
  const std::string knots = "0 0 1 1";
  std::ofstream(cli::join(s.path, "wedge.xml"))
    << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<xml>\n"
       "<Geometry type=\"TensorBSpline3\" id=\"0\">\n"
       "<Basis type=\"TensorBSplineBasis3\">\n"
       "<Basis type=\"BSplineBasis\" index=\"0\"><KnotVector degree=\"1\">"
    << knots
    << "</KnotVector></Basis>\n"
       "<Basis type=\"BSplineBasis\" index=\"1\"><KnotVector degree=\"1\">"
    << knots
    << "</KnotVector></Basis>\n"
       "<Basis type=\"BSplineBasis\" index=\"2\"><KnotVector degree=\"1\">"
    << knots << "</KnotVector></Basis>\n</Basis>\n<coefs geoDim=\"3\">\n"
    << coefs.str() << "</coefs>\n</Geometry>\n</xml>\n";
  std::ofstream(cli::join(s.path, "wedge.prm"))
    << "set Dimension = 3\n"
       "subsection Discretization\n  set Type = nurbs\n  set Degree = 2\nend\n"
       "subsection Body 1\n  set Geometry = file\n"
       "  set Geometry file = wedge.xml\n  set Subdivisions = 4, 4, 1\n"
       "  set Young's modulus = 1000\n"
       "  set Poisson's ratio = 0.3\n  set Supports = 0.0: x; 0.2: y\n"
       "  set Tractions = 0.5: pressure 1\nend\n"
       "subsection Body 2\n  set Type = rigid plane\n"
       "  set Plane point = 0, 0, 0\n  set Plane normal = 0, 0, 1\nend\n"
       "subsection Contact\n  set Enabled = true\n"
       "  set Slave face = 0.4\nend\n"
       "subsection Output\n  set Write vtu = false\nend\n";
  const auto run = run_igabde("wedge.prm --set 'Output/Directory=out'", s.path);
  ASSERT_EQ(run.status, 0) << run.output;
  const nlohmann::json summary =
    nlohmann::json::parse(read_file(cli::join(s.path, "out/summary.json")));
  ASSERT_TRUE(summary.contains("contact_points_left_out")) << run.output;
  EXPECT_EQ(summary.at("contact_points_left_out")
              .at("degenerate_normal")
              .get<unsigned int>(),
            6u)
    << run.output;
  EXPECT_TRUE(contains(run.output, "have a degenerate normal")) << run.output;
  // The top pressure's resultant, 1 over the unit square, reaches the
  // plane (the solid is held vertically by the contact alone).
  EXPECT_NEAR(summary.at("total_contact_force")[2].get<double>(), 1., 1e-8)
    << run.output;
}
