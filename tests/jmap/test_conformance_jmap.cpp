// The conformance suite with the J-map validity checker (paper 000) in place of FCL: planners behave the same and
// their solutions pass the independent Boost.Geometry re-check, so the conservative J-map never lets a colliding
// state through.
#include "support/PlannerConformance.h"

INSTANTIATE_TEST_SUITE_P(JMapChecker, PlannerConformance,
                         ::testing::Values(michi::test::ConformanceCase{"geometric::RRTConnect", {}, 10., "jmap"},
                                           michi::test::ConformanceCase{"geometric::PRM", {}, 2., "jmap"}));
