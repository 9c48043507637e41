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

        /** \brief Allocate by name; throws std::invalid_argument listing the known names for an unknown one. */
        ompl::base::PlannerPtr allocatePlanner(const std::string &name, const ompl::base::SpaceInformationPtr &si);

        /** \brief The names, sorted. */
        std::vector<std::string> plannerNames();
    }  // namespace tools
}  // namespace michi

#endif
