// Hold rotation: a body held by forces and contact, its rotation held as a
// distributing coupling holds it. Checked against Cattaneo and Mindlin's
// partial-slip solution, and the two ways of condensing a body with a held
// rotation (Schur complement with a rank-two correction, one projected
// solve per column) against each other.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  using nlohmann::json;

  using cli::SceneRun;

  SceneRun
  run_partial_slip(const cli::ScratchFolder &scratch, const std::string &sets)
  {
    return cli::run_prm_scene(scratch.path, "v6-partial-slip-force.prm", sets);
  }

  struct PairRow
  {
    double      x = 0.;
    std::string status;
  };

  /// The pairs of a contact CSV (x and status), sorted by x.
  std::vector<PairRow>
  read_pairs(const std::string &file)
  {
    std::ifstream            in(file);
    std::string              line;
    std::vector<std::string> header;
    std::vector<PairRow>     rows;
    std::getline(in, line);
    {
      std::istringstream s(line);
      std::string        name;
      while (std::getline(s, name, ','))
        header.push_back(name);
    }
    const auto column = [&](const std::string &name) {
      return std::find(header.begin(), header.end(), name) - header.begin();
    };
    const auto x_column      = column("x");
    const auto status_column = column("status");
    while (std::getline(in, line))
      {
        std::vector<std::string> cells;
        std::istringstream       s(line);
        std::string              cell;
        while (std::getline(s, cell, ','))
          cells.push_back(cell);
        rows.push_back(
          {std::stod(cells.at(x_column)), cells.at(status_column)});
      }
    std::sort(rows.begin(), rows.end(), [](const auto &a, const auto &b) {
      return a.x < b.x;
    });
    return rows;
  }

  /// Half the extent of the pairs whose status is in @p statuses, each end
  /// midway between the last such pair and its outer neighbour.
  double
  half_width(const std::vector<PairRow>     &rows,
             const std::vector<std::string> &statuses)
  {
    const auto in = [&](const PairRow &r) {
      return std::find(statuses.begin(), statuses.end(), r.status) !=
             statuses.end();
    };
    std::size_t first = rows.size(), last = 0;
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (in(rows[i]))
        {
          first = std::min(first, i);
          last  = i;
        }
    EXPECT_LT(first, rows.size());
    EXPECT_GT(first, 0u);
    EXPECT_LT(last + 1, rows.size());
    if (first >= rows.size() || first == 0 || last + 1 >= rows.size())
      return 0.;
    const double left  = 0.5 * (rows[first - 1].x + rows[first].x);
    const double right = 0.5 * (rows[last].x + rows[last + 1].x);
    return 0.5 * (right - left);
  }
} // namespace



TEST(CliHoldRotation, ForceControlledPartialSlipMeetsCattaneoMindlin)
{
  // Cattaneo and Mindlin for two elastically similar bodies (no coupling
  // of normal and tangential tractions): under a constant normal force P
  // and a growing tangential force Q the stick zone is centred, of
  // half-width c = a sqrt(1 - Q / (mu P)). The contact half-width a and
  // c are read from the same run's pairs (ends midway between a pair in
  // and the next out), so the finite disc's departure from the
  // half-space does not enter; pair spacing h ~ a / 17 bounds the error of
  // each end by h / 2, about 3 % of c at Q / (mu P) = 0.6, so 5 %. (At
  // Q = 0 the finite bodies let the outermost pairs slip: c / a = 1 within
  // the same 5 %.)
  const cli::ScratchFolder scratch("force_slip", "hold");
  const SceneRun           run = run_partial_slip(scratch, "");
  ASSERT_EQ(run.status, 0) << run.output;
  ASSERT_EQ(run.summary.at("status"), "ok") << run.output;
  const double mu    = 0.5;
  const json  &steps = run.summary.at("load_steps");
  ASSERT_EQ(steps.size(), 5u);
  for (unsigned int s = 0; s < steps.size(); ++s)
    {
      SCOPED_TRACE("step " + std::to_string(s + 1));
      // The forces applied on the diameter: 200 down, 60 s / 4 sideways.
      // The contact carries them (the disc is held by contact alone, its
      // equilibrium rows make the resultant the load): they are the data
      // of the closed form, not a check.
      const double P = 200., Q = 15. * s;
      char         name[32];
      std::snprintf(name, sizeof(name), "out/contact-%04u.csv", s + 1);
      const auto   rows = read_pairs(cli::join(scratch.path, name));
      const double a    = half_width(rows, {"stick", "slip"});
      const double c    = half_width(rows, {"stick"});
      EXPECT_NEAR(c / a, std::sqrt(1. - Q / (mu * P)), 0.05 * c / a)
        << "a = " << a << ", c = " << c;
      // The held rotation's reaction balances the moment of the contact
      // forces about the diameter's centre (the uniform tractions on the
      // diameter have none): 8 Q from the tangential force at depth 8,
      // less e P from the centre of pressure's offset e, which stays
      // within half a pair spacing (0.06), so e P < 0.1 * 8 Q for Q >= 15.
      if (s == 0)
        continue;
      const auto moment =
        steps[s].at("bodies")[0].at("held_moment").get<std::vector<double>>();
      ASSERT_EQ(moment.size(), 1u);
      EXPECT_NEAR(moment[0], 8. * Q, 0.1 * 8. * Q);
    }
}



TEST(CliHoldRotation, SchurComplementAndColumnsAgree)
{
  // The Schur-complement flexibility of a body with a held rotation is
  // corrected by a rank-two update; one solve per column projects every
  // solve instead. Two independent computations of the same W: the runs
  // agree to the contact tolerance's order.
  const std::string        coarse = "--set 'Body 1/Subdivisions=58, 8' "
                                    "--set 'Body 2/Subdivisions=70, 16'";
  const cli::ScratchFolder schur_folder("schur", "hold");
  const cli::ScratchFolder columns_folder("columns", "hold");
  const SceneRun           schur = run_partial_slip(schur_folder, coarse);
  const SceneRun           columns =
    run_partial_slip(columns_folder,
                     coarse + " --set 'Contact/Condensation=columns'");
  ASSERT_EQ(schur.status, 0) << schur.output;
  ASSERT_EQ(columns.status, 0) << columns.output;
  const json &a = schur.summary.at("load_steps");
  const json &b = columns.summary.at("load_steps");
  ASSERT_EQ(a.size(), b.size());
  for (unsigned int s = 0; s < a.size(); ++s)
    {
      EXPECT_EQ(a[s].at("n_stick"), b[s].at("n_stick"));
      EXPECT_EQ(a[s].at("n_slip"), b[s].at("n_slip"));
      const double ma = a[s].at("bodies")[0].at("held_moment")[0].get<double>();
      const double mb = b[s].at("bodies")[0].at("held_moment")[0].get<double>();
      EXPECT_NEAR(ma, mb, 1e-8 * (1. + std::abs(ma)));
    }
  const auto ua =
    schur.summary.at("points").at("top").get<std::vector<double>>();
  const auto ub =
    columns.summary.at("points").at("top").get<std::vector<double>>();
  ASSERT_EQ(ua.size(), 2u);
  ASSERT_EQ(ub.size(), 2u);
  const double scale = std::hypot(ua[0], ua[1]);
  EXPECT_GT(scale, 0.);
  for (unsigned int c = 0; c < 2; ++c)
    EXPECT_NEAR(ua[c], ub[c], 1e-8 * scale);
}
