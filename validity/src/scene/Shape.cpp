#include <michi/validity/scene/Shape.h>
#include <michi/validity/InputFile.h>
#include <michi/validity/Limits.h>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace bg = boost::geometry;

namespace michi
{
    namespace validity
    {
        namespace
        {
            /** An FCL triangle tree with bounding volumes \e BV. */
            template <typename BV>
            std::shared_ptr<fcl::BVHModel<BV>> bvhModel(const std::vector<Eigen::Vector3d> &vertices,
                                                        const std::vector<fcl::Triangle> &triangles)
            {
                auto model = std::make_shared<fcl::BVHModel<BV>>();
                model->beginModel();
                model->addSubModel(vertices, triangles);
                model->endModel();
                return model;
            }

            double signedArea(const std::vector<Eigen::Vector2d> &p)
            {
                double a = 0.;
                for (std::size_t i = 0; i < p.size(); ++i)
                {
                    const auto &u = p[i];
                    const auto &v = p[(i + 1) % p.size()];
                    a += u.x() * v.y() - v.x() * u.y();
                }
                return 0.5 * a;
            }

            double cross(const Eigen::Vector2d &o, const Eigen::Vector2d &a, const Eigen::Vector2d &b)
            {
                return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
            }

            bool isConvexCcw(const std::vector<Eigen::Vector2d> &p)
            {
                for (std::size_t i = 0; i < p.size(); ++i)
                    // A corner turning right (beyond round-off) makes a CCW outline non-convex; collinear corners are
                    // allowed.
                    if (cross(p[i], p[(i + 1) % p.size()], p[(i + 2) % p.size()]) < -1e-12)
                        return false;
                return true;
            }

            /** A convex prism over a CCW convex outline, faces counter-clockwise seen from outside. */
            std::shared_ptr<fcl::CollisionGeometryd> convexPrism(const std::vector<Eigen::Vector2d> &outline,
                                                                 double zMin, double zMax)
            {
                const int n = static_cast<int>(outline.size());
                auto vertices = std::make_shared<std::vector<Eigen::Vector3d>>();
                for (const auto &p : outline)
                    vertices->emplace_back(p.x(), p.y(), zMin);
                for (const auto &p : outline)
                    vertices->emplace_back(p.x(), p.y(), zMax);
                auto faces = std::make_shared<std::vector<int>>();
                // fcl::Convex's face list: each face is its vertex count followed by its vertex indices.
                faces->push_back(n);  // top, seen from +z
                for (int i = 0; i < n; ++i)
                    faces->push_back(n + i);
                faces->push_back(n);  // bottom, seen from -z
                for (int i = n - 1; i >= 0; --i)
                    faces->push_back(i);
                for (int i = 0; i < n; ++i)
                {
                    const int j = (i + 1) % n;
                    // Side quad i, j, j', i' is counter-clockwise seen from outside because the outline is CCW seen
                    // from +z.
                    faces->insert(faces->end(), {4, i, j, n + j, n + i});
                }
                return std::make_shared<fcl::Convexd>(vertices, n + 2, faces);
            }

            std::vector<Eigen::Vector3d> samplePoints(const Shape &shape, int circleSides)
            {
                std::vector<Eigen::Vector3d> points;
                const Eigen::Vector3d &s = shape.size();
                // circles are sampled on a polygon that contains them
                const double grow = 1. / std::cos(M_PI / circleSides);
                auto circle = [&](double r, double z)
                {
                    for (int i = 0; i < circleSides; ++i)
                    {
                        const double a = 2. * M_PI * i / circleSides;
                        points.emplace_back(r * grow * std::cos(a), r * grow * std::sin(a), z);
                    }
                };
                switch (shape.type())
                {
                    case Shape::Type::BOX:
                        for (int i = 0; i < 8; ++i)
                            points.emplace_back((i & 1 ? 0.5 : -0.5) * s.x(), (i & 2 ? 0.5 : -0.5) * s.y(),
                                                (i & 4 ? 0.5 : -0.5) * s.z());
                        break;
                    case Shape::Type::CYLINDER:
                        circle(s.x(), -0.5 * s.z());
                        circle(s.x(), 0.5 * s.z());
                        break;
                    case Shape::Type::SPHERE:
                    case Shape::Type::CAPSULE:
                        break;  // handled as disks by footprint()
                    case Shape::Type::PRISM:
                        for (const auto &p : shape.outline())
                        {
                            // The outline at z_min (size_.x()) and z_max (size_.y()): a tilted prism's shadow needs
                            // both ends.
                            points.emplace_back(p.x(), p.y(), s.x());
                            points.emplace_back(p.x(), p.y(), s.y());
                        }
                        break;
                    case Shape::Type::MESH:
                        points = shape.vertices();
                        break;
                }
                return points;
            }
        }  // namespace

