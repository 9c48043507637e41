#include <michi/tools/SvgPlot.h>
#include <michi/tools/FileOutput.h>

#include <cstdio>
#include <cstdlib>

#include <michi/validity/Polygon2.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

using michi::validity::MultiPolygon2;
using michi::validity::Point2;

namespace michi
{
    namespace tools
    {
        namespace
        {
            using Vec2 = Eigen::Vector2d;
            using Polyline = std::vector<Vec2>;
            using Values = std::vector<double>;

            /** Path colours: distinguishable on white and from the start (green) and goal (red) colours. */
            const char *const PALETTE[] = {"#1f77b4", "#ff7f0e", "#9467bd", "#8c564b",
                                           "#e377c2", "#17becf", "#bcbd22", "#393b79"};
            const std::size_t PALETTE_SIZE = sizeof(PALETTE) / sizeof(PALETTE[0]);
            const char *const START_COLOUR = "#2ca02c";
            const char *const GOAL_COLOUR = "#d62728";
            const char *const OBSTACLE_FILL = "#9a9a9a";
            const char *const FIXED_LINK_FILL = "#d9d9d9";

            const std::size_t POSES_PER_PATH = 12;  ///< robot poses drawn along every path
            const std::size_t TRACE_SAMPLES = 240;  ///< points of an end-effector trace (plus the path's states)
            const std::size_t MAX_KEY_FRAMES = 5;   ///< key frames drawn per moving obstacle
            const std::size_t MAX_OUTLINED_OBSTACLES = 100;  ///< more are filled only (occupancy maps)
            const double PLOT_SIZE = 520.;                   ///< pixels of the longest side of a world panel
            const double MIN_CSPACE_SIZE = 260.;
            const double MARGIN_LEFT = 64.;
            const double PANEL_TOP = 84.;
            const double PANEL_GAP = 84.;
            const double MARGIN_BOTTOM = 56.;
            const double LEGEND_WIDTH = 240.;

            // ---------------------------------------------------------------- text

            /** A number for SVG: fixed point, at most \e decimals digits, no trailing zeros, no "-0". */
            std::string num(double value, int decimals = 2)
            {
                const double unit = std::pow(10., decimals);
                value = std::round(value * unit) / unit;
                if (value == 0.)
                    value = 0.;  // drops the sign of -0
                char buffer[64];
                const auto result =
                    std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::fixed, decimals);
                std::string text(buffer, result.ptr);
                if (text.find('.') != std::string::npos)
                {
                    while (text.back() == '0')
                        text.pop_back();
                    if (text.back() == '.')
                        text.pop_back();
                }
                return text;
            }

            std::string escapeXml(const std::string &text)
            {
                std::string escaped;
                for (char c : text)
                    switch (c)
                    {
                        case '&':
                            escaped += "&amp;";
                            break;
                        case '<':
                            escaped += "&lt;";
                            break;
                        case '>':
                            escaped += "&gt;";
                            break;
                        case '"':
                            escaped += "&quot;";
                            break;
                        case '\'':
                            escaped += "&apos;";
                            break;
                        default:
                            escaped += c;
                    }
                return escaped;
            }

            // ---------------------------------------------------------------- SVG output

            using Attributes = std::vector<std::pair<std::string, std::string>>;

            /** Writes well-formed SVG elements into a string; attribute values and text are escaped here. */
            class SvgWriter
            {
            public:
                SvgWriter(double width, double height)
                {
                    const std::string w = num(width, 0), h = num(height, 0);
                    open("svg", {{"xmlns", "http://www.w3.org/2000/svg"},
                                 {"width", w},
                                 {"height", h},
                                 {"viewBox", "0 0 " + w + " " + h},
                                 {"font-family", "DejaVu Sans, Arial, sans-serif"},
                                 {"font-size", "12"}});
                    element("rect", {{"width", w}, {"height", h}, {"fill", "white"}});
                }

                void open(const std::string &tag, const Attributes &attributes = {})
                {
                    indent();
                    out_ << '<' << tag;
                    writeAttributes(attributes);
                    out_ << ">\n";
                    open_.push_back(tag);
                }

                void close()
                {
                    const std::string tag = open_.back();
                    open_.pop_back();
                    indent();
                    out_ << "</" << tag << ">\n";
                }

                void element(const std::string &tag, const Attributes &attributes, const std::string &text = "")
                {
                    indent();
                    out_ << '<' << tag;
                    writeAttributes(attributes);
                    if (text.empty())
                        out_ << "/>\n";
                    else
                        out_ << '>' << escapeXml(text) << "</" << tag << ">\n";
                }

                void text(double x, double y, const std::string &content, Attributes attributes = {})
                {
                    attributes.insert(attributes.begin(), {{"x", num(x)}, {"y", num(y)}});
                    element("text", attributes, content);
                }

                /** The document, with every element still open closed. */
                std::string finish()
                {
                    while (!open_.empty())
                        close();
                    return out_.str();
                }

            private:
                void indent()
                {
                    for (std::size_t i = 0; i < open_.size(); ++i)
                        out_ << "  ";
                }

                void writeAttributes(const Attributes &attributes)
                {
                    for (const auto &a : attributes)
                        out_ << ' ' << a.first << "=\"" << escapeXml(a.second) << '"';
                }

                std::ostringstream out_;
                std::vector<std::string> open_;
            };

            // ---------------------------------------------------------------- world rectangle and view transform

            /** Axis-aligned rectangle that grows to hold what is added to it. */
            struct Extent
            {
                double xMin{std::numeric_limits<double>::infinity()};
                double xMax{-std::numeric_limits<double>::infinity()};
                double yMin{std::numeric_limits<double>::infinity()};
                double yMax{-std::numeric_limits<double>::infinity()};

