// ConcentricCircle on 50 random planar scenes (label `slow`): each scene (6 random polygons, a 0.5 m + 0.4 m arm,
// fixed seeds 1..50) gets a start and a goal whose straight motion collides and that a grid search (0.05 rad
// cells over the whole C-space, neighbours joined by valid motions) proves linked. ConcentricCircle must solve
// every one, with paths that pass the motion validator and, finely interpolated, the exact FCL checker.
// MICHI_CC_SET="name=value,..." sets planner parameters (for ablations, e.g. point_spacing=0: the test then
// reports how many scenes the changed planner solves).
#include "support/GridReachability.h"

#include <michi/planners/concentric_circle/ConcentricCircle.h>

#include <ompl/geometric/SimpleSetup.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <iostream>

using namespace michi;
namespace ob = ompl::base;
namespace og = ompl::geometric;

TEST(ConcentricCircleScenes, SolvesFiftyScenesTheGridSolves)
{
    int scenes = 0, solved = 0;
    double seconds = 0.;
    for (unsigned int seed = 1; scenes < 50 && seed <= 80; ++seed)
    {
        const auto q = test::reachableArmQuery(seed);
        if (!q.found)
            continue;
        ++scenes;
        const auto ss = test::armQuerySetup(q);
        auto planner = std::make_shared<planners::ConcentricCircle>(ss->getSpaceInformation());
        if (const char *set = std::getenv("MICHI_CC_SET"))
        {
            std::stringstream in(set);
            std::string kv;
            while (std::getline(in, kv, ','))
                ASSERT_TRUE(planner->params().setParam(kv.substr(0, kv.find('=')), kv.substr(kv.find('=') + 1))) << kv;
        }
        ss->setPlanner(planner);
        const auto status = ss->solve(60.);
        seconds += ss->getLastPlanComputationTime();
        EXPECT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << "scene " << seed;
        if (status != ob::PlannerStatus::EXACT_SOLUTION)
            continue;
        const auto &path = ss->getSolutionPath();
        bool ok = true;
        for (std::size_t i = 1; i < path.getStateCount(); ++i)
            ok = ok && q.setup.si->checkMotion(path.getState(i - 1), path.getState(i));
        og::PathGeometric fine(path);
        fine.interpolate(static_cast<unsigned int>(std::ceil(path.length() / 0.005)) + path.getStateCount());
        for (std::size_t i = 0; i < fine.getStateCount(); ++i)
            ok = ok && q.setup.checker->isValid(fine.getState(i));
        EXPECT_TRUE(ok) << "scene " << seed;
        solved += ok ? 1 : 0;
    }
    EXPECT_EQ(scenes, 50);
    EXPECT_EQ(solved, scenes);
    std::cout << "ConcentricCircle solved " << solved << " of " << scenes << " grid-solvable scenes, "
              << seconds / std::max(1, scenes) << " s per scene on average" << std::endl;
}
