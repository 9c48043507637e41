#ifndef MICHI_VALIDITY_PLANAR_ARM_
#define MICHI_VALIDITY_PLANAR_ARM_

#include <michi/validity/scene/Polygon2.h>
#include <michi/validity/robot/RobotModel.h>

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

            Shapes -> capsules (conservative: each capsule contains the shape's shadow, for any orientation):
            - a cylinder (or capsule) of radius r: the segment of its axis projected on the plane, radius r. For a
              cylinder lying in the plane (a link) the shadow is a rectangle length x 2r and the capsule adds the
              two half-disks at its ends (at most r beyond the rectangle): the capsule model never misses a
              collision FCL finds and is at most r too cautious at the link ends. Tilted axes: the end disks'
              shadows are ellipses within r of the projected axis. Upright: a disk of radius r;
            - a box: the segment of its longest projected edge through the centre, radius = the sum of the other
              two projected half edges (exact for a box whose z axis stays vertical: its rectangle);
            - a sphere: a disk; meshes and prisms: a disk of the shape's bounding radius about its origin.

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
                int modelLink{-1};               ///< index in RobotModel::links()
                int joint{-1};                   ///< index into joints() of the joint that moves it; -1 for the root
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
            /** \brief The same into \e frames (no allocation once it has grown). */
            void linkFrames(const double *q, std::vector<Eigen::Isometry2d> &frames) const;
            /** \brief Every capsule in the world frame for configuration \e q; \e owner gets each one's link. */
            std::vector<Capsule2> worldCapsules(const double *q, std::vector<int> *owner = nullptr) const;
            /** \brief The same into \e out, with \e frames as scratch: no allocation once both have grown (hot
                loops, e.g. a clearance gradient). */
            void worldCapsules(const double *q, std::vector<Capsule2> &out,
                               std::vector<Eigen::Isometry2d> &frames) const;
            /** \brief True when link \e link is moved by configuration value \e variable (it lies below that
                joint in the tree). */
            bool moves(int variable, int link) const;
            /** \brief Upper bound, over all configurations, of the distance from joint \e variable's axis to any
                point of the centre segments of link \e link's capsules (0 when the joint does not move it).
                A rotation of that joint by an angle a then moves every capsule by at most 2 rho sin(a/2). */
            double reachFrom(int variable, int link) const;

            /** \brief The paper's link lengths along the chain, one per movable joint: distance from the joint
                to the next movable joint's origin; for the last joint, the farthest extent along the links
                it moves of their collision geometry (the farthest capsule segment end) from its axis. */
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
    }  // namespace validity
}  // namespace michi

#endif
