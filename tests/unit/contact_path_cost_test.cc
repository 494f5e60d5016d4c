// The cost model of Contact/Path = auto (contact/path_cost.h) on inputs
// whose costs are computed by hand: each path wins once.

#include <igabde/contact/path_cost.h>

#include <gtest/gtest.h>

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
    c.sparse              = 1.;
    c.iterations_per_step = 10.;
    return c;
  }
} // namespace



// Two bodies with 100 face unknowns each, 100 contact unknowns, factors of
// 10^4 entries, 10 Newton iterations:
//   condensed = 2 (100^3/3 + 100^2 100 + 100 100^2) + 10 100^3/3
//             = 2 (1e6/3 + 2e6) + 1e7/3 = 8e6,
//   full      = 10 (2 (1e4)^1.5) = 2e7:   condensed wins.
TEST(PathCost, CondensedWinsWithFewPairsOnLargeFactors)
{
  PathCostInputs in;
  in.contact_unknowns      = 100.;
  in.face_unknowns         = {100., 100.};
  in.factor_entries        = {1e4, 1e4};
  in.newton_iterations     = 10.;
  const PathCostEstimate e = estimate_path_costs(in, unit_constants());
  EXPECT_NEAR(e.condensed_seconds, 8e6, 1e-9 * 8e6);
  EXPECT_NEAR(e.full_seconds, 2e7, 1e-9 * 2e7);
  EXPECT_EQ(e.path, Path::condensed);
  EXPECT_NE(e.reason.find("condensed is cheaper"), std::string::npos)
    << e.reason;
}



// One body, 1000 face and contact unknowns (a thin body in contact over a
// whole face), a factor of 10^4 entries:
//   condensed = (1e9/3 + 1e9 + 1e9) + 10 1e9/3 = 17e9/3,
//   full      = 10 (1e4)^1.5 = 1e7:   full wins.
TEST(PathCost, FullWinsWithManyPairsOnASmallFactor)
{
  PathCostInputs in;
  in.contact_unknowns      = 1000.;
  in.face_unknowns         = {1000.};
  in.factor_entries        = {1e4};
  in.newton_iterations     = 10.;
  const PathCostEstimate e = estimate_path_costs(in, unit_constants());
  EXPECT_NEAR(e.condensed_seconds, 17e9 / 3., 1e-9 * 17e9 / 3.);
  EXPECT_NEAR(e.full_seconds, 1e7, 1e-9 * 1e7);
  EXPECT_EQ(e.path, Path::full);
  EXPECT_NE(e.reason.find("full is cheaper"), std::string::npos) << e.reason;
}



// The measured constants, fitted on B2 FE_Q(2) at 8x32x8, on a case they
// were not fitted to: B2 NURBS at 8x16x8 (510 contact unknowns, 510 face
// unknowns per beam, estimated factors of 7.9e6 entries per beam, 9 Newton
// iterations), where the condensed path took 1.25 s against 9.39 s for the
// full path (doc/performance.md, 2026-11-23).
TEST(PathCost, MeasuredConstantsChooseCondensedForHeldOutB2NurbsAt8x16x8)
{
  PathCostInputs in;
  in.contact_unknowns  = 510.;
  in.face_unknowns     = {510., 510.};
  in.factor_entries    = {7.9e6, 7.9e6};
  in.newton_iterations = 9.;
  const PathCostEstimate e =
    estimate_path_costs(in, PathCostConstants::measured());
  EXPECT_EQ(e.path, Path::condensed) << e.reason;
}
