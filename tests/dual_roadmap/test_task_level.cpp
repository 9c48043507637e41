// Tests of DualRoadmap's task level (paper 002's hierarchical roadmap for arms, setTaskLevel): the upper level's
// route over the hand's cells (TaskLevel), and its effect on a query. The query's space stands for a redundant arm:
// R^8 whose first three coordinates are the hand (Jacobian [I 0]) and whose last five must stay within 0.02 of 0.5
// (a posture the arm must keep: a uniform sample keeps it with a chance of 1e-7). A block stands in the hand's
// straight way. Samples along the hand's route, realised by Jacobian micro-motions from the query's ends, keep the
// posture, and the route goes round the cells where its states were found invalid; uniform samples alone do not
// find a way in the same budget (seeds 1-20 tried: both hold for each; with the route blind to the invalid cells the
// first test fails). Work is counted, never timed. Last, the hand michi installs for an arm (handTaskMap).
#include "support/CountedSolve.h"
#include "support/TestScenes.h"

#include <michi/planners/dual_roadmap/DualRoadmap.h>
#include <michi/planners/dual_roadmap/HandTaskMap.h>
#include <michi/validity/robot/RobotModel.h>

#include "../../planners/src/dual_roadmap/TaskLevel.h"

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

namespace ob = ompl::base;
using michi::planners::TaskLevel;

namespace
{
    /** The wall: x in [0.45, 0.55], except the opening y, z in [0.4, 0.55]. */
    bool inWall(const Eigen::Vector3d &p)
    {
        const bool opening = p.y() >= 0.4 && p.y() <= 0.55 && p.z() >= 0.4 && p.z() <= 0.55;
        return p.x() >= 0.45 && p.x() <= 0.55 && !opening;
    }

    /** The block in the hand's straight way of the query. */
    bool inBlock(const Eigen::Vector3d &p)
    {
        return p.x() >= 0.4 && p.x() <= 0.6 && p.y() >= 0.1 && p.y() <= 0.3 && p.z() >= 0.0 && p.z() <= 0.3;
    }

    struct RedundantArm
    {
        ob::SpaceInformationPtr si;
        std::shared_ptr<michi::planners::DualRoadmap> planner;
        ompl::geometric::PathGeometric path{nullptr};
        bool valid{false};

        explicit RedundantArm(bool taskLevel)
        {
            ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
            auto space = std::make_shared<ob::RealVectorStateSpace>(8);
            space->setBounds(0., 1.);
            si = std::make_shared<ob::SpaceInformation>(space);
            si->setStateValidityChecker(
                [](const ob::State *s)
                {
                    const double *x = s->as<ob::RealVectorStateSpace::StateType>()->values;
                    for (int i = 3; i < 8; ++i)
                        if (std::fabs(x[i] - 0.5) > 0.02)
                            return false;
                    return !inBlock(Eigen::Vector3d(x[0], x[1], x[2]));
                });
            si->setStateValidityCheckingResolution(0.002);
            si->setup();
            path = ompl::geometric::PathGeometric(si);
            planner = std::make_shared<michi::planners::DualRoadmap>(si);
            planner->setTaskLevel(taskLevel);
            planner->setTaskCell(0.05);
            planner->setTaskMap(
                [](const ob::State *s, Eigen::Vector3d &hand, Eigen::MatrixXd *jacobian)
                {
                    const double *x = s->as<ob::RealVectorStateSpace::StateType>()->values;
                    hand = Eigen::Vector3d(x[0], x[1], x[2]);
                    if (jacobian != nullptr)
                    {
                        *jacobian = Eigen::MatrixXd::Zero(3, 8);
                        jacobian->leftCols(3).setIdentity();
                    }
                });
        }