        std::vector<std::array<int, 3>> triangulatePolygon(const std::vector<Eigen::Vector2d> &outline)
        {
            const int n = static_cast<int>(outline.size());
            if (n < 3)
                throw std::invalid_argument("polygon has " + std::to_string(n) + " vertices, at least 3 needed");
            std::vector<Point2> pts;
            for (const auto &p : outline)
                pts.emplace_back(p.x(), p.y());
            Polygon2 poly = makePolygon2(pts);
            std::string reason;
            if (!bg::is_valid(poly, reason))
                throw std::invalid_argument("polygon is not simple: " + reason);

            std::vector<int> idx(n);
            for (int i = 0; i < n; ++i)
                idx[i] = i;
            // The ear test below assumes a counter-clockwise walk (a left turn is a convex corner).
            if (signedArea(outline) < 0.)
                std::reverse(idx.begin(), idx.end());
            std::vector<std::array<int, 3>> triangles;
            // ear clipping: O(n^3) worst case, fine for map polygons of tens of vertices
            while (idx.size() > 3)
            {
                bool clipped = false;
                const std::size_t m = idx.size();
                for (std::size_t k = 0; k < m && !clipped; ++k)
                {
                    const int a = idx[(k + m - 1) % m], b = idx[k], c = idx[(k + 1) % m];
                    if (cross(outline[a], outline[b], outline[c]) <= 1e-14)
                        continue;  // reflex or degenerate corner
                    bool empty = true;
                    for (std::size_t t = 0; t < m && empty; ++t)
                    {
                        const int q = idx[t];
                        if (q == a || q == b || q == c)
                            continue;
                        const auto &p = outline[q];
                        // A vertex inside the candidate ear or on its border (>= 0) would be cut off by the diagonal
                        // a-c.
                        if (cross(outline[a], outline[b], p) >= 0 && cross(outline[b], outline[c], p) >= 0 &&
                            cross(outline[c], outline[a], p) >= 0)
                            empty = false;
                    }
                    if (!empty)
                        continue;
                    triangles.push_back({a, b, c});
                    // clipped ends the for loop: m and the indices of idx changed with the erase.
                    idx.erase(idx.begin() + static_cast<long>(k));
                    clipped = true;
                }
                if (!clipped)
                {
                    // only collinear corners remain: drop one
                    idx.erase(idx.begin());
                }
            }
            // The last three vertices may be collinear (a zero-area triangle); FCL gains nothing from it.
            if (cross(outline[idx[0]], outline[idx[1]], outline[idx[2]]) > 1e-14)
                triangles.push_back({idx[0], idx[1], idx[2]});
            return triangles;
        }

        std::shared_ptr<const Shape> Shape::box(const Eigen::Vector3d &extents)
        {
            for (int i = 0; i < 3; ++i)
                requireGeometryValue(extents[i], "box extent");
            if ((extents.array() <= 0.).any())
                throw std::invalid_argument("box extents must be positive");
            std::shared_ptr<Shape> s(new Shape);
            s->type_ = Type::BOX;
            s->size_ = extents;
            s->geometries_.push_back(std::make_shared<fcl::Boxd>(extents));
            s->finish();
            return s;
        }

        std::shared_ptr<const Shape> Shape::sphere(double radius)
        {
            requireGeometryValue(radius, "sphere radius");
            if (!(radius > 0.))
                throw std::invalid_argument("sphere radius must be positive");
            std::shared_ptr<Shape> s(new Shape);
            s->type_ = Type::SPHERE;
            s->size_ = Eigen::Vector3d(radius, radius, radius);
            s->geometries_.push_back(std::make_shared<fcl::Sphered>(radius));
            s->finish();
            return s;
        }

