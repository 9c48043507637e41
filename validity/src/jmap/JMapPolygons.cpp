/* J-map polygons from slices: theta2-monotone pieces, border chains, the paper's line walk, union. */

#include <michi/validity/jmap/JMap.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bg = boost::geometry;

namespace michi
{
    namespace validity
    {
        namespace
        {
            /** \brief Smallest height of an interval in the polygons (zero-width touching intervals). */
            const double MIN_HEIGHT = 2e-9;
            /** \brief How far (radians) the line walk may pass inside an end point: rounding of collinear points. */
            const double SIDE_EPS = 1e-12;

            /** \brief Intervals of neighbouring cells that continue each other: they overlap by more than
                MIN_HEIGHT (so the piece's polygon never pinches to a point). */
            bool overlap(const JointInterval &x, const JointInterval &y)
            {
                return x.lo < y.hi - MIN_HEIGHT && y.lo < x.hi - MIN_HEIGHT;
            }

            /** \brief Line walk test: does the line from \e p to \e q cross the circle of radius r about every
                point strictly between them, and pass on the outer side of each? */
            bool straightEnough(const std::vector<Point2> &chain, std::size_t i, std::size_t k, double r, bool upper)
            {
                const Point2 &p = chain[i], &q = chain[k];
                const double dx = q.x() - p.x(), dy = q.y() - p.y();
                const double len = std::hypot(dx, dy);
                for (std::size_t j = i + 1; j < k; ++j)
                {
                    const Point2 &s = chain[j];
                    // perpendicular distance from the circle's centre to the line
                    const double dist = std::abs(dx * (s.y() - p.y()) - dy * (s.x() - p.x())) / len;
                    if (dist > r)
                        return false;
                    // the line's height at the point's x must be outside the end point (up to rounding: the
                    // sources pad their interval ends by 1e-9, far more)
                    const double t = (s.x() - p.x()) / dx;
                    const double y = p.y() + t * dy;
                    if (upper ? y < s.y() - SIDE_EPS : y > s.y() + SIDE_EPS)
                        return false;
                }
                return true;
            }
        }  // namespace

        std::vector<Point2> lineWalk(const std::vector<Point2> &chain, double r, bool upper)
        {
            if (chain.size() <= 2)
                return chain;
            std::vector<Point2> out{chain.front()};
            const std::size_t last = chain.size() - 1;
            std::size_t i = 0;
            while (i < last)
            {
                std::size_t best = i + 1;
                for (std::size_t k = i + 2; k <= last; ++k)
                {
                    if (!straightEnough(chain, i, k, r, upper))
                        break;  // point k - 1 (= best) becomes a vertex
                    best = k;
                }
                out.push_back(chain[best]);
                i = best;
            }
            return out;
        }

