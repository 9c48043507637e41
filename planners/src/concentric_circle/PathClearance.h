// Clearance of ConcentricCircle's paths: measured on the J-map (ranking paths in J-map mode) and raised by moving
// path points away from obstacles (the "clearance" selection). Private to the planner.
#ifndef MICHI_PLANNERS_CONCENTRIC_CIRCLE_PATH_CLEARANCE_
#define MICHI_PLANNERS_CONCENTRIC_CIRCLE_PATH_CLEARANCE_

#include <michi/validity/jmap/JMapValidityChecker.h>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/SpaceInformation.h>

#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief Distance (radians, in the map plane) from a state of a two-value space to the J-map polygons,
            capped at \e cap: the clearance the method's potential stands for, at the cost of a slab walk (the
            checker's clearance() is a workspace FCL distance, a hundred times dearer). */
        double jmapClearance(const ompl::base::SpaceInformation &si, const validity::JMapValidityChecker &checker,
                             const ompl::base::State *state, double cap);

        /** \brief The smallest jmapClearance() along a path, its segments sampled at the space's validity
            resolution (the "clearance" selection of the J-map mode). */
        double jmapPathClearance(const ompl::base::SpaceInformation &si, const validity::JMapValidityChecker &checker,
                                 const std::vector<ompl::base::State *> &states, double cap);

        /** \brief Paper 000 chooses circle points of low potential, i.e. far from obstacle edges, but a point of a
            circle can only be as far as its circle lets it. This moves every interior state of \e states uphill on
            the space's clearance() (the checker's workspace distance; a central-difference gradient in the first
            two values, steps of \e step, halved when no state moves), keeping a move only when the state and both
            of its motions pass the space's checker and motion validator; at most \e sweeps passes over the path,
            or until \e ptc. The start and goal stay. Returns the number of moves kept.
            (The J-map's own distance in the map plane was tried as the gradient first: moving along it lowered the
            workspace clearance, 0.185 -> 0.173 m on planar_2link, as joint 1 moves the far links most.) */
        int pushAwayFromObstacles(const ompl::base::SpaceInformationPtr &si, std::vector<ompl::base::State *> &states,
                                  const ompl::base::PlannerTerminationCondition &ptc, int sweeps = 12,
                                  double step = 0.04);
    }  // namespace planners
}  // namespace michi

#endif
