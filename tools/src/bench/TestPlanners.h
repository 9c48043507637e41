#ifndef MICHI_TOOLS_SRC_BENCH_TEST_PLANNERS_
#define MICHI_TOOLS_SRC_BENCH_TEST_PLANNERS_

// Private to michi_tools: planners that misbehave on purpose, so that the tests can check that a campaign survives a
// planner that crashes or hangs (OMPL 1.5.2's BIT* once segfaulted here). Made only through allocatePlanner() when
// MICHI_TEST_PLANNERS=1 (PlannerRegistry.h isTestPlanner()).

#include <ompl/base/Planner.h>

#include <string>

namespace michi
{
    namespace tools
    {
        /** \brief "test::Segfault" (raises SIGSEGV in solve()) or "test::Hang" (never returns from solve()). */
        ompl::base::PlannerPtr allocateTestPlanner(const std::string &name, const ompl::base::SpaceInformationPtr &si);
    }  // namespace tools
}  // namespace michi

#endif
