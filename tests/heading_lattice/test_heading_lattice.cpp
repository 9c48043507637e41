// michi::planners::HeadingLattice (paper 003) on problems/se2_corridor.yaml: it finds the path that turns in place
// at the corner, the same path every time, keeps its graph across queries and rebuilds it when the scene changes;
// a disk of the robot's circumradius cannot pass the same corridor; on the grid checker its direct node checks answer
// as the space information does.
#include <michi/planners/heading_lattice/HeadingLattice.h>
#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/tools/bench/PathCertificate.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>
#include <michi/validity/grid/GridValidityChecker.h>

#include <ompl/base/PlannerData.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <iostream>

namespace og = ompl::geometric;
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
    // the paper's path: the lattice path after its correction, not shortened further
    auto paperPlanner = [](michi::tools::PlanningContext &c)
    {
        auto planner = std::make_shared<HeadingLattice>(c.setup->getSpaceInformation());
        planner->setShortcut(false);
        return planner;
    };
    const auto first = solvePath(ctx, paperPlanner(ctx));
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
    EXPECT_EQ(solvePath(ctx2, paperPlanner(ctx2)), first);
    ctx2.setup->clear();
    EXPECT_EQ(solvePath(ctx2, ctx2.setup->getPlanner()), first);
}

namespace
{
    /** Length of a path of state values in the context's space. */
    double pathLength(michi::tools::PlanningContext &ctx, const std::vector<std::vector<double>> &path)
    {
        const auto space = ctx.setup->getStateSpace();
        ob::ScopedState<> a(space), b(space);
        double length = 0.;
        for (std::size_t i = 0; i + 1 < path.size(); ++i)
        {
            a = path[i];
            b = path[i + 1];
            length += space->distance(a.get(), b.get());
        }
        return length;
    }

    /** The path with and without the shortcut: the shortcut's is valid (solvePath checks every motion), no longer
        (shorter when \e strictly), has fewer states, starts and ends where the other does, and is the same on a
        second solve. */
    void expectShortcutShortens(const std::string &file, bool strictly, std::vector<std::vector<double>> &lattice,
                                std::vector<std::vector<double>> &shortened)
    {
        const auto problem = michi::tools::loadProblem(file);
        auto ctx = michi::tools::makePlanningContext(problem);
        auto plain = std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation());
        plain->setShortcut(false);
        lattice = solvePath(ctx, plain);
        auto ctx2 = michi::tools::makePlanningContext(problem);
        auto shortcut = std::make_shared<HeadingLattice>(ctx2.setup->getSpaceInformation());
        EXPECT_TRUE(shortcut->getShortcut());  // the default
        shortened = solvePath(ctx2, shortcut);
        ASSERT_GE(lattice.size(), 2u);
        ASSERT_GE(shortened.size(), 2u);
        EXPECT_EQ(shortened.front(), lattice.front());
        EXPECT_EQ(shortened.back(), lattice.back());
        EXPECT_LT(shortened.size(), lattice.size());
        EXPECT_LE(pathLength(ctx2, shortened), pathLength(ctx, lattice) + 1e-9);
        if (strictly)
            EXPECT_LT(pathLength(ctx2, shortened), pathLength(ctx, lattice) - 1e-6)
                << file << ": the lattice's zig-zags are gone";
        EXPECT_GT(shortcut->work().shortcutChecks, 0u);
        EXPECT_EQ(plain->work().shortcutChecks, 0u);
        ctx2.setup->clear();
        EXPECT_EQ(solvePath(ctx2, ctx2.setup->getPlanner()), shortened);
    }
}  // namespace

TEST(HeadingLattice, ShortcutShortensTheTurnMoveTurnPath)
{
    // the corridor's lattice path is straight drives and one turn already: the same length in 3 states
    std::vector<std::vector<double>> lattice, path;
    expectShortcutShortens(CORRIDOR, false, lattice, path);
}

