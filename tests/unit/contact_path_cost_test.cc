// The cost model of Contact/Path = auto (contact/path_cost.h) on inputs
// whose costs are computed by hand: each path wins once.

#include <igabde/contact/path_cost.h>

#include <gtest/gtest.h>

#include <vector>

using namespace igabde::contact;

namespace
{
  // Unit constants: the estimates are the model's work terms themselves.
  PathCostConstants
  unit_constants()
  {
    PathCostConstants c;
    c.dense               = 1.;
    c.schur               = 1.;
    c.sparse_2d           = 1.;
    c.sparse_3d           = 10.;
    c.iterations_per_step = 10.;
    return c;
  }
} // namespace



// Two bodies with 100 face unknowns each, 100 contact unknowns, factors of
// 10^6 entries, 10 Newton iterations, 3D (sparse_3d = 10):
//   condensed = 2 (100^3/3 + 100^2 100 + 100 100^2) + 10 100^3/3
//             = 2 (1e6/3 + 2e6) + 1e7/3 = 8e6,
//   full      = 10 10 (2 1e6) = 2e8:   condensed wins.
TEST(PathCost, CondensedWinsWithFewPairsOnLargeFactors)
{
  PathCostInputs in;
  in.contact_unknowns      = 100.;
  in.face_unknowns         = {100., 100.};
  in.factor_entries        = {1e6, 1e6};
  in.newton_iterations     = 10.;
  in.dimension             = 3;
  const PathCostEstimate e = estimate_path_costs(in, unit_constants());
  EXPECT_NEAR(e.condensed_seconds, 8e6, 1e-9 * 8e6);
  EXPECT_NEAR(e.full_seconds, 2e8, 1e-9 * 2e8);
  EXPECT_EQ(e.path, Path::condensed);
  EXPECT_NE(e.reason.find("condensed is cheaper"), std::string::npos)
    << e.reason;
}



// One body, 1000 face and contact unknowns (a thin body in contact over a
// whole face), a factor of 10^6 entries, 2D (sparse_2d = 1):
//   condensed = (1e9/3 + 1e9 + 1e9) + 10 1e9/3 = 17e9/3,
//   full      = 10 1e6 = 1e7:   full wins. The same factor in 3D costs ten
//   times more on the full path (1e8), still less than the condensed.
TEST(PathCost, FullWinsWithManyPairsOnASmallFactor)
{
  PathCostInputs in;
  in.contact_unknowns      = 1000.;
  in.face_unknowns         = {1000.};
  in.factor_entries        = {1e6};
  in.newton_iterations     = 10.;
  in.dimension             = 2;
  const PathCostEstimate e = estimate_path_costs(in, unit_constants());
  EXPECT_NEAR(e.condensed_seconds, 17e9 / 3., 1e-9 * 17e9 / 3.);
  EXPECT_NEAR(e.full_seconds, 1e7, 1e-9 * 1e7);
  EXPECT_EQ(e.path, Path::full);
  EXPECT_NE(e.reason.find("full is cheaper"), std::string::npos) << e.reason;
  in.dimension = 3;
  EXPECT_NEAR(estimate_path_costs(in, unit_constants()).full_seconds,
              1e8,
              1e-9 * 1e8);
}



// The measured constants on cases they were not fitted on
// (contrib/benchmarks/path-cost --cases b1-24,v6,v7,strip-2000; the
// inputs are each run's contact_path_cost_inputs, the measured whole-run
// seconds of both paths are in doc/performance.md, "Choosing the contact
// path"): B1 NURBS at 24x4x4, V6 and V7 as given, where the condensed path
// was measured faster by factors of 9, 5 and 5, and V3's strips at 2000 x 2
// spans (2D, many pairs on a small factor), where the full path was
// measured faster by a factor of 2. The model must choose the faster path
// on each.
TEST(PathCost, MeasuredConstantsChooseTheFasterPathOnHeldOutCases)
{
  struct Case
  {
    const char    *name;
    PathCostInputs inputs;
    Path           faster;
  };
  const auto inputs = [](const double               m,
                         const std::vector<double> &face,
                         const std::vector<double> &factor,
                         const unsigned int         dimension) {
    PathCostInputs in;
    in.contact_unknowns  = m;
    in.face_unknowns     = face;
    in.factor_entries    = factor;
    in.newton_iterations = 8.;
    in.dimension         = dimension;
    return in;
  };
  const std::vector<Case> cases = {
    {"B1 24x4x4",
     inputs(468., {450., 450.}, {2.35e6, 2.35e6}, 3),
     Path::condensed},
    {"V6", inputs(236., {236., 204.}, {1.13e6, 2.84e6}, 2), Path::condensed},
    {"V7", inputs(484., {1408., 1157.}, {1.68e7, 1.68e7}, 3), Path::condensed},
    {"V3 strips 2000x2",
     inputs(4004., {4003., 4003.}, {4.98e6, 4.98e6}, 2),
     Path::full}};
  for (const Case &c : cases)
    {
      const PathCostEstimate e =
        estimate_path_costs(c.inputs, PathCostConstants::measured());
      EXPECT_EQ(e.path, c.faster) << c.name << ": " << e.reason;
    }
}
