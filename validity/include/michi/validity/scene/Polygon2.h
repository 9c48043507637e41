#ifndef MICHI_VALIDITY_POLYGON2_
#define MICHI_VALIDITY_POLYGON2_

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/linestring.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief Planar types of michi's 2-D views (Boost.Geometry, clockwise outer rings, closed). */
        using Point2 = boost::geometry::model::d2::point_xy<double>;
        using Polygon2 = boost::geometry::model::polygon<Point2>;
        using MultiPolygon2 = boost::geometry::model::multi_polygon<Polygon2>;
        using Segment2 = boost::geometry::model::segment<Point2>;
        using Linestring2 = boost::geometry::model::linestring<Point2>;
        using Box2 = boost::geometry::model::box<Point2>;

        /** \brief Build a valid (corrected) polygon from an outline given in either orientation. */
        Polygon2 makePolygon2(const std::vector<Point2> &outline);

        /** \brief The union of \e parts (an obstacle's footprint each): only parts whose bounding boxes overlap,
            directly or through others, are united with Boost.Geometry; the rest are listed as they are. */
        MultiPolygon2 uniteFootprints(std::vector<MultiPolygon2> parts);

        /** \brief A circle approximated by a regular polygon that contains it (vertices outside the circle). */
        Polygon2 circlePolygon2(const Point2 &centre, double radius, int sides = 32);
    }  // namespace validity
}  // namespace michi

#endif
