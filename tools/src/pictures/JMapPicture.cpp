/* SVG picture of a J-map (paper 000, Fig. 1(c) / 7(a)). */

#include <michi/tools/pictures/JMapPicture.h>
#include <michi/tools/FileOutput.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

using michi::validity::JMap;
using michi::validity::MultiPolygon2;
using michi::validity::Polygon2;

namespace michi
{
    namespace tools
    {
        namespace
        {
            const char *const MAP_FILL = "#3b6fb6";
            const char *const MAP_STROKE = "#1d3f73";
            const char *const GROWN_FILL = "#f2a541";
            const char *const GROWN_STROKE = "#b86e00";
            const char *const NECK_FILL = "#d62728";
            const char *const SEGMENT = "#111111";
            const char *const CELL = "#6a8fc9";
            const char *const START_COLOUR = "#2ca02c";
            const char *const GOAL_COLOUR = "#d62728";
            const char *const PATH_COLOUR = "#9467bd";
            const double LEFT = 72., RIGHT = 230., TOP = 48., BOTTOM = 56.;

            std::string num(double v)
            {
                char buffer[32];
                // Two decimals of a pixel are plenty; values that round to zero print as 0, never as -0.00.
                std::snprintf(buffer, sizeof(buffer), "%.2f", std::abs(v) < 5e-3 ? 0. : v);
                return buffer;
            }

            std::string escape(const std::string &text)
            {
                std::string out;
                for (char c : text)
                {
                    if (c == '&')
                        out += "&amp;";
                    else if (c == '<')
                        out += "&lt;";
                    else if (c == '>')
                        out += "&gt;";
                    else if (c == '"')
                        out += "&quot;";
                    else
                        out += c;
                }
                return out;
            }

            /** \brief Tick label of a multiple of pi/4 ("-π/2", "0", "3π/4"), else the number. */
            std::string radians(double v)
            {
                const double quarters = v / (M_PI / 4);
                const long q = std::lround(quarters);
                if (std::abs(quarters - q) > 1e-6)
                    return num(v);
                if (q == 0)
                    return "0";
                long n = q, d = 4;
                // The fraction in lowest terms: 2π/4 reads π/2.
                while (n % 2 == 0 && d > 1)
                {
                    n /= 2;
                    d /= 2;
                }
                std::string s = n < 0 ? "−" : "";
                if (std::abs(n) != 1)
                    s += std::to_string(std::abs(n));
                s += "π";
                if (d != 1)
                    s += "/" + std::to_string(d);
                return s;
            }

            struct Frame
            {
                double lo1, hi1, lo2, hi2;
                double width, height;  // plot area in pixels
                double x(double t1) const
                {
                    return LEFT + (t1 - lo1) / (hi1 - lo1) * width;
                }
                double y(double t2) const
                {
                    // theta2 grows upwards, as in a plot; SVG's y grows downwards.
                    return TOP + (hi2 - t2) / (hi2 - lo2) * height;
                }
            };

            std::string pathData(const MultiPolygon2 &polygons, const Frame &f)
            {
                std::ostringstream d;
                auto ring = [&](const Polygon2::ring_type &r)
                {
                    for (std::size_t i = 0; i < r.size(); ++i)
                        d << (i == 0 ? "M" : "L") << num(f.x(r[i].x())) << " " << num(f.y(r[i].y())) << " ";
                    d << "Z ";
                };
                for (const auto &p : polygons)
                {
                    ring(p.outer());
                    for (const auto &inner : p.inners())
                        ring(inner);
                }
                return d.str();
            }

        }  // namespace

