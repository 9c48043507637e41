// PathSeed's stages that the ring-task numbers credit but nothing tested (issue 17): stitching decoded paths,
// decoding across +-pi on continuous joints, and a library that grows past its size bound.
#include <michi/planners/path_seed/PathSeed.h>
#include <michi/planners/path_seed/PathSeedLibrary.h>
#include <michi/planners/path_seed/PathSeedRepair.h>
#include <michi/state_spaces/JointStateSpace.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>

namespace ob = ompl::base;
namespace og = ompl::geometric;
using michi::planners::PathSeed;
using michi::planners::PathSeedLibrary;

namespace
{
    struct Box
    {
        double x0, x1, y0, y1;
    };

    // the unit square with three boxes: O1 blocks the straight start-goal line, O2 path A's last segment, O3 path
    // B's first segment; A's first half and B's second half are free, and so is the way between them
    ob::SpaceInformationPtr squareWithBoxes()
    {
        auto space = std::make_shared<ob::RealVectorStateSpace>(2);
        space->setBounds(0., 1.);
        auto si = std::make_shared<ob::SpaceInformation>(space);
        const std::vector<Box> boxes = {{0.4, 0.6, 0.28, 0.72}, {0.72, 0.86, 0.55, 0.8}, {0.15, 0.27, 0.15, 0.42}};
        si->setStateValidityChecker(
            [boxes](const ob::State *state)
            {
                const double *v = state->as<ob::RealVectorStateSpace::StateType>()->values;
                for (const auto &b : boxes)
                    if (v[0] >= b.x0 && v[0] <= b.x1 && v[1] >= b.y0 && v[1] <= b.y1)
                        return false;
                return true;
            });
        si->setStateValidityCheckingResolution(0.002);
        si->setup();
        return si;
    }

    og::PathGeometric makePath(const ob::SpaceInformationPtr &si, const std::vector<std::vector<double>> &values)
    {
        og::PathGeometric path(si);
        ob::ScopedState<> s(si->getStateSpace());
        for (const auto &v : values)
        {
            s = v;
            path.append(s.get());
        }
        return path;
    }

    std::vector<double> reals(const ob::SpaceInformationPtr &si, const ob::State *state)
    {
        std::vector<double> v;
        si->getStateSpace()->copyToReals(v, state);
        return v;
    }

    double angleBetween(double a, double b)
    {
        return std::abs(std::remainder(a - b, 2. * M_PI));
    }
}  // namespace

TEST(PathSeedStitch, JoinsTheValidHalvesOfTwoInvalidPaths)
{
    ompl::RNG::setSeed(1);
    const auto si = squareWithBoxes();
    const og::PathGeometric a = makePath(si, {{0.1, 0.5}, {0.3, 0.9}, {0.7, 0.9}, {0.9, 0.5}});
    const og::PathGeometric b = makePath(si, {{0.1, 0.5}, {0.3, 0.1}, {0.7, 0.1}, {0.9, 0.5}});
    const auto ptc = ob::plannerNonTerminatingCondition();
    // each fails on one segment only: A on its last (O2), B on its first (O3)
    const auto va = michi::planners::checkPathFull(si, a, ptc), vb = michi::planners::checkPathFull(si, b, ptc);
    EXPECT_EQ(va.invalidStates(), 0u);
    EXPECT_EQ(vb.invalidStates(), 0u);
    EXPECT_EQ(va.invalidSegments(), 1u);
    EXPECT_EQ(vb.invalidSegments(), 1u);
    EXPECT_FALSE(va.segment[2]);  // 0: invalid
    EXPECT_FALSE(vb.segment[0]);
    ASSERT_FALSE(michi::planners::checkPathFailFast(si, a, ptc));
    ASSERT_FALSE(michi::planners::checkPathFailFast(si, b, ptc));

    og::PathGeometric out(si);
    unsigned long checks = 0;
    ASSERT_TRUE(michi::planners::stitchPaths(si, {a, b}, ptc, out, 3, &checks));
    EXPECT_TRUE(out.check());
    EXPECT_GT(checks, 0u);
    EXPECT_TRUE(si->equalStates(out.getState(0), a.getState(0)));
    EXPECT_TRUE(si->equalStates(out.getState(out.getStateCount() - 1), a.getState(3)));
    // it leaves the start along A (B's first segment is blocked) and reaches the goal along B (A's last is)
    EXPECT_TRUE(si->equalStates(out.getState(1), a.getState(1)));
    EXPECT_TRUE(si->equalStates(out.getState(out.getStateCount() - 2), b.getState(2)));

    // one path alone cannot be stitched into anything valid
    og::PathGeometric alone(si);
    EXPECT_FALSE(michi::planners::stitchPaths(si, {a}, ptc, alone, 3));
    // a terminated condition stops it
    EXPECT_FALSE(michi::planners::stitchPaths(si, {a, b}, ob::plannerAlwaysTerminatingCondition(), alone, 3));
}

