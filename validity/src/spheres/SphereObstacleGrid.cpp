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
            /** Cells of a mesh's own field at most (2 bytes each), and how far around the mesh's box it reaches
                (metres): beyond it a sphere smaller than that is clear without a lookup. */
            constexpr std::size_t MAX_MESH_CELLS = 1u << 17;
            constexpr float MESH_REACH = 0.1f;

            /** The finest cell, at least \e smallest metres, that covers \e extent with at most \e maxCells cells
                and MAX_PER_AXIS per axis; the cell counts per axis go to \e nx, \e ny, \e nz. */
            float fitCells(const Eigen::Vector3f &extent, std::size_t maxCells, float smallest, int &nx, int &ny,
                           int &nz)
            {
                float cell = std::cbrt(extent.prod() / static_cast<float>(maxCells));
                cell = std::max({cell, extent.maxCoeff() / static_cast<float>(MAX_PER_AXIS), smallest});
                for (;; cell *= 1.01f)
                {
                    nx = static_cast<int>(std::ceil(extent.x() / cell));
                    ny = static_cast<int>(std::ceil(extent.y() / cell));
                    nz = static_cast<int>(std::ceil(extent.z() / cell));
                    if (nx <= MAX_PER_AXIS && ny <= MAX_PER_AXIS && nz <= MAX_PER_AXIS &&
                        static_cast<std::size_t>(nx) * ny * nz <= maxCells)
                        return cell;
                }
            }
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
            const float cell = fitCells(extent, MAX_CELLS, 0.01f, grid->nx, grid->ny, grid->nz);
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
            grid->meshFields.reserve(meshes_.size());
            for (const Mesh &mesh : meshes_)
                grid->meshFields.push_back(buildMeshField(mesh));
            return grid;
        }

        SphereObstacles::MeshField SphereObstacles::buildMeshField(const Mesh &mesh) const
        {
            MeshField field;
            Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
            Eigen::Vector3f hi = -lo;
            for (const Eigen::Vector3f &c : mesh.corners)
            {
                lo = lo.cwiseMin(c);
                hi = hi.cwiseMax(c);
            }
            if (mesh.corners.empty())
                return field;  // no cell: every query walks (and finds nothing)
            field.reach = MESH_REACH;
            field.lo = lo - Eigen::Vector3f::Constant(MESH_REACH);
            const Eigen::Vector3f extent = hi - lo + Eigen::Vector3f::Constant(2.f * MESH_REACH);
            const float cell = fitCells(extent, MAX_MESH_CELLS, 0.002f, field.nx, field.ny, field.nz);
            field.cell = cell;
            field.inverse = 1.f / cell;
            // Exact distances only up to a cell beyond the reach: a walk with that limit prunes the far cells early,
            // and a sphere that far out is decided by the lower bound alone.
            const float limit = MESH_REACH + cell;
            field.farBound = limit - MARGIN;
            field.steps.assign(static_cast<std::size_t>(field.nx) * field.ny * field.nz, MeshField::FAR);
            std::size_t at = 0;
            for (int k = 0; k < field.nz; ++k)
                for (int j = 0; j < field.ny; ++j)
                    for (int i = 0; i < field.nx; ++i, ++at)
                    {
                        const Eigen::Vector3f c = field.lo + cell * Eigen::Vector3f(i + 0.5f, j + 0.5f, k + 0.5f);
                        const float d = meshDistance(mesh, c, limit);
                        if (d < limit)
                            // rounded down after the margin: the stored distance never exceeds the true one
                            field.steps[at] = static_cast<std::uint16_t>(std::min(
                                std::floor(std::max(d - MARGIN, 0.f) / MeshField::STEP), MeshField::FAR - 1.f));
                    }
            return field;
        }

        int SphereObstacles::MeshField::decide(const Eigen::Vector3f &p, float r) const
        {
            const Eigen::Vector3f u = (p - lo) * inverse;
            if (!((u.array() >= 0.f).all() && u.x() < nx && u.y() < ny && u.z() < nz))
                // outside the field: more than reach from the mesh's box on some axis, so from every triangle
                return r < reach - MARGIN ? -1 : 0;
            const int i = static_cast<int>(u.x()), j = static_cast<int>(u.y()), k = static_cast<int>(u.z());
            const Eigen::Vector3f centre = lo + cell * Eigen::Vector3f(i + 0.5f, j + 0.5f, k + 0.5f);
            // 1-Lipschitz both ways: the distance at p is within |p - centre| of the centre's
            const float off = (p - centre).norm();
            const std::uint16_t q = steps[(static_cast<std::size_t>(k) * ny + j) * nx + i];
            if (q == FAR)
                return farBound - off >= r ? -1 : 0;
            // stored: floor((d - MARGIN) / STEP), so the centre's distance d lies in [q STEP + MARGIN, (q + 1) STEP +
            // MARGIN), up to the walk's float round-off, which the second MARGIN covers: clear by at least MARGIN,
            // or nearer than r by at least that
            if (STEP * q - off >= r)
                return -1;
            if (STEP * (q + 1) + 2.f * MARGIN + off < r)
                return 1;
            return 0;
        }
    }  // namespace validity
}  // namespace michi
