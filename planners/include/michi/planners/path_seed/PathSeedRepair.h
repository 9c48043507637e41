#ifndef MICHI_PLANNERS_PATH_SEED_REPAIR_
#define MICHI_PLANNERS_PATH_SEED_REPAIR_

#include <michi/planners/path_seed/CheckThreads.h>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/PathGeometric.h>

#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief Check a path (states and the straight motions between them) and stop at the first failure.
            Order, for failing fast: every state first (bounds and validity), then the motions. With michi's
            WorkspaceMotionValidator the motions' intermediate states are checked round-robin over all segments
            in bisection order (first every segment's midpoint, then the quarters, ...): exactly the states the
            validator itself would check, so a path that passes also passes PathGeometric::check(). With any
            other motion validator the segments go to SpaceInformation::checkMotion one by one. Returns false
            when \e ptc fires before the check is complete. \e checks (if given) counts the state checks. With
            \e threads > 1 the motions' states (in the same order) are shared out among that many threads, which stop
            at the first invalid state (the validity checker must be thread-safe, as michi's FCL checker is); with
            \e pool (at least threads - 1 helpers) its threads do that share instead of threads started per call. */
        bool checkPathFailFast(const ompl::base::SpaceInformationPtr &si, const ompl::geometric::PathGeometric &path,
                               const ompl::base::PlannerTerminationCondition &ptc, unsigned long *checks = nullptr,
                               unsigned int threads = 1, CheckThreads *pool = nullptr);

        /** \brief Where a path is invalid: state i (bounds or collision), segment i (from state i to i + 1). */
        struct PathValidity
        {
            std::vector<char> state;
            std::vector<char> segment;
            std::size_t invalidStates() const;
            std::size_t invalidSegments() const;
        };

        /** \brief Every state and every segment checked (segments only where both ends are valid). */
        PathValidity checkPathFull(const ompl::base::SpaceInformationPtr &si,
                                   const ompl::geometric::PathGeometric &path,
                                   const ompl::base::PlannerTerminationCondition &ptc);

        /** \brief Repair the invalid stretches of \e path: between the nearest valid waypoints around each
            stretch, first the straight motion is tried, then RRT-Connect (\e range: its step, 0 for OMPL's
            default) plans a detour; then the path is shortcut (OMPL's PathSimplifier::shortcutPath, at most
            \e shortcutSteps attempts; 0 leaves it as it is). The first and last states must be valid. Returns true
            with a valid path, false (path unspecified) when a stretch cannot be repaired before \e ptc. */
        bool repairWithRRTConnect(const ompl::base::SpaceInformationPtr &si, ompl::geometric::PathGeometric &path,
                                  const ompl::base::PlannerTerminationCondition &ptc, double range = 0.,
                                  unsigned int shortcutSteps = 20);

        /** \brief Stitch decoded paths that share start and goal into one valid path, lazily (as LazyPRM does): the
            paths' states are the vertices of a graph (start and goal shared), their segments its edges, and every
            state is also joined to its \e neighbours nearest states of the other paths. The shortest start-goal
            path in the graph (Boost.Graph's Dijkstra, joint-space length) has its unchecked states checked, then
            its unchecked edges (checkPathFailFast order); what is invalid leaves the graph and the search repeats,
            until a path checks valid (true, in \e out) or start and goal are disconnected or \e ptc fires
            (false). A valid path costs its own check; an invalid one usually a few state checks. */
        bool stitchPaths(const ompl::base::SpaceInformationPtr &si,
                         const std::vector<ompl::geometric::PathGeometric> &paths,
                         const ompl::base::PlannerTerminationCondition &ptc, ompl::geometric::PathGeometric &out,
                         unsigned int neighbours = 3, unsigned long *checks = nullptr, unsigned int threads = 1,
                         CheckThreads *pool = nullptr);
    }  // namespace planners
}  // namespace michi

#endif
