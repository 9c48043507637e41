#ifndef MICHI_PLANNERS_HAND_IK_
#define MICHI_PLANNERS_HAND_IK_

#include <michi/planners/dual_arm/Manipulability.h>

#include <Eigen/Core>

#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief A hand position with a constraint on one axis of the tool frame (the hand's approach axis):
            either the axis points along a world direction (2 constraints: "hand pointing down"), or it is
            perpendicular to a world direction (1 constraint: "hand horizontal" is perpendicular to z). Rotation
            about the axis is left free. */
        struct HandTarget
        {
            enum class Mode
            {
                AXIS_ALONG,         ///< toolAxis (in the world) == direction
                AXIS_PERPENDICULAR  ///< toolAxis (in the world) . direction == 0
            };
            Eigen::Vector3d position{Eigen::Vector3d::Zero()};
            Mode mode{Mode::AXIS_ALONG};
            Eigen::Vector3d toolAxis{Eigen::Vector3d::UnitZ()};    ///< in the tool frame
            Eigen::Vector3d direction{-Eigen::Vector3d::UnitZ()};  ///< in the world, unit

            /** \brief Position error (metres) and axis error (radians) of a tool pose. */
            void errors(const Eigen::Isometry3d &tool, double &position, double &angle) const;
        };

        struct HandIkSettings
        {
            unsigned int maxIterations{60};
            double positionTolerance{1e-4};  ///< metres
            double angleTolerance{1e-3};     ///< radians
            double damping{0.02};            ///< damped least squares lambda
            double maxStep{0.3};             ///< largest joint change per iteration (radians)
            double angleWeight{0.2};         ///< metres per radian: how axis errors weigh against position errors
            /** \brief Give up when the weighted error has not halved over this many iterations (0: never). */
            unsigned int stallIterations{12};
        };

        /** \brief Damped-least-squares inverse kinematics of an ArmChain for a HandTarget, from the arm's values
            in \e q (the seed; other values of \e q stay as they are). Joint limits are enforced by clamping after
            every step. Returns true with \e q solved when both tolerances are met. Deterministic. */
        bool solveHandIk(const ArmChain &arm, const HandTarget &target, std::vector<double> &q,
                         const HandIkSettings &settings = HandIkSettings());
    }  // namespace planners
}  // namespace michi

#endif
