/* `michi lattice`: node counts and timings of the heading-constrained lattice (paper 003) and its pictures. */

#include <michi/tools/commands/HeadingLatticeReport.h>

#include <michi/planners/heading_lattice/HeadingLattice.h>
#include <michi/tools/FileOutput.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/pictures/SvgPlot.h>
#include <michi/tools/viewer/ReplayPage.h>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/Time.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace ob = ompl::base;

namespace michi
{
    namespace tools
    {
        namespace
        {
            std::string num(double v, const char *format = "%.4g")
            {
                char buffer[48];
                std::snprintf(buffer, sizeof(buffer), format, v);
                return buffer;
            }

            /** A colour per heading index, around the hue circle. */
            std::string headingColour(unsigned int k, unsigned int count)
            {
                // Hue follows heading, so neighbouring headings get neighbouring colours and the circle of hues reads
                // as the turn.
                const double h = 360. * k / std::max(1u, count);
                return "hsl(" + num(h, "%.0f") + ",70%,42%)";
            }

            std::vector<std::vector<double>> pathValues(const ompl::geometric::PathGeometric &path)
            {
                std::vector<std::vector<double>> values;
                for (std::size_t i = 0; i < path.getStateCount(); ++i)
                {
                    std::vector<double> v;
                    path.getSpaceInformation()->getStateSpace()->copyToReals(v, path.getState(i));
                    values.push_back(v);
                }
                return values;
            }

            /** An SVG of the window [x0, x1] x [y0, y1] of the map (y up), obstacles drawn; add() appends. */
            class WindowSvg
            {
            public:
                WindowSvg(const Problem &problem, double x0, double y0, double x1, double y1, const std::string &title)
                    // 640 px along the longer side, whatever the window; y is flipped (SVG's y points down, the map's
                    // up).
                    : x0_(x0), y1_(y1), scale_(640. / std::max(x1 - x0, y1 - y0))
                {
                    const double w = (x1 - x0) * scale_, h = (y1 - y0) * scale_;
                    out_ << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(w + 20) << "\" height=\""
                         << num(h + 50) << "\" font-family=\"sans-serif\">\n"
                         << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
                         << "<text x=\"10\" y=\"22\" font-size=\"12\">" << title << "</text>\n"
                         << "<svg x=\"10\" y=\"36\" width=\"" << num(w) << "\" height=\"" << num(h) << "\">\n"
                         << "<rect width=\"100%\" height=\"100%\" fill=\"#fafafa\" stroke=\"#999\"/>\n";
                    for (const auto &polygon : problem.scene->polygons2d())
                    {
                        out_ << "<path fill=\"#9a9a9a\" fill-rule=\"evenodd\" d=\"";
                        ring(polygon.outer());
                        for (const auto &inner : polygon.inners())
                            ring(inner);
                        out_ << "\"/>\n";
                    }
                }
                double sx(double x) const
                {
                    return (x - x0_) * scale_;
                }
                double sy(double y) const
                {
                    return (y1_ - y) * scale_;
                }
                double scale() const
                {
                    return scale_;
                }
                void line(double ax, double ay, double bx, double by, const std::string &style)
                {
                    out_ << "<line x1=\"" << num(sx(ax)) << "\" y1=\"" << num(sy(ay)) << "\" x2=\"" << num(sx(bx))
                         << "\" y2=\"" << num(sy(by)) << "\" " << style << "/>\n";
                }
                void circle(double x, double y, double r, const std::string &style)
                {
                    out_ << "<circle cx=\"" << num(sx(x)) << "\" cy=\"" << num(sy(y)) << "\" r=\"" << num(r) << "\" "
                         << style << "/>\n";
                }
                /** A node: a dot with a short stroke along its heading. */
                void arrow(double x, double y, double yaw, double length, const std::string &colour)
                {
                    line(x, y, x + length * std::cos(yaw), y + length * std::sin(yaw),
                         "stroke=\"" + colour + "\" stroke-width=\"1.4\"");
                    circle(x, y, 2., "fill=\"" + colour + "\"");
                }
                void footprint(const std::vector<Eigen::Vector2d> &outline, double x, double y, double yaw,
                               const std::string &style)
                {
                    out_ << "<polygon points=\"";
                    for (const auto &p : outline)
                    {
                        const double px = x + std::cos(yaw) * p.x() - std::sin(yaw) * p.y();
                        const double py = y + std::sin(yaw) * p.x() + std::cos(yaw) * p.y();
                        out_ << num(sx(px)) << "," << num(sy(py)) << " ";
                    }
                    out_ << "\" " << style << "/>\n";
                }
                void polyline(const std::vector<std::vector<double>> &states, const std::string &style)
                {
                    out_ << "<polyline fill=\"none\" points=\"";
                    for (const auto &s : states)
                        out_ << num(sx(s[0])) << "," << num(sy(s[1])) << " ";
                    out_ << "\" " << style << "/>\n";
                }
                void legend(const std::vector<std::pair<std::string, std::string>> &entries)
                {
                    out_ << "</svg>\n";
                    double x = 10.;
                    for (const auto &e : entries)
                    {
                        out_ << "<rect x=\"" << num(x) << "\" y=\"28\" width=\"10\" height=\"4\" fill=\"" << e.second
                             << "\"/><text x=\"" << num(x + 14) << "\" y=\"33\" font-size=\"10\">" << e.first
                             << "</text>\n";
                        x += 20. + 6. * e.first.size();
                    }
                }
                std::string finish()
                {
                    out_ << "</svg>\n";
                    return out_.str();
                }

