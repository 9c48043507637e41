// Tests of the grid checker's band table (validity/.../grid/BandTable.h): the finer bits of the entries the heading
// table refuses but cannot call blocked. Ground truth is HeadingTable::freePose, the exact test of the footprint at
// the pose against the occupied cells (itself checked against FCL on every bundled map problem in
// test_grid_checker). Deterministic: random grids and poses from a seeded ompl::RNG.
#include <michi/validity/grid/HeadingTable.h>

#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace michi;

namespace
{
    validity::OccupancyGrid randomGrid(int w, int h, double r, double fraction, ompl::RNG &rng)
    {
        validity::OccupancyGrid g;
        g.width = w;
        g.height = h;
        g.resolution = r;
        g.origin = Eigen::Vector2d(-0.3, 0.2);
        g.cells.assign(static_cast<std::size_t>(w) * h, 0);
        // walls of 4 x 4-cell blocks (a map's cells split into table cells) and single cells
        for (int j = 0; j + 4 <= h; j += 4)
            for (int i = 0; i + 4 <= w; i += 4)
                if (rng.uniform01() < fraction)
                    for (int b = 0; b < 16; ++b)
                        g.cells[static_cast<std::size_t>(j + b / 4) * w + i + b % 4] = 1;
        for (auto &c : g.cells)
            c = c || rng.uniform01() < fraction / 10.;
        return g;
    }

    struct Counts
    {
        std::size_t band{0}, decided{0}, free{0};
    };

    /** Every sub-entry claim at random poses agrees with freePose, and freeOnGrid equals freePose everywhere. */
    Counts checkAgainstFreePose(const validity::HeadingTable &table, ompl::RNG &rng, int poses)
    {
        Counts counts;
        const auto &g = table.grid();
        // poses whose footprint stays in the grid (the checker's grid has that margin around its bounds; the
        // table, as FCL, knows no obstacles beyond the grid, freePose refuses to reach there)
        const double pad = table.circumradius() + 2. * g.resolution;
        for (int n = 0; n < poses; ++n)
        {
            const double x = g.origin.x() + rng.uniformReal(pad, g.width * g.resolution - pad);
            const double y = g.origin.y() + rng.uniformReal(pad, g.height * g.resolution - pad);
            const double yaw = rng.uniformReal(-M_PI, M_PI);
            const bool exact = table.freePose(x, y, yaw);
            EXPECT_EQ(table.freeOnGrid(x, y, yaw), exact) << x << " " << y << " " << yaw;
            counts.free += exact ? 1 : 0;
            const int i = g.column(x), j = g.row(y), k = table.headingBin(yaw);
            const validity::BandTable::Entry *e = table.bandEntry(i, j, k);
            if (!e)
                continue;
            ++counts.band;
            const int s = table.band().subEntry((x - g.origin.x()) / g.resolution, (y - g.origin.y()) / g.resolution,
                                                yaw / table.headingStep() + 0.5);
            const bool valid = (e->valid >> s) & 1u, blocked = (e->blocked >> s) & 1u;
            EXPECT_FALSE(valid && blocked);
            if (valid)
                EXPECT_TRUE(exact) << "sub-entry " << s << " valid at a colliding pose " << x << " " << y << " " << yaw;
            if (blocked)
                EXPECT_FALSE(exact) << "sub-entry " << s << " blocked at a free pose " << x << " " << y << " " << yaw;
            counts.decided += (valid || blocked) ? 1 : 0;
        }
        std::cout << "band: " << table.band().positions() << " x " << table.band().positions() << " positions, "
                  << table.band().subHeadings() << " sub-bins, " << table.band().size() << " band entries; "
                  << counts.band << " of " << poses << " poses in band entries, " << counts.decided
                  << " decided by their bits" << std::endl;
        return counts;
    }
}  // namespace

