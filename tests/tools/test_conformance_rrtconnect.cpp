// The conformance suite run on OMPL's own RRTConnect, so the suite itself is tested against a planner that is
// known to behave.
#include "support/PlannerConformance.h"

INSTANTIATE_TEST_SUITE_P(RRTConnect, PlannerConformance,
                         ::testing::Values(michi::test::ConformanceCase{"geometric::RRTConnect", {{"range", "0.5"}}},
                                           michi::test::ConformanceCase{"geometric::PRM", {}, 2.},
                                           michi::test::ConformanceCase{"geometric::KPIECE1", {}}));
