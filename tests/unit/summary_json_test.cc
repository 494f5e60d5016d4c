// summary.json numbers read back exactly: the writer (nlohmann::json's
// dump(), as the simulator uses it) must round-trip every double, including
// the largest finite one, which 16 significant digits round up to infinity,
// and write non-finite values as null, never as a number.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <nlohmann/json.hpp>

TEST(SummaryJson, NumbersRoundTrip)
{
  for (const double x : {DBL_MAX,
                         -DBL_MAX,
                         DBL_MIN,
                         0.1,
                         1. / 3.,
                         2.2250738585072009e-308,
                         123456789.12345678})
    {
      const nlohmann::json summary = {{"value", x}};
      const std::string    text    = summary.dump(2);
      const double back = nlohmann::json::parse(text).at("value").get<double>();
      EXPECT_EQ(back, x) << text;
      // Independently of the library's reader.
      const auto colon = text.find(':');
      EXPECT_EQ(std::strtod(text.c_str() + colon + 1, nullptr), x) << text;
    }
}



TEST(SummaryJson, NonFiniteIsNull)
{
  for (const double x : {std::numeric_limits<double>::infinity(),
                         std::numeric_limits<double>::quiet_NaN()})
    EXPECT_TRUE(
      nlohmann::json::parse(nlohmann::json{{"v", x}}.dump()).at("v").is_null());
}

// bodies[].factorization_flops against bounds that hold for any sparse
// LDL^T of an n x n matrix: each off-diagonal factor entry takes at least
// one operation (so at least half the factor entries, the diagonal
// included), and no order does more than the dense n^3/3 + n^2.
TEST(SummaryJson, FactorizationFlopsWithinTheBoundsOfAnyOrder)
{
  const cli::ScratchFolder scratch("summary-json", "flops");
  const auto run = cli::run_prm_scene(scratch.path, "v5-hertz-2d.prm");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto  &body    = run.summary.at("bodies").at(0);
  const double flops   = body.at("factorization_flops").get<double>();
  const double entries = body.at("factor_entries").get<double>();
  const double n       = body.at("n_dofs").get<double>();
  EXPECT_GE(flops, 0.5 * entries);
  EXPECT_LE(flops, n * n * n / 3. + n * n);
}
