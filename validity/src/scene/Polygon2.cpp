#include <michi/validity/scene/Polygon2.h>

#include <cmath>

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
    }  // namespace validity
}  // namespace michi
