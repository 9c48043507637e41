/* JMap: building a map from a source, and its fast point queries (a slab index over the polygons' edges). */

#include <michi/validity/jmap/JMap.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace michi
{
    namespace validity
    {
        /** \brief Vertical slabs between consecutive vertex x values; in a slab no two edges cross, so its edges
            are sorted by height and a point's inside/outside parity is a binary search. */
        class JMapIndex
        {
        public:
            explicit JMapIndex(const MultiPolygon2 &polygons)
            {
                const XSnap snap(polygons);
                std::vector<std::pair<Point2, Point2>> edges;
                auto addRing = [&](const Polygon2::ring_type &ring)
                {
                    // Boost.Geometry rings are closed (the last point repeats the first), so ring.size() - 1 edges.
                    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
                    {
                        const Point2 p(snap(ring[i].x()), ring[i].y()), q(snap(ring[i + 1].x()), ring[i + 1].y());
                        xs_.push_back(p.x());
                        if (p.x() == q.x())
                        {
                            if (p.y() != q.y())
                                // A vertical edge has zero width in x and belongs to no slab: it is kept apart and
                                // tested directly.
                                verticals_.push_back({p.x(), std::min(p.y(), q.y()), std::max(p.y(), q.y())});
                        }
                        else if (p.x() < q.x())
                            edges.emplace_back(p, q);
                        else
                            // Stored left to right, so every edge covers the slabs from its first to its second x.
                            edges.emplace_back(q, p);
                    }
                };
                for (const auto &polygon : polygons)
                {
                    addRing(polygon.outer());
                    for (const auto &inner : polygon.inners())
                        addRing(inner);
                }
                std::sort(xs_.begin(), xs_.end());
                xs_.erase(std::unique(xs_.begin(), xs_.end()), xs_.end());
                std::sort(verticals_.begin(), verticals_.end(),
                          [](const Vertical &a, const Vertical &b)
                          {
                              return a.x < b.x;
                          });
                if (xs_.size() < 2)
                {
                    xs_.clear();
                    return;
                }
                const std::size_t slabs = xs_.size() - 1;
                std::vector<std::vector<Line>> perSlab(slabs);
                for (const auto &e : edges)
                {
                    const double m = (e.second.y() - e.first.y()) / (e.second.x() - e.first.x());
                    const Line line{m, e.first.y() - m * e.first.x(), e.first.x(), e.first.y()};
                    std::size_t k = std::lower_bound(xs_.begin(), xs_.end(), e.first.x()) - xs_.begin();
                    // Both ends are vertex x values, so the edge spans whole slabs exactly: [lower_bound(first x),
                    // second x].
                    for (; k < slabs && xs_[k + 1] <= e.second.x(); ++k)
                        perSlab[k].push_back(line);
                }
                start_.push_back(0);
                for (std::size_t k = 0; k < slabs; ++k)
                {
                    // Sorted at the slab's middle: edges of a slab never cross inside it, so their order there holds
                    // over the whole slab (at the borders they may meet at a shared vertex).
                    const double mid = 0.5 * (xs_[k] + xs_[k + 1]);
                    std::sort(perSlab[k].begin(), perSlab[k].end(),
                              [mid](const Line &a, const Line &b)
                              {
                                  return a.at(mid) < b.at(mid);
                              });
                    lines_.insert(lines_.end(), perSlab[k].begin(), perSlab[k].end());
                    start_.push_back(static_cast<std::uint32_t>(lines_.size()));
                }
                // uniform bins in x -> first slab that can hold x
                // About four bins per slab: slabOf() then walks on average a slab or less from its bin's first slab.
                const std::size_t bins = std::max<std::size_t>(64, 4 * slabs);
                binScale_ = bins / (xs_.back() - xs_.front());
                binSlab_.resize(bins + 1);
                for (std::size_t b = 0; b <= bins; ++b)
                {
                    const double x = xs_.front() + b / binScale_;
                    std::size_t k = std::upper_bound(xs_.begin(), xs_.end(), x) - xs_.begin();
                    k = k == 0 ? 0 : std::min(k - 1, slabs - 1);
                    binSlab_[b] = static_cast<std::uint32_t>(k);
                }
                buildRaster(edges);
            }

            bool inside(double x, double y) const
            {
                // Written with ! so that a NaN coordinate is outside rather than undefined behaviour in slabOf().
                if (xs_.empty() || !(x >= xs_.front() && x <= xs_.back()))
                    return false;
                // most points lie in a raster cell no edge touches, wholly inside or outside: one byte decides
                const double fx = (x - rasterX0_) * rasterScaleX_, fy = (y - rasterY0_) * rasterScaleY_;
                if (fx >= 0. && fy >= 0. && fx < rasterColumns_ && fy < rasterRows_)
                {
                    const std::uint8_t cell =
                        raster_[static_cast<std::size_t>(fy) * rasterColumns_ + static_cast<std::size_t>(fx)];
                    if (cell != MIXED)
                        return cell == INSIDE;
                }
                return insideExact(x, y);
            }

            /** \brief inside() by the slabs alone (the raster's ground truth). */
            bool insideExact(double x, double y) const
            {
                if (xs_.empty() || !(x >= xs_.front() && x <= xs_.back()))
                    return false;
                const std::size_t k = slabOf(x);
                if (insideSlab(k, x, y))
                    return true;
                // on a slab border: a vertical edge there separates the two slabs; inside either counts
                if (x == xs_[k] && k > 0)
                    return insideSlab(k - 1, x, y);
                if (x == xs_[k + 1] && k + 2 < xs_.size())
                    return insideSlab(k + 1, x, y);
                return false;
            }

            double distance(double x, double y, double maxDistance) const
            {
                double best = maxDistance;
                if (xs_.empty())
                    return best;
                const double x0 = x - maxDistance, x1 = x + maxDistance;
                if (x1 < xs_.front() || x0 > xs_.back())
                    return best;
                const std::size_t slabs = xs_.size() - 1;
                std::size_t k = x0 <= xs_.front() ? 0 : slabOf(x0);
                for (; k < slabs && xs_[k] <= x1; ++k)
                {
                    const double xa = xs_[k], xb = xs_[k + 1];
                    for (std::uint32_t e = start_[k]; e < start_[k + 1]; ++e)
                    {
                        const Line &l = lines_[e];
                        const double ya = l.at(xa), yb = l.at(xb);
                        // The edge lies wholly above or below y by at least the best distance so far: it cannot be
                        // nearer.
                        if (std::min(ya, yb) - y >= best || y - std::max(ya, yb) >= best)
                            continue;
                        best = std::min(best, pointSegment(x, y, xa, ya, xb, yb));
                    }
                }
                auto v = std::lower_bound(verticals_.begin(), verticals_.end(), x0,
                                          [](const Vertical &a, double value)
                                          {
                                              return a.x < value;
                                          });
                for (; v != verticals_.end() && v->x <= x1; ++v)
                    best = std::min(best, pointSegment(x, y, v->x, v->y0, v->x, v->y1));
                return best;
            }

            /** \brief The smallest t in [0, 1] at which the segment (x0, y0) + t (x1 - x0, y1 - y0) touches a
                polygon, or +infinity. In a slab no two edges cross, so a line segment crosses the edges whose
                rank lies between its ranks at the slab's two sides, all in the same direction: two binary searches
                per slab, and intersections only where the ranks differ. Vertical edges are tested directly. */
            double firstHit(double x0, double y0, double x1, double y1) const
            {
                const double none = std::numeric_limits<double>::infinity();
                if (xs_.empty())
                    return none;
                // A motion that starts inside a polygon touches it at once.
                if (inside(x0, y0))
                    return 0.;
                const double xmin = std::min(x0, x1), xmax = std::max(x0, x1);
                if (xmax < xs_.front() || xmin > xs_.back())
                    return none;
                const double dx = x1 - x0, dy = y1 - y0;
                double best = none;
                auto v = std::lower_bound(verticals_.begin(), verticals_.end(), xmin,
                                          [](const Vertical &a, double value)
                                          {
                                              return a.x < value;
                                          });
                for (; v != verticals_.end() && v->x <= xmax; ++v)
                {
                    if (dx != 0.)
                    {
                        const double t = (v->x - x0) / dx, y = y0 + t * dy;
                        if (y >= v->y0 && y <= v->y1)
                            best = std::min(best, t);
                    }
                    else if (std::max(y0, y1) >= v->y0 && std::min(y0, y1) <= v->y1 && dy != 0.)
                        // A vertical motion along a vertical edge's line: it first meets the edge's near end (clamped
                        // to 0 when it starts on the edge).
                        best = std::min(best, std::clamp(((dy > 0. ? v->y0 : v->y1) - y0) / dy, 0., 1.));
                }
                const std::size_t slabs = xs_.size() - 1;
                for (std::size_t k = xmin <= xs_.front() ? 0 : slabOf(xmin); k < slabs && xs_[k] <= xmax; ++k)
                {
                    const double xa = std::max(xs_[k], xmin), xb = std::min(xs_[k + 1], xmax);
                    if (xb < xa)
                        continue;
                    // the segment's heights at the two sides of its part in this slab
                    double ya = y0, yb = y1;
                    if (dx != 0.)
                    {
                        ya = y0 + (xa - x0) / dx * dy;
                        yb = y0 + (xb - x0) / dx * dy;
                    }
                    const std::uint32_t ra = rankBelow(k, xa, ya), rb = rankBelow(k, xb, yb);
                    // the edges between the two ranks are crossed; one more on each side may be touched
                    const std::uint32_t lo = std::max(std::min(ra, rb), start_[k] + 1) - 1,
                                        hi = std::min(std::max(ra, rb) + 1, start_[k + 1]);
                    for (std::uint32_t e = lo; e < hi; ++e)
                    {
                        const Line &l = lines_[e];
                        // f = segment height - edge height; a crossing or a touch where f changes sign or is ~0
                        const double eps = 1e-12, fa = ya - l.at(xa), fb = yb - l.at(xb);
                        if ((fa > eps && fb > eps) || (fa < -eps && fb < -eps))
                            continue;
                        double x = xa;
                        if (std::abs(fa - fb) > 0. && xb > xa)
                            // f is linear in x within the slab: its zero by linear interpolation.
                            x = xa + std::clamp(fa / (fa - fb), 0., 1.) * (xb - xa);
                        double t = 0.;
                        if (dx != 0.)
                            t = (x - x0) / dx;
                        else if (dy != 0.)
                            // A vertical motion: within the slab it is a single x, where the edge's height gives the
                            // contact.
                            t = (l.at(x0) - y0) / dy;
                        best = std::min(best, std::clamp(t, 0., 1.));
                    }
                }
                return best;
            }

        private:
            /** Vertex x values closer than SNAP (radians) as one value, the smallest of their run. A polygons' union
               can leave an edge that is an ulp off vertical (x from -0.043633231299858251 to -0.043633231299858244 on a
                slice border): as a sloped edge of slope 1e15 in a slab 7e-18 wide, its heights rounded so badly that
                firstHit() missed segments crossing it. Snapped, it is a vertical edge. Moving a vertex by 1e-12 rad
                moves the arm by about 1e-12 m, far inside the map's conservative growth. Used while the index is
                built only. */
            class XSnap
            {
            public:
                static constexpr double SNAP = 1e-12;

                explicit XSnap(const MultiPolygon2 &polygons)
                {
                    for (const auto &polygon : polygons)
                    {
                        for (const auto &p : polygon.outer())
                            from_.push_back(p.x());
                        for (const auto &inner : polygon.inners())
                            for (const auto &p : inner)
                                from_.push_back(p.x());
                    }
                    std::sort(from_.begin(), from_.end());
                    from_.erase(std::unique(from_.begin(), from_.end()), from_.end());
                    to_.resize(from_.size());
                    for (std::size_t i = 0; i < from_.size(); ++i)
                        // each value joins the run of the first value within SNAP below it (measured from that first
                        // value, so a run never creeps)
                        to_[i] = i > 0 && from_[i] - to_[i - 1] <= SNAP ? to_[i - 1] : from_[i];
                }

                double operator()(double x) const
                {
                    const auto it = std::lower_bound(from_.begin(), from_.end(), x);
                    return it != from_.end() && *it == x ? to_[static_cast<std::size_t>(it - from_.begin())] : x;
                }

            private:
                std::vector<double> from_, to_;
            };

            struct Line
            {
                double m, c;    ///< y = m x + c
                double x0, y0;  ///< the left end (exact at the vertex)
                double at(double x) const
                {
                    // Exact at the left vertex: m x + c there may round off by an ulp, and edges meeting at a vertex
                    // must agree on it for the parity and rank searches.
                    return x == x0 ? y0 : m * x + c;
                }
            };
            struct Vertical
            {
                double x, y0, y1;
            };

            std::size_t slabOf(double x) const
            {
                const std::size_t slabs = xs_.size() - 1;
                std::size_t b = static_cast<std::size_t>((x - xs_.front()) * binScale_);
                b = std::min(b, binSlab_.size() - 1);
                std::size_t k = binSlab_[b];
                // A bin can straddle slab borders; its entry is the first slab it touches, so walk right to the slab
                // holding x.
                while (k + 1 < slabs && xs_[k + 1] < x)
                    ++k;
                return k;
            }

            /** \brief Index (into lines_) of the first edge of slab k that is not below y at x. */
            std::uint32_t rankBelow(std::size_t k, double x, double y) const
            {
                std::uint32_t lo = start_[k], hi = start_[k + 1];
                while (lo < hi)
                {
                    const std::uint32_t mid = (lo + hi) / 2;
                    if (lines_[mid].at(x) < y)
                        lo = mid + 1;
                    else
                        hi = mid;
                }
                return lo;
            }

            bool insideSlab(std::size_t k, double x, double y) const
            {
                // number of edges below y: binary search over the slab's sorted edges
                const std::uint32_t first = start_[k], lo = rankBelow(k, x, y);
                // Even-odd rule: an odd number of edges below the point (in its slab) means it is inside a polygon
                // (holes included).
                if ((lo - first) % 2 == 1)
                    return true;
                // on an edge (up to rounding): the boundary belongs to the collision region
                const double eps = 1e-12;
                if (lo < start_[k + 1] && lines_[lo].at(x) - y <= eps)
                    return true;
                return lo > first && y - lines_[lo - 1].at(x) <= eps;
            }

            static double pointSegment(double px, double py, double ax, double ay, double bx, double by)
            {
                const double dx = bx - ax, dy = by - ay;
                const double len2 = dx * dx + dy * dy;
                double t = len2 > 0. ? ((px - ax) * dx + (py - ay) * dy) / len2 : 0.;
                t = std::max(0., std::min(1., t));
                // sqrt rather than std::hypot: map coordinates are radians, nowhere near overflow, and hypot's care
                // cost a sixth of ConcentricCircle's clearance ranking (perf, bench_concentric_circle)
                const double ex = px - ax - t * dx, ey = py - ay - t * dy;
                return std::sqrt(ex * ex + ey * ey);
            }

            /** About RASTER_CELLS cells over the edges' bounding box: a cell that no edge touches (with a margin
                against rounding) is wholly inside or wholly outside, classified by its centre; the others are MIXED
                and go to the slabs. */
            void buildRaster(const std::vector<std::pair<Point2, Point2>> &edges)
            {
                raster_.clear();
                if (xs_.size() < 2)
                    return;
                double y0 = std::numeric_limits<double>::infinity(), y1 = -y0;
                for (const auto &e : edges)
                {
                    y0 = std::min({y0, e.first.y(), e.second.y()});
                    y1 = std::max({y1, e.first.y(), e.second.y()});
                }
                for (const auto &v : verticals_)
                {
                    y0 = std::min(y0, v.y0);
                    y1 = std::max(y1, v.y1);
                }
                if (!(y1 > y0) || !(xs_.back() > xs_.front()))
                    return;
                // about square cells, RASTER_CELLS in all: a J-map tile is a narrow strip of θ1
                const double w = xs_.back() - xs_.front(), h = y1 - y0;
                rasterColumns_ =
                    std::clamp(static_cast<int>(std::round(std::sqrt(RASTER_CELLS * w / h))), 1, RASTER_CELLS);
                rasterRows_ = std::max(1, RASTER_CELLS / rasterColumns_);
                rasterX0_ = xs_.front();
                rasterY0_ = y0;
                rasterScaleX_ = rasterColumns_ / w;
                rasterScaleY_ = rasterRows_ / h;
                raster_.assign(static_cast<std::size_t>(rasterColumns_) * rasterRows_, OUTSIDE);
                const auto column = [&](double x)
                {
                    return static_cast<int>(std::floor((x - rasterX0_) * rasterScaleX_));
                };
                const auto row = [&](double y)
                {
                    return static_cast<int>(std::floor((y - rasterY0_) * rasterScaleY_));
                };
                // every cell a segment touches or comes within EPS of (rounding): per column of cells, the rows
                // between the segment's heights at the column's sides
                const double eps =
                    1e-9 * (1. + std::max({std::abs(rasterX0_), std::abs(xs_.back()), std::abs(y0), std::abs(y1)}));
                const auto mark = [&](double ax, double ay, double bx, double by)
                {
                    const int c0 = std::max(0, column(ax - eps)), c1 = std::min(rasterColumns_ - 1, column(bx + eps));
                    for (int c = c0; c <= c1; ++c)
                    {
                        const double xa = std::max(ax, rasterX0_ + c / rasterScaleX_),
                                     xb = std::min(bx, rasterX0_ + (c + 1) / rasterScaleX_);
                        double ya = ay, yb = by;
                        if (bx > ax)
                        {
                            // the heights over the column widened by eps: a steep edge's height at a column border
                            // moves by its slope times the rounding of that border
                            const double m = (by - ay) / (bx - ax);
                            ya = ay + m * (std::clamp(xa - eps, ax, bx) - ax);
                            yb = ay + m * (std::clamp(xb + eps, ax, bx) - ax);
                        }
                        const int r0 = std::max(0, row(std::min(ya, yb) - eps)),
                                  r1 = std::min(rasterRows_ - 1, row(std::max(ya, yb) + eps));
                        for (int r = r0; r <= r1; ++r)
                            raster_[static_cast<std::size_t>(r) * rasterColumns_ + c] = MIXED;
                    }
                };
                for (const auto &e : edges)
                    mark(e.first.x(), e.first.y(), e.second.x(), e.second.y());
                for (const auto &v : verticals_)
                    mark(v.x, v.y0, v.x, v.y1);
                for (int r = 0; r < rasterRows_; ++r)
                    for (int c = 0; c < rasterColumns_; ++c)
                    {
                        std::uint8_t &cell = raster_[static_cast<std::size_t>(r) * rasterColumns_ + c];
                        if (cell != MIXED &&
                            insideExact(rasterX0_ + (c + 0.5) / rasterScaleX_, rasterY0_ + (r + 0.5) / rasterScaleY_))
                            cell = INSIDE;
                    }
            }

            /** cells of a raster, one byte each: 16 KiB a map (planar_2link's eight tiles: 3-8 % of the cells
                mixed; 64 KiB measured no faster) */
            static constexpr int RASTER_CELLS = 1 << 14;
            static constexpr std::uint8_t OUTSIDE = 0, INSIDE = 1, MIXED = 2;
            std::vector<std::uint8_t> raster_;
            int rasterColumns_{0}, rasterRows_{0};
            double rasterX0_{0.}, rasterY0_{0.}, rasterScaleX_{0.}, rasterScaleY_{0.};

            std::vector<double> xs_;
            std::vector<std::uint32_t> start_;
            std::vector<Line> lines_;
            std::vector<Vertical> verticals_;
            double binScale_{1.};
            std::vector<std::uint32_t> binSlab_;
        };

        JMap::~JMap() = default;

        std::shared_ptr<const JMap> JMap::build(const JMapIntervalSource &source, const JMapSettings &settings)
        {
            if (settings.slices < 1)
                throw std::invalid_argument("J-map: slices must be >= 1, got " + std::to_string(settings.slices));
            const auto t0 = std::chrono::steady_clock::now();
            const JMapAxes &axes = source.axes();
            // Each slice stands for its whole θ1 cell, not only its centre value (jmap.md "Intervals"), so the cells
            // tile the axis without gaps.
            const double step = (axes.hi1 - axes.lo1) / settings.slices;
            std::vector<JMapSlice> slices(settings.slices);
            for (int i = 0; i < settings.slices; ++i)
            {
                JMapSlice &s = slices[i];
                s.lo = axes.lo1 + i * step;
                // The last cell ends exactly at the axis limit, whatever the rounding of i * step.
                s.hi = i + 1 == settings.slices ? axes.hi1 : axes.lo1 + (i + 1) * step;
                s.theta1 = 0.5 * (s.lo + s.hi);
                if (settings.trueIntervals)
                    s.trueIntervals = source.intervals(s.theta1);
                const int columns = std::max(1, settings.columns);
                std::vector<JointInterval> all;
                for (int k = 0; k < columns; ++k)
                {
                    const double lo = s.lo + k * (s.hi - s.lo) / columns;
                    const double hi = k + 1 == columns ? s.hi : s.lo + (k + 1) * (s.hi - s.lo) / columns;
                    // Intervals that hold every collision for every θ1 in the column (inflated by how far the links can
                    // move over the column's half width), not only at its centre.
                    s.columns.push_back(source.cellIntervals(lo, hi));
                    all.insert(all.end(), s.columns.back().begin(), s.columns.back().end());
                }
                // The slice's intervals: the union of its columns', so they contain every collision in the whole cell.
                s.intervals = mergeIntervals(std::move(all));
                if (settings.progress)
                    settings.progress(i + 1, settings.slices);
            }
            std::shared_ptr<JMap> map(new JMap());
            map->slices_ = std::move(slices);
            map->settings_ = settings;
            map->settings_.progress = nullptr;  // the caller's callback need not outlive the build
            map->lo1_ = axes.lo1;
            map->hi1_ = axes.hi1;
            map->lo2_ = axes.lo2;
            map->hi2_ = axes.hi2;
            map->finish();
            map->buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            return map;
        }

        std::shared_ptr<const JMap> JMap::fromSlices(std::vector<JMapSlice> slices, double lo2, double hi2,
                                                     const JMapSettings &settings)
        {
            if (slices.empty())
                throw std::invalid_argument("J-map: no slices");
            const auto t0 = std::chrono::steady_clock::now();
            std::shared_ptr<JMap> map(new JMap());
            map->settings_ = settings;
            map->settings_.slices = static_cast<int>(slices.size());
            map->lo1_ = slices.front().lo;
            map->hi1_ = slices.back().hi;
            map->lo2_ = lo2;
            map->hi2_ = hi2;
            map->slices_ = std::move(slices);
            map->finish();
            map->buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            return map;
        }

        std::shared_ptr<const JMap> JMap::fromPolygons(MultiPolygon2 polygons, double lo1, double hi1, double lo2,
                                                       double hi2)
        {
            std::shared_ptr<JMap> map(new JMap());
            map->lo1_ = lo1;
            map->hi1_ = hi1;
            map->lo2_ = lo2;
            map->hi2_ = hi2;
            map->polygons_ = std::move(polygons);
            map->index_ = std::make_unique<JMapIndex>(map->polygons_);
            return map;
        }

        void JMap::finish()
        {
            jmapPolygons(slices_, lo2_, hi2_, settings_, pieces_, polygons_);
            index_ = std::make_unique<JMapIndex>(polygons_);
        }

        bool JMap::collides(double theta1, double theta2) const
        {
            return index_->inside(theta1, theta2);
        }

        double JMap::firstContact(double theta1a, double theta2a, double theta1b, double theta2b) const
        {
            return index_->firstHit(theta1a, theta2a, theta1b, theta2b);
        }

        double JMap::distanceToBoundary(double theta1, double theta2, double maxDistance) const
        {
            return index_->distance(theta1, theta2, maxDistance);
        }

        std::size_t JMap::sliceIndex(double theta1) const
        {
            auto it = std::upper_bound(slices_.begin(), slices_.end(), theta1,
                                       [](double value, const JMapSlice &s)
                                       {
                                           return value < s.lo;
                                       });
            // The last slice whose lower end is at or below theta1; values below the first slice map to slice 0.
            return it == slices_.begin() ? 0 : static_cast<std::size_t>(it - slices_.begin()) - 1;
        }
    }  // namespace validity
}  // namespace michi
