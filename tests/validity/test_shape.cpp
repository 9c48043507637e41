// Tests of michi::validity::Shape: FCL geometry of the primitive shapes, ear-clipped prisms (non-convex outlines),
// triangulatePolygon, 2-D footprints and meshes read from STL files.

#include "support/TestScenes.h"

#include <michi/validity/scene/Shape.h>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <gtest/gtest.h>

#include <boost/geometry.hpp>

using namespace michi;
using validity::Shape;
using validity::ShapePtr;

namespace bg = boost::geometry;

namespace
{
    Eigen::Isometry3d at(double x, double y, double z)
    {
        return Eigen::Isometry3d(Eigen::Translation3d(x, y, z));
    }

    /** Whether two placed shapes touch, by FCL over all their geometries. */
    bool collides(const Shape &a, const Eigen::Isometry3d &poseA, const Shape &b, const Eigen::Isometry3d &poseB)
    {
        for (const auto &ga : a.geometries())
            for (const auto &gb : b.geometries())
            {
                fcl::CollisionObjectd oa(ga, poseA), ob(gb, poseB);
                fcl::CollisionRequestd request;
                fcl::CollisionResultd result;
                if (fcl::collide(&oa, &ob, request, result) > 0)
                    return true;
            }
        return false;
    }

    /** Smallest FCL distance between two placed shapes (over all geometry pairs). */
    double distance(const Shape &a, const Eigen::Isometry3d &poseA, const Shape &b, const Eigen::Isometry3d &poseB)
    {
        double best = std::numeric_limits<double>::infinity();
        for (const auto &ga : a.geometries())
            for (const auto &gb : b.geometries())
            {
                fcl::CollisionObjectd oa(ga, poseA), ob(gb, poseB);
                fcl::DistanceRequestd request;
                fcl::DistanceResultd result;
                fcl::distance(&oa, &ob, request, result);
                best = std::min(best, result.min_distance);
            }
        return best;
    }

    /** An L-shaped outline: the square [0, 2]^2 without the quadrant [1, 2] x [1, 2]. Area 3. */
    test::Outline lShape()
    {
        return {{0., 0.}, {2., 0.}, {2., 1.}, {1., 1.}, {1., 2.}, {0., 2.}};
    }

    double trianglesArea(const test::Outline &outline, const std::vector<std::array<int, 3>> &triangles)
    {
        double sum = 0.;
        for (const auto &t : triangles)
            sum += test::outlineArea({outline[t[0]], outline[t[1]], outline[t[2]]});
        return sum;
    }

