// The distance grid of a sphere-checker scene snapshot: a broad phase of one lookup per robot body.

#include "SphereObstacles.h"

#include <algorithm>
#include <cmath>

namespace michi
{
    namespace validity
    {
        namespace
        {
            /** Cells at most, and per axis at most (squaredDistances() takes batches of up to 256 points). */
            constexpr std::size_t MAX_CELLS = 1u << 18;
            constexpr int MAX_PER_AXIS = 256;
            /** How far around the obstacles the grid reaches (metres): the radius of a large robot body. */
            constexpr float REACH = 0.3f;
            /** Float rounding of the kernels and of the cell centres stays far below this (metres). */
            constexpr float MARGIN = 1e-4f;
        }  // namespace

        void SphereObstacles::countQuery() const
        {
            // Per thread, queries in a row on this snapshot; a snapshot replaced before GRID_AFTER never gets a grid.
            // By serial number, not address: a snapshot made where a destroyed one lived must start from 0.
            thread_local std::uint64_t last = 0;
            thread_local unsigned count = 0;
            if (last != serial_)
            {
                last = serial_;
                count = 0;
            }
            if (++count == GRID_AFTER)
                makeGrid();
        }

        std::size_t SphereObstacles::gridCells() const
        {
            const DistanceGrid *grid = grid_.load(std::memory_order_acquire);
            return grid == nullptr ? 0 : grid->distance.size();
        }

        void SphereObstacles::makeGrid() const
        {
            std::call_once(gridOnce_,
                           [this]
                           {
                               gridStore_ = buildGrid();
                               grid_.store(gridStore_.get(), std::memory_order_release);
                           });
        }

        std::unique_ptr<SphereObstacles::DistanceGrid> SphereObstacles::buildGrid() const
        {
            const std::size_t n = kind_.size();
            if (n == 0)
                return nullptr;  // no obstacle: the broad phase finds nothing anyway
            auto grid = std::make_unique<DistanceGrid>();
            Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
            Eigen::Vector3f hi = -lo;
            for (std::size_t o = 0; o < n; ++o)
            {
                const Eigen::Vector3f c(bx_[o], by_[o], bz_[o]);
                lo = lo.cwiseMin(c - Eigen::Vector3f::Constant(br_[o]));
                hi = hi.cwiseMax(c + Eigen::Vector3f::Constant(br_[o]));
            }
            grid->boundLo = lo;
            grid->boundHi = hi;
            grid->lo = lo - Eigen::Vector3f::Constant(REACH);
            const Eigen::Vector3f extent = hi + Eigen::Vector3f::Constant(REACH) - grid->lo;
            // the finest cell that keeps the grid within MAX_CELLS and MAX_PER_AXIS
            float cell = std::cbrt(extent.prod() / static_cast<float>(MAX_CELLS));
            cell = std::max(cell, extent.maxCoeff() / static_cast<float>(MAX_PER_AXIS));
            cell = std::max(cell, 0.01f);
            for (;; cell *= 1.01f)
            {
                grid->nx = static_cast<int>(std::ceil(extent.x() / cell));
                grid->ny = static_cast<int>(std::ceil(extent.y() / cell));
                grid->nz = static_cast<int>(std::ceil(extent.z() / cell));
                if (grid->nx <= MAX_PER_AXIS && grid->ny <= MAX_PER_AXIS && grid->nz <= MAX_PER_AXIS &&
                    static_cast<std::size_t>(grid->nx) * grid->ny * grid->nz <= MAX_CELLS)
                    break;
            }
            grid->cell = cell;
            grid->inverse = 1.f / cell;
            const int nx = grid->nx;
            grid->distance.assign(static_cast<std::size_t>(nx) * grid->ny * grid->nz, 0);
            std::vector<float> x(nx), y(nx), z(nx), r(nx, 0.f), d2(nx), row(nx);
            for (int i = 0; i < nx; ++i)
                x[i] = grid->lo.x() + cell * (i + 0.5f);
            for (int k = 0; k < grid->nz; ++k)
                for (int j = 0; j < grid->ny; ++j)
                {
                    std::fill(y.begin(), y.end(), grid->lo.y() + cell * (j + 0.5f));
                    std::fill(z.begin(), z.end(), grid->lo.z() + cell * (k + 0.5f));
                    std::fill(row.begin(), row.end(), std::numeric_limits<float>::infinity());
                    const SphereBatch batch{x.data(), y.data(), z.data(), r.data(), nx};
                    for (std::size_t o = 0; o < n; ++o)
                    {
                        // A row far from the obstacle's bounding sphere takes that distance (a
                        // lower bound, and all a broad phase needs that far out); only rows near
                        // it pay for the exact kernels (meshes walk a tree per point).
                        float nearest = std::numeric_limits<float>::infinity();
                        for (int i = 0; i < nx; ++i)
                        {
                            const float dx = x[i] - bx_[o], dy = y[i] - by_[o], dz = z[i] - bz_[o];
                            d2[i] = std::sqrt(dx * dx + dy * dy + dz * dz) - br_[o];
                            nearest = std::min(nearest, d2[i]);
                        }
                        if (nearest > REACH)
                        {
                            for (int i = 0; i < nx; ++i)
                                row[i] = std::min(row[i], d2[i]);
                            continue;
                        }
                        squaredDistances(static_cast<int>(o), batch, d2.data());
                        for (int i = 0; i < nx; ++i)
                            row[i] = std::min(row[i], std::sqrt(d2[i]));
                    }
                    // whole steps, rounded down: the stored distance never exceeds the true one
                    std::uint8_t *cells = grid->distance.data() + (static_cast<std::size_t>(k) * grid->ny + j) * nx;
                    for (int i = 0; i < nx; ++i)
                        cells[i] = static_cast<std::uint8_t>(
                            std::min(std::floor(std::max(row[i] - MARGIN, 0.f) / DistanceGrid::STEP), 255.f));
                }
            return grid;
        }
    }  // namespace validity
}  // namespace michi
