#include "SvgRobot.h"

#include <michi/validity/scene/Polygon2.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

using michi::validity::Point2;

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
            RobotGeometry::RobotGeometry(const Problem &problem) : problem_(problem)
            {
                const std::size_t n = problem.dimension();
                if (problem.kind == Problem::Kind::SE2)
                {
                    // Yaw wraps: paths are sampled the short way round, as OMPL's SE(2) interpolates them, not across
                    // the whole axis.
                    wraps_ = {false, false, true};
                    for (const auto &p : problem.footprint)
                        // The heading tick scales with the robot, so it reads the same on a small robot and a large
                        // one.
                        headingLength_ = std::max(headingLength_, p.norm());
                    return;
                }
                if (!problem.model)
                    throw std::invalid_argument("problem '" + problem.name + "' has no robot model");
                const auto &model = *problem.model;
                std::set<int> groupJoints;
                for (std::size_t i = 0; i < n; ++i)
                {
                    const auto &joint = model.variableJoint(problem.groupVariables[i]);
                    wraps_.push_back(joint.type == validity::RobotJoint::Type::CONTINUOUS);
                    groupJoints.insert(model.jointIndex(joint.name));
                }
                findMovedLinks(groupJoints);
                // An arm that leaves the x-y plane gets a side view as well: a top view alone would hide its height.
                spatial_ = movesOutOfPlane(groupJoints);
            }

            RobotPicture RobotGeometry::picture(const Values &values, const Eigen::Isometry3d &view) const
            {
                return problem_.kind == Problem::Kind::SE2 ? footprintPicture(values, view) : armPicture(values, view);
            }

            Vec2 RobotGeometry::endPoint(const Values &values, const Eigen::Isometry3d &view) const
            {
                if (problem_.kind == Problem::Kind::SE2)
                    return (view * Eigen::Vector3d(values[0], values[1], 0.)).head<2>();
                if (skeleton_.empty())
                    return Vec2::Zero();
                const auto poses = problem_.model->forwardKinematics(fullConfiguration(values));
                return (view * poses[skeleton_.back()].translation()).head<2>();
            }

            std::vector<MultiPolygon2> RobotGeometry::fixedLinks(const Values &values,
                                                                 const Eigen::Isometry3d &view) const
            {
                std::vector<MultiPolygon2> shapes;
                if (problem_.kind == Problem::Kind::SE2)
                    return shapes;
                const auto poses = problem_.model->forwardKinematics(fullConfiguration(values));
                for (std::size_t l = 0; l < poses.size(); ++l)
                    if (!moved_[l])
                        addLinkShapes(l, view * poses[l], shapes);
                return shapes;
            }

            Values RobotGeometry::fullConfiguration(const Values &values) const
            {
                // Joints outside the planned group are drawn at the problem's fixed values, as the checker sees them.
                Values q = problem_.fixedValues;
                q.resize(problem_.model->variableCount(), 0.);
                for (std::size_t i = 0; i < values.size(); ++i)
                    q[problem_.groupVariables[i]] = values[i];
                return q;
            }

            void RobotGeometry::findMovedLinks(const std::set<int> &groupJoints)
            {
                const auto &model = *problem_.model;
                moved_.assign(model.links().size(), false);
                for (std::size_t l = 0; l < model.links().size(); ++l)
                {
                    const auto chain = model.chainTo(static_cast<int>(l));
                    moved_[l] = std::any_of(chain.begin(), chain.end(),
                                            [&](int j)
                                            {
                                                return groupJoints.count(j) > 0;
                                            });
                }
                int end = -1;
                std::size_t deepest = 0;
                for (int j : groupJoints)
                {
                    const int child = model.joints()[j].childLink;
                    const std::size_t depth = model.chainTo(child).size();
                    if (end < 0 || depth > deepest)
                    {
                        end = child;
                        deepest = depth;
                    }
                }
                if (end < 0)
                    return;
                std::vector<std::vector<int>> children(model.links().size());
                for (const auto &joint : model.joints())
                    if (joint.parentLink >= 0)
                        children[joint.parentLink].push_back(joint.childLink);
                // Down to the tip: links below the last planned joint (a hand, a tool) still move with it, and the
                // skeleton should end where the arm ends, not at the last joint.
                while (children[end].size() == 1)
                    end = children[end].front();
                const auto chain = model.chainTo(end);
                skeleton_.push_back(chain.empty() ? end : model.joints()[chain.front()].parentLink);
                for (int j : chain)
                    skeleton_.push_back(model.joints()[j].childLink);
            }

            bool RobotGeometry::movesOutOfPlane(const std::set<int> &groupJoints) const
            {
                const auto &model = *problem_.model;
                const auto poses = model.forwardKinematics(fullConfiguration(Values(problem_.dimension(), 0.)));
                for (int j : groupJoints)
                {
                    const auto &joint = model.joints()[j];
                    const Eigen::Isometry3d frame =
                        (joint.parentLink >= 0 ? poses[joint.parentLink] : model.basePose()) * joint.origin;
                    const double z = std::abs((frame.linear() * joint.axis).z());
                    const bool prismatic = joint.type == validity::RobotJoint::Type::PRISMATIC;
                    // A revolute joint stays in the plane only about a vertical axis; a prismatic one only along a
                    // horizontal axis.
                    if (prismatic ? z > 1e-9 : z < 1. - 1e-9)
                        return true;
                }
                return false;
            }

            void RobotGeometry::addLinkShapes(std::size_t link, const Eigen::Isometry3d &pose,
                                              std::vector<MultiPolygon2> &shapes) const
            {
                for (const auto &collision : problem_.model->links()[link].collisions)
                    shapes.push_back(collision.shape->footprint(pose * collision.origin));
            }

            RobotPicture RobotGeometry::armPicture(const Values &values, const Eigen::Isometry3d &view) const
            {
                RobotPicture picture;
                picture.arm = true;
                const auto poses = problem_.model->forwardKinematics(fullConfiguration(values));
                for (std::size_t l = 0; l < poses.size(); ++l)
                    if (moved_[l])
                        addLinkShapes(l, view * poses[l], picture.shapes);
                for (int l : skeleton_)
                    picture.skeleton.push_back((view * poses[l].translation()).head<2>());
                if (!picture.skeleton.empty())
                    picture.end = picture.skeleton.back();
                return picture;
            }

            RobotPicture RobotGeometry::footprintPicture(const Values &values, const Eigen::Isometry3d &view) const
            {
                RobotPicture picture;
                const Eigen::Rotation2Dd rotation(values[2]);
                const Vec2 centre(values[0], values[1]);
                auto project = [&](const Vec2 &p) -> Vec2
                {
                    return (view * Eigen::Vector3d(p.x(), p.y(), 0.)).head<2>();
                };
                std::vector<Point2> outline;
                for (const auto &p : problem_.footprint)
                {
                    const Vec2 w = project(centre + rotation * p);
                    outline.emplace_back(w.x(), w.y());
                }
                if (outline.size() >= 3)
                {
                    MultiPolygon2 shape;
                    shape.push_back(validity::makePolygon2(outline));
                    picture.shapes.push_back(shape);
                }
                picture.end = project(centre);
                picture.skeleton = {picture.end, project(centre + rotation * Vec2(0.6 * headingLength_, 0.))};
                return picture;
            }
        }  // namespace svg_plot
    }      // namespace tools
}  // namespace michi