                bool empty() const
                {
                    return !(xMin <= xMax && yMin <= yMax);
                }
                double width() const
                {
                    return xMax - xMin;
                }
                double height() const
                {
                    return yMax - yMin;
                }
                void add(double x, double y)
                {
                    if (!std::isfinite(x) || !std::isfinite(y))
                        return;
                    xMin = std::min(xMin, x);
                    xMax = std::max(xMax, x);
                    yMin = std::min(yMin, y);
                    yMax = std::max(yMax, y);
                }
                void add(const Vec2 &p)
                {
                    add(p.x(), p.y());
                }
                void add(const Polyline &line)
                {
                    for (const auto &p : line)
                        add(p);
                }
                void add(const MultiPolygon2 &shape)
                {
                    for (const auto &polygon : shape)
                        for (const auto &p : polygon.outer())
                            add(p.x(), p.y());
                }
                void add(const Extent &other)
                {
                    if (!other.empty())
                    {
                        add(other.xMin, other.yMin);
                        add(other.xMax, other.yMax);
                    }
                }
            };

            /** The extent with a margin, never degenerate and never thinner than 1:4, for a world panel. */
            Extent framed(Extent e)
            {
                if (e.empty())
                    e.add(0., 0.);
                const double pad = std::max(0.05 * std::max(e.width(), e.height()), 0.05);
                e.xMin -= pad;
                e.xMax += pad;
                e.yMin -= pad;
                e.yMax += pad;
                const double minimum = 0.25 * std::max(e.width(), e.height());
                for (auto range : {std::make_pair(&e.xMin, &e.xMax), std::make_pair(&e.yMin, &e.yMax)})
                {
                    const double grow = 0.5 * (minimum - (*range.second - *range.first));
                    if (grow > 0.)
                    {
                        *range.first -= grow;
                        *range.second += grow;
                    }
                }
                return e;
            }

            /** Maps a world rectangle onto a pixel rectangle, y up (SVG's y goes down). */
            class ViewTransform
            {
            public:
                ViewTransform(const Extent &world, double left, double top, double scaleX, double scaleY)
                    : world_(world), left_(left), top_(top), scaleX_(scaleX), scaleY_(scaleY)
                {
                }

                double x(double worldX) const
                {
                    return left_ + (worldX - world_.xMin) * scaleX_;
                }
                double y(double worldY) const
                {
                    return top_ + (world_.yMax - worldY) * scaleY_;
                }
                double left() const
                {
                    return left_;
                }
                double top() const
                {
                    return top_;
                }
                double width() const
                {
                    return world_.width() * scaleX_;
                }
                double height() const
                {
                    return world_.height() * scaleY_;
                }
                const Extent &world() const
                {
                    return world_;
                }

                /** "x,y x,y ..." for a polyline's points attribute. */
                std::string points(const Polyline &line) const
                {
                    std::string text;
                    for (const auto &p : line)
                    {
                        if (!text.empty())
                            text += ' ';
                        text += num(x(p.x())) + ',' + num(y(p.y()));
                    }
                    return text;
                }

                /** Path data of polygons (outer rings and holes), appended to \e data. */
                void appendPathData(const MultiPolygon2 &shape, std::string &data) const
                {
                    for (const auto &polygon : shape)
                    {
                        appendRing(polygon.outer(), data);
                        for (const auto &ring : polygon.inners())
                            appendRing(ring, data);
                    }
                }

            private:
                template <typename Ring>
                void appendRing(const Ring &ring, std::string &data) const
                {
                    if (ring.size() < 3)
                        return;
                    char command = 'M';
                    for (const auto &p : ring)
                    {
                        data += command;
                        data += num(x(p.x())) + ' ' + num(y(p.y()));
                        command = 'L';
                    }
                    data += 'Z';
                }

                Extent world_;
                double left_, top_, scaleX_, scaleY_;
            };

            /** A tick spacing of 1, 2 or 5 times a power of ten giving about \e count ticks over \e range. */
            double niceStep(double range, double count)
            {
                const double raw = range / count;
                const double magnitude = std::pow(10., std::floor(std::log10(raw)));
                const double n = raw / magnitude;
                return (n < 1.5 ? 1. : n < 3. ? 2. : n < 7. ? 5. : 10.) * magnitude;
            }

            // ---------------------------------------------------------------- paths in the value space

            double wrapDifference(double from, double to)
            {
                return std::remainder(to - from, 2. * M_PI);
            }

            /** Positions along a path of states, linear in the values except for angles that wrap, which take
                the short way round. Length is the Euclidean length in the values. */
            class PathSampler
            {
            public:
                PathSampler(std::vector<Values> states, std::vector<bool> wraps)
                    : states_(std::move(states)), wraps_(std::move(wraps))
                {
                    cumulative_.push_back(0.);
                    for (std::size_t k = 1; k < states_.size(); ++k)
                        cumulative_.push_back(cumulative_.back() + segmentLength(k - 1));
                }

                double length() const
                {
                    return cumulative_.back();
                }

                /** \e count states evenly spaced by length, the first and last state included. */
                std::vector<Values> evenlySpaced(std::size_t count) const
                {
                    if (states_.empty())
                        return {};
                    if (states_.size() == 1 || length() <= 0.)
                        return {states_.front()};
                    std::vector<Values> result;
                    for (std::size_t i = 0; i < count; ++i)
                        result.push_back(at(length() * static_cast<double>(i) / static_cast<double>(count - 1)));
                    return result;
                }

