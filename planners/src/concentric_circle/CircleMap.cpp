#include <michi/planners/concentric_circle/CircleMap.h>

#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace michi
{
    namespace planners
    {
        namespace
        {
            double cross(const Eigen::Vector2d &o, const Eigen::Vector2d &a, const Eigen::Vector2d &b)
            {
                return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
            }

            bool onSegment(const Eigen::Vector2d &p, const Eigen::Vector2d &a, const Eigen::Vector2d &b)
            {
                // Bounding-box test for a point already known to be collinear; the 1e-12 slack keeps an end point that
                // rounding puts just outside the box on the segment.
                return std::min(a.x(), b.x()) - 1e-12 <= p.x() && p.x() <= std::max(a.x(), b.x()) + 1e-12 &&
                       std::min(a.y(), b.y()) - 1e-12 <= p.y() && p.y() <= std::max(a.y(), b.y()) + 1e-12;
            }

            /** closed segments [p1, p2] and [q1, q2] share a point */
            bool segmentsTouch(const Eigen::Vector2d &p1, const Eigen::Vector2d &p2, const Eigen::Vector2d &q1,
                               const Eigen::Vector2d &q2)
            {
                const double d1 = cross(q1, q2, p1), d2 = cross(q1, q2, p2);
                const double d3 = cross(p1, p2, q1), d4 = cross(p1, p2, q2);
                // Proper crossing: each segment's ends lie strictly on both sides of the other's line.
                if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
                    return true;
                // Touching: an end point on the other segment. Touches count as blocked because the polygons are closed
                // sets (the boundary belongs to the collision region, as in JMap).
                const double eps = 1e-14;
                return (std::abs(d1) <= eps && onSegment(p1, q1, q2)) ||
                       (std::abs(d2) <= eps && onSegment(p2, q1, q2)) ||
                       (std::abs(d3) <= eps && onSegment(q1, p1, p2)) || (std::abs(d4) <= eps && onSegment(q2, p1, p2));
            }

            double segmentDistance(const Eigen::Vector2d &p, const Eigen::Vector2d &a, const Eigen::Vector2d &b)
            {
                const Eigen::Vector2d ab = b - a;
                const double len2 = ab.squaredNorm();
                const double t = len2 > 0. ? std::clamp((p - a).dot(ab) / len2, 0., 1.) : 0.;
                return (a + t * ab - p).norm();
            }

            using Value = std::pair<validity::Box2, int>;
        }  // namespace

        std::vector<Eigen::Vector2d> CircleMap::breakpoints(const Eigen::Vector2d &, const Eigen::Vector2d &) const
        {
            return {};
        }

        bool CircleMap::obstacleEdges(const Eigen::Vector2d &, double, std::vector<Edge2> &) const
        {
            return false;
        }

        bool CircleMap::freeArcs(const Eigen::Vector2d &, double, double, int, std::vector<int> &) const
        {
            return false;
        }

        bool CircleMap::inRange(const Eigen::Vector2d &p) const
        {
            // A wrapping axis has no edge: the search may draw circles across +-pi, and lifting wraps the value.
            for (int i = 0; i < 2; ++i)
                if (!wraps[i] && (p[i] < lo[i] || p[i] > hi[i]))
                    return false;
            return true;
        }

        CallbackCircleMap::CallbackCircleMap(PointTest isFree, SegmentTest isVisible, Breaks breaks)
            : isFree_(std::move(isFree)), isVisible_(std::move(isVisible)), breaks_(std::move(breaks))
        {
        }

        bool CallbackCircleMap::isFree(const Eigen::Vector2d &p) const
        {
            return inRange(p) && isFree_(p);
        }

        bool CallbackCircleMap::isVisible(const Eigen::Vector2d &a, const Eigen::Vector2d &b) const
        {
            return isVisible_(a, b);
        }

        std::vector<Eigen::Vector2d> CallbackCircleMap::breakpoints(const Eigen::Vector2d &a,
                                                                    const Eigen::Vector2d &b) const
        {
            return breaks_ ? breaks_(a, b) : std::vector<Eigen::Vector2d>{};
        }

        struct PolygonCircleMap::Index
        {
            // An R-tree of the edges' bounding boxes: visibility and potential queries touch only the few edges near a
            // segment or point, not every edge of the map.
            bgi::rtree<Value, bgi::quadratic<16>> tree;
        };

        PolygonCircleMap::PolygonCircleMap(validity::MultiPolygon2 obstacles, const Eigen::Vector2d &lo,
                                           const Eigen::Vector2d &hi)
            : obstacles_(std::move(obstacles)), index_(std::make_unique<Index>())
        {
            this->lo = lo;
            this->hi = hi;
            auto addRing = [this](const validity::Polygon2::ring_type &ring)
            {
                // closed rings: the last point repeats the first
                const std::size_t n = ring.size() > 0 ? ring.size() - 1 : 0;
                if (n < 2)
                    return;
                const int first = static_cast<int>(edges_.size());
                for (std::size_t i = 0; i < n; ++i)
                {
                    const auto &p = ring[i], &q = ring[i + 1];
                    edges_.push_back({{p.x(), p.y()}, {q.x(), q.y()}});
                    prev_.push_back(i == 0 ? first + static_cast<int>(n) - 1 : static_cast<int>(edges_.size()) - 2);
                }
            };
            for (const auto &poly : obstacles_)
            {
                addRing(poly.outer());
                for (const auto &inner : poly.inners())
                    addRing(inner);
            }
            // next_ is the inverse of prev_: together they name the two edges that share each vertex.
            next_.assign(edges_.size(), -1);
            for (std::size_t e = 0; e < edges_.size(); ++e)
                next_[prev_[e]] = static_cast<int>(e);
            std::vector<Value> values;
            values.reserve(edges_.size());
            for (std::size_t e = 0; e < edges_.size(); ++e)
            {
                const auto &ed = edges_[e];
                validity::Box2 box(validity::Point2(std::min(ed.a.x(), ed.b.x()), std::min(ed.a.y(), ed.b.y())),
                                   validity::Point2(std::max(ed.a.x(), ed.b.x()), std::max(ed.a.y(), ed.b.y())));
                values.emplace_back(box, static_cast<int>(e));
            }
            index_->tree = bgi::rtree<Value, bgi::quadratic<16>>(values.begin(), values.end());
        }

        PolygonCircleMap::~PolygonCircleMap() = default;

        bool PolygonCircleMap::isFree(const Eigen::Vector2d &p) const
        {
            if (!inRange(p))
                return false;
            return inside_ ? !inside_(p) : !bg::covered_by(validity::Point2(p.x(), p.y()), obstacles_);
        }

        bool PolygonCircleMap::blocked(const Eigen::Vector2d &a, const Eigen::Vector2d &b, int skip1, int skip2) const
        {
            validity::Box2 box(validity::Point2(std::min(a.x(), b.x()), std::min(a.y(), b.y())),
                               validity::Point2(std::max(a.x(), b.x()), std::max(a.y(), b.y())));
            thread_local std::vector<Value> found;
            found.clear();
            index_->tree.query(bgi::intersects(box), std::back_inserter(found));
            for (const Value &v : found)
            {
                const int e = v.second;
                if (e == skip1 || e == skip2)
                    continue;
                if (segmentsTouch(a, b, edges_[e].a, edges_[e].b))
                    return true;
            }
            return false;
        }

        bool PolygonCircleMap::isVisible(const Eigen::Vector2d &a, const Eigen::Vector2d &b) const
        {
            if (!inRange(a) || !inRange(b))
                return false;
            // both ends free and no edge crossed or touched: the whole segment is outside every polygon
            return !blocked(a, b, -1, -1) && isFree(a) && isFree(b);
        }

        bool PolygonCircleMap::obstacleEdges(const Eigen::Vector2d &p, double range, std::vector<Edge2> &edges) const
        {
            validity::Box2 box(validity::Point2(p.x() - range, p.y() - range),
                               validity::Point2(p.x() + range, p.y() + range));
            // Buffers kept per thread: this runs for every circle point the search evaluates (about 800 times per
            // solve on planar_2link's J-map), so it allocates nothing after the first calls.
            thread_local std::vector<int> near;
            near.clear();
            Eigen::Vector2d lo = p, hi = p;
            // query() into a vector rather than the qbegin() iterator: the iterator is type-erased and cost more
            // than the edge tests here (perf on planar_2link's J-map).
            thread_local std::vector<Value> found;
            found.clear();
            index_->tree.query(bgi::intersects(box), std::back_inserter(found));
            for (const Value &v : found)
            {
                const int e = v.second;
                const Edge2 &ed = edges_[e];
                // potential_range: a far edge's term Kp / Dp^2 is small (docs/concentric-circle.md), and leaving it out
                // keeps the cost per point bounded on large maps.
                if (segmentDistance(p, ed.a, ed.b) > range)
                    continue;
                near.push_back(e);
                lo = lo.cwiseMin(ed.a).cwiseMin(ed.b);
                hi = hi.cwiseMax(ed.a).cwiseMax(ed.b);
            }
            if (near.empty())
                return true;
            std::sort(near.begin(), near.end());  // deterministic order of the sum
            // Every sight line from P to an end point of a near edge lies in the box of P and those end points, so
            // the edges that can block one are those meeting that box: one R-tree query for all of them, then plain
            // segment tests (an R-tree query per sight line cost more than the tests it saved). The blockers are
            // copied next to their boxes, so the scan per sight line reads one contiguous array.
            struct Blocker
            {
                double loX, loY, hiX, hiY;
                int edge;
            };
            thread_local std::vector<Blocker> blockers;
            blockers.clear();
            const validity::Box2 sight(validity::Point2(lo.x(), lo.y()), validity::Point2(hi.x(), hi.y()));
            found.clear();
            index_->tree.query(bgi::intersects(sight), std::back_inserter(found));
            for (const Value &v : found)
                blockers.push_back({v.first.min_corner().x(), v.first.min_corner().y(), v.first.max_corner().x(),
                                    v.first.max_corner().y(), v.second});
            auto blockedAmong = [&](const Eigen::Vector2d &a, const Eigen::Vector2d &b, int skip1, int skip2)
            {
                const double sLoX = std::min(a.x(), b.x()), sLoY = std::min(a.y(), b.y());
                const double sHiX = std::max(a.x(), b.x()), sHiY = std::max(a.y(), b.y());
                for (const Blocker &q : blockers)
                {
                    // boxes apart: no contact (most blockers are, and this is cheaper than the orientation tests)
                    if (q.hiX < sLoX || q.loX > sHiX || q.hiY < sLoY || q.loY > sHiY)
                        continue;
                    if (q.edge != skip1 && q.edge != skip2 && segmentsTouch(a, b, edges_[q.edge].a, edges_[q.edge].b))
                        return true;
                }
                return false;
            };
            // Vertex v is the first end point of edge v (and the second of prev_[v]): two near edges that share a
            // vertex ask the same question about it (the same sight line, the same two edges skipped), so each
            // answer is kept for the other edge.
            thread_local std::vector<std::pair<int, bool>> seen;
            seen.clear();
            auto vertexHidden = [&](int v)
            {
                for (const auto &known : seen)
                    if (known.first == v)
                        return known.second;
                const bool hidden = blockedAmong(p, edges_[v].a, v, prev_[v]);
                seen.emplace_back(v, hidden);
                return hidden;
            };
            for (const int e : near)
            {
                // Paper 000: only edges whose both end points are visible from P count, so the pockets of concave
                // polygons do not pull the potential in. The edges meeting at the end point itself are skipped, since a
                // sight line always touches them there.
                if (vertexHidden(e) || vertexHidden(next_[e]))
                    continue;
                edges.push_back(edges_[e]);
            }
            return true;
        }

        bool PolygonCircleMap::freeArcs(const Eigen::Vector2d &centre, double radius, double phase, int n,
                                        std::vector<int> &arc) const
        {
            arc.assign(static_cast<std::size_t>(std::max(n, 0)), -1);
            if (n <= 0)
                return true;
            if (!(radius > 0.))
                return false;  // a point, not a circle: the point test
            const double twoPi = 2. * M_PI;
            // Angles (from phase, in [0, 2 pi)) where the circle crosses an edge: |a + t (b - a) - c| = r for t in
            // [0, 1]. Only edges meeting the circle's bounding box can.
            const validity::Box2 box(validity::Point2(centre.x() - radius, centre.y() - radius),
                                     validity::Point2(centre.x() + radius, centre.y() + radius));
            thread_local std::vector<Value> found;
            found.clear();
            index_->tree.query(bgi::intersects(box), std::back_inserter(found));
            std::vector<double> crossings;
            for (const Value &v : found)
            {
                const Edge2 &e = edges_[v.second];
                const Eigen::Vector2d d = e.b - e.a, f = e.a - centre;
                const double a = d.squaredNorm(), b = 2. * f.dot(d), c = f.squaredNorm() - radius * radius;
                const double disc = b * b - 4. * a * c;
                if (!(a > 0.) || disc < 0.)
                    continue;
                const double root = std::sqrt(disc);
                for (const double t : {(-b - root) / (2. * a), (-b + root) / (2. * a)})
                    if (t >= 0. && t <= 1.)
                    {
                        const Eigen::Vector2d q = e.a + t * d - centre;
                        double angle = std::atan2(q.y(), q.x()) - phase;
                        angle -= twoPi * std::floor(angle / twoPi);
                        crossings.push_back(angle >= twoPi ? 0. : angle);
                    }
            }
            std::sort(crossings.begin(), crossings.end());
            auto pointAt = [&](double angle)
            {
                return Eigen::Vector2d(centre +
                                       radius * Eigen::Vector2d(std::cos(phase + angle), std::sin(phase + angle)));
            };
            const std::size_t m = crossings.size();
            // Interval k runs from crossing k to crossing k + 1; the last one wraps round to the first crossing. A
            // circle that crosses nothing is one interval. Each is free or blocked as its middle is.
            std::vector<char> intervalFree(std::max<std::size_t>(m, 1), 0);
            for (std::size_t k = 0; k < intervalFree.size(); ++k)
            {
                const double from = m == 0 ? 0. : crossings[k];
                const double to = m == 0 ? 0. : (k + 1 < m ? crossings[k + 1] : crossings[0] + twoPi);
                const Eigen::Vector2d middle = pointAt(0.5 * (from + to));
                // isFree() is false out of the map's range, but the range's border is no polygon edge: an interval
                // leaving the map is judged by the polygons alone, and the points beyond the border drop out below.
                intervalFree[k] =
                    inside_ ? !inside_(middle) : !bg::covered_by(validity::Point2(middle.x(), middle.y()), obstacles_);
            }
            const double touch = 1e-12;
            for (int i = 0; i < n; ++i)
            {
                const double angle = twoPi * i / n;
                const Eigen::Vector2d p = pointAt(angle);
                if (!inRange(p))
                    continue;
                std::size_t k = m == 0 ? 0 : m - 1;  // before the first crossing: the wrapping interval
                if (m > 0)
                {
                    const auto it = std::upper_bound(crossings.begin(), crossings.end(), angle);
                    if (it != crossings.begin())
                        k = static_cast<std::size_t>(it - crossings.begin()) - 1;
                    // on a crossing: the point touches a polygon, which counts as blocked (closed polygons)
                    const double next = it != crossings.end() ? *it : crossings[0] + twoPi;
                    const double prev = it != crossings.begin() ? *(it - 1) : crossings[m - 1] - twoPi;
                    if (angle - prev <= touch || next - angle <= touch)
                        continue;
                }
                if (intervalFree[k])
                    arc[i] = static_cast<int>(k);
            }
            return true;
        }
    }  // namespace planners
}  // namespace michi