TEST(HeadingLattice, ShortcutInAPlainSe2SpaceOnlyTurnsInPlaceAndDrivesAlongTheHeading)
{
    // movingai_arena plans in OMPL's plain SE2StateSpace, whose motions would turn while driving: the shortcut must
    // keep the lattice's moves (a turn on the spot, or a drive along the heading or against it)
    std::vector<std::vector<double>> lattice, path;
    expectShortcutShortens(std::string(MICHI_SOURCE_DIR) + "/problems/movingai_arena.yaml", true, lattice, path);
    std::size_t made = 0;
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
    {
        bool own = false;  // a motion of the lattice path itself (the joins of start and goal are straight SE(2))
        for (std::size_t k = 0; k + 1 < lattice.size() && !own; ++k)
            own = lattice[k] == path[i] && lattice[k + 1] == path[i + 1];
        if (own)
            continue;
        ++made;
        const double dx = path[i + 1][0] - path[i][0], dy = path[i + 1][1] - path[i][1];
        const double turned = std::abs(std::remainder(path[i + 1][2] - path[i][2], 2. * M_PI));
        if (std::hypot(dx, dy) < 1e-9)
            continue;  // a turn on the spot
        EXPECT_LT(turned, 1e-9) << "motion " << i << " turns while it drives";
        // sideways: the drive's direction against the heading
        const double across = std::abs(std::sin(std::atan2(dy, dx) - path[i][2]));
        EXPECT_LT(across, 1e-6) << "motion " << i << " does not drive along its heading";
    }
    EXPECT_GT(made, 0u);
}

TEST(HeadingLattice, CrossesOneCellDoorsOnTheGridChecker)
{
    // 64room's doors are one 0.1 m cell: the grid checker's table (0.025 m cells, 16 heading bins) closes them for
    // the 0.06 m x 0.04 m robot, its exact test of the pose (HeadingTable::freePose) opens them again. The lattice
    // (nodes on the cell centres) finds query 0's path through them, FCL finds no collision along it, and weighted
    // A* returns a path at most heuristic_weight times plain A*'s.
    const auto problem = michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/movingai_64room.yaml");
    michi::tools::ContextOptions options;
    options.checker = "grid";
    std::vector<double> lengths;
    for (double weight : {1., 1.2})
    {
        auto ctx = michi::tools::makePlanningContext(problem, options);
        ASSERT_TRUE(ctx.grid);
        auto planner = std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation());
        planner->params().setParam("cell_size", "0.05");
        planner->params().setParam("heuristic_weight", std::to_string(weight));
        EXPECT_DOUBLE_EQ(planner->getHeuristicWeight(), weight);
        const auto path = solvePath(ctx, planner, 60.);
        ASSERT_GE(path.size(), 3u);
        const auto certificate = michi::tools::certifyPath(ctx.setup->getSolutionPath(), *ctx.checker);
        EXPECT_TRUE(certificate.certified) << certificate.reason;
        lengths.push_back(ctx.setup->getSolutionPath().length());
    }
    EXPECT_LE(lengths[1], 1.2 * lengths[0] + 1e-9);
    EXPECT_GT(lengths[0], 15.);  // the scenario's grid path is 16-20 m
}

TEST(HeadingLattice, AutomaticCellSizeFollowsTheMapsCells)
{
    // cell_size 0 (the default): half a map cell on a map scene, not below the robot's reach, at most 0.25 m; the
    // setting reads back as 0 and the spacing used as effectiveCellSize(), once solve() has built the lattice.
    const auto spacing = [](const std::string &file, const std::string &checker)
    {
        const auto problem = michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/" + file);
        michi::tools::ContextOptions options;
        options.checker = checker;
        auto ctx = michi::tools::makePlanningContext(problem, options);
        auto planner = std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation());
        EXPECT_EQ(planner->getCellSize(), 0.);
        ctx.setup->setPlanner(planner);
        ctx.setup->solve(ob::timedPlannerTerminationCondition(0.));  // builds the lattice, then stops
        EXPECT_EQ(planner->getCellSize(), 0.);
        return planner->effectiveCellSize();
    };
    // 64room: 0.1 m cells, a 0.036 m reach: 0.05 m, on either checker (the scene carries the map's cell)
    EXPECT_DOUBLE_EQ(spacing("movingai_64room.yaml", "grid"), 0.05);
    EXPECT_DOUBLE_EQ(spacing("movingai_64room.yaml", "fcl"), 0.05);
    // ros_office (0.05 m cells, a 0.36 m reach) and se2_rooms (0.05 m, 0.825 m): robots larger than the cap, 0.25 m;
    // se2_corridor: polygons, no map: 0.25 m
    EXPECT_DOUBLE_EQ(spacing("ros_office.yaml", "fcl"), 0.25);
    EXPECT_DOUBLE_EQ(spacing("se2_rooms.yaml", "grid"), 0.25);
    EXPECT_DOUBLE_EQ(spacing("se2_corridor.yaml", "fcl"), 0.25);

    const auto problem = michi::tools::loadProblem(CORRIDOR);
    auto ctx = michi::tools::makePlanningContext(problem);
    HeadingLattice planner(ctx.setup->getSpaceInformation());
    EXPECT_THROW(planner.setCellSize(-0.1), ompl::Exception);
    planner.params().setParam("cell_size", "0.1");
    EXPECT_DOUBLE_EQ(planner.getCellSize(), 0.1);
    EXPECT_DOUBLE_EQ(planner.effectiveCellSize(), 0.1);
}