    /** Points on the surface of a shape, in its own frame (for footprint checks). */
    std::vector<Eigen::Vector3d> surfacePoints(const Shape &shape)
    {
        std::vector<Eigen::Vector3d> points;
        const Eigen::Vector3d &s = shape.size();
        const int n = 90;
        switch (shape.type())
        {
            case Shape::Type::BOX:
                for (int i = 0; i <= 10; ++i)
                    for (int j = 0; j <= 10; ++j)
                        for (int k = 0; k <= 10; ++k)
                            points.emplace_back((i / 10. - 0.5) * s.x(), (j / 10. - 0.5) * s.y(),
                                                (k / 10. - 0.5) * s.z());
                break;
            case Shape::Type::SPHERE:
                for (int i = 0; i <= n; ++i)
                    for (int j = 0; j < n; ++j)
                    {
                        const double theta = M_PI * i / n, phi = 2. * M_PI * j / n;
                        points.push_back(s.x() * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                                 std::sin(theta) * std::sin(phi), std::cos(theta)));
                    }
                break;
            case Shape::Type::CYLINDER:
                for (int i = 0; i < 4 * n; ++i)
                    for (double z : {-0.5 * s.z(), 0., 0.5 * s.z()})
                    {
                        const double a = 2. * M_PI * i / (4 * n);
                        points.emplace_back(s.x() * std::cos(a), s.x() * std::sin(a), z);
                    }
                break;
            case Shape::Type::PRISM:
                for (std::size_t i = 0; i < shape.outline().size(); ++i)
                {
                    const auto &p = shape.outline()[i];
                    const auto &q = shape.outline()[(i + 1) % shape.outline().size()];
                    for (int k = 0; k <= 10; ++k)
                        for (double z : {s.x(), s.y()})
                        {
                            const Eigen::Vector2d v = p + (q - p) * (k / 10.);
                            points.emplace_back(v.x(), v.y(), z);
                        }
                }
                break;
            default:
                points = shape.vertices();
        }
        return points;
    }

    /** Every surface point of \e shape placed at \e pose projects into its footprint. */
    void expectFootprintContainsShadow(const Shape &shape, const Eigen::Isometry3d &pose)
    {
        const validity::MultiPolygon2 footprint = shape.footprint(pose);
        ASSERT_FALSE(footprint.empty()) << shape.describe();
        std::string reason;
        EXPECT_TRUE(bg::is_valid(footprint, reason)) << shape.describe() << ": " << reason;
        for (const auto &p : surfacePoints(shape))
        {
            const Eigen::Vector3d w = pose * p;
            const validity::Point2 q(w.x(), w.y());
            EXPECT_LT(bg::distance(q, footprint), 1e-9)
                << shape.describe() << ": shadow point (" << w.x() << ", " << w.y() << ") is outside the footprint";
        }
    }

    const Eigen::Isometry3d TILTED =
        at(0.3, -0.7, 0.2) * Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, -1).normalized());
}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// Primitives

TEST(Shape, PrimitivesKeepTheirSizesAndBoundingRadii)
{
    const auto box = Shape::box({0.2, 0.4, 0.6});
    EXPECT_EQ(box->type(), Shape::Type::BOX);
    EXPECT_TRUE(box->size().isApprox(Eigen::Vector3d(0.2, 0.4, 0.6)));
    EXPECT_NEAR(box->boundingRadius(), 0.5 * std::sqrt(0.04 + 0.16 + 0.36), 1e-15);
    EXPECT_EQ(box->geometries().size(), 1u);

    const auto sphere = Shape::sphere(0.3);
    EXPECT_EQ(sphere->type(), Shape::Type::SPHERE);
    EXPECT_DOUBLE_EQ(sphere->boundingRadius(), 0.3);

    const auto cylinder = Shape::cylinder(0.1, 0.4);
    EXPECT_EQ(cylinder->type(), Shape::Type::CYLINDER);
    EXPECT_NEAR(cylinder->boundingRadius(), std::hypot(0.1, 0.2), 1e-15);

    const auto capsule = Shape::capsule(0.1, 0.4);
    EXPECT_EQ(capsule->type(), Shape::Type::CAPSULE);
    EXPECT_NEAR(capsule->boundingRadius(), 0.3, 1e-15);

    EXPECT_NE(box->describe().find("box"), std::string::npos);
    EXPECT_NE(sphere->describe().find("sphere"), std::string::npos);
    EXPECT_NE(cylinder->describe().find("cylinder"), std::string::npos);

    EXPECT_THROW(Shape::box({0.1, 0., 0.1}), std::invalid_argument);
    EXPECT_THROW(Shape::sphere(-1.), std::invalid_argument);
    EXPECT_THROW(Shape::cylinder(0.1, 0.), std::invalid_argument);
    EXPECT_THROW(Shape::capsule(0., 1.), std::invalid_argument);
    EXPECT_THROW(Shape::prism(lShape(), 1., 1.), std::invalid_argument);
    EXPECT_THROW(Shape::mesh({}, {}), std::invalid_argument);
    EXPECT_THROW(Shape::mesh({Eigen::Vector3d::Zero()}, {Eigen::Vector3i(0, 0, 1)}), std::invalid_argument);
}

