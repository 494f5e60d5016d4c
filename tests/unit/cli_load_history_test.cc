// Load histories (Load path/Histories, '@ name' on load entries): a normal
// load held while a tangential one grows and reverses, each on its own
// history, run by the executable. The reference is the statics of the
// scene, computed here from the loads the test prescribes: a body held
// only by the contact carries, at every step, a total contact force equal
// and opposite to the resultant of its loads at that step's factors; a
// clamped body's support reactions do the same, and a prescribed
// displacement is met exactly where it is prescribed.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  /// Tolerance on resultants relative to the largest load: the rigid-mode
  /// rows of the contact system (sum of the contact forces = minus the
  /// applied resultant) are linear and solved to round-off in every Newton
  /// step; the natural-map stopping test (1e-10, amplified at most 1e2 by
  /// the condensed system's conditioning, as in hard_cases_test.cc) bounds
  /// the rest.
  constexpr double solver_tolerance = 1e-8;

  /// steps.csv as one map column name -> value per row (status as 1 = ok).
  std::vector<std::map<std::string, double>>
  read_steps(const std::string &path)
  {
    std::ifstream                              in(path);
    std::string                                line;
    std::vector<std::string>                   names;
    std::vector<std::map<std::string, double>> rows;
    const auto cells = [](const std::string &l) {
      std::vector<std::string> result;
      std::stringstream        s(l);
      std::string              cell;
      while (std::getline(s, cell, ','))
        result.push_back(cell);
      return result;
    };
    if (std::getline(in, line))
      names = cells(line);
    while (std::getline(in, line))
      {
        const auto                    values = cells(line);
        std::map<std::string, double> row;
        for (unsigned int c = 0; c < names.size() && c < values.size(); ++c)
          row[names[c]] =
            (names[c] == "status" ? (values[c] == "ok" ? 1. : 0.) :
                                    std::stod(values[c]));
        rows.push_back(row);
      }
    return rows;
  }

  /// "name: f1, f2, ..." for Load path/Histories.
  std::string
  history_entry(const std::string &name, const std::vector<double> &factors)
  {
    std::ostringstream s;
    s << name << ":";
    for (unsigned int i = 0; i < factors.size(); ++i)
      s << (i == 0 ? " " : ", ") << factors[i];
    return s.str();
  }
} // namespace



class LoadHistory : public ::testing::TestWithParam<std::string>
{};



// The block [0, 1] x [0, h] of prm/load-histories-block.prm on a rigid flat,
// no support: pressure p on the top (history 'normal', held after the first
// step), tangential traction (-t, 0) on the right face x = 1 (history
// 'shear', zero while the normal load comes on, then growing and reversing).
// The contact force on the block is (t h shear_s, p normal_s) at every step,
// whatever the friction state of the pairs; |t h shear| < mu p normal, so
// the block as a whole sticks and every step has a solution.
TEST_P(LoadHistory, TangentialResultantFollowsItsHistory)
{
  const double              p = 10., t = 4., h = 0.5, mu = 0.4;
  const std::vector<double> normal = {0.5, 1., 1., 1., 1., 1., 1.};
  const std::vector<double> shear  = {0., 0., 0.3, 0.6, 0.9, 0.3, -0.9};
  ASSERT_LT(t * h * 0.9, mu * p * 1.);

  const cli::ScratchFolder scratch("load-history-" + GetParam());
  std::ostringstream       sets;
  sets << "--set 'Discretization/Type=" << GetParam() << "' "
       << "--set 'Body 1/Lower corner=0, 0' "
       << "--set 'Body 1/Upper corner=1, " << h << "' "
       << "--set 'Body 1/Tractions=3: pressure " << p << " @ normal; 1: vector "
       << -t << ", 0 @ shear' "
       << "--set 'Contact/Friction coefficient=" << mu << "' "
       << "--set 'Load path/Number of steps=" << shear.size() << "' "
       << "--set 'Load path/Histories=" << history_entry("normal", normal)
       << "; " << history_entry("shear", shear) << "' ";
  const auto result = cli::run_igabde(
    "'" +
      cli::join(std::string(IGABDE_SOURCE_DIR),
                "prm/load-histories-block.prm") +
      "' --quiet --set 'Output/Directory=out' --set 'Output/Write vtu=false' "
      "--set 'Output/Print timing=false' " +
      sets.str(),
    scratch.path);
  ASSERT_EQ(result.status, 0) << result.output;

  const auto rows = read_steps(cli::join(scratch.path, "out/steps.csv"));
  ASSERT_EQ(rows.size(), shear.size());
  const double scale = p;
  for (unsigned int s = 0; s < rows.size(); ++s)
    {
      SCOPED_TRACE("step " + std::to_string(s + 1));
      const auto &row = rows[s];
      ASSERT_EQ(row.count("shear_factor"), 1u);
      ASSERT_EQ(row.count("force_x"), 1u);
      EXPECT_EQ(row.at("status"), 1.);
      // The factors as given (steps.csv prints 12 digits).
      EXPECT_NEAR(row.at("normal_factor"), normal[s], 1e-12);
      EXPECT_NEAR(row.at("shear_factor"), shear[s], 1e-12);
      // Statics of the floating block: minus the applied resultant.
      EXPECT_NEAR(row.at("force_x"),
                  t * h * shear[s],
                  solver_tolerance * scale);
      EXPECT_NEAR(row.at("force_y"),
                  p * 1. * normal[s],
                  solver_tolerance * scale);
    }
}



