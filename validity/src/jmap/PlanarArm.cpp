#include <michi/validity/jmap/PlanarArm.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace bg = boost::geometry;

namespace michi
{
    namespace validity
    {
        namespace
        {
            const double TOL = 1e-9;

            /** \brief True when rotation \e r turns only about z. */
            bool aboutZ(const Eigen::Matrix3d &r)
            {
                // R(2, 2) = 1 only when z maps onto itself, i.e. the rotation turns about z alone.
                return std::abs(r(2, 2) - 1.) < TOL;
            }

            double yaw(const Eigen::Matrix3d &r)
            {
                return std::atan2(r(1, 0), r(0, 0));
            }

            /** \brief A capsule (link frame) that contains the x-y shadow of one collision shape, for any
                orientation of the shape. */
            std::vector<Capsule2> shapeCapsules(const LinkCollision &c)
            {
                const Shape &shape = *c.shape;
                const Eigen::Matrix3d r = c.origin.linear();
                const Eigen::Vector2d centre = c.origin.translation().head<2>();
                const Eigen::Vector3d &s = shape.size();
                Capsule2 cap;
                cap.a = cap.b = centre;
                switch (shape.type())
                {
                    case Shape::Type::SPHERE:
                        cap.radius = s.x();
                        return {cap};
                    case Shape::Type::CYLINDER:
                    case Shape::Type::CAPSULE:
                    {
                        // the shadow is the axis segment's shadow plus the end disks' shadows (ellipses with
                        // semi-axes r and r |cos tilt|), all within the 2-D capsule of radius r about the
                        // projected axis: exact for an axis in the plane, a disk for an upright one
                        const Eigen::Vector2d half = 0.5 * s.z() * r.col(2).head<2>();
                        cap.a = centre - half;
                        cap.b = centre + half;
                        cap.radius = s.x();
                        return {cap};
                    }
                    case Shape::Type::BOX:
                    {
                        // shadow = centre + sum_i t_i (s_i / 2) R_i.xy, |t_i| <= 1: the segment of the longest
                        // projected edge, radius = the sum of the other projected half edges (exact for a box
                        // whose z axis stays vertical)
                        int lng = 0;
                        for (int k = 1; k < 3; ++k)
                            if (s[k] * r.col(k).head<2>().norm() > s[lng] * r.col(lng).head<2>().norm())
                                lng = k;
                        const Eigen::Vector2d half = 0.5 * s[lng] * r.col(lng).head<2>();
                        cap.a = centre - half;
                        cap.b = centre + half;
                        for (int k = 0; k < 3; ++k)
                            if (k != lng)
                                cap.radius += 0.5 * s[k] * r.col(k).head<2>().norm();
                        return {cap};
                    }
                    default:
                        break;
                }
                cap.radius = shape.boundingRadius();  // meshes and prisms: a bounding disk about the origin
                return {cap};
            }
        }  // namespace

