// CpuBudget (michi replan's CPU-time limit): it reads the CPU clock only when the wall time since the last read could
// have used the budget up, and still stops exactly when the CPU time passes it.
#include <michi/tools/commands/CpuBudget.h>

#include <gtest/gtest.h>

#include <limits>

using michi::tools::CpuBudget;

namespace
{
    struct FakeClocks
    {
        double cpu{10.}, wall{100.};
        std::size_t cpuReads{0};
    };
}  // namespace

TEST(CpuBudget, ReadsTheCpuClockOnlyWhenTheWallTimeCouldHaveUsedTheBudgetUp)
{
    FakeClocks c;
    CpuBudget budget(
        1.,
        [&c]
        {
            ++c.cpuReads;
            return c.cpu;
        },
        [&c]
        {
            return c.wall;
        });
    EXPECT_EQ(c.cpuReads, 1u);  // the start
    // 0.9 s of wall time, whatever the CPU did: the budget cannot be spent, the CPU clock is not read
    for (int i = 0; i < 9; ++i)
    {
        c.wall += 0.1;
        c.cpu += 0.05;
        EXPECT_FALSE(budget.spent());
    }
    EXPECT_EQ(c.cpuReads, 1u);
    // past 1 s of wall time the bound no longer holds: read, 0.55 s of CPU used, not spent
    c.wall += 0.2;
    c.cpu += 0.05;
    EXPECT_FALSE(budget.spent());
    EXPECT_EQ(c.cpuReads, 2u);
    EXPECT_EQ(budget.cpuReads(), 2u);
    // from that read, 0.45 s of CPU are left: no read before 0.45 s more of wall time
    c.wall += 0.4;
    c.cpu += 0.4;
    EXPECT_FALSE(budget.spent());
    EXPECT_EQ(c.cpuReads, 2u);
    // the CPU time passes the budget: noticed at the next ask
    c.wall += 0.1;
    c.cpu += 0.1;
    EXPECT_TRUE(budget.spent());
    EXPECT_EQ(c.cpuReads, 3u);
    EXPECT_TRUE(budget.spent());
}

TEST(CpuBudget, ABusyThreadIsStoppedAtItsBudget)
{
    // CPU time growing as fast as the wall clock (a thread that never waits): spent once 1 s has gone, not before
    FakeClocks c;
    CpuBudget budget(
        1.,
        [&c]
        {
            return c.cpu;
        },
        [&c]
        {
            return c.wall;
        });
    int asks = 0;
    while (!budget.spent())
    {
        c.wall += 0.01;
        c.cpu += 0.01;
        ++asks;
        ASSERT_LT(asks, 1000);
    }
    EXPECT_GE(asks, 100);
    EXPECT_LE(asks, 101);
}

TEST(CpuBudget, AnInfiniteBudgetIsNeverSpent)
{
    FakeClocks c;
    CpuBudget budget(
        std::numeric_limits<double>::infinity(),
        [&c]
        {
            return c.cpu;
        },
        [&c]
        {
            return c.wall;
        });
    c.wall += 1e6;
    c.cpu += 1e6;
    EXPECT_FALSE(budget.spent());
    EXPECT_EQ(budget.cpuReads(), 1u);
}