// Point loads and a prescribed displacement on their own histories, no
// contact: the block clamped at its bottom (face 2), a point load (f, 0) at
// the top right corner on 'shear', (0, -g) at the top centre on 'normal',
// and the top face moved down by d on 'press'. Whatever the displacement
// field, the support reactions (which include the prescribed face) balance
// the point loads: (-f shear_s, g normal_s); at the last step the top face
// has moved by -d press_last.
TEST_P(LoadHistory, PointLoadsAndPrescribedDisplacementFollowTheirHistories)
{
  const double              f = 3., g = 5., d = 0.01;
  const std::vector<double> normal = {1., 1., 1., 1.};
  const std::vector<double> shear  = {0., 0.5, 1., -1.};
  const std::vector<double> press  = {0., 0., 1., 0.5};

  const cli::ScratchFolder scratch("load-history-points-" + GetParam());
  std::ostringstream       sets;
  sets << "--set 'Discretization/Type=" << GetParam() << "' "
       << "--set 'Body 1/Tractions=' "
       << "--set 'Body 1/Supports=2: x y; 3: y=" << -d << " @ press' "
       << "--set 'Body 1/Point loads=1, 0.5 : " << f
       << ", 0 @ shear; 0.5, 0.5 : 0, " << -g << " @ normal' "
       << "--set 'Body 2/Type=none' --set 'Contact/Enabled=false' "
       << "--set 'Probe points=T: 0.25, 0.5' "
       << "--set 'Load path/Number of steps=" << shear.size() << "' "
       << "--set 'Load path/Histories=" << history_entry("normal", normal)
       << "; " << history_entry("shear", shear) << "; "
       << history_entry("press", press) << "' ";
  const auto result = cli::run_igabde(
    "'" +
      cli::join(std::string(IGABDE_SOURCE_DIR),
                "prm/load-histories-block.prm") +
      "' --quiet --set 'Output/Directory=out' --set 'Output/Write vtu=false' "
      "--set 'Output/Print timing=false' " +
      sets.str(),
    scratch.path);
  ASSERT_EQ(result.status, 0) << result.output;

  std::ifstream in(cli::join(scratch.path, "out/summary.json"));
  const auto    summary = nlohmann::json::parse(in, nullptr, false);
  ASSERT_FALSE(summary.is_discarded());
  const auto &steps = summary.at("load_steps");
  ASSERT_EQ(steps.size(), shear.size());
  // Reactions are sums of K u - f over the supported unknowns: round-off of
  // the direct solve relative to the loads.
  const double tolerance = 1e-10 * std::max(f, g);
  for (unsigned int s = 0; s < steps.size(); ++s)
    {
      SCOPED_TRACE("step " + std::to_string(s + 1));
      const auto reaction = steps[s]
                              .at("bodies")
                              .at(0)
                              .at("support_reaction")
                              .get<std::vector<double>>();
      EXPECT_NEAR(reaction.at(0), -f * shear[s], tolerance);
      EXPECT_NEAR(reaction.at(1), g * normal[s], tolerance);
    }
  // The prescribed top face: exact for a constant value (sum of the basis
  // functions is one on the face), to round-off.
  const auto top = summary.at("points").at("T").get<std::vector<double>>();
  EXPECT_NEAR(top.at(1), -d * press.back(), 1e-12);
}



INSTANTIATE_TEST_SUITE_P(BothDiscretisations,
                         LoadHistory,
                         ::testing::Values("nurbs", "lagrange"));



// Histories that cannot be followed are refused when the scene is read.
TEST(CliBadInput, LoadHistoryUndeclaredOrOfWrongLength)
{
  const std::string scene =
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/load-histories-block.prm");
  const std::vector<std::pair<std::string, std::string>> cases = {
    {"Body 1/Tractions=3: pressure 10 @ nrmal", "load history 'nrmal'"},
    {"Load path/Histories=normal: 1, 1; shear: 0, 1",
     "'normal' has 2 factors but the load path has 5 steps"},
    {"Load path/Histories=normal: 1, 1, 1, 1, 1; normal: 1, 1, 1, 1, 1",
     "'normal' is declared twice"},
    {"Load path/Histories=load: 1, 1, 1, 1, 1", "is not a usable name"}};
  for (const auto &[setting, message] : cases)
    {
      SCOPED_TRACE(setting);
      const cli::ScratchFolder folder("bad-input-history");
      const auto result = cli::run_igabde("'" + scene + "' --set \"" + setting +
                                            "\" --set 'Output/Directory=out'",
                                          folder);
      EXPECT_EQ(result.status, 2) << result.output;
      EXPECT_EQ(result.output.find('\n'), result.output.size() - 1)
        << result.output;
      EXPECT_NE(result.output.find(message), std::string::npos)
        << result.output;
      EXPECT_FALSE(std::filesystem::exists(cli::join(folder.path, "out")));
    }
}