        ob::PlannerStatus solve(unsigned long evaluations)
        {
            ob::ScopedState<> start(si), goal(si);
            const double s[8] = {0.2, 0.2, 0.2, 0.5, 0.5, 0.5, 0.5, 0.5},
                         g[8] = {0.8, 0.2, 0.2, 0.5, 0.5, 0.5, 0.5, 0.5};
            for (unsigned int i = 0; i < 8; ++i)
            {
                start[i] = s[i];
                goal[i] = g[i];
            }
            auto result = michi::test::solveCounted(*planner, start, goal, evaluations);
            path = result.path;
            valid = result.valid;
            return result.status;
        }
    };
}  // namespace

TEST(TaskLevel, RouteIsStraightWithoutMarks)
{
    TaskLevel level;
    const Eigen::Vector3d from(0.1, 0.1, 0.1), to(0.9, 0.1, 0.1);
    level.begin(from, to, 0.05, 0.3);
    std::vector<Eigen::Vector3d> route;
    ASSERT_TRUE(level.route(10., route));
    ASSERT_GE(route.size(), 3u);
    EXPECT_TRUE(route.front().isApprox(from));
    EXPECT_TRUE(route.back().isApprox(to));
    double length = 0.;
    for (std::size_t i = 1; i < route.size(); ++i)
        length += (route[i] - route[i - 1]).norm();
    EXPECT_LT(length, (to - from).norm() + 0.1);
}

TEST(TaskLevel, RouteGoesRoundCellsMarkedInvalidAndThroughTheirOpening)
{
    TaskLevel level;
    const Eigen::Vector3d from(0.2, 0.2, 0.2), to(0.8, 0.2, 0.2);
    level.begin(from, to, 0.05, 0.3);
    // the wall's cells marked invalid, as the lower level's states there would be; one valid mark does not free a
    // cell with two invalid ones
    for (double y = -0.1; y < 0.5; y += 0.025)
        for (double z = -0.1; z < 0.5; z += 0.025)
            for (double x = 0.45; x <= 0.55; x += 0.025)
            {
                const Eigen::Vector3d p(x, y, z);
                if (!inWall(p))
                    continue;
                level.mark(p, false);
                level.mark(p, false);
                level.mark(p, true);
            }
    EXPECT_TRUE(level.blocked(Eigen::Vector3d(0.5, 0.2, 0.2)));
    EXPECT_FALSE(level.blocked(Eigen::Vector3d(0.5, 0.45, 0.45)));
    std::vector<Eigen::Vector3d> route;
    ASSERT_TRUE(level.route(10., route));
    for (const auto &p : route)
        EXPECT_FALSE(level.blocked(p)) << p.transpose();
    // with blocked cells as cheap as free ones the straight way is taken again
    ASSERT_TRUE(level.route(1., route));
    bool crosses = false;
    for (const auto &p : route)
        crosses = crosses || level.blocked(p);
    EXPECT_TRUE(crosses);
}

TEST(TaskLevel, MarksOutsideTheGridAndNaNsAreIgnored)
{
    TaskLevel level;
    level.begin(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 0.1, 0.);
    level.mark(Eigen::Vector3d(5., 5., 5.), false);
    level.mark(Eigen::Vector3d::Constant(std::nan("")), false);
    EXPECT_FALSE(level.blocked(Eigen::Vector3d(5., 5., 5.)));
    EXPECT_LE(level.cellCount(), 33u * 33u * 33u);
    // an end that is not finite (a hand the task map could not give): no grid, no route
    level.begin(Eigen::Vector3d::Constant(std::nan("")), Eigen::Vector3d::Ones(), 0.1, 0.3);
    std::vector<Eigen::Vector3d> route;
    EXPECT_FALSE(level.route(50., route));
    EXPECT_TRUE(route.empty());
}

