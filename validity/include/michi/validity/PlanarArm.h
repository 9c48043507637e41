#ifndef MICHI_VALIDITY_PLANAR_ARM_
#define MICHI_VALIDITY_PLANAR_ARM_

#include <michi/validity/Polygon2.h>
#include <michi/validity/RobotModel.h>

#include <Eigen/Geometry>

#include <memory>
#include <string>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief A 2-D capsule: the points within \e radius of the segment [a, b] (a == b: a disk). */
        struct Capsule2
        {
            Eigen::Vector2d a{Eigen::Vector2d::Zero()};
            Eigen::Vector2d b{Eigen::Vector2d::Zero()};
            double radius{0.};
        };

        /** \brief The x-y view of a URDF arm whose movable joints all rotate about z (axis +z or -z), for the
            exact J-map: every collision shape becomes a capsule in its link's frame that contains the shape's
            shadow on the x-y plane.

            Shapes -> capsules (conservative: each capsule contains the shape's shadow):
            - a cylinder or capsule lying in the plane (axis in x-y): the segment of its axis (length of the
              cylinder), radius = its radius. The shadow of such a cylinder is a rectangle length x 2 radius;
              the capsule of the same segment and radius contains it (it adds the two half-disks at the ends,
              at most radius beyond the rectangle), so the capsule model never misses a collision FCL finds
              and is at most radius too cautious at the link ends;
            - a box whose z axis stays vertical: the segment through its centre along its longer in-plane side,
              of that side's length, radius = half the shorter side (the rectangle lies within that capsule);
            - an upright cylinder or capsule, a sphere: a disk (a == b) of its radius;
            - anything else (meshes, tilted shapes): a disk of the shape's bounding radius about its origin.

            Joint origins may carry a rotation about z (their x-y translation is used; z is ignored because the
            obstacles are prisms straddling the plane, see Scene::polygons2d()). Prismatic joints and joints about
            other axes are rejected (std::invalid_argument naming the joint). Immutable, thread-safe. */
        class PlanarArm
        {
        public:
            /** \brief One link of the chain, in tree order (root first). */
            struct Link
            {
                std::string name;
                int modelLink{-1};  ///< index in RobotModel::links()
                int joint{-1};      ///< index into joints() of the joint that moves it; -1 for the root
                std::vector<Capsule2> capsules;  ///< in the link frame
            };
            /** \brief One joint (movable or fixed): the child frame relative to the parent link at q = 0. */
            struct Joint
            {
                std::string name;
                int parentLink{-1};  ///< index into links()
                int childLink{-1};   ///< index into links()
                Eigen::Vector2d origin{Eigen::Vector2d::Zero()};
                double originAngle{0.};  ///< rotation of the child frame about z at q = 0
                double axisSign{1.};     ///< +1 for axis +z, -1 for -z
                int variable{-1};        ///< configuration index, -1 for a fixed joint
                double lower{0.};
                double upper{0.};
            };

            /** \brief Build from \e model; throws std::invalid_argument naming the joint when a movable joint
                does not rotate about z. The base pose's x-y translation and yaw are applied. */
            static std::shared_ptr<const PlanarArm> fromModel(const RobotModel &model);

            const std::vector<Link> &links() const
            {
                return links_;
            }
            const std::vector<Joint> &joints() const
            {
                return joints_;
            }
            std::size_t variableCount() const
            {
                return variableCount_;
            }
            /** \brief Index into joints() of configuration value \e variable. */
            int variableJoint(int variable) const
            {
                return variableJoints_[variable];
            }
            /** \brief Joint limits of configuration value \e variable. */
            double lower(int variable) const
            {
                return joints_[variableJoints_[variable]].lower;
            }
            double upper(int variable) const
            {
                return joints_[variableJoints_[variable]].upper;
            }

            /** \brief World frame (2-D rigid transform) of every link for configuration \e q (variableCount()). */
            std::vector<Eigen::Isometry2d> linkFrames(const double *q) const;
            /** \brief Every capsule in the world frame for configuration \e q; \e owner gets each one's link. */
            std::vector<Capsule2> worldCapsules(const double *q, std::vector<int> *owner = nullptr) const;
            /** \brief True when link \e link is moved by configuration value \e variable (it lies below that
                joint in the tree). */
            bool moves(int variable, int link) const;
            /** \brief Upper bound, over all configurations, of the distance from joint \e variable's axis to any
                point of the centre segments of link \e link's capsules (0 when the joint does not move it).
                A rotation of that joint by an angle a then moves every capsule by at most 2 rho sin(a/2). */
            double reachFrom(int variable, int link) const;

            /** \brief The paper's link lengths along the chain, one per movable joint: distance from the joint
                to the next movable joint's origin; for the last joint, the farthest extent of the collision
                geometry of the links it moves (capsule end point plus radius) from its axis. */
            std::vector<double> linkLengths() const;

        private:
            PlanarArm() = default;
            std::vector<Link> links_;
            std::vector<Joint> joints_;
            std::vector<int> order_;  ///< joints, parents first
            std::vector<int> variableJoints_;
            std::size_t variableCount_{0};
            int rootLink_{0};
            Eigen::Isometry2d base_{Eigen::Isometry2d::Identity()};
            std::vector<std::vector<double>> reach_;  ///< [variable][link]
        };

        using PlanarArmPtr = std::shared_ptr<const PlanarArm>;

        /** \brief Distance between a capsule's centre segment and obstacle polygons (0 when they intersect or
            the segment lies inside); the capsule collides when this is <= its radius. */
        double segmentDistance(const Eigen::Vector2d &a, const Eigen::Vector2d &b, const MultiPolygon2 &obstacles);
    }
}

#endif
