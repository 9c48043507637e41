#ifndef MICHI_VALIDITY_ROBOT_MODEL_
#define MICHI_VALIDITY_ROBOT_MODEL_

#include <michi/validity/scene/Shape.h>

#include <Eigen/Geometry>

#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief Thrown for a URDF that cannot be used; what() names the file. */
        class UrdfError : public std::runtime_error
        {
        public:
            using std::runtime_error::runtime_error;
        };

        /** \brief One collision shape of a link, placed in the link frame. */
        struct LinkCollision
        {
            ShapePtr shape;
            Eigen::Isometry3d origin{Eigen::Isometry3d::Identity()};
        };

        struct RobotLink
        {
            std::string name;
            int parentJoint{-1};  ///< index into joints(), -1 for the root link
            std::vector<LinkCollision> collisions;
        };

        struct RobotJoint
        {
            enum class Type
            {
                REVOLUTE,
                CONTINUOUS,
                PRISMATIC,
                FIXED
            };
            std::string name;
            Type type{Type::FIXED};
            int parentLink{-1};
            int childLink{-1};
            Eigen::Isometry3d origin{Eigen::Isometry3d::Identity()};  ///< child frame in parent frame at q = 0
            Eigen::Vector3d axis{Eigen::Vector3d::UnitZ()};           ///< unit, in the joint frame
            double lower{0.};
            double upper{0.};
            int variable{-1};  ///< index of its value in a configuration vector, -1 for fixed joints
            /** A movable joint with a URDF <mimic>: the joint whose value it follows (value = mimicMultiplier *
                that value + mimicOffset), -1 for none. Its own configuration value is only ever that
                (RobotModel::applyMimic()). */
            int mimic{-1};
            double mimicMultiplier{1.};
            double mimicOffset{0.};

            bool movable() const
            {
                return type != Type::FIXED;
            }
        };

        /** \brief A kinematic tree loaded from URDF (urdfdom): revolute, continuous, prismatic and fixed joints,
            joint limits, collision shapes (box, cylinder, sphere, mesh through assimp). Forward kinematics of
            every link and the geometric Jacobian of any point on any link (Eigen). The model is immutable after
            loading except for the base pose and the allowed-collision list; its const methods are thread-safe. */
        class RobotModel
        {
        public:
            /** \brief Load a URDF file; mesh file names are resolved relative to the file (package:// URIs
                relative to the parent of the package directory when it exists, else to the file). */
            static std::shared_ptr<RobotModel> fromUrdfFile(const std::string &path);
            /** \brief Load a URDF document; \e source names it in errors, \e baseDir resolves meshes. */
            static std::shared_ptr<RobotModel> fromUrdfString(const std::string &xml, const std::string &source,
                                                              const std::string &baseDir);

            const std::string &name() const
            {
                return name_;
            }
            const std::string &source() const
            {
                return source_;
            }
            const std::vector<RobotLink> &links() const
            {
                return links_;
            }
            const std::vector<RobotJoint> &joints() const
            {
                return joints_;
            }
            /** \brief Number of values in a configuration (movable joints, in URDF tree order). */
            std::size_t variableCount() const
            {
                return variableJoints_.size();
            }
            /** \brief The movable joint that owns configuration value \e variable. */
            const RobotJoint &variableJoint(std::size_t variable) const
            {
                return joints_[variableJoints_[variable]];
            }
            std::vector<std::string> variableNames() const;
            /** \brief Index of a link / joint / variable by name; throws std::out_of_range naming it. */
            int linkIndex(const std::string &name) const;
            int jointIndex(const std::string &name) const;
            int variableIndex(const std::string &jointName) const;

            /** \brief Pose of the root link in the world. */
            const Eigen::Isometry3d &basePose() const
            {
                return basePose_;
            }
            void setBasePose(const Eigen::Isometry3d &pose)
            {
                basePose_ = pose;
            }

            /** \brief Set the value of every mimic joint (RobotJoint::mimic) in the configuration \e q
                (variableCount() values) from the joint it follows. */
            void applyMimic(double *q) const;
            void applyMimic(std::vector<double> &q) const
            {
                applyMimic(q.data());
            }
            /** \brief The mimic joint tied to configuration value \e variable: its own joint when that is a mimic
                joint, else a mimic joint that follows it; null for none. Such a value cannot be planned: the mimic's
                links would move where neither applyMimic() on fixed values nor the displacement bounds follow. */
            const RobotJoint *mimicTiedTo(std::size_t variable) const;
            /** \brief World pose of every link for configuration \e q (variableCount() values). */
            void forwardKinematics(const double *q, std::vector<Eigen::Isometry3d> &linkPoses) const;
            std::vector<Eigen::Isometry3d> forwardKinematics(const std::vector<double> &q) const;

            /** \brief Geometric Jacobian (rows: linear velocity of the point, then angular velocity, both in the
                world frame) of the point \e pointInLink fixed to link \e link, with one column per configuration
                value (zero for joints not between the root and the link). */
            Eigen::MatrixXd jacobian(const std::vector<double> &q, int link,
                                     const Eigen::Vector3d &pointInLink = Eigen::Vector3d::Zero()) const;

            /** \brief Joints on the path from the root to \e link, root first. */
            std::vector<int> chainTo(int link) const;

            /** \brief Link pairs checked for self-collision: all pairs of links with collision geometry, except
                links joined by one joint (adjacent), links that are adjacent through fixed joints only, and the
                allowed pairs. */
            std::vector<std::pair<int, int>> selfCollisionPairs() const;
            /** \brief Never check this pair for self-collision (throws std::out_of_range for unknown links). */
            void allowCollision(const std::string &linkA, const std::string &linkB);
            bool isCollisionAllowed(int linkA, int linkB) const;

            /** \brief Upper bound of how far any point of the collision geometry moved by joint \e variable can
                travel per unit of that joint's motion (metres per radian or per metre), for conservative motion
                checks. */
            double displacementBound(std::size_t variable) const
            {
                return displacementBounds_[variable];
            }
            /** \brief The same bound for the geometry of one link only: 0 when the joint is not above the link. */
            double displacementBound(std::size_t variable, int link) const
            {
                return linkDisplacementBounds_[variable][link];
            }

        private:
            RobotModel() = default;
            void computeDisplacementBounds();
            std::string name_;
            std::string source_;
            std::vector<RobotLink> links_;
            std::vector<RobotJoint> joints_;
            std::vector<int> variableJoints_;
            std::vector<int> jointOrder_;  ///< joints sorted so that a parent comes before its children
            int rootLink_{0};
            Eigen::Isometry3d basePose_{Eigen::Isometry3d::Identity()};
            std::set<std::pair<int, int>> allowed_;
            std::vector<double> displacementBounds_;
            std::vector<std::vector<double>> linkDisplacementBounds_;  ///< [variable][link]
        };

        using RobotModelPtr = std::shared_ptr<RobotModel>;
    }  // namespace validity
}  // namespace michi

#endif
