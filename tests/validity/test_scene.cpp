// Tests of michi::validity::Scene: obstacles, the change counter, moving obstacles, 2-D polygons, bounds and
// occupancy maps read from PGM images.

#include "support/TestScenes.h"

#include <michi/validity/scene/Scene.h>

#include <gtest/gtest.h>

#include <boost/geometry.hpp>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/shape/sphere.h>

#include <algorithm>
#include <array>
#include <random>
#include <set>

using namespace michi;
using validity::Obstacle;
using validity::Scene;
using validity::Shape;
using validity::TimedPose;

namespace bg = boost::geometry;

namespace
{
    Eigen::Isometry3d at(double x, double y, double z, double yaw = 0.)
    {
        return Eigen::Translation3d(x, y, z) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
    }

    Obstacle box(const std::string &name, const Eigen::Vector3d &extents, const Eigen::Isometry3d &pose)
    {
        Obstacle o;
        o.name = name;
        o.shape = Shape::box(extents);
        o.pose = pose;
        return o;
    }

    void expectPoseNear(const Eigen::Isometry3d &expected, const Eigen::Isometry3d &actual, double tol = 1e-12)
    {
        EXPECT_LT((expected.matrix() - actual.matrix()).cwiseAbs().maxCoeff(), tol) << "expected\n"
                                                                                    << expected.matrix() << "\nactual\n"
                                                                                    << actual.matrix();
    }

    Obstacle findObstacle(const Scene &scene, const std::string &name)
    {
        for (const auto &o : scene.obstacles())
            if (o.name == name)
                return o;
        ADD_FAILURE() << "no obstacle " << name;
        return {};
    }

    /** Whether a 0.1 m sphere at \e p touches an obstacle, asked through the scene's broad phase. */
    bool broadPhaseHits(const Scene &scene, const Eigen::Vector3d &p)
    {
        fcl::CollisionObjectd probe(std::make_shared<fcl::Sphered>(0.1), Eigen::Isometry3d(Eigen::Translation3d(p)));
        fcl::DefaultCollisionData<double> data;
        auto lock = scene.lockShared();
        scene.manager().collide(&probe, &data, fcl::DefaultCollisionFunction<double>);
        return data.result.isCollision();
    }
}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// Obstacles and the change counter

TEST(Scene, ChangesBumpTheChangeCounter)
{
    Scene scene;
    EXPECT_EQ(scene.size(), 0u);
    std::uint64_t count = scene.changeCount();

    scene.add(box("a", {1, 1, 1}, at(0, 0, 0)));
    EXPECT_GT(scene.changeCount(), count);
    count = scene.changeCount();
    scene.add(box("b", {1, 1, 1}, at(3, 0, 0)));
    EXPECT_GT(scene.changeCount(), count);
    count = scene.changeCount();
    EXPECT_EQ(scene.size(), 2u);

    scene.setPose("a", at(0, 5, 0));
    EXPECT_GT(scene.changeCount(), count);
    count = scene.changeCount();
    expectPoseNear(at(0, 5, 0), findObstacle(scene, "a").pose);

    EXPECT_TRUE(scene.remove("b"));
    EXPECT_GT(scene.changeCount(), count);
    count = scene.changeCount();
    EXPECT_EQ(scene.size(), 1u);

    // failed changes change nothing
    EXPECT_FALSE(scene.remove("b"));
    EXPECT_THROW(scene.setPose("b", at(0, 0, 0)), std::out_of_range);
    EXPECT_THROW(scene.add(box("a", {2, 2, 2}, at(9, 9, 9))), std::invalid_argument);
    Obstacle shapeless;
    shapeless.name = "nothing";
    EXPECT_THROW(scene.add(shapeless), std::invalid_argument);
    EXPECT_EQ(scene.changeCount(), count);
    EXPECT_EQ(scene.size(), 1u);
    expectPoseNear(at(0, 5, 0), findObstacle(scene, "a").pose);
    EXPECT_TRUE(findObstacle(scene, "a").shape->size().isApprox(Eigen::Vector3d(1, 1, 1)));

    // setTime without moving obstacles moves nothing
    scene.setTime(4.);
    EXPECT_DOUBLE_EQ(scene.time(), 4.);
    EXPECT_EQ(scene.changeCount(), count);

    // with a moving obstacle it bumps whenever the obstacle moves
    Obstacle mover = box("mover", {1, 1, 1}, Eigen::Isometry3d::Identity());
    mover.trajectory = {TimedPose{0., at(0, 0, 0)}, TimedPose{10., at(10, 0, 0)}};
    scene.add(mover);
    EXPECT_GT(scene.changeCount(), count);
    count = scene.changeCount();
    expectPoseNear(at(4, 0, 0), findObstacle(scene, "mover").pose);  // placed at the scene's time
    scene.setTime(5.);
    EXPECT_GT(scene.changeCount(), count);
    count = scene.changeCount();
    scene.setTime(5.);  // same time: nothing moves
    EXPECT_EQ(scene.changeCount(), count);
    scene.setTime(20.);
    EXPECT_GT(scene.changeCount(), count);
    count = scene.changeCount();
    scene.setTime(30.);  // held after the last key frame
    EXPECT_EQ(scene.changeCount(), count);
}

