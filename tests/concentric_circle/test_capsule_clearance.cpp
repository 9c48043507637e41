// The capsule clearance that ConcentricCircle's clearance push climbs (planners/src/concentric_circle/
// PathClearance.h) against FCL's clearance on the same states, FCL being the ground truth: never above it (each
// capsule contains its link's shadow) and at most a link radius below it (the capsule's rounded ends). And the push
// itself: asked for clearance, the planner's path is clearer for FCL (OMPL's waypoint clearance, as bench reports
// it) than the path it chose before pushing, and still valid.
#include "../../planners/src/concentric_circle/PathClearance.h"
#include "support/TestScenes.h"

#include <michi/planners/concentric_circle/ConcentricCircle.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <algorithm>

using namespace michi;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace
{
    tools::PlanningContext context(const std::string &name, const std::string &checker)
    {
        auto problem = tools::loadProblem(test::sourcePath("problems/" + name + ".yaml"));
        problem.checker = checker;
        auto ctx = tools::makePlanningContext(problem);
        ctx.setup->setup();
        return ctx;
    }

    /** OMPL's PathGeometric::clearance() (the mean of the checker's clearance over the waypoints; the column
        OMPL's Benchmark records and michi bench reports) */
    double waypointClearance(const ob::SpaceInformationPtr &si, const std::vector<ob::State *> &states)
    {
        og::PathGeometric path(si);
        for (auto *s : states)
            path.append(s);
        return path.clearance();
    }
}  // namespace

TEST(CapsuleClearance, BoundsFclClearanceFromBelowWithinALinkRadius)
{
    ompl::RNG::setSeed(7);
    for (const std::string checker : {"fcl", "jmap"})
    {
        auto ctx = context("planar_2link", checker);
        const auto si = ctx.setup->getSpaceInformation();
        const auto capsules = planners::CapsuleClearance::make(*si);
        ASSERT_TRUE(capsules) << "planar_2link is a planar arm among prisms (" << checker << ")";
        auto sampler = si->allocStateSampler();
        ob::State *s = si->allocState();
        std::vector<double> values;
        int valid = 0;
        double worstGap = 0.;
        for (int i = 0; i < 400; ++i)
        {
            sampler->sampleUniform(s);
            if (!si->isValid(s))
                continue;
            ++valid;
            si->getStateSpace()->copyToReals(values, s);
            const double fcl = si->getStateValidityChecker()->clearance(s);
            const double capsule = capsules->at(values.data());
            EXPECT_LE(capsule, fcl + 1e-9) << "state " << values[0] << ", " << values[1];
            // the links are cylinders of radius 0.01 m (problems/robots/planar_2link.urdf)
            EXPECT_GE(capsule, fcl - 0.01 - 1e-9) << "state " << values[0] << ", " << values[1];
            worstGap = std::max(worstGap, fcl - capsule);
        }
        EXPECT_GT(valid, 100);
        EXPECT_GT(worstGap, 0.) << "the rounded ends should make some state's capsule clearance smaller";
        si->freeState(s);
    }
}

TEST(CapsuleClearance, NoModelForARobotThatIsNotAPlanarArm)
{
    auto ctx = context("se2_corridor", "fcl");
    EXPECT_FALSE(planners::CapsuleClearance::make(*ctx.setup->getSpaceInformation()));
}

TEST(CapsuleClearance, ThePushRaisesTheChosenPathsClearance)
{
    auto ctx = context("planar_2link", "jmap");
    const auto si = ctx.setup->getSpaceInformation();
    auto pdef = ctx.setup->getProblemDefinition();
    pdef->setOptimizationObjective(std::make_shared<ob::MaximizeMinClearanceObjective>(si));
    auto planner = std::make_shared<planners::ConcentricCircle>(si);
    planner->setProblemDefinition(pdef);
    planner->setup();
    ASSERT_EQ(planner->solve(ob::timedPlannerTerminationCondition(10.)), ob::PlannerStatus::EXACT_SOLUTION);
    auto &chosen = *pdef->getSolutionPath()->as<og::PathGeometric>();
    // The search's path before the push: the lifted points of the chosen path of the last stage.
    const auto &stage = planner->stages().back();
    ASSERT_GE(stage.chosenPath, 0);
    std::vector<ob::State *> before;
    for (const auto &p : stage.search->pathPoints(static_cast<std::size_t>(stage.chosenPath)))
    {
        before.push_back(si->allocState());
        stage.lift(p, before.back());
    }
    const double pushed = waypointClearance(si, chosen.getStates());
    const double searched = waypointClearance(si, before);
    EXPECT_GT(pushed, searched + 0.01) << "pushed " << pushed << " m, searched " << searched << " m";
    for (std::size_t i = 1; i < chosen.getStateCount(); ++i)
        EXPECT_TRUE(si->checkMotion(chosen.getState(i - 1), chosen.getState(i))) << "segment " << i;
    for (auto *s : before)
        si->freeState(s);
}
