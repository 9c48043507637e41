#ifndef MICHI_PLANNERS_DUAL_ROADMAP_PATH_DEFORMATION_
#define MICHI_PLANNERS_DUAL_ROADMAP_PATH_DEFORMATION_

#include <michi/planners/dual_roadmap/NonStopExecutor.h>
#include <michi/validity/robot/CollisionBodies.h>
#include <michi/validity/fcl/FclValidityChecker.h>

#include <Eigen/Core>

#include <functional>

namespace michi
{
    namespace planners
    {
        /** \brief Settings of deformPath(). */
        struct DeformationSettings
        {
            double startDistance{0.3};  ///< d_i: points of the robot closer than this to an obstacle are pushed away
            double spacing{0.1};        ///< waypoints are this far apart (state space distance) in the window
            double window{2.};          ///< path length (from the robot) that is deformed; the rest is kept
            unsigned int iterations{15};
            double maxStep{0.1};  ///< largest change of one waypoint per iteration (state space distance)
            int spread{3};        ///< a waypoint's change is passed on, fading, to this many neighbours each side
        };

        /** \brief 3 x n Jacobian of the world point \e point fixed to body \e body for configuration \e values (the
            state's reals): analytic for validity::RobotGroupBodies (RobotModel::jacobian, the group's columns) and
            validity::PlanarRigidBody (x, y, yaw), by finite differences of bodyPoses() for other bodies. */
        Eigen::MatrixXd pointJacobian(const validity::CollisionBodies &bodies, const double *values, int body,
                                      const Eigen::Vector3d &point);

        /** \brief Path deformation of paper 002 (temporal adaptation): along the first \e window of \e path (which
            starts at the robot, kept fixed), every waypoint whose nearest robot point P is closer than d_i to an
            obstacle point Q (FCL, \e checker's scene) is moved so that P moves away along n = (P - Q) / |P - Q|
            by d_i - d: dq = J^T n * (d_i - d) / |J^T n|^2 (Jacobian transpose, no inverse); the change fades out
            over neighbouring waypoints so the path stays smooth. Repeated \e iterations times. Returns false (and
            leaves \e path alone) when a waypoint is in collision (no direction), or when \e accept rejects the
            deformed path (it should check it against the world). \e interpolate is the state space's. */
        bool deformPath(ConfigurationPath &path, const validity::FclValidityChecker &checker,
                        const std::function<double(const Configuration &, const Configuration &)> &distance,
                        const std::function<void(const Configuration &, const Configuration &, double, Configuration &)>
                            &interpolate,
                        const std::function<bool(const ConfigurationPath &)> &accept,
                        const DeformationSettings &settings);
    }  // namespace planners
}  // namespace michi

#endif
