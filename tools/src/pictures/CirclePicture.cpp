/* SVG picture of a concentric-circle search (paper 000, Fig. 5). */

#include <michi/tools/pictures/CirclePicture.h>
#include <michi/tools/FileOutput.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace michi
{
    namespace tools
    {
        namespace
        {
            std::string num(double v)
            {
                char buffer[32];
                std::snprintf(buffer, sizeof(buffer), "%.1f", v);
                return buffer;
            }
        }  // namespace

        void writeCircleSvg(const planners::ConcentricCircle::Stage &stage, const std::string &file,
                            const CirclePictureOptions &options)
        {
            const auto &map = *stage.map;
            const auto &search = *stage.search;
            const double left = 70., right = 200., top = 44., bottom = 50.;
            std::ostringstream svg0;
            const double w = options.width - left - right, h = options.height - top - bottom;
            // the plot covers the map's ranges and every circle
            Eigen::Vector2d lo = map.lo, hi = map.hi;
            for (const auto &ring : search.rings())
                for (const auto &p : ring.points)
                {
                    lo = lo.cwiseMin(p);
                    hi = hi.cwiseMax(p);
                }
            Eigen::Vector2d bgLo = map.lo, bgHi = map.hi;
            if (options.view.size() == 4)
            {
                lo = Eigen::Vector2d(options.view[0], options.view[1]);
                hi = Eigen::Vector2d(options.view[2], options.view[3]);
                bgLo = lo;
                bgHi = hi;
                svg0 << "<clipPath id=\"plot\"><rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << w
                     << "\" height=\"" << h << "\"/></clipPath>\n";
            }
            const double sx = w / std::max(hi.x() - lo.x(), 1e-9), sy = h / std::max(hi.y() - lo.y(), 1e-9);
            // One scale for both axes: circles stay circles and distances read the same in every direction.
            const double s = std::min(sx, sy);
            auto X = [&](double x)
            {
                return left + (x - lo.x()) * s;
            };
            auto Y = [&](double y)
            {
                return top + h - (y - lo.y()) * s;
            };
            std::ostringstream svg;
            svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << options.width << "\" height=\""
                << options.height << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
                << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
                << svg0.str() << "<g" << (options.view.size() == 4 ? " clip-path=\"url(#plot)\"" : "") << ">\n";
            if (!options.title.empty())
                svg << "<text x=\"" << left << "\" y=\"24\" font-size=\"15\">" << options.title << "</text>\n";
            // the map's range
            svg << "<rect x=\"" << num(X(map.lo.x())) << "\" y=\"" << num(Y(map.hi.y())) << "\" width=\""
                << num((map.hi.x() - map.lo.x()) * s) << "\" height=\"" << num((map.hi.y() - map.lo.y()) * s)
                << "\" fill=\"none\" stroke=\"#444\"/>\n";
            // obstacles: polygons of a J-map, else the map's point test on a grid
            if (const auto *poly = dynamic_cast<const planners::PolygonCircleMap *>(&map))
            {
                for (const auto &p : poly->obstacles())
                {
                    svg << "<path fill=\"#3b6fb6\" fill-opacity=\"0.45\" stroke=\"#1d3f73\" stroke-width=\"0.8\" d=\"";
                    auto ring = [&](const validity::Polygon2::ring_type &r)
                    {
                        for (std::size_t i = 0; i < r.size(); ++i)
                            svg << (i ? " L" : " M") << num(X(r[i].x())) << " " << num(Y(r[i].y()));
                        svg << " Z";
                    };
                    ring(p.outer());
                    for (const auto &in : p.inners())
                        ring(in);
                    svg << "\" fill-rule=\"evenodd\"/>\n";
                }
            }
            // Any other map answers only point queries: the picture samples it on an n x n grid.
            else if (options.background > 0)
            {
                const int n = options.background;
                const double cw = (bgHi.x() - bgLo.x()) / n, ch = (bgHi.y() - bgLo.y()) / n;
                // one rectangle per vertical run of blocked cells
                for (int i = 0; i < n; ++i)
                {
                    const double x = bgLo.x() + i * cw;
                    int runStart = -1;
                    for (int j = 0; j <= n; ++j)
                    {
                        const bool blocked =
                            j < n && !map.isFree(Eigen::Vector2d(x + 0.5 * cw, bgLo.y() + (j + 0.5) * ch));
                        if (blocked && runStart < 0)
                            runStart = j;
                        if (!blocked && runStart >= 0)
                        {
                            svg << "<rect x=\"" << num(X(x)) << "\" y=\"" << num(Y(bgLo.y() + j * ch)) << "\" width=\""
                                << num(cw * s + 0.6) << "\" height=\"" << num((j - runStart) * ch * s + 0.6)
                                << "\" fill=\"#3b6fb6\" fill-opacity=\"0.45\"/>\n";
                            runStart = -1;
                        }
                    }
                }
            }
            // circles and their points
            for (const auto &ring : search.rings())
            {
                svg << "<circle cx=\"" << num(X(ring.centre.x())) << "\" cy=\"" << num(Y(ring.centre.y())) << "\" r=\""
                    << num(ring.radius * s) << "\" fill=\"none\" stroke=\"#999\" stroke-width=\"0.4\""
                    << (ring.set > 0 ? " stroke-dasharray=\"2,2\"" : "") << "/>\n";
                for (std::size_t i = 0; i < ring.points.size(); ++i)
                    // Only blocked points are drawn: a circle's free points are most of them and would hide the
                    // picture.
                    if (!ring.free[i] && map.inRange(ring.points[i]))
                        svg << "<circle cx=\"" << num(X(ring.points[i].x())) << "\" cy=\"" << num(Y(ring.points[i].y()))
                            << "\" r=\"1\" fill=\"#d62728\"/>\n";
            }
            // links
            const auto &nodes = search.nodes();
            for (const auto &l : search.links())
            {
                // On a wrapping axis the link goes to the other node's copy nearest a, the way the search joined them,
                // not across the whole plot.
                const Eigen::Vector2d a = nodes[l.first].p, b = search.image(a, nodes[l.second].p);
                svg << "<line x1=\"" << num(X(a.x())) << "\" y1=\"" << num(Y(a.y())) << "\" x2=\"" << num(X(b.x()))
                    << "\" y2=\"" << num(Y(b.y())) << "\" stroke=\"#2ca02c\" stroke-width=\"0.7\"/>\n";
            }
            // paths
            std::vector<std::size_t> order;
            for (std::size_t i = 0; i < search.paths().size(); ++i)
                if (static_cast<int>(i) != stage.chosenPath)
                    order.push_back(i);
            if (stage.chosenPath >= 0 && stage.chosenPath < static_cast<int>(search.paths().size()))
                order.push_back(stage.chosenPath);  // drawn last, on top
            for (const std::size_t i : order)
            {
                const bool chosen = static_cast<int>(i) == stage.chosenPath;
                svg << "<polyline fill=\"none\" stroke=\"" << (chosen ? "#9467bd" : "#ff7f0e") << "\" stroke-width=\""
                    << (chosen ? 3.2 : 1.4) << "\" points=\"";
                for (const auto &p : search.pathPoints(i))
                    svg << num(X(p.x())) << "," << num(Y(p.y())) << " ";
                svg << "\"/>\n";
            }
            // candidates: black, or green / red when linked to the start / the goal while no path exists
            // While no path exists, colouring the candidates by whom they reach shows where the start's and the goal's
            // sides fail to meet.
            const bool joined = !search.paths().empty();
            const auto fromStart = search.component(0), toGoal = search.component(1);
            for (std::size_t v = 2; v < nodes.size(); ++v)
                svg << "<circle cx=\"" << num(X(nodes[v].p.x())) << "\" cy=\"" << num(Y(nodes[v].p.y()))
                    << "\" r=\"2.2\" fill=\""
                    << (joined         ? "#111"
                        : fromStart[v] ? "#2ca02c"
                        : toGoal[v]    ? "#d62728"
                                       : "#111")
                    << "\"/>\n";
            const char *colours[2] = {"#2ca02c", "#d62728"};
            for (int v = 0; v < 2 && v < static_cast<int>(nodes.size()); ++v)
                svg << "<circle cx=\"" << num(X(nodes[v].p.x())) << "\" cy=\"" << num(Y(nodes[v].p.y()))
                    << "\" r=\"6\" fill=\"" << colours[v] << "\"/>\n";
            svg << "</g>\n";
            // axes and legend
            svg << "<text x=\"" << num(left + w / 2) << "\" y=\"" << options.height - 14 << "\">" << options.axis1
                << " [" << num(lo.x()) << ", " << num(hi.x()) << "]</text>\n"
                << "<text x=\"14\" y=\"" << num(top + h / 2) << "\" transform=\"rotate(-90 14 " << num(top + h / 2)
                << ")\">" << options.axis2 << " [" << num(lo.y()) << ", " << num(hi.y()) << "]</text>\n";
            const double lx = options.width - right + 16;
            const char *labels[][2] = {{"#3b6fb6", "obstacle"},   {"#d62728", "blocked circle point"},
                                       {"#111", "candidate"},     {"#2ca02c", "link"},
                                       {"#ff7f0e", "path found"}, {"#9467bd", "chosen path"}};
            for (int i = 0; i < 6; ++i)
                svg << "<rect x=\"" << lx << "\" y=\"" << top + 20 * i << "\" width=\"12\" height=\"12\" fill=\""
                    << labels[i][0] << "\"/><text x=\"" << lx + 18 << "\" y=\"" << top + 20 * i + 11 << "\">"
                    << labels[i][1] << "</text>\n";
            svg << "<text x=\"" << lx << "\" y=\"" << top + 140 << "\">" << search.rings().size() << " circles, "
                << nodes.size() - 2 << " candidates</text>\n"
                << "<text x=\"" << lx << "\" y=\"" << top + 158 << "\">" << search.links().size() << " links, "
                << search.paths().size() << " paths</text>\n"
                << "<text x=\"" << lx << "\" y=\"" << top + 176 << "\">" << search.recursions()
                << " recursions</text>\n";
            svg << "</svg>\n";
            writeAtomically(svg.str(), file);
        }
    }  // namespace tools
}  // namespace michi
