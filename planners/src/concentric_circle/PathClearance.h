// Clearance of ConcentricCircle's paths: measured on the J-map (ranking paths in J-map mode) and raised by moving
// path points away from obstacles (the "clearance" selection). Private to the planner.
#ifndef MICHI_PLANNERS_CONCENTRIC_CIRCLE_PATH_CLEARANCE_
#define MICHI_PLANNERS_CONCENTRIC_CIRCLE_PATH_CLEARANCE_

#include <michi/planners/concentric_circle/CircleMap.h>
#include <michi/validity/jmap/JMapValidityChecker.h>
#include <michi/validity/jmap/PlanarArm.h>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/SpaceInformation.h>

#include <functional>
#include <limits>
#include <memory>
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
            resolution (the "clearance" selection of the J-map mode). The walk stops once the smallest is at or
            below \e floor (the path cannot beat one of that clearance); the value returned is then <= floor. */
        double jmapPathClearance(const ompl::base::SpaceInformation &si, const validity::JMapValidityChecker &checker,
                                 const std::vector<ompl::base::State *> &states, double cap,
                                 double floor = -std::numeric_limits<double>::infinity());

        /** \brief The space's FCL checker: the checker itself, or the FCL checker a J-map checker keeps (same robot and
            scene); null when the checker is neither. */
        const validity::FclValidityChecker *fclOf(const ompl::base::SpaceInformation &si);

        /** \brief Workspace clearance of a planar arm among prisms from its capsule model (validity::PlanarArm):
            the smallest distance from a capsule's centre segment to an obstacle polygon's edge, minus the capsule's
            radius. Every capsule contains its link's shadow, so this is a lower bound of FCL's clearance and at most
            a radius below it (at a link's rounded ends). About a microsecond where FCL's distance takes about a
            hundred (GJK over the link cylinders and obstacle prisms): the push below calls it six times per point
            and step. Only meaningful on states the checker accepts (a segment wholly inside a polygon is not
            detected; such a state is invalid). Immutable, thread-safe. */
        class CapsuleClearance
        {
        public:
            /** \brief The model of the robot checked by the space's checker (FCL, or the FCL checker a J-map
                checker keeps), or null when it is not a planar arm or the scene has no polygons. */
            static std::shared_ptr<const CapsuleClearance> make(const ompl::base::SpaceInformation &si);
            /** \brief The clearance at the group's values (copyToReals order). */
            double at(const double *values) const;

        private:
            CapsuleClearance() = default;
            std::shared_ptr<const validity::PlanarArm> arm_;
            std::vector<int> variables_;                  ///< model configuration index of each group value
            std::vector<double> configuration_;           ///< the model's configuration with the group's values unset
            std::vector<Edge2> edges_;                    ///< every obstacle polygon's edges (outer and inner rings)
            std::vector<Eigen::Vector2d> boxLo_, boxHi_;  ///< each edge's bounding box
        };

        /** \brief When \e states is a single motion (the search linked start and goal directly, as it does when they
            see each other), it is cut into equal pieces of at most \e piece times the space's maximum extent, so
            that pushAwayFromObstacles() has interior states to move: a direct link bends away from the obstacles
            it passes instead of staying where it is. The pieces are checked (states and motions) and the path is
            left whole if one fails. Returns the number of states added. */
        std::size_t splitDirectLink(const ompl::base::SpaceInformationPtr &si, std::vector<ompl::base::State *> &states,
                                    double piece = 0.05);

        /** \brief A clearance to push along: the state's clearance in some measure (larger is safer). */
        using ClearanceFunction = std::function<double(const ompl::base::State *)>;

        /** \brief Paper 000 chooses circle points of low potential, i.e. far from obstacle edges, but a point of a
            circle can only be as far as its circle lets it. This moves every interior state of \e states uphill on
            \e clearance (the checker's clearance() when empty: its workspace distance; a central-difference gradient in
           the first two values, steps of \e step, halved when no state moves), keeping a move only when the state and
           both of its motions pass the space's checker and motion validator; at most \e sweeps passes over the path, or
           until \e ptc. The start and goal stay. Returns the number of moves kept. (The J-map's own distance in the map
           plane was tried as the gradient first: moving along it lowered the workspace clearance, 0.185 -> 0.173 m on
           planar_2link, as joint 1 moves the far links most.) */
        int pushAwayFromObstacles(const ompl::base::SpaceInformationPtr &si, std::vector<ompl::base::State *> &states,
                                  const ompl::base::PlannerTerminationCondition &ptc,
                                  const ClearanceFunction &clearance = {}, int sweeps = 12, double step = 0.04);
    }  // namespace planners
}  // namespace michi

#endif
