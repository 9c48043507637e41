#ifndef MICHI_VALIDITY_GRID_OCCUPANCY_GRID_
#define MICHI_VALIDITY_GRID_OCCUPANCY_GRID_

#include <michi/validity/scene/Scene.h>

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief A planar occupancy grid: \e width x \e height square cells of \e resolution metres, cell (i, j)
            covering [origin.x + i r, origin.x + (i + 1) r] x [origin.y + j r, origin.y + (j + 1) r] (row 0 at the
            bottom, y up). A cell is occupied when an obstacle may cover part of its (closed) square; outside the
            grid nothing is occupied. */
        struct OccupancyGrid
        {
            int width{0};
            int height{0};
            double resolution{1.};
            Eigen::Vector2d origin{Eigen::Vector2d::Zero()};
            std::vector<std::uint8_t> cells;  ///< 1: occupied; index j * width + i

            bool inside(int i, int j) const
            {
                return i >= 0 && j >= 0 && i < width && j < height;
            }
            bool occupied(int i, int j) const
            {
                return inside(i, j) && cells[static_cast<std::size_t>(j) * width + i] != 0;
            }
            /** \brief Column / row of the cell holding x / y (may lie outside the grid). */
            int column(double x) const;
            int row(double y) const;
            std::size_t occupiedCount() const;
        };

        /** \brief The scene's obstacles rasterised conservatively: a cell is occupied when the shadow of an
            obstacle on the x-y plane (Shape::footprint: the outline of prisms and boxes, the convex hull of other
            shapes) overlaps the cell's square shrunk by \e tolerance metres on each side, so obstacles that only
            touch a cell's edge (a map's boxes on cell boundaries) leave it free; whatever of an obstacle lies in a
            cell's closed square is then covered by an occupied cell grown by \e tolerance. An obstacle whose z range
            (its bounding box) lies wholly above \e zMax or below \e zMin is left out: a robot within [zMin, zMax]
            cannot touch it (a table top over a low robot); by default every obstacle counts. Moving obstacles are
            taken where the scene has them now. */
        OccupancyGrid rasterizeScene(const Scene &scene, double resolution, const Eigen::Vector2d &origin, int width,
                                     int height, double tolerance,
                                     double zMin = -std::numeric_limits<double>::infinity(),
                                     double zMax = std::numeric_limits<double>::infinity());
    }  // namespace validity
}  // namespace michi

#endif
