#include <michi/planners/dual_arm/Manipulability.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace michi
{
    namespace planners
    {
        double manipulability(const Eigen::MatrixXd &jacobian)
        {
            if (jacobian.rows() == 0 || jacobian.rows() > jacobian.cols())
                throw std::invalid_argument("manipulability of a " + std::to_string(jacobian.rows()) + " x " +
                                            std::to_string(jacobian.cols()) +
                                            " Jacobian: needs at least as many joints as rows (it would be 0 "
                                            "everywhere); use the position rows for an arm with fewer than 6 joints");
            // Yoshikawa's measure w = sqrt(det(J J^T)) (paper 004). Rounding can make det slightly negative at a
            // singularity: that is w = 0, not a NaN.
            const double d = (jacobian * jacobian.transpose()).determinant();
            return d > 0. ? std::sqrt(d) : 0.;
        }

        ArmChain::ArmChain(validity::RobotModelPtr model, const std::string &tipLink, const Eigen::Vector3d &toolPoint)
            : model_(std::move(model)), tipName_(tipLink), toolPoint_(toolPoint)
        {
            tip_ = model_->linkIndex(tipLink);
            for (int j : model_->chainTo(tip_))
                if (model_->joints()[j].movable())
                    variables_.push_back(model_->joints()[j].variable);
        }

        bool ArmChain::owns(int variable) const
        {
            return std::find(variables_.begin(), variables_.end(), variable) != variables_.end();
        }

        Eigen::Isometry3d ArmChain::toolPose(const std::vector<double> &q) const
        {
            std::vector<Eigen::Isometry3d> poses;
            model_->forwardKinematics(q.data(), poses);
            Eigen::Isometry3d pose = poses[tip_];
            // The tool point (e.g. a spoon's tip) is fixed in the tip link's frame; the orientation stays the link's.
            pose.translation() = poses[tip_] * toolPoint_;
            return pose;
        }

        Eigen::MatrixXd ArmChain::jacobian(const std::vector<double> &q) const
        {
            const Eigen::MatrixXd full = model_->jacobian(q, tip_, toolPoint_);
            Eigen::MatrixXd jac(6, static_cast<long>(variables_.size()));
            // Only this arm's joints: manipulability and IK concern one arm, the other arm's columns would inflate
            // w.
            for (std::size_t i = 0; i < variables_.size(); ++i)
                jac.col(static_cast<long>(i)) = full.col(variables_[i]);
            return jac;
        }

        double ArmChain::manipulability(const std::vector<double> &q, ManipulabilityRows rows) const
        {
            const Eigen::MatrixXd jac = jacobian(q);
            return planners::manipulability(rows == ManipulabilityRows::POSITION ? Eigen::MatrixXd(jac.topRows(3))
                                                                                 : jac);
        }

        void ArmChain::requireRows(ManipulabilityRows rows) const
        {
            const std::size_t needed = rows == ManipulabilityRows::POSITION ? 3 : 6;
            if (variables_.size() < needed)
                throw std::invalid_argument(
                    "arm to '" + tipName_ + "' has " + std::to_string(variables_.size()) + " joints: its " +
                    std::to_string(needed) + "-row manipulability is 0 in every configuration (use " +
                    (needed == 6 ? std::string("position rows") : std::string("a longer arm")) + ")");
        }

        void ArmChain::clampToLimits(std::vector<double> &q) const
        {
            for (int v : variables_)
            {
                const auto &joint = model_->variableJoint(static_cast<std::size_t>(v));
                // Continuous joints have no limits to clamp to (their lower and upper are not meaningful).
                if (joint.type == validity::RobotJoint::Type::CONTINUOUS)
                    continue;
                q[v] = std::min(std::max(q[v], joint.lower), joint.upper);
            }
        }

        void ArmChain::reachSphere(Eigen::Vector3d &centre, double &radius) const
        {
            const auto chain = model_->chainTo(tip_);
            // configurations that move every arm joint (deterministic, so the sphere is too)
            std::vector<std::vector<double>> probes;
            for (int k = 1; k <= 3; ++k)
            {
                std::vector<double> q(model_->variableCount(), 0.);
                for (std::size_t i = 0; i < variables_.size(); ++i)
                {
                    const auto &joint = model_->variableJoint(static_cast<std::size_t>(variables_[i]));
                    const double lo = joint.type == validity::RobotJoint::Type::CONTINUOUS ? -M_PI : joint.lower;
                    const double hi = joint.type == validity::RobotJoint::Type::CONTINUOUS ? M_PI : joint.upper;
                    // Fractions from incommensurate steps put every joint away from 0 and from its neighbours' values,
                    // so a joint that moves a link origin cannot hide by happening to stay near its zero.
                    q[variables_[i]] = lo + (hi - lo) * std::fmod(0.31 * k + 0.17 * static_cast<double>(i), 1.);
                }
                probes.push_back(q);
            }
            std::vector<Eigen::Isometry3d> zero, moved;
            model_->forwardKinematics(std::vector<double>(model_->variableCount(), 0.).data(), zero);
            // from: the first joint of the chain whose frame origin some joint moves. The joints before it keep their
            // frame origins fixed, so the centre is the origin of that joint's parent link. When no joint is still
            // (a prismatic first joint, e.g. a rail, moves its own child), the centre is the root link's origin and
            // every joint counts: the centre must not be a point that the prismatic joint itself carries along.
            std::size_t from = 0;
            for (std::size_t c = 0; c < chain.size(); ++c)
            {
                const int child = model_->joints()[chain[c]].childLink;
                bool still = true;
                for (const auto &q : probes)
                {
                    model_->forwardKinematics(q.data(), moved);
                    still = still && (moved[child].translation() - zero[child].translation()).norm() < 1e-9;
                }
                if (!still)
                    break;
                from = c + 1;
            }
            centre = zero[from < chain.size() ? model_->joints()[chain[from]].parentLink : tip_].translation();
            // An upper bound on the reach (triangle inequality): from the centre, each later joint moves its child's
            // origin by its offset plus, for a prismatic joint, q along its unit axis (|q| <= max(|lower|, |upper|)),
            // and the tool point is toolPoint_ from the tip's origin. The sphere may be larger than the real work
            // space, never smaller: DualArmWorkspace::compute() skips every cell outside it.
            radius = toolPoint_.norm();
            for (std::size_t c = from; c < chain.size(); ++c)
            {
                const auto &joint = model_->joints()[chain[c]];
                radius += joint.origin.translation().norm();
                if (joint.type == validity::RobotJoint::Type::PRISMATIC)
                    radius += std::max(std::abs(joint.lower), std::abs(joint.upper));
            }
        }
    }  // namespace planners
}  // namespace michi