TEST(Scene, SetPosesMovesEveryObstacleInOneChange)
{
    Scene scene;
    scene.add(box("a", {1, 1, 1}, at(0, 0, 0)));
    scene.add(box("b", {1, 1, 1}, at(3, 0, 0)));
    auto count = scene.changeCount();
    scene.setPoses({{"a", at(0, 5, 0)}, {"b", at(0, -5, 0)}});
    EXPECT_EQ(scene.changeCount(), count + 1);  // one change for the lot
    expectPoseNear(at(0, 5, 0), findObstacle(scene, "a").pose);
    expectPoseNear(at(0, -5, 0), findObstacle(scene, "b").pose);
    // the broad phase follows: the new places are occupied, the old ones free
    EXPECT_TRUE(broadPhaseHits(scene, {0, 5, 0}));
    EXPECT_TRUE(broadPhaseHits(scene, {0, -5, 0}));
    EXPECT_FALSE(broadPhaseHits(scene, {0, 0, 0}));
    EXPECT_FALSE(broadPhaseHits(scene, {3, 0, 0}));

    // obstacles already where they are asked to be: no change
    count = scene.changeCount();
    scene.setPoses({{"a", at(0, 5, 0)}, {"b", at(0, -5, 0)}});
    EXPECT_EQ(scene.changeCount(), count);
    // one unknown name: nothing moves, not even the known ones before it
    EXPECT_THROW(scene.setPoses({{"a", at(9, 9, 9)}, {"nobody", at(0, 0, 0)}}), std::out_of_range);
    EXPECT_EQ(scene.changeCount(), count);
    expectPoseNear(at(0, 5, 0), findObstacle(scene, "a").pose);
}

TEST(Scene, DuplicateNameThrowsNamingIt)
{
    Scene scene;
    scene.add(box("table", {1, 1, 1}, at(0, 0, 0)));
    try
    {
        scene.add(box("table", {1, 1, 1}, at(5, 0, 0)));
        ADD_FAILURE() << "no exception for a duplicate name";
    }
    catch (const std::invalid_argument &e)
    {
        EXPECT_NE(std::string(e.what()).find("table"), std::string::npos) << e.what();
    }
    EXPECT_EQ(scene.size(), 1u);
}

TEST(Scene, BoundsCoverAllObstacles)
{
    Scene scene;
    EXPECT_TRUE(scene.bounds().first.isZero());
    EXPECT_TRUE(scene.bounds().second.isZero());
    scene.add(box("a", {1, 2, 3}, at(0, 0, 0)));
    scene.add(box("b", {1, 1, 1}, at(5, -4, 1)));
    const auto [lo, hi] = scene.bounds();
    EXPECT_LE(lo.x(), -0.5);
    EXPECT_LE(lo.y(), -4.5);
    EXPECT_LE(lo.z(), -1.5);
    EXPECT_GE(hi.x(), 5.5);
    EXPECT_GE(hi.y(), 1.);
    EXPECT_GE(hi.z(), 1.5);
    // FCL's AABBs of boxes are exact up to rounding
    EXPECT_NEAR(lo.x(), -0.5, 1e-9);
    EXPECT_NEAR(hi.x(), 5.5, 1e-9);
}