        std::shared_ptr<const Shape> Shape::cylinder(double radius, double length)
        {
            requireGeometryValue(radius, "cylinder radius");
            requireGeometryValue(length, "cylinder length");
            if (!(radius > 0.) || !(length > 0.))
                throw std::invalid_argument("cylinder radius and length must be positive");
            std::shared_ptr<Shape> s(new Shape);
            s->type_ = Type::CYLINDER;
            s->size_ = Eigen::Vector3d(radius, radius, length);
            s->geometries_.push_back(std::make_shared<fcl::Cylinderd>(radius, length));
            s->finish();
            return s;
        }

        std::shared_ptr<const Shape> Shape::capsule(double radius, double length)
        {
            requireGeometryValue(radius, "capsule radius");
            requireGeometryValue(length, "capsule length");
            if (!(radius > 0.) || !(length >= 0.))
                throw std::invalid_argument("capsule radius must be positive and length non-negative");
            std::shared_ptr<Shape> s(new Shape);
            s->type_ = Type::CAPSULE;
            s->size_ = Eigen::Vector3d(radius, radius, length);
            s->geometries_.push_back(std::make_shared<fcl::Capsuled>(radius, length));
            s->finish();
            return s;
        }

        std::shared_ptr<const Shape> Shape::prism(const std::vector<Eigen::Vector2d> &outline, double zMin, double zMax)
        {
            requireGeometryValue(zMin, "prism z_min");
            requireGeometryValue(zMax, "prism z_max");
            for (const auto &p : outline)
            {
                requireGeometryValue(p.x(), "prism outline x");
                requireGeometryValue(p.y(), "prism outline y");
            }
            if (!(zMax > zMin))
                throw std::invalid_argument("prism needs z_max > z_min");
            const auto triangles = triangulatePolygon(outline);  // validates the outline
            std::shared_ptr<Shape> s(new Shape);
            s->type_ = Type::PRISM;
            // A prism's size_ is (z_min, z_max, height), unlike the other shapes' extents (see Shape.h).
            s->size_ = Eigen::Vector3d(zMin, zMax, zMax - zMin);
            s->outline_ = outline;
            std::vector<Eigen::Vector2d> ccw = outline;
            if (signedArea(ccw) < 0.)
                std::reverse(ccw.begin(), ccw.end());
            // One convex prism when possible; otherwise one per triangle. A single non-convex piece as a surface mesh
            // would only report contact with its walls, not a body deep inside (foundation.md).
            if (isConvexCcw(ccw))
                s->convexPieces_.push_back(ccw);
            else
                for (const auto &t : triangles)
                    s->convexPieces_.push_back({outline[t[0]], outline[t[1]], outline[t[2]]});
            for (const auto &piece : s->convexPieces_)
                s->geometries_.push_back(convexPrism(piece, zMin, zMax));
            s->finish();
            return s;
        }

        namespace
        {
            /** The capsule along \e axis (unit) through \e centre that holds every vertex, with the smallest radius
                about that line and the shortest segment for it. */
            Shape::Capsule capsuleAlong(const std::vector<Eigen::Vector3d> &vertices, const Eigen::Vector3d &centre,
                                        const Eigen::Vector3d &axis)
            {
                double r2 = 0.;
                for (const auto &v : vertices)
                {
                    const Eigen::Vector3d d = v - centre;
                    r2 = std::max(r2, (d - d.dot(axis) * axis).squaredNorm());
                }
                const double r = std::sqrt(r2);
                // a vertex at axial position t and distance d from the line lies in the end sphere about the
                // segment's end e when |t - e| <= sqrt(r^2 - d^2)
                double lo = std::numeric_limits<double>::infinity(), hi = -lo;
                for (const auto &v : vertices)
                {
                    const Eigen::Vector3d d = v - centre;
                    const double t = d.dot(axis);
                    const double reach = std::sqrt(std::max(0., r * r - (d - t * axis).squaredNorm()));
                    lo = std::min(lo, t + reach);
                    hi = std::max(hi, t - reach);
                }
                if (lo > hi)
                    lo = hi = 0.5 * (lo + hi);
                // the farthest vertices lie on the surface: a little over it, so that rounding never puts one outside
                return {centre + lo * axis, centre + hi * axis, r * (1. + 1e-9) + 1e-9};
            }

