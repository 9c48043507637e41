// Tests of michi::validity::FclValidityChecker: collision against the scene and itself, exact clearance, nearest
// points, collision descriptions, bounds and thread safety.

#include "support/TestScenes.h"

#include <michi/state_spaces/JointStateSpace.h>
#include <michi/validity/fcl/FclValidityChecker.h>

#include <ompl/base/ScopedState.h>
#include <ompl/util/RandomNumbers.h>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

using namespace michi;
using validity::Obstacle;
using validity::Shape;

namespace ob = ompl::base;

namespace
{
    /** Accuracy of FCL 0.7 distances that involve a curved shape against a polytope or another cylinder (cylinder
        and prism, cylinder and cylinder): they go through GJK, which stops at the request's distance_tolerance,
        1e-6 by default; errors of 1e-6 to 2e-6 are measured here with either GJK solver (a 1e-3 gap reads
        0.0010011). Sphere-box is analytic, and polytope pairs (box, prism) are exact to rounding. */
    const double CYLINDER_GJK_TOL = 5e-6;

    /** A ball of radius 0.1 on a slide along x (prismatic joint "slide", limits [-2, 2]); its centre is at
        (q, 0, 0). */
    const char *BALL_URDF = R"(<?xml version="1.0"?>
<robot name="ball_on_slide">
  <link name="base_link"/>
  <link name="ball"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <joint name="slide" type="prismatic">
    <parent link="base_link"/><child link="ball"/><axis xyz="1 0 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
</robot>
)";

    /** A box obstacle whose face x = 0.9 faces the ball: the ball at q is 0.8 - q from it. */
    validity::ScenePtr wallAtPointNine()
    {
        auto scene = std::make_shared<validity::Scene>();
        Obstacle wall;
        wall.name = "wall";
        wall.shape = Shape::box({0.2, 1., 1.});
        wall.pose = Eigen::Translation3d(1., 0.2, 0.1) * Eigen::Isometry3d::Identity();
        scene->add(wall);
        return scene;
    }

    test::CheckerSetup ballSetup()
    {
        return test::robotSetup(validity::RobotModel::fromUrdfString(BALL_URDF, "<ball urdf>", "."), wallAtPointNine());
    }

    /** A state of \e si from a configuration. */
    ob::ScopedState<> state(const ob::SpaceInformationPtr &si, const std::vector<double> &values)
    {
        ob::ScopedState<> s(si);
        si->getStateSpace()->copyFromReals(s.get(), values);
        return s;
    }

    /** Random configurations uniformly within the bounds of a joint space, from a local generator. */
    std::vector<std::vector<double>> randomConfigurations(const test::CheckerSetup &setup, std::size_t count,
                                                          std::uint_fast32_t seed)
    {
        ompl::RNG rng(seed);
        std::vector<std::vector<double>> configurations;
        for (std::size_t i = 0; i < count; ++i)
        {
            std::vector<double> q;
            for (std::size_t v = 0; v < setup.model->variableCount(); ++v)
            {
                const auto &joint = setup.model->variableJoint(v);
                q.push_back(rng.uniformReal(joint.lower, joint.upper));
            }
            configurations.push_back(q);
        }
        return configurations;
    }
}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// Collision and clearance against the scene

TEST(FclValidityChecker, TouchingIsInvalidAndSeparatedHasTheExactClearance)
{
    const auto setup = ballSetup();
    // overlapping by 1e-3
    EXPECT_FALSE(setup.si->isValid(state(setup.si, {0.801}).get()));
    EXPECT_EQ(setup.checker->describeCollision(std::vector<double>{0.801}.data()), "ball touches obstacle 'wall'");
    EXPECT_LE(setup.checker->clearance(state(setup.si, {0.801}).get()), 0.);
    double dist = 1.;
    EXPECT_FALSE(setup.checker->isValid(state(setup.si, {0.801}).get(), dist));
    EXPECT_EQ(dist, 0.);
    // deep inside
    EXPECT_FALSE(setup.si->isValid(state(setup.si, {1.}).get()));

    // separated: FCL's sphere-box distance is exact
    for (double q : {0.799, 0.7, 0.5, -1.2})
    {
        const auto s = state(setup.si, {q});
        EXPECT_TRUE(setup.si->isValid(s.get())) << q;
        EXPECT_TRUE(setup.checker->describeCollision(&q).empty());
        EXPECT_NEAR(setup.checker->clearance(s.get()), 0.8 - q, 1e-9) << q;
        EXPECT_NEAR(setup.checker->clearanceConfiguration(&q), 0.8 - q, 1e-9) << q;
        double d = -1.;
        EXPECT_TRUE(setup.checker->isValid(s.get(), d));
        EXPECT_NEAR(d, 0.8 - q, 1e-9);
    }
    EXPECT_EQ(setup.checker->getSpecs().clearanceComputationType, ob::StateValidityCheckerSpecs::EXACT);
}

