// summary.json numbers read back exactly: 17 significant digits round-trip
// every double (IEEE 754: max_digits10 = 17), including the largest finite
// one, which 16 digits round up to infinity.

#include <igabde/base/json.h>

#include <gtest/gtest.h>

#include <cfloat>
#include <cstdlib>
#include <sstream>

TEST(Json, NumbersRoundTrip)
{
  for (const double x : {DBL_MAX,
                         -DBL_MAX,
                         DBL_MIN,
                         0.1,
                         1. / 3.,
                         2.2250738585072009e-308,
                         123456789.12345678})
    {
      igabde::base::Json value(x);
      std::ostringstream out;
      value.write(out);
      const double back = std::strtod(out.str().c_str(), nullptr);
      EXPECT_EQ(back, x) << out.str();
    }
}
