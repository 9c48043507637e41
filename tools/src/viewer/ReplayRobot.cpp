#include "viewer/ReplayRobot.h"
#include "viewer/ReplayJson.h"

#include <michi/tools/FileOutput.h>

#include <cmath>

namespace michi
{
    namespace tools
    {
        namespace replay
        {
            RobotBodies::RobotBodies(const Problem &problem, ShapeTable &shapes, const std::vector<double> &fixedValues)
                : problem_(problem), fixed_(fixedValues.empty() ? problem.fixedValues : fixedValues), geometry_(problem)
            {
                if (problem.kind == Problem::Kind::SE2)
                {
                    Body body;
                    body.name = "footprint";
                    // the shape the SE(2) checker places (PlanarRigidBody): the footprint over [0, height]
                    body.parts.emplace_back(
                        shapes.index(validity::Shape::prism(problem.footprint, 0., problem.footprintHeight)),
                        Eigen::Isometry3d::Identity());
                    bodies_.push_back(body);
                    endBody_ = 0;
                    return;
                }
                const auto &links = problem.model->links();
                const auto &moved = geometry_.movedLinks();
                for (std::size_t l = 0; l < links.size(); ++l)
                {
                    const bool end = static_cast<int>(l) == geometry_.endLink();
                    // Only moved links are bodies (posed per frame); the others are drawn once as static parts. The end
                    // link is kept even without geometry: the page's end-effector trace follows it.
                    if (!moved[l] || (links[l].collisions.empty() && !end))
                        continue;
                    Body body;
                    body.name = links[l].name;
                    for (const auto &collision : links[l].collisions)
                        body.parts.emplace_back(shapes.index(collision.shape), collision.origin);
                    if (end)
                        endBody_ = static_cast<int>(bodies_.size());
                    bodies_.push_back(body);
                    links_.push_back(static_cast<int>(l));
                }
            }

            std::vector<Eigen::Isometry3d> RobotBodies::poses(const std::vector<double> &values) const
            {
                std::vector<Eigen::Isometry3d> result;
                if (problem_.kind == Problem::Kind::SE2)
                {
                    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
                    pose.translation() = Eigen::Vector3d(values[0], values[1], 0.);
                    pose.linear() = Eigen::AngleAxisd(values[2], Eigen::Vector3d::UnitZ()).toRotationMatrix();
                    result.push_back(pose);
                    return result;
                }
                const auto linkPoses = problem_.model->forwardKinematics(fullConfiguration(values));
                // Poses only of the links that are bodies, in bodies_' order: the page reads 7 numbers per body per
                // frame.
                for (int l : links_)
                    result.push_back(linkPoses[l]);
                return result;
            }

            std::vector<double> RobotBodies::fullConfiguration(const std::vector<double> &values) const
            {
                std::vector<double> q = fixed_;
                q.resize(problem_.model->variableCount(), 0.);
                for (std::size_t i = 0; i < values.size(); ++i)
                    q[problem_.groupVariables[i]] = values[i];
                return q;
            }

            std::string RobotBodies::staticPartsJson(ShapeTable &shapes) const
            {
                std::string out = "[";
                if (problem_.kind == Problem::Kind::ARM)
                {
                    // links no planned joint moves do not depend on the planned values: any values place them
                    const auto linkPoses = problem_.model->forwardKinematics(
                        fullConfiguration(std::vector<double>(problem_.dimension(), 0.)));
                    const auto &links = problem_.model->links();
                    const auto &moved = geometry_.movedLinks();
                    for (std::size_t l = 0; l < links.size(); ++l)
                    {
                        if (moved[l])
                            continue;
                        for (const auto &collision : links[l].collisions)
                        {
                            if (out.size() > 1)
                                out += ',';
                            out += '[' + std::to_string(shapes.index(collision.shape)) + ',';
                            appendPose(out, linkPoses[l] * collision.origin);
                            out += ']';
                        }
                    }
                }
                return out + "]";
            }

            std::string RobotBodies::bodiesJson() const
            {
                std::string out = "[";
                for (std::size_t b = 0; b < bodies_.size(); ++b)
                {
                    if (b)
                        out += ',';
                    out += "{\"name\":" + jsonString(bodies_[b].name) + ",\"parts\":[";
                    for (std::size_t p = 0; p < bodies_[b].parts.size(); ++p)
                    {
                        if (p)
                            out += ',';
                        out += '[' + std::to_string(bodies_[b].parts[p].first) + ',';
                        appendPose(out, bodies_[b].parts[p].second);
                        out += ']';
                    }
                    out += "]}";
                }
                return out + "]";
            }
        }  // namespace replay
    }      // namespace tools
}  // namespace michi
