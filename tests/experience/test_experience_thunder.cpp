// experience::Thunder (OMPL's ThunderDB on a SPARSdb roadmap + ThunderRetrieveRepair racing RRT-Connect, as michi
// wraps it for michi bench): trained on solved queries, it plans a held-out query, and its roadmap survives clear()
// as OMPL's Benchmark calls it before every run.
#include "support/ConformanceProblem.h"

#include <michi/planners/experience/ExperiencePeers.h>

#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace
{
    void setQuery(const og::SimpleSetupPtr &setup, const std::vector<double> &s, const std::vector<double> &g)
    {
        ob::ScopedState<> start(setup->getStateSpace()), goal(setup->getStateSpace());
        start = s;
        goal = g;
        setup->setStartAndGoalStates(start, goal);
    }
}  // namespace

TEST(ExperienceThunder, TrainedItSolvesAHeldOutQueryAndKeepsItsRoadmapThroughClear)
{
    ompl::RNG::setSeed(7);
    auto problem = michi::test::makeConformanceProblem();
    const auto &setup = problem.setup;
    auto si = setup->getSpaceInformation();

    // training: RRT-Connect solutions of queries on both sides of the obstacle, simplified
    const std::vector<std::pair<std::vector<double>, std::vector<double>>> training = {
        {{0.2, 0.3}, {1.2, -0.4}}, {{0.15, 0.35}, {1.25, -0.35}}, {{0.25, 0.2}, {1.1, -0.45}}};
    std::vector<og::PathGeometric> paths;
    for (const auto &q : training)
    {
        setQuery(setup, q.first, q.second);
        setup->setPlanner(std::make_shared<og::RRTConnect>(si));
        ASSERT_EQ(setup->solve(10.), ob::PlannerStatus::EXACT_SOLUTION);
        og::PathGeometric path(setup->getSolutionPath());
        og::PathSimplifier(si).simplifyMax(path);
        ASSERT_TRUE(path.check());
        paths.push_back(path);
    }

    auto thunder = std::make_shared<michi::planners::ThunderPlanner>(si);
    EXPECT_EQ(thunder->experienceCount(), 0u);
    for (const auto &path : paths)
        thunder->addExperience(path);
    EXPECT_EQ(thunder->experienceCount(), paths.size());
    EXPECT_GT(thunder->connectedExperienceCount(), 0u);
    const std::size_t learned = thunder->experienceCount();

    // a held-out query (not trained), twice, with clear() before each as OMPL's Benchmark does
    setQuery(setup, {0.22, 0.28}, {1.18, -0.38});
    setup->setPlanner(thunder);
    for (int run = 0; run < 2; ++run)
    {
        thunder->clear();
        setup->getProblemDefinition()->clearSolutionPaths();
        EXPECT_EQ(thunder->experienceCount(), learned) << "run " << run;
        ASSERT_EQ(setup->solve(10.), ob::PlannerStatus::EXACT_SOLUTION) << "run " << run;
        const auto &solution = setup->getSolutionPath();
        EXPECT_TRUE(solution.check()) << "run " << run;
        EXPECT_EQ(michi::test::independentPathCheck(solution), "") << "run " << run;
    }
    // the retrieve-repair planner's roadmap (SPARSdb) and the racer's tree are exported
    ob::PlannerData data(si);
    thunder->getPlannerData(data);
    EXPECT_GT(data.numVertices(), 0u);
}

// A goal the checker rejects (the sphere checker's grasp goals): OMPL 1.5.2's retrieve-repair planners hand the null
// goal PlannerInputStates gives them to the database and crash; the race must not run them, and report the goal.
TEST(ExperienceThunder, AnInvalidGoalIsReportedNotACrash)
{
    ompl::RNG::setSeed(7);
    auto problem = michi::test::makeConformanceProblem();
    const auto &setup = problem.setup;
    auto si = setup->getSpaceInformation();
    setQuery(setup, {0.2, 0.3}, {1.2, -0.4});
    setup->setPlanner(std::make_shared<og::RRTConnect>(si));
    ASSERT_EQ(setup->solve(10.), ob::PlannerStatus::EXACT_SOLUTION);
    const og::PathGeometric trained(setup->getSolutionPath());

    // a goal in collision: the first of a scan of the joint square that the checker refuses
    std::vector<double> blocked;
    ob::ScopedState<> probe(setup->getStateSpace());
    for (double a = -3.; a <= 3. && blocked.empty(); a += 0.05)
        for (double b = -3.; b <= 3. && blocked.empty(); b += 0.05)
        {
            probe = std::vector<double>{a, b};
            if (!si->isValid(probe.get()))
                blocked = {a, b};
        }
    ASSERT_FALSE(blocked.empty());

    std::vector<std::shared_ptr<michi::planners::ExperienceRace>> planners = {
        std::make_shared<michi::planners::ThunderPlanner>(si), std::make_shared<michi::planners::LightningPlanner>(si)};
    for (const auto &planner : planners)
    {
        planner->addExperience(trained);
        ASSERT_GT(planner->experienceCount(), 0u);
        setQuery(setup, {0.22, 0.28}, blocked);
        setup->setPlanner(planner);
        planner->clear();
        setup->getProblemDefinition()->clearSolutionPaths();
        const ob::PlannerStatus status = setup->solve(1.);
        EXPECT_NE(status, ob::PlannerStatus::EXACT_SOLUTION) << planner->getName();
        EXPECT_FALSE(setup->getProblemDefinition()->hasExactSolution()) << planner->getName();
    }
}