            private:
                template <typename Ring>
                void ring(const Ring &r)
                {
                    for (std::size_t i = 0; i < r.size(); ++i)
                        out_ << (i ? " L" : " M") << num(sx(r[i].x())) << " " << num(sy(r[i].y()));
                    out_ << " Z";
                }
                double x0_, y1_, scale_;
                std::ostringstream out_;
            };

            struct Row
            {
                double cell, angle;
                unsigned int headings{0};
                std::size_t nodes{0}, edges{0};
                double build{0.}, first{0.}, second{0.}, length{0.};
                std::uint64_t checks1{0}, checks2{0};  ///< node + edge + join checks of query 0 and the next
                bool solved{false}, reused{false}, solved2{false};
            };

            /** Where the (corrected) path first turns in place; else its middle state. */
            std::vector<double> firstTurn(const std::vector<std::vector<double>> &path)
            {
                for (std::size_t i = 0; i + 1 < path.size(); ++i)
                    // A turn in place (same position, another yaw) is where the correction shows: the window is centred
                    // there.
                    if (std::hypot(path[i][0] - path[i + 1][0], path[i][1] - path[i + 1][1]) < 1e-9 &&
                        std::abs(path[i][2] - path[i + 1][2]) > 1e-6)
                        return path[i];
                return path[path.size() / 2];
            }