        std::shared_ptr<const PlanarArm> PlanarArm::fromModel(const RobotModel &model)
        {
            std::shared_ptr<PlanarArm> arm(new PlanarArm());
            const auto &links = model.links();
            const auto &joints = model.joints();
            if (!aboutZ(model.basePose().linear()))
                throw std::invalid_argument("robot '" + model.name() + "': base pose is not a rotation about z");
            arm->base_ = Eigen::Translation2d(model.basePose().translation().head<2>()) *
                         Eigen::Rotation2Dd(yaw(model.basePose().linear()));
            for (std::size_t l = 0; l < links.size(); ++l)
            {
                Link link;
                link.name = links[l].name;
                link.modelLink = static_cast<int>(l);
                link.joint = links[l].parentJoint;
                if (link.joint < 0)
                    arm->rootLink_ = static_cast<int>(l);
                for (const auto &c : links[l].collisions)
                    for (const auto &cap : shapeCapsules(c))
                        link.capsules.push_back(cap);
                arm->links_.push_back(std::move(link));
            }
            arm->variableJoints_.assign(model.variableCount(), -1);
            arm->variableCount_ = model.variableCount();
            for (std::size_t j = 0; j < joints.size(); ++j)
            {
                const RobotJoint &rj = joints[j];
                Joint joint;
                joint.name = rj.name;
                joint.parentLink = rj.parentLink;
                joint.childLink = rj.childLink;
                if (!aboutZ(rj.origin.linear()))
                    throw std::invalid_argument("robot '" + model.name() + "': joint '" + rj.name +
                                                "' origin turns out of the x-y plane (planar arms only)");
                joint.origin = rj.origin.translation().head<2>();
                joint.originAngle = yaw(rj.origin.linear());
                if (rj.movable())
                {
                    if (rj.type == RobotJoint::Type::PRISMATIC)
                        throw std::invalid_argument("robot '" + model.name() + "': joint '" + rj.name +
                                                    "' is prismatic (planar arms rotate about z only)");
                    if (std::abs(std::abs(rj.axis.z()) - 1.) > TOL)
                        throw std::invalid_argument("robot '" + model.name() + "': joint '" + rj.name +
                                                    "' does not rotate about z");
                    // A joint about -z turns the arm clockwise for a positive value: the sign goes into every angle.
                    joint.axisSign = rj.axis.z() > 0. ? 1. : -1.;
                    joint.variable = rj.variable;
                    joint.lower = rj.lower;
                    joint.upper = rj.upper;
                    if (rj.type == RobotJoint::Type::CONTINUOUS)
                    {
                        joint.lower = -M_PI;
                        joint.upper = M_PI;
                    }
                    arm->variableJoints_[rj.variable] = static_cast<int>(j);
                }
                arm->joints_.push_back(joint);
            }
            // joint order: parents first
            std::vector<char> placed(links.size(), 0);
            placed[arm->rootLink_] = 1;
            while (arm->order_.size() < joints.size())
            {
                const std::size_t before = arm->order_.size();
                for (std::size_t j = 0; j < joints.size(); ++j)
                    if (placed[joints[j].parentLink] && !placed[joints[j].childLink])
                    {
                        arm->order_.push_back(static_cast<int>(j));
                        placed[joints[j].childLink] = 1;
                    }
                // A pass that places no joint means some joint hangs below a link the root never reaches.
                if (arm->order_.size() == before)
                    throw std::invalid_argument("robot '" + model.name() + "': joints do not form a tree");
            }
            // reach of every link's capsule centre segments from every movable joint above it
            arm->reach_.assign(arm->variableCount_, std::vector<double>(links.size(), 0.));
            for (std::size_t l = 0; l < links.size(); ++l)
            {
                double ends = 0.;
                for (const auto &cap : arm->links_[l].capsules)
                    ends = std::max({ends, cap.a.norm(), cap.b.norm()});
                if (arm->links_[l].capsules.empty())
                    continue;
                double along = ends;  // distance bound from the current frame's origin
                int link = static_cast<int>(l);
                while (arm->links_[link].joint >= 0)
                {
                    const Joint &joint = arm->joints_[arm->links_[link].joint];
                    if (joint.variable >= 0)
                        // Turning this joint by w moves the capsule's axis points by at most along * w (about 2 along
                        // sin(w / 2)), which is what the J-map inflates the capsules by between slices (jmap.md).
                        arm->reach_[joint.variable][l] = along;
                    along += joint.origin.norm();
                    link = joint.parentLink;
                }
            }
            return arm;
        }

        std::vector<Eigen::Isometry2d> PlanarArm::linkFrames(const double *q) const
        {
            std::vector<Eigen::Isometry2d> frames;
            linkFrames(q, frames);
            return frames;
        }

