#ifndef MICHI_PLANNERS_MANIPULABILITY_
#define MICHI_PLANNERS_MANIPULABILITY_

#include <michi/validity/robot/RobotModel.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief Which rows of the geometric Jacobian enter the manipulability: the hand's linear velocity only
            (3 x n) or linear and angular velocity (6 x n). */
        enum class ManipulabilityRows
        {
            POSITION,
            FULL
        };

        /** \brief Yoshikawa's manipulability w = sqrt(det(J J^T)) of an m x n Jacobian (0 when J J^T is singular).
            Throws std::invalid_argument when m > n or m == 0: an arm with fewer joints than rows is singular
            everywhere, and a silent 0 would make every cell look equally bad (use the position rows instead). */
        double manipulability(const Eigen::MatrixXd &jacobian);

        /** \brief One serial arm of a RobotModel: the movable joints from the root to a tip link, and a tool
            point fixed to that link. Several arms may share one model (a dual-arm robot): every method takes the
            model's full configuration and touches only this arm's values. Thread-safe (const). */
        class ArmChain
        {
        public:
            /** \brief Throws std::out_of_range naming \e tipLink when the model has no such link. */
            ArmChain(validity::RobotModelPtr model, const std::string &tipLink,
                     const Eigen::Vector3d &toolPoint = Eigen::Vector3d::Zero());

            const validity::RobotModelPtr &model() const
            {
                return model_;
            }
            const std::string &tipLinkName() const
            {
                return tipName_;
            }
            int tipLink() const
            {
                return tip_;
            }
            /** \brief Configuration indices of the arm's joints, root first. */
            const std::vector<int> &variables() const
            {
                return variables_;
            }
            std::size_t size() const
            {
                return variables_.size();
            }
            /** \brief Whether configuration index \e variable belongs to this arm. */
            bool owns(int variable) const;

            /** \brief World pose of the tool frame (the tip link's frame moved to the tool point). */
            Eigen::Isometry3d toolPose(const std::vector<double> &q) const;
            /** \brief The geometric Jacobian of the tool point (6 rows: linear, then angular velocity in the
                world frame), one column per arm joint, root first. */
            Eigen::MatrixXd jacobian(const std::vector<double> &q) const;
            /** \brief w = sqrt(det(J J^T)) of the arm at \e q. */
            double manipulability(const std::vector<double> &q, ManipulabilityRows rows) const;

            /** \brief Throws std::invalid_argument naming the tip link when this arm has fewer joints than \e rows
                gives Jacobian rows (3 or 6): its manipulability would be 0 everywhere. */
            void requireRows(ManipulabilityRows rows) const;

            /** \brief A point that stays fixed whatever the arm's joints do (the origin of the last joint whose
                origin no earlier joint moves, e.g. the shoulder of an arm with a vertical first joint; the root
                link's origin when the first joint is prismatic) and an upper bound of the tool point's distance
                from it (the later joints' offsets, each prismatic joint's max(|lower|, |upper|) and the tool
                point's offset): every reachable tool position is inside this sphere. */
            void reachSphere(Eigen::Vector3d &centre, double &radius) const;

            /** \brief Clamp the arm's values of \e q into the joint limits. */
            void clampToLimits(std::vector<double> &q) const;

        private:
            validity::RobotModelPtr model_;
            std::string tipName_;
            int tip_{-1};
            Eigen::Vector3d toolPoint_;
            std::vector<int> variables_;
        };
    }  // namespace planners
}  // namespace michi

#endif
