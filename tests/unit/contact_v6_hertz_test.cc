// V6 (prm/v6-cylinder-on-block.prm, issue #12): an elastic cylinder R = 8
// pressed by P = 60 per unit length onto an elastic block of the same
// material (E = 1000, nu = 0.3, plane strain), mu = 0.5, full model,
// weighted-gap pairs. The reference is Johnson's two-body line contact
// (Contact Mechanics sec. 4.2), computed here from the scene's data:
// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2, a = sqrt(4 P R / (pi E*)),
// p(x) = p0 sqrt(1 - x^2/a^2), p0 = 2 P / (pi a). Identical materials make
// Dundurs' beta vanish, so friction leaves this normal problem unchanged
// (Johnson sec. 5.4). The criteria are the issue's: a and p0 within 1 %,
// and every pair inside |x| < 0.9 a within 3 % of p0 of Johnson's profile
// for cylinder-to-block spacing ratios 1:2, 1:1 and 2:1 at the contact.
// They leave room for what the discrete scene is not: the block is 16 x 8
// and clamped, not a half-space, and a pair's pressure is the mean of the
// pressure over the support of its basis function (about 1.5 % of p0 below
// the point value at 0.9 a on these meshes, from the curvature of the
// profile there).

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  constexpr double P = 60., R = 8., E = 1000., nu = 0.3;

  /// Johnson's half-width and peak pressure of the two-body contact.
  std::pair<double, double>
  johnson()
  {
    const double e_star = 1. / (2. * (1. - nu * nu) / E);
    const double a      = std::sqrt(4. * P * R / (M_PI * e_star));
    return {a, 2. * P / (M_PI * a)};
  }

  struct V6Run
  {
    nlohmann::json summary;
    /// Pair x coordinate, pressure and normal force (contact-0001.csv).
    std::vector<std::array<double, 3>> pairs;
    /// The recovered pressure of each pair (NaN where none was written).
    std::vector<double> recovered;
    /// Whether each pair is open.
    std::vector<bool> open;
  };

  /// Runs V6 with the overrides @p sets in a scratch folder.
  V6Run
  run_v6(const std::string &name, const std::string &sets)
  {
    const cli::ScratchFolder scratch(name, "v6");
    const auto               result = cli::run_igabde(
      "'" +
        cli::join(std::string(IGABDE_SOURCE_DIR),
                  "prm/v6-cylinder-on-block.prm") +
        "' --quiet --set 'Output/Directory=out' --set 'Output/Print "
                      "timing=false' " +
        sets,
      scratch.path);
    EXPECT_EQ(result.status, 0) << result.output;
    V6Run run;
    run.summary =
      nlohmann::json::parse(cli::read_file(
                              cli::join(scratch.path, "out/summary.json")),
                            nullptr,
                            false);
    const cli::CsvTable table =
      cli::read_table(cli::join(scratch.path, "out/contact-0001.csv"));
    EXPECT_EQ(table.header,
              (std::vector<std::string>{"pair",
                                        "x",
                                        "y",
                                        "area",
                                        "gap",
                                        "p_n",
                                        "p_t1",
                                        "pressure",
                                        "recovered_pressure",
                                        "slip_t1",
                                        "status"}));
    for (std::size_t r = 0; r < table.rows.size(); ++r)
      {
        run.pairs.push_back(std::array<double, 3>{{table.number(r, "x"),
                                                   table.number(r, "pressure"),
                                                   table.number(r, "p_n")}});
        run.recovered.push_back(table.number(r, "recovered_pressure"));
        run.open.push_back(table.rows[r][table.column("status")] == "open");
      }
    return run;
  }

  /// Largest |p_i - p(x_i)| / p0 over the pairs with |x_i| < 0.9 a, and
  /// how many there are.
  std::pair<double, unsigned int>
  pair_deviation(const V6Run &run)
  {
    const auto [a, p0] = johnson();
    double       worst = 0.;
    unsigned int n     = 0;
    for (const auto &[x, p, f] : run.pairs)
      if (std::abs(x) < 0.9 * a)
        {
          worst =
            std::max(worst,
                     std::abs(p - p0 * std::sqrt(1. - x * x / (a * a))) / p0);
          ++n;
        }
    return {worst, n};
  }
} // namespace



// The scene as it is (116 spans on the cylinder's contact arc, 140 across
// the block: spacing 0.114 on both sides of the contact, about a / 9).
TEST(ContactV6Hertz, HalfWidthAndPeakPressureWithinOnePercent)
{
  const auto [a, p0] = johnson();
  const V6Run run    = run_v6("scene", "");
  ASSERT_EQ(run.summary.at("status"), "ok");
  const auto &checks = run.summary.at("checks");
  // The scene's own reference is this one (E* from both bodies).
  EXPECT_NEAR(checks.at("hertz_half_width_exact").get<double>(), a, 1e-12 * a);
  EXPECT_NEAR(checks.at("hertz_peak_pressure_exact").get<double>(),
              p0,
              1e-12 * p0);

  // The sum of the pair forces is not checked against P: the cylinder is
  // held by the contact alone, whose equilibrium rows G^T p = b make it P
  // by construction. It is the denominator of the moment below.
  double force = 0., moment = 0., peak = 0.;
  for (const auto &[x, p, f] : run.pairs)
    {
      force += f;
      moment += f * x * x;
      peak = std::max(peak, p);
    }

  // a from the second moment of the pair forces (int p x^2 = P a^2 / 4 for
  // Johnson's profile), recomputed here from the pair table; p0 the
  // largest pair pressure.
  const double a_h = 2. * std::sqrt(moment / force);
  EXPECT_NEAR(a_h / a, 1., 0.01) << "a_h = " << a_h << ", Johnson " << a;
  EXPECT_NEAR(peak / p0, 1., 0.01) << "p0_h = " << peak << ", Johnson " << p0;
  // The scene's figures are these (the pair table has 12 significant
  // digits).
  EXPECT_NEAR(checks.at("hertz_half_width_moment").get<double>(),
              a_h,
              1e-10 * a);
  EXPECT_NEAR(checks.at("hertz_peak_pressure").get<double>(), peak, 1e-10 * p0);

  const auto [worst, n] = pair_deviation(run);
  EXPECT_GE(n, 14u);
  EXPECT_LE(worst, 0.03);
  EXPECT_NEAR(checks.at("hertz_max_pair_deviation").get<double>(),
              worst,
              1e-10);
}



