// Self-pair tables: a cell read as free is free over the whole cell (certified), on a hand-made distance and on the
// Panda's wrist pairs against FCL; continuous joints wrap; values outside the range are never free.
#include "../../validity/src/spheres/SelfPairTable.h"

#include <michi/tools/bench/PlanningContext.h>
#include <michi/validity/spheres/SphereValidityChecker.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>

using namespace michi;
using namespace michi::validity;

namespace
{
    /** Two bodies that touch where x is within 0.3 of 1.0 (and of 1.0 + 2 pi: a continuous joint), a distance
        that grows by at most 1 metre per unit of x. */
    double bandDistance(double x)
    {
        const double wrapped = std::remainder(x - 1.0, 2. * M_PI);
        return std::abs(wrapped) - 0.3;
    }
}  // namespace

TEST(SelfPairTable, FreeCellsAreFreeEverywhereInside)
{
    const SelfPairTable table({0}, {-M_PI}, {M_PI}, {1}, {1.0}, 256,
                              [](const double *at)
                              {
                                  return bandDistance(at[0]);
                              });
    ompl::RNG rng(4);
    int free = 0;
    for (int i = 0; i < 20000; ++i)
    {
        const double x = rng.uniformReal(-M_PI, M_PI);
        const double v[1] = {x};
        if (!table.free(v))
            continue;
        ++free;
        EXPECT_GT(bandDistance(x), 0.) << "free at " << x;
        // a span: every value within it is free
        const float span[1] = {0.05f};
        if (table.freeOver(v, span))
            for (int k = -10; k <= 10; ++k)
                EXPECT_GT(bandDistance(x + 0.005 * k), 0.) << "span around " << x;
    }
    // the band is 0.6 of 2 pi wide: the rest, less a few cells at its edges, is free
    EXPECT_GT(free, 20000 * 0.85);
    EXPECT_LT(table.evaluations(), 256u * 2u);  // adaptive: far fewer queries than cells where it is far
}

TEST(SelfPairTable, ContinuousJointsWrapAndLimitedJointsDoNot)
{
    const SelfPairTable wrapped({0}, {-M_PI}, {M_PI}, {1}, {1.0}, 128,
                                [](const double *at)
                                {
                                    return bandDistance(at[0]);
                                });
    for (double x : {-3.0, -2.0, 0.0, 2.5, 3.1})
    {
        const double v[1] = {x}, shifted[1] = {x + 2. * M_PI}, back[1] = {x - 4. * M_PI};
        EXPECT_EQ(wrapped.free(v), wrapped.free(shifted)) << x;
        EXPECT_EQ(wrapped.free(v), wrapped.free(back)) << x;
    }
    // a span across the -pi/pi seam reads the cells on both sides
    const double nearSeam[1] = {M_PI - 0.01};
    const float wide[1] = {0.05f};
    EXPECT_TRUE(wrapped.freeOver(nearSeam, wide));

    const SelfPairTable limited({0}, {-1.0}, {2.5}, {0}, {1.0}, 128,
                                [](const double *)
                                {
                                    return 1.0;
                                });
    const double inside[1] = {2.5}, outside[1] = {2.6}, nan[1] = {std::nan("")};
    EXPECT_TRUE(limited.free(inside));
    EXPECT_FALSE(limited.free(outside));
    EXPECT_FALSE(limited.free(nan));
}

