// summary.json numbers read back exactly: the writer (nlohmann::json's
// dump(), as the simulator uses it) must round-trip every double, including
// the largest finite one, which 16 significant digits round up to infinity,
// and write non-finite values as null, never as a number.

#include <gtest/gtest.h>

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
