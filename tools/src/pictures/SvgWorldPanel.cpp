#include "SvgPanels.h"

#include <cmath>

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
            namespace
            {
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
                        // At most MAX_KEY_FRAMES outlines per moving obstacle, first and last included: a long
                        // trajectory would otherwise paint over the whole panel.
                        for (std::size_t i : spreadIndices(obstacle.trajectory.size(), MAX_KEY_FRAMES))
                            v.keyFrames.push_back(obstacle.shape->footprint(view * obstacle.trajectory[i].pose));
                    }
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
            }  // namespace

            WorldView buildWorldView(const Problem &problem, const validity::Scene *scene, const RobotGeometry &robot,
                                     const std::vector<SampledPath> &paths, const Query *query,
                                     const Eigen::Isometry3d &view)
            {
                WorldView v;
                addScene(scene, view, v);
                // Links no planned joint moves look the same in every state: any values place them.
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
                // Start and goal last, so they stay visible on top of every path.
                if (v.start)
                    drawRobotSolid(svg, t, *v.start, "start", START_COLOUR);
                if (v.goal)
                    drawRobotSolid(svg, t, *v.goal, "goal", GOAL_COLOUR);
                closePanel(svg);
            }
        }  // namespace svg_plot
    }      // namespace tools
}  // namespace michi
