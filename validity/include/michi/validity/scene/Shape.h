#ifndef MICHI_VALIDITY_SHAPE_
#define MICHI_VALIDITY_SHAPE_

#include <michi/validity/scene/Polygon2.h>

#include <Eigen/Geometry>
#include <fcl/geometry/collision_geometry.h>

#include <memory>
#include <string>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief A collision shape in its own frame, with the FCL geometry (one or more convex pieces or one BVH
            mesh) that represents it. Shapes are immutable once made and shared between threads. */
        class Shape
        {
        public:
            enum class Type
            {
                BOX,       ///< full extents size_ (x, y, z), centred
                SPHERE,    ///< radius size_.x()
                CYLINDER,  ///< radius size_.x(), length size_.z(), axis z, centred
                CAPSULE,   ///< radius size_.x(), cylinder length size_.z(), axis z, centred
                PRISM,     ///< planar outline polygon_ (x-y) extruded over z in [size_.x(), size_.y()]
                MESH       ///< triangle mesh (vertices_, triangles_) as an FCL BVH
            };

            static std::shared_ptr<const Shape> box(const Eigen::Vector3d &extents);
            static std::shared_ptr<const Shape> sphere(double radius);
            static std::shared_ptr<const Shape> cylinder(double radius, double length);
            static std::shared_ptr<const Shape> capsule(double radius, double length);
            /** \brief A simple polygon (any orientation, convex or not) extruded over [zMin, zMax]. Non-convex
                outlines are split into convex pieces (ear clipping), so a body inside the prism is detected. */
            static std::shared_ptr<const Shape> prism(const std::vector<Eigen::Vector2d> &outline, double zMin,
                                                      double zMax);
            static std::shared_ptr<const Shape> mesh(std::vector<Eigen::Vector3d> vertices,
                                                     std::vector<Eigen::Vector3i> triangles, std::string source = "");
            /** \brief Load a mesh file (STL, OBJ, DAE, ... through assimp), scaled. Throws std::runtime_error
                naming the file when it cannot be read or holds no triangles. */
            static std::shared_ptr<const Shape> meshFromFile(const std::string &path,
                                                             const Eigen::Vector3d &scale = Eigen::Vector3d::Ones());

            Type type() const
            {
                return type_;
            }
            const Eigen::Vector3d &size() const
            {
                return size_;
            }
            const std::vector<Eigen::Vector2d> &outline() const
            {
                return outline_;
            }
            const std::vector<Eigen::Vector3d> &vertices() const
            {
                return vertices_;
            }
            const std::vector<Eigen::Vector3i> &triangles() const
            {
                return triangles_;
            }
            const std::string &source() const
            {
                return source_;
            }
            /** \brief FCL geometries in the shape's frame. */
            const std::vector<std::shared_ptr<fcl::CollisionGeometryd>> &geometries() const
            {
                return geometries_;
            }
            /** \brief For a mesh, the same triangles with oriented boxes (OBB) as bounding volumes, for collision
                queries only (null for other shapes). Against a primitive, FCL bounds the primitive with the tree's
                bounding-volume type on every query: an OBB is a direct fit, an OBBRSS an eigen-decomposition of its
                corners, which took about half of a Panda state check (docs/checking.md). geometries() keep the
                OBBRSS tree, which distance queries need. */
            const fcl::CollisionGeometryd *collisionMesh() const
            {
                return collisionMesh_.get();
            }
            /** \brief The shape a geometry of geometries() belongs to (its FCL user data); null for a geometry no
                Shape made. */
            static const Shape *owner(const fcl::CollisionGeometryd *geometry);
            /** \brief A capsule (the segment a-b grown by radius) that contains a mesh: every vertex, hence every
                triangle, lies inside it. For a quick "apart" answer before a mesh's tree is walked (objectsTouch()). */
            struct Capsule
            {
                Eigen::Vector3d a{Eigen::Vector3d::Zero()}, b{Eigen::Vector3d::Zero()};
                double radius{0.};
            };
            /** \brief The enclosing capsule of a mesh, in the shape's frame; null for other shapes. */
            const Capsule *enclosingCapsule() const
            {
                return type_ == Type::MESH ? &capsule_ : nullptr;
            }
            /** \brief Radius of a sphere about the shape's origin that contains the shape. */
            double boundingRadius() const
            {
                return boundingRadius_;
            }
            /** \brief The shape's shadow on the x-y plane when placed at \e pose (convex hull for 3-D shapes,
                the outline for prisms), for the 2-D views. */
            MultiPolygon2 footprint(const Eigen::Isometry3d &pose) const;
            /** \brief Human-readable description ("box 0.1x0.2x0.3"). */
            std::string describe() const;

        private:
            Shape() = default;
            void finish();
            Type type_{Type::BOX};
            Eigen::Vector3d size_{Eigen::Vector3d::Zero()};
            std::vector<Eigen::Vector2d> outline_;
            std::vector<Eigen::Vector3d> vertices_;
            std::vector<Eigen::Vector3i> triangles_;
            std::vector<std::vector<Eigen::Vector2d>> convexPieces_;
            std::string source_;
            std::vector<std::shared_ptr<fcl::CollisionGeometryd>> geometries_;
            std::shared_ptr<fcl::CollisionGeometryd> collisionMesh_;  ///< see collisionMesh()
            double boundingRadius_{0.};
            Capsule capsule_;  ///< meshes: see enclosingCapsule()
        };

        using ShapePtr = std::shared_ptr<const Shape>;

        /** \brief Split a simple polygon into triangles (ear clipping); indices into \e outline. Throws
            std::invalid_argument for fewer than 3 vertices or a self-intersecting outline. */
        std::vector<std::array<int, 3>> triangulatePolygon(const std::vector<Eigen::Vector2d> &outline);
    }  // namespace validity
}  // namespace michi

#endif