TEST(FclValidityChecker, ProximityPointsLieOnBothSurfaces)
{
    const auto setup = ballSetup();
    const double q = 0.5;
    const auto p = setup.checker->proximity(&q);
    EXPECT_NEAR(p.distance, 0.3, 1e-9);
    EXPECT_EQ(p.body, 0);
    EXPECT_EQ(p.otherBody, -1);
    EXPECT_EQ(p.obstacle, "wall");
    EXPECT_LT((p.robotPoint - Eigen::Vector3d(0.6, 0., 0.)).norm(), 1e-9) << p.robotPoint.transpose();
    EXPECT_LT((p.otherPoint - Eigen::Vector3d(0.9, 0., 0.)).norm(), 1e-9) << p.otherPoint.transpose();
    EXPECT_NEAR((p.otherPoint - p.robotPoint).norm(), p.distance, 1e-9);
}

TEST(FclValidityChecker, EmptySceneHasInfiniteClearance)
{
    const auto setup = test::robotSetup(validity::RobotModel::fromUrdfString(BALL_URDF, "<ball urdf>", "."),
                                        std::make_shared<validity::Scene>());
    const double q = 0.;
    EXPECT_TRUE(setup.checker->isValidConfiguration(&q));
    EXPECT_EQ(setup.checker->clearanceConfiguration(&q), std::numeric_limits<double>::infinity());
    EXPECT_TRUE(setup.checker->proximity(&q).obstacle.empty());
}

namespace
{
    /** The planar arm (links 0.5 and 0.4, half width 0.02) below the wall x in [0.1, 0.8], y in [0.3, 0.5]: known
        clearances, nearest points, touching. \e tol is the accuracy FCL reaches for the link shape. */
    void checkArmBelowWall(test::PlanarArmOptions::LinkShape shape, double tol)
    {
        const double radius = 0.02;
        test::PlanarArmOptions options;
        options.linkRadius = radius;
        options.linkShape = shape;
        const auto setup = test::planarArmSetup({0.5, 0.4}, {test::boxOutline({0.1, 0.3}, {0.8, 0.5})}, options);

        struct Case
        {
            std::vector<double> q;
            double clearance;  // by hand
            double nearestY;   // y of the nearest point on the arm
        };
        const double h = 0.5 * std::sin(0.3);
        const std::vector<Case> cases = {
            // straight along x: the links' top at y = r
            {{0., 0.}, 0.3 - radius, radius},
            // link 1 raised by 0.3 rad, link 2 horizontal at y = 0.5 sin 0.3 under the wall
            {{0.3, -0.3}, 0.3 - h - radius, h + radius}};
        for (const auto &c : cases)
        {
            const auto s = state(setup.si, c.q);
            ASSERT_TRUE(setup.si->isValid(s.get()));
            EXPECT_NEAR(setup.checker->clearance(s.get()), c.clearance, tol) << "q = " << c.q[0] << ", " << c.q[1];
            const auto p = setup.checker->proximity(c.q.data());
            EXPECT_NEAR(p.distance, c.clearance, tol);
            EXPECT_EQ(p.obstacle, "polygon0");
            EXPECT_EQ(setup.bodies->bodies()[p.body].name, c.q[0] == 0. ? "link1" : "link2");
            EXPECT_NEAR(p.robotPoint.y(), c.nearestY, tol);
            EXPECT_NEAR(p.otherPoint.y(), 0.3, tol);
            EXPECT_GE(p.otherPoint.x(), 0.1 - tol);
            EXPECT_LE(p.otherPoint.x(), 0.8 + tol);
            EXPECT_NEAR(p.robotPoint.x(), p.otherPoint.x(), 1e-3) << "the nearest points face each other";
            EXPECT_NEAR((p.otherPoint - p.robotPoint).norm(), p.distance, tol);
        }

        // link 2 raised into the wall
        const std::vector<double> into{0., 0.9};
        EXPECT_FALSE(setup.si->isValid(state(setup.si, into).get()));
        EXPECT_EQ(setup.checker->describeCollision(into.data()), "link2 touches obstacle 'polygon0'");
        // link 1 raised by a, link 2 horizontal with its top 1e-3 into / below the wall's lower face
        for (double gap : {-1e-3, 1e-3})
        {
            const double a = std::asin((0.3 - gap - radius) / 0.5);
            const std::vector<double> q{a, -a};
            EXPECT_EQ(setup.checker->isValidConfiguration(q.data()), gap > 0.) << gap;
            if (gap > 0.)
                EXPECT_NEAR(setup.checker->clearanceConfiguration(q.data()), gap, tol);
        }
    }
}  // namespace