// ---------------------------------------------------------------------------------------------------------------
// Moving obstacles

TEST(Scene, MovingObstaclesInterpolateBetweenKeyFramesAndHoldOutside)
{
    const std::vector<TimedPose> trajectory = {TimedPose{1., at(0, 0, 0)}, TimedPose{3., at(2, 4, 0, M_PI / 2)},
                                               TimedPose{4., at(2, 4, 1, M_PI / 2)}};
    expectPoseNear(at(0, 0, 0), Scene::poseAt(trajectory, -5.));
    expectPoseNear(at(0, 0, 0), Scene::poseAt(trajectory, 1.));
    expectPoseNear(at(0.5, 1, 0, M_PI / 8), Scene::poseAt(trajectory, 1.5));
    expectPoseNear(at(1, 2, 0, M_PI / 4), Scene::poseAt(trajectory, 2.));
    expectPoseNear(at(2, 4, 0, M_PI / 2), Scene::poseAt(trajectory, 3.));
    expectPoseNear(at(2, 4, 0.25, M_PI / 2), Scene::poseAt(trajectory, 3.25));
    expectPoseNear(at(2, 4, 1, M_PI / 2), Scene::poseAt(trajectory, 4.));
    expectPoseNear(at(2, 4, 1, M_PI / 2), Scene::poseAt(trajectory, 100.));
    EXPECT_THROW(Scene::poseAt({}, 0.), std::invalid_argument);

    // in a scene, with the key frames given out of order
    Scene scene;
    Obstacle mover = box("mover", {0.2, 0.2, 0.2}, Eigen::Isometry3d::Identity());
    mover.trajectory = {trajectory[2], trajectory[0], trajectory[1]};
    scene.add(mover);
    for (double t : {0., 1.5, 2., 3.25, 7.})
    {
        scene.setTime(t);
        EXPECT_DOUBLE_EQ(scene.time(), t);
        const Obstacle o = findObstacle(scene, "mover");
        ASSERT_EQ(o.trajectory.size(), 3u);
        EXPECT_DOUBLE_EQ(o.trajectory.front().time, 1.);
        EXPECT_DOUBLE_EQ(o.trajectory.back().time, 4.);
        expectPoseNear(Scene::poseAt(trajectory, t), o.pose);
        // the broad-phase objects moved too
        const auto [lo, hi] = scene.bounds();
        const Eigen::Vector3d centre = 0.5 * (lo + hi);
        EXPECT_NEAR(centre.x(), o.pose.translation().x(), 1e-9) << "t = " << t;
        EXPECT_NEAR(centre.y(), o.pose.translation().y(), 1e-9) << "t = " << t;
        EXPECT_NEAR(centre.z(), o.pose.translation().z(), 1e-9) << "t = " << t;
    }
}

TEST(Scene, StaticObstaclesIgnoreTime)
{
    Scene scene;
    scene.add(box("still", {1, 1, 1}, at(3, 2, 1)));
    scene.setTime(12.);
    expectPoseNear(at(3, 2, 1), findObstacle(scene, "still").pose);
}

// ---------------------------------------------------------------------------------------------------------------
// 2-D views

