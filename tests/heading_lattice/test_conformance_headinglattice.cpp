// The conformance suite on michi::HeadingLattice, on the SE(2) conformance problem (a rectangle in
// TurnMoveTurnStateSpace), with OMPL's RRTConnect on the same problem as the suite's reference.
#include "support/PlannerConformance.h"

INSTANTIATE_TEST_SUITE_P(
    HeadingLattice, PlannerConformance,
    ::testing::Values(
        michi::test::ConformanceCase{"michi::HeadingLattice", {{"cell_size", "0.1"}}, 10., "fcl", "se2"},
        michi::test::ConformanceCase{
            "michi::HeadingLattice", {{"cell_size", "0.2"}, {"angle_step", "0.7853981633974483"}}, 10., "fcl", "se2"},
        michi::test::ConformanceCase{"geometric::RRTConnect", {}, 10., "fcl", "se2"}));
