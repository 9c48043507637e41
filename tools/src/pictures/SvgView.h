#ifndef MICHI_TOOLS_SRC_SVG_VIEW_
#define MICHI_TOOLS_SRC_SVG_VIEW_

// Private to michi_tools (not installed): world rectangles and their mapping onto an SVG panel (SvgView.cpp).

#include "SvgWriter.h"

#include <michi/validity/scene/Polygon2.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
            using Vec2 = Eigen::Vector2d;
            using Polyline = std::vector<Vec2>;
            using Values = std::vector<double>;
            using validity::MultiPolygon2;

            /** Axis-aligned rectangle that grows to hold what is added to it. */
            struct Extent
            {
                double xMin{std::numeric_limits<double>::infinity()};
                double xMax{-std::numeric_limits<double>::infinity()};
                double yMin{std::numeric_limits<double>::infinity()};
                double yMax{-std::numeric_limits<double>::infinity()};

                bool empty() const
                {
                    return !(xMin <= xMax && yMin <= yMax);
                }
                double width() const
                {
                    return xMax - xMin;
                }
                double height() const
                {
                    return yMax - yMin;
                }
                void add(double x, double y)
                {
                    if (!std::isfinite(x) || !std::isfinite(y))
                        return;
                    xMin = std::min(xMin, x);
                    xMax = std::max(xMax, x);
                    yMin = std::min(yMin, y);
                    yMax = std::max(yMax, y);
                }
                void add(const Vec2 &p)
                {
                    add(p.x(), p.y());
                }
                void add(const Polyline &line)
                {
                    for (const auto &p : line)
                        add(p);
                }
                void add(const MultiPolygon2 &shape)
                {
                    for (const auto &polygon : shape)
                        for (const auto &p : polygon.outer())
                            add(p.x(), p.y());
                }
                void add(const Extent &other)
                {
                    if (!other.empty())
                    {
                        add(other.xMin, other.yMin);
                        add(other.xMax, other.yMax);
                    }
                }
            };

            /** The extent with a margin, never degenerate and never thinner than 1:4, for a world panel. */
            Extent framed(Extent e);

            /** Maps a world rectangle onto a pixel rectangle, y up (SVG's y goes down). */
            class ViewTransform
            {
            public:
                ViewTransform(const Extent &world, double left, double top, double scaleX, double scaleY)
                    : world_(world), left_(left), top_(top), scaleX_(scaleX), scaleY_(scaleY)
                {
                }

                double x(double worldX) const
                {
                    return left_ + (worldX - world_.xMin) * scaleX_;
                }
                double y(double worldY) const
                {
                    return top_ + (world_.yMax - worldY) * scaleY_;
                }
                double left() const
                {
                    return left_;
                }
                double top() const
                {
                    return top_;
                }
                double width() const
                {
                    return world_.width() * scaleX_;
                }
                double height() const
                {
                    return world_.height() * scaleY_;
                }
                const Extent &world() const
                {
                    return world_;
                }

                /** "x,y x,y ..." for a polyline's points attribute. */
                std::string points(const Polyline &line) const
                {
                    std::string text;
                    for (const auto &p : line)
                    {
                        if (!text.empty())
                            text += ' ';
                        text += num(x(p.x())) + ',' + num(y(p.y()));
                    }
                    return text;
                }

                /** Path data of polygons (outer rings and holes), appended to \e data. */
                void appendPathData(const MultiPolygon2 &shape, std::string &data) const
                {
                    for (const auto &polygon : shape)
                    {
                        appendRing(polygon.outer(), data);
                        for (const auto &ring : polygon.inners())
                            appendRing(ring, data);
                    }
                }

            private:
                template <typename Ring>
                void appendRing(const Ring &ring, std::string &data) const
                {
                    if (ring.size() < 3)
                        return;
                    char command = 'M';
                    for (const auto &p : ring)
                    {
                        data += command;
                        data += num(x(p.x())) + ' ' + num(y(p.y()));
                        command = 'L';
                    }
                    data += 'Z';
                }

                Extent world_;
                double left_, top_, scaleX_, scaleY_;
            };

            /** A tick spacing of 1, 2 or 5 times a power of ten giving about \e count ticks over \e range. */
            double niceStep(double range, double count);
        }  // namespace svg_plot
    }      // namespace tools
}  // namespace michi

#endif
