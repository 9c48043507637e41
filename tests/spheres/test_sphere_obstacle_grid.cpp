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
        // clears() is the same test without the square root: it answers as the bound for every radius (rounding
        // aside, within a hundredth of a millimetre of the bound)
        for (const float r : {0.f, 0.05f, 0.2f, bound - 2e-5f, bound + 2e-5f})
            if (std::abs(bound - r) > 1e-5f)
                ASSERT_EQ(obstacles.clears(p, r), bound > r) << "radius " << r << " at (" << p.transpose() << ")";
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

// Where a mesh's own field answers (a sphere clear of the ring's triangles, or into them, by more than a field cell),
// the answer must be the tree walk's: a snapshot with its grid and fields made and one without (which walks every
// time) agree on every sphere, also for spheres whose surface lies within a few millimetres of the mesh.
TEST(SphereObstacleGrid, MeshFieldAnswersAsTheTreeWalk)
{
    const auto problem = tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/xarm6_ring.yaml");
    const auto ctx = tools::makePlanningContext(problem);
    const SphereObstacles withField(*ctx.scene), walkOnly(*ctx.scene);
    withField.makeGrid();
    ASSERT_GT(withField.gridCells(), 0u);
    ASSERT_EQ(walkOnly.gridCells(), 0u);
    ompl::RNG rng(11);
    int hits = 0, misses = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i)
    {
        // around the ring (0.4 m in front of the arm, 0.35 m high) and beyond the field's box
        const Eigen::Vector3f p(static_cast<float>(rng.uniformReal(0.0, 0.8)),
                                static_cast<float>(rng.uniformReal(-0.4, 0.4)),
                                static_cast<float>(rng.uniformReal(0.0, 0.7)));
        const float r = static_cast<float>(rng.uniformReal(0.0, 0.2));
        for (std::size_t o = 0; o < withField.size(); ++o)
        {
            const bool a = withField.hitsSphere(static_cast<int>(o), p, r);
            ASSERT_EQ(a, walkOnly.hitsSphere(static_cast<int>(o), p, r))
                << "sphere of radius " << r << " at (" << p.transpose() << "), obstacle "
                << withField.name(static_cast<int>(o));
            (a ? hits : misses) += 1;
        }
    }
    // both answers occur many times (the comparison is not one-sided)
    EXPECT_GT(hits, n / 20);
    EXPECT_GT(misses, n / 20);
}

INSTANTIATE_TEST_SUITE_P(Problems, SphereObstacleGridOf,
                         ::testing::Values("panda_table_pick", "xarm6_ring", "dynamic_reach_box", "arch_3dof"));