        void jmapPolygons(const std::vector<JMapSlice> &slices, double lo2, double hi2, const JMapSettings &settings,
                          std::vector<Polygon2> &pieces, MultiPolygon2 &polygons)
        {
            pieces.clear();
            polygons.clear();
            if (slices.empty())
                return;
            const double margin = settings.borderMargin;
            // the columns (each slice's cell cut into equal parts) and their borders; the outer borders pushed
            // beyond the axis-1 limits; intervals on the axis-2 limits pushed beyond them
            std::vector<double> border;
            std::vector<std::vector<JointInterval>> cells;
            for (const auto &slice : slices)
            {
                const std::size_t m = slice.columns.empty() ? 1 : slice.columns.size();
                for (std::size_t k = 0; k < m; ++k)
                {
                    border.push_back(slice.lo + k * (slice.hi - slice.lo) / m);
                    std::vector<JointInterval> column;
                    for (JointInterval iv : mergeIntervals(slice.columns.empty() ? slice.intervals : slice.columns[k]))
                    {
                        // A region touching an axis limit is pushed past it (borderMargin): a state at the limit itself
                        // must fall inside the polygon, not on an edge that rounding could put on either side.
                        if (iv.lo <= lo2 + 1e-12)
                            iv.lo = lo2 - margin;
                        if (iv.hi >= hi2 - 1e-12)
                            iv.hi = hi2 + margin;
                        // A touching angle (lo == hi) becomes a sliver of height MIN_HEIGHT: a zero-height interval
                        // would make a degenerate polygon with no area.
                        if (iv.hi - iv.lo < MIN_HEIGHT)
                        {
                            const double mid = 0.5 * (iv.lo + iv.hi);
                            iv.lo = mid - 0.5 * MIN_HEIGHT;
                            iv.hi = mid + 0.5 * MIN_HEIGHT;
                        }
                        column.push_back(iv);
                    }
                    cells.push_back(std::move(column));
                }
            }
            const std::size_t n = cells.size();
            border.push_back(slices.back().hi);
            border.front() -= margin;
            border.back() += margin;

            // link each interval to the one it continues in the next cell (one-to-one overlaps only)
            std::vector<std::vector<int>> next(n), linked(n);
            for (std::size_t i = 0; i < n; ++i)
            {
                next[i].assign(cells[i].size(), -1);
                linked[i].assign(cells[i].size(), 0);
            }
            for (std::size_t i = 0; i + 1 < n; ++i)
            {
                const auto &left = cells[i], &right = cells[i + 1];
                std::vector<int> out(left.size(), 0), in(right.size(), 0), partner(left.size(), -1);
                for (std::size_t a = 0; a < left.size(); ++a)
                    for (std::size_t b = 0; b < right.size(); ++b)
                        if (overlap(left[a], right[b]))
                        {
                            ++out[a];
                            ++in[b];
                            partner[a] = static_cast<int>(b);
                        }
                for (std::size_t a = 0; a < left.size(); ++a)
                    // Only one-to-one continuations are followed: at a split or a merge the piece ends, so every piece
                    // is theta2-monotone and its lower and upper chains are well defined.
                    if (out[a] == 1 && in[partner[a]] == 1)
                    {
                        next[i][a] = partner[a];
                        linked[i + 1][partner[a]] = 1;
                    }
            }

            // one polygon per piece: lower chain left to right, upper chain back
            for (std::size_t s = 0; s < n; ++s)
                for (std::size_t a0 = 0; a0 < cells[s].size(); ++a0)
                {
                    if (linked[s][a0])
                        continue;  // continues a piece started further left
                    std::vector<JointInterval> run;
                    std::size_t i = s;
                    int a = static_cast<int>(a0);
                    while (true)
                    {
                        run.push_back(cells[i][a]);
                        if (i + 1 >= n || next[i][a] < 0)
                            break;
                        a = next[i][a];
                        ++i;
                    }
                    // the staircase: each interval spans its whole cell; the chains jump at the borders
                    std::vector<Point2> lower, upper;
                    auto add = [](std::vector<Point2> &chain, double x, double y)
                    {
                        if (chain.empty() || chain.back().x() != x || chain.back().y() != y)
                            chain.emplace_back(x, y);
                    };
                    for (std::size_t j = 0; j < run.size(); ++j)
                    {
                        add(lower, border[s + j], run[j].lo);
                        add(lower, border[s + j + 1], run[j].lo);
                        add(upper, border[s + j], run[j].hi);
                        add(upper, border[s + j + 1], run[j].hi);
                    }
                    // The walk keeps the lower chain below and the upper chain above every end point it skips: the
                    // polygon still holds the staircase whatever the tolerance (jmap.md, "Polygons").
                    lower = lineWalk(lower, settings.tolerance, false);
                    upper = lineWalk(upper, settings.tolerance, true);
                    std::vector<Point2> ring = lower;
                    ring.insert(ring.end(), upper.rbegin(), upper.rend());
                    pieces.push_back(makePolygon2(ring));
                }

            for (const auto &piece : pieces)
            {
                MultiPolygon2 merged;
                // United: pieces of one region overlap at their splits and merges, and a planner needs one polygon per
                // region.
                bg::union_(polygons, piece, merged);
                polygons = std::move(merged);
            }
        }
    }  // namespace validity
}  // namespace michi
