#include "SvgPanels.h"

#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/ProblemJMap.h>

#include <cmath>
#include <exception>

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
            namespace
            {
                /** Value \e v moved into [lower, lower + 2 pi) when it wraps. */
                double normalised(double v, double lower, bool wraps)
                {
                    if (!wraps)
                        return v;
                    const double shifted = std::fmod(v - lower, 2. * M_PI);
                    return lower + (shifted < 0. ? shifted + 2. * M_PI : shifted);
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
                            // A jump of more than half a turn is the path crossing the wrap (it moves the short way):
                            // start a new piece, or the line would cut across the whole panel.
                            if ((c.wraps[0] && jump.x() > M_PI) || (c.wraps[1] && jump.y() > M_PI))
                                pieces.emplace_back();
                        }
                        pieces.back().push_back(p);
                    }
                    return pieces;
                }

                /** The J-map polygons of a two-joint arm problem, built with the problem's collision.jmap settings;
                    none when the map cannot be made (e.g. a robot the J-map does not model). */
                MultiPolygon2 jmapPolygons(const Problem &problem)
                {
                    try
                    {
                        ContextOptions options;
                        options.checker = "fcl";  // the problem's own checker is not needed: the map is built here
                        const PlanningContext ctx = makePlanningContext(problem, options);
                        return makeJMapChecker(problem, ctx, problem.jmap)->unitedPolygons();
                    }
                    // A picture without the J-map beats no picture: the panel then shows the joint limits only.
                    catch (const std::exception &)
                    {
                        return {};
                    }
                }
            }  // namespace

            ConfigView buildConfigView(const Problem &problem, const RobotGeometry &robot,
                                       const std::vector<SampledPath> &paths, const Query *query, bool jmap)
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
                        // Half a unit of room around the data, so the states do not sit on the frame.
                        lower[i] = e.empty() ? -1. : e.xMin - 0.5;
                        upper[i] = e.empty() ? 1. : e.xMax + 0.5;
                    }
                    const bool prismatic = joint.type == validity::RobotJoint::Type::PRISMATIC;
                    (i == 0 ? c.xLabel : c.yLabel) = names[i] + (prismatic ? " [m]" : " [rad]");
                }
                c.limits.add(lower[0], lower[1]);
                c.limits.add(upper[0], upper[1]);
                if (jmap)
                    c.jmap = jmapPolygons(problem);
                if (query)
                {
                    c.start = Vec2(normalised(query->start[0], lower[0], c.wraps[0]),
                                   normalised(query->start[1], lower[1], c.wraps[1]));
                    c.goal = Vec2(normalised(query->goal[0], lower[0], c.wraps[0]),
                                  normalised(query->goal[1], lower[1], c.wraps[1]));
                }
                return c;
            }

            void drawConfigPanel(SvgWriter &svg, const ConfigView &c, const ViewTransform &t,
                                 const std::vector<SampledPath> &paths)
            {
                openPanel(svg, "cspace",
                          c.jmap.empty() ? "configuration space (joint limits)"
                                         : "configuration space: J-map polygons (collisions, conservative)",
                          t, c.xLabel, c.yLabel);
                if (!c.jmap.empty())
                    drawShapes(svg, t, {c.jmap}, {{"class", "jmap"}, {"fill", "#3b6fb6"}, {"fill-opacity", "0.45"}});
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
        }  // namespace svg_plot
    }      // namespace tools
}  // namespace michi
