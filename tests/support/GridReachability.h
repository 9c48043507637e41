// Ground truth for planners on 2-D joint spaces: a fine grid search over the whole C-space, and random planar
// arm queries that the grid search proves solvable.
#ifndef MICHI_TESTS_SUPPORT_GRID_REACHABILITY_
#define MICHI_TESTS_SUPPORT_GRID_REACHABILITY_

#include "support/TestScenes.h"

#include <michi/tools/problem/GridReachability.h>

#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/SimpleSetup.h>

#include <cstdint>
#include <vector>

namespace michi
{
    namespace test
    {
        /** \brief Grid search over a 2-D joint space (michi/tools/GridReachability.h). */
        using tools::gridReachable;

        /** \brief A random planar scene (6 random polygons, a 0.5 m + 0.4 m arm) with a start and a goal at
            least 1 rad apart whose straight motion collides and that gridReachable() links at \e step. The space's
            motion validator is the exact ConservativeMotionValidator (for the grid and for planners). */
        struct ArmQuery
        {
            CheckerSetup setup;
            std::vector<double> start;
            std::vector<double> goal;
            bool found{false};  ///< false when no such query was found in 200 tries
        };
        ArmQuery reachableArmQuery(std::uint_fast32_t seed, double step = 0.05);

        /** \brief A SimpleSetup on the query's space information with its start and goal (no planner set yet). */
        ompl::geometric::SimpleSetupPtr armQuerySetup(const ArmQuery &query);
    }  // namespace test
}  // namespace michi

#endif
