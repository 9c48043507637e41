// The conformance suite on michi::PathSeed: with an empty library (RRT-Connect from scratch wins), without the
// race (recall, then RRT-Connect), and with no repair (recall, stitching, or RRT-Connect from scratch).
#include "support/PlannerConformance.h"

INSTANTIATE_TEST_SUITE_P(
    PathSeed, PlannerConformance,
    ::testing::Values(michi::test::ConformanceCase{"michi::PathSeed", {{"range", "0.5"}}},
                      michi::test::ConformanceCase{"michi::PathSeed", {{"race", "0"}, {"variant", "rotation"}}},
                      michi::test::ConformanceCase{"michi::PathSeed", {{"repair", "none"}, {"candidates", "2"}}}));