TEST(HeadingLattice, DefaultsCrossAMapsOneCellDoors)
{
    // With every setting at its default but the weight, the lattice finds 64room's query 0 through its one-cell
    // doors (with the paper's 0.25 m most doors fall between two rows of nodes); FCL finds no collision on the path.
    const auto problem = michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/movingai_64room.yaml");
    michi::tools::ContextOptions options;
    options.checker = "grid";
    auto ctx = michi::tools::makePlanningContext(problem, options);
    auto planner = std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation());
    planner->params().setParam("heuristic_weight", "1.2");
    const auto path = solvePath(ctx, planner, 60.);
    ASSERT_GE(path.size(), 3u);
    const auto certificate = michi::tools::certifyPath(ctx.setup->getSolutionPath(), *ctx.checker);
    EXPECT_TRUE(certificate.certified) << certificate.reason;
}

TEST(HeadingLattice, KeepsTheGraphAcrossQueriesAndRebuildsWhenTheSceneChanges)
{
    const auto problem = michi::tools::loadProblem(CORRIDOR);
    auto ctx = michi::tools::makePlanningContext(problem);
    auto planner = std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation());
    ASSERT_FALSE(solvePath(ctx, planner).empty());
    EXPECT_EQ(planner->buildCount(), 1u);

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
    const std::size_t nodes = planner->nodes().size();
    EXPECT_GT(nodes, 0u);
    EXPECT_EQ(data.numVertices(), nodes + 2);
    EXPECT_EQ(data.numStartVertices(), 1u);
    EXPECT_EQ(data.numGoalVertices(), 1u);
    EXPECT_GT(data.numEdges(), nodes);

    // an obstacle in the room at the corner: the lattice is updated (not built again) and no path turns there
    // any more
    problem.scene->add(michi::validity::Obstacle{
        "block",
        michi::validity::Shape::prism({{7.3, 1.8}, {7.7, 1.8}, {7.7, 2.2}, {7.3, 2.2}}, 0., 1.),
        Eigen::Isometry3d::Identity(),
        {}});
    ctx.setup->getProblemDefinition()->clearSolutionPaths();
    EXPECT_NE(ctx.setup->solve(5.), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(planner->buildCount(), 1u);
    EXPECT_EQ(planner->updateCount(), 1u);
    EXPECT_GT(planner->lastUpdate().nodesReset, 0u);
    // no node kept as free where the footprint would overlap the block
    for (const auto &n : planner->nodes())
        EXPECT_FALSE(n.x > 7.3 && n.x < 7.7 && n.y > 1.8 && n.y < 2.2) << n.x << " " << n.y;
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

namespace
{
    /** A door over the first wall (x or y = 5, 10 or 15 on se2_rooms) that \e path crosses: a box 2 m along the
        wall and 0.3 m across it, and a test of whether a point lies in it. */
    struct Door
    {
        bool vertical{false};
        double wall{0.}, along{0.};
        static constexpr double halfAcross = 0.15, halfAlong = 1.0;
        bool contains(double x, double y) const
        {
            return vertical ? std::abs(x - wall) < halfAcross && std::abs(y - along) < halfAlong
                            : std::abs(y - wall) < halfAcross && std::abs(x - along) < halfAlong;
        }
        michi::validity::Obstacle obstacle() const
        {
            std::vector<Eigen::Vector2d> box;
            for (const auto &corner :
                 {std::make_pair(-1., -1.), std::make_pair(1., -1.), std::make_pair(1., 1.), std::make_pair(-1., 1.)})
            {
                const double across = corner.first * halfAcross, length = corner.second * halfAlong;
                box.emplace_back(vertical ? wall + across : along + length, vertical ? along + length : wall + across);
            }
            return michi::validity::Obstacle{
                "door", michi::validity::Shape::prism(box, 0., 1.), Eigen::Isometry3d::Identity(), {}};
        }
    };

    Door firstDoor(og::PathGeometric path)
    {
        path.interpolate(2000);
        Door door;
        for (std::size_t i = 0; i + 1 < path.getStateCount() && door.wall == 0.; ++i)
        {
            const auto *a = path.getState(i)->as<ob::SE2StateSpace::StateType>();
            const auto *b = path.getState(i + 1)->as<ob::SE2StateSpace::StateType>();
            for (double w : {5., 10., 15.})
            {
                if ((a->getX() - w) * (b->getX() - w) <= 0. && a->getX() != b->getX())
                {
                    door = Door{true, w, a->getY()};
                    break;
                }
                if ((a->getY() - w) * (b->getY() - w) <= 0. && a->getY() != b->getY())
                {
                    door = Door{false, w, a->getX()};
                    break;
                }
            }
        }
        return door;
    }

    /** Does no state of \e path, interpolated finely, lie in \e door? */
    bool avoids(og::PathGeometric path, const Door &door)
    {
        path.interpolate(4000);
        for (std::size_t i = 0; i < path.getStateCount(); ++i)
        {
            const auto *s = path.getState(i)->as<ob::SE2StateSpace::StateType>();
            if (door.contains(s->getX(), s->getY()))
                return false;
        }
        return true;
    }
}  // namespace

TEST(HeadingLattice, ClosedDoorUpdatesOnlyTheLatticeAroundIt)
{
    // se2_rooms (400 x 400 cells of 0.05 m): solve query 0, close the first door the path goes through (a box over
    // the wall there, 2 m x 0.3 m: 240 cells, 0.15 % of the map), solve again
    const auto problem = michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/se2_rooms.yaml");
    auto ctx = michi::tools::makePlanningContext(problem);
    auto planner = std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation());
    ctx.setup->setPlanner(planner);
    ASSERT_EQ(ctx.setup->solve(60.), ob::PlannerStatus::EXACT_SOLUTION);
    const Door door = firstDoor(ctx.setup->getSolutionPath());
    ASSERT_NE(door.wall, 0.);
    const double halfAcross = Door::halfAcross, halfAlong = Door::halfAlong;
    const double cells = 4. * halfAcross * halfAlong / (0.05 * 0.05);
    EXPECT_LE(cells, 0.01 * 400 * 400);
    const auto before = planner->work();
    problem.scene->add(door.obstacle());
    ctx.setup->getProblemDefinition()->clearSolutionPaths();
    ASSERT_EQ(ctx.setup->solve(60.), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(planner->buildCount(), 1u);
    EXPECT_EQ(planner->updateCount(), 1u);
    const auto &update = planner->lastUpdate();
    const auto &after = planner->work();
    // the new path does not go through the closed door
    EXPECT_TRUE(ctx.setup->getSolutionPath().check());
    EXPECT_TRUE(avoids(ctx.setup->getSolutionPath(), door));

    // a rebuild: a fresh planner on the changed map, the same query
    auto fresh = std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation());
    ctx.setup->setPlanner(fresh);
    ctx.setup->getProblemDefinition()->clearSolutionPaths();
    ASSERT_EQ(ctx.setup->solve(60.), ob::PlannerStatus::EXACT_SOLUTION);
    const std::uint64_t rebuild = fresh->work().nodeChecks + fresh->work().edgeChecks;
    // the update: checks forgotten near the door and checked again
    const std::uint64_t forgotten = update.nodesReset + update.edgesReset;
    const std::uint64_t rechecked =
        (after.nodeRechecks - before.nodeRechecks) + (after.edgeRechecks - before.edgeRechecks);
    RecordProperty("forgotten", std::to_string(forgotten));
    RecordProperty("known", std::to_string(update.nodesKnown + update.edgesKnown));
    RecordProperty("rechecked", std::to_string(rechecked));
    RecordProperty("rebuild_checks", std::to_string(rebuild));
    std::cout << "closed door: " << forgotten << " of " << update.nodesKnown + update.edgesKnown
              << " checked nodes and edges forgotten, " << rechecked << " checked again; a rebuild checks " << rebuild
              << std::endl;
    EXPECT_GT(forgotten, 0u);
    EXPECT_LT(forgotten, update.nodesKnown + update.edgesKnown);
    // the update costs at least 10x less than a rebuild: it forgets, and checks again, a tenth of what a rebuild
    // checks (measured: 3766 forgotten, 2782 checked again, 50491 for a rebuild; since the heuristic's 2-D search
    // is directed at the start, the lattice knows fewer checks before the door closes: 33201)
    EXPECT_LE(10 * forgotten, rebuild);
    EXPECT_LE(10 * rechecked, rebuild);
}

