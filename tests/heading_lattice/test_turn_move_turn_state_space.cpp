// TurnMoveTurnStateSpace: distance and interpolation of turn-in-place / drive-straight motions, OMPL's sanity
// checks, and OMPL's stock planners planning in it.
#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/tools/bench/PlannerRegistry.h>

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>

namespace ob = ompl::base;
using michi::state_spaces::makeTurnMoveTurnStateSpace;
using michi::state_spaces::TurnMoveTurnStateSpace;

namespace
{
    const double PI = M_PI;

    ob::ScopedState<ob::SE2StateSpace> pose(const ob::StateSpacePtr &space, double x, double y, double yaw)
    {
        ob::ScopedState<ob::SE2StateSpace> s(space);
        s->setXY(x, y);
        s->setYaw(yaw);
        return s;
    }
}  // namespace

TEST(TurnMoveTurnStateSpace, DistanceIsTurnsTimesWeightPlusDrive)
{
    auto space = makeTurnMoveTurnStateSpace(-10, 10, -10, 10, 0.5, false);
    // facing the target already: only the drive
    EXPECT_NEAR(space->distance(pose(space, 0, 0, 0).get(), pose(space, 3, 0, 0).get()), 3., 1e-12);
    // turn by 90 degrees to face (0, 2), drive 2, turn back by 90 degrees
    EXPECT_NEAR(space->distance(pose(space, 0, 0, 0).get(), pose(space, 0, 2, 0).get()), 2. + 0.5 * PI, 1e-12);
    // same position: one turn by the shorter way
    EXPECT_NEAR(space->distance(pose(space, 1, 1, 0.2).get(), pose(space, 1, 1, -0.3).get()), 0.5 * 0.5, 1e-12);
    // forward only: a target behind needs a half turn before and after
    EXPECT_NEAR(space->distance(pose(space, 0, 0, 0).get(), pose(space, -1, 0, 0).get()), 1. + 0.5 * 2 * PI, 1e-9);
    space->setAllowBackward(true);
    EXPECT_NEAR(space->distance(pose(space, 0, 0, 0).get(), pose(space, -1, 0, 0).get()), 1., 1e-12);
    auto m = space->motion(0, 0, 0, -1, 0, 0);
    EXPECT_TRUE(m.backward);
    EXPECT_NEAR(m.move, 1., 1e-12);
}

TEST(TurnMoveTurnStateSpace, InterpolationTurnsDrivesTurns)
{
    auto space = makeTurnMoveTurnStateSpace(-10, 10, -10, 10, 1., true);
    auto a = pose(space, 0, 0, 0), b = pose(space, 0, 2, 0);
    // distance pi/2 + 2 + pi/2: the first quarter-turn ends at t = (pi/2) / total
    const double total = PI + 2.;
    auto s = pose(space, 0, 0, 0);
    space->interpolate(a.get(), b.get(), 0.5 * (PI / 2.) / total, s.get());
    EXPECT_NEAR(s->getX(), 0., 1e-12);
    EXPECT_NEAR(s->getY(), 0., 1e-12);
    EXPECT_NEAR(std::abs(s->getYaw()), PI / 4., 1e-9);  // half of the first turn, in place
    space->interpolate(a.get(), b.get(), 0.5, s.get());
    EXPECT_NEAR(s->getX(), 0., 1e-12);
    EXPECT_NEAR(s->getY(), 1., 1e-9);  // half way along the drive, heading along it (or against it, reversing)
    EXPECT_NEAR(std::abs(std::cos(s->getYaw())), 0., 1e-9);
    space->interpolate(a.get(), b.get(), 1. - 0.5 * (PI / 2.) / total, s.get());
    EXPECT_NEAR(s->getY(), 2., 1e-12);
    EXPECT_NEAR(std::abs(s->getYaw()), PI / 4., 1e-9);  // half of the last turn
    // every interpolated state is t * distance from the start
    for (double t : {0.1, 0.3, 0.7, 0.95})
    {
        space->interpolate(a.get(), b.get(), t, s.get());
        EXPECT_NEAR(space->distance(a.get(), s.get()), t * total, 1e-9) << t;
        EXPECT_NEAR(space->distance(s.get(), b.get()), (1. - t) * total, 1e-9) << t;
    }
}

TEST(TurnMoveTurnStateSpace, DrivingTowardsMinusXStaysWithinTheYawBounds)
{
    // atan2 gives +pi for a drive towards -x, outside OMPL's SO2 bounds [-pi, pi): the drive's heading is -pi
    for (bool backward : {false, true})
    {
        auto space = makeTurnMoveTurnStateSpace(-10, 10, -10, 10, 0.5, backward);
        auto a = pose(space, 1, 0, PI / 2), b = pose(space, -1, 0, PI / 2), s = pose(space, 0, 0, 0);
        for (double t : {0.1, 0.25, 0.5, 0.75, 0.9})
        {
            space->interpolate(a.get(), b.get(), t, s.get());
            EXPECT_TRUE(space->satisfiesBounds(s.get())) << backward << " " << t << ": yaw " << s->getYaw();
        }
    }
}

TEST(TurnMoveTurnStateSpace, PassesOmplSanityChecks)
{
    ompl::RNG::setSeed(3);
    for (bool backward : {true, false})
        for (double weight : {0.2, 1., 3.})
        {
            auto space = makeTurnMoveTurnStateSpace(-2, 5, 0, 3, weight, backward);
            space->setup();
            EXPECT_NO_THROW(space->sanityChecks()) << "backward " << backward << " weight " << weight;
            EXPECT_FALSE(space->isMetricSpace());
            EXPECT_EQ(space->hasSymmetricDistance(), backward);
        }
}

TEST(TurnMoveTurnStateSpace, RejectsBadWeight)
{
    EXPECT_THROW(TurnMoveTurnStateSpace(0.), std::invalid_argument);
    EXPECT_THROW(TurnMoveTurnStateSpace(-1.), std::invalid_argument);
}

TEST(TurnMoveTurnStateSpace, StockPlannersSolveInIt)
{
    // a wall with a gap in a 4 x 4 square; the robot is a point here (the space, not the footprint, is tested)
    for (const char *name : {"geometric::RRTConnect", "geometric::PRM", "geometric::RRTstar", "geometric::BITstar"})
    {
        auto space = makeTurnMoveTurnStateSpace(0, 4, 0, 4, 0.5, true);
        ompl::geometric::SimpleSetup ss(space);
        ss.setStateValidityChecker(
            [](const ob::State *s)
            {
                const auto *p = s->as<ob::SE2StateSpace::StateType>();
                return !(p->getX() > 1.9 && p->getX() < 2.1 && p->getY() < 3.);
            });
        ss.getSpaceInformation()->setStateValidityCheckingResolution(0.002);
        ss.setStartAndGoalStates(pose(space, 1, 1, 0), pose(space, 3, 1, PI / 2));
        ss.setPlanner(michi::tools::allocatePlanner(name, ss.getSpaceInformation()));
        // the first solution is enough: optimising planners stop once the cost is below the (huge) threshold
        auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(ss.getSpaceInformation());
        objective->setCostThreshold(ob::Cost(1e9));
        ss.setOptimizationObjective(objective);
        ASSERT_TRUE(ss.solve(5.)) << name;
        ASSERT_TRUE(ss.haveExactSolutionPath()) << name;
        EXPECT_TRUE(ss.getSolutionPath().check()) << name;
        // a path over the wall's end at y = 3 is at least 2 * 2 long
        EXPECT_GT(ss.getSolutionPath().length(), 4.) << name;
    }
}
