#ifndef MICHI_VALIDITY_SPHERES_SPHERE_OBSTACLES_
#define MICHI_VALIDITY_SPHERES_SPHERE_OBSTACLES_

// Internal to the sphere checker: a scene snapshot in structure-of-arrays form and the sphere-vs-obstacle kernels.

#include <michi/validity/scene/Scene.h>

#include <Eigen/Core>

#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief Spheres of one robot body in world coordinates (pointers into the checker's scratch arrays). */
        struct SphereBatch
        {
            const float *x, *y, *z, *r;  ///< r: radius (grown by the motion's inflation where asked)
            int n;
        };

        /** \brief A scene's obstacles for the sphere checker, at one changeCount(): each obstacle's bounding
            sphere (broad phase) and its exact shape in closed form. */
        class SphereObstacles
        {
        public:
            SphereObstacles(const Scene &scene);

            const std::string &name(int o) const
            {
                return names_[o];
            }
            /** \brief A body the group does not move touches an obstacle (set by the checker, FCL). */
            bool staticBlocked{false};
            std::uint64_t version() const
            {
                return version_;
            }
            std::size_t size() const
            {
                return kind_.size();
            }
            /** \brief Obstacles per block of the broad phase. */
            static constexpr std::size_t BLOCK = 8;
            /** \brief Writes to \e out the indices of the obstacles whose bounding sphere meets the sphere (c, r)
                and returns their count; \e out holds candidateCapacity() entries. */
            int candidates(const Eigen::Vector3f &c, float r, int *out) const;
            std::size_t candidateCapacity() const
            {
                return bx_.size();
            }
            /** \brief Does the sphere (c, r) touch obstacle \e o? (The same test as hits() for one sphere.) */
            bool hitsSphere(int o, const Eigen::Vector3f &c, float r) const;
            /** \brief Does any sphere of \e batch touch obstacle \e o? */
            bool hits(int o, const SphereBatch &batch) const;
            /** \brief Smallest distance between a sphere's surface and obstacle \e o (negative inside; lower
                bound: shapes in closed form are exact, meshes too). */
            float distance(int o, const SphereBatch &batch) const;
            /** \brief Distance between the bounding spheres of obstacle \e o and (c, r). */
            float boundDistance(int o, const Eigen::Vector3f &c, float r) const;

            /** \brief A lower bound of the distance from \e p to every obstacle (the shapes as squaredDistances()
                measures them), from a grid of distances made after GRID_AFTER calls in a row on one thread (the sphere
                checker asks once per moving body: about 400 state checks of a 10-body arm), so a scene that keeps
                changing never pays for one; -infinity (no bound) until then. A body
                whose bounding sphere is closer to nothing than this skips the broad and narrow phases. */
            float distanceBound(const Eigen::Vector3f &p) const
            {
                const DistanceGrid *grid = grid_.load(std::memory_order_acquire);
                if (grid == nullptr)
                {
                    countQuery();
                    return -std::numeric_limits<float>::infinity();
                }
                return grid->bound(p);
            }
            /** \brief distanceBound(c) > r, without its square root (a state check asks it for every moving body). */
            bool clears(const Eigen::Vector3f &c, float r) const
            {
                const DistanceGrid *grid = grid_.load(std::memory_order_acquire);
                if (grid == nullptr)
                {
                    countQuery();
                    return false;
                }
                return grid->clears(c, r);
            }
            static constexpr unsigned GRID_AFTER = 4096;
            /** \brief Make the grid now (tests; queries make it themselves). */
            void makeGrid() const;
            /** \brief Cells of the grid (0 before it is made, or when the scene has no obstacle). */
            std::size_t gridCells() const;

        private:
            /** Distances from cell centres to one mesh's triangles over a box around the mesh, in both directions
                bounded: a sphere clear of the mesh or in it by more than the cell's reach is decided by one lookup,
                and only spheres whose surface lies within about a cell of the mesh walk its tree (on xarm6_ring the
                walks were a quarter of a state check's time: docs/checking.md). */
            struct MeshField
            {
                Eigen::Vector3f lo{Eigen::Vector3f::Zero()};  ///< the field's lowest corner
                float cell{1.f}, inverse{1.f};
                int nx{0}, ny{0}, nz{0};
                float reach{0.f};  ///< how far beyond the mesh's box the field reaches
                /** per cell, x fastest: the distance from its centre to the mesh in STEPs, rounded down (lowered by
                    the float margin first), or FAR */
                std::vector<std::uint16_t> steps;
                static constexpr float STEP = 5e-5f;          ///< metres; 65534 steps reach 3.2 m
                static constexpr std::uint16_t FAR = 0xffff;  ///< no triangle within farBound of the cell's centre
                float farBound{0.f};                          ///< the distance a FAR cell's centre has at least
                /** -1: the sphere (p, r) is clear of the mesh; 1: it meets the mesh (distance below r); 0: the field
                    cannot tell (the caller walks the tree). */
                int decide(const Eigen::Vector3f &p, float r) const;
            };
            /** Distances from cell centres to the nearest obstacle over a box around the obstacles; outside it, the
                distance to the obstacles' bounding box. */
            struct DistanceGrid
            {
                Eigen::Vector3f lo;                ///< the grid's lowest corner
                Eigen::Vector3f boundLo, boundHi;  ///< box of every obstacle's bounding sphere
                float cell{1.f}, inverse{1.f};
                int nx{0}, ny{0}, nz{0};
                /** per cell, x fastest: the distance in STEPs, rounded down (already lowered by the float margin); a
                    byte keeps the grid in a quarter of the memory, so its lookups stay in a core's cache */
                std::vector<std::uint8_t> distance;
                std::vector<MeshField> meshFields;     ///< per mesh (index_ of a MESH obstacle)
                static constexpr float STEP = 0.002f;  ///< metres; 255 steps: distances from 0.51 m on read as 0.51 m
                float bound(const Eigen::Vector3f &p) const
                {
                    const Eigen::Vector3f u = (p - lo) * inverse;
                    if ((u.array() >= 0.f).all() && u.x() < nx && u.y() < ny && u.z() < nz)
                    {
                        const int i = static_cast<int>(u.x()), j = static_cast<int>(u.y()), k = static_cast<int>(u.z());
                        const Eigen::Vector3f centre = lo + cell * Eigen::Vector3f(i + 0.5f, j + 0.5f, k + 0.5f);
                        // 1-Lipschitz: the distance at p is at least the centre's minus how far p is from it
                        return STEP * distance[(static_cast<std::size_t>(k) * ny + j) * nx + i] - (p - centre).norm();
                    }
                    // outside the grid: at least the distance to the box that holds every obstacle
                    return (p.cwiseMax(boundLo).cwiseMin(boundHi) - p).norm();
                }
                /** bound(p) > r, compared in squares: the cell's distance less r must exceed |p - centre|. */
                bool clears(const Eigen::Vector3f &p, float r) const
                {
                    const Eigen::Vector3f u = (p - lo) * inverse;
                    if ((u.array() >= 0.f).all() && u.x() < nx && u.y() < ny && u.z() < nz)
                    {
                        const int i = static_cast<int>(u.x()), j = static_cast<int>(u.y()), k = static_cast<int>(u.z());
                        const Eigen::Vector3f centre = lo + cell * Eigen::Vector3f(i + 0.5f, j + 0.5f, k + 0.5f);
                        const float a = STEP * distance[(static_cast<std::size_t>(k) * ny + j) * nx + i] - r;
                        return a > 0.f && a * a > (p - centre).squaredNorm();
                    }
                    return r < 0.f || (p.cwiseMax(boundLo).cwiseMin(boundHi) - p).squaredNorm() > r * r;
                }
            };
            void countQuery() const;
            /** The distance grid of this snapshot (null without obstacles); makeGrid() publishes it once. */
            std::unique_ptr<DistanceGrid> buildGrid() const;

            enum Kind : int
            {
                BOX,
                SPHERE,
                CYLINDER,
                CAPSULE,
                PRISM,
                MESH
            };
            struct Frame
            {
                Eigen::Matrix3f rt;  ///< world to obstacle rotation
                Eigen::Vector3f t;   ///< obstacle origin in the world
            };
            struct Prism
            {
                std::vector<Eigen::Vector2f> outline;
                float zMin, zMax;
            };
            struct MeshNode
            {
                Eigen::Vector3f centre;
                float radius;
                int left, right;   ///< children, or -1 for a leaf
                int first, count;  ///< leaf: triangles [first, first + count) of order
            };
            struct Mesh
            {
                std::vector<Eigen::Vector3f> corners;  ///< world coordinates, 3 per triangle
                std::vector<MeshNode> nodes;
            };
            /** Squared distance from each centre of \e batch to the shape of \e o, in \e d2 (n values). */
            void squaredDistances(int o, const SphereBatch &batch, float *d2) const;
            /** The kernel of squaredDistances() on Eigen arrays \e x, \e y, \e z (temporaries of type A), written to
                \e d2: the batch's maps, or fixed one-element arrays for hitsSphere(). */
            template <typename A, typename In, typename Out>
            void squaredDistancesOf(int o, const In &x, const In &y, const In &z, Out &d2) const;
            float meshDistance(const Mesh &mesh, const Eigen::Vector3f &p, float limit) const;
            MeshField buildMeshField(const Mesh &mesh) const;
            void addMesh(const Obstacle &obstacle);

            std::uint64_t version_{0};
            std::vector<std::string> names_;
            std::vector<int> kind_, index_;         ///< per obstacle: kind and index into frames_/the kind's table
            std::vector<float> bx_, by_, bz_, br_;  ///< bounding spheres, padded to whole BLOCKs
            std::vector<Frame> frames_;
            std::vector<Eigen::Vector3f> size_;  ///< box: half extents; sphere/cylinder/capsule: (r, half length, 0)
            std::vector<Prism> prisms_;
            std::vector<Mesh> meshes_;
            std::uint64_t serial_{0};  ///< distinct per snapshot made in this process (countQuery())
            mutable std::once_flag gridOnce_;
            mutable std::unique_ptr<DistanceGrid> gridStore_;
            mutable std::atomic<const DistanceGrid *> grid_{nullptr};
        };
    }  // namespace validity
}  // namespace michi

#endif