            void writePictures(const Problem &problem, const planners::HeadingLattice &lattice,
                               const std::vector<std::vector<double>> &path, const std::string &dir, double cell)
            {
                const auto turn = firstTurn(path);
                const double half = std::max(1.2, 6. * cell);
                const double x0 = turn[0] - half, x1 = turn[0] + half, y0 = turn[1] - half, y1 = turn[1] + half;
                const auto &nodes = lattice.nodes();
                const unsigned int K = lattice.getHeadingCount();
                const double step = lattice.getHeadingStep();
                auto inside = [&](double x, double y)
                {
                    return x >= x0 && x <= x1 && y >= y0 && y <= y1;
                };
                std::vector<std::pair<std::string, std::string>> legend;
                for (unsigned int k = 0; k < K; k += std::max(1u, K / 4))
                    legend.emplace_back("heading " + num(k * step * 180. / M_PI, "%.1f") + " deg", headingColour(k, K));
                const std::string where = " around (" + num(turn[0], "%.2f") + ", " + num(turn[1], "%.2f") +
                                          "), cell_size " + num(cell) + " m";

                {  // Fig. 1: the nodes of every heading, and the drives between them
                    WindowSvg svg(problem, x0, y0, x1, y1, "Lattice nodes and drives per heading" + where);
                    for (const auto &e : lattice.latticeEdges())
                    {
                        const auto &a = nodes[e.first], &b = nodes[e.second];
                        if (a.group != b.group && e.first < e.second && inside(a.x, a.y) && inside(b.x, b.y))
                            svg.line(a.x, a.y, b.x, b.y,
                                     "stroke=\"" + headingColour(a.heading, K) + "\" stroke-opacity=\"0.35\"");
                    }
                    for (const auto &n : nodes)
                        if (inside(n.x, n.y))
                            svg.arrow(n.x, n.y, n.heading * step, 0.35 * cell, headingColour(n.heading, K));
                    svg.legend(legend);
                    writeAtomically(svg.finish(), (boost::filesystem::path(dir) / "lattice.svg").string());
                }
                {  // the groups: every node joined to the heading-0 grid point of its group
                    WindowSvg svg(problem, x0, y0, x1, y1, "Groups: each node to its heading-0 grid point" + where);
                    const auto &b = problem.se2Bounds;
                    for (const auto &n : nodes)
                    {
                        if (!inside(n.x, n.y))
                            continue;
                        // the group's grid point (i, j) is at the space's lower bounds + (i, j) * cell_size
                        const double rows = std::floor((b[3] - b[2]) / cell + 1e-9) + 1.;
                        const double gi = std::floor(n.group / rows), gj = n.group - gi * rows;
                        const double gx = b[0] + gi * cell, gy = b[2] + gj * cell;
                        svg.line(gx, gy, n.x, n.y,
                                 "stroke=\"" + headingColour(n.heading, K) + "\" stroke-width=\"1.2\"");
                        svg.circle(gx, gy, std::max(1.5, 0.08 * cell * svg.scale()),
                                   "fill=\"none\" stroke=\"#333\" stroke-width=\"0.8\"");
                        svg.arrow(n.x, n.y, n.heading * step, 0.2 * cell, headingColour(n.heading, K));
                    }
                    svg.legend(legend);
                    writeAtomically(svg.finish(), (boost::filesystem::path(dir) / "groups.svg").string());
                }
                {  // Figs. 2-3: the path on the nodes, and corrected
                    WindowSvg svg(problem, x0, y0, x1, y1, "Path on the nodes (Fig. 2) and corrected (Fig. 3)" + where);
                    const auto &raw = lattice.rawPath();
                    for (std::size_t i = 0; i < path.size(); ++i)
                        if (i + 1 == path.size() ||
                            std::hypot(path[i][0] - path[i + 1][0], path[i][1] - path[i + 1][1]) < 1e-9)
                            svg.footprint(
                                problem.footprint, path[i][0], path[i][1], path[i][2],
                                "fill=\"#1f77b4\" fill-opacity=\"0.06\" stroke=\"#1f77b4\" stroke-width=\"0.6\"");
                    svg.polyline(raw, "stroke=\"#d62728\" stroke-width=\"2\" stroke-dasharray=\"5,3\"");
                    for (const auto &s : raw)
                        svg.arrow(s[0], s[1], s[2], 0.3 * cell, "#d62728");
                    svg.polyline(path, "stroke=\"#1f77b4\" stroke-width=\"2\"");
                    for (const auto &s : path)
                        svg.arrow(s[0], s[1], s[2], 0.3 * cell, "#1f77b4");
                    // with the planner's shortcut on (its default) the returned path is corrected and then
                    // shortened; `shortcut: 0` in the problem's HeadingLattice parameters shows the correction alone
                    svg.legend(
                        {{"path on the lattice nodes", "#d62728"},
                         {lattice.getShortcut() ? "returned path: corrected, then shortened (footprint at each turn)"
                                                : "corrected path (footprint at each turn)",
                          "#1f77b4"}});
                    writeAtomically(svg.finish(), (boost::filesystem::path(dir) / "correction.svg").string());
                }
                // Fig. 4: the robot along the whole path
                writeProblemSvg(problem, {PlotPath{"michi::HeadingLattice", path}},
                                (boost::filesystem::path(dir) / "path.svg").string());
            }
        }  // namespace

