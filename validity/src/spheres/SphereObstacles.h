#ifndef MICHI_VALIDITY_SPHERES_SPHERE_OBSTACLES_
#define MICHI_VALIDITY_SPHERES_SPHERE_OBSTACLES_

// Internal to the sphere checker: a scene snapshot in structure-of-arrays form and the sphere-vs-obstacle kernels.

#include <michi/validity/scene/Scene.h>

#include <Eigen/Core>

#include <cstdint>
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
            /** \brief Indices of the obstacles whose bounding sphere meets the sphere (c, r). */
            void candidates(const Eigen::Vector3f &c, float r, std::vector<int> &out) const;
            /** \brief Does the sphere (c, r) touch obstacle \e o? (The same test as hits() for one sphere.) */
            bool hitsSphere(int o, const Eigen::Vector3f &c, float r) const;
            /** \brief Does any sphere of \e batch touch obstacle \e o? */
            bool hits(int o, const SphereBatch &batch) const;
            /** \brief Smallest distance between a sphere's surface and obstacle \e o (negative inside; lower
                bound: shapes in closed form are exact, meshes too). */
            float distance(int o, const SphereBatch &batch) const;
            /** \brief Distance between the bounding spheres of obstacle \e o and (c, r). */
            float boundDistance(int o, const Eigen::Vector3f &c, float r) const;

        private:
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
            void addMesh(const Obstacle &obstacle);

            std::uint64_t version_{0};
            std::vector<std::string> names_;
            std::vector<int> kind_, index_;         ///< per obstacle: kind and index into frames_/the kind's table
            std::vector<float> bx_, by_, bz_, br_;  ///< bounding spheres
            std::vector<Frame> frames_;
            std::vector<Eigen::Vector3f> size_;  ///< box: half extents; sphere/cylinder/capsule: (r, half length, 0)
            std::vector<Prism> prisms_;
            std::vector<Mesh> meshes_;
        };
    }  // namespace validity
}  // namespace michi

#endif
