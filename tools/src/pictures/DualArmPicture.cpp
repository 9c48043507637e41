#include <michi/tools/pictures/DualArmPicture.h>

#include <michi/tools/FileOutput.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace michi
{
    namespace tools
    {
        namespace
        {
            using planners::DualArmWorkspace;

            const double SCALE = 420.;  // pixels per metre
            const double MARGIN = 50.;

            /** A slice of the grid: cells (u, v) of two axes at a fixed index of the third. */
            struct Slice
            {
                int axisU, axisV, axisFixed, fixedIndex;
                std::string title;
            };

            std::string colourOf(std::uint8_t f)
            {
                // Most specific flag first: a stirring cell is also in the area, the common space and both reaches.
                if (f & DualArmWorkspace::STIR)
                    return "#1b7837";
                if (f & DualArmWorkspace::AREA)
                    return "#7fbf7b";
                if (f & DualArmWorkspace::COMMON)
                    return "#fee08b";
                if ((f & DualArmWorkspace::REACH_LARGE) && (f & DualArmWorkspace::REACH_SMALL))
                    return "#bbbbbb";
                if (f & DualArmWorkspace::REACH_LARGE)
                    return "#c6dbef";
                if (f & DualArmWorkspace::REACH_SMALL)
                    return "#fcc5c0";
                return "";
            }

            /** Colour of w relative to the threshold: blues below, reds above (log scale over 1/4 .. 4 x). */
            std::string heat(double w, double threshold)
            {
                // On a log scale, centred on the threshold: what matters is how far a cell is above or below it, in
                // factors; the floor keeps log(0) away where the arm is singular.
                const double t = std::max(-1., std::min(1., std::log(std::max(w, 1e-12) / threshold) / std::log(4.)));
                int r, g, b;
                if (t < 0.)
                {
                    r = static_cast<int>(255 * (1. + 0.8 * t));
                    g = static_cast<int>(255 * (1. + 0.6 * t));
                    b = 255;
                }
                else
                {
                    r = 255;
                    g = static_cast<int>(255 * (1. - 0.8 * t));
                    b = static_cast<int>(255 * (1. - 0.9 * t));
                }
                std::ostringstream s;
                s << "rgb(" << r << "," << g << "," << b << ")";
                return s.str();
            }

            const char *AXIS = "xyz";

            /** Draw one slice panel at (ox, oy); returns its width. \e cellColour gives the fill of a cell. */
            template <typename ColourFn>
            double panel(std::ostringstream &svg, const DualArmWorkspace &ws, const Slice &s, double ox, double oy,
                         ColourFn cellColour)
            {
                const auto &g = ws.grid();
                const double cell = g.resolution * SCALE;
                const double w = g.size[s.axisU] * cell, h = g.size[s.axisV] * cell;
                svg << "<g>\n<text x='" << ox << "' y='" << oy - 8 << "' font-size='14'>" << s.title << "</text>\n";
                svg << "<rect x='" << ox << "' y='" << oy << "' width='" << w << "' height='" << h
                    << "' fill='white' stroke='#444'/>\n";
                for (int u = 0; u < g.size[s.axisU]; ++u)
                    for (int v = 0; v < g.size[s.axisV]; ++v)
                    {
                        std::array<int, 3> c{};
                        c[s.axisU] = u;
                        c[s.axisV] = v;
                        c[s.axisFixed] = s.fixedIndex;
                        const std::string colour = cellColour(g.index(c[0], c[1], c[2]));
                        if (colour.empty())
                            continue;
                        // SVG's y axis points down: v is counted up from the panel's bottom edge. 0.3 px of overlap
                        // hides the hairline seams that anti-aliasing leaves between adjacent rectangles.
                        svg << "<rect x='" << ox + u * cell << "' y='" << oy + h - (v + 1) * cell << "' width='"
                            << cell + 0.3 << "' height='" << cell + 0.3 << "' fill='" << colour << "'/>\n";
                    }
                // axes ticks every 0.2 m
                for (int a = 0; a < 2; ++a)
                {
                    const int axis = a == 0 ? s.axisU : s.axisV;
                    const double lo = g.origin[axis], hi = g.origin[axis] + g.size[axis] * g.resolution;
                    for (double t = std::ceil(lo / 0.2) * 0.2; t <= hi + 1e-9; t += 0.2)
                    {
                        const double p = (t - lo) * SCALE;
                        std::ostringstream label;
                        label << std::fixed << std::setprecision(1) << t;
                        if (a == 0)
                            svg << "<line x1='" << ox + p << "' y1='" << oy + h << "' x2='" << ox + p << "' y2='"
                                << oy + h + 5 << "' stroke='#444'/><text x='" << ox + p - 8 << "' y='" << oy + h + 18
                                << "' font-size='11'>" << label.str() << "</text>\n";
                        else
                            svg << "<line x1='" << ox - 5 << "' y1='" << oy + h - p << "' x2='" << ox << "' y2='"
                                << oy + h - p << "' stroke='#444'/><text x='" << ox - 32 << "' y='" << oy + h - p + 4
                                << "' font-size='11'>" << label.str() << "</text>\n";
                    }
                }
                svg << "<text x='" << ox + w / 2 << "' y='" << oy + h + 34 << "' font-size='12'>" << AXIS[s.axisU]
                    << " [m]</text><text x='" << ox - 40 << "' y='" << oy - 8 + 0 << "' font-size='12'></text>\n";
                svg << "<text x='" << ox - 45 << "' y='" << oy + h / 2 << "' font-size='12'>" << AXIS[s.axisV]
                    << "</text>\n</g>\n";
                return w;
            }

            /** Marker of a world point on a slice panel. */
            void marker(std::ostringstream &svg, const DualArmWorkspace &ws, const Slice &s, double ox, double oy,
                        const Eigen::Vector3d &p, const std::string &colour, const std::string &label,
                        const std::string &shape = "circle")
            {
                const auto &g = ws.grid();
                const double h = g.size[s.axisV] * g.resolution * SCALE;
                const double x = ox + (p[s.axisU] - g.origin[s.axisU]) * SCALE;
                const double y = oy + h - (p[s.axisV] - g.origin[s.axisV]) * SCALE;
                if (shape == "square")
                    svg << "<rect x='" << x - 5 << "' y='" << y - 5 << "' width='10' height='10' fill='" << colour
                        << "' stroke='black'/>\n";
                else if (shape == "cross")
                    svg << "<path d='M" << x - 6 << " " << y - 6 << " L" << x + 6 << " " << y + 6 << " M" << x - 6
                        << " " << y + 6 << " L" << x + 6 << " " << y - 6 << "' stroke='" << colour
                        << "' stroke-width='2.5'/>\n";
                else
                    svg << "<circle cx='" << x << "' cy='" << y << "' r='6' fill='" << colour
                        << "' stroke='black' stroke-width='1.5'/>\n";
                svg << "<text x='" << x + 8 << "' y='" << y - 6 << "' font-size='12' font-weight='bold'>" << label
                    << "</text>\n";
            }

            std::array<Slice, 2> slices(const DualArmWorkspace &ws)
            {
                const auto &g = ws.grid();
                const Eigen::Vector3d b = ws.typeBPosition();
                auto index = [&](int axis)
                {
                    return std::max(0,
                                    std::min(g.size[axis] - 1,
                                             static_cast<int>(std::floor((b[axis] - g.origin[axis]) / g.resolution))));
                };
                std::ostringstream top, side;
                top << std::fixed << std::setprecision(3)
                    << "horizontal slice z = " << g.origin.z() + (index(2) + 0.5) * g.resolution
                    << " m (through B), seen from above";
                side << std::fixed << std::setprecision(3)
                     << "vertical slice y = " << g.origin.y() + (index(1) + 0.5) * g.resolution
                     << " m (through B), seen from the side";
                // Both slices pass through B, the chosen stirring position, so the picture shows the cells around the
                // answer.
                return {{Slice{0, 1, 2, index(2), top.str()}, Slice{0, 2, 1, index(1), side.str()}}};
            }

            void markers(std::ostringstream &svg, const DualArmWorkspace &ws, const Slice &s, double ox, double oy)
            {
                const auto &model = *ws.model();
                const auto poses = model.forwardKinematics(ws.home());
                for (const auto *task : {&ws.large(), &ws.small()})
                {
                    const int first = model.variableJoint(static_cast<std::size_t>(task->arm.variables()[0])).childLink;
                    marker(svg, ws, s, ox, oy, poses[first].translation(), "#555", task->name + " mount", "square");
                }
                marker(svg, ws, s, ox, oy, ws.typeAPosition(), "#d73027", "A");
                marker(svg, ws, s, ox, oy, ws.typeBPosition(), "#4575b4", "B");
            }

            void legend(std::ostringstream &svg, double x, double y,
                        const std::vector<std::pair<std::string, std::string>> &items)
            {
                for (std::size_t i = 0; i < items.size(); ++i)
                    svg << "<rect x='" << x << "' y='" << y + 20 * i << "' width='14' height='14' fill='"
                        << items[i].first << "' stroke='#444'/><text x='" << x + 20 << "' y='" << y + 20 * i + 12
                        << "' font-size='12'>" << items[i].second << "</text>\n";
            }

            std::string header(double w, double h)
            {
                std::ostringstream s;
                s << "<?xml version='1.0' encoding='UTF-8'?>\n<svg xmlns='http://www.w3.org/2000/svg' width='" << w
                  << "' height='" << h << "' viewBox='0 0 " << w << " " << h
                  << "' font-family='sans-serif'>\n<rect width='100%' height='100%' fill='white'/>\n";
                return s.str();
            }
        }  // namespace

        void writeDualArmPictures(const planners::DualArmWorkspace &ws, const std::string &workspaceSvg,
                                  const std::string &manipulabilitySvg, const std::string &stirringSvg,
                                  const std::vector<DualArmJointPlot> &stirring, const std::string &title)
        {
            const auto &g = ws.grid();
            const auto sl = slices(ws);
            const double w0 = g.size[0] * g.resolution * SCALE;
            const double h0 = g.size[1] * g.resolution * SCALE, h1 = g.size[2] * g.resolution * SCALE;
            const double width = 2 * w0 + 3 * MARGIN + 330, height = std::max(h0, h1) + 2 * MARGIN + 60;
            const double threshold = ws.settings().threshold;

            {
                std::ostringstream svg;
                svg << header(width, height);
                svg << "<text x='" << MARGIN << "' y='24' font-size='16' font-weight='bold'>" << title
                    << ": work spaces, manipulability area and work positions (cf. paper 004, Fig. 4, 6, 7)</text>\n";
                double ox = MARGIN;
                for (const auto &s : sl)
                {
                    const auto &flags = ws.flags();
                    ox += panel(svg, ws, s, ox, MARGIN + 20,
                                [&](std::size_t c)
                                {
                                    return colourOf(flags[c]);
                                }) +
                          MARGIN;
                    markers(svg, ws, s, ox - MARGIN - g.size[s.axisU] * g.resolution * SCALE, MARGIN + 20);
                }
                std::ostringstream area;
                area << "manipulability area (small arm w > " << threshold << ")";
                legend(svg, ox, MARGIN + 20,
                       {{"#c6dbef", "large arm's work space only (hand horizontal)"},
                        {"#fcc5c0", "small arm's work space only (hand down)"},
                        {"#bbbbbb", "both reach, but the arms collide"},
                        {"#fee08b", "common work space"},
                        {"#7fbf7b", area.str()},
                        {"#1b7837", "stirring area (whole 3 cm square inside)"},
                        {"#d73027", "A: hand-over (common space centroid)"},
                        {"#4575b4", "B: stirring (stirring area centroid)"},
                        {"#555", "arm mounts (first joint)"}});
                writeAtomically(svg.str() + "</svg>\n", workspaceSvg);
            }
            {
                std::ostringstream svg;
                svg << header(width, height);
                svg << "<text x='" << MARGIN << "' y='24' font-size='16' font-weight='bold'>" << title
                    << ": the small arm's manipulability w (hand pointing down; cf. paper 004, Fig. 6)</text>\n";
                double ox = MARGIN;
                for (const auto &s : sl)
                {
                    const auto &flags = ws.flags();
                    const auto &w = ws.smallManipulability();
                    ox += panel(svg, ws, s, ox, MARGIN + 20,
                                [&](std::size_t c)
                                {
                                    return (flags[c] & DualArmWorkspace::REACH_SMALL) ? heat(w[c], threshold)
                                                                                      : std::string();
                                }) +
                          MARGIN;
                    markers(svg, ws, s, ox - MARGIN - g.size[s.axisU] * g.resolution * SCALE, MARGIN + 20);
                }
                std::vector<std::pair<std::string, std::string>> items;
                for (double f : {0.25, 0.5, 1., 2., 4.})
                {
                    std::ostringstream label;
                    label << "w = " << f * threshold << (f == 1. ? " (threshold)" : "");
                    // The threshold's own swatch shows the colour just above it (white is exactly at it), as cells that
                    // pass.
                    items.emplace_back(heat(f * threshold * (f == 1. ? 1.0001 : 1.), threshold), label.str());
                }
                legend(svg, ox, MARGIN + 20, items);
                writeAtomically(svg.str() + "</svg>\n", manipulabilitySvg);
            }
            {
                const double pw = 520, ph = 260;
                std::ostringstream svg;
                svg << header(pw + 2 * MARGIN + 260, stirring.size() * (ph + MARGIN + 30) + MARGIN + 20);
                svg << "<text x='" << MARGIN << "' y='24' font-size='16' font-weight='bold'>" << title
                    << ": small arm joint angles along the stirring square</text>\n";
                const char *colours[] = {"#e41a1c", "#377eb8", "#4daf4a", "#984ea3", "#ff7f00", "#a65628"};
                for (std::size_t p = 0; p < stirring.size(); ++p)
                {
                    const auto &plot = stirring[p];
                    const double oy = MARGIN + 20 + p * (ph + MARGIN + 30);
                    double lo = 1e9, hi = -1e9;
                    for (const auto &v : plot.values)
                        for (double x : v)
                        {
                            lo = std::min(lo, x);
                            hi = std::max(hi, x);
                        }
                    if (plot.values.empty())
                        continue;
                    // A little room above and below, so flat joint curves do not lie on the frame.
                    lo -= 0.05;
                    hi += 0.05;
                    svg << "<text x='" << MARGIN << "' y='" << oy - 8 << "' font-size='14'>" << plot.label
                        << "</text>\n<rect x='" << MARGIN << "' y='" << oy << "' width='" << pw << "' height='" << ph
                        << "' fill='none' stroke='#444'/>\n";
                    for (double t = std::ceil(lo * 2) / 2; t <= hi; t += 0.5)
                    {
                        const double y = oy + ph - (t - lo) / (hi - lo) * ph;
                        svg << "<line x1='" << MARGIN << "' y1='" << y << "' x2='" << MARGIN + pw << "' y2='" << y
                            << "' stroke='#ddd'/><text x='" << MARGIN - 34 << "' y='" << y + 4 << "' font-size='11'>"
                            << t << "</text>\n";
                    }
                    const std::size_t joints = plot.values[0].size();
                    std::vector<double> motion(joints, 0.);
                    for (std::size_t j = 0; j < joints; ++j)
                    {
                        svg << "<polyline fill='none' stroke='" << colours[j % 6] << "' stroke-width='2' points='";
                        for (std::size_t i = 0; i < plot.values.size(); ++i)
                        {
                            const double x = MARGIN + pw * i / std::max<double>(1., plot.values.size() - 1.);
                            const double y = oy + ph - (plot.values[i][j] - lo) / (hi - lo) * ph;
                            svg << x << "," << y << " ";
                            if (i)
                                motion[j] += std::abs(plot.values[i][j] - plot.values[i - 1][j]);
                        }
                        svg << "'/>\n";
                    }
                    std::vector<std::pair<std::string, std::string>> items;
                    for (std::size_t j = 0; j < joints; ++j)
                    {
                        std::ostringstream label;
                        label << "joint " << j + 1 << ": total motion " << std::fixed << std::setprecision(3)
                              << motion[j] << " rad";
                        items.emplace_back(colours[j % 6], label.str());
                    }
                    legend(svg, MARGIN + pw + 20, oy, items);
                    svg << "<text x='" << MARGIN + pw / 2 - 60 << "' y='" << oy + ph + 18
                        << "' font-size='12'>state along the square</text>\n";
                }
                writeAtomically(svg.str() + "</svg>\n", stirringSvg);
            }
        }
    }  // namespace tools
}  // namespace michi