TEST(SelfPairTable, TwoValuesCertifiedAgainstTheirDistance)
{
    // a disc of radius 0.5 around (0.2, -0.4) in the plane of the two values is contact
    auto distance = [](const double *at)
    {
        return std::hypot(at[0] - 0.2, at[1] + 0.4) - 0.5;
    };
    const SelfPairTable table({2, 5}, {-2., -3.}, {2., 3.}, {0, 0}, {1., 1.}, 128, distance);
    EXPECT_EQ(table.variables(), (std::vector<int>{2, 5}));
    ompl::RNG rng(8);
    int free = 0;
    for (int i = 0; i < 20000; ++i)
    {
        double v[6] = {9., 9., rng.uniformReal(-2., 2.), 9., 9., rng.uniformReal(-3., 3.)};
        if (!table.free(v))
            continue;
        ++free;
        const double at[2] = {v[2], v[5]};
        EXPECT_GT(distance(at), 0.);
    }
    EXPECT_GT(free, 20000 * 0.9);  // the disc is 3 % of the box
    EXPECT_GT(table.freeFraction(), 0.9);
}

// A motion's piece reads every cell its spans touch: a span read as free is free at every value inside it, with either
// value wrapping round (a continuous joint, across the seam too) or both limited; and a span over the contact is not.
TEST(SelfPairTable, TwoValueSpansAreFreeEverywhereInside)
{
    // contact in a disc of radius 0.15 around (0.2, 2.95), just short of the seam of the second value: a span that
    // starts below -pi reaches it only by wrapping round
    auto distance = [](const double *at)
    {
        return std::hypot(at[0] - 0.2, std::remainder(at[1] - 2.95, 2. * M_PI)) - 0.15;
    };
    for (const std::vector<char> &wrap : {std::vector<char>{0, 1}, std::vector<char>{1, 0}, std::vector<char>{0, 0}})
    {
        const double lo0 = wrap[0] ? -M_PI : -2., hi0 = wrap[0] ? M_PI : 2.;
        const SelfPairTable table({0, 1}, {lo0, -M_PI}, {hi0, M_PI}, wrap, {1., 1.}, 64, distance);
        ompl::RNG rng(21);
        int free = 0, refused = 0;
        for (int i = 0; i < 8000; ++i)
        {
            // half of the values near the seam, beside the disc
            const double v[2] = {rng.uniformReal(lo0, hi0),
                                 i % 2 == 0 ? rng.uniformReal(-M_PI, M_PI) : rng.uniformReal(-M_PI, -M_PI + 0.3)};
            const float span[2] = {static_cast<float>(rng.uniformReal(0., 0.3)),
                                   static_cast<float>(rng.uniformReal(0., 0.3))};
            if (!table.freeOver(v, span))
            {
                ++refused;
                continue;
            }
            ++free;
            for (int a = -4; a <= 4; ++a)
                for (int b = -4; b <= 4; ++b)
                {
                    const double at[2] = {v[0] + span[0] * a / 4., v[1] + span[1] * b / 4.};
                    if (!wrap[0] && (at[0] < lo0 || at[0] > hi0))
                        continue;
                    ASSERT_GT(distance(at), 0.) << "span around (" << v[0] << ", " << v[1] << ")";
                }
        }
        // the disc and its margin are a small part of the box: most spans are free, those over the disc are not
        EXPECT_GT(free, 8000 * 0.6);
        EXPECT_GT(refused, 0);
        const double onDisc[2] = {0.2, 2.95};
        const float small[2] = {0.01f, 0.01f};
        EXPECT_FALSE(table.freeOver(onDisc, small));
    }
}

