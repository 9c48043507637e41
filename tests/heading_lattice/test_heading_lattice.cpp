// michi::planners::HeadingLattice (paper 003) on problems/se2_corridor.yaml: it finds the path that turns in place
// at the corner, the same path every time, keeps its graph across queries and rebuilds it when the scene changes;
// a disk of the robot's circumradius cannot pass the same corridor.
#include <michi/planners/heading_lattice/HeadingLattice.h>
#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <ompl/base/PlannerData.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>

namespace ob = ompl::base;
using michi::planners::HeadingLattice;

namespace
{
    const std::string CORRIDOR = std::string(MICHI_SOURCE_DIR) + "/problems/se2_corridor.yaml";

    std::vector<std::vector<double>> solvePath(michi::tools::PlanningContext &ctx, const ob::PlannerPtr &planner,
                                               double time = 20.)
    {
        ctx.setup->setPlanner(planner);
        const auto status = ctx.setup->solve(time);
        EXPECT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION);
        std::vector<std::vector<double>> values;
        if (status != ob::PlannerStatus::EXACT_SOLUTION)
            return values;
        auto &path = ctx.setup->getSolutionPath();
        EXPECT_TRUE(path.check());
        for (std::size_t i = 0; i < path.getStateCount(); ++i)
        {
            std::vector<double> v;
            ctx.setup->getStateSpace()->copyToReals(v, path.getState(i));
            values.push_back(v);
        }
        return values;
    }
}  // namespace

TEST(HeadingLattice, CorridorUsesTurnMoveTurnSpace)
{
    const auto problem = michi::tools::loadProblem(CORRIDOR);
    EXPECT_EQ(problem.se2Motion.model, "turn_move_turn");
    auto ctx = michi::tools::makePlanningContext(problem);
    EXPECT_NE(std::dynamic_pointer_cast<michi::state_spaces::TurnMoveTurnStateSpace>(ctx.setup->getStateSpace()),
              nullptr);
}

TEST(HeadingLattice, SolvesTheCorridorTheSameWayEveryTime)
{
    const auto problem = michi::tools::loadProblem(CORRIDOR);
    auto ctx = michi::tools::makePlanningContext(problem);
    const auto first = solvePath(ctx, std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation()));
    ASSERT_GE(first.size(), 3u);
    // it turns in place at the corner: somewhere the position stays while the heading changes by 90 degrees
    bool turnsInRoom = false;
    for (std::size_t i = 0; i + 1 < first.size(); ++i)
        if (std::hypot(first[i][0] - first[i + 1][0], first[i][1] - first[i + 1][1]) < 1e-9 && first[i][0] > 6.55 &&
            first[i][1] < 2.95)
            turnsInRoom = true;
    EXPECT_TRUE(turnsInRoom);
    // a fresh planner, and the same planner after clear(), give the very same path
    ompl::RNG::setSeed(99);
    auto ctx2 = michi::tools::makePlanningContext(problem);
    EXPECT_EQ(solvePath(ctx2, std::make_shared<HeadingLattice>(ctx2.setup->getSpaceInformation())), first);
    ctx2.setup->clear();
    EXPECT_EQ(solvePath(ctx2, ctx2.setup->getPlanner()), first);
}

TEST(HeadingLattice, KeepsTheGraphAcrossQueriesAndRebuildsWhenTheSceneChanges)
{
    const auto problem = michi::tools::loadProblem(CORRIDOR);
    auto ctx = michi::tools::makePlanningContext(problem);
    auto planner = std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation());
    ASSERT_FALSE(solvePath(ctx, planner).empty());
    EXPECT_EQ(planner->buildCount(), 1u);
    const std::size_t nodes = planner->nodes().size();

    // a new query off the lattice nodes (start between nodes, odd heading), same map: the graph is reused
    ob::ScopedState<ob::SE2StateSpace> start(ctx.setup->getStateSpace()), goal(ctx.setup->getStateSpace());
    start->setXY(2.13, 1.97);
    start->setYaw(0.05);
    goal->setXY(7.52, 7.3);
    goal->setYaw(-M_PI / 2);
    ctx.setup->setStartAndGoalStates(start, goal);
    const auto second = solvePath(ctx, planner);
    ASSERT_FALSE(second.empty());
    EXPECT_EQ(planner->buildCount(), 1u);
    EXPECT_EQ(planner->lastBuildTime(), 0.);
    EXPECT_NEAR(second.front()[0], 2.13, 1e-12);
    EXPECT_NEAR(second.back()[1], 7.3, 1e-12);

    // PlannerData holds every node and the query states
    ob::PlannerData data(ctx.setup->getSpaceInformation());
    planner->getPlannerData(data);
    EXPECT_EQ(data.numVertices(), nodes + 2);
    EXPECT_EQ(data.numStartVertices(), 1u);
    EXPECT_EQ(data.numGoalVertices(), 1u);
    EXPECT_GT(data.numEdges(), nodes);

    // an obstacle in the room at the corner: the lattice is built again and no path turns there any more
    problem.scene->add(michi::validity::Obstacle{
        "block",
        michi::validity::Shape::prism({{7.3, 1.8}, {7.7, 1.8}, {7.7, 2.2}, {7.3, 2.2}}, 0., 1.),
        Eigen::Isometry3d::Identity(),
        {}});
    ctx.setup->getProblemDefinition()->clearSolutionPaths();
    EXPECT_NE(ctx.setup->solve(5.), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(planner->buildCount(), 2u);
    EXPECT_LT(planner->nodes().size(), nodes);
}