        std::vector<double> parseNumberList(const std::string &text, const std::string &option)
        {
            std::vector<double> values;
            std::stringstream in(text);
            for (std::string item; std::getline(in, item, ',');)
            {
                std::size_t used = 0;
                double v = 0.;
                try
                {
                    v = std::stod(item, &used);
                }
                catch (const std::exception &)
                {
                }
                if (used == 0 || used != item.size() || !(v > 0.))
                    throw std::invalid_argument(option + " expects positive numbers separated by commas, got '" + text +
                                                "'");
                values.push_back(v);
            }
            if (values.empty())
                throw std::invalid_argument(option + " expects positive numbers separated by commas, got '" + text +
                                            "'");
            return values;
        }

        std::string runHeadingLatticeReport(const Problem &problem, const HeadingLatticeReportOptions &options)
        {
            if (problem.kind != Problem::Kind::SE2)
                throw ProblemError(problem.file, "robot", "michi lattice needs an SE2 robot (robot.type: se2)");
            for (double a : options.angleSteps)
                // At most pi/2: the planner rounds the step so that a whole number K >= 4 of steps makes a full turn.
                if (!(a > 0.) || a > M_PI / 2. + 1e-9)
                    throw std::invalid_argument("--angle-steps: " + num(a) + " is outside (0, pi/2]");
            for (double c : options.cellSizes)
                if (!(c > 0.))
                    throw std::invalid_argument("--cell-sizes: " + num(c) + " is not positive");
            // staged output: nothing in DIR unless every setting ran (a later setting that fails left the first
            // one's pictures behind)
            StagedDirectory stage(options.outDir);
            const std::string outDir = stage.path("").string();
            std::vector<Row> rows;
            bool drawn = !options.pictures;
            bool paged = !options.html;  // the replay page shows the first solved configuration's path
            for (double cell : options.cellSizes)
                for (double angle : options.angleSteps)
                {
                    Row row;
                    row.cell = cell;
                    row.angle = angle;
                    // A fresh context and planner per row: no row reuses another's lattice, so every build time is a
                    // full build.
                    auto ctx = makePlanningContext(problem, 0);
                    auto si = ctx.setup->getSpaceInformation();
                    auto planner = std::make_shared<planners::HeadingLattice>(si);
                    // the problem's other settings of the planner (heuristic_weight, connection_cells), as bench
                    // would set them; cell_size and angle_step are the rows of the table
                    for (const auto &spec : problem.planners)
                        if (spec.name == "michi::HeadingLattice")
                            for (const auto &kv : spec.params)
                                if (kv.first != "cell_size" && kv.first != "angle_step" &&
                                    !planner->params().setParam(kv.first, kv.second))
                                    throw ProblemError(problem.file, "planners",
                                                       "michi::HeadingLattice refuses " + kv.first + " = " + kv.second);
                    planner->setCellSize(cell);
                    planner->setAngleStep(angle);
                    ctx.setup->setPlanner(planner);
                    ctx.setup->setup();
                    auto started = ompl::time::now();
                    auto status = planner->solve(ob::timedPlannerTerminationCondition(options.timeLimit));
                    // solve() includes building the lattice: the table reports the search as this time minus
                    // lastBuildTime().
                    row.first = ompl::time::seconds(ompl::time::now() - started);
                    auto checks = [&]
                    {
                        const auto &w = planner->work();
                        return w.nodeChecks + w.edgeChecks + w.queryChecks;
                    };
                    row.checks1 = checks();
                    row.build = planner->lastBuildTime();
                    row.headings = planner->getHeadingCount();
                    row.nodes = planner->nodes().size();
                    row.edges = planner->latticeEdges().size();
                    row.solved = status == ob::PlannerStatus::EXACT_SOLUTION;
                    std::vector<std::vector<double>> path;
                    if (row.solved)
                    {
                        auto solution = ctx.setup->getProblemDefinition()->getSolutionPath();
                        row.length = solution->length();
                        path = pathValues(*solution->as<ompl::geometric::PathGeometric>());
                        if (!drawn)
                        {
                            writePictures(problem, *planner, path, outDir, cell);
                            drawn = true;
                        }
                        if (!paged)
                        {
                            writeReplayPage(problem, {PlotPath{"michi::HeadingLattice", path}},
                                            stage.path(problem.name + ".html").string());
                            paged = true;
                        }
                    }
                    // the next query on the kept graph: query 1 if there is one, else query 0 again
                    // A second query on the same planner shows the multi-query case: the lattice is kept, and only the
                    // search (and its heuristic) is redone. reused says whether it really was.
                    const std::size_t next = problem.queries.size() > 1 ? 1 : 0;
                    makePlanningContext(problem, next);  // checks the query's start and goal
                    const unsigned int builds = planner->buildCount();
                    auto pdef = std::make_shared<ob::ProblemDefinition>(si);
                    ob::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
                    si->getStateSpace()->copyFromReals(start.get(), problem.queries[next].start);
                    si->getStateSpace()->copyFromReals(goal.get(), problem.queries[next].goal);
                    // Wraps the yaw into [-pi, pi) as the space stores it.
                    si->enforceBounds(start.get());
                    si->enforceBounds(goal.get());
                    pdef->setStartAndGoalStates(start, goal);
                    planner->setProblemDefinition(pdef);
                    started = ompl::time::now();
                    status = planner->solve(ob::timedPlannerTerminationCondition(options.timeLimit));
                    row.second = ompl::time::seconds(ompl::time::now() - started);
                    row.checks2 = checks() - row.checks1;
                    row.solved2 = status == ob::PlannerStatus::EXACT_SOLUTION;
                    row.reused = planner->buildCount() == builds;
                    rows.push_back(row);
                    if (options.progress)
                        *options.progress << "michi lattice: cell_size " << cell << ", angle_step " << angle << ": "
                                          << row.nodes << " nodes, build " << row.build << " s, query 0 "
                                          << row.first - row.build << " s, query " << next << " " << row.second << " s"
                                          << std::endl;
                }

            std::ostringstream md;
            const int next = problem.queries.size() > 1 ? 1 : 0;
            md << "| cell_size (m) | angle_step (deg) | headings | free nodes | edges | build (s) | query 0 search (s) "
                  "| "
                  "query 0 checks | query "
               << next << " on the kept lattice (s) | query " << next
               << " checks | solved | path length "
                  "|\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|\n";
            for (const auto &r : rows)
                md << "| " << num(r.cell) << " | " << num(r.angle * 180. / M_PI, "%.2f") << " | " << r.headings << " | "
                   << r.nodes << " | " << r.edges << " | " << num(r.build, "%.4f") << " | "
                   << num(r.first - r.build, "%.4f") << " | " << r.checks1 << " | " << num(r.second, "%.4f")
                   << (r.reused ? "" : " (rebuilt)") << " | " << r.checks2 << " | " << (r.solved ? "yes" : "no")
                   << " / " << (r.solved2 ? "yes" : "no") << " | "
                   << (r.solved ? num(r.length, "%.3f") : std::string("-")) << " |\n";
            writeAtomically(md.str(), stage.path("lattice.md").string());
            stage.commit();
            return md.str();
        }
    }  // namespace tools
}  // namespace michi