// Cylinder-to-block spacing 1:2 (block 70 spans) and 2:1 (block 280 spans)
// at the contact; 1:1 is the scene above.
TEST(ContactV6Hertz, PairsFollowJohnsonWhateverTheMeshRatio)
{
  for (const unsigned int block : {70u, 280u})
    {
      SCOPED_TRACE("block " + std::to_string(block) + " spans");
      const V6Run run =
        run_v6("ratio-" + std::to_string(block),
               "--set 'Body 2/Subdivisions=" + std::to_string(block) + ", 32'");
      ASSERT_EQ(run.summary.at("status"), "ok");
      const auto [worst, n] = pair_deviation(run);
      EXPECT_GE(n, 14u);
      EXPECT_LE(worst, 0.03);
    }
}



// The recovered pressure -n.sigma(u_h).n (n Body 1's outward normal) is
// read from the cylinder's stress field at the point of its contact face
// closest to each pair (FE_Q(2) weighted-gap pair points are weighted means
// over the pairs' supports and some lie just off the cylinder). It is
// finite at every pair, and it converges at the rate the theory gives,
// checked between the mesh of spacing 2h and the scene's, h, on the same
// two windows: at the contact edge the pressure is a square root,
// p0 sqrt(1 - x^2/a^2), so at a fixed distance from it the stress error
// falls at least as h^(1/2), the problem's slowest rate. With D the largest
// distance of the recovered pressure from the exact traction over p0:
//  - inside |x| < 0.9 a, from Johnson's p(x), which the finite cylinder on
//    its finite block is not: D(h) <= D(2h) / sqrt(2) + F(h), F(h) the
//    pair pressures' own largest distance from Johnson there (they
//    converge faster; this run's figure);
//  - on the traction-free face past a + 3 (2h), from zero, exact for the
//    finite model too: D(h) <= D(2h) / sqrt(2).
TEST(ContactV6Hertz, RecoveredPressuresConvergeAtTheEdgeSingularitysRate)
{
  const auto [a, p0] = johnson();
  for (const std::string type : {"nurbs", "lagrange"})
    {
      SCOPED_TRACE(type);
      const std::string discretisation =
        "--set 'Discretization/Type=" + type + "'";
      const V6Run fine = run_v6("recovered-" + type, discretisation);
      const V6Run coarse =
        run_v6("recovered-coarse-" + type,
               discretisation + " --set 'Body 1/Subdivisions=58, 8' " +
                 "--set 'Body 2/Subdivisions=70, 16'");
      ASSERT_EQ(fine.summary.at("status"), "ok");
      ASSERT_EQ(coarse.summary.at("status"), "ok");
      // The coarse run's pair spacing at the axis.
      std::vector<double> xs;
      for (const auto &pair : coarse.pairs)
        xs.push_back(pair[0]);
      std::sort(xs.begin(), xs.end());
      double h = std::numeric_limits<double>::max();
      for (std::size_t i = 0; i + 1 < xs.size(); ++i)
        if (std::abs(xs[i]) < a)
          h = std::min(h, xs[i + 1] - xs[i]);
      const double edge_zone = a + 3. * h;
      // Inside and outside distances, and the pairs' inside distance.
      const auto distances = [&](const V6Run &run) {
        double inside = 0., outside = 0., pairs = 0.;
        for (std::size_t i = 0; i < run.pairs.size(); ++i)
          {
            const double x = run.pairs[i][0];
            EXPECT_TRUE(std::isfinite(run.recovered[i])) << "pair " << i;
            if (std::abs(x) < 0.9 * a)
              {
                const double exact = p0 * std::sqrt(1. - x * x / (a * a));
                inside =
                  std::max(inside, std::abs(run.recovered[i] - exact) / p0);
                pairs = std::max(pairs, std::abs(run.pairs[i][1] - exact) / p0);
              }
            else if (std::abs(x) > edge_zone)
              {
                EXPECT_TRUE(run.open[i]) << "pair " << i << " at x = " << x;
                outside = std::max(outside, std::abs(run.recovered[i]) / p0);
              }
          }
        return std::array<double, 3>{{inside, outside, pairs}};
      };
      const auto d_fine   = distances(fine);
      const auto d_coarse = distances(coarse);
      EXPECT_LE(d_fine[0], d_coarse[0] / std::sqrt(2.) + d_fine[2])
        << "inside |x| < 0.9 a: " << d_coarse[0] << " -> " << d_fine[0];
      EXPECT_LE(d_fine[1], d_coarse[1] / std::sqrt(2.))
        << "traction-free, |x| > " << edge_zone << ": " << d_coarse[1] << " -> "
        << d_fine[1];
    }
}