                /** Every state and about \e count states in between, spread by length. */
                std::vector<Values> dense(std::size_t count) const
                {
                    std::vector<Values> result;
                    for (std::size_t k = 0; k + 1 < states_.size(); ++k)
                    {
                        const double share = length() > 0. ? segmentLength(k) / length() : 0.;
                        const std::size_t steps = std::max<std::size_t>(1, std::ceil(share * count));
                        for (std::size_t j = 0; j < steps; ++j)
                            result.push_back(interpolate(k, static_cast<double>(j) / steps));
                    }
                    if (!states_.empty())
                        result.push_back(states_.back());
                    return result;
                }

            private:
                double difference(std::size_t i, double from, double to) const
                {
                    return wraps_[i] ? wrapDifference(from, to) : to - from;
                }

                double segmentLength(std::size_t k) const
                {
                    double squared = 0.;
                    for (std::size_t i = 0; i < wraps_.size(); ++i)
                        squared += std::pow(difference(i, states_[k][i], states_[k + 1][i]), 2);
                    return std::sqrt(squared);
                }

                Values interpolate(std::size_t k, double t) const
                {
                    Values v(wraps_.size());
                    for (std::size_t i = 0; i < v.size(); ++i)
                        v[i] = states_[k][i] + t * difference(i, states_[k][i], states_[k + 1][i]);
                    return v;
                }

                Values at(double s) const
                {
                    const auto next = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
                    if (next == cumulative_.end())
                        return states_.back();
                    const std::size_t k = std::max<std::ptrdiff_t>(next - cumulative_.begin() - 1, 0);
                    const double segment = cumulative_[k + 1] - cumulative_[k];
                    return interpolate(k, segment > 0. ? (s - cumulative_[k]) / segment : 0.);
                }

                std::vector<Values> states_;
                std::vector<bool> wraps_;
                std::vector<double> cumulative_;  ///< length from the first state to each state
            };

            // ---------------------------------------------------------------- the robot, projected

            /** One robot pose seen through a view: what is drawn of it. */
            struct RobotPicture
            {
                std::vector<MultiPolygon2> shapes;  ///< link shadows (arm) or the footprint (SE2)
                Polyline skeleton;                  ///< arm: joint origins, root first; SE2: heading tick
                Vec2 end{Vec2::Zero()};             ///< arm: end link origin; SE2: x, y
                bool arm{false};
            };

            /** What the picture needs of the robot: its projected shapes for a state, which values wrap, and
                whether it moves out of the x-y plane. A view is an isometry applied to world coordinates before
                the x, y of the result are drawn (top view: identity). */
            class RobotGeometry
            {
            public:
                explicit RobotGeometry(const Problem &problem) : problem_(problem)
                {
                    const std::size_t n = problem.dimension();
                    if (problem.kind == Problem::Kind::SE2)
                    {
                        wraps_ = {false, false, true};
                        for (const auto &p : problem.footprint)
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
                    spatial_ = movesOutOfPlane(groupJoints);
                }

                bool wraps(std::size_t i) const
                {
                    return wraps_[i];
                }
                const std::vector<bool> &wraps() const
                {
                    return wraps_;
                }
                /** True for robots whose links leave planes parallel to x-y (they get a side view). */
                bool spatial() const
                {
                    return spatial_;
                }

                RobotPicture picture(const Values &values, const Eigen::Isometry3d &view) const
                {
                    return problem_.kind == Problem::Kind::SE2 ? footprintPicture(values, view)
                                                               : armPicture(values, view);
                }

                /** The end link's origin (arm) or x, y (SE2) at \e values: the point a trace follows. */
                Vec2 endPoint(const Values &values, const Eigen::Isometry3d &view) const
                {
                    if (problem_.kind == Problem::Kind::SE2)
                        return (view * Eigen::Vector3d(values[0], values[1], 0.)).head<2>();
                    if (skeleton_.empty())
                        return Vec2::Zero();
                    const auto poses = problem_.model->forwardKinematics(fullConfiguration(values));
                    return (view * poses[skeleton_.back()].translation()).head<2>();
                }

                /** Links that no planned joint moves (drawn once), at the group's values \e values. */
                std::vector<MultiPolygon2> fixedLinks(const Values &values, const Eigen::Isometry3d &view) const
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

            private:
                Values fullConfiguration(const Values &values) const
                {
                    Values q = problem_.fixedValues;
                    q.resize(problem_.model->variableCount(), 0.);
                    for (std::size_t i = 0; i < values.size(); ++i)
                        q[problem_.groupVariables[i]] = values[i];
                    return q;
                }

                /** moved_: links below a planned joint. skeleton_: links from the root to the end link, the child
                    of the deepest planned joint followed down while the tree does not branch (a flange or tool
                    frame, not one of several fingers). */
                void findMovedLinks(const std::set<int> &groupJoints)
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
                    while (children[end].size() == 1)
                        end = children[end].front();
                    const auto chain = model.chainTo(end);
                    skeleton_.push_back(chain.empty() ? end : model.joints()[chain.front()].parentLink);
                    for (int j : chain)
                        skeleton_.push_back(model.joints()[j].childLink);
                }

                /** A revolute joint about a non-vertical axis or a prismatic joint along a non-horizontal one
                    moves links out of the x-y plane. Parents that only turn about z keep every axis's angle to z,
                    so one configuration decides. */
                bool movesOutOfPlane(const std::set<int> &groupJoints) const
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
                        if (prismatic ? z > 1e-9 : z < 1. - 1e-9)
                            return true;
                    }
                    return false;
                }