TEST(Shape, PrimitivesCollideByTheirExactExtents)
{
    const auto box = Shape::box({0.2, 0.4, 0.6});
    const auto probe = Shape::sphere(0.05);
    // faces at x = 0.1, y = 0.2, z = 0.3
    EXPECT_TRUE(collides(*box, at(0, 0, 0), *probe, at(0.149, 0, 0)));
    EXPECT_FALSE(collides(*box, at(0, 0, 0), *probe, at(0.151, 0, 0)));
    EXPECT_TRUE(collides(*box, at(0, 0, 0), *probe, at(0, 0.249, 0)));
    EXPECT_FALSE(collides(*box, at(0, 0, 0), *probe, at(0, 0.251, 0)));
    EXPECT_TRUE(collides(*box, at(0, 0, 0), *probe, at(0, 0, 0.349)));
    EXPECT_FALSE(collides(*box, at(0, 0, 0), *probe, at(0, 0, 0.351)));
    EXPECT_NEAR(distance(*box, at(0, 0, 0), *probe, at(0.5, 0, 0)), 0.35, 1e-9);

    const auto cylinder = Shape::cylinder(0.1, 0.4);  // axis z
    EXPECT_TRUE(collides(*cylinder, at(0, 0, 0), *probe, at(0.149, 0, 0)));
    EXPECT_FALSE(collides(*cylinder, at(0, 0, 0), *probe, at(0.151, 0, 0)));
    EXPECT_TRUE(collides(*cylinder, at(0, 0, 0), *probe, at(0, 0, 0.249)));
    EXPECT_FALSE(collides(*cylinder, at(0, 0, 0), *probe, at(0, 0, 0.251)));
}

// ---------------------------------------------------------------------------------------------------------------
// Prisms and triangulation

TEST(Shape, NonConvexPrismDetectsBodiesInsideAndNotInTheNotch)
{
    for (bool clockwise : {false, true})
    {
        auto outline = lShape();
        if (clockwise)
            std::reverse(outline.begin(), outline.end());
        const auto prism = Shape::prism(outline, 0., 1.);
        EXPECT_EQ(prism->type(), Shape::Type::PRISM);
        EXPECT_GT(prism->geometries().size(), 1u) << "a non-convex outline is split into convex pieces";
        EXPECT_EQ(prism->outline(), outline);
        EXPECT_DOUBLE_EQ(prism->size().x(), 0.);
        EXPECT_DOUBLE_EQ(prism->size().y(), 1.);

        const auto small = Shape::sphere(0.05);
        // deep inside each arm of the L, 0.45 from every wall: only the convex decomposition finds these
        for (const Eigen::Vector3d &p : {Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(1.5, 0.5, 0.5),
                                         Eigen::Vector3d(0.5, 1.5, 0.5), Eigen::Vector3d(0.3, 0.7, 0.5)})
            EXPECT_TRUE(collides(*prism, at(0, 0, 0), *small, at(p.x(), p.y(), p.z())))
                << "sphere inside the prism at " << p.transpose() << (clockwise ? " (clockwise)" : "");
        // in the notch (the convex hull of the L would contain these) and outside
        for (const Eigen::Vector3d &p : {Eigen::Vector3d(1.5, 1.5, 0.5), Eigen::Vector3d(1.2, 1.2, 0.5),
                                         Eigen::Vector3d(3., 0.5, 0.5), Eigen::Vector3d(0.5, 0.5, 1.2)})
            EXPECT_FALSE(collides(*prism, at(0, 0, 0), *small, at(p.x(), p.y(), p.z())))
                << "sphere outside the prism at " << p.transpose() << (clockwise ? " (clockwise)" : "");
        // in the notch, 0.5 from both inner walls
        EXPECT_FALSE(collides(*prism, at(0, 0, 0), *Shape::sphere(0.49), at(1.5, 1.5, 0.5)));
        EXPECT_TRUE(collides(*prism, at(0, 0, 0), *Shape::sphere(0.51), at(1.5, 1.5, 0.5)));
        // the prism moves with its pose
        EXPECT_TRUE(collides(*prism, at(10, 0, 0), *small, at(10.5, 0.5, 0.5)));
        EXPECT_FALSE(collides(*prism, at(10, 0, 0), *small, at(0.5, 0.5, 0.5)));
    }
}

