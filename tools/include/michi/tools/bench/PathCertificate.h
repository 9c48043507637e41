#ifndef MICHI_TOOLS_PATH_CERTIFICATE_
#define MICHI_TOOLS_PATH_CERTIFICATE_

#include <michi/validity/fcl/FclValidityChecker.h>

#include <ompl/geometric/PathGeometric.h>

#include <string>

namespace michi
{
    namespace tools
    {
        /** \brief What re-checking a returned path found. */
        struct PathCertificate
        {
            bool certified{false};
            std::size_t statesChecked{0};
            std::string reason;  ///< empty when certified: "segment 3 at 0.42: panda_hand touches obstacle 'can'"
        };

        /** \brief Re-check a solution path independently of the checker that planned it: every segment with FCL
            on the real geometry (\e fcl) at states at most \e fraction of the state validity checking resolution
            apart (the default is ten times finer than the planner's checks), bounds included. A fast checker's
            mistakes (a sphere model that misses a part of the robot, a coarse grid) show up here; a path that fails
            is not a solution. */
        PathCertificate certifyPath(const ompl::geometric::PathGeometric &path, const validity::FclValidityChecker &fcl,
                                    double fraction = 0.1);
    }  // namespace tools
}  // namespace michi

#endif