                void addLinkShapes(std::size_t link, const Eigen::Isometry3d &pose,
                                   std::vector<MultiPolygon2> &shapes) const
                {
                    for (const auto &collision : problem_.model->links()[link].collisions)
                        shapes.push_back(collision.shape->footprint(pose * collision.origin));
                }

                RobotPicture armPicture(const Values &values, const Eigen::Isometry3d &view) const
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

                RobotPicture footprintPicture(const Values &values, const Eigen::Isometry3d &view) const
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

                const Problem &problem_;
                std::vector<bool> wraps_;
                std::vector<bool> moved_;  ///< per link: moved by a planned joint
                std::vector<int> skeleton_;
                bool spatial_{false};
                double headingLength_{0.};
            };

            // ---------------------------------------------------------------- what a world panel shows

            /** One path, sampled once for every panel. */
            struct SampledPath
            {
                std::string label;
                std::string colour;
                std::vector<Values> poses;   ///< robot drawn here
                std::vector<Values> dense;   ///< for the traces
                std::vector<Values> states;  ///< the path's own states
            };

            struct PathPicture
            {
                std::vector<RobotPicture> poses;
                Polyline trace;
            };

            /** A world panel's content in world units on its plane, before it is scaled to pixels. */
            struct WorldView
            {
                std::string id;
                std::string title;
                std::string xLabel;
                std::string yLabel;
                std::vector<MultiPolygon2> obstacles;
                std::vector<MultiPolygon2> keyFrames;  ///< moving obstacles at some of their key frames
                std::vector<Polyline> routes;          ///< moving obstacles' key frame positions
                std::optional<Extent> limits;          ///< SE2 bounds of x, y
                std::vector<MultiPolygon2> fixedLinks;
                std::optional<RobotPicture> start;
                std::optional<RobotPicture> goal;
                std::vector<PathPicture> paths;

                Extent extent() const
                {
                    Extent e;
                    for (const auto *group : {&obstacles, &keyFrames, &fixedLinks})
                        for (const auto &shape : *group)
                            e.add(shape);
                    if (limits)
                        e.add(*limits);
                    auto addRobot = [&e](const RobotPicture &robot)
                    {
                        for (const auto &shape : robot.shapes)
                            e.add(shape);
                        e.add(robot.skeleton);
                    };
                    for (const auto *robot : {&start, &goal})
                        if (*robot)
                            addRobot(**robot);
                    for (const auto &path : paths)
                    {
                        for (const auto &pose : path.poses)
                            addRobot(pose);
                        e.add(path.trace);
                    }
                    return e;
                }
            };

            /** Indices of at most \e count key frames spread over \e size. */
            std::vector<std::size_t> spreadIndices(std::size_t size, std::size_t count)
            {
                std::vector<std::size_t> indices;
                if (size <= count)
                {
                    for (std::size_t i = 0; i < size; ++i)
                        indices.push_back(i);
                    return indices;
                }
                for (std::size_t i = 0; i < count; ++i)
                    indices.push_back(static_cast<std::size_t>(
                        std::lround(static_cast<double>(i * (size - 1)) / static_cast<double>(count - 1))));
                return indices;
            }

            void addScene(const validity::Scene *scene, const Eigen::Isometry3d &view, WorldView &v)
            {
                if (!scene)
                    return;
                for (const auto &obstacle : scene->obstacles())
                {
                    v.obstacles.push_back(obstacle.shape->footprint(view * obstacle.pose));
                    if (obstacle.trajectory.empty())
                        continue;
                    Polyline route;
                    for (const auto &frame : obstacle.trajectory)
                        route.push_back((view * frame.pose.translation()).head<2>());
                    v.routes.push_back(route);
                    for (std::size_t i : spreadIndices(obstacle.trajectory.size(), MAX_KEY_FRAMES))
                        v.keyFrames.push_back(obstacle.shape->footprint(view * obstacle.trajectory[i].pose));
                }
            }

            WorldView buildWorldView(const Problem &problem, const RobotGeometry &robot,
                                     const std::vector<SampledPath> &paths, const Query *query,
                                     const Eigen::Isometry3d &view)
            {
                WorldView v;
                addScene(problem.scene.get(), view, v);
                const Values reference = query ? query->start : Values(problem.dimension(), 0.);
                v.fixedLinks = robot.fixedLinks(reference, view);
                if (query)
                {
                    v.start = robot.picture(query->start, view);
                    v.goal = robot.picture(query->goal, view);
                }
                for (const auto &path : paths)
                {
                    PathPicture picture;
                    for (const auto &pose : path.poses)
                        picture.poses.push_back(robot.picture(pose, view));
                    for (const auto &values : path.dense)
                        picture.trace.push_back(robot.endPoint(values, view));
                    v.paths.push_back(std::move(picture));
                }
                return v;
            }

            // ---------------------------------------------------------------- drawing

            /** Panel frame, grid, ticks with labels and axis names; opens the clipped group of the content. */
            void openPanel(SvgWriter &svg, const std::string &id, const std::string &title, const ViewTransform &t,
                           const std::string &xLabel, const std::string &yLabel)
            {
                const double left = t.left(), top = t.top(), right = left + t.width(), bottom = top + t.height();
                svg.open("g", {{"id", id}});
                svg.text(left, top - 10., title, {{"font-size", "14"}, {"font-weight", "bold"}});
                svg.element("rect", {{"x", num(left)},
                                     {"y", num(top)},
                                     {"width", num(t.width())},
                                     {"height", num(t.height())},
                                     {"fill", "#fcfcfc"},
                                     {"stroke", "#444"}});
                const Extent &w = t.world();
                const double step = niceStep(std::max(w.width(), w.height()), 6.);
                const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
                svg.open("g", {{"class", "axes"}, {"font-size", "10"}, {"fill", "#333"}});
                for (double v = std::ceil(w.xMin / step) * step; v <= w.xMax + 1e-9 * step; v += step)
                {
                    const double x = t.x(v);
                    svg.element(
                        "line",
                        {{"x1", num(x)}, {"y1", num(top)}, {"x2", num(x)}, {"y2", num(bottom)}, {"stroke", "#e6e6e6"}});
                    svg.element("line", {{"x1", num(x)},
                                         {"y1", num(bottom)},
                                         {"x2", num(x)},
                                         {"y2", num(bottom + 4.)},
                                         {"stroke", "#444"}});
                    svg.text(x, bottom + 15., num(v, decimals), {{"text-anchor", "middle"}});
                }
                for (double v = std::ceil(w.yMin / step) * step; v <= w.yMax + 1e-9 * step; v += step)
                {
                    const double y = t.y(v);
                    svg.element(
                        "line",
                        {{"x1", num(left)}, {"y1", num(y)}, {"x2", num(right)}, {"y2", num(y)}, {"stroke", "#e6e6e6"}});
                    svg.element("line", {{"x1", num(left - 4.)},
                                         {"y1", num(y)},
                                         {"x2", num(left)},
                                         {"y2", num(y)},
                                         {"stroke", "#444"}});
                    svg.text(left - 6., y + 3.5, num(v, decimals), {{"text-anchor", "end"}});
                }
                svg.text(0.5 * (left + right), bottom + 32., xLabel, {{"text-anchor", "middle"}, {"font-size", "12"}});
                const std::string ly = num(left - 44.), my = num(0.5 * (top + bottom));
                svg.element("text",
                            {{"x", ly},
                             {"y", my},
                             {"text-anchor", "middle"},
                             {"font-size", "12"},
                             {"transform", "rotate(-90 " + ly + " " + my + ")"}},
                            yLabel);
                svg.close();
                svg.open("clipPath", {{"id", id + "-clip"}});
                svg.element(
                    "rect",
                    {{"x", num(left)}, {"y", num(top)}, {"width", num(t.width())}, {"height", num(t.height())}});
                svg.close();
                svg.open("g", {{"clip-path", "url(#" + id + "-clip)"}});
            }

            void closePanel(SvgWriter &svg)
            {
                svg.close();  // clipped content
                svg.close();  // panel
            }

            /** Shapes as one path element (one element for thousands of map cells keeps the file small). */
            void drawShapes(SvgWriter &svg, const ViewTransform &t, const std::vector<MultiPolygon2> &shapes,
                            Attributes attributes)
            {
                std::string data;
                for (const auto &shape : shapes)
                    t.appendPathData(shape, data);
                if (data.empty())
                    return;
                attributes.emplace_back("d", data);
                svg.element("path", attributes);
            }

            void drawPolyline(SvgWriter &svg, const ViewTransform &t, const Polyline &line, Attributes attributes)
            {
                if (line.size() < 2)
                    return;
                attributes.emplace_back("points", t.points(line));
                attributes.emplace_back("fill", "none");
                svg.element("polyline", attributes);
            }

            void drawDot(SvgWriter &svg, double x, double y, double radius, const std::string &colour,
                         Attributes attributes = {})
            {
                attributes.insert(attributes.begin(),
                                  {{"cx", num(x)}, {"cy", num(y)}, {"r", num(radius)}, {"fill", colour}});
                svg.element("circle", attributes);
            }

            /** A robot pose along a path: thin, semi-transparent outlines in the path's colour. */
            void drawRobotOutline(SvgWriter &svg, const ViewTransform &t, const RobotPicture &robot,
                                  const std::string &colour)
            {
                svg.open("g", {{"class", "robot"}});
                drawShapes(svg, t, robot.shapes,
                           {{"class", robot.arm ? "link" : "footprint"},
                            {"fill", colour},
                            {"fill-opacity", "0.06"},
                            {"stroke", colour},
                            {"stroke-opacity", "0.6"},
                            {"stroke-width", "0.8"}});
                drawPolyline(
                    svg, t, robot.skeleton,
                    {{"class", "skeleton"}, {"stroke", colour}, {"stroke-opacity", "0.6"}, {"stroke-width", "1"}});
                svg.close();
            }

            /** The robot at the start or goal: filled, with its joints (arm) or heading (SE2) marked. */
            void drawRobotSolid(SvgWriter &svg, const ViewTransform &t, const RobotPicture &robot,
                                const std::string &id, const std::string &colour)
            {
                svg.open("g", {{"class", "robot " + id}});
                drawShapes(svg, t, robot.shapes,
                           {{"class", robot.arm ? "link" : "footprint"},
                            {"fill", colour},
                            {"fill-opacity", "0.3"},
                            {"stroke", colour},
                            {"stroke-width", "1.5"}});
                drawPolyline(svg, t, robot.skeleton,
                             {{"class", "skeleton"}, {"stroke", colour}, {"stroke-width", "2"}});
                if (robot.arm)
                    for (const auto &p : robot.skeleton)
                        drawDot(svg, t.x(p.x()), t.y(p.y()), 2.5, colour);
                drawDot(svg, t.x(robot.end.x()), t.y(robot.end.y()), 3.5, "white",
                        {{"stroke", colour}, {"stroke-width", "1.5"}});
                svg.close();
            }

            void drawWorldPanel(SvgWriter &svg, const WorldView &v, const ViewTransform &t,
                                const std::vector<SampledPath> &paths)
            {
                openPanel(svg, v.id, v.title, t, v.xLabel, v.yLabel);
                if (v.limits)
                {
                    const Extent &l = *v.limits;
                    svg.element("rect", {{"class", "limits"},
                                         {"x", num(t.x(l.xMin))},
                                         {"y", num(t.y(l.yMax))},
                                         {"width", num(t.x(l.xMax) - t.x(l.xMin))},
                                         {"height", num(t.y(l.yMin) - t.y(l.yMax))},
                                         {"fill", "none"},
                                         {"stroke", "#555"},
                                         {"stroke-dasharray", "6 4"}});
                }
                // outlines help to see small obstacles, but would hatch a map made of many cells
                const bool outlined = v.obstacles.size() <= MAX_OUTLINED_OBSTACLES;
                drawShapes(svg, t, v.obstacles,
                           {{"class", "obstacles"},
                            {"fill", OBSTACLE_FILL},
                            {"stroke", outlined ? "#707070" : "none"},
                            {"stroke-width", "0.5"}});
                drawShapes(svg, t, v.keyFrames,
                           {{"class", "key-frames"},
                            {"fill", "none"},
                            {"stroke", "#707070"},
                            {"stroke-opacity", "0.6"},
                            {"stroke-dasharray", "3 3"}});
                for (const auto &route : v.routes)
                    drawPolyline(svg, t, route,
                                 {{"class", "route"}, {"stroke", "#707070"}, {"stroke-dasharray", "2 4"}});
                drawShapes(
                    svg, t, v.fixedLinks,
                    {{"class", "fixed-links"}, {"fill", FIXED_LINK_FILL}, {"stroke", "#444"}, {"stroke-width", "1"}});
                for (std::size_t i = 0; i < v.paths.size(); ++i)
                {
                    const std::string &colour = paths[i].colour;
                    svg.open("g", {{"class", "path"}, {"data-label", paths[i].label}});
                    for (const auto &pose : v.paths[i].poses)
                        drawRobotOutline(svg, t, pose, colour);
                    drawPolyline(
                        svg, t, v.paths[i].trace,
                        {{"class", "trace"}, {"stroke", colour}, {"stroke-width", "2"}, {"stroke-linejoin", "round"}});
                    svg.close();
                }
                if (v.start)
                    drawRobotSolid(svg, t, *v.start, "start", START_COLOUR);
                if (v.goal)
                    drawRobotSolid(svg, t, *v.goal, "goal", GOAL_COLOUR);
                closePanel(svg);
            }

            // ---------------------------------------------------------------- configuration space panel

            /** Value \e v moved into [lower, lower + 2 pi) when it wraps. */
            double normalised(double v, double lower, bool wraps)
            {
                if (!wraps)
                    return v;
                const double shifted = std::fmod(v - lower, 2. * M_PI);
                return lower + (shifted < 0. ? shifted + 2. * M_PI : shifted);
            }

            struct ConfigView
            {
                Extent limits;
                std::string xLabel, yLabel;
                std::vector<bool> wraps;
                std::optional<Vec2> start, goal;
            };

            ConfigView buildConfigView(const Problem &problem, const RobotGeometry &robot,
                                       const std::vector<SampledPath> &paths, const Query *query)
            {
                ConfigView c;
                c.wraps = robot.wraps();
                const auto names = problem.valueNames();
                double lower[2], upper[2];
                for (std::size_t i = 0; i < 2; ++i)
                {
                    const auto &joint = problem.model->variableJoint(problem.groupVariables[i]);
                    lower[i] = joint.lower;
                    upper[i] = joint.upper;
                    if (!(upper[i] > lower[i]))
                    {
                        // no usable limits: fit the data
                        Extent e;
                        for (const auto &path : paths)
                            for (const auto &v : path.states)
                                e.add(v[i], v[i]);
                        if (query)
                            for (const auto *v : {&query->start, &query->goal})
                                e.add((*v)[i], (*v)[i]);
                        lower[i] = e.empty() ? -1. : e.xMin - 0.5;
                        upper[i] = e.empty() ? 1. : e.xMax + 0.5;
                    }
                    const bool prismatic = joint.type == validity::RobotJoint::Type::PRISMATIC;
                    (i == 0 ? c.xLabel : c.yLabel) = names[i] + (prismatic ? " [m]" : " [rad]");
                }
                c.limits.add(lower[0], lower[1]);
                c.limits.add(upper[0], upper[1]);
                if (query)
                {
                    c.start = Vec2(normalised(query->start[0], lower[0], c.wraps[0]),
                                   normalised(query->start[1], lower[1], c.wraps[1]));
                    c.goal = Vec2(normalised(query->goal[0], lower[0], c.wraps[0]),
                                  normalised(query->goal[1], lower[1], c.wraps[1]));
                }
                return c;
            }

            /** A path in the configuration space, split where a wrapping value crosses its limits. */
            std::vector<Polyline> configPolylines(const ConfigView &c, const std::vector<Values> &dense)
            {
                std::vector<Polyline> pieces(1);
                for (const auto &v : dense)
                {
                    const Vec2 p(normalised(v[0], c.limits.xMin, c.wraps[0]),
                                 normalised(v[1], c.limits.yMin, c.wraps[1]));
                    if (!pieces.back().empty())
                    {
                        const Vec2 jump = (p - pieces.back().back()).cwiseAbs();
                        if ((c.wraps[0] && jump.x() > M_PI) || (c.wraps[1] && jump.y() > M_PI))
                            pieces.emplace_back();
                    }
                    pieces.back().push_back(p);
                }
                return pieces;
            }

            void drawConfigPanel(SvgWriter &svg, const ConfigView &c, const ViewTransform &t,
                                 const std::vector<SampledPath> &paths)
            {
                openPanel(svg, "cspace", "configuration space (joint limits)", t, c.xLabel, c.yLabel);
                for (const auto &path : paths)
                {
                    svg.open("g", {{"class", "path"}, {"data-label", path.label}});
                    for (const auto &piece : configPolylines(c, path.dense))
                        drawPolyline(svg, t, piece,
                                     {{"class", "cspace-trace"}, {"stroke", path.colour}, {"stroke-width", "2"}});
                    for (const auto &v : path.states)
                        drawDot(svg, t.x(normalised(v[0], c.limits.xMin, c.wraps[0])),
                                t.y(normalised(v[1], c.limits.yMin, c.wraps[1])), 2., path.colour);
                    svg.close();
                }
                if (c.start)
                    drawDot(svg, t.x(c.start->x()), t.y(c.start->y()), 5., START_COLOUR, {{"class", "start"}});
                if (c.goal)
                    drawDot(svg, t.x(c.goal->x()), t.y(c.goal->y()), 5., GOAL_COLOUR, {{"class", "goal"}});
                closePanel(svg);
            }

            // ---------------------------------------------------------------- legend, title, file

            struct LegendEntry
            {
                std::string label;
                std::string colour;
                bool line;  ///< a line (paths) or a filled square
                bool dashed{false};
            };

            void drawLegend(SvgWriter &svg, double left, double top, const std::vector<LegendEntry> &entries)
            {
                svg.open("g", {{"id", "legend"}});
                svg.text(left, top - 10., "legend", {{"font-size", "14"}, {"font-weight", "bold"}});
                double y = top + 8.;
                for (const auto &entry : entries)
                {
                    if (entry.line)
                        svg.element("line", {{"x1", num(left)},
                                             {"y1", num(y)},
                                             {"x2", num(left + 24.)},
                                             {"y2", num(y)},
                                             {"stroke", entry.colour},
                                             {"stroke-width", entry.dashed ? "1.5" : "3"},
                                             {"stroke-dasharray", entry.dashed ? "4 3" : "none"}});
                    else
                        svg.element("rect", {{"x", num(left + 4.)},
                                             {"y", num(y - 7.)},
                                             {"width", "14"},
                                             {"height", "14"},
                                             {"fill", entry.colour},
                                             {"fill-opacity", "0.6"},
                                             {"stroke", entry.colour}});
                    svg.text(left + 32., y + 4., entry.label, {{"class", "legend-label"}});
                    y += 22.;
                }
                svg.close();
            }

            std::vector<LegendEntry> legendEntries(const Problem &problem, const WorldView &top,
                                                   const std::vector<SampledPath> &paths, bool hasQuery)
            {
                std::vector<LegendEntry> entries;
                if (hasQuery)
                {
                    entries.push_back({"start", START_COLOUR, false});
                    entries.push_back({"goal", GOAL_COLOUR, false});
                }
                if (!top.obstacles.empty())
                    entries.push_back({"obstacles", OBSTACLE_FILL, false});
                if (!top.keyFrames.empty())
                    entries.push_back({"moving obstacles at key frames", "#707070", true, true});
                if (!top.fixedLinks.empty())
                    entries.push_back({"robot links not planned", FIXED_LINK_FILL, false});
                if (problem.kind == Problem::Kind::SE2)
                    entries.push_back({"x, y bounds", "#555", true, true});
                for (const auto &path : paths)
                    entries.push_back({path.label + (path.states.empty() ? " (empty)" : ""), path.colour, true});
                return entries;
            }

            void checkValues(const Values &values, std::size_t dimension, const std::string &what)
            {
                if (values.size() != dimension)
                    throw std::invalid_argument(what + " has " + std::to_string(values.size()) +
                                                " values, the problem's state has " + std::to_string(dimension));
                for (double v : values)
                    if (!std::isfinite(v))
                        throw std::invalid_argument(what + " has a value that is not finite");
            }

            std::vector<SampledPath> samplePaths(const std::vector<PlotPath> &paths, const RobotGeometry &robot,
                                                 std::size_t dimension)
            {
                std::vector<SampledPath> sampled;
                for (std::size_t p = 0; p < paths.size(); ++p)
                {
                    const auto &path = paths[p];
                    for (std::size_t k = 0; k < path.states.size(); ++k)
                        checkValues(path.states[k], dimension, "path '" + path.label + "': state " + std::to_string(k));
                    const PathSampler sampler(path.states, robot.wraps());
                    sampled.push_back({path.label, PALETTE[p % PALETTE_SIZE], sampler.evenlySpaced(POSES_PER_PATH),
                                       sampler.dense(TRACE_SAMPLES), path.states});
                }
                return sampled;
            }

            /** World to side view: x stays, z becomes the view's y (seen from -y). */
            Eigen::Isometry3d sideView()
            {
                Eigen::Isometry3d view = Eigen::Isometry3d::Identity();
                view.linear() << 1., 0., 0., 0., 0., 1., 0., -1., 0.;
                return view;
            }

            /** The query to draw (checked), or none when the problem has no queries. */
            const Query *chosenQuery(const Problem &problem, std::size_t query)
            {
                if (problem.queries.empty())
                    return nullptr;
                if (query >= problem.queries.size())
                    throw std::out_of_range("query " + std::to_string(query) + ": problem '" + problem.name + "' has " +
                                            std::to_string(problem.queries.size()) + " queries");
                const Query &q = problem.queries[query];
                checkValues(q.start, problem.dimension(), "start of query " + std::to_string(query));
                checkValues(q.goal, problem.dimension(), "goal of query " + std::to_string(query));
                return &q;
            }

            /** The top view, and the side view for robots that leave the x-y plane. */
            std::vector<WorldView> buildWorldViews(const Problem &problem, const RobotGeometry &robot,
                                                   const std::vector<SampledPath> &paths, const Query *query)
            {
                std::vector<WorldView> views;
                views.push_back(buildWorldView(problem, robot, paths, query, Eigen::Isometry3d::Identity()));
                WorldView &top = views.back();
                top.id = "top-view";
                top.title = "top view (x-y)";
                top.xLabel = "x [m]";
                top.yLabel = "y [m]";
                if (problem.kind == Problem::Kind::SE2)
                {
                    top.limits = Extent();
                    top.limits->add(problem.se2Bounds[0], problem.se2Bounds[2]);
                    top.limits->add(problem.se2Bounds[1], problem.se2Bounds[3]);
                }
                if (robot.spatial())
                {
                    views.push_back(buildWorldView(problem, robot, paths, query, sideView()));
                    WorldView &side = views.back();
                    side.id = "side-view";
                    side.title = "side view (x-z, seen from -y)";
                    side.xLabel = "x [m]";
                    side.yLabel = "z [m]";
                }
                return views;
            }

            /** Where the panels (left to right) and the legend go. World panels share one scale. */
            struct Layout
            {
                std::vector<ViewTransform> world;
                std::optional<ViewTransform> config;
                double legendLeft{0.};
                double width{0.};
                double height{0.};
            };

            Layout layoutPanels(const std::vector<WorldView> &views, const std::optional<ConfigView> &config,
                                std::size_t legendEntries)
            {
                std::vector<Extent> frames;
                double longest = 0.;
                for (const auto &v : views)
                {
                    frames.push_back(framed(v.extent()));
                    longest = std::max({longest, frames.back().width(), frames.back().height()});
                }
                Layout layout;
                const double scale = PLOT_SIZE / longest;  // pixels per metre
                double x = MARGIN_LEFT, panelHeight = 0.;
                for (const auto &frame : frames)
                {
                    layout.world.emplace_back(frame, x, PANEL_TOP, scale, scale);
                    x += layout.world.back().width() + PANEL_GAP;
                    panelHeight = std::max(panelHeight, layout.world.back().height());
                }
                if (config)
                {
                    const double side = std::clamp(panelHeight, MIN_CSPACE_SIZE, PLOT_SIZE);
                    layout.config.emplace(config->limits, x, PANEL_TOP, side / config->limits.width(),
                                          side / config->limits.height());
                    x += side + PANEL_GAP;
                    panelHeight = std::max(panelHeight, side);
                }
                layout.legendLeft = x - PANEL_GAP + 40.;
                layout.width = layout.legendLeft + LEGEND_WIDTH;
                layout.height = std::max(PANEL_TOP + panelHeight + MARGIN_BOTTOM,
                                         PANEL_TOP + 22. * static_cast<double>(legendEntries) + 30.);
                return layout;
            }

            void drawTitle(SvgWriter &svg, const Problem &problem, const Query *q, std::size_t query,
                           std::size_t pathCount)
            {
                svg.text(MARGIN_LEFT, 28., problem.name.empty() ? "problem" : problem.name,
                         {{"id", "title"}, {"font-size", "18"}, {"font-weight", "bold"}});
                std::string subtitle =
                    problem.kind == Problem::Kind::SE2 ? "SE(2) footprint" : "arm " + problem.model->name();
                if (!problem.group.empty())
                    subtitle += ", group " + problem.group;
                if (q)
                    subtitle += ", query " + std::to_string(query);
                subtitle +=
                    ", " + std::to_string(pathCount) + " path(s), robot drawn at " + std::to_string(POSES_PER_PATH) +
                    " poses per path, trace: " + (problem.kind == Problem::Kind::SE2 ? "x, y" : "end link origin");
                svg.text(MARGIN_LEFT, 48., subtitle, {{"fill", "#555"}});
            }
        }  // namespace

        void writeProblemSvg(const Problem &problem, const std::vector<PlotPath> &paths, const std::string &file,
                             std::size_t query)
        {
            const Query *q = chosenQuery(problem, query);
            const RobotGeometry robot(problem);
            const std::vector<SampledPath> sampled = samplePaths(paths, robot, problem.dimension());
            const std::vector<WorldView> views = buildWorldViews(problem, robot, sampled, q);
            std::optional<ConfigView> config;
            if (problem.kind == Problem::Kind::ARM && problem.dimension() == 2)
                config = buildConfigView(problem, robot, sampled, q);
            const auto legend = legendEntries(problem, views.front(), sampled, q != nullptr);
            const Layout layout = layoutPanels(views, config, legend.size());

            SvgWriter svg(layout.width, layout.height);
            drawTitle(svg, problem, q, query, paths.size());
            for (std::size_t i = 0; i < views.size(); ++i)
                drawWorldPanel(svg, views[i], layout.world[i], sampled);
            if (config)
                drawConfigPanel(svg, *config, *layout.config, sampled);
            drawLegend(svg, layout.legendLeft, PANEL_TOP, legend);
            writeAtomically(svg.finish(), file);
        }

        bool svgToPng(const std::string &svg, const std::string &png, int width)
        {
            const std::string tmp = png + ".tmp";
            const std::string command = "rsvg-convert -w " + std::to_string(width) + " -f png -o " + shellQuote(tmp) +
                                        " " + shellQuote(svg) + " > /dev/null 2>&1";
            if (std::system(command.c_str()) != 0 || std::rename(tmp.c_str(), png.c_str()) != 0)
            {
                std::remove(tmp.c_str());
                return false;
            }
            return true;
        }
    }  // namespace tools
}  // namespace michi