TEST(Scene, Polygons2dUniteObstacleShadows)
{
    Scene scene;
    EXPECT_TRUE(scene.polygons2d().empty());
    scene.add(box("a", {1, 2, 1}, at(0, 0, 0)));
    scene.add(box("b", {0.5, 0.5, 3}, at(4, 4, 2, 0.3)));
    auto polygons = scene.polygons2d();
    EXPECT_EQ(polygons.size(), 2u);
    EXPECT_NEAR(bg::area(polygons), 2. + 0.25, 1e-12);

    // an overlapping box is united with the first: the overlap counts once
    scene.add(box("c", {1, 2, 1}, at(0.5, 0, 0)));
    polygons = scene.polygons2d();
    EXPECT_EQ(polygons.size(), 2u);
    EXPECT_NEAR(bg::area(polygons), 3. + 0.25, 1e-12);

    // a non-convex prism keeps its notch
    scene.add(
        []
        {
            Obstacle o;
            o.name = "L";
            o.shape = Shape::prism({{0., 0.}, {2., 0.}, {2., 1.}, {1., 1.}, {1., 2.}, {0., 2.}}, 0., 1.);
            o.pose = at(10, 0, 0);
            return o;
        }());
    polygons = scene.polygons2d();
    EXPECT_EQ(polygons.size(), 3u);
    EXPECT_NEAR(bg::area(polygons), 3. + 0.25 + 3., 1e-12);
    EXPECT_TRUE(bg::within(validity::Point2(10.5, 1.5), polygons));
    EXPECT_FALSE(bg::within(validity::Point2(11.5, 1.5), polygons));
}

// uniteFootprints unites only pieces whose boxes overlap: the region of all of them, whatever their layout
TEST(Scene, UniteFootprintsCoversWhatTheUnionOfAllCovers)
{
    std::mt19937 random(7);
    std::uniform_real_distribution<double> where(0., 20.), size(0.1, 2.);
    std::vector<validity::MultiPolygon2> parts;
    std::vector<std::array<double, 4>> boxes;
    for (int i = 0; i < 300; ++i)
    {
        const double x = where(random), y = where(random), w = size(random), h = size(random);
        parts.push_back({validity::makePolygon2({{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}})});
        boxes.push_back({x, y, x + w, y + h});
    }
    // the rectangles' union area, exactly: over the grid their edges make, a cell is in or out
    std::vector<double> xs, ys;
    for (const auto &b : boxes)
    {
        xs.insert(xs.end(), {b[0], b[2]});
        ys.insert(ys.end(), {b[1], b[3]});
    }
    std::sort(xs.begin(), xs.end());
    std::sort(ys.begin(), ys.end());
    double rectangles = 0.;
    for (std::size_t i = 0; i + 1 < xs.size(); ++i)
        for (std::size_t j = 0; j + 1 < ys.size(); ++j)
        {
            const double cx = 0.5 * (xs[i] + xs[i + 1]), cy = 0.5 * (ys[j] + ys[j + 1]);
            for (const auto &b : boxes)
                if (b[0] < cx && cx < b[2] && b[1] < cy && cy < b[3])
                {
                    rectangles += (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]);
                    break;
                }
        }
    // a frame with a hole, and a square inside the hole: apart from the frame's outline, within its box
    validity::Polygon2 frame = validity::makePolygon2({{30, 0}, {36, 0}, {36, 6}, {30, 6}});
    frame.inners().push_back(validity::makePolygon2({{31, 1}, {31, 5}, {35, 5}, {35, 1}}).outer());
    bg::correct(frame);
    parts.push_back({frame});
    parts.push_back({validity::makePolygon2({{32, 2}, {34, 2}, {34, 4}, {32, 4}})});
    parts.push_back({});  // an obstacle whose shadow is empty
    const validity::MultiPolygon2 united = validity::uniteFootprints(parts);
    EXPECT_TRUE(bg::is_valid(united));
    // (uniting every piece into one growing union, as before, was 1e-5 off here; this is 5e-8 off)
    EXPECT_NEAR(bg::area(united), rectangles + 20. + 4., 1e-6);
    EXPECT_TRUE(bg::within(validity::Point2(33, 3), united));
    EXPECT_FALSE(bg::within(validity::Point2(31.5, 3), united));
    EXPECT_TRUE(validity::uniteFootprints({}).empty());
}

TEST(Scene, PolygonSceneHelperMakesOnePrismPerPolygon)
{
    const auto polygons = test::randomPolygons(3);
    const auto scene = test::polygonScene(polygons);
    EXPECT_EQ(scene->size(), polygons.size());
    std::set<std::string> names;
    for (const auto &o : scene->obstacles())
    {
        names.insert(o.name);
        EXPECT_EQ(o.shape->type(), Shape::Type::PRISM);
    }
    EXPECT_EQ(names.size(), polygons.size());
    // the same seed gives the same polygons
    EXPECT_EQ(test::randomPolygons(3), polygons);
    EXPECT_NE(test::randomPolygons(4), polygons);
}