TEST(SelfPairTable, PandaWristTablesAgreeWithFcl)
{
    const auto problem = tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/panda_table_pick.yaml");
    auto ctx = tools::makePlanningContext(problem);
    auto group = std::dynamic_pointer_cast<const RobotGroupBodies>(ctx.bodies);
    auto spheres = std::make_shared<SphereValidityChecker>(
        ctx.setup->getSpaceInformation(), group, SphereModel::enclose(*group->model()), ctx.scene, ctx.checker);
    // link5 against link7, the hand and both fingers depend on joints 6 and 7 only
    EXPECT_EQ(spheres->tabulatedPairs(), 4u);
    // states the spheres accept are free for FCL, self pairs included; and the wrist no longer makes most states
    // false-invalid (spheres alone overlap there in most states)
    ompl::RNG rng(12);
    const auto &bounds = ctx.setup->getStateSpace()->as<ompl::base::RealVectorStateSpace>()->getBounds();
    int fclValid = 0, falseInvalid = 0;
    for (int i = 0; i < 2000; ++i)
    {
        std::vector<double> q;
        for (std::size_t d = 0; d < bounds.low.size(); ++d)
            q.push_back(rng.uniformReal(bounds.low[d], bounds.high[d]));
        const bool exact = ctx.checker->isValidConfiguration(q.data());
        const bool fast = spheres->isValidConfiguration(q.data());
        ASSERT_FALSE(fast && !exact) << ctx.checker->describeCollision(q.data());
        fclValid += exact;
        falseInvalid += exact && !fast;
    }
    ASSERT_GT(fclValid, 1000);
    EXPECT_LT(falseInvalid, fclValid / 20) << falseInvalid << " of " << fclValid;
}

// The tables go to the cache folder once and come back from it for the next checker of the same robot, with the
// same answers; a damaged file is not trusted but rebuilt.
TEST(SelfPairTable, CachedOnDiskAndReadBack)
{
    const std::string dir = ::testing::TempDir() + "michi-self-pairs-" + std::to_string(::getpid());
    std::filesystem::remove_all(dir);
    ::setenv("MICHI_CACHE_DIR", dir.c_str(), 1);
    const auto problem = tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/panda_table_pick.yaml");
    auto ctx = tools::makePlanningContext(problem);
    auto group = std::dynamic_pointer_cast<const RobotGroupBodies>(ctx.bodies);
    const auto model = SphereModel::enclose(*group->model());
    auto make = [&]
    {
        return std::make_shared<SphereValidityChecker>(ctx.setup->getSpaceInformation(), group, model, ctx.scene,
                                                       ctx.checker);
    };
    ompl::RNG rng(21);
    const auto &bounds = ctx.setup->getStateSpace()->as<ompl::base::RealVectorStateSpace>()->getBounds();
    std::vector<std::vector<double>> states;
    for (int i = 0; i < 3000; ++i)
    {
        std::vector<double> q;
        for (std::size_t d = 0; d < bounds.low.size(); ++d)
            q.push_back(rng.uniformReal(bounds.low[d], bounds.high[d]));
        states.push_back(q);
    }
    std::vector<char> built;
    {
        auto first = make();
        EXPECT_FALSE(first->selfPairTablesFromDisk());
        for (const auto &q : states)
            built.push_back(first->isValidConfiguration(q.data()));
    }  // the last user of the tables: the next checker cannot share them in memory
    std::vector<std::filesystem::path> files;
    for (const auto &entry : std::filesystem::directory_iterator(dir))
        files.push_back(entry.path());
    ASSERT_EQ(files.size(), 1u);
    {
        auto second = make();
        EXPECT_TRUE(second->selfPairTablesFromDisk());
        for (std::size_t i = 0; i < states.size(); ++i)
            ASSERT_EQ(second->isValidConfiguration(states[i].data()), built[i] != 0) << "state " << i;
    }
    // one byte flipped in the middle of the bits: the checksum refuses the file, the tables are built again
    {
        std::fstream f(files[0], std::ios::in | std::ios::out | std::ios::binary);
        const auto middle = static_cast<std::streamoff>(std::filesystem::file_size(files[0]) / 2);
        f.seekg(middle);
        const char byte = static_cast<char>(f.get());
        f.seekp(middle);
        f.put(static_cast<char>(~byte));
    }
    {
        auto third = make();
        EXPECT_FALSE(third->selfPairTablesFromDisk());
        for (std::size_t i = 0; i < states.size(); ++i)
            ASSERT_EQ(third->isValidConfiguration(states[i].data()), built[i] != 0) << "state " << i;
    }
    ::unsetenv("MICHI_CACHE_DIR");
    std::filesystem::remove_all(dir);
}