TEST(HeadingLattice, TakesInAGridCheckersRefreshBothWays)
{
    // The grid checker answers from its table until refresh() rasterises a changed scene again. The lattice kept its
    // checks across that: a door that opened stayed closed for it (ABORT at once, where a fresh planner found the
    // path), and nodes inside a door that closed stayed in its planner data as valid.
    auto problem = michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/se2_rooms.yaml");
    problem.checker = "grid";
    auto ctx = michi::tools::makePlanningContext(problem);
    auto *grid = dynamic_cast<michi::validity::GridValidityChecker *>(
        ctx.setup->getSpaceInformation()->getStateValidityChecker().get());
    ASSERT_NE(grid, nullptr);
    auto planner = std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation());
    ctx.setup->setPlanner(planner);
    ASSERT_EQ(ctx.setup->solve(60.), ob::PlannerStatus::EXACT_SOLUTION);
    const double open = ctx.setup->getSolutionPath().length();
    const Door door = firstDoor(ctx.setup->getSolutionPath());
    ASSERT_NE(door.wall, 0.);

    // the door closes
    problem.scene->add(door.obstacle());
    ASSERT_FALSE(grid->refresh().empty());
    ctx.setup->getProblemDefinition()->clearSolutionPaths();
    ASSERT_EQ(ctx.setup->solve(60.), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(planner->buildCount(), 1u);
    EXPECT_EQ(planner->updateCount(), 1u);
    EXPECT_TRUE(avoids(ctx.setup->getSolutionPath(), door));
    const double closed = ctx.setup->getSolutionPath().length();
    EXPECT_GT(closed, open);
    // no node the planner data lists lies in the door
    ob::PlannerData data(ctx.setup->getSpaceInformation());
    planner->getPlannerData(data);
    for (unsigned int v = 0; v < data.numVertices(); ++v)
    {
        const auto *s = data.getVertex(v).getState()->as<ob::SE2StateSpace::StateType>();
        EXPECT_FALSE(door.contains(s->getX(), s->getY()) && grid->isValid(s)) << s->getX() << " " << s->getY();
    }

    // the door opens again: the short way is back
    problem.scene->remove("door");
    ASSERT_FALSE(grid->refresh().empty());
    ctx.setup->getProblemDefinition()->clearSolutionPaths();
    ASSERT_EQ(ctx.setup->solve(60.), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(planner->buildCount(), 1u);
    EXPECT_EQ(planner->updateCount(), 2u);
    EXPECT_NEAR(ctx.setup->getSolutionPath().length(), open, 1e-9);
}

TEST(HeadingLattice, GridNodeChecksAnswerAsTheSpaceInformation)
{
    // On michi's grid checker a node check asks the checker about the node's pose directly (no OMPL state); behind
    // a checker that only forwards isValid() the lattice takes the generic way. Both must see the same free and
    // blocked nodes: the same path, node checks and expansions on 64room's query 0.
    struct Forwarding : ob::StateValidityChecker
    {
        Forwarding(const ob::SpaceInformationPtr &si, ob::StateValidityCheckerPtr inner)
            : ob::StateValidityChecker(si), inner_(std::move(inner))
        {
        }
        bool isValid(const ob::State *state) const override
        {
            return inner_->isValid(state);
        }
        ob::StateValidityCheckerPtr inner_;
    };
    const auto problem = michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/movingai_64room.yaml");
    michi::tools::ContextOptions options;
    options.checker = "grid";
    std::vector<std::vector<double>> paths[2];
    HeadingLattice::WorkCounters work[2];
    for (int forwarded = 0; forwarded < 2; ++forwarded)
    {
        auto ctx = michi::tools::makePlanningContext(problem, options);
        ASSERT_TRUE(ctx.grid);
        const auto si = ctx.setup->getSpaceInformation();
        if (forwarded == 1)
            si->setStateValidityChecker(std::make_shared<Forwarding>(si, ctx.grid));
        auto planner = std::make_shared<HeadingLattice>(si);
        planner->params().setParam("cell_size", "0.05");
        planner->params().setParam("heuristic_weight", "1.2");
        paths[forwarded] = solvePath(ctx, planner, 60.);
        work[forwarded] = planner->work();
    }
    ASSERT_FALSE(paths[0].empty());
    EXPECT_EQ(paths[0], paths[1]);
    EXPECT_GT(work[0].nodeChecks, 1000u);
    EXPECT_EQ(work[0].nodeChecks, work[1].nodeChecks);
    EXPECT_EQ(work[0].expansions, work[1].expansions);
    EXPECT_EQ(work[0].edgeChecks, work[1].edgeChecks);
}

namespace
{
    /** Cost of the lattice search's own path (rawPath: start, lattice nodes, goal) as A* counts it: the joins and
        drives at the space's distance, a turn edge (the heading changes, the position may shift by part of a cell)
        at the cost of a pure turn by one heading step. */
    double latticePathCost(michi::tools::PlanningContext &ctx, const HeadingLattice &planner)
    {
        const auto space = ctx.setup->getStateSpace();
        const auto &raw = planner.rawPath();
        ob::ScopedState<> a(space), b(space);
        double cost = 0.;
        for (std::size_t i = 0; i + 1 < raw.size(); ++i)
        {
            a = raw[i];
            b = raw[i + 1];
            const bool turn =
                i > 0 && i + 2 < raw.size() && std::abs(std::remainder(raw[i + 1][2] - raw[i][2], 2. * M_PI)) > 1e-9;
            if (turn)
            {
                b = raw[i];
                b[2] = raw[i][2] + planner.getHeadingStep();
            }
            cost += space->distance(a.get(), b.get());
        }
        return cost;
    }
}  // namespace

TEST(HeadingLattice, TurnsLeftToTheGoalsHeadingKeepTheShortestLatticePath)
{
    // The heuristic counts the turning left to a goal's heading where a turn costs more than the shift of position
    // it allows (plain SE(2) spaces; large robots). It must stay a lower bound: plain A* (heuristic_weight 1) then
    // still returns the lattice's shortest path, whose cost is pinned here (measured with plain A* before the turn
    // term, commit e09103f), and needs fewer expansions than that search did (21,596 and 79).
    struct Case
    {
        std::string file;
        bool grid;
        double cost;
        unsigned int expansionsBefore;
    };
    const std::vector<Case> cases{{"movingai_arena.yaml", true, 7.12866500411, 21596},
                                  {"se2_corridor.yaml", false, 13.7953118343, 79}};
    for (const auto &c : cases)
    {
        const auto problem = michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/" + c.file);
        michi::tools::ContextOptions options;
        if (c.grid)
            options.checker = "grid";
        auto ctx = michi::tools::makePlanningContext(problem, options);
        auto planner = std::make_shared<HeadingLattice>(ctx.setup->getSpaceInformation());
        planner->setShortcut(false);
        ASSERT_EQ(planner->getHeuristicWeight(), 1.);
        solvePath(ctx, planner);
        const double cost = latticePathCost(ctx, *planner);
        std::cout << c.file << ": lattice path cost " << std::setprecision(12) << cost << ", "
                  << planner->work().expansions << " expansions" << std::endl;
        EXPECT_NEAR(cost, c.cost, 1e-9) << c.file;
        EXPECT_LT(planner->work().expansions, c.expansionsBefore) << c.file;
    }
}

TEST(HeadingLattice, AGoalInCollisionIsRefusedWithoutWaitingForTheTimeLimit)
{
    // Found 2026-12-07: with a goal state in collision the planner waited in OMPL's nextGoal(ptc) for the whole time
    // limit before answering "no valid goal" (an invalid start was refused at once). Counted, not timed: the
    // condition ends the wait after 2,000 evaluations, and the planner must not need more than a few.
    auto problem = michi::tools::loadProblem(CORRIDOR);
    auto ctx = michi::tools::makePlanningContext(problem);
    const auto si = ctx.setup->getSpaceInformation();
    ob::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
    si->getStateSpace()->copyFromReals(start.get(), problem.queries[0].start);
    si->getStateSpace()->copyFromReals(goal.get(), {5., 5., 0.});  // inside the walls
    ASSERT_TRUE(si->isValid(start.get()));
    ASSERT_FALSE(si->isValid(goal.get()));
    ctx.setup->setStartAndGoalStates(start, goal);
    auto planner = std::make_shared<michi::planners::HeadingLattice>(si);
    planner->setProblemDefinition(ctx.setup->getProblemDefinition());
    planner->setup();
    int asked = 0;
    const ob::PlannerTerminationCondition ptc(
        [&asked]
        {
            return ++asked > 2000;
        });
    EXPECT_EQ(planner->solve(ptc), ob::PlannerStatus::INVALID_GOAL);
    EXPECT_LT(asked, 50);
}
