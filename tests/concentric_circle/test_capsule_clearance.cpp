// The capsule clearance that ConcentricCircle's clearance push climbs (planners/src/concentric_circle/
// PathClearance.h) against FCL's clearance on the same states, FCL being the ground truth: never above it (each
// capsule contains its link's shadow) and at most a link radius below it (the capsule's rounded ends). And the push
// itself: asked for clearance, the planner's path is clearer for FCL (OMPL's waypoint clearance, as bench reports
// it) than the path it chose before pushing, and still valid; a direct start-goal link is cut into pieces first, so
// that it bends away from the obstacles too.
#include "../../planners/src/concentric_circle/PathClearance.h"
#include "support/TestScenes.h"

#include <michi/planners/concentric_circle/ConcentricCircle.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>
#include <michi/tools/problem/RandomPlanarScene.h>

#include <ompl/base/goals/GoalState.h>
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

    /** ConcentricCircle asked for clearance (the problem's objective, as michi bench --objective clearance sets
        it) on \e ctx's problem; its solution path. */
    std::shared_ptr<planners::ConcentricCircle> solveForClearance(tools::PlanningContext &ctx)
    {
        const auto si = ctx.setup->getSpaceInformation();
        auto pdef = ctx.setup->getProblemDefinition();
        pdef->setOptimizationObjective(std::make_shared<ob::MaximizeMinClearanceObjective>(si));
        auto planner = std::make_shared<planners::ConcentricCircle>(si);
        planner->setProblemDefinition(pdef);
        planner->setup();
        EXPECT_EQ(planner->solve(ob::timedPlannerTerminationCondition(10.)), ob::PlannerStatus::EXACT_SOLUTION);
        return planner;
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
    const auto planner = solveForClearance(ctx);
    ASSERT_TRUE(pdef->hasExactSolution());
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

namespace
{
    /** The checker's clearance averaged over the path's length (sampled every 0.005 rad), and its smallest value. */
    std::pair<double, double> clearanceAlong(const ob::SpaceInformationPtr &si, const std::vector<ob::State *> &states)
    {
        ob::State *t = si->allocState();
        double sum = 0., length = 0., least = std::numeric_limits<double>::infinity();
        for (std::size_t j = 1; j < states.size(); ++j)
        {
            const double d = si->distance(states[j - 1], states[j]);
            const int m = std::max(1, static_cast<int>(std::ceil(d / 0.005)));
            for (int k = 0; k < m; ++k)
            {
                si->getStateSpace()->interpolate(states[j - 1], states[j], (k + 0.5) / m, t);
                const double c = si->getStateValidityChecker()->clearance(t);
                sum += c * d / m;
                least = std::min(least, c);
            }
            length += d;
        }
        si->freeState(t);
        return {sum / length, least};
    }
}  // namespace

TEST(CapsuleClearance, ADirectLinkIsCutAndBentAwayFromTheObstacles)
{
    // Random scene 228 of planar_2link (michi random-scenes --seed 228): start and goal see each other, so the
    // search links them directly; asked for clearance, that link is cut into pieces and pushed. Along the path the
    // clearance averages about twice the straight link's (0.092 -> 0.180 m when measured), never less at any
    // point than the straight link's smallest, and every motion is valid.
    ompl::RNG::setSeed(5);
    auto arm = tools::loadProblem(test::sourcePath("problems/planar_2link.yaml"));
    auto scene = tools::randomPlanarScene(arm, 228);
    scene.problem.checker = "jmap";
    auto ctx = tools::makePlanningContext(scene.problem);
    ctx.setup->setup();
    const auto si = ctx.setup->getSpaceInformation();
    auto pdef = ctx.setup->getProblemDefinition();
    std::vector<ob::State *> direct{si->cloneState(pdef->getStartState(0)), si->allocState()};
    si->copyState(direct[1], pdef->getGoal()->as<ob::GoalState>()->getState());
    ASSERT_TRUE(si->checkMotion(direct[0], direct[1]));  // the scene still has a direct link
    solveForClearance(ctx);
    ASSERT_TRUE(pdef->hasExactSolution());
    auto &chosen = *pdef->getSolutionPath()->as<og::PathGeometric>();
    ASSERT_GT(chosen.getStateCount(), 2u);
    for (std::size_t i = 1; i < chosen.getStateCount(); ++i)
        EXPECT_TRUE(si->checkMotion(chosen.getState(i - 1), chosen.getState(i))) << "segment " << i;
    const auto straight = clearanceAlong(si, direct);
    const auto bent = clearanceAlong(si, chosen.getStates());
    EXPECT_GT(bent.first, 1.5 * straight.first) << bent.first << " against " << straight.first;
    EXPECT_GE(bent.second, straight.second - 1e-9);
    for (auto *s : direct)
        si->freeState(s);
}

TEST(CapsuleClearance, SplitDirectLinkCutsOnlyASingleMotion)
{
    auto ctx = context("planar_2link", "jmap");
    const auto si = ctx.setup->getSpaceInformation();
    std::vector<ob::State *> link{si->cloneState(ctx.setup->getProblemDefinition()->getStartState(0)),
                                  si->cloneState(ctx.setup->getProblemDefinition()->getStartState(0))};
    std::vector<double> v;
    si->getStateSpace()->copyToReals(v, link[1]);
    v[1] += 0.5;  // joint 2 bent further: a short motion the arm can make where it starts
    si->getStateSpace()->copyFromReals(link[1], v);
    ASSERT_TRUE(si->checkMotion(link[0], link[1]));
    const double piece = 0.05 * si->getMaximumExtent();
    const std::size_t added = planners::splitDirectLink(si, link);
    EXPECT_EQ(added, static_cast<std::size_t>(std::ceil(0.5 / piece)) - 1);
    ASSERT_EQ(link.size(), added + 2);
    for (std::size_t j = 1; j < link.size(); ++j)
        EXPECT_NEAR(si->distance(link[j - 1], link[j]), 0.5 / (added + 1), 1e-9);
    EXPECT_EQ(planners::splitDirectLink(si, link), 0u);  // interior states already: left alone
    for (auto *s : link)
        si->freeState(s);
}
