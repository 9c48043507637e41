// Paper 000's arm -> hand split for three joints (planar_3dof_hand): the arm is planned on its J-map (the polygons of
// the arm's links without the hand), the grown map (obstacles grown by the hand's reach) says where the hand can
// touch an obstacle at all, and the hand map spans only the stretch of the arm path in it (the bottleneck). FCL is the
// ground truth for the grown map's claim: an arm configuration outside it keeps the robot off every obstacle at every
// hand value (self-collisions, e.g. the hand folded onto link 1, are not the grown map's business: the planner's
// motion checks and final check see them).
#include "support/TestScenes.h"

#include <michi/planners/concentric_circle/CircleLifts.h>
#include <michi/planners/concentric_circle/ConcentricCircle.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>
#include <michi/validity/fcl/FclValidityChecker.h>

#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace michi;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace
{
    struct Hierarchy
    {
        tools::Problem problem;
        tools::PlanningContext ctx;
        std::shared_ptr<planners::ConcentricCircle> planner;
        ob::PlannerStatus status;
    };

    Hierarchy solve(const std::map<std::string, std::string> &params)
    {
        Hierarchy h{tools::loadProblem(test::sourcePath("problems/planar_3dof_hand.yaml")), {}, nullptr, {}};
        h.ctx = tools::makePlanningContext(h.problem);
        h.planner = std::make_shared<planners::ConcentricCircle>(h.ctx.setup->getSpaceInformation());
        for (const auto &p : params)
            EXPECT_TRUE(h.planner->params().setParam(p.first, p.second)) << p.first;
        h.ctx.setup->setPlanner(h.planner);
        h.status = h.ctx.setup->solve(30.);
        return h;
    }
}  // namespace

TEST(ConcentricCircleHierarchy, ArmOnItsJMapAndHandOnlyOverTheBottleneck)
{
    auto h = solve({});
    ASSERT_EQ(h.status, ob::PlannerStatus::EXACT_SOLUTION);
    ASSERT_EQ(h.planner->usedMode(), "hierarchy");
    EXPECT_EQ(h.planner->armMapKind(), "jmap");
    ASSERT_EQ(h.planner->stages().size(), 2u);
    const auto &arm = h.planner->stages()[0];
    const auto &hand = h.planner->stages()[1];
    EXPECT_NE(dynamic_cast<const planners::PolygonCircleMap *>(arm.map.get()), nullptr)
        << "the arm is searched on the J-map polygons";
    // The start (arm folded below the wall) is far from every obstacle: the hand map begins later along the arm
    // path, where the arm enters the grown map; the goal (link 2 in the slot) is inside it, so the map ends at the
    // path's end.
    ASSERT_GE(arm.chosenPath, 0);
    const auto armPath = arm.search->pathPoints(static_cast<std::size_t>(arm.chosenPath));
    double length = 0.;
    for (std::size_t i = 1; i < armPath.size(); ++i)
        length += (armPath[i] - armPath[i - 1]).norm();
    EXPECT_GT(hand.map->lo.x(), 0.05 * length) << "hand map from " << hand.map->lo.x() << " of " << length;
    EXPECT_NEAR(hand.map->hi.x(), length, 1e-6);
    // the full path is valid for the space's motion validator, before, in and after the window
    const auto si = h.ctx.setup->getSpaceInformation();
    const auto &path = h.ctx.setup->getSolutionPath();
    for (std::size_t i = 1; i < path.getStateCount(); ++i)
        EXPECT_TRUE(si->checkMotion(path.getState(i - 1), path.getState(i))) << "segment " << i;

    // the switches: the whole arm path for the hand, the capsule geometry for the arm
    auto whole = solve({{"hand_in_bottleneck", "0"}, {"arm_slices", "0"}});
    ASSERT_EQ(whole.status, ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(whole.planner->armMapKind(), "capsules");
    ASSERT_EQ(whole.planner->stages().size(), 2u);
    EXPECT_EQ(whole.planner->stages()[1].map->lo.x(), 0.);
}

TEST(ConcentricCircleHierarchy, OutsideTheGrownMapNoHandValueTouchesAnObstacle)
{
    ompl::RNG::setSeed(3);
    auto problem = tools::loadProblem(test::sourcePath("problems/planar_3dof_hand.yaml"));
    auto ctx = tools::makePlanningContext(problem);
    ctx.setup->setup();
    const auto si = ctx.setup->getSpaceInformation();
    std::vector<double> start, goal;
    si->getStateSpace()->copyToReals(start, ctx.setup->getProblemDefinition()->getStartState(0));
    goal = {0.927, 0.619, -1.7};  // problems/planar_3dof_hand.yaml
    planners::ProjectionLift lift(si, start, goal, 0, 1);
    const auto maps = planners::makeArmMaps(si, lift, {2}, 720, 0.01);
    ASSERT_TRUE(maps.inGrown) << "a planar arm with a hand has a grown map";
    ompl::RNG rng;
    const auto fcl = std::dynamic_pointer_cast<validity::FclValidityChecker>(si->getStateValidityChecker());
    ASSERT_TRUE(fcl);
    int outside = 0, inside = 0;
    for (int i = 0; i < 300; ++i)
    {
        const Eigen::Vector2d q(rng.uniformReal(-M_PI, M_PI), rng.uniformReal(-M_PI, M_PI));
        if (!maps.map->isFree(q))
            continue;
        if (maps.inGrown(q))
        {
            ++inside;
            continue;
        }
        ++outside;
        for (double hand = -M_PI; hand <= M_PI; hand += 0.05)
        {
            const double values[3] = {q.x(), q.y(), hand};
            // robot against obstacles only (self pairs left out)
            EXPECT_GT(fcl->proximity(values, false).distance, 0.)
                << "arm (" << q.x() << ", " << q.y() << ") outside the grown map, hand " << hand;
        }
    }
    EXPECT_GT(outside, 20);
    EXPECT_GT(inside, 20);
}
