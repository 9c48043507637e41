// The conformance suite on DualRoadmap (paper 002): with its learning roadmap, and in the ablation without it.
#include "support/PlannerConformance.h"

INSTANTIATE_TEST_SUITE_P(DualRoadmap, PlannerConformance,
                         ::testing::Values(michi::test::ConformanceCase{"michi::DualRoadmap", {}},
                                           michi::test::ConformanceCase{"michi::DualRoadmap",
                                                                        {{"use_learning", "0"}, {"smooth", "0"}}}));
