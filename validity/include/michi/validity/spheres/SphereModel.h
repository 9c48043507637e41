#ifndef MICHI_VALIDITY_SPHERES_SPHERE_MODEL_
#define MICHI_VALIDITY_SPHERES_SPHERE_MODEL_

#include <michi/validity/robot/RobotModel.h>

#include <Eigen/Geometry>

#include <memory>
#include <string>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief A sphere fixed to a link: centre in the link frame, radius (metres). */
        struct LinkSphere
        {
            Eigen::Vector3d centre{Eigen::Vector3d::Zero()};
            double radius{0.};
        };

        /** \brief How SphereModel::enclose() covers a link. */
        struct SphereModelSettings
        {
            /** \brief Most spheres per link (at least 1). More spheres hug the surface closer (fewer states judged
                in collision that are not) and cost more per check. */
            int spheresPerLink{24};
            /** \brief Surface triangles longer than this fraction of the link's size are split first, so that no
                triangle forces a sphere larger than its cluster. */
            double maxTriangleFraction{0.1};
            /** \brief Sides of the polygon that replaces a cylinder's circle (the polygon contains the circle). */
            int circleSides{16};
        };

        /** \brief Spheres that enclose the collision geometry of every link of a RobotModel: every point of the
            surface of a link's geometry (boxes, cylinders, spheres, meshes) lies inside at least one of the link's
            spheres. A checker that finds the spheres free of obstacles has therefore shown the real geometry free,
            which is what makes the sphere checker safe to use in place of FCL on the meshes. Immutable. */
        class SphereModel
        {
        public:
            /** \brief Cover each link's geometry with at most settings.spheresPerLink spheres: the surface
                (triangles; boxes and cylinders as the triangles of a polyhedron that contains them) is split by
                its longest extent until the budget is used, and each part gets the sphere that holds its
                triangles' corners (a sphere is convex, so it holds the triangles). URDF spheres are kept as they
                are. Takes a few milliseconds per link. */
            static std::shared_ptr<const SphereModel> enclose(const RobotModel &model,
                                                              const SphereModelSettings &settings = {});

            /** \brief Spheres read from a spherized URDF (collision geometry made only of spheres, as
                panda_spherized.urdf), matched to \e model's links by name, then grown so that they enclose the
                real geometry of \e model: each surface triangle is given to the sphere that needs to grow least
                to hold it. Links the spherized file leaves out are covered as by enclose(). Throws UrdfError when
                the file cannot be read or holds geometry other than spheres. */
            static std::shared_ptr<const SphereModel> fromSpherizedUrdf(const RobotModel &model,
                                                                        const std::string &spherizedUrdf,
                                                                        const SphereModelSettings &settings = {});

            /** \brief The spheres of link \e link (empty for links without collision geometry). */
            const std::vector<LinkSphere> &linkSpheres(int link) const
            {
                return spheres_[link];
            }
            std::size_t linkCount() const
            {
                return spheres_.size();
            }
            std::size_t sphereCount() const;

            /** \brief The surface triangles (corners in the link frame) of a link's collision geometry, as the
                model covers them: boxes exactly, cylinders by a circumscribed prism, meshes as they are. URDF
                spheres give no triangles (they are kept as spheres). */
            static std::vector<Eigen::Vector3d> surfaceTriangles(const RobotLink &link, int circleSides = 16);

        private:
            SphereModel() = default;
            std::vector<std::vector<LinkSphere>> spheres_;  ///< per link
        };

        using SphereModelPtr = std::shared_ptr<const SphereModel>;
    }  // namespace validity
}  // namespace michi

#endif