        void writeJMapSvg(const JMap &map, const std::string &file, const JMapPictureOptions &options)
        {
            const int W = std::max(options.width, 400), H = std::max(options.height, 300);
            const Frame f{map.lo1(), map.hi1(), map.lo2(), map.hi2(), W - LEFT - RIGHT, H - TOP - BOTTOM};
            std::ostringstream svg;
            svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
                << "\" viewBox=\"0 0 " << W << " " << H << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
                << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
            if (!options.title.empty())
                svg << "<text x=\"" << LEFT << "\" y=\"24\" font-size=\"15\">" << escape(options.title) << "</text>\n";
            // plot clip: polygons extend slightly beyond the joint limits
            svg << "<defs><clipPath id=\"plot\"><rect x=\"" << LEFT << "\" y=\"" << TOP << "\" width=\"" << num(f.width)
                << "\" height=\"" << num(f.height) << "\"/></clipPath></defs>\n";
            svg << "<g clip-path=\"url(#plot)\">\n";
            // the grown map: filled when no bottleneck is drawn (the bottleneck is grown - plain), else outlined
            if (options.grown)
                svg << "<path d=\"" << pathData(options.grown->polygons(), f) << "\" fill=\""
                    << (options.bottleneck.empty() ? GROWN_FILL : "none")
                    << "\" fill-opacity=\"0.35\" fill-rule=\"evenodd\" stroke=\"" << GROWN_STROKE
                    << "\" stroke-width=\"1.2\"/>\n";
            if (options.cellIntervals)
                for (const auto &s : map.slices())
                {
                    const std::size_t m = s.columns.empty() ? 1 : s.columns.size();
                    for (std::size_t k = 0; k < m; ++k)
                    {
                        const double x0 = s.lo + k * (s.hi - s.lo) / m, x1 = s.lo + (k + 1) * (s.hi - s.lo) / m;
                        for (const auto &i : s.columns.empty() ? s.intervals : s.columns[k])
                            svg << "<rect x=\"" << num(f.x(x0)) << "\" y=\"" << num(f.y(i.hi)) << "\" width=\""
                                << num(f.x(x1) - f.x(x0)) << "\" height=\"" << num(f.y(i.lo) - f.y(i.hi))
                                << "\" fill=\"none\" stroke=\"" << CELL << "\" stroke-width=\"0.4\"/>\n";
                    }
                }
            svg << "<path d=\"" << pathData(map.polygons(), f) << "\" fill=\"" << MAP_FILL
                << "\" fill-opacity=\"0.4\" fill-rule=\"evenodd\" stroke=\"" << MAP_STROKE
                << "\" stroke-width=\"1\"/>\n";
            if (!options.bottleneck.empty())
                svg << "<path d=\"" << pathData(options.bottleneck, f) << "\" fill=\"" << NECK_FILL
                    << "\" fill-opacity=\"0.45\" fill-rule=\"evenodd\" stroke=\"none\"/>\n";
            // the true collision intervals of every slice: the paper's vertical segments
            // Drawn over the polygons, so the picture shows at a glance that every segment lies inside them (the
            // containment the map guarantees).
            svg << "<g stroke=\"" << SEGMENT << "\" stroke-width=\"1.2\">\n";
            for (const auto &s : map.slices())
                for (const auto &i : s.trueIntervals)
                {
                    // At least half a pixel long: an isolated touching angle (lo == hi) still shows as a dot.
                    const double y0 = f.y(i.lo), y1 = f.y(i.hi);
                    svg << "<line x1=\"" << num(f.x(s.theta1)) << "\" y1=\"" << num(y0) << "\" x2=\""
                        << num(f.x(s.theta1)) << "\" y2=\"" << num(std::min(y1, y0 - 0.5)) << "\"/>\n";
                }
            svg << "</g>\n";
            if (options.path.size() > 1)
            {
                svg << "<polyline fill=\"none\" stroke=\"" << PATH_COLOUR << "\" stroke-width=\"2\" points=\"";
                for (const auto &p : options.path)
                    if (p.size() >= 2)
                        svg << num(f.x(p[0])) << "," << num(f.y(p[1])) << " ";
                svg << "\"/>\n";
            }
            svg << "</g>\n";
            if (options.start.size() >= 2)
                svg << "<circle cx=\"" << num(f.x(options.start[0])) << "\" cy=\"" << num(f.y(options.start[1]))
                    << "\" r=\"6\" fill=\"" << START_COLOUR << "\" stroke=\"white\" stroke-width=\"1.5\"/>\n";
            if (options.goal.size() >= 2)
            {
                const double gx = f.x(options.goal[0]), gy = f.y(options.goal[1]);
                svg << "<rect x=\"" << num(gx - 6) << "\" y=\"" << num(gy - 6)
                    << "\" width=\"12\" height=\"12\" fill=\"" << GOAL_COLOUR
                    << "\" stroke=\"white\" stroke-width=\"1.5\" transform=\"rotate(45 " << num(gx) << " " << num(gy)
                    << ")\"/>\n";
            }

            // axes: frame, ticks at multiples of pi/4 (pi/2 when the range is wide), labels in radians
            svg << "<rect x=\"" << LEFT << "\" y=\"" << TOP << "\" width=\"" << num(f.width) << "\" height=\""
                << num(f.height) << "\" fill=\"none\" stroke=\"#333\"/>\n";
            auto ticks = [](double lo, double hi)
            {
                // Ticks at pi/4 would crowd an axis wider than a full turn: pi/2 there.
                const double step = hi - lo > 2. * M_PI ? M_PI / 2 : M_PI / 4;
                std::vector<double> out;
                for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9; t += step)
                    out.push_back(t);
                return out;
            };
            for (double t : ticks(f.lo1, f.hi1))
                svg << "<line x1=\"" << num(f.x(t)) << "\" y1=\"" << num(TOP + f.height) << "\" x2=\"" << num(f.x(t))
                    << "\" y2=\"" << num(TOP + f.height + 5) << "\" stroke=\"#333\"/><text x=\"" << num(f.x(t))
                    << "\" y=\"" << num(TOP + f.height + 19) << "\" text-anchor=\"middle\">" << radians(t)
                    << "</text>\n";
            for (double t : ticks(f.lo2, f.hi2))
                svg << "<line x1=\"" << num(LEFT - 5) << "\" y1=\"" << num(f.y(t)) << "\" x2=\"" << LEFT << "\" y2=\""
                    << num(f.y(t)) << "\" stroke=\"#333\"/><text x=\"" << num(LEFT - 8) << "\" y=\"" << num(f.y(t) + 4)
                    << "\" text-anchor=\"end\">" << radians(t) << "</text>\n";
            svg << "<text x=\"" << num(LEFT + f.width / 2) << "\" y=\"" << num(H - 14) << "\" text-anchor=\"middle\">"
                << escape(options.axis1) << " [rad]</text>\n";
            svg << "<text transform=\"translate(18 " << num(TOP + f.height / 2)
                << ") rotate(-90)\" text-anchor=\"middle\">" << escape(options.axis2) << " [rad]</text>\n";

