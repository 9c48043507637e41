/* Grown obstacles (Minkowski sum with the hand's disk) and the bottleneck region of the paper. */

#include <michi/validity/jmap/JMap.h>

#include <cmath>
#include <stdexcept>

namespace bg = boost::geometry;

namespace michi
{
    namespace validity
    {
        MultiPolygon2 growObstacles(const MultiPolygon2 &obstacles, double distance, int pointsPerCircle)
        {
            if (distance < 0.)
                throw std::invalid_argument("growObstacles: negative distance " + std::to_string(distance));
            if (distance == 0. || obstacles.empty())
                return obstacles;
            // Below 8 points the chords' inflation (1 / cos(pi / n) - 1, over 8 % at n = 8) would grow obstacles
            // visibly.
            pointsPerCircle = std::max(pointsPerCircle, 8);
            // Boost puts the arc vertices on the circle and joins them by chords; grow the circle so the chords
            // stay outside the true arc: the result contains the exact Minkowski sum
            const double grown = distance / std::cos(M_PI / pointsPerCircle);
            bg::strategy::buffer::distance_symmetric<double> dist(grown);
            bg::strategy::buffer::join_round join(pointsPerCircle);
            bg::strategy::buffer::end_round end(pointsPerCircle);
            bg::strategy::buffer::point_circle circle(pointsPerCircle);
            // Round joins and ends everywhere: the hand is a disk (paper 000: grown by the hand's reach), so sharp
            // corners grow into arcs, not mitres.
            bg::strategy::buffer::side_straight side;
            MultiPolygon2 out;
            bg::buffer(obstacles, out, dist, side, join, end, circle);
            return out;
        }

        MultiPolygon2 bottleneck(const JMap &grown, const JMap &plain)
        {
            MultiPolygon2 out;
            // Paper 000: the bottleneck is grown J-map - J-map, where the arm itself is free but the hand may collide.
            bg::difference(grown.polygons(), plain.polygons(), out);
            return out;
        }
    }  // namespace validity
}  // namespace michi
