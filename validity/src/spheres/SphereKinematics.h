#ifndef MICHI_VALIDITY_SPHERES_SPHERE_KINEMATICS_
#define MICHI_VALIDITY_SPHERES_SPHERE_KINEMATICS_

// Internal to the sphere checker: forward kinematics of only what a state check needs. RobotModel's
// forwardKinematics poses every link through Eigen's AngleAxis and Isometry products, and per state that cost more
// than the sphere tests themselves. Here every fixed transform (fixed joints, joints outside the planned group at
// their template values) is folded into the few frames the group's joints move, and a body is a frame plus a
// constant offset that the checker folds into its sphere centres.

#include "../FastSinCos.h"

#include <michi/validity/robot/RobotModel.h>

#include <Eigen/Core>

#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief A rigid transform as a 3x3 rotation and a translation (double). */
        struct RigidFrame
        {
            Eigen::Matrix3d r{Eigen::Matrix3d::Identity()};
            Eigen::Vector3d t{Eigen::Vector3d::Zero()};
        };

        /** \brief The same transform in floats, each column of the rotation and the translation in a 4-lane
            array (the last lane 0): a product of two frames is then 9 multiply-adds of whole SIMD registers. */
        struct FloatFrame
        {
            Eigen::Array4f c0{Eigen::Array4f::Zero()}, c1{Eigen::Array4f::Zero()}, c2{Eigen::Array4f::Zero()},
                t{Eigen::Array4f::Zero()};
        };

        class SphereKinematics
        {
        public:
            /** \param variables the group's variable indices (as RobotGroupBodies::variables())
                \param fullTemplate a whole configuration: joints outside the group keep these values
                \param links the links whose poses are asked for */
            SphereKinematics(const RobotModel &model, const std::vector<int> &variables,
                             const std::vector<double> &fullTemplate, const std::vector<int> &links);

            std::size_t frameCount() const
            {
                return steps_.size() + 1;
            }
            /** \brief Frame that link links[i] rides on, and its constant pose in that frame. */
            int frameOf(std::size_t i) const
            {
                return linkFrame_[i];
            }
            const RigidFrame &offsetOf(std::size_t i) const
            {
                return linkOffset_[i];
            }
            /** \brief Every frame for group values \e values (frame 0: the robot's base pose, read per call), in
                floats (the sphere checker's centres are floats; a metre-long arm's frames are within a few 1e-7 of
                RobotModel's double forward kinematics). \e frames holds frameCount() entries. */
            void framesFloat(const double *values, FloatFrame *frames) const;

        private:
            struct Step
            {
                int parent;  ///< frame the joint hangs from
                Eigen::Vector3d axis;
                bool prismatic;
                int value;     ///< group index of its value
                double zSign;  ///< axis +z: 1, -z: -1, other: 0 (general rotation)
                // the joint origin in the parent frame: its rotation's (i, j) in every lane at [3 j + i], its
                // translation's i in every lane, and the axis in the parent's frame (a prismatic joint's direction)
                Eigen::Array4f rotation[9];
                Eigen::Array4f translation[3];
                Eigen::Vector3f slide;
            };
            const RobotModel &model_;
            std::size_t dimension_;    ///< group values
            std::vector<Step> steps_;  ///< frame s + 1 is made by step s; parents come first
            std::vector<int> linkFrame_;
            std::vector<RigidFrame> linkOffset_;
        };
    }  // namespace validity
}  // namespace michi

#endif