TEST(Shape, ConvexPrismIsOnePiece)
{
    const auto hexagon = Shape::prism(test::regularPolygon({0., 0.}, 1., 6), -0.5, 0.5);
    EXPECT_EQ(hexagon->geometries().size(), 1u);
    EXPECT_TRUE(collides(*hexagon, at(0, 0, 0), *Shape::sphere(0.1), at(0, 0, 0)));
    EXPECT_FALSE(collides(*hexagon, at(0, 0, 0), *Shape::sphere(0.1), at(0, 0, 0.65)));
    // a vertex lies at (1, 0); the middle of an edge at distance cos(30 deg) in the direction of 30 deg
    const Eigen::Vector2d normal(std::cos(M_PI / 6), std::sin(M_PI / 6));
    for (double gap : {0.099, 0.101})
    {
        const Eigen::Vector2d c = (std::cos(M_PI / 6) + gap) * normal;
        EXPECT_EQ(collides(*hexagon, at(0, 0, 0), *Shape::sphere(0.1), at(c.x(), c.y(), 0)), gap < 0.1) << gap;
    }
    EXPECT_TRUE(collides(*hexagon, at(0, 0, 0), *Shape::sphere(0.1), at(1.099, 0, 0)));
    EXPECT_FALSE(collides(*hexagon, at(0, 0, 0), *Shape::sphere(0.1), at(1.101, 0, 0)));
}

TEST(Shape, TriangulationAreasSumToThePolygonArea)
{
    std::vector<test::Outline> outlines = {lShape(),
                                           test::regularPolygon({1., 2.}, 0.7, 9),
                                           {{0., 0.}, {4., 0.}, {4., 3.}, {3., 1.}, {2., 3.}, {1., 1.}, {0., 3.}}};
    test::RandomPolygonOptions options;
    options.count = 40;
    options.minSides = 3;
    options.maxSides = 14;
    for (const auto &p : test::randomPolygons(7, options))
        outlines.push_back(p);
    for (auto outline : outlines)
        for (bool reversed : {false, true})
        {
            if (reversed)
                std::reverse(outline.begin(), outline.end());
            const auto triangles = validity::triangulatePolygon(outline);
            EXPECT_EQ(triangles.size(), outline.size() - 2);
            EXPECT_NEAR(trianglesArea(outline, triangles), test::outlineArea(outline), 1e-12);
            for (const auto &t : triangles)
                for (int i : t)
                {
                    EXPECT_GE(i, 0);
                    EXPECT_LT(i, static_cast<int>(outline.size()));
                }
        }
}

TEST(Shape, TriangulationRejectsDegenerateOutlines)
{
    EXPECT_THROW(validity::triangulatePolygon({{0., 0.}, {1., 0.}}), std::invalid_argument);
    // a bow tie crosses itself
    EXPECT_THROW(validity::triangulatePolygon({{0., 0.}, {1., 1.}, {1., 0.}, {0., 1.}}), std::invalid_argument);
    EXPECT_THROW(Shape::prism({{0., 0.}, {1., 1.}, {1., 0.}, {0., 1.}}, 0., 1.), std::invalid_argument);
}