        void PlanarArm::linkFrames(const double *q, std::vector<Eigen::Isometry2d> &frames) const
        {
            frames.assign(links_.size(), Eigen::Isometry2d::Identity());
            frames[rootLink_] = base_;
            for (int j : order_)
            {
                const Joint &joint = joints_[j];
                double angle = joint.originAngle;
                if (joint.variable >= 0)
                    angle += joint.axisSign * q[joint.variable];
                frames[joint.childLink] =
                    frames[joint.parentLink] * Eigen::Translation2d(joint.origin) * Eigen::Rotation2Dd(angle);
            }
        }

        std::vector<Capsule2> PlanarArm::worldCapsules(const double *q, std::vector<int> *owner) const
        {
            std::vector<Capsule2> out;
            std::vector<Eigen::Isometry2d> frames;
            worldCapsules(q, out, frames);
            if (owner)
            {
                owner->clear();
                for (std::size_t l = 0; l < links_.size(); ++l)
                    owner->insert(owner->end(), links_[l].capsules.size(), static_cast<int>(l));
            }
            return out;
        }

        void PlanarArm::worldCapsules(const double *q, std::vector<Capsule2> &out,
                                      std::vector<Eigen::Isometry2d> &frames) const
        {
            linkFrames(q, frames);
            out.clear();
            for (std::size_t l = 0; l < links_.size(); ++l)
                for (const auto &cap : links_[l].capsules)
                    out.push_back({frames[l] * cap.a, frames[l] * cap.b, cap.radius});
        }

        bool PlanarArm::moves(int variable, int link) const
        {
            while (links_[link].joint >= 0)
            {
                const Joint &joint = joints_[links_[link].joint];
                if (joint.variable == variable)
                    return true;
                link = joint.parentLink;
            }
            return false;
        }

        double PlanarArm::reachFrom(int variable, int link) const
        {
            return reach_[variable][link];
        }

        std::vector<double> PlanarArm::linkLengths() const
        {
            std::vector<double> lengths(variableCount_, 0.);
            for (std::size_t v = 0; v < variableCount_; ++v)
            {
                // the next movable joint below (first found in a depth-first walk down the chain)
                const Joint &joint = joints_[variableJoints_[v]];
                int link = joint.childLink;
                Eigen::Vector2d offset = Eigen::Vector2d::Zero();
                double angle = 0.;
                bool found = false;
                while (!found)
                {
                    int next = -1;
                    for (int j : order_)
                        if (joints_[j].parentLink == link)
                        {
                            next = j;
                            break;
                        }
                    if (next < 0)
                        break;
                    offset += Eigen::Rotation2Dd(angle) * joints_[next].origin;
                    angle += joints_[next].originAngle;
                    found = joints_[next].variable >= 0;
                    link = joints_[next].childLink;
                }
                if (found)
                    lengths[v] = offset.norm();
                else
                {
                    // the last movable joint: farthest extent of the geometry it moves
                    const auto zero = std::vector<double>(variableCount_, 0.);
                    const auto frames = linkFrames(zero.data());
                    const Eigen::Vector2d pivot = frames[joint.childLink].translation();
                    for (std::size_t l = 0; l < links_.size(); ++l)
                        if (moves(static_cast<int>(v), static_cast<int>(l)))
                            for (const auto &cap : links_[l].capsules)
                                lengths[v] = std::max({lengths[v], (frames[l] * cap.a - pivot).norm(),
                                                       (frames[l] * cap.b - pivot).norm()});
                }
            }
            return lengths;
        }

        double segmentDistance(const Eigen::Vector2d &a, const Eigen::Vector2d &b, const MultiPolygon2 &obstacles)
        {
            if (obstacles.empty())
                return std::numeric_limits<double>::infinity();
            // A sphere's capsule has a == b: measured from its centre point.
            if ((a - b).squaredNorm() == 0.)
                return bg::distance(Point2(a.x(), a.y()), obstacles);
            return bg::distance(Segment2(Point2(a.x(), a.y()), Point2(b.x(), b.y())), obstacles);
        }
    }  // namespace validity
}  // namespace michi