            // legend
            struct Entry
            {
                std::string label, colour, kind;
            };
            std::vector<Entry> entries{{"true collision intervals (slices)", SEGMENT, "line"},
                                       {"J-map polygons", MAP_FILL, "box"}};
            if (options.cellIntervals)
                entries.push_back({"column intervals (conservative)", CELL, "outline"});
            if (options.grown)
                entries.push_back({"grown J-map", GROWN_FILL, options.bottleneck.empty() ? "box" : "outline"});
            if (!options.bottleneck.empty())
                entries.push_back({"bottleneck (grown − plain)", NECK_FILL, "box"});
            if (options.path.size() > 1)
                entries.push_back({"path", PATH_COLOUR, "line"});
            if (options.start.size() >= 2)
                entries.push_back({"start", START_COLOUR, "dot"});
            if (options.goal.size() >= 2)
                entries.push_back({"goal", GOAL_COLOUR, "diamond"});
            const double lx = LEFT + f.width + 18;
            double ly = TOP + 8;
            for (const auto &e : entries)
            {
                if (e.kind == "line")
                    svg << "<line x1=\"" << num(lx) << "\" y1=\"" << num(ly) << "\" x2=\"" << num(lx + 18) << "\" y2=\""
                        << num(ly) << "\" stroke=\"" << e.colour << "\" stroke-width=\"2\"/>\n";
                else if (e.kind == "box" || e.kind == "outline")
                    svg << "<rect x=\"" << num(lx) << "\" y=\"" << num(ly - 6)
                        << "\" width=\"18\" height=\"12\" fill=\"" << (e.kind == "box" ? e.colour : "none")
                        << "\" fill-opacity=\"0.45\" stroke=\"" << e.colour << "\" stroke-width=\"1.5\"/>\n";
                else if (e.kind == "dot")
                    svg << "<circle cx=\"" << num(lx + 9) << "\" cy=\"" << num(ly) << "\" r=\"5\" fill=\"" << e.colour
                        << "\"/>\n";
                else
                    svg << "<rect x=\"" << num(lx + 4) << "\" y=\"" << num(ly - 5)
                        << "\" width=\"10\" height=\"10\" fill=\"" << e.colour << "\" transform=\"rotate(45 "
                        << num(lx + 9) << " " << num(ly) << ")\"/>\n";
                svg << "<text x=\"" << num(lx + 26) << "\" y=\"" << num(ly + 4) << "\">" << escape(e.label)
                    << "</text>\n";
                ly += 20;
            }
            svg << "<text x=\"" << num(lx) << "\" y=\"" << num(ly + 8) << "\" fill=\"#555\">" << map.slices().size()
                << " slices, " << map.polygons().size() << " polygons</text>\n";
            svg << "<text x=\"" << num(lx) << "\" y=\"" << num(ly + 26)
                << "\" fill=\"#555\">r = " << num(map.settings().tolerance) << " rad</text>\n";
            svg << "</svg>\n";
            writeAtomically(svg.str(), file);
        }
    }  // namespace tools
}  // namespace michi