TEST(FclValidityChecker, PlanarArmClearanceToAPolygonWall)
{
    // box links against a prism: a polytope pair, which FCL's GJK solves exactly (to rounding)
    checkArmBelowWall(test::PlanarArmOptions::LinkShape::BOX, 1e-9);
}

TEST(FclValidityChecker, CylinderLinkClearanceIsAsAccurateAsFclTolerance)
{
    // cylinder links against a prism: GJK stops at FCL's default distance_tolerance (1e-6)
    checkArmBelowWall(test::PlanarArmOptions::LinkShape::CYLINDER, CYLINDER_GJK_TOL);
}

TEST(FclValidityChecker, PlanarRigidBodyInSe2)
{
    // a 0.2 x 0.2 square robot and a wall x in [1, 1.2]
    const auto setup = test::planarRigidBodySetup(test::boxOutline({-0.1, -0.1}, {0.1, 0.1}),
                                                  {test::boxOutline({1., -1.}, {1.2, 1.})}, {-2., -2.}, {2., 2.});
    EXPECT_TRUE(setup.si->isValid(state(setup.si, {0.5, 0., 0.}).get()));
    EXPECT_NEAR(setup.checker->clearance(state(setup.si, {0.5, 0., 0.}).get()), 0.4, 1e-6);
    // turned by 45 degrees the corner reaches x + 0.1 sqrt(2)
    EXPECT_NEAR(setup.checker->clearance(state(setup.si, {0.5, 0.3, M_PI / 4}).get()), 0.5 - 0.1 * std::sqrt(2.), 1e-6);
    EXPECT_FALSE(setup.si->isValid(state(setup.si, {0.901, 0., 0.}).get()));
    EXPECT_TRUE(setup.si->isValid(state(setup.si, {0.899, 0., 0.}).get()));
    EXPECT_FALSE(setup.si->isValid(state(setup.si, {0.87, 0., M_PI / 4}).get()));
    // out of the SE(2) bounds
    EXPECT_FALSE(setup.si->isValid(state(setup.si, {-2.5, 0., 0.}).get()));
}