TEST(Shape, RandomNonConvexPrismsContainTheirInteriorPoints)
{
    // a small sphere at the centroid of every ear-clipping triangle, well inside it, touches the prism
    test::RandomPolygonOptions options;
    options.count = 20;
    options.maxSides = 10;
    options.minRadius = 0.3;
    options.maxRadius = 1.;
    const auto probe = Shape::sphere(1e-4);
    for (const auto &outline : test::randomPolygons(11, options))
    {
        const auto prism = Shape::prism(outline, 0., 1.);
        for (const auto &t : validity::triangulatePolygon(outline))
        {
            const Eigen::Vector2d c = (outline[t[0]] + outline[t[1]] + outline[t[2]]) / 3.;
            EXPECT_TRUE(collides(*prism, at(0, 0, 0), *probe, at(c.x(), c.y(), 0.5)));
        }
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Footprints

TEST(Shape, FootprintsContainTheTrueShadow)
{
    const std::vector<ShapePtr> shapes = {Shape::box({0.2, 0.4, 0.6}), Shape::cylinder(0.1, 0.4), Shape::sphere(0.3),
                                          Shape::prism(lShape(), 0., 1.)};
    const std::vector<Eigen::Isometry3d> poses = {Eigen::Isometry3d::Identity(), TILTED,
                                                  at(1, 2, 3) * Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ()),
                                                  at(-1, 0, 0) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX())};
    for (const auto &shape : shapes)
        for (const auto &pose : poses)
            expectFootprintContainsShadow(*shape, pose);
}

TEST(Shape, FootprintsAreTightForUprightShapes)
{
    // an upright box's shadow is exactly its x-y rectangle
    const auto box = Shape::box({0.2, 0.4, 0.6});
    const Eigen::Isometry3d turned = at(1, 2, 0) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ());
    EXPECT_NEAR(bg::area(box->footprint(turned)), 0.08, 1e-12);

    // an upright prism keeps its non-convex outline: area 3, and the notch stays free
    const auto prism = Shape::prism(lShape(), 0., 1.);
    const auto footprint = prism->footprint(at(5, 0, 0));
    EXPECT_NEAR(bg::area(footprint), 3., 1e-12);
    EXPECT_TRUE(bg::within(validity::Point2(5.5, 0.5), footprint));
    EXPECT_FALSE(bg::within(validity::Point2(6.5, 1.5), footprint));

    // a sphere's footprint is a polygon around the disk, not much larger than it
    const double r = 0.3;
    const double area = bg::area(Shape::sphere(r)->footprint(at(0, 0, 7)));
    EXPECT_GE(area, M_PI * r * r);
    EXPECT_LE(area, 1.02 * M_PI * r * r);
}

// ---------------------------------------------------------------------------------------------------------------
// Meshes

TEST(Shape, MeshFromStlCollidesAtKnownPlacements)
{
    test::TempDir dir("michi_shape");
    const std::string path = dir.write("box.stl", test::asciiStlBox({0.2, 0.4, 0.6}, {0., 0., 0.}, "box"));
    const auto mesh = Shape::meshFromFile(path);
    EXPECT_EQ(mesh->type(), Shape::Type::MESH);
    EXPECT_EQ(mesh->triangles().size(), 12u);
    EXPECT_EQ(mesh->source(), path);
    EXPECT_NE(mesh->describe().find("12 triangles"), std::string::npos) << mesh->describe();
    // assimp reads vertices in single precision
    const double tol = 1e-7;
    for (const auto &v : mesh->vertices())
    {
        EXPECT_NEAR(std::abs(v.x()), 0.1, tol);
        EXPECT_NEAR(std::abs(v.y()), 0.2, tol);
        EXPECT_NEAR(std::abs(v.z()), 0.3, tol);
    }
    EXPECT_NEAR(mesh->boundingRadius(), 0.5 * std::sqrt(0.04 + 0.16 + 0.36), tol);

    // spheres that cross a face touch the mesh; ones clear of it do not (an FCL mesh is a surface: a body
    // entirely inside it, touching no triangle, would not be reported)
    const auto probe = Shape::sphere(0.05);
    EXPECT_TRUE(collides(*mesh, at(0, 0, 0), *probe, at(0.14, 0, 0)));
    EXPECT_FALSE(collides(*mesh, at(0, 0, 0), *probe, at(0.16, 0, 0)));
    EXPECT_TRUE(collides(*mesh, at(0, 0, 0), *probe, at(0, -0.24, 0.1)));
    EXPECT_FALSE(collides(*mesh, at(0, 0, 0), *probe, at(0, -0.26, 0.1)));
    EXPECT_TRUE(collides(*mesh, at(0, 0, 0), *probe, at(0.05, 0.1, 0.34)));
    EXPECT_FALSE(collides(*mesh, at(0, 0, 0), *probe, at(0.05, 0.1, 0.36)));
    // placed elsewhere and turned a quarter about z: the x extent becomes 0.4
    const Eigen::Isometry3d pose = at(1, 1, 0) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
    EXPECT_TRUE(collides(*mesh, pose, *probe, at(1.24, 1, 0)));
    EXPECT_FALSE(collides(*mesh, pose, *probe, at(1.26, 1, 0)));
    // a mesh against a box
    EXPECT_TRUE(collides(*mesh, at(0, 0, 0), *Shape::box({0.1, 0.1, 0.1}), at(0.14, 0, 0)));
    EXPECT_FALSE(collides(*mesh, at(0, 0, 0), *Shape::box({0.1, 0.1, 0.1}), at(0.16, 0, 0)));

    // footprint of the mesh: its vertices' hull, 0.2 x 0.4 upright
    EXPECT_NEAR(bg::area(mesh->footprint(Eigen::Isometry3d::Identity())), 0.08, tol);
    expectFootprintContainsShadow(*mesh, TILTED);
}

