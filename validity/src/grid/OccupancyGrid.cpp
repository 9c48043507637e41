#include <michi/validity/grid/OccupancyGrid.h>

#include <fcl/math/bv/AABB.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace bg = boost::geometry;

namespace michi
{
    namespace validity
    {
        int OccupancyGrid::column(double x) const
        {
            const double c = std::floor((x - origin.x()) / resolution);
            // Clamped before the cast: a far (or infinite) coordinate would overflow int; callers test inside() anyway.
            return static_cast<int>(std::max(-1e9, std::min(1e9, c)));
        }

        int OccupancyGrid::row(double y) const
        {
            const double c = std::floor((y - origin.y()) / resolution);
            return static_cast<int>(std::max(-1e9, std::min(1e9, c)));
        }

        std::size_t OccupancyGrid::occupiedCount() const
        {
            return static_cast<std::size_t>(std::count(cells.begin(), cells.end(), std::uint8_t{1}));
        }

        namespace
        {
            /** The lowest and highest z of an obstacle: its FCL geometries' local boxes taken to the world. */
            std::pair<double, double> zRange(const Obstacle &obstacle)
            {
                double lo = std::numeric_limits<double>::infinity(), hi = -lo;
                for (const auto &g : obstacle.shape->geometries())
                {
                    const fcl::AABBd &box = g->aabb_local;
                    for (int corner = 0; corner < 8; ++corner)
                    {
                        const Eigen::Vector3d local((corner & 1) ? box.max_.x() : box.min_.x(),
                                                    (corner & 2) ? box.max_.y() : box.min_.y(),
                                                    (corner & 4) ? box.max_.z() : box.min_.z());
                        const double z = (obstacle.pose * local).z();
                        lo = std::min(lo, z);
                        hi = std::max(hi, z);
                    }
                }
                return {lo, hi};
            }
        }  // namespace

        OccupancyGrid rasterizeScene(const Scene &scene, double resolution, const Eigen::Vector2d &origin, int width,
                                     int height, double tolerance, double zMin, double zMax)
        {
            OccupancyGrid grid;
            grid.width = width;
            grid.height = height;
            grid.resolution = resolution;
            grid.origin = origin;
            grid.cells.assign(static_cast<std::size_t>(width) * height, 0);
            const double r = resolution;
            const bool everyHeight = std::isinf(zMin) && std::isinf(zMax);
            for (const auto &obstacle : scene.obstacles())
            {
                if (!everyHeight)
                {
                    // Wholly above or below the robot (with a margin of float rounding): FCL finds no contact with
                    // it at any pose, so leaving it out keeps the grid conservative. Touching still counts.
                    const auto z = zRange(obstacle);
                    const double margin = 1e-9 * (1. + std::abs(zMin) + std::abs(zMax));
                    if (z.first > zMax + margin || z.second < zMin - margin)
                        continue;
                }
                const MultiPolygon2 shadow = obstacle.shape->footprint(obstacle.pose);
                for (const auto &polygon : shadow)
                {
                    const Box2 bounds = bg::return_envelope<Box2>(polygon);
                    // One cell of slack around the envelope: the per-cell test below decides, with the tolerance.
                    const int i0 = std::max(0, grid.column(bounds.min_corner().x()) - 1);
                    const int i1 = std::min(width - 1, grid.column(bounds.max_corner().x()) + 1);
                    const int j0 = std::max(0, grid.row(bounds.min_corner().y()) - 1);
                    const int j1 = std::min(height - 1, grid.row(bounds.max_corner().y()) + 1);
                    // an axis-aligned rectangle (a map's run of cells) needs no polygon test
                    const bool rectangle = polygon.inners().empty() && polygon.outer().size() == 5 &&
                                           // A four-corner polygon as large as its envelope is that envelope.
                                           std::abs(bg::area(polygon)) >=
                                               (1. - 1e-12) * (bounds.max_corner().x() - bounds.min_corner().x()) *
                                                   (bounds.max_corner().y() - bounds.min_corner().y());
                    for (int j = j0; j <= j1; ++j)
                        for (int i = i0; i <= i1; ++i)
                        {
                            std::uint8_t &cell = grid.cells[static_cast<std::size_t>(j) * width + i];
                            if (cell)
                                continue;
                            // The cell shrunk by the tolerance: a box of a map that ends exactly on a cell edge
                            // occupies its own cells, not the neighbours it touches.
                            const double x0 = origin.x() + i * r + tolerance, x1 = origin.x() + (i + 1) * r - tolerance;
                            const double y0 = origin.y() + j * r + tolerance, y1 = origin.y() + (j + 1) * r - tolerance;
                            if (x1 < bounds.min_corner().x() || x0 > bounds.max_corner().x() ||
                                y1 < bounds.min_corner().y() || y0 > bounds.max_corner().y())
                                continue;
                            if (rectangle || bg::intersects(Box2(Point2(x0, y0), Point2(x1, y1)), polygon))
                                cell = 1;
                        }
                }
            }
            return grid;
        }
    }  // namespace validity
}  // namespace michi
