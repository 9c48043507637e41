// The conformance suite on michi::ConcentricCircle: in projection mode with the FCL checker, and in J-map mode
// (circles and visibility on the J-map polygons, paths re-checked with the space's motion validator).
#include "support/PlannerConformance.h"

INSTANTIATE_TEST_SUITE_P(ConcentricCircle, PlannerConformance,
                         ::testing::Values(michi::test::ConformanceCase{"michi::ConcentricCircle",
                                                                        {{"divisions", "72"}}},
                                           michi::test::ConformanceCase{
                                               "michi::ConcentricCircle", {{"objective", "clearance"}}, 10., "jmap"}));