TEST(Shape, MeshFileIsScaled)
{
    test::TempDir dir("michi_shape");
    const std::string path = dir.write("cube.stl", test::asciiStlBox(Eigen::Vector3d::Ones()));
    const auto mesh = Shape::meshFromFile(path, Eigen::Vector3d(2., 0.5, 0.1));
    for (const auto &v : mesh->vertices())
    {
        EXPECT_NEAR(std::abs(v.x()), 1., 1e-7);
        EXPECT_NEAR(std::abs(v.y()), 0.25, 1e-7);
        EXPECT_NEAR(std::abs(v.z()), 0.05, 1e-7);
    }
}

TEST(Shape, AMeshFileLoadedTwiceIsReadOnceWhileHeldAndAgainWhenChanged)
{
    // meshFromFile() keeps what it read while a caller holds it: a dataset's hundred problems share one robot's
    // meshes instead of reading and tree-building them a hundred times.
    test::TempDir dir("michi_shape_cache");
    const std::string path = dir.write("box.stl", test::asciiStlBox({0.2, 0.4, 0.6}, {0., 0., 0.}, "box"));
    auto first = Shape::meshFromFile(path);
    EXPECT_EQ(Shape::meshFromFile(path), first);
    EXPECT_EQ(Shape::meshFromFile(dir.path() + "/./box.stl"), first);  // the same file by another name
    // another scale is another shape
    const auto scaled = Shape::meshFromFile(path, Eigen::Vector3d(2., 2., 2.));
    EXPECT_NE(scaled, first);
    EXPECT_NEAR(std::abs(scaled->vertices().front().x()), 0.2, 1e-7);
    // a file written again with other contents is read again, even while the old shape is held
    dir.write("box.stl", test::asciiStlBox({0.5, 0.5, 0.5}, {0., 0., 0.}, "bigger box"));
    const auto changed = Shape::meshFromFile(path);
    EXPECT_NE(changed, first);
    EXPECT_NEAR(std::abs(changed->vertices().front().x()), 0.25, 1e-7);
    EXPECT_NEAR(std::abs(first->vertices().front().x()), 0.1, 1e-7);  // the old one is untouched
    // the old contents' holder lets go: the current contents are still served from what `changed` holds
    const Shape *address = changed.get();
    first.reset();
    EXPECT_EQ(Shape::meshFromFile(path).get(), address);
}

TEST(Shape, UnreadableMeshFilesThrowNamingTheFile)
{
    test::TempDir dir("michi_shape");
    const std::string missing = dir.path() + "/missing.stl";
    const std::string garbage = dir.write("garbage.stl", "solid x\nnot really\n");
    for (const auto &path : {missing, garbage})
    {
        try
        {
            Shape::meshFromFile(path);
            ADD_FAILURE() << "no exception for " << path;
        }
        catch (const std::runtime_error &e)
        {
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        }
    }
}
