#ifndef MICHI_PLANNERS_DUAL_ROADMAP_HAND_TASK_MAP_
#define MICHI_PLANNERS_DUAL_ROADMAP_HAND_TASK_MAP_

#include <michi/planners/dual_roadmap/DualRoadmap.h>
#include <michi/validity/robot/CollisionBodies.h>

#include <ompl/base/StateSpace.h>

namespace michi
{
    namespace planners
    {
        /** \brief DualRoadmap's task map (setTaskMap()) for an arm: the hand is the origin of the last body of the
            robot group \e bodies (its tip), its Jacobian RobotModel's (pointJacobian()); states are read as reals of
            \e space (copyToReals, the bodies' configuration). Empty (no task level) when \e bodies is not a
            validity::RobotGroupBodies or has no body. Thread-safe. */
        DualRoadmap::TaskMap handTaskMap(const validity::CollisionBodiesPtr &bodies,
                                         const ompl::base::StateSpacePtr &space);

        /** \brief The bodies of \e checker when it is one of michi's arm checkers (FCL or spheres), else null. */
        validity::CollisionBodiesPtr checkerBodies(const ompl::base::StateValidityCheckerPtr &checker);
    }  // namespace planners
}  // namespace michi

#endif