TEST(PathSeedPlanner, DecodesAcrossPiOnAContinuousJoint)
{
    ompl::RNG::setSeed(2);
    // joint 1 continuous (SO(2), values in [-pi, pi)), joint 2 a revolute joint in [-1, 1]; no obstacle
    const auto space = michi::state_spaces::makeJointStateSpace({{"j1", 0., 0., true}, {"j2", -1., 1., false}});
    og::SimpleSetup setup(space);
    setup.setStateValidityChecker(
        [](const ob::State *)
        {
            return true;
        });
    const auto si = setup.getSpaceInformation();
    auto planner = std::make_shared<PathSeed>(si);
    planner->setRace(false);
    planner->setLearn(false);
    setup.setPlanner(planner);
    // a training path from 2 to -2 through pi, the short way round (1.14 rad each side), its waypoint 0.5 off the
    // line: unwrapped its ratio is 0.5; on the raw values (2 -> -2 through 0) it would be -0.29
    planner->addExperience(makePath(si, {{2.0, 0.}, {M_PI - 1e-9, 0.5}, {-2.0, 0.}}));
    ASSERT_EQ(planner->experienceCount(), 1u);

    auto solve = [&](const std::vector<double> &s, const std::vector<double> &g)
    {
        ob::ScopedState<> start(space), goal(space);
        start = s;
        goal = g;
        planner->clear();
        setup.clear();
        setup.setStartAndGoalStates(start, goal);
        EXPECT_EQ(setup.solve(1.), ob::PlannerStatus::EXACT_SOLUTION);
        EXPECT_EQ(planner->getLastSource(), "recall");
        return setup.getSolutionPath();
    };
    // its own query gives it back
    og::PathGeometric own = solve({2.0, 0.}, {-2.0, 0.});
    ASSERT_EQ(own.getStateCount(), 3u);
    EXPECT_LT(angleBetween(reals(si, own.getState(1))[0], M_PI), 1e-6);
    EXPECT_NEAR(reals(si, own.getState(1))[1], 0.5, 1e-6);
    // a new query across pi: the waypoint is decoded halfway along the short way (at pi), 0.5 off the line; on
    // raw values it would land at 2.83, a third of a radian short of pi
    og::PathGeometric across = solve({1.8, 0.}, {-1.8, 0.});
    ASSERT_EQ(across.getStateCount(), 3u);
    EXPECT_LT(angleBetween(reals(si, across.getState(1))[0], M_PI), 1e-6);
    EXPECT_NEAR(reals(si, across.getState(1))[1], 0.5, 1e-6);
    // the decoded path goes the short way (the space's distance sums the joints: 2 x (1.34 + 0.5) = 3.68), not
    // around through 0 (2 x (1.8 + 0.5) = 4.6 and more)
    EXPECT_LT(across.length(), 4.);
    // across pi the other way (start on the negative side): the waypoint is at pi again, its offset turned with
    // the line
    og::PathGeometric back = solve({-2.5, 0.}, {2.5, 0.});
    ASSERT_EQ(back.getStateCount(), 3u);
    EXPECT_LT(angleBetween(reals(si, back.getState(1))[0], M_PI), 1e-6);
    EXPECT_NEAR(std::abs(reals(si, back.getState(1))[1]), 0.5, 1e-6);
    EXPECT_LT(back.length(), 4.);
}

TEST(PathSeedLibrary, ForgetsTheLeastUsedSeedsPastItsBound)
{
    PathSeedLibrary library;
    auto path = [](double x)
    {
        return std::vector<Eigen::VectorXd>{Eigen::Vector2d(0., 0.), Eigen::Vector2d(x, 1.), Eigen::Vector2d(2., 0.)};
    };
    library.setCapacity(3);
    library.add(path(0.));
    library.markUsed(library.seed(0).id);  // seed 0 took part in a solution
    for (int i = 1; i <= 4; ++i)
        library.add(path(i));
    ASSERT_EQ(library.size(), 3u);  // never more than the bound
    // the unused seeds went oldest first (1, then 2); the used one and the newest stay
    std::vector<std::uint64_t> ids;
    for (std::size_t i = 0; i < library.size(); ++i)
        ids.push_back(library.seed(i).id);
    EXPECT_EQ(ids, (std::vector<std::uint64_t>{0, 3, 4}));
    EXPECT_EQ(library.seed(0).uses, 1u);
    // a tighter bound forgets at once, the used seed last
    library.setCapacity(1);
    ASSERT_EQ(library.size(), 1u);
    EXPECT_EQ(library.seed(0).id, 0u);
    // 0: no bound
    library.setCapacity(0);
    for (int i = 0; i < 10; ++i)
        library.add(path(i));
    EXPECT_EQ(library.size(), 11u);
}

TEST(PathSeedPlanner, MaxSeedsBoundsALearningLibrary)
{
    ompl::RNG::setSeed(3);
    auto space = std::make_shared<ob::RealVectorStateSpace>(2);
    space->setBounds(0., 1.);
    og::SimpleSetup setup(space);
    setup.setStateValidityChecker(
        [](const ob::State *)
        {
            return true;
        });
    const auto si = setup.getSpaceInformation();
    auto planner = std::make_shared<PathSeed>(si);
    ASSERT_TRUE(planner->params().setParam("max_seeds", "2"));
    EXPECT_EQ(planner->getMaxSeeds(), 2u);
    for (int i = 0; i < 5; ++i)
        planner->addExperience(makePath(si, {{0.1, 0.1}, {0.1 * i, 0.8}, {0.9, 0.9}}));
    EXPECT_EQ(planner->experienceCount(), 2u);
    // a library loaded later keeps the bound too
    auto big = std::make_shared<PathSeedLibrary>();
    for (int i = 0; i < 4; ++i)
        big->add({Eigen::Vector2d(0.1, 0.1), Eigen::Vector2d(0.1 * i, 0.5), Eigen::Vector2d(0.9, 0.9)});
    planner->setLibrary(big);
    EXPECT_EQ(planner->experienceCount(), 2u);
}