TEST(FclValidityChecker, ConvexPrismsCollideExactlyAsPolygons)
{
    // dynamic_mobile_passage's robot and central block, both convex prisms. With FCL's default solver (libccd) the
    // boolean query refused poses up to 4.4 cm clear of the block (31 of 200,000 near it); the answer must be the
    // exact one: the footprint's polygon intersects the block's.
    using Point = boost::geometry::model::d2::point_xy<double>;
    using Polygon = boost::geometry::model::polygon<Point>;
    const std::vector<Eigen::Vector2d> footprint = test::boxOutline({-0.25, -0.2}, {0.25, 0.2});
    const std::vector<Eigen::Vector2d> block = test::boxOutline({5.5, 1.6}, {7.5, 5.4});
    const auto setup = test::planarRigidBodySetup(footprint, {block}, {0., 0.}, {12., 7.});
    const auto polygon = [](const std::vector<Eigen::Vector2d> &outline, const Eigen::Isometry2d &pose)
    {
        Polygon p;
        for (std::size_t i = 0; i <= outline.size(); ++i)
        {
            const Eigen::Vector2d q = pose * outline[i % outline.size()];
            boost::geometry::append(p.outer(), Point(q.x(), q.y()));
        }
        boost::geometry::correct(p);
        return p;
    };
    const Polygon blockPolygon = polygon(block, Eigen::Isometry2d::Identity());
    // the pose found: 1.30 cm from the block's face x = 5.5, refused by libccd
    EXPECT_TRUE(setup.si->isValid(state(setup.si, {5.17361, 2.00220, -2.67221}).get()));
    ompl::RNG rng(3);
    int checked = 0, colliding = 0;
    for (int n = 0; n < 20000; ++n)
    {
        const double x = rng.uniformReal(4.8, 8.2), y = rng.uniformReal(0.9, 6.1), yaw = rng.uniformReal(-M_PI, M_PI);
        Eigen::Isometry2d pose = Eigen::Isometry2d::Identity();
        pose.translate(Eigen::Vector2d(x, y));
        pose.rotate(yaw);
        const Polygon robot = polygon(footprint, pose);
        const bool touches = boost::geometry::intersects(robot, blockPolygon);
        if (!touches && boost::geometry::distance(robot, blockPolygon) < 1e-6)
            continue;  // touching within rounding: either answer is right
        ++checked;
        colliding += touches ? 1 : 0;
        ASSERT_EQ(setup.si->isValid(state(setup.si, {x, y, yaw}).get()), !touches) << x << " " << y << " " << yaw;
    }
    EXPECT_GT(checked, 19000);
    EXPECT_GT(colliding, 5000);  // poses on both sides of the block's boundary
    EXPECT_LT(colliding, checked - 5000);
}

// ---------------------------------------------------------------------------------------------------------------
// Self-collision

TEST(FclValidityChecker, FoldedArmCollidesWithItselfUntilThePairIsAllowed)
{
    auto model = test::planarArmModel({0.4, 0.3, 0.3});
    auto setup = test::robotSetup(model, std::make_shared<validity::Scene>());
    // link 2 turns back over link 1 and link 3 forward again, crossing link 1 near x = 0.25
    const std::vector<double> folded{0., 3.0, 3.0};
    const auto s = state(setup.si, folded);
    EXPECT_FALSE(setup.si->isValid(s.get()));
    EXPECT_EQ(setup.checker->describeCollision(folded.data()), "link1 touches link3");
    const auto p = setup.checker->proximity(folded.data(), true);
    EXPECT_LE(p.distance, 0.);
    EXPECT_EQ(setup.bodies->bodies()[p.body].name, "link1");
    EXPECT_EQ(setup.bodies->bodies()[p.otherBody].name, "link3");
    EXPECT_TRUE(p.obstacle.empty());
    // self distance is not part of the clearance (there are no obstacles)
    EXPECT_EQ(setup.checker->clearance(s.get()), std::numeric_limits<double>::infinity());

    // stretched out, link 1 and link 3 are 0.3 apart (end cap to end cap). This coaxial pair with parallel end
    // faces is degenerate for GJK: FCL 0.7 answers the rim-to-rim distance hypot(0.3, 2 r) = 0.30265 here (libccd
    // whatever the tolerance; GST_INDEP too with these URDF-made poses), so only bracket it
    const std::vector<double> straight{0., 0., 0.};
    EXPECT_TRUE(setup.checker->isValidConfiguration(straight.data()));
    const double selfDistance = setup.checker->proximity(straight.data(), true).distance;
    EXPECT_GE(selfDistance, 0.3 - CYLINDER_GJK_TOL);
    EXPECT_LE(selfDistance, std::hypot(0.3, 0.04) + CYLINDER_GJK_TOL);
    // bent a little, the end faces are no longer parallel and the answer is right to GJK's tolerance: link 3 turned
    // by 0.1 about joint 3 at (0.7, 0) brings its upper start corner nearest, facing link 1's end disk at x = 0.4
    const std::vector<double> bent{0., 0., 0.1};
    EXPECT_NEAR(setup.checker->proximity(bent.data(), true).distance, 0.3 - 0.02 * std::sin(0.1), CYLINDER_GJK_TOL);

    // the bodies take the model's pairs when they are made: allow the pair, then build the checker again
    model->allowCollision("link3", "link1");
    setup = test::robotSetup(model, std::make_shared<validity::Scene>());
    EXPECT_TRUE(setup.si->isValid(state(setup.si, folded).get()));
    EXPECT_TRUE(setup.checker->describeCollision(folded.data()).empty());
}

