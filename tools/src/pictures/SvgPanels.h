#ifndef MICHI_TOOLS_SRC_SVG_PANELS_
#define MICHI_TOOLS_SRC_SVG_PANELS_

// Private to michi_tools (not installed): the pieces of writeProblemSvg() (SvgPlot.cpp): its style, the paths
// sampled for drawing (SvgPaths.cpp), the panel frame and drawing primitives (SvgPanel.cpp), the world panels
// (SvgWorldPanel.cpp) and the configuration space panel (SvgConfigPanel.cpp).

#include "SvgRobot.h"
#include "SvgView.h"
#include "SvgWriter.h"

#include <michi/tools/problem/Problem.h>
#include <michi/tools/pictures/SvgPlot.h>

#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
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

            // ---------------------------------------------------------------- paths (SvgPaths.cpp)

            /** One path, sampled once for every panel. */
            struct SampledPath
            {
                std::string label;
                std::string colour;
                std::vector<Values> poses;   ///< robot drawn here
                std::vector<Values> dense;   ///< for the traces
                std::vector<Values> states;  ///< the path's own states
            };

            void checkValues(const Values &values, std::size_t dimension, const std::string &what);

            std::vector<SampledPath> samplePaths(const std::vector<PlotPath> &paths, const RobotGeometry &robot,
                                                 std::size_t dimension);

            // ---------------------------------------------------------------- panel frame and drawing (SvgPanel.cpp)

            /** Panel frame, grid, ticks with labels and axis names; opens the clipped group of the content. */
            void openPanel(SvgWriter &svg, const std::string &id, const std::string &title, const ViewTransform &t,
                           const std::string &xLabel, const std::string &yLabel);

            void closePanel(SvgWriter &svg);

            /** Shapes as one path element (one element for thousands of map cells keeps the file small). */
            void drawShapes(SvgWriter &svg, const ViewTransform &t, const std::vector<MultiPolygon2> &shapes,
                            Attributes attributes);

            void drawPolyline(SvgWriter &svg, const ViewTransform &t, const Polyline &line, Attributes attributes);

            void drawDot(SvgWriter &svg, double x, double y, double radius, const std::string &colour,
                         Attributes attributes = {});

            // ---------------------------------------------------------------- world panels (SvgWorldPanel.cpp)

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

            /** \e scene: the obstacles drawn (the problem's, or a picture's own: PictureOverride) */
            WorldView buildWorldView(const Problem &problem, const validity::Scene *scene, const RobotGeometry &robot,
                                     const std::vector<SampledPath> &paths, const Query *query,
                                     const Eigen::Isometry3d &view);

            void drawWorldPanel(SvgWriter &svg, const WorldView &v, const ViewTransform &t,
                                const std::vector<SampledPath> &paths);

            // ---------------------------------------------------------------- configuration space panel
            // (SvgConfigPanel.cpp)

            struct ConfigView
            {
                Extent limits;
                std::string xLabel, yLabel;
                std::vector<bool> wraps;
                std::optional<Vec2> start, goal;
                /** the J-map's polygons (paper 000) of a two-joint arm: the configuration-space obstacles the
                    planners went round; empty when the map cannot be made (then only the limits are drawn) */
                MultiPolygon2 jmap;
            };

            /** \e jmap false: no J-map polygons (a picture of another scene than the problem's) */
            ConfigView buildConfigView(const Problem &problem, const RobotGeometry &robot,
                                       const std::vector<SampledPath> &paths, const Query *query, bool jmap = true);

            void drawConfigPanel(SvgWriter &svg, const ConfigView &c, const ViewTransform &t,
                                 const std::vector<SampledPath> &paths);
        }  // namespace svg_plot
    }      // namespace tools
}  // namespace michi

#endif
