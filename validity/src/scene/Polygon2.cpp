#include <michi/validity/scene/Polygon2.h>

#include <boost/geometry/index/rtree.hpp>

#include <cmath>
#include <iterator>

namespace bg = boost::geometry;

namespace michi
{
    namespace validity
    {
        Polygon2 makePolygon2(const std::vector<Point2> &outline)
        {
            Polygon2 polygon;
            for (const auto &p : outline)
                bg::append(polygon.outer(), p);
            bg::correct(polygon);  // orientation and closure as the polygon type wants them
            return polygon;
        }

        Polygon2 circlePolygon2(const Point2 &centre, double radius, int sides)
        {
            // vertices at radius / cos(pi / sides): the polygon's edges touch the circle from outside
            const double r = radius / std::cos(M_PI / sides);
            std::vector<Point2> outline;
            outline.reserve(sides);
            for (int i = 0; i < sides; ++i)
            {
                const double a = 2. * M_PI * i / sides;
                outline.emplace_back(centre.x() + r * std::cos(a), centre.y() + r * std::sin(a));
            }
            return makePolygon2(outline);
        }

        namespace
        {
            /** Union of pieces in pairs, level by level: each piece takes part in about log2(n) unions. */
            MultiPolygon2 uniteInPairs(std::vector<MultiPolygon2> parts)
            {
                while (parts.size() > 1)
                {
                    std::vector<MultiPolygon2> next((parts.size() + 1) / 2);
                    for (std::size_t i = 0; i + 1 < parts.size(); i += 2)
                        bg::union_(parts[i], parts[i + 1], next[i / 2]);
                    if (parts.size() % 2 == 1)
                        next.back() = std::move(parts.back());
                    parts = std::move(next);
                }
                return parts.empty() ? MultiPolygon2{} : std::move(parts.front());
            }
        }  // namespace

        MultiPolygon2 uniteFootprints(std::vector<MultiPolygon2> parts)
        {
            // Only pieces whose boxes overlap (directly or through others) are united; the groups are then listed
            // side by side, which is their union because boxes apart mean outlines apart (a piece in another's hole
            // has its box inside the other's). Uniting everything, even in pairs, compared every ring with every
            // other ring (Boost.Geometry's select_rings): a map of 23,000 boxes took minutes in one union.
            namespace bgi = boost::geometry::index;
            using Entry = std::pair<Box2, std::size_t>;
            std::vector<Entry> boxes;
            for (std::size_t i = 0; i < parts.size(); ++i)
                if (!parts[i].empty())
                    boxes.emplace_back(bg::return_envelope<Box2>(parts[i]), i);
            const bgi::rtree<Entry, bgi::rstar<16>> tree(boxes.begin(), boxes.end());
            std::vector<std::size_t> root(parts.size());
            for (std::size_t i = 0; i < root.size(); ++i)
                root[i] = i;
            const auto find = [&root](std::size_t i)
            {
                while (root[i] != i)
                    i = root[i] = root[root[i]];
                return i;
            };
            std::vector<Entry> touching;
            for (const auto &b : boxes)
            {
                touching.clear();
                tree.query(bgi::intersects(b.first), std::back_inserter(touching));
                for (const auto &t : touching)
                    root[find(t.second)] = find(b.second);
            }
            std::vector<std::vector<MultiPolygon2>> groups(parts.size());
            for (const auto &b : boxes)
                groups[find(b.second)].push_back(std::move(parts[b.second]));
            MultiPolygon2 all;
            for (auto &group : groups)
                for (auto &polygon : uniteInPairs(std::move(group)))
                    all.push_back(std::move(polygon));
            return all;
        }

    }  // namespace validity
}  // namespace michi
