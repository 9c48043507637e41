#ifndef MICHI_VALIDITY_SPHERES_SPHERE_KINEMATICS_
#define MICHI_VALIDITY_SPHERES_SPHERE_KINEMATICS_

// Internal to the sphere checker: forward kinematics of only what a state check needs. RobotModel's
// forwardKinematics poses every link through Eigen's AngleAxis and Isometry products, and per state that cost more
// than the sphere tests themselves. Here every fixed transform (fixed joints, joints outside the planned group at
// their template values) is folded into the few frames the group's joints move, and a body is a frame plus a
// constant offset that the checker folds into its sphere centres.

#include <michi/validity/robot/RobotModel.h>

#include <Eigen/Core>

#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief sin and cos of \e x (|x| up to a few thousand radians), accurate to a few units in the last
            place: one reduction by pi/2 and the two minimax polynomials on [-pi/4, pi/4]. Inline: called once per
            joint of every state check, where a call returning through memory cost as much as the polynomials. */
        inline void fastSinCos(double x, double &s, double &c)
        {
            // x = k pi/2 + r with |r| <= pi/4; pi/2 in two parts so that k pi/2 is subtracted without rounding for
            // the joint ranges of real robots.
            constexpr double twoOverPi = 0.636619772367581343076, pio2Hi = 1.57079632673412561417e+00,
                             pio2Lo = 6.07710050650619224932e-11;
            // round to nearest by the 1.5 * 2^52 shifter: inline, where nearbyint() is a library call per joint
            // (exact for |x| below 2^51 pi/2; strict IEEE arithmetic, no -ffast-math, keeps the two additions)
            constexpr double shifter = 6755399441055744.0;
            const double k = (x * twoOverPi + shifter) - shifter;
            const double r = (x - k * pio2Hi) - k * pio2Lo;
            const double z = r * r;
            // minimax polynomials of sin and cos on [-pi/4, pi/4] (the coefficients of the classic fdlibm kernels)
            const double sr =
                r + r * z *
                        (-1.66666666666666324348e-01 +
                         z * (8.33333333332248946124e-03 +
                              z * (-1.98412698298579493134e-04 +
                                   z * (2.75573137070700676789e-06 +
                                        z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)))));
            const double cr =
                1. - 0.5 * z +
                z * z *
                    (4.16666666666666019037e-02 +
                     z * (-1.38888888888741095749e-03 +
                          z * (2.48015872894767294178e-05 +
                               z * (-2.75573143513906633035e-07 +
                                    z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
            switch (static_cast<long>(k) & 3)
            {
                case 0:
                    s = sr;
                    c = cr;
                    break;
                case 1:
                    s = cr;
                    c = -sr;
                    break;
                case 2:
                    s = -sr;
                    c = -cr;
                    break;
                default:
                    s = -cr;
                    c = sr;
            }
        }

        /** \brief A rigid transform as a 3x3 rotation and a translation (double). */
        struct RigidFrame
        {
            Eigen::Matrix3d r{Eigen::Matrix3d::Identity()};
            Eigen::Vector3d t{Eigen::Vector3d::Zero()};
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
            /** \brief Every frame for group values \e values (frame 0: the robot's base pose, read per call).
                \e frames holds frameCount() entries. */
            void frames(const double *values, RigidFrame *frames) const;

        private:
            struct Step
            {
                int parent;         ///< frame the joint hangs from
                RigidFrame offset;  ///< joint origin in that frame
                Eigen::Vector3d axis;
                bool prismatic;
                int value;     ///< group index of its value
                double zSign;  ///< axis +z: 1, -z: -1, other: 0 (general rotation)
            };
            const RobotModel &model_;
            std::vector<Step> steps_;  ///< frame s + 1 is made by step s; parents come first
            std::vector<int> linkFrame_;
            std::vector<RigidFrame> linkOffset_;
        };
    }  // namespace validity
}  // namespace michi

#endif