            /** Of the capsules along the vertices' principal axes and the frame's axes, the one of least volume. */
            Shape::Capsule enclosingCapsuleOf(const std::vector<Eigen::Vector3d> &vertices)
            {
                Eigen::Vector3d centre = Eigen::Vector3d::Zero();
                for (const auto &v : vertices)
                    centre += v;
                centre /= static_cast<double>(vertices.size());
                Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
                for (const auto &v : vertices)
                    covariance += (v - centre) * (v - centre).transpose();
                const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
                std::vector<Eigen::Vector3d> axes{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                                  Eigen::Vector3d::UnitZ()};
                for (int i = 0; i < 3; ++i)
                    if (eigen.info() == Eigen::Success && eigen.eigenvectors().col(i).allFinite())
                        axes.push_back(eigen.eigenvectors().col(i).normalized());
                Shape::Capsule best;
                double bestVolume = std::numeric_limits<double>::infinity();
                for (const auto &axis : axes)
                {
                    const Shape::Capsule c = capsuleAlong(vertices, centre, axis);
                    const double volume = M_PI * c.radius * c.radius * ((c.b - c.a).norm() + 4. / 3. * c.radius);
                    if (volume < bestVolume)
                    {
                        bestVolume = volume;
                        best = c;
                    }
                }
                return best;
            }
        }  // namespace

        std::shared_ptr<const Shape> Shape::mesh(std::vector<Eigen::Vector3d> vertices,
                                                 std::vector<Eigen::Vector3i> triangles, std::string source)
        {
            if (vertices.empty() || triangles.empty())
                throw std::invalid_argument("mesh " + source + " has no triangles");
            for (const auto &t : triangles)
                if ((t.array() < 0).any() || (t.array() >= static_cast<int>(vertices.size())).any())
                    throw std::invalid_argument("mesh " + source + " has a triangle index out of range");
            // a non-finite or huge vertex would make FCL's bounding volumes overflow (and its broad phase crash)
            for (std::size_t v = 0; v < vertices.size(); ++v)
                for (int i = 0; i < 3; ++i)
                    if (!isGeometryValue(vertices[v][i]))
                        throw std::invalid_argument("mesh " + source + ": vertex " + std::to_string(v) +
                                                    " coordinate " + geometryValueProblem(vertices[v][i]));
            std::shared_ptr<Shape> s(new Shape);
            s->type_ = Type::MESH;
            s->vertices_ = std::move(vertices);
            s->triangles_ = std::move(triangles);
            s->source_ = std::move(source);
            std::vector<fcl::Triangle> tris;
            tris.reserve(s->triangles_.size());
            for (const auto &t : s->triangles_)
                tris.emplace_back(t[0], t[1], t[2]);
            // OBBRSS bounding volumes serve every query of a mesh (swept spheres for distance); the OBB tree of the
            // same triangles serves collision queries against primitives and other meshes (collisionMesh()).
            s->geometries_.push_back(bvhModel<fcl::OBBRSSd>(s->vertices_, tris));
            s->collisionMesh_ = bvhModel<fcl::OBBd>(s->vertices_, tris);
            s->capsule_ = enclosingCapsuleOf(s->vertices_);
            s->finish();
            return s;
        }

        namespace
        {
            /** Meshes already loaded, by file (canonical path and contents, so an edited file is read again) and
                scale. A dataset's problems share one robot: loading the 100 MotionBenchMaker table_pick problems read
                the Panda's meshes 100 times and built their trees each time. A Shape is immutable once made, so one
                copy serves every model; the cache holds it only while some model does. */
            struct MeshCache
            {
                using Key = std::tuple<std::string, std::size_t, std::size_t, double, double, double>;
                std::mutex mutex;
                std::map<Key, std::weak_ptr<const Shape>> shapes;
            };
            MeshCache &meshCache()
            {
                static MeshCache cache;
                return cache;
            }