// ---------------------------------------------------------------------------------------------------------------
// Bounds and construction

TEST(FclValidityChecker, StatesOutOfBoundsAreInvalid)
{
    const auto setup = test::planarArmSetup({0.5, 0.4}, {});
    const auto inside = state(setup.si, {3.1, -3.1});
    EXPECT_TRUE(setup.si->isValid(inside.get()));
    const auto outside = state(setup.si, {3.2, 0.});
    EXPECT_FALSE(setup.si->isValid(outside.get()));
    double dist = 1.;
    EXPECT_FALSE(setup.checker->isValid(outside.get(), dist));
    EXPECT_EQ(dist, 0.);
    // the raw configuration query does not know the space's bounds
    EXPECT_TRUE(setup.checker->isValidConfiguration(std::vector<double>{3.2, 0.}.data()));
}

TEST(FclValidityChecker, ConstructorRejectsAMismatchedSpace)
{
    const auto model = test::planarArmModel({0.5, 0.4});
    auto bodies =
        std::make_shared<validity::RobotGroupBodies>(model, std::vector<int>{0, 1}, std::vector<double>{0., 0.});
    auto si = std::make_shared<ob::SpaceInformation>(state_spaces::makeJointStateSpace({{"a", -1., 1.}}));
    EXPECT_THROW(validity::FclValidityChecker(si, bodies, std::make_shared<validity::Scene>()), std::invalid_argument);
}

TEST(FclValidityChecker, GroupOfJointsKeepsTheOthersFixed)
{
    // only joint 2 moves; joint 1 is held at pi/2, so the arm points up into a wall above it
    const auto model = test::planarArmModel({0.5, 0.4});
    auto scene = test::polygonScene({test::boxOutline({-0.5, 0.7}, {0.5, 0.9})});
    auto bodies =
        std::make_shared<validity::RobotGroupBodies>(model, std::vector<int>{1}, std::vector<double>{M_PI / 2, 0.});
    EXPECT_EQ(bodies->dimension(), 1u);
    auto si = std::make_shared<ob::SpaceInformation>(state_spaces::makeJointStateSpace({{"joint2", -3., 3.}}));
    auto checker = std::make_shared<validity::FclValidityChecker>(si, bodies, scene);
    si->setStateValidityChecker(checker);
    si->setup();
    EXPECT_FALSE(si->isValid(state(si, {0.}).get()));  // tip at y = 0.9
    EXPECT_TRUE(si->isValid(state(si, {M_PI / 2}).get()));
    EXPECT_EQ(bodies->fullConfiguration(std::vector<double>{0.25}.data()), (std::vector<double>{M_PI / 2, 0.25}));
}

// ---------------------------------------------------------------------------------------------------------------
// Thread safety

namespace
{
    struct Answers
    {
        std::vector<char> valid;
        std::vector<double> clearance;
    };

    Answers answer(const test::CheckerSetup &setup, const std::vector<std::vector<double>> &configurations)
    {
        Answers a;
        ob::ScopedState<> s(setup.si);
        for (const auto &q : configurations)
        {
            setup.si->getStateSpace()->copyFromReals(s.get(), q);
            double d = 0.;
            a.valid.push_back(setup.checker->isValid(s.get(), d) ? 1 : 0);
            a.clearance.push_back(d);
        }
        return a;
    }

