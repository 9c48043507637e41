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
            : model_(model), dimension_(variables.size())
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
                    Step step{parent.first,
                              joint.axis,
                              joint.type == RobotJoint::Type::PRISMATIC,
                              static_cast<int>(group - variables.begin()),
                              zSign,
                              {},
                              {},
                              {}};
                    for (int c = 0; c < 3; ++c)
                        for (int r = 0; r < 3; ++r)
                            step.rotation[3 * c + r] = Eigen::Array4f::Constant(static_cast<float>(origin.r(r, c)));
                    for (int r = 0; r < 3; ++r)
                        step.translation[r] = Eigen::Array4f::Constant(static_cast<float>(origin.t(r)));
                    step.slide = (origin.r * joint.axis).cast<float>();
                    steps_.push_back(step);
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

        void SphereKinematics::framesFloat(const double *values, FloatFrame *out) const
        {
            const Eigen::Isometry3d &base = model_.basePose();
            FloatFrame &b = out[0];
            for (int r = 0; r < 3; ++r)
            {
                b.c0(r) = static_cast<float>(base.linear()(r, 0));
                b.c1(r) = static_cast<float>(base.linear()(r, 1));
                b.c2(r) = static_cast<float>(base.linear()(r, 2));
                b.t(r) = static_cast<float>(base.translation()(r));
            }
            b.c0(3) = b.c1(3) = b.c2(3) = b.t(3) = 0.f;
            // sin and cos of every value first, in one pass over SIMD lanes: off the chain of frame products below,
            // where each frame waits for its parent
            constexpr int CHUNK = 32;
            float sines[CHUNK], cosines[CHUNK];
            const int n = static_cast<int>(dimension_);
            if (n <= CHUNK)
                fastSinCosFloat(values, n, sines, cosines);
            // the frame just made, passed on by value to the next step when it is that step's parent (a serial arm:
            // every step), rather than read back from the output array
            FloatFrame last = out[0];
            for (std::size_t k = 0; k < steps_.size(); ++k)
            {
                const Step &step = steps_[k];
                const FloatFrame p = step.parent == static_cast<int>(k) ? last : out[step.parent];
                FloatFrame f;
                const Eigen::Array4f *o = step.rotation;
                f.t = p.c0 * step.translation[0] + p.c1 * step.translation[1] + p.c2 * step.translation[2] + p.t;
                const double q = values[step.value];
                if (step.prismatic)
                {
                    f.c0 = p.c0 * o[0] + p.c1 * o[1] + p.c2 * o[2];
                    f.c1 = p.c0 * o[3] + p.c1 * o[4] + p.c2 * o[5];
                    f.c2 = p.c0 * o[6] + p.c1 * o[7] + p.c2 * o[8];
                    const float qf = static_cast<float>(q);
                    f.t += p.c0 * (qf * step.slide.x()) + p.c1 * (qf * step.slide.y()) + p.c2 * (qf * step.slide.z());
                    out[k + 1] = last = f;
                    continue;
                }
                float sf, cf;
                if (n <= CHUNK)
                {
                    sf = sines[step.value];
                    cf = cosines[step.value];
                }
                else
                {
                    double sd, cd;
                    fastSinCos(q, sd, cd);
                    sf = static_cast<float>(sd);
                    cf = static_cast<float>(cd);
                }
                if (step.zSign != 0.)
                {
                    // about z: the joint's rotation mixes the origin's first two columns. The origin times the
                    // rotation (X) does not depend on the parent, so the chain from frame to frame is one 3x3
                    // product (X's entries in every lane, column j's row i at x[j][i]).
                    const float sz = step.zSign > 0. ? sf : -sf;
                    const Eigen::Array4f x00 = cf * o[0] + sz * o[3], x01 = cf * o[1] + sz * o[4],
                                         x02 = cf * o[2] + sz * o[5];
                    const Eigen::Array4f x10 = cf * o[3] - sz * o[0], x11 = cf * o[4] - sz * o[1],
                                         x12 = cf * o[5] - sz * o[2];
                    f.c0 = p.c0 * x00 + p.c1 * x01 + p.c2 * x02;
                    f.c1 = p.c0 * x10 + p.c1 * x11 + p.c2 * x12;
                    f.c2 = p.c0 * o[6] + p.c1 * o[7] + p.c2 * o[8];
                    out[k + 1] = last = f;
                    continue;
                }
                // Rodrigues' rotation about the unit axis, on the right of the origin and the parent's rotation
                const Eigen::Array4f m0 = p.c0 * o[0] + p.c1 * o[1] + p.c2 * o[2];
                const Eigen::Array4f m1 = p.c0 * o[3] + p.c1 * o[4] + p.c2 * o[5];
                const Eigen::Array4f m2 = p.c0 * o[6] + p.c1 * o[7] + p.c2 * o[8];
                const Eigen::Vector3f a = step.axis.cast<float>();
                const float v = 1.f - cf;
                Eigen::Matrix3f rot;
                rot << cf + a.x() * a.x() * v, a.x() * a.y() * v - a.z() * sf, a.x() * a.z() * v + a.y() * sf,
                    a.y() * a.x() * v + a.z() * sf, cf + a.y() * a.y() * v, a.y() * a.z() * v - a.x() * sf,
                    a.z() * a.x() * v - a.y() * sf, a.z() * a.y() * v + a.x() * sf, cf + a.z() * a.z() * v;
                f.c0 = m0 * rot(0, 0) + m1 * rot(1, 0) + m2 * rot(2, 0);
                f.c1 = m0 * rot(0, 1) + m1 * rot(1, 1) + m2 * rot(2, 1);
                f.c2 = m0 * rot(0, 2) + m1 * rot(1, 2) + m2 * rot(2, 2);
                out[k + 1] = last = f;
            }
        }
    }  // namespace validity
}  // namespace michi
