// Tests of the grid-native SE(2) checker (validity/.../grid/, issue 14): against FCL on every bundled SE2 map problem
// (0 unsafe states and motions, FCL is the reference), the table's geometry on small grids, the motion validator's
// cell walk for SE(2) and turn-move-turn motions, local updates equal to a rebuild, the memory bound of a 512 x 512
// map, the problem-file and planning-context plumbing, and dataset selections.
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/commands/VerifyChecker.h>
#include <michi/tools/problem/Dataset.h>
#include <michi/validity/grid/GridMotionValidator.h>
#include <michi/validity/grid/HeadingTable.h>

#include <ompl/base/ScopedState.h>
#include <ompl/util/RandomNumbers.h>

#include <boost/filesystem.hpp>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>

#include <gtest/gtest.h>

#include <fstream>

using namespace michi;
namespace ob = ompl::base;

namespace
{
    std::string problemPath(const std::string &name)
    {
        return std::string(MICHI_SOURCE_DIR) + "/problems/" + name + ".yaml";
    }

    /** Every bundled problem whose robot is SE2 and whose scene is static. */
    std::vector<std::string> se2Problems()
    {
        std::vector<std::string> names;
        for (const auto &e : boost::filesystem::directory_iterator(std::string(MICHI_SOURCE_DIR) + "/problems"))
        {
            if (e.path().extension() != ".yaml")
                continue;
            const auto problem = tools::loadProblem(e.path().string());
            bool moving = false;
            for (const auto &o : problem.scene->obstacles())
                moving = moving || !o.trajectory.empty();
            if (problem.kind == tools::Problem::Kind::SE2 && !moving)
                names.push_back(e.path().stem().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }

    validity::OccupancyGrid emptyGrid(int w, int h, double r)
    {
        validity::OccupancyGrid g;
        g.width = w;
        g.height = h;
        g.resolution = r;
        g.cells.assign(static_cast<std::size_t>(w) * h, 0);
        return g;
    }

    const std::vector<Eigen::Vector2d> SQUARE{{-0.1, -0.1}, {0.1, -0.1}, {0.1, 0.1}, {-0.1, 0.1}};

    /** freeOnGrid() and freePose() agree at 20,000 uniform poses of [x0, x1] x [y0, y1], of which more than 1,000
        are refused and more than 1,000 free (so both answers were exercised). */
    void expectFreeOnGridAgrees(const validity::HeadingTable &table, ompl::RNG &rng, double x0, double x1, double y0,
                                double y1, const char *when)
    {
        int refused = 0;
        for (int n = 0; n < 20000; ++n)
        {
            const double x = rng.uniformReal(x0, x1), y = rng.uniformReal(y0, y1), yaw = rng.uniformReal(-M_PI, M_PI);
            const bool free = table.freePose(x, y, yaw);
            ASSERT_EQ(table.freeOnGrid(x, y, yaw), free) << when << ": " << x << " " << y << " " << yaw;
            refused += free ? 0 : 1;
        }
        EXPECT_GT(refused, 1000) << when;
        EXPECT_LT(refused, 19000) << when;
    }
}  // namespace

TEST(GridChecker, NeverValidWhereFclIsInvalidOnEveryBundledMapProblem)
{
    const auto names = se2Problems();
    ASSERT_GE(names.size(), 4u);  // movingai_arena, se2_corridor, se2_corridor_pgm, se2_rooms (and more)
    for (const auto &name : names)
    {
        tools::VerifyCheckerOptions options;
        options.checker = "grid";
        options.states = 20000;
        options.seed = 7;
        const auto r = tools::verifyChecker(tools::loadProblem(problemPath(name)), options);
        SCOPED_TRACE(name + ": " + r.json());
        EXPECT_EQ(r.unsafeStates, 0u);
        EXPECT_EQ(r.unsafeMotions, 0u);
        EXPECT_GT(r.referenceValid, 0u);
        EXPECT_GT(r.motionsValid, 0u);  // the motion check was exercised
        if (name.find("movingai") != std::string::npos || name.find("ros_") != std::string::npos)
        {
            // exact on a map's grid: where the table refuses, the pose itself is tested (and the table's "blocked
            // at every pose" entries are right), so no state FCL calls free is refused
            EXPECT_EQ(r.falseInvalidFraction(), 0.);
        }
    }
}

TEST(GridTable, OneOccupiedCellBlocksItsNeighbourhoodOnly)
{
    auto g = emptyGrid(40, 40, 0.1);
    g.cells[20 * 40 + 20] = 1;
    validity::HeadingTable table(g, SQUARE, 16);
    for (int k = 0; k < 16; ++k)
    {
        EXPECT_FALSE(table.valid(20, 20, k));
        EXPECT_FALSE(table.valid(21, 20, k));  // the square reaches 0.1 m plus half a cell: the neighbours
        EXPECT_FALSE(table.valid(19, 19, k));
        EXPECT_TRUE(table.valid(24, 20, k));  // 0.4 m away: beyond the circumradius (0.141) and a cell
        EXPECT_TRUE(table.valid(5, 5, k));
    }
    EXPECT_FALSE(table.valid(-1, 3, 0));  // outside the grid
    EXPECT_FALSE(table.valid(40, 3, 0));
    EXPECT_EQ(table.headingBin(0.), 0);
    EXPECT_EQ(table.headingBin(2 * M_PI), 0);
    EXPECT_EQ(table.headingBin(-M_PI / 16 + 1e-9), 0);
    EXPECT_EQ(table.headingBin(M_PI / 16 + 1e-9), 1);
    EXPECT_EQ(table.headingBin(-M_PI / 16 - 1e-9), 15);
}

TEST(GridTable, FreePoseIsExactWhereTheTableIsConservative)
{
    // a wall of 0.1 m map cells at y in [0.5, 0.6] with a one-cell door at x in [0.5, 0.6], in table cells of
    // 0.025 m; the 64room robot, 0.06 m x 0.04 m
    auto g = emptyGrid(40, 40, 0.025);
    for (int j = 20; j < 24; ++j)
        for (int i = 0; i < 40; ++i)
            if (i < 20 || i > 23)
                g.cells[j * 40 + i] = 1;
    const std::vector<Eigen::Vector2d> robot{{-0.03, -0.02}, {0.03, -0.02}, {0.03, 0.02}, {-0.03, 0.02}};
    validity::HeadingTable table(g, robot, 16);
    // the wall and the door are whole 4 x 4 blocks: the exact test reads a bit per block
    EXPECT_EQ(table.coarseFactor(), 4);
    // in the door along it: the entry is invalid (the footprint grown by the cell and swept over the heading bin
    // reaches the wall), the pose itself is free with 0.03 m either side
    EXPECT_FALSE(table.validPose(0.55, 0.55, M_PI / 2));
    EXPECT_TRUE(table.freePose(0.55, 0.55, M_PI / 2));
    EXPECT_TRUE(table.freePose(0.55, 0.55, 0.));                // across it: 0.06 m long in 0.1 m
    EXPECT_FALSE(table.freePose(0.585, 0.55, M_PI / 2));        // its side 5 mm into the wall
    EXPECT_FALSE(table.freePose(0.58, 0.55, M_PI / 2));         // touching counts, as for FCL
    EXPECT_TRUE(table.freePose(0.575, 0.55, M_PI / 2, 0.004));  // 5 mm from the wall
    EXPECT_FALSE(table.freePose(0.575, 0.55, M_PI / 2, 0.006));
    EXPECT_TRUE(table.freePose(0.55, 0.55, M_PI / 4));   // it can turn in the door's middle (circumradius 0.036)
    EXPECT_FALSE(table.freePose(0.52, 0.55, M_PI / 4));  // not beside its post
    EXPECT_FALSE(table.freePose(-1., 0.5, 0.));          // outside the grid
    EXPECT_FALSE(table.freePose(0.2, 0.2, std::nan("")));
    // marking cells changes it
    table.setOccupied({{22, 22}}, true);
    EXPECT_EQ(table.coarseFactor(), 1);  // one cell of a block: the table's own rows from now on
    EXPECT_FALSE(table.freePose(0.55, 0.55, M_PI / 2));
    EXPECT_TRUE(table.occupied(22, 22));
}

TEST(GridTable, ExactTestOnWholeMapCellsAgreesWithBoostGeometry)
{
    // Map cells of 4 x 4 table cells (the table's split of a map): the exact test reads one bit per map cell. Checked
    // at random poses and margins against the footprint grown by the margin (a square growth: each cell grown by it)
    // meeting an occupied table cell, by Boost.Geometry; then again after a map cell is occupied (still whole
    // blocks) and after a single table cell is (the table's own rows).
    namespace bg = boost::geometry;
    using Point = bg::model::d2::point_xy<double>;
    ompl::RNG rng(21);
    const double r = 0.025;
    auto g = emptyGrid(96, 80, r);
    g.origin = Eigen::Vector2d(-0.4, 0.3);
    for (int bj = 0; bj < 20; ++bj)
        for (int bi = 0; bi < 24; ++bi)
            if (rng.uniform01() < 0.15)
                for (int j = 4 * bj; j < 4 * bj + 4; ++j)
                    for (int i = 4 * bi; i < 4 * bi + 4; ++i)
                        g.cells[static_cast<std::size_t>(j) * 96 + i] = 1;
    const std::vector<Eigen::Vector2d> robot{{-0.09, -0.04}, {0.07, -0.05}, {0.09, 0.04}, {-0.06, 0.05}};
    validity::HeadingTable table(g, robot, 16);
    ASSERT_EQ(table.coarseFactor(), 4);
    auto check = [&](int poses)
    {
        int free = 0, blocked = 0;
        for (int n = 0; n < poses; ++n)
        {
            const double x = g.origin.x() + rng.uniformReal(0.15, 96 * r - 0.15);
            const double y = g.origin.y() + rng.uniformReal(0.15, 80 * r - 0.15);
            // one pose in eight with a yaw of 1e16-1e17 rad either way (a caller that keeps no bounds): its sin and
            // cos must still be the C library's, as the reference's are
            const double yaw =
                n % 8 == 3 ? (n % 16 == 3 ? -1. : 1.) * rng.uniformReal(1e16, 1e17) : rng.uniformReal(-M_PI, M_PI);
            const double margin = n % 2 ? rng.uniformReal(0., 0.03) : 0.;
            bg::model::polygon<Point> poly;
            for (std::size_t c = 0; c <= robot.size(); ++c)
            {
                const Eigen::Vector2d q = Eigen::Rotation2Dd(yaw) * robot[c % robot.size()] + Eigen::Vector2d(x, y);
                bg::append(poly.outer(), Point(q.x(), q.y()));
            }
            bg::correct(poly);
            bool meets = false;
            for (int j = 0; j < 80 && !meets; ++j)
                for (int i = 0; i < 96 && !meets; ++i)
                    if (table.occupied(i, j))
                    {
                        const double x0 = g.origin.x() + i * r - margin, y0 = g.origin.y() + j * r - margin;
                        meets = bg::intersects(poly, bg::model::box<Point>(Point(x0, y0), Point(x0 + r + 2 * margin,
                                                                                                y0 + r + 2 * margin)));
                    }
            // a pose within 1e-7 m of touching may go either way (round-off); none are drawn at random
            EXPECT_EQ(table.freePose(x, y, yaw, margin), !meets) << x << " " << y << " " << yaw << " " << margin;
            (meets ? blocked : free) += 1;
        }
        EXPECT_GT(free, poses / 10);
        EXPECT_GT(blocked, poses / 10);
    };
    check(4000);
    std::vector<std::pair<int, int>> block;
    for (int j = 40; j < 44; ++j)
        for (int i = 48; i < 52; ++i)
            block.emplace_back(i, j);
    table.setOccupied(block, !table.occupied(48, 40));
    EXPECT_EQ(table.coarseFactor(), 4);
    check(2000);
    table.setOccupied({{10, 10}}, !table.occupied(10, 10));
    EXPECT_EQ(table.coarseFactor(), 1);
    check(2000);
}

TEST(GridTable, SweepsTheFootprintOverTheHeadingBin)
{
    // a long thin bar on cell (30, 30): one occupied cell 0.25 m above its centre, one at (0.4, 0.25)
    auto g = emptyGrid(60, 60, 0.05);
    g.cells[35 * 60 + 30] = 1;
    g.cells[35 * 60 + 38] = 1;
    const std::vector<Eigen::Vector2d> bar{{-0.5, -0.02}, {0.5, -0.02}, {0.5, 0.02}, {-0.5, 0.02}};
    validity::HeadingTable table(g, bar, 16);
    EXPECT_TRUE(table.valid(30, 30, 0));   // yaw within +-pi/16: at x = 0.4 the bar rises 0.1 m at most
    EXPECT_FALSE(table.valid(30, 30, 4));  // pi/2: the bar crosses the cell above
    // bin 1 covers yaws pi/16 .. 3 pi/16: at 3 pi/16 the bar passes (0.4, 0.27), inside the cell at (0.4, 0.25)
    EXPECT_FALSE(table.valid(30, 30, 1));
    EXPECT_TRUE(table.valid(30, 30, 15));  // the mirror image meets nothing
}

TEST(GridTable, LocalUpdateEqualsRebuild)
{
    ompl::RNG rng(5);
    auto g = emptyGrid(80, 70, 0.05);
    for (auto &c : g.cells)
        c = rng.uniform01() < 0.05 ? 1 : 0;
    const std::vector<Eigen::Vector2d> robot{{-0.2, -0.07}, {0.2, -0.07}, {0.2, 0.07}, {-0.2, 0.07}};
    validity::HeadingTable table(g, robot, 16);
    // close a "door": a short wall of 6 cells (under 1 % of the cells)
    std::vector<std::pair<int, int>> door;
    for (int j = 30; j < 36; ++j)
        door.emplace_back(40, j);
    const auto box = table.setOccupied(door, true);
    EXPECT_FALSE(box.empty());
    EXPECT_LT((box.i1 - box.i0 + 1) * (box.j1 - box.j0 + 1), 80 * 70 / 4);  // recomputed locally
    auto h = g;
    for (const auto &c : door)
        h.cells[c.second * 80 + c.first] = 1;
    validity::HeadingTable rebuilt(h, robot, 16);
    for (int k = 0; k < 16; ++k)
        for (int j = 0; j < 70; ++j)
            for (int i = 0; i < 80; ++i)
                ASSERT_EQ(table.valid(i, j, k), rebuilt.valid(i, j, k)) << i << " " << j << " " << k;
    // and open it again
    table.setOccupied(door, false);
    validity::HeadingTable original(g, robot, 16);
    for (int k = 0; k < 16; ++k)
        for (int j = 0; j < 70; ++j)
            for (int i = 0; i < 80; ++i)
                ASSERT_EQ(table.valid(i, j, k), original.valid(i, j, k));
}

TEST(GridTable, ExactTestFirstOnlyForAFootprintOverTwoRowsAndStillExact)
{
    // A map of 0.1 m cells split into 8 x 8 table cells (as arena is): the exact test reads the map's own bits,
    // which the small robot spans at most two rows of, so freeOnGrid() tests a pose the summaries leave open
    // exactly rather than through the table word and the band.
    auto g = emptyGrid(160, 160, 0.0125);
    for (int j = 0; j < 160; ++j)
        for (int i = 0; i < 160; ++i)
            if (((i / 8) % 3 == 1 && (j / 8) % 4 != 0) || (j / 8) == 10)
                g.cells[static_cast<std::size_t>(j) * 160 + i] = 1;
    const std::vector<Eigen::Vector2d> robot{{-0.04, -0.025}, {0.04, -0.025}, {0.04, 0.025}, {-0.04, 0.025}};
    validity::HeadingTable table(g, robot, 16);
    ASSERT_EQ(table.coarseFactor(), 8);
    EXPECT_TRUE(table.exactFirst());
    // the same map with a robot whose circle spans 4.5 map rows keeps the table word and the band
    const std::vector<Eigen::Vector2d> big{{-0.2, -0.1}, {0.2, -0.1}, {0.2, 0.1}, {-0.2, 0.1}};
    EXPECT_FALSE(validity::HeadingTable(g, big, 16).exactFirst());
    ompl::RNG rng(5);
    expectFreeOnGridAgrees(table, rng, 0.1, 1.9, 0.1, 1.9, "built");
    // one table cell occupied splits a map cell: the exact test falls back to the table's own rows, which the
    // robot spans more than two of, and the table word decides again
    table.setOccupied({{5 * 8 + 3, 6 * 8 + 3}}, true);
    EXPECT_EQ(table.coarseFactor(), 1);
    EXPECT_FALSE(table.exactFirst());
    expectFreeOnGridAgrees(table, rng, 0.1, 1.9, 0.1, 1.9, "split cell");
}

TEST(GridTable, FreeOnGridAnswersAsFreePoseThroughItsBlockSummaries)
{
    // Thick walls (whole 8 x 8 summary blocks occupied, where freeOnGrid() answers from the block alone) and thin
    // ones, a robot holding its origin; the block summaries must follow a local update both ways (a room filled,
    // then emptied again).
    auto g = emptyGrid(96, 80, 0.025);
    for (int j = 16; j < 40; ++j)
        for (int i = 24; i < 48; ++i)
            g.cells[j * 96 + i] = 1;
    for (int i = 0; i < 96; ++i)
        g.cells[60 * 96 + i] = 1;
    const std::vector<Eigen::Vector2d> robot{{-0.04, -0.025}, {0.04, -0.025}, {0.04, 0.025}, {-0.04, 0.025}};
    validity::HeadingTable table(g, robot, 16);
    ompl::RNG rng(11);
    // a footprint radius and two cells inside the grid, as GridValidityChecker pads it (beyond, the table and
    // freePose() differ on purpose: cells past the edge are free to one, blocked to the other)
    const auto agree = [&](const char *when)
    {
        expectFreeOnGridAgrees(table, rng, 0.1, 2.3, 0.1, 1.9, when);
    };
    agree("built");
    std::vector<std::pair<int, int>> room;
    for (int j = 64; j < 80; ++j)
        for (int i = 64; i < 96; ++i)
            room.emplace_back(i, j);
    table.setOccupied(room, true);
    agree("room filled");
    EXPECT_FALSE(table.freeOnGrid(2.0, 1.8, 0.3));  // inside the filled room
    // emptied but for one column: its blocks turn mixed (neither all free nor all colliding), where a block
    // summary left over from the filled room would refuse free poses
    std::vector<std::pair<int, int>> open;
    for (const auto &c : room)
        if (c.first != 84)
            open.push_back(c);
    table.setOccupied(open, false);
    agree("room emptied but a column");
    EXPECT_TRUE(table.freeOnGrid(2.0, 1.8, M_PI / 2));  // beside the column, along it
    EXPECT_FALSE(table.freeOnGrid(2.1, 1.8, 0.));       // across it
}

TEST(GridTable, SuperBlocksOnALargeMapAnswerAsFreePoseBeforeAndAfterUpdates)
{
    // 64room's layout at a quarter of its size: map cells of 4 x 4 table cells (so summary blocks of one map cell),
    // one-cell walls every 16 map cells with one-cell doors, and 1040 x 1040 table cells, enough blocks for the
    // second summary level of 16 x 16 table cells. It must say only what each of its blocks says, also after a room
    // is filled (its super-blocks must stop saying "free") and emptied again.
    const int n = 1040;
    auto g = emptyGrid(n, n, 0.025);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
            const int mi = i / 4, mj = j / 4;
            if ((mi % 16 == 0 && mj % 16 != 8) || (mj % 16 == 0 && mi % 16 != 8))
                g.cells[static_cast<std::size_t>(j) * n + i] = 1;
        }
    const std::vector<Eigen::Vector2d> robot{{-0.04, -0.025}, {0.04, -0.025}, {0.04, 0.025}, {-0.04, 0.025}};
    validity::HeadingTable table(g, robot, 16);
    ASSERT_EQ(table.coarseFactor(), 4);
    ASSERT_EQ(table.superBlockCells(), 16);
    // a 96 x 96-cell map has no second level
    EXPECT_EQ(validity::HeadingTable(emptyGrid(96, 96, 0.025), robot, 16).superBlockCells(), 0);
    ompl::RNG rng(13);
    const double lo = 0.1, hi = n * 0.025 - 0.1;
    expectFreeOnGridAgrees(table, rng, lo, hi, lo, hi, "built");
    // most of the room of map cells 17-31 (table cells 72-119 in both directions), filled, then emptied but for one
    // column
    std::vector<std::pair<int, int>> room, open;
    for (int j = 72; j < 120; ++j)
        for (int i = 72; i < 120; ++i)
        {
            room.emplace_back(i, j);
            if (i != 96)
                open.emplace_back(i, j);
        }
    EXPECT_TRUE(table.freeOnGrid(2.4, 2.4, 0.3));  // the room's middle, before
    table.setOccupied(room, true);
    EXPECT_FALSE(table.freeOnGrid(2.4, 2.4, 0.3));
    expectFreeOnGridAgrees(table, rng, 1.0, 4.0, 1.0, 4.0, "room filled");
    table.setOccupied(open, false);
    expectFreeOnGridAgrees(table, rng, 1.0, 4.0, 1.0, 4.0, "room emptied but a column");
    expectFreeOnGridAgrees(table, rng, lo, hi, lo, hi, "after both updates");
}

TEST(GridTable, A512MapWith16HeadingsStaysUnder64MiB)
{
    const auto g = emptyGrid(512, 512, 0.1);
    const std::vector<Eigen::Vector2d> robot{{-0.03, -0.02}, {0.03, -0.02}, {0.03, 0.02}, {-0.03, 0.02}};
    validity::HeadingTable table(g, robot, 16);
    EXPECT_LT(table.bytes(), 64u << 20);
    EXPECT_EQ(table.validCount(), 512u * 512u * 16u);
}

TEST(GridChecker, PlanningContextInstallsCheckerAndMotionValidator)
{
    auto problem = tools::loadProblem(problemPath("se2_corridor"));
    // the 1.6 m robot fits its 0.8 m corridor only within +-14 degrees: finer heading bins than the default 16
    problem.grid.headings = 64;
    problem.grid.resolution = 0.025;
    tools::ContextOptions options;
    options.checker = "grid";
    auto ctx = tools::makePlanningContext(problem, options);
    ASSERT_TRUE(ctx.grid);
    EXPECT_EQ(ctx.checkerName, "grid");
    auto si = ctx.setup->getSpaceInformation();
    EXPECT_EQ(si->getStateValidityChecker(), ctx.grid);
    auto mv = std::dynamic_pointer_cast<validity::GridMotionValidator>(si->getMotionValidator());
    ASSERT_TRUE(mv);
    ASSERT_TRUE(ctx.referenceMotions);
    // turn-move-turn: driving from the corridor straight through the wall into the room above is invalid, the
    // lastValid state is valid and lies before the wall; driving along the corridor is valid
    ob::ScopedState<> a(si->getStateSpace()), b(si->getStateSpace()), c(si->getStateSpace());
    si->getStateSpace()->copyFromReals(a.get(), {1.5, 2.0, 0.});
    si->getStateSpace()->copyFromReals(b.get(), {5.5, 2.0, 0.});
    si->getStateSpace()->copyFromReals(c.get(), {1.5, 5.0, 0.});
    EXPECT_TRUE(si->isValid(a.get()));
    EXPECT_TRUE(si->checkMotion(a.get(), b.get()));
    std::pair<ob::State *, double> last{si->allocState(), 0.};
    EXPECT_FALSE(si->checkMotion(a.get(), c.get(), last));
    EXPECT_TRUE(si->isValid(last.first));
    EXPECT_GE(last.second, 0.);
    EXPECT_LT(last.second, 0.5);
    EXPECT_TRUE(ctx.checker->isValid(last.first));
    si->freeState(last.first);
    // clearance: a lower bound of FCL's
    EXPECT_GT(ctx.grid->clearance(a.get()), 0.);
    EXPECT_LE(ctx.grid->clearance(a.get()), ctx.checker->clearance(a.get()) + 1e-9);
}

TEST(GridChecker, ACheckerOverTheSameMapCopiesTheTableAndKeepsItsOwnUpdates)
{
    // code that makes a planning context per query of a map (the tests, a user's loop) made the same table again
    // for every query: 1.5 s each on movingai_64room. A second checker over the same grid copies the table
    auto problem = tools::loadProblem(problemPath("se2_corridor"));
    problem.grid.headings = 64;
    problem.grid.resolution = 0.0237;  // no other test makes this table, so the first context below builds it
    tools::ContextOptions options;
    options.checker = "grid";
    const std::size_t before = validity::GridValidityChecker::tablesBuilt();
    auto first = tools::makePlanningContext(problem, options);
    EXPECT_EQ(validity::GridValidityChecker::tablesBuilt(), before + 1);
    auto second = tools::makePlanningContext(problem, options);
    EXPECT_EQ(validity::GridValidityChecker::tablesBuilt(), before + 1);
    ASSERT_TRUE(first.grid && second.grid);
    ASSERT_NE(&first.grid->table(), &second.grid->table());
    ompl::RNG::setSeed(7);
    auto si = first.setup->getSpaceInformation();
    auto sampler = si->allocStateSampler();
    ob::ScopedState<> s(si->getStateSpace());
    int valid = 0;
    for (int i = 0; i < 2000; ++i)
    {
        sampler->sampleUniform(s.get());
        const bool a = first.grid->isValid(s.get());
        ASSERT_EQ(a, second.grid->isValid(s.get())) << i;
        valid += a ? 1 : 0;
    }
    // the 1.6 m robot fits the corridor's 0.8 m at few uniform poses: 19 of the 2,000 here
    EXPECT_GT(valid, 10);
    EXPECT_LT(valid, 2000);
    // a box put in the corridor, seen by the second checker only (refresh() changes its own copy of the table)
    ob::ScopedState<> a(si->getStateSpace());
    si->getStateSpace()->copyFromReals(a.get(), {3.5, 2.0, 0.});
    ASSERT_TRUE(first.grid->isValid(a.get()));
    validity::Obstacle box;
    box.name = "dropped box";
    box.shape = validity::Shape::box(Eigen::Vector3d(0.3, 0.3, 1.));
    box.pose.translation() = Eigen::Vector3d(3.5, 2.0, 0.5);
    second.scene->add(box);
    EXPECT_FALSE(second.grid->refresh().empty());
    EXPECT_FALSE(second.grid->isValid(a.get()));
    EXPECT_TRUE(first.grid->isValid(a.get()));
    // the changed map is another grid: its table is built, not copied
    options.scene = second.scene;
    auto third = tools::makePlanningContext(problem, options);
    EXPECT_EQ(validity::GridValidityChecker::tablesBuilt(), before + 2);
    EXPECT_FALSE(third.grid->isValid(a.get()));
}

TEST(GridChecker, ProblemFileKeys)
{
    const std::string dir = ::testing::TempDir();
    const std::string base = std::string(MICHI_SOURCE_DIR) + "/problems/";
    auto write = [&](const std::string &collision)
    {
        const std::string path = dir + "/grid_problem.yaml";
        std::ofstream out(path);
        out << "name: g\nrobot: {type: se2, footprint: [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]], "
               "bounds: {x: [0, 2], y: [0, 2]}}\nstart: [0.5, 0.5, 0]\ngoal: [1.5, 1.5, 0]\n"
            << collision;
        return path;
    };
    const auto p = tools::loadProblem(write("collision: {checker: grid, grid: {resolution: 0.02, headings: 32}}\n"));
    EXPECT_EQ(p.checker, "grid");
    EXPECT_DOUBLE_EQ(p.grid.resolution, 0.02);
    EXPECT_EQ(p.grid.headings, 32u);
    auto ctx = tools::makePlanningContext(p);
    ASSERT_TRUE(ctx.grid);
    EXPECT_EQ(ctx.grid->table().headings(), 32);
    EXPECT_DOUBLE_EQ(ctx.grid->table().grid().resolution, 0.02);
    EXPECT_THROW(tools::loadProblem(write("collision: {checker: grids}\n")), tools::ProblemError);
    EXPECT_THROW(tools::loadProblem(write("collision: {grid: {headings: 0}}\n")), tools::ProblemError);
    EXPECT_THROW(tools::loadProblem(write("collision: {grid: {cells: 3}}\n")), tools::ProblemError);
    EXPECT_THROW(tools::loadProblem(write("benchmark: {queries: 3-1}\n")), tools::ProblemError);
    // a map problem aligns the table with the map's cells
    const auto arena = tools::loadProblem(base + "movingai_arena.yaml");
    EXPECT_DOUBLE_EQ(arena.grid.mapResolution, 0.1);
}

TEST(Dataset, SelectionsAndProblemQueries)
{
    EXPECT_TRUE(tools::parseQuerySelection("all").all);
    const auto s = tools::parseQuerySelection("2-5");
    EXPECT_FALSE(s.all);
    EXPECT_EQ(s.first, 2u);
    EXPECT_EQ(s.last, 5u);
    EXPECT_EQ(tools::parseQuerySelection("4").last, 4u);
    for (const char *bad : {"", "-", "a-b", "5-2", "1-", "-3", "1.5", "all,2"})
        EXPECT_THROW(tools::parseQuerySelection(bad), std::invalid_argument) << bad;
    const auto arena = tools::loadProblem(problemPath("movingai_arena"));
    const auto all = tools::datasetOf(arena, tools::parseQuerySelection("all"));
    ASSERT_EQ(all.entries.size(), arena.queries.size());
    EXPECT_EQ(all.entries[1].query, 1u);
    EXPECT_NE(all.entries[1].label.find("arena.map.scen line"), std::string::npos);
    EXPECT_EQ(tools::datasetOf(arena, tools::parseQuerySelection("1-2")).entries.size(), 2u);
    EXPECT_THROW(tools::datasetOf(arena, tools::parseQuerySelection("0-99")), tools::ProblemError);
}

TEST(GridChecker, ObstaclesAboveOrBelowTheRobotStayOutOfTheGrid)
{
    // Found by the exploratory sweep of 2026-12-07: a table top over a robot lower than it blocked the grid beneath
    // it (55 % of the states FCL calls free were refused, the start among them), where FCL finds no contact.
    validity::Scene scene;
    auto at = [](double x, double y, double z)
    {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translation() = Eigen::Vector3d(x, y, z);
        return pose;
    };
    // a robot over z in [0, 0.5]: a table top at [0.75, 0.85] is above it, a lamp hanging down to 0.45 reaches
    // into it, a plate lying on it from 0.5 up touches it (contact counts), a box under the floor is below it
    scene.add(validity::Obstacle{"table_top", validity::Shape::box({1., 1., 0.1}), at(1., 1., 0.8), {}});
    scene.add(validity::Obstacle{"lamp", validity::Shape::box({0.2, 0.2, 0.4}), at(3., 1., 0.65), {}});
    scene.add(validity::Obstacle{"plate", validity::Shape::box({0.2, 0.2, 0.1}), at(1., 3., 0.55), {}});
    scene.add(validity::Obstacle{"cellar", validity::Shape::box({0.2, 0.2, 0.1}), at(3., 3., -0.1), {}});
    const Eigen::Vector2d origin(0., 0.);
    const validity::OccupancyGrid heights = validity::rasterizeScene(scene, 0.1, origin, 40, 40, 1e-7, 0., 0.5);
    const validity::OccupancyGrid every = validity::rasterizeScene(scene, 0.1, origin, 40, 40, 1e-7);
    auto occupied = [](const validity::OccupancyGrid &g, double x, double y)
    {
        return g.cells[static_cast<std::size_t>(g.row(y)) * g.width + g.column(x)] != 0;
    };
    EXPECT_FALSE(occupied(heights, 1., 1.));  // table top
    EXPECT_TRUE(occupied(heights, 3., 1.));   // lamp
    EXPECT_TRUE(occupied(heights, 1., 3.));   // plate
    EXPECT_FALSE(occupied(heights, 3., 3.));  // cellar
    // without a height range every obstacle counts, as before
    for (const auto &p :
         {Eigen::Vector2d(1., 1.), Eigen::Vector2d(3., 1.), Eigen::Vector2d(1., 3.), Eigen::Vector2d(3., 3.)})
        EXPECT_TRUE(occupied(every, p.x(), p.y()));
    EXPECT_EQ(heights.occupiedCount() + 100 + 4, every.occupiedCount());
}
