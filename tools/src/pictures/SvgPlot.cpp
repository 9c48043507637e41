#include <michi/tools/pictures/SvgPlot.h>
#include <michi/tools/FileOutput.h>

#include "SvgPanels.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
            namespace
            {
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

                /** World to side view: x stays, z becomes the view's y (seen from -y). */
                Eigen::Isometry3d sideView()
                {
                    Eigen::Isometry3d view = Eigen::Isometry3d::Identity();
                    // Rows: view x = world x, view y = world z, view z = -world y; a proper rotation, so nothing is
                    // mirrored.
                    view.linear() << 1., 0., 0., 0., 0., 1., 0., -1., 0.;
                    return view;
                }

                /** The query to draw (checked), or none when the problem has no queries. */
                const Query *chosenQuery(const Problem &problem, std::size_t query)
                {
                    if (problem.queries.empty())
                        return nullptr;
                    if (query >= problem.queries.size())
                        throw std::out_of_range("query " + std::to_string(query) + ": problem '" + problem.name +
                                                "' has " + std::to_string(problem.queries.size()) + " queries");
                    const Query &q = problem.queries[query];
                    checkValues(q.start, problem.dimension(), "start of query " + std::to_string(query));
                    checkValues(q.goal, problem.dimension(), "goal of query " + std::to_string(query));
                    return &q;
                }

                /** The top view, and the side view for robots that leave the x-y plane. */
                std::vector<WorldView> buildWorldViews(const Problem &problem, const validity::Scene *scene,
                                                       const RobotGeometry &robot,
                                                       const std::vector<SampledPath> &paths, const Query *query)
                {
                    std::vector<WorldView> views;
                    views.push_back(buildWorldView(problem, scene, robot, paths, query, Eigen::Isometry3d::Identity()));
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
                        views.push_back(buildWorldView(problem, scene, robot, paths, query, sideView()));
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
                    // One scale for every world panel: a metre is as long in the side view as in the top view.
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
                        // The configuration panel is square and as tall as the world panels, within bounds: its axes
                        // are radians, not metres, so it cannot share their scale.
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
                    subtitle += ", " + std::to_string(pathCount) + " path(s), robot drawn at " +
                                std::to_string(POSES_PER_PATH) + " poses per path, trace: " +
                                (problem.kind == Problem::Kind::SE2 ? "x, y" : "end link origin");
                    svg.text(MARGIN_LEFT, 48., subtitle, {{"fill", "#555"}});
                }
            }  // namespace
        }      // namespace svg_plot

        void writeProblemSvg(const Problem &problem, const std::vector<PlotPath> &paths, const std::string &file,
                             std::size_t query, const PictureOverride &override)
        {
            using namespace svg_plot;  // the pieces of the picture (SvgPanels.h)
            const Query *q = override.query;
            if (q)
            {
                checkValues(q->start, problem.dimension(), "start of the picture's query");
                checkValues(q->goal, problem.dimension(), "goal of the picture's query");
            }
            else
                q = chosenQuery(problem, query);
            const validity::Scene *scene = override.scene ? override.scene.get() : problem.scene.get();
            const RobotGeometry robot(problem);
            const std::vector<SampledPath> sampled = samplePaths(paths, robot, problem.dimension());
            const std::vector<WorldView> views = buildWorldViews(problem, scene, robot, sampled, q);
            std::optional<ConfigView> config;
            // A configuration-space panel only for two planned joints: the plane of (theta1, theta2), as in the J-map
            // (the problem's J-map: none for a picture of another scene).
            if (problem.kind == Problem::Kind::ARM && problem.dimension() == 2)
                config = buildConfigView(problem, robot, sampled, q, !override.scene);
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
            // Rendered to a temporary file and renamed: a failed or interrupted rsvg-convert never leaves a broken PNG
            // behind.
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