// ---------------------------------------------------------------------------------------------------------------
// Occupancy maps

namespace
{
    /** A 5 x 3 image (row 0 at the top): grey values, 0 black. */
    const std::vector<std::vector<int>> IMAGE = {{0, 255, 0, 0, 254},  //
                                                 {255, 255, 255, 255, 255},
                                                 {100, 0, 200, 0, 0}};

    std::string p5(const std::vector<std::vector<int>> &image, bool truncate = false)
    {
        std::string data = "P5\n# written by test_scene\n" + std::to_string(image[0].size()) + " " +
                           std::to_string(image.size()) + "\n255\n";
        for (const auto &row : image)
            for (int v : row)
                data.push_back(static_cast<char>(v));
        if (truncate)
            data.resize(data.size() - 3);
        return data;
    }

    std::string p2(const std::vector<std::vector<int>> &image, int maxValue)
    {
        std::string data = "P2\n# ascii\n" + std::to_string(image[0].size()) + " " + std::to_string(image.size()) +
                           "\n" + std::to_string(maxValue) + "\n";
        for (const auto &row : image)
        {
            for (int v : row)
                data += std::to_string(v * maxValue / 255) + " ";
            data += "\n";
        }
        return data;
    }

    /** The occupancy obstacles cover exactly the cells darker than half grey: every dark cell's centre lies in
        one box, no light cell's centre lies in any, the boxes' area is the dark cells' area. */
    void expectBoxesCoverDarkCells(const std::vector<Obstacle> &obstacles, const std::vector<std::vector<int>> &image,
                                   double resolution, const Eigen::Vector2d &origin, double height)
    {
        const int rows = static_cast<int>(image.size()), cols = static_cast<int>(image[0].size());
        double area = 0.;
        int dark = 0;
        for (const auto &o : obstacles)
        {
            ASSERT_EQ(o.shape->type(), Shape::Type::BOX);
            EXPECT_NEAR(o.shape->size().y(), resolution, 1e-12) << "one box per row run";
            EXPECT_NEAR(o.shape->size().z(), height, 1e-12);
            EXPECT_NEAR(o.pose.translation().z(), 0.5 * height, 1e-12);
            EXPECT_TRUE(o.pose.linear().isIdentity());
            area += o.shape->size().x() * o.shape->size().y();
        }
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c)
            {
                // row 0 is the top of the image
                const Eigen::Vector2d centre = origin + resolution * Eigen::Vector2d(c + 0.5, rows - 1 - r + 0.5);
                int inside = 0;
                for (const auto &o : obstacles)
                {
                    const Eigen::Vector2d d = centre - o.pose.translation().head<2>();
                    if (std::abs(d.x()) < 0.5 * o.shape->size().x() && std::abs(d.y()) < 0.5 * o.shape->size().y())
                        ++inside;
                }
                const bool occupied = image[r][c] < 0.5 * 255;
                dark += occupied;
                EXPECT_EQ(inside, occupied ? 1 : 0) << "cell row " << r << " column " << c;
            }
        EXPECT_NEAR(area, dark * resolution * resolution, 1e-12);
    }
}  // namespace

