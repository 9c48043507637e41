// robot.motion in problem files (turn_move_turn), and the footprint displacement bound the motion validators use
// for turn-move-turn motions (tools::TurnMoveTurnBodies).
#include "support/TestScenes.h"

#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>
#include <michi/tools/problem/TurnMoveTurnBodies.h>

#include <ompl/base/ScopedState.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>

namespace ob = ompl::base;
using michi::tools::ProblemError;

namespace
{
    std::string se2Problem(const std::string &motion)
    {
        return "robot:\n  type: se2\n  footprint: [[-0.5, -0.1], [0.5, -0.1], [0.5, 0.1], [-0.5, 0.1]]\n"
               "  bounds: {x: [0, 4], y: [0, 4]}\n" +
               motion + "start: [1, 1, 0]\ngoal: [3, 3, pi/2]\n";
    }

    std::string loadError(const std::string &yaml)
    {
        michi::test::TempDir dir("michi_tmt_problem");
        const std::string file = dir.write("p.yaml", yaml);
        try
        {
            michi::tools::loadProblem(file);
        }
        catch (const ProblemError &e)
        {
            return e.what();
        }
        return "";
    }
}  // namespace

TEST(TurnMoveTurnProblem, MotionKeySelectsTheSpace)
{
    michi::test::TempDir dir("michi_tmt_problem");
    auto free = michi::tools::loadProblem(dir.write("free.yaml", se2Problem("")));
    EXPECT_EQ(free.se2Motion.model, "free");
    EXPECT_EQ(
        std::dynamic_pointer_cast<michi::state_spaces::TurnMoveTurnStateSpace>(michi::tools::makeStateSpace(free)),
        nullptr);

    auto tmt = michi::tools::loadProblem(dir.write("tmt.yaml", se2Problem("  motion: turn_move_turn\n")));
    auto space =
        std::dynamic_pointer_cast<michi::state_spaces::TurnMoveTurnStateSpace>(michi::tools::makeStateSpace(tmt));
    ASSERT_NE(space, nullptr);
    EXPECT_NEAR(space->getTurnWeight(), std::hypot(0.5, 0.1), 1e-12);  // default: the circumradius
    EXPECT_TRUE(space->getAllowBackward());

    auto set = michi::tools::loadProblem(
        dir.write("set.yaml", se2Problem("  motion: {model: turn_move_turn, turn_weight: 0.3, backward: false}\n")));
    space = std::dynamic_pointer_cast<michi::state_spaces::TurnMoveTurnStateSpace>(michi::tools::makeStateSpace(set));
    ASSERT_NE(space, nullptr);
    EXPECT_EQ(space->getTurnWeight(), 0.3);
    EXPECT_FALSE(space->getAllowBackward());
    // the planning context checks turn-move-turn motions with the matching bodies
    auto ctx = michi::tools::makePlanningContext(set);
    EXPECT_NE(std::dynamic_pointer_cast<const michi::tools::TurnMoveTurnBodies>(ctx.bodies), nullptr);
}

TEST(TurnMoveTurnProblem, BadMotionKeysNameFileAndKey)
{
    EXPECT_NE(loadError(se2Problem("  motion: sideways\n")).find("robot.motion: expected 'free' or 'turn_move_turn'"),
              std::string::npos);
    EXPECT_NE(loadError(se2Problem("  motion: {model: turn_move_turn, turn_weigth: 1}\n"))
                  .find("robot.motion.turn_weigth: unknown key"),
              std::string::npos);
    EXPECT_NE(
        loadError(se2Problem("  motion: {model: turn_move_turn, turn_weight: -1}\n")).find("robot.motion.turn_weight"),
        std::string::npos);
    EXPECT_NE(loadError(se2Problem("  motion: {model: turn_move_turn, backward: maybe}\n"))
                  .find("robot.motion.backward: expected true or false"),
              std::string::npos);
    EXPECT_NE(loadError(se2Problem("  motion: {turn_weight: 1}\n")).find("robot.motion.model: missing"),
              std::string::npos);
    EXPECT_EQ(loadError(se2Problem("  motion: {model: turn_move_turn}\n")), "");  // the settings are optional
}

TEST(TurnMoveTurnProblem, DisplacementBoundCoversEveryStepOfTheMotion)
{
    // a point of the footprint moves at most bound * dt between interpolated states t and t + dt
    const std::vector<Eigen::Vector2d> outline{{-0.8, -0.2}, {0.8, -0.2}, {0.8, 0.2}, {-0.8, 0.2}};
    auto body = std::make_shared<michi::validity::PlanarRigidBody>(outline);
    ompl::RNG rng(5);
    for (double weight : {0.2, 0.825, 2.})
        for (bool backward : {true, false})
        {
            auto space = michi::state_spaces::makeTurnMoveTurnStateSpace(0, 10, 0, 10, weight, backward);
            michi::tools::TurnMoveTurnBodies bodies(body, space);
            ob::ScopedState<ob::SE2StateSpace> a(space), b(space), s(space), prev(space);
            for (int trial = 0; trial < 50; ++trial)
            {
                a.random();
                b.random();
                const double from[3] = {a->getX(), a->getY(), a->getYaw()}, to[3] = {b->getX(), b->getY(), b->getYaw()};
                const double bound = bodies.displacementBound(from, to);
                const int n = 400;
                prev = a;
                for (int i = 1; i <= n; ++i)
                {
                    space->interpolate(a.get(), b.get(), static_cast<double>(i) / n, s.get());
                    double moved = 0.;
                    for (const auto &p : outline)
                    {
                        auto at = [&](const ob::ScopedState<ob::SE2StateSpace> &q)
                        {
                            const double c = std::cos(q->getYaw()), sn = std::sin(q->getYaw());
                            return Eigen::Vector2d(q->getX() + c * p.x() - sn * p.y(),
                                                   q->getY() + sn * p.x() + c * p.y());
                        };
                        moved = std::max(moved, (at(s) - at(prev)).norm());
                    }
                    // a chord is shorter than its arc: the straight-line movement is below the bound's share
                    ASSERT_LE(moved, bound / n + 1e-9) << "weight " << weight << " trial " << trial << " step " << i;
                    prev = s;
                }
            }
        }
}
