// Tests of DualRoadmap's narrowing to the dominant degrees of freedom (paper 002, setDominantDofs): in R^6 the free
// space is a slab around a plane (|x_i - 0.5| <= 0.02 for i >= 2: a planar task seen by a 6-joint robot), and a wall
// in that plane appears after training. The local paths learnt in the slab span the plane; a query past the wall
// needs new states in the slab beyond the training region, which uniform samples (each in the slab with a chance of
// 0.04^4, 2.6e-6) never give, and samples along the dominant directions do (20 seeds tried: every one). Work is
// counted, never timed.
#include "support/CountedSolve.h"

#include <michi/planners/dual_roadmap/DualRoadmap.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace ob = ompl::base;

namespace
{
    struct Slab
    {
        bool wall{false};
        ob::SpaceInformationPtr si;
        std::shared_ptr<michi::planners::DualRoadmap> planner;

        explicit Slab(unsigned int dominantDofs)
        {
            ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
            auto space = std::make_shared<ob::RealVectorStateSpace>(6);
            space->setBounds(0., 1.);
            si = std::make_shared<ob::SpaceInformation>(space);
            si->setStateValidityChecker(
                [this](const ob::State *s)
                {
                    const double *x = s->as<ob::RealVectorStateSpace::StateType>()->values;
                    for (int i = 2; i < 6; ++i)
                        if (std::fabs(x[i] - 0.5) > 0.02)
                            return false;
                    // the wall: across the plane's first axis at 0.5, from its second axis' 0 to 0.6
                    return !(wall && x[0] >= 0.45 && x[0] <= 0.55 && x[1] <= 0.6);
                });
            si->setStateValidityCheckingResolution(0.002);
            si->setup();
            planner = std::make_shared<michi::planners::DualRoadmap>(si);
            planner->setDominantDofs(dominantDofs);
        }

        /** A query in the slab's middle plane; at most \e evaluations of the termination condition. */
        ob::PlannerStatus solve(double x0, double x1, double y0, double y1, unsigned long evaluations)
        {
            ob::ScopedState<> start(si), goal(si);
            for (unsigned int i = 2; i < 6; ++i)
                start[i] = goal[i] = 0.5;
            start[0] = x0;
            start[1] = x1;
            goal[0] = y0;
            goal[1] = y1;
            auto result = michi::test::solveCounted(*planner, start, goal, evaluations);
            path = result.path;
            valid = result.valid;
            return result.status;
        }

        /** Short queries in the plane's part below 0.55 on its second axis, before the wall: each solved by its
            direct motion, which the learning roadmap keeps. */
        void train()
        {
            ompl::RNG rng;
            for (int q = 0; q < 40; ++q)
            {
                const double x0 = rng.uniformReal(0.05, 0.95), x1 = rng.uniformReal(0.05, 0.55);
                const double y0 = std::clamp(x0 + rng.uniformReal(-0.3, 0.3), 0.05, 0.95);
                const double y1 = std::clamp(x1 + rng.uniformReal(-0.3, 0.3), 0.05, 0.55);
                ASSERT_EQ(solve(x0, x1, y0, y1, 100000), ob::PlannerStatus::EXACT_SOLUTION);
                planner->clear();
            }
        }

        ompl::geometric::PathGeometric path{si};
        bool valid{false};
    };
}  // namespace

TEST(DualRoadmapDominantDofs, SamplesAlongTheLearntPlaneFindTheWayAroundANewWall)
{
    ompl::RNG::setSeed(11);
    Slab narrowed(2);
    narrowed.train();
    ASSERT_GT(narrowed.planner->learningEdgeCount(), 20u);
    narrowed.wall = true;
    narrowed.planner->notifySceneChanged();
    ASSERT_EQ(narrowed.solve(0.2, 0.3, 0.8, 0.3, 50000), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_TRUE(narrowed.valid);
    double highest = 0.;
    for (std::size_t i = 0; i < narrowed.path.getStateCount(); ++i)
        highest = std::max(highest, narrowed.path.getState(i)->as<ob::RealVectorStateSpace::StateType>()->values[1]);
    EXPECT_GT(highest, 0.6) << "round the wall's end, beyond where it was trained";
    EXPECT_GT(narrowed.planner->lastWork().samples, 0u) << "the way needed new states";
}

TEST(DualRoadmapDominantDofs, UniformSamplesAloneDoNotFindIt)
{
    // the same training and query without the narrowing (the ablation): the same budget runs out
    ompl::RNG::setSeed(11);
    Slab uniform(0);
    uniform.train();
    uniform.wall = true;
    uniform.planner->notifySceneChanged();
    EXPECT_NE(uniform.solve(0.2, 0.3, 0.8, 0.3, 50000), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_GT(uniform.planner->lastWork().samples, 1000u);
}