TEST(TaskLevel, RoundMarksLastOneRoundAndCountWithTheKeptOnes)
{
    TaskLevel level;
    level.begin(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 0.1, 0.);
    const Eigen::Vector3d p(0.55, 0.55, 0.55);
    level.mark(p, false);
    EXPECT_TRUE(level.blocked(p));
    level.beginRound();
    level.markRound(p, true);
    EXPECT_FALSE(level.blocked(p)) << "one valid state of this round against one kept invalid mark";
    level.markRound(p, false);
    EXPECT_TRUE(level.blocked(p));
    level.beginRound();
    EXPECT_TRUE(level.blocked(p)) << "the kept mark stays";
    level.markRound(p, true);
    level.markRound(p, true);
    EXPECT_FALSE(level.blocked(p));
    level.begin(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 0.1, 0.);
    EXPECT_FALSE(level.blocked(p)) << "begin() forgets every mark";
}

TEST(DualRoadmapTaskLevel, TheHandsRouteGoesRoundABlockInItsWay)
{
    ompl::RNG::setSeed(7);
    RedundantArm arm(true);
    ASSERT_EQ(arm.solve(200000), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_TRUE(arm.valid);
    // the straight motion crosses the block: a valid path goes round it
    EXPECT_FALSE(arm.si->checkMotion(arm.path.getState(0), arm.path.getState(arm.path.getStateCount() - 1)));
    EXPECT_GT(arm.planner->lastWork().samples, 0u) << "the way needed new states";
}

TEST(DualRoadmapTaskLevel, UniformSamplesAloneDoNotFindAWay)
{
    // the ablation: the same query and budget without the task level
    ompl::RNG::setSeed(7);
    RedundantArm arm(false);
    EXPECT_NE(arm.solve(200000), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_GT(arm.planner->lastWork().samples, 1000u);
}

TEST(HandTaskMap, GivesTheArmsTipAndItsJacobian)
{
    namespace validity = michi::validity;
    const auto model = validity::RobotModel::fromUrdfFile(michi::test::sourcePath("problems/robots/iiwa7dof.urdf"));
    ASSERT_EQ(model->variableCount(), 7u);
    auto bodies = std::make_shared<validity::RobotGroupBodies>(model, std::vector<int>{0, 1, 2, 3, 4, 5, 6},
                                                               std::vector<double>(7, 0.));
    auto space = std::make_shared<ob::RealVectorStateSpace>(7);
    space->setBounds(-3., 3.);
    space->setup();
    const auto map = michi::planners::handTaskMap(bodies, space);
    ASSERT_TRUE(static_cast<bool>(map));
    ob::ScopedState<> state(space);
    const std::vector<double> q{0.3, -0.5, 0.8, -1.2, 0.4, 0.9, -0.2};
    for (unsigned int i = 0; i < 7; ++i)
        state[i] = q[i];
    Eigen::Vector3d hand;
    Eigen::MatrixXd jacobian;
    map(state.get(), hand, &jacobian);
    std::vector<Eigen::Isometry3d> poses;
    bodies->bodyPoses(q.data(), poses);
    EXPECT_LT((hand - poses.back().translation()).norm(), 1e-12) << "the last body's origin";
    ASSERT_EQ(jacobian.rows(), 3);
    ASSERT_EQ(jacobian.cols(), 7);
    // every column against central differences of the hand
    for (unsigned int j = 0; j < 7; ++j)
    {
        const double h = 1e-6;
        Eigen::Vector3d plus, minus;
        state[j] = q[j] + h;
        map(state.get(), plus, nullptr);
        state[j] = q[j] - h;
        map(state.get(), minus, nullptr);
        state[j] = q[j];
        EXPECT_LT((jacobian.col(j) - (plus - minus) / (2. * h)).norm(), 1e-6) << "joint " << j;
    }
    // a robot without a hand (SE(2)): no task map
    auto planar = std::make_shared<validity::PlanarRigidBody>(
        std::vector<Eigen::Vector2d>{{-0.2, -0.1}, {0.2, -0.1}, {0.2, 0.1}, {-0.2, 0.1}}, 0., 0.3);
    EXPECT_FALSE(static_cast<bool>(michi::planners::handTaskMap(planar, space)));
}