TEST(Scene, OccupancyObstaclesCoverExactlyTheDarkCells)
{
    test::TempDir dir("michi_scene");
    const double resolution = 0.5, height = 2.;
    const Eigen::Vector2d origin(-1., 2.);
    const std::string binary = dir.write("map_p5.pgm", p5(IMAGE));
    const std::string ascii = dir.write("map_p2.pgm", p2(IMAGE, 255));
    for (const auto &path : {binary, ascii})
    {
        const auto obstacles = validity::occupancyObstacles(path, resolution, origin, height);
        // row 0: runs [0] and [2, 3]; row 2: [0, 1] (100 is dark, 200 is not) and [3, 4]
        ASSERT_EQ(obstacles.size(), 4u) << path;
        expectBoxesCoverDarkCells(obstacles, IMAGE, resolution, origin, height);
        // the first run by hand: the top-left cell, x in [-1, -0.5], y in [3, 3.5]
        EXPECT_NEAR(obstacles[0].pose.translation().x(), -0.75, 1e-12);
        EXPECT_NEAR(obstacles[0].pose.translation().y(), 3.25, 1e-12);
        EXPECT_NEAR(obstacles[0].shape->size().x(), 0.5, 1e-12);
        // the run of two cells [2, 3] in the top row
        EXPECT_NEAR(obstacles[1].pose.translation().x(), 0.5, 1e-12);
        EXPECT_NEAR(obstacles[1].shape->size().x(), 1., 1e-12);
        std::set<std::string> names;
        for (const auto &o : obstacles)
            names.insert(o.name);
        EXPECT_EQ(names.size(), obstacles.size()) << "names are unique, so they can all go into one scene";
        Scene scene;
        for (const auto &o : obstacles)
            scene.add(o);
        EXPECT_NEAR(bg::area(scene.polygons2d()), 7 * 0.25, 1e-12);
    }
}

TEST(Scene, OccupancyObstaclesFromOtherGreyRangesAndThresholds)
{
    test::TempDir dir("michi_scene");
    // an ASCII map with a maximum grey value of 15 gives the same cells
    const std::string ascii = dir.write("map15.pgm", p2(IMAGE, 15));
    expectBoxesCoverDarkCells(validity::occupancyObstacles(ascii, 1., Eigen::Vector2d::Zero()), IMAGE, 1.,
                              Eigen::Vector2d::Zero(), 1.);

    // a 16-bit binary map
    std::string data = "P5 3 1 65535\n";
    for (int v : {0, 65535, 1000})
    {
        data.push_back(static_cast<char>(v >> 8));
        data.push_back(static_cast<char>(v & 0xff));
    }
    const auto wide = validity::occupancyObstacles(dir.write("map16.pgm", data), 1., Eigen::Vector2d::Zero());
    ASSERT_EQ(wide.size(), 2u);
    EXPECT_NEAR(wide[0].pose.translation().x(), 0.5, 1e-12);
    EXPECT_NEAR(wide[1].pose.translation().x(), 2.5, 1e-12);

    // a threshold of 0.9 makes 200 (0.78) dark too: row 2 becomes one run
    const std::string binary = dir.write("map.pgm", p5(IMAGE));
    const auto obstacles = validity::occupancyObstacles(binary, 1., Eigen::Vector2d::Zero(), 1., 0.9);
    ASSERT_EQ(obstacles.size(), 3u);
    EXPECT_NEAR(obstacles[2].shape->size().x(), 5., 1e-12);
}

TEST(Scene, BrokenOccupancyFilesThrowNamingTheFile)
{
    test::TempDir dir("michi_scene");
    const std::vector<std::string> paths = {dir.write("truncated_p5.pgm", p5(IMAGE, true)),
                                            dir.write("truncated_p2.pgm", "P2 5 3 255\n0 255 0 0 254\n255 255\n"),
                                            dir.write("not_a_pgm.pgm", "P6\n5 3\n255\n" + std::string(45, '\0')),
                                            dir.write("text.pgm", "hello, world\n"),
                                            dir.write("empty.pgm", ""),
                                            dir.write("bad_width.pgm", "P5\nfive 3\n255\n"),
                                            dir.write("zero_height.pgm", "P5\n5 0\n255\n"),
                                            dir.path() + "/does_not_exist.pgm"};
    for (const auto &path : paths)
    {
        try
        {
            validity::occupancyObstacles(path, 0.1, Eigen::Vector2d::Zero());
            ADD_FAILURE() << "no exception for " << path;
        }
        catch (const std::runtime_error &e)
        {
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(validity::occupancyObstacles(dir.write("ok.pgm", p5(IMAGE)), 0., Eigen::Vector2d::Zero()),
                 std::invalid_argument);
}