TEST(GridBandTable, SubEntriesAgreeWithTheExactTest)
{
    ompl::RNG::setSeed(11);
    ompl::RNG rng(3);
    // the 64room robot on 0.025 m table cells, a long robot (se2_rooms-like) on 0.05 m cells
    const std::vector<std::vector<Eigen::Vector2d>> robots{{{-0.03, -0.02}, {0.03, -0.02}, {0.03, 0.02}, {-0.03, 0.02}},
                                                           {{-0.4, -0.1}, {0.4, -0.1}, {0.4, 0.1}, {-0.4, 0.1}}};
    const double resolutions[] = {0.025, 0.05};
    for (std::size_t r = 0; r < robots.size(); ++r)
    {
        SCOPED_TRACE(r);
        const auto g = randomGrid(120, 100, resolutions[r], 0.08, rng);
        validity::HeadingTable table(g, robots[r], 16, 1e-6 * resolutions[r]);
        EXPECT_TRUE(table.band().empty());
        table.buildBand();
        ASSERT_FALSE(table.band().empty());
        EXPECT_EQ(table.band().positions() * table.band().positions() * table.band().subHeadings(), 64);
        const Counts c = checkAgainstFreePose(table, rng, 100000);
        EXPECT_GT(c.band, 1000u);
        EXPECT_GT(c.free, 10000u);
        // most poses of band entries are decided by bits (the rest by the exact test)
        EXPECT_GT(c.decided, c.band / 2) << c.decided << " of " << c.band;
    }
}

TEST(GridBandTable, NonConvexFootprint)
{
    ompl::RNG rng(5);
    // an L: triangles, no blocked bits in the heading table (every invalid entry is a band entry)
    const std::vector<Eigen::Vector2d> ell{{-0.05, -0.05}, {0.06, -0.05}, {0.06, -0.02},
                                           {-0.02, -0.02}, {-0.02, 0.05}, {-0.05, 0.05}};
    const auto g = randomGrid(80, 80, 0.02, 0.06, rng);
    validity::HeadingTable table(g, ell, 16, 2e-8);
    table.buildBand();
    const Counts c = checkAgainstFreePose(table, rng, 50000);
    EXPECT_GT(c.band, 1000u);
    EXPECT_GT(c.decided, c.band / 2) << c.decided << " of " << c.band;
}

TEST(GridBandTable, LocalUpdateEqualsRebuild)
{
    ompl::RNG rng(7);
    const std::vector<Eigen::Vector2d> robot{{-0.1, -0.04}, {0.1, -0.04}, {0.1, 0.04}, {-0.1, 0.04}};
    auto g = randomGrid(96, 80, 0.025, 0.06, rng);
    validity::HeadingTable table(g, robot, 16);
    table.buildBand();
    std::vector<std::pair<int, int>> door;
    for (int j = 30; j < 38; ++j)
        for (int i = 60; i < 64; ++i)
            door.emplace_back(i, j);
    auto expectSame = [&](const validity::HeadingTable &a, const validity::HeadingTable &b)
    {
        ASSERT_EQ(a.band().size(), b.band().size());
        for (int k = 0; k < 16; ++k)
            for (int j = 0; j < 80; ++j)
                for (int i = 0; i < 96; ++i)
                {
                    const auto *ea = a.bandEntry(i, j, k), *eb = b.bandEntry(i, j, k);
                    ASSERT_EQ(ea == nullptr, eb == nullptr) << i << " " << j << " " << k;
                    if (ea)
                    {
                        ASSERT_EQ(ea->valid, eb->valid) << i << " " << j << " " << k;
                        ASSERT_EQ(ea->blocked, eb->blocked) << i << " " << j << " " << k;
                    }
                }
    };
    for (bool occupied : {true, false})
    {
        table.setOccupied(door, occupied);
        auto h = g;
        for (const auto &c : door)
            h.cells[static_cast<std::size_t>(c.second) * 96 + c.first] = occupied ? 1 : 0;
        validity::HeadingTable rebuilt(h, robot, 16);
        rebuilt.buildBand();
        expectSame(table, rebuilt);
        // and the queries read the updated entries (freeOnGrid's per-entry codes are made again)
        checkAgainstFreePose(table, rng, 20000);
    }
}