            /** meshFromFile() without its cache: assimp, then the triangle trees. */
            std::shared_ptr<const Shape> readMeshFile(const std::string &path, const Eigen::Vector3d &scale)
            {
                Assimp::Importer importer;
                // Triangulate: FCL takes triangles only. PreTransformVertices: a file's node transforms are baked into
                // the vertices, so the mesh is in the file's frame as a viewer shows it. SortByPType: points and lines
                // land in meshes of their own, whose faces the loop below skips (it keeps 3-index faces only).
                const aiScene *scene =
                    importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                aiProcess_PreTransformVertices | aiProcess_SortByPType);
                if (scene == nullptr)
                    throw std::runtime_error(path + ": cannot read mesh: " + importer.GetErrorString());
                std::vector<Eigen::Vector3d> vertices;
                std::vector<Eigen::Vector3i> triangles;
                for (unsigned int m = 0; m < scene->mNumMeshes; ++m)
                {
                    const aiMesh *mesh = scene->mMeshes[m];
                    const int offset = static_cast<int>(vertices.size());
                    for (unsigned int v = 0; v < mesh->mNumVertices; ++v)
                    {
                        const aiVector3D &p = mesh->mVertices[v];
                        vertices.emplace_back(p.x * scale.x(), p.y * scale.y(), p.z * scale.z());
                    }
                    for (unsigned int f = 0; f < mesh->mNumFaces; ++f)
                    {
                        const aiFace &face = mesh->mFaces[f];
                        if (face.mNumIndices == 3)
                            triangles.emplace_back(offset + static_cast<int>(face.mIndices[0]),
                                                   offset + static_cast<int>(face.mIndices[1]),
                                                   offset + static_cast<int>(face.mIndices[2]));
                    }
                }
                if (triangles.empty())
                    throw std::runtime_error(path + ": mesh holds no triangles");
                return Shape::mesh(std::move(vertices), std::move(triangles), path);
            }

            /** Smallest mesh scale factor accepted (metres per file unit): files in micrometres still load. */
            constexpr double MIN_MESH_SCALE = 1e-9;
        }  // namespace

        std::shared_ptr<const Shape> Shape::meshFromFile(const std::string &path, const Eigen::Vector3d &scale)
        {
            // A zero scale flattens the mesh into a plane or a point, which collides with nearly nothing: the link or
            // obstacle would silently drop out of checking. A negative one mirrors the mesh (some URDFs do that).
            // A scale below a nanometre per unit shrinks it as good as to a point too, and FCL's distance queries on
            // such coordinates (denormal numbers at 1e-300) ran for seconds per call.
            for (int i = 0; i < 3; ++i)
                if (!std::isfinite(scale[i]) || !(std::abs(scale[i]) >= MIN_MESH_SCALE))
                {
                    std::ostringstream what;
                    what << path << ": mesh scale " << scale[i] << " (axis "
                         << "xyz"[i] << ") must be finite and at least " << MIN_MESH_SCALE << " in size";
                    throw std::invalid_argument(what.str());
                }
            requireInputFile(path);  // a directory or device would give assimp's own confusing message
            // The key holds the file's contents (a hash of them) rather than its modification time, whose clock
            // ticks too coarsely to tell apart two writes in a row; reading the bytes costs little beside parsing
            // them and building the trees.
            std::error_code error;
            const std::filesystem::path canonical = std::filesystem::canonical(path, error);
            std::ifstream in(path, std::ios::binary);
            const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
            const bool cacheable = !error && !in.bad();
            const MeshCache::Key key{
                canonical.string(), std::hash<std::string>{}(bytes), bytes.size(), scale.x(), scale.y(), scale.z()};
            if (cacheable)
            {
                MeshCache &cache = meshCache();
                const std::lock_guard<std::mutex> lock(cache.mutex);
                const auto it = cache.shapes.find(key);
                if (it != cache.shapes.end())
                    if (auto shape = it->second.lock())
                        return shape;
            }
            auto shape = readMeshFile(path, scale);
            if (cacheable)
            {
                MeshCache &cache = meshCache();
                const std::lock_guard<std::mutex> lock(cache.mutex);
                // entries whose shapes every holder let go of are dropped here, so a long run that loads many
                // meshes one after another does not keep a key per file it ever read
                for (auto it = cache.shapes.begin(); it != cache.shapes.end();)
                    it = it->second.expired() ? cache.shapes.erase(it) : std::next(it);
                cache.shapes[key] = shape;
            }
            return shape;
        }

