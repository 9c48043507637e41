#include "SvgPanels.h"

#include <algorithm>
#include <cmath>

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
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
                // One step for both axes (about six ticks on the longer one), so the grid squares show the panel's
                // equal scale.
                const double step = niceStep(std::max(w.width(), w.height()), 6.);
                // As many decimals as the step needs: niceStep gives 1, 2 or 5 times a power of ten, one significant
                // digit.
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
                // Content is clipped to the panel: a path or obstacle beyond the frame must not draw over the
                // neighbouring panel.
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

            void drawShapes(SvgWriter &svg, const ViewTransform &t, const std::vector<MultiPolygon2> &shapes,
                            Attributes attributes)
            {
                std::string data;
                // All shapes in one path element: a map of thousands of cells stays one element of the SVG.
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
                         Attributes attributes)
            {
                attributes.insert(attributes.begin(),
                                  {{"cx", num(x)}, {"cy", num(y)}, {"r", num(radius)}, {"fill", colour}});
                svg.element("circle", attributes);
            }
        }  // namespace svg_plot
    }      // namespace tools
}  // namespace michi
