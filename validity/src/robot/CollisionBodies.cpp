#include <michi/validity/robot/CollisionBodies.h>

#include <cmath>
#include <stdexcept>

namespace michi
{
    namespace validity
    {
        namespace
        {
            double angleDifference(double a, double b)
            {
                // The short way round: a continuous joint interpolates (SO(2)) through the smaller angle, so that is
                // the motion a bound must cover.
                double d = std::fmod(b - a, 2. * M_PI);
                if (d > M_PI)
                    d -= 2. * M_PI;
                else if (d < -M_PI)
                    d += 2. * M_PI;
                return std::abs(d);
            }
        }  // namespace

        RobotGroupBodies::RobotGroupBodies(RobotModelPtr model, std::vector<int> variables,
                                           std::vector<double> fixedValues)
            : model_(std::move(model)), variables_(std::move(variables)), fixedValues_(std::move(fixedValues))
        {
            if (fixedValues_.size() != model_->variableCount())
                throw std::invalid_argument("fixed configuration has " + std::to_string(fixedValues_.size()) +
                                            " values, robot has " + std::to_string(model_->variableCount()));
            for (int v : variables_)
                if (v < 0 || v >= static_cast<int>(model_->variableCount()))
                    throw std::invalid_argument("group variable index out of range");
            // Mimic joints (URDF <mimic>) follow their joints in the fixed values. A planned joint that is one, or
            // that one follows, would move links that neither these poses nor the displacement bounds follow.
            for (int v : variables_)
                if (const RobotJoint *mimic = model_->mimicTiedTo(static_cast<std::size_t>(v)))
                    throw std::invalid_argument("planned joint '" + model_->variableJoint(v).name +
                                                "' is or drives mimic joint '" + mimic->name + "': not supported");
            model_->applyMimic(fixedValues_);
            std::vector<int> bodyOfLink(model_->links().size(), -1);
            for (std::size_t l = 0; l < model_->links().size(); ++l)
            {
                const auto &link = model_->links()[l];
                // Only links with collision geometry become bodies: FCL has nothing to check for the others, and every
                // per-body loop (poses, distances, bounds) skips them.
                if (link.collisions.empty())
                    continue;
                bodyOfLink[l] = static_cast<int>(bodies_.size());
                bodies_.push_back(Body{link.name, link.collisions});
                bodyLinks_.push_back(static_cast<int>(l));
            }
            for (const auto &p : model_->selfCollisionPairs())
                pairs_.emplace_back(bodyOfLink[p.first], bodyOfLink[p.second]);
        }

        std::vector<double> RobotGroupBodies::fullConfiguration(const double *values) const
        {
            // Joints outside the planned group keep their fixed values (e.g. the other arm, or a mobile base).
            std::vector<double> q = fixedValues_;
            for (std::size_t i = 0; i < variables_.size(); ++i)
                q[variables_[i]] = values[i];
            return q;
        }

        void RobotGroupBodies::bodyPoses(const double *values, std::vector<Eigen::Isometry3d> &poses) const
        {
            const std::vector<double> q = fullConfiguration(values);
            std::vector<Eigen::Isometry3d> links;
            model_->forwardKinematics(q.data(), links);
            poses.resize(bodies_.size());
            for (std::size_t b = 0; b < bodies_.size(); ++b)
                poses[b] = links[bodyLinks_[b]];
        }

        double RobotGroupBodies::displacementBound(const double *from, const double *to) const
        {
            double bound = 0.;
            for (std::size_t i = 0; i < variables_.size(); ++i)
            {
                const auto &joint = model_->variableJoint(variables_[i]);
                const double dq = joint.type == RobotJoint::Type::CONTINUOUS ? angleDifference(from[i], to[i])
                                                                             : std::abs(to[i] - from[i]);
                // No point of the robot moves farther than sum_i (max lever arm of joint i) * |dq_i| (triangle
                // inequality over the chain): a bound for continuous collision checking without sweeping the geometry.
                bound += model_->displacementBound(variables_[i]) * dq;
            }
            return bound;
        }

        void RobotGroupBodies::bodyDisplacementBounds(const double *from, const double *to,
                                                      std::vector<double> &bounds) const
        {
            bounds.assign(bodies_.size(), 0.);
            for (std::size_t i = 0; i < variables_.size(); ++i)
            {
                const auto &joint = model_->variableJoint(variables_[i]);
                const double dq = joint.type == RobotJoint::Type::CONTINUOUS ? angleDifference(from[i], to[i])
                                                                             : std::abs(to[i] - from[i]);
                // The same bound per body, with each joint's lever arm measured to that link only: far tighter for
                // links near the base, which inner joints hardly move.
                for (std::size_t b = 0; b < bodies_.size(); ++b)
                    bounds[b] += model_->displacementBound(variables_[i], bodyLinks_[b]) * dq;
            }
        }

        PlanarRigidBody::PlanarRigidBody(std::vector<Eigen::Vector2d> footprint, double zMin, double zMax)
            : footprint_(std::move(footprint))
        {
            bodies_.push_back(Body{"footprint", {LinkCollision{Shape::prism(footprint_, zMin, zMax)}}});
            // A point at radius r from the body's origin moves at most r * |dyaw| when the body turns.
            for (const auto &p : footprint_)
                circumradius_ = std::max(circumradius_, p.norm());
        }

        void PlanarRigidBody::bodyPoses(const double *values, std::vector<Eigen::Isometry3d> &poses) const
        {
            poses.resize(1);
            poses[0] = Eigen::Isometry3d::Identity();
            poses[0].translation() = Eigen::Vector3d(values[0], values[1], 0.);
            poses[0].linear() = Eigen::AngleAxisd(values[2], Eigen::Vector3d::UnitZ()).toRotationMatrix();
        }

        double PlanarRigidBody::displacementBound(const double *from, const double *to) const
        {
            // Translation plus the farthest footprint point's arc: a bound on any point's motion whatever the
            // interpolation between the two poses does.
            return std::hypot(to[0] - from[0], to[1] - from[1]) + circumradius_ * angleDifference(from[2], to[2]);
        }

        void PlanarRigidBody::bodyDisplacementBounds(const double *from, const double *to,
                                                     std::vector<double> &bounds) const
        {
            bounds.assign(1, displacementBound(from, to));
        }
    }  // namespace validity
}  // namespace michi
