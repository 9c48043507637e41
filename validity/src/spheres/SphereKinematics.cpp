#include "SphereKinematics.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

namespace michi
{
    namespace validity
    {
        namespace
        {
            RigidFrame compose(const RigidFrame &a, const RigidFrame &b)
            {
                RigidFrame out;
                out.r.noalias() = a.r * b.r;
                out.t.noalias() = a.r * b.t;
                out.t += a.t;
                return out;
            }

            RigidFrame fromIsometry(const Eigen::Isometry3d &pose)
            {
                RigidFrame f;
                f.r = pose.linear();
                f.t = pose.translation();
                return f;
            }

            /** The joint's own motion for value q (URDF: about or along its axis, in the joint frame). */
            RigidFrame motion(const RobotJoint &joint, double q)
            {
                RigidFrame m;
                if (joint.type == RobotJoint::Type::PRISMATIC)
                    m.t = q * joint.axis;
                else if (joint.movable())
                    m.r = Eigen::AngleAxisd(q, joint.axis).toRotationMatrix();
                return m;
            }
        }  // namespace

        SphereKinematics::SphereKinematics(const RobotModel &model, const std::vector<int> &variables,
                                           const std::vector<double> &fullTemplate, const std::vector<int> &links)
            : model_(model)
        {
            std::map<int, int> stepOfJoint;
            // (frame, pose in that frame) of a link, parents first; a joint of the group starts a new frame
            std::function<std::pair<int, RigidFrame>(int)> locate = [&](int link) -> std::pair<int, RigidFrame>
            {
                const int j = model.links()[link].parentJoint;
                if (j < 0)
                    return {0, RigidFrame{}};
                const RobotJoint &joint = model.joints()[j];
                auto parent = locate(joint.parentLink);
                const RigidFrame origin = compose(parent.second, fromIsometry(joint.origin));
                const auto group =
                    joint.movable() ? std::find(variables.begin(), variables.end(), joint.variable) : variables.end();
                if (group == variables.end())
                    // Fixed, or held at the template's value: part of the constant offset.
                    return {parent.first,
                            compose(origin, motion(joint, joint.movable() ? fullTemplate[joint.variable] : 0.))};
                auto it = stepOfJoint.find(j);
                if (it == stepOfJoint.end())
                {
                    // about +z or -z (most arms' URDFs): the rotation mixes two columns only; -z turns by -q
                    const double zSign = joint.axis == Eigen::Vector3d::UnitZ()    ? 1.
                                         : joint.axis == -Eigen::Vector3d::UnitZ() ? -1.
                                                                                   : 0.;
                    steps_.push_back({parent.first, origin, joint.axis, joint.type == RobotJoint::Type::PRISMATIC,
                                      static_cast<int>(group - variables.begin()), zSign});
                    it = stepOfJoint.emplace(j, static_cast<int>(steps_.size())).first;
                }
                return {it->second, RigidFrame{}};
            };
            for (int link : links)
            {
                const auto at = locate(link);
                linkFrame_.push_back(at.first);
                linkOffset_.push_back(at.second);
            }
        }

        void SphereKinematics::frames(const double *values, RigidFrame *out) const
        {
            // Per joint, its local transform (offset times its own motion) does not depend on the chain, so the CPU
            // computes it while the previous frame's product is still in flight; the chain then costs one product per
            // frame, which is what a state check waits for.
            out[0] = fromIsometry(model_.basePose());
            for (std::size_t k = 0; k < steps_.size(); ++k)
            {
                const Step &step = steps_[k];
                RigidFrame l;
                const double q = values[step.value];
                if (step.prismatic)
                {
                    l.r = step.offset.r;
                    l.t.noalias() = step.offset.r * (q * step.axis);
                    l.t += step.offset.t;
                }
                else
                {
                    double s, c;
                    fastSinCos(q, s, c);
                    l.t = step.offset.t;
                    const Eigen::Matrix3d &o = step.offset.r;
                    if (step.zSign != 0.)
                    {
                        s *= step.zSign;
                        // about z: only the first two columns mix
                        l.r.col(0) = c * o.col(0) + s * o.col(1);
                        l.r.col(1) = c * o.col(1) - s * o.col(0);
                        l.r.col(2) = o.col(2);
                    }
                    else
                    {
                        // Rodrigues' rotation about the unit axis, applied on the right (the motion is in the joint
                        // frame)
                        const Eigen::Vector3d &a = step.axis;
                        const double v = 1. - c;
                        Eigen::Matrix3d rot;
                        rot << c + a.x() * a.x() * v, a.x() * a.y() * v - a.z() * s, a.x() * a.z() * v + a.y() * s,
                            a.y() * a.x() * v + a.z() * s, c + a.y() * a.y() * v, a.y() * a.z() * v - a.x() * s,
                            a.z() * a.x() * v - a.y() * s, a.z() * a.y() * v + a.x() * s, c + a.z() * a.z() * v;
                        l.r.noalias() = o * rot;
                    }
                }
                const RigidFrame &p = out[step.parent];
                RigidFrame &f = out[k + 1];
                f.r.noalias() = p.r * l.r;
                f.t.noalias() = p.r * l.t;
                f.t += p.t;
            }
        }
    }  // namespace validity
}  // namespace michi
