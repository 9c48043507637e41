// michi::planners::ConcentricCircle (paper 000): the bundled planar problems (the 3-joint one through the arm ->
// hand hierarchy), determinism, honest failure, continuous joints, and random planar scenes that a grid search
// proves solvable (5 here; 50 in slow_concentric_circle_scenes.cpp). Every path is re-checked: each segment by
// the space's motion validator and, interpolated at 1/10 of the validity resolution, by the exact FCL checker.
#include "support/GridReachability.h"
#include "support/TestScenes.h"

#include <michi/planners/concentric_circle/ConcentricCircle.h>
#include <michi/tools/pictures/CirclePicture.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>
#include <michi/validity/jmap/JMapValidityChecker.h>

#include <ompl/base/PlannerData.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <Eigen/SVD>

using namespace michi;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace
{
    /** empty when every segment passes the motion validator and every interpolated state the exact checker */
    std::string exactCheck(const ob::SpaceInformationPtr &si, const ob::StateValidityChecker &exact,
                           const og::PathGeometric &path)
    {
        for (std::size_t i = 1; i < path.getStateCount(); ++i)
            if (!si->checkMotion(path.getState(i - 1), path.getState(i)))
                return "segment " + std::to_string(i) + " rejected by the motion validator";
        og::PathGeometric fine(path);
        const double step = si->getStateValidityCheckingResolution() * si->getMaximumExtent() / 10.;
        fine.interpolate(static_cast<unsigned int>(std::ceil(path.length() / step)) + path.getStateCount());
        for (std::size_t i = 0; i < fine.getStateCount(); ++i)
            if (!exact.isValid(fine.getState(i)))
                return "interpolated state " + std::to_string(i) + " collides";
        return "";
    }

    struct Run
    {
        tools::Problem problem;
        tools::PlanningContext ctx;
        std::shared_ptr<planners::ConcentricCircle> planner;
        ob::PlannerStatus status;
    };

    Run planProblem(const std::string &name, const std::string &checker = "")
    {
        Run r{tools::loadProblem(test::sourcePath("problems/" + name + ".yaml")), {}, nullptr, {}};
        if (!checker.empty())
            r.problem.checker = checker;
        r.ctx = tools::makePlanningContext(r.problem);
        r.planner = std::make_shared<planners::ConcentricCircle>(r.ctx.setup->getSpaceInformation());
        r.ctx.setup->setPlanner(r.planner);
        r.status = r.ctx.setup->solve(20.);
        return r;
    }

    std::vector<std::vector<double>> pathValues(const ob::SpaceInformationPtr &si, const og::PathGeometric &path)
    {
        std::vector<std::vector<double>> out;
        for (std::size_t i = 0; i < path.getStateCount(); ++i)
        {
            out.emplace_back();
            si->getStateSpace()->copyToReals(out.back(), path.getState(i));
        }
        return out;
    }
}  // namespace