        void Shape::finish()
        {
            double r = 0.;
            switch (type_)
            {
                case Type::BOX:
                    // Bounding radius about the shape's origin: half the box's diagonal.
                    r = 0.5 * size_.norm();
                    break;
                case Type::SPHERE:
                    r = size_.x();
                    break;
                case Type::CYLINDER:
                    // A rim point: radius out and half the length up.
                    r = std::hypot(size_.x(), 0.5 * size_.z());
                    break;
                case Type::CAPSULE:
                    r = size_.x() + 0.5 * size_.z();
                    break;
                case Type::PRISM:
                    for (const auto &p : outline_)
                        // Each outline vertex at either end height; the prism's z range need not contain the origin.
                        r = std::max({r, std::hypot(p.norm(), size_.x()), std::hypot(p.norm(), size_.y())});
                    break;
                case Type::MESH:
                    for (const auto &v : vertices_)
                        r = std::max(r, v.norm());
                    break;
            }
            boundingRadius_ = r;
            for (auto &g : geometries_)
            {
                g->computeLocalAABB();
                // the way back from a geometry to its shape (owner()); a Shape never moves once made
                g->setUserData(this);
            }
            if (collisionMesh_)
            {
                collisionMesh_->computeLocalAABB();
                collisionMesh_->setUserData(this);
            }
        }

        const Shape *Shape::owner(const fcl::CollisionGeometryd *geometry)
        {
            return geometry == nullptr ? nullptr : static_cast<const Shape *>(geometry->getUserData());
        }

        MultiPolygon2 Shape::footprint(const Eigen::Isometry3d &pose) const
        {
            MultiPolygon2 result;
            // Circles become 32-gons whose edges touch the circle from outside, so a shadow never misses part of the
            // shape.
            const int sides = 32;
            if (type_ == Type::SPHERE || type_ == Type::CAPSULE)
            {
                // shadow of a sphere is a disk; of a capsule, the hull of its two end disks
                const double half = type_ == Type::CAPSULE ? 0.5 * size_.z() : 0.;
                bg::model::multi_point<Point2> pts;
                for (double z : {-half, half})
                {
                    const Eigen::Vector3d c = pose * Eigen::Vector3d(0, 0, z);
                    const Polygon2 circle = circlePolygon2(Point2(c.x(), c.y()), size_.x(), sides);
                    for (const auto &p : circle.outer())
                        pts.push_back(p);
                }
                Polygon2 hull;
                bg::convex_hull(pts, hull);
                result.push_back(hull);
                return result;
            }
            // Anything else: the convex hull of the projected corner points (exact for boxes, conservative for
            // cylinders through the outer polygons, and for tilted prisms and meshes the hull fills in concave parts).
            const Eigen::Vector3d zAxis = pose.linear().col(2);
            if (type_ == Type::PRISM && std::abs(std::abs(zAxis.z()) - 1.) < 1e-9)
            {
                // an upright prism keeps its (possibly non-convex) outline
                std::vector<Point2> pts;
                for (const auto &p : outline_)
                {
                    const Eigen::Vector3d w = pose * Eigen::Vector3d(p.x(), p.y(), size_.x());
                    pts.emplace_back(w.x(), w.y());
                }
                result.push_back(makePolygon2(pts));
                return result;
            }
            bg::model::multi_point<Point2> pts;
            for (const auto &p : samplePoints(*this, sides))
            {
                const Eigen::Vector3d w = pose * p;
                pts.emplace_back(w.x(), w.y());
            }
            Polygon2 hull;
            bg::convex_hull(pts, hull);
            result.push_back(hull);
            return result;
        }

        std::string Shape::describe() const
        {
            std::ostringstream out;
            switch (type_)
            {
                case Type::BOX:
                    out << "box " << size_.x() << "x" << size_.y() << "x" << size_.z();
                    break;
                case Type::SPHERE:
                    out << "sphere r=" << size_.x();
                    break;
                case Type::CYLINDER:
                    out << "cylinder r=" << size_.x() << " l=" << size_.z();
                    break;
                case Type::CAPSULE:
                    out << "capsule r=" << size_.x() << " l=" << size_.z();
                    break;
                case Type::PRISM:
                    out << "prism of " << outline_.size() << " vertices, z " << size_.x() << ".." << size_.y();
                    break;
                case Type::MESH:
                    out << "mesh " << source_ << " (" << triangles_.size() << " triangles)";
                    break;
            }
            return out.str();
        }
    }  // namespace validity
}  // namespace michi
