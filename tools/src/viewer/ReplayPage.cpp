#include <michi/tools/viewer/ReplayPage.h>

#include "viewer/ReplayAssets.h"
#include "viewer/ReplayJson.h"
#include "viewer/ReplayMap.h"
#include "viewer/ReplayRobot.h"
#include "viewer/ReplayShapes.h"

#include <michi/tools/FileOutput.h>
#include <michi/tools/bench/PlanningContext.h>

#include <ompl/base/ScopedState.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace michi
{
    namespace tools
    {
        const char *const REPLAY_PAGE_MARK = "\"format\":\"michi-replay-1\"";

        namespace
        {
            namespace ob = ompl::base;

            std::string obstaclesJson(const Problem &problem, const validity::Scene &scene, replay::ShapeTable &shapes,
                                      std::string &map)
            {
                std::string out = "[";
                std::vector<validity::Obstacle> cells;
                for (const auto &obstacle : scene.obstacles())
                {
                    // A map's cells go into one textured plane (mapJson) instead of thousands of boxes: the page stays
                    // small and fast.
                    if (replay::isMapCell(problem, obstacle))
                    {
                        cells.push_back(obstacle);
                        continue;
                    }
                    if (out.size() > 1)
                        out += ',';
                    out += "{\"name\":" + jsonString(obstacle.name) +
                           ",\"shape\":" + std::to_string(shapes.index(obstacle.shape)) + ",\"pose\":";
                    replay::appendPose(out, obstacle.pose);
                    // a moving obstacle's key frames: the page interpolates them as Scene::poseAt does
                    out += ",\"trajectory\":[";
                    for (std::size_t k = 0; k < obstacle.trajectory.size(); ++k)
                    {
                        out += k ? ",[" : "[";
                        replay::appendPrecise(out, obstacle.trajectory[k].time);
                        out += ',';
                        replay::appendPrecisePoseValues(out, obstacle.trajectory[k].pose);
                        out += ']';
                    }
                    out += "]}";
                }
                map = cells.empty() ? "null" : replay::mapJson(problem, cells);
                return out + "]";
            }

            /** One path cut into frames: its waypoints verbatim (so the page shows exactly the states michi
                wrote) and states interpolated by the problem's state space between them. */
            struct Frames
            {
                std::vector<double> times;
                std::vector<std::vector<double>> states;
                std::vector<std::size_t> waypoints;  ///< frame index of each waypoint
            };

            Frames cutPath(const ob::StateSpacePtr &space, const std::vector<std::vector<double>> &states, double speed,
                           std::size_t frames)
            {
                Frames f;
                ob::ScopedState<> a(space), b(space), s(space);
                double length = 0.;
                std::vector<double> segment;
                for (std::size_t i = 0; i + 1 < states.size(); ++i)
                {
                    space->copyFromReals(a.get(), states[i]);
                    space->copyFromReals(b.get(), states[i + 1]);
                    segment.push_back(space->distance(a.get(), b.get()));
                    length += segment.back();
                }
                // Frames evenly spaced in state-space distance: a long segment gets more frames than a short one, so
                // the robot moves at a steady speed.
                const double step = length / static_cast<double>(std::max<std::size_t>(frames, 1));
                double travelled = 0.;
                for (std::size_t i = 0; i + 1 < states.size(); ++i)
                {
                    space->copyFromReals(a.get(), states[i]);
                    space->copyFromReals(b.get(), states[i + 1]);
                    const double d = segment[i];
                    const std::size_t n = step > 0. ? std::max<std::size_t>(1, std::ceil(d / step)) : 1;
                    for (std::size_t k = 0; k < n; ++k)
                    {
                        const double fraction = static_cast<double>(k) / static_cast<double>(n);
                        if (k == 0)
                        {
                            f.waypoints.push_back(f.states.size());
                            f.states.push_back(states[i]);
                        }
                        else
                        {
                            space->interpolate(a.get(), b.get(), fraction, s.get());
                            std::vector<double> values;
                            space->copyToReals(values, s.get());
                            f.states.push_back(values);
                        }
                        // Every path shares one speed in state space (the longest takes the whole duration): a shorter
                        // path arrives sooner, so the page also compares lengths.
                        f.times.push_back((travelled + fraction * d) / speed);
                    }
                    travelled += d;
                }
                f.waypoints.push_back(f.states.size());
                f.states.push_back(states.back());
                f.times.push_back(travelled / speed);
                return f;
            }

            /** A path that keeps its own clock (ReplayOptions::times): every state a frame and a waypoint. */
            Frames timedPath(const std::vector<std::vector<double>> &states, const std::vector<double> &times)
            {
                Frames f;
                f.times = times;
                f.states = states;
                for (std::size_t i = 0; i < states.size(); ++i)
                    f.waypoints.push_back(i);
                return f;
            }

            double pathLength(const ob::StateSpacePtr &space, const std::vector<std::vector<double>> &states)
            {
                ob::ScopedState<> a(space), b(space);
                double length = 0.;
                for (std::size_t i = 0; i + 1 < states.size(); ++i)
                {
                    space->copyFromReals(a.get(), states[i]);
                    space->copyFromReals(b.get(), states[i + 1]);
                    length += space->distance(a.get(), b.get());
                }
                return length;
            }

            std::string pathJson(const PlotPath &path, const Frames &f, const replay::RobotBodies &robot)
            {
                std::string out = "{\"label\":" + jsonString(path.label) + ",\"waypoints\":[";
                for (std::size_t i = 0; i < f.waypoints.size(); ++i)
                    out += (i ? "," : "") + std::to_string(f.waypoints[i]);
                out += "],\"times\":";
                replay::appendPreciseArray(out, f.times);
                out += ",\"states\":[";
                for (std::size_t i = 0; i < f.states.size(); ++i)
                {
                    if (i)
                        out += ',';
                    replay::appendPreciseArray(out, f.states[i]);
                }
                // per frame, every body's pose one after the other: 7 numbers a body
                out += "],\"poses\":[";
                for (std::size_t i = 0; i < f.states.size(); ++i)
                {
                    out += i ? ",[" : "[";
                    const auto poses = robot.poses(f.states[i]);
                    for (std::size_t b = 0; b < poses.size(); ++b)
                    {
                        if (b)
                            out += ',';
                        replay::appendPoseValues(out, poses[b]);
                    }
                    out += ']';
                }
                return out + "]}";
            }

            /** The template with each "@MICHI_<NAME>@" replaced by its value. Placeholders are found in the
                template only, never in what was put in (a problem's name or a script could hold such text). */
            std::string fill(const std::string &text, const std::map<std::string, std::string> &values)
            {
                std::string out;
                std::size_t from = 0;
                std::size_t used = 0;
                // Searching the template only (from advances past each value put in): a value that holds "@MICHI_..."
                // itself, such as three.js or a problem's name, is never expanded again.
                for (std::size_t at = text.find("@MICHI_"); at != std::string::npos; at = text.find("@MICHI_", from))
                {
                    const std::size_t end = text.find('@', at + 1);
                    const auto it =
                        end == std::string::npos ? values.end() : values.find(text.substr(at, end + 1 - at));
                    if (it == values.end())
                        throw std::logic_error("replay page template: unknown placeholder at byte " +
                                               std::to_string(at));
                    out.append(text, from, at - from);
                    out += it->second;
                    from = end + 1;
                    ++used;
                }
                if (used != values.size())
                    throw std::logic_error("replay page template: a placeholder is missing");
                return out + text.substr(from);
            }
        }  // namespace

        std::string replayData(const Problem &problem, const std::vector<PlotPath> &paths, const ReplayOptions &options)
        {
            const std::size_t dimension = problem.dimension();
            for (const auto &path : paths)
                for (const auto &state : path.states)
                    if (state.size() != dimension)
                        throw std::invalid_argument("replay page of " + problem.name + ": path '" + path.label +
                                                    "' has a state of " + std::to_string(state.size()) +
                                                    " values, expected " + std::to_string(dimension));
            if (!(options.duration > 0.))
                throw std::invalid_argument("replay page: duration must be positive");
            if (!options.times.empty() && options.times.size() != paths.size())
                throw std::invalid_argument("replay page of " + problem.name + ": times for " +
                                            std::to_string(options.times.size()) + " paths, but " +
                                            std::to_string(paths.size()) + " paths");
            const auto timed = [&](std::size_t i)
            {
                return !options.times.empty() && !options.times[i].empty();
            };
            for (std::size_t i = 0; i < paths.size(); ++i)
            {
                if (!timed(i))
                    continue;
                const auto &times = options.times[i];
                bool ordered = times.size() == paths[i].states.size();
                for (std::size_t k = 0; ordered && k < times.size(); ++k)
                    // The page plays a path by looking up the clock in these times: they must never run backwards.
                    ordered = std::isfinite(times[k]) && times[k] >= 0. && (k == 0 || times[k] >= times[k - 1]);
                if (!ordered)
                    throw std::invalid_argument("replay page of " + problem.name + ": path '" + paths[i].label +
                                                "' needs one finite, non-negative, non-decreasing time per state (" +
                                                std::to_string(paths[i].states.size()) + " states, " +
                                                std::to_string(times.size()) + " times)");
            }
            const ob::StateSpacePtr space = makeStateSpace(problem);
            space->setup();
            double longest = 0.;
            for (std::size_t i = 0; i < paths.size(); ++i)
                if (!timed(i))
                    longest = std::max(longest, pathLength(space, paths[i].states));
            // Timed paths (replan's executed motion) keep their own clock and do not set the common speed.
            const double speed = longest > 0. ? longest / options.duration : 1.;

            replay::ShapeTable shapes;
            const replay::RobotBodies robot(problem, shapes, options.fixedValues);
            std::string map;
            // One shape table for obstacles and robot: a shape both use (or many links share) is written once.
            const std::string obstacles =
                obstaclesJson(problem, options.scene ? *options.scene : *problem.scene, shapes, map);
            const std::string fixedParts = robot.staticPartsJson(shapes);
            std::string pathsJson = "[";
            for (std::size_t i = 0; i < paths.size(); ++i)
            {
                const auto &path = paths[i];
                if (path.states.empty())
                    continue;
                if (pathsJson.size() > 1)
                    pathsJson += ',';
                pathsJson += pathJson(path,
                                      timed(i) ? timedPath(path.states, options.times[i])
                                               : cutPath(space, path.states, speed, options.frames),
                                      robot);
            }
            pathsJson += "]";

            std::string out = std::string("{") + REPLAY_PAGE_MARK + ",\"problem\":" + jsonString(problem.name) +
                              ",\"kind\":" + (problem.kind == Problem::Kind::SE2 ? "\"se2\"" : "\"arm\"") +
                              ",\"description\":" + jsonString(problem.description) + ",\"valueNames\":[";
            const auto names = problem.valueNames();
            for (std::size_t i = 0; i < names.size(); ++i)
                out += (i ? "," : "") + jsonString(names[i]);
            out += "],\"shapes\":" + shapes.json() + ",\"obstacles\":" + obstacles + ",\"map\":" + map +
                   ",\"fixedParts\":" + fixedParts + ",\"bodies\":" + robot.bodiesJson() +
                   ",\"endBody\":" + std::to_string(robot.endBody()) +
                   ",\"planar\":" + (robot.planar() ? "true" : "false") + ",\"paths\":" + pathsJson + "}";
            // '<' only occurs inside JSON strings, where \u003c means the same: no "</script>" can end the block
            std::string safe;
            safe.reserve(out.size());
            for (char c : out)
                safe += c == '<' ? std::string("\\u003c") : std::string(1, c);
            return safe;
        }

        std::string replayPage(const Problem &problem, const std::vector<PlotPath> &paths, const ReplayOptions &options)
        {
            using namespace replay_assets;
            std::string title;
            // The title is HTML text: a name with '<' or '&' must not open a tag or an entity.
            for (char c : problem.name)
                title += c == '<' ? "&lt;" : c == '&' ? "&amp;" : std::string(1, c);
            return fill(std::string(PAGE_HTML, PAGE_HTML_SIZE),
                        {{"@MICHI_TITLE@", title},
                         {"@MICHI_DATA@", replayData(problem, paths, options)},
                         {"@MICHI_PAGE_JS@", std::string(PAGE_JS, PAGE_JS_SIZE)},
                         {"@MICHI_ORBIT_CONTROLS_JS@", std::string(ORBIT_CONTROLS_JS, ORBIT_CONTROLS_JS_SIZE)},
                         {"@MICHI_THREE_JS@", std::string(THREE_JS, THREE_JS_SIZE)}});
        }

        void writeReplayPage(const Problem &problem, const std::vector<PlotPath> &paths, const std::string &file,
                             const ReplayOptions &options)
        {
            writeAtomically(replayPage(problem, paths, options), file);
        }
    }  // namespace tools
}  // namespace michi