    /** A 3-link arm among random polygons, plus a moving obstacle far from anything the arm can reach. */
    test::CheckerSetup busyArmSetup()
    {
        test::RandomPolygonOptions options;
        options.count = 10;
        options.lo = {-1.2, -1.2};
        options.hi = {1.2, 1.2};
        options.keepClearRadius = 0.15;  // the base stays free
        auto setup = test::planarArmSetup({0.4, 0.35, 0.3}, test::randomPolygons(5, options));
        Obstacle far;
        far.name = "far_mover";
        far.shape = Shape::box({0.5, 0.5, 0.5});
        far.trajectory = {validity::TimedPose{0., Eigen::Isometry3d(Eigen::Translation3d(100., 0., 0.))},
                          validity::TimedPose{1., Eigen::Isometry3d(Eigen::Translation3d(100., 50., 0.))}};
        setup.scene->add(far);
        return setup;
    }
}  // namespace

TEST(FclValidityChecker, ConcurrentQueriesGiveTheSameAnswers)
{
    const auto setup = busyArmSetup();
    const auto configurations = randomConfigurations(setup, 2000, 17);
    const Answers reference = answer(setup, configurations);
    const auto validCount = std::count(reference.valid.begin(), reference.valid.end(), 1);
    // the scene is neither empty nor full
    EXPECT_GT(validCount, 200);
    EXPECT_LT(validCount, 1800);

    const std::uint64_t queriesBefore = setup.checker->queryCount();
    std::vector<Answers> results(4);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back(
            [&, t]
            {
                results[t] = answer(setup, configurations);
            });
    for (auto &thread : threads)
        thread.join();
    for (int t = 0; t < 4; ++t)
    {
        EXPECT_EQ(results[t].valid, reference.valid) << "thread " << t;
        EXPECT_EQ(results[t].clearance, reference.clearance) << "thread " << t;
    }
    EXPECT_GE(setup.checker->queryCount() - queriesBefore, 4u * 2000u);
}

TEST(FclValidityChecker, MoreThreadsThanObjectSlotsShareTheSetsAndCountEveryQuery)
{
    // The checker keeps one set of FCL objects per thread slot (16): 24 threads at once share slots, take sets from
    // other slots or make their own, and put them back where there is room. Answers and counts must not change.
    const auto setup = busyArmSetup();
    const auto configurations = randomConfigurations(setup, 300, 29);
    const Answers reference = answer(setup, configurations);
    const std::uint64_t queriesBefore = setup.checker->queryCount();
    const int threadCount = 24;
    std::vector<Answers> results(threadCount);
    std::vector<std::thread> threads;
    for (int t = 0; t < threadCount; ++t)
        threads.emplace_back(
            [&, t]
            {
                results[t] = answer(setup, configurations);
            });
    for (auto &thread : threads)
        thread.join();
    for (int t = 0; t < threadCount; ++t)
        EXPECT_EQ(results[t].valid, reference.valid) << "thread " << t;
    // each answer() is one isValid per configuration (clearance is a distance query, not counted)
    EXPECT_GE(setup.checker->queryCount() - queriesBefore, static_cast<std::uint64_t>(threadCount) * 300u);
}

TEST(FclValidityChecker, ConcurrentQueriesWhileTheSceneTimeChanges)
{
    const auto setup = busyArmSetup();
    const auto configurations = randomConfigurations(setup, 2000, 23);
    const Answers reference = answer(setup, configurations);

    std::atomic<bool> done{false};
    std::atomic<int> timeChanges{0};
    const std::uint64_t changesBefore = setup.scene->changeCount();
    std::thread clock(
        [&]
        {
            for (int i = 0; !done.load() || i < 10; ++i)
            {
                setup.scene->setTime((i % 101) / 100.);
                ++timeChanges;
            }
        });
    std::vector<Answers> results(4);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back(
            [&, t]
            {
                results[t] = answer(setup, configurations);
            });
    for (auto &thread : threads)
        thread.join();
    done = true;
    clock.join();

    EXPECT_GT(setup.scene->changeCount(), changesBefore) << "the moving obstacle moved";
    EXPECT_GE(timeChanges.load(), 10);
    for (int t = 0; t < 4; ++t)
    {
        EXPECT_EQ(results[t].valid, reference.valid) << "thread " << t;
        // the nearest obstacle is never the far one, so clearances are the same too
        EXPECT_EQ(results[t].clearance, reference.clearance) << "thread " << t;
    }
}