TEST(ConcentricCircle, SolvesPlanar2Link)
{
    auto r = planProblem("planar_2link");
    ASSERT_EQ(r.status, ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(r.planner->usedMode(), "projection");
    const auto si = r.ctx.setup->getSpaceInformation();
    EXPECT_EQ(exactCheck(si, *r.ctx.checker, r.ctx.setup->getSolutionPath()), "");
    ASSERT_EQ(r.planner->stages().size(), 1u);
    const auto &search = *r.planner->stages()[0].search;
    EXPECT_GT(search.rings().size(), 5u);
    EXPECT_FALSE(search.paths().empty());
    // every path kept is a chain of links from the start (node 0) to the goal (node 1), and all are valid
    for (const auto &p : r.planner->fullPaths())
    {
        og::PathGeometric path(si);
        for (auto *s : p)
            path.append(s);
        EXPECT_EQ(exactCheck(si, *r.ctx.checker, path), "");
    }
    ob::PlannerData data(si);
    r.planner->getPlannerData(data);
    EXPECT_EQ(data.numVertices(), search.nodes().size());
    EXPECT_EQ(data.numEdges(), 2 * search.links().size());
}

TEST(ConcentricCircle, PlansOnTheJMapPolygonsWithTheJMapChecker)
{
    auto r = planProblem("planar_2link", "jmap");
    ASSERT_EQ(r.status, ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(r.planner->usedMode(), "jmap");
    ASSERT_EQ(r.planner->stages().size(), 1u);
    EXPECT_NE(dynamic_cast<const planners::PolygonCircleMap *>(r.planner->stages()[0].map.get()), nullptr);
    EXPECT_EQ(exactCheck(r.ctx.setup->getSpaceInformation(), *r.ctx.checker, r.ctx.setup->getSolutionPath()), "");
}

TEST(ConcentricCircle, UnitesTheJMapPolygonsOncePerCheckerNotPerSolve)
{
    // The J-map mode's map depends on the checker only: its polygons are united in setup(), not in every solve
    // (solve() once made a second map just to see whether the mode applies: a sixth of a planar_2link solve).
    auto r = planProblem("planar_2link", "jmap");
    ASSERT_EQ(r.status, ob::PlannerStatus::EXACT_SOLUTION);
    const auto *checker =
        dynamic_cast<const validity::JMapValidityChecker *>(r.ctx.setup->getStateValidityChecker().get());
    ASSERT_NE(checker, nullptr);
    EXPECT_EQ(checker->unionsMade(), 1u);
    const auto first = r.planner->stages()[0].map;
    for (int i = 0; i < 3; ++i)
    {
        r.planner->clear();
        r.ctx.setup->getProblemDefinition()->clearSolutionPaths();
        ASSERT_EQ(r.planner->solve(ob::timedPlannerTerminationCondition(20.)), ob::PlannerStatus::EXACT_SOLUTION);
        EXPECT_EQ(r.planner->usedMode(), "jmap");
        EXPECT_EQ(r.planner->stages()[0].map, first);
    }
    EXPECT_EQ(checker->unionsMade(), 1u);
}

TEST(ConcentricCircle, SolvesPlanar3dofHandThroughTheHierarchy)
{
    auto r = planProblem("planar_3dof_hand");
    ASSERT_EQ(r.status, ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(r.planner->usedMode(), "hierarchy");
    ASSERT_EQ(r.planner->stages().size(), 2u);
    EXPECT_EQ(r.planner->stages()[0].name, "arm");
    EXPECT_EQ(r.planner->stages()[1].name, "hand");
    EXPECT_EQ(exactCheck(r.ctx.setup->getSpaceInformation(), *r.ctx.checker, r.ctx.setup->getSolutionPath()), "");
}

TEST(ConcentricCircle, SolvesArch3dofOnTheRestrictionSurface)
{
    auto r = planProblem("arch_3dof");
    ASSERT_EQ(r.status, ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(r.planner->usedMode(), "surface");
    const auto si = r.ctx.setup->getSpaceInformation();
    // the straight joint motion collides: the path leaves the start-goal line
    EXPECT_FALSE(si->checkMotion(r.ctx.setup->getProblemDefinition()->getStartState(0),
                                 r.ctx.setup->getSolutionPath().getStates().back()));
    EXPECT_GT(r.ctx.setup->getSolutionPath().getStateCount(), 2u);
    EXPECT_EQ(exactCheck(si, *r.ctx.checker, r.ctx.setup->getSolutionPath()), "");
    // every state lies on the plane through start and goal: a combination of start, goal - start and one more
    // direction, so the path's states span at most a 2-D affine subspace
    const auto values = pathValues(si, r.ctx.setup->getSolutionPath());
    Eigen::MatrixXd m(values.size() - 1, 3);
    for (std::size_t i = 1; i < values.size(); ++i)
        for (int j = 0; j < 3; ++j)
            m(i - 1, j) = values[i][j] - values[0][j];
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(m);
    EXPECT_LT(svd.singularValues()(2), 1e-9);
}

TEST(ConcentricCircle, SameProblemTwiceGivesTheSamePath)
{
    for (const std::string name : {"planar_2link", "planar_3dof_hand", "arch_3dof"})
    {
        auto a = planProblem(name);
        auto b = planProblem(name);
        ASSERT_EQ(a.status, ob::PlannerStatus::EXACT_SOLUTION) << name;
        ASSERT_EQ(b.status, ob::PlannerStatus::EXACT_SOLUTION) << name;
        EXPECT_EQ(pathValues(a.ctx.setup->getSpaceInformation(), a.ctx.setup->getSolutionPath()),
                  pathValues(b.ctx.setup->getSpaceInformation(), b.ctx.setup->getSolutionPath()))
            << name;
    }
}

TEST(ConcentricCircle, ReportsFailureWhenAWallCutsTheMap)
{
    auto space = std::make_shared<ob::RealVectorStateSpace>(2);
    space->setBounds(-1., 1.);
    og::SimpleSetup ss(space);
    ss.setStateValidityChecker(
        [](const ob::State *s)
        {
            return std::abs(s->as<ob::RealVectorStateSpace::StateType>()->values[0]) > 0.1;
        });
    ob::ScopedState<> start(space), goal(space);
    start[0] = -0.5;
    start[1] = 0.;
    goal[0] = 0.5;
    goal[1] = 0.2;
    ss.setStartAndGoalStates(start, goal);
    auto planner = std::make_shared<planners::ConcentricCircle>(ss.getSpaceInformation());
    planner->setMaxRecursions(3);
    ss.setPlanner(planner);
    const auto status = ss.solve(30.);
    EXPECT_EQ(status, ob::PlannerStatus::ABORT);  // gave up, did not run out of time
    EXPECT_EQ(planner->stages().at(0).search->recursions(), 3);

    // the same map with a gap in the wall is solved
    ss.clear();
    ss.setStateValidityChecker(
        [](const ob::State *s)
        {
            const auto *v = s->as<ob::RealVectorStateSpace::StateType>()->values;
            return std::abs(v[0]) > 0.1 || std::abs(v[1] + 0.6) < 0.1;
        });
    ASSERT_EQ(ss.solve(30.), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_TRUE(ss.getSolutionPath().check());
}

TEST(ConcentricCircle, ContinuousJointsWrap)
{
    // a continuous 2-link arm; a post blocks the way through zero, the way round through +-pi is free
    test::PlanarArmOptions options;
    options.continuous = true;
    const auto setup = test::planarArmSetup({0.5, 0.4}, {test::boxOutline({0.35, -0.08}, {0.6, 0.08})}, options);
    og::SimpleSetup ss(setup.si);
    ob::ScopedState<> start(setup.si->getStateSpace()), goal(setup.si->getStateSpace());
    std::vector<double> s{-1.2, 0.}, g{1.2, 0.};
    setup.si->getStateSpace()->copyFromReals(start.get(), s);
    setup.si->getStateSpace()->copyFromReals(goal.get(), g);
    ss.setStartAndGoalStates(start, goal);
    auto planner = std::make_shared<planners::ConcentricCircle>(ss.getSpaceInformation());
    ss.setPlanner(planner);
    ASSERT_EQ(ss.solve(20.), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(exactCheck(setup.si, *setup.checker, ss.getSolutionPath()), "");
}

TEST(ConcentricCircle, SolvesRandomScenesTheGridSolves)
{
    int tried = 0;
    for (unsigned int seed = 1; seed <= 5; ++seed)
    {
        const auto q = test::reachableArmQuery(seed);
        if (!q.found)
            continue;
        ++tried;
        const auto ss = test::armQuerySetup(q);
        auto planner = std::make_shared<planners::ConcentricCircle>(ss->getSpaceInformation());
        ss->setPlanner(planner);
        const auto status = ss->solve(30.);
        if (status != ob::PlannerStatus::EXACT_SOLUTION && std::getenv("MICHI_CC_DEBUG"))
        {
            tools::CirclePictureOptions o;
            o.view = {-M_PI, -M_PI, M_PI, M_PI};
            o.background = 200;
            tools::writeCircleSvg(planner->stages()[0], "/tmp/ccdbg/scene" + std::to_string(seed) + ".svg", o);
            std::cout << "start " << q.start[0] << " " << q.start[1] << " goal " << q.goal[0] << " " << q.goal[1]
                      << std::endl;
        }
        ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << "scene " << seed;
        EXPECT_EQ(exactCheck(q.setup.si, *q.setup.checker, ss->getSolutionPath()), "") << "scene " << seed;
    }
    EXPECT_GE(tried, 4);
}

TEST(ConcentricCircle, StopsItsLinkChecksAndItsArmJMapWhenTimeIsUp)
{
    // Found by a sweep of every planner setting at its declared limits: with ring_spacing 0.005 the checked search
    // went on with its motion checks after the time was up (2.9 s past a 0.5 s limit), and with arm_slices 100,000
    // the arm's J-map was built to its end (5 s). A condition that turns true after a count of evaluations stands in
    // for the clock, so the test does not depend on this machine's speed.
    {
        auto problem = tools::loadProblem(test::sourcePath("problems/planar_2link.yaml"));
        auto ctx = tools::makePlanningContext(problem);
        const auto si = ctx.setup->getSpaceInformation();
        auto planner = std::make_shared<planners::ConcentricCircle>(si);
        planner->params().setParam("ring_spacing", "0.005");
        planner->setProblemDefinition(ctx.setup->getProblemDefinition());
        planner->setup();
        const auto &validator = *si->getMotionValidator();
        const unsigned int before = validator.getCheckedMotionCount();
        // the time runs out once 100 links have been checked: in the middle of the checked search (it checks
        // about 2,700 on its way), which reads the condition before each link check
        const ob::PlannerTerminationCondition ptc(
            [&]
            {
                return validator.getCheckedMotionCount() - before >= 100;
            });
        EXPECT_EQ(planner->solve(ptc), ob::PlannerStatus::TIMEOUT);
        EXPECT_LE(validator.getCheckedMotionCount() - before, 101u) << "links checked after the time was up";
    }
    {
        auto problem = tools::loadProblem(test::sourcePath("problems/planar_3dof_hand.yaml"));
        auto ctx = tools::makePlanningContext(problem);
        auto planner = std::make_shared<planners::ConcentricCircle>(ctx.setup->getSpaceInformation());
        planner->params().setParam("arm_slices", "100000");
        planner->setProblemDefinition(ctx.setup->getProblemDefinition());
        planner->setup();
        int evaluations = 0;
        const ob::PlannerTerminationCondition ptc(
            [&]
            {
                return ++evaluations > 1;
            });
        EXPECT_EQ(planner->solve(ptc), ob::PlannerStatus::TIMEOUT);
        EXPECT_TRUE(planner->stages().empty()) << "the search ran on a map built after the time was up";
    }
}
