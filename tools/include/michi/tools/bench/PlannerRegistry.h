#ifndef MICHI_TOOLS_PLANNER_REGISTRY_
#define MICHI_TOOLS_PLANNER_REGISTRY_

#include <ompl/base/Planner.h>

#include <map>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief Every planner michi can run, by name: michi's own ("michi::ConcentricCircle", ...) as they
            arrive, and OMPL's geometric planners under MoveIt-style ids ("geometric::RRTConnect", ...). Each
            allocator builds the planner from \e si alone; planners that need a projection use the space's default
            projection, which michi's spaces register. */
        const std::map<std::string, ompl::base::PlannerAllocator> &plannerAllocators();

        /** \brief Throws std::invalid_argument listing the known names unless \e name is one of them (or a test
            planner isTestPlanner() admits): the one check of a planner name, wherever a name comes from. */
        void requirePlannerName(const std::string &name);

        /** \brief Allocate by name; throws std::invalid_argument listing the known names for an unknown one. */
        ompl::base::PlannerPtr allocatePlanner(const std::string &name, const ompl::base::SpaceInformationPtr &si);

        /** \brief The names, sorted (the test planners are not among them). */
        std::vector<std::string> plannerNames();

        /** \brief True for the planners made for testing the tools' crash handling, and only when the environment
            variable MICHI_TEST_PLANNERS is 1: `test::Segfault` raises SIGSEGV in solve(), `test::Hang` sleeps and
            never returns (it ignores its termination condition). allocatePlanner() makes them then; they never
            appear in plannerNames(). */
        bool isTestPlanner(const std::string &name);

        /** \brief A planner's status in words for a message: OMPL 1.5.2's PlannerStatus::asString() calls ABORT (a
            planner that ended its search without a path, as HeadingLattice does when its lattice holds none)
            "Unknown status". */
        std::string statusText(const ompl::base::PlannerStatus &status);
    }  // namespace tools
}  // namespace michi

#endif