TEST(HeadingLattice, DiskOfTheCircumradiusCannotPass)
{
    // the same walls, the robot replaced by a disk of the rectangle's circumradius (a 64-gon around it)
    auto problem = michi::tools::loadProblem(CORRIDOR);
    const double r = michi::validity::PlanarRigidBody(problem.footprint).circumradius();
    EXPECT_NEAR(r, std::hypot(0.8, 0.2), 1e-12);
    std::vector<Eigen::Vector2d> disk;
    for (int i = 0; i < 64; ++i)
        disk.emplace_back(r / std::cos(M_PI / 64) * std::cos(2 * M_PI * i / 64),
                          r / std::cos(M_PI / 64) * std::sin(2 * M_PI * i / 64));
    problem.footprint = disk;
    // start and goal collide: a planner for the disk cannot even begin
    EXPECT_THROW(michi::tools::makePlanningContext(problem), michi::tools::ProblemError);
    // and no position along either corridor is free for it, so no path exists for the disk at all
    auto body = problem.bodies();
    michi::validity::FclValidityChecker checker(
        std::make_shared<ob::SpaceInformation>(michi::tools::makeStateSpace(problem)), body, problem.scene);
    int free = 0, tried = 0;
    for (double x = 0.5; x <= 6.55; x += 0.05)
        for (double y = 1.6; y <= 2.4; y += 0.05, ++tried)
            free += checker.isValidConfiguration(std::vector<double>{x, y, 0.}.data()) ? 1 : 0;
    for (double y = 2.95; y <= 9.5; y += 0.05)
        for (double x = 7.1; x <= 7.9; x += 0.05, ++tried)
            free += checker.isValidConfiguration(std::vector<double>{x, y, 0.}.data()) ? 1 : 0;
    EXPECT_GT(tried, 500);
    EXPECT_EQ(free, 0);
}

TEST(HeadingLattice, ForwardOnlyPathsDriveForwards)
{
    auto problem = michi::tools::loadProblem(CORRIDOR);
    problem.se2Motion.backward = false;
    auto ctx = michi::tools::makePlanningContext(problem);
    auto space = std::dynamic_pointer_cast<michi::state_spaces::TurnMoveTurnStateSpace>(ctx.setup->getStateSpace());
    ASSERT_NE(space, nullptr);
    ASSERT_FALSE(space->getAllowBackward());
    const auto path = solvePath(ctx, std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation()));
    ASSERT_GE(path.size(), 2u);
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
        EXPECT_FALSE(
            space->motion(path[i][0], path[i][1], path[i][2], path[i + 1][0], path[i + 1][1], path[i + 1][2]).backward);
}

TEST(HeadingLattice, RefusesSpacesThatAreNotSe2)
{
    auto space = std::make_shared<ob::RealVectorStateSpace>(2);
    space->setBounds(0., 1.);
    ompl::geometric::SimpleSetup ss(space);
    ss.setStateValidityChecker(
        [](const ob::State *)
        {
            return true;
        });
    ob::ScopedState<> start(space), goal(space);
    start = std::vector<double>{0.1, 0.1};
    goal = std::vector<double>{0.9, 0.9};
    ss.setStartAndGoalStates(start, goal);
    ss.setPlanner(std::make_shared<HeadingLattice>(ss.getSpaceInformation()));
    EXPECT_EQ(ss.solve(1.), ob::PlannerStatus::ABORT);
}
