// The distance grid of a sphere-checker scene snapshot is a lower bound: no sphere of the radius it gives at a point
// touches any obstacle, and it is made only once a snapshot has served enough queries.
#include "../../validity/src/spheres/SphereObstacles.h"

#include <michi/tools/bench/PlanningContext.h>

#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <iostream>

using namespace michi;
using namespace michi::validity;

namespace
{
    class SphereObstacleGridOf : public ::testing::TestWithParam<std::string>
    {
    };
}  // namespace

TEST_P(SphereObstacleGridOf, BoundNeverReachesAnObstacle)
{
    const auto problem = tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/" + GetParam() + ".yaml");
    const auto ctx = tools::makePlanningContext(problem);
    const SphereObstacles obstacles(*ctx.scene);
    ASSERT_GT(obstacles.size(), 0u);
    // no grid before its queries: the bound says nothing
    EXPECT_EQ(obstacles.gridCells(), 0u);
    EXPECT_EQ(obstacles.distanceBound(Eigen::Vector3f::Zero()), -std::numeric_limits<float>::infinity());
    obstacles.makeGrid();
    ASSERT_GT(obstacles.gridCells(), 0u);
    ompl::RNG rng(7);
    int informative = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i)
    {
        // the robot's workspace and beyond the grid's box on every side
        const Eigen::Vector3f p(static_cast<float>(rng.uniformReal(-2., 2.)),
                                static_cast<float>(rng.uniformReal(-2., 2.)),
                                static_cast<float>(rng.uniformReal(-1., 3.)));
        const float bound = obstacles.distanceBound(p);
        if (bound <= 0.f)
            continue;
        ++informative;
        for (std::size_t o = 0; o < obstacles.size(); ++o)
            ASSERT_FALSE(obstacles.hitsSphere(static_cast<int>(o), p, bound))
                << "a sphere of radius " << bound << " at (" << p.transpose() << ") touches obstacle "
                << obstacles.name(static_cast<int>(o));
    }
    // a bound that is never positive would skip nothing
    EXPECT_GT(informative, n / 4);
    std::cout << GetParam() << ": " << obstacles.gridCells() << " grid cells, bound positive at " << informative
              << " of " << n << " points" << std::endl;
}

TEST(SphereObstacleGrid, MadeAfterEnoughQueriesInARow)
{
    const auto problem = tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/panda_table_pick.yaml");
    const auto ctx = tools::makePlanningContext(problem);
    const SphereObstacles obstacles(*ctx.scene);
    for (unsigned i = 1; i < SphereObstacles::GRID_AFTER; ++i)
        obstacles.distanceBound(Eigen::Vector3f::Zero());
    EXPECT_EQ(obstacles.gridCells(), 0u);
    obstacles.distanceBound(Eigen::Vector3f::Zero());
    EXPECT_GT(obstacles.gridCells(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Problems, SphereObstacleGridOf,
                         ::testing::Values("panda_table_pick", "xarm6_ring", "dynamic_reach_box", "arch_3dof"));
