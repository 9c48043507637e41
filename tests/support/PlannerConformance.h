// Conformance suite every michi planner passes. A planner's test file includes this header once and instantiates
// the suite:
//
//   INSTANTIATE_TEST_SUITE_P(MyPlanner, PlannerConformance,
//                            ::testing::Values(michi::test::ConformanceCase{"michi::MyPlanner", {{"p", "1"}}}));
//
// The checks: built by its registry allocator from `si` alone; every declared parameter can be read and set back by
// name, and the case's parameters are accepted; solve -> clear -> solve gives exact solutions both times; with a
// termination condition that is already true, solve() returns without a solution and after at most a handful of
// validity checks (counted, not timed); on a problem whose goal is walled in, solve() returns within 0.1 s after its
// termination condition becomes true (the one timed check: issue 13 asks for it; setup is timed apart); every solution
// is re-validated at 1/10 of the space's resolution by an independent checker (Boost.Geometry, not FCL);
// getPlannerData() is not empty.
#ifndef MICHI_TESTS_SUPPORT_PLANNER_CONFORMANCE_
#define MICHI_TESTS_SUPPORT_PLANNER_CONFORMANCE_

#include "support/ConformanceProblem.h"

#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/validity/fcl/FclValidityChecker.h>

#include <ompl/base/PlannerData.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <chrono>
#include <atomic>
#include <ctime>

#include <pthread.h>
#include <map>
#include <ostream>
#include <string>

class PlannerConformance : public ::testing::TestWithParam<michi::test::ConformanceCase>
{
protected:
    void SetUp() override
    {
        ompl::RNG::setSeed(42);
        problem_ = michi::test::makeConformanceProblem(GetParam().checker, GetParam().problem);
        planner_ = michi::tools::allocatePlanner(GetParam().planner, problem_.setup->getSpaceInformation());
        ASSERT_TRUE(planner_ != nullptr);
        for (const auto &kv : GetParam().params)
            ASSERT_TRUE(planner_->params().setParam(kv.first, kv.second)) << kv.first << " = " << kv.second;
        problem_.setup->setPlanner(planner_);
    }

    ompl::base::PlannerStatus solve()
    {
        return problem_.setup->solve(GetParam().timeLimit);
    }

    michi::test::ConformanceProblem problem_;
    ompl::base::PlannerPtr planner_;
};

TEST_P(PlannerConformance, BuiltFromSpaceInformationAlone)
{
    // a fresh planner from the allocator alone: named, bound to si, declares its settings, and sets itself up
    auto fresh = michi::tools::allocatePlanner(GetParam().planner, problem_.setup->getSpaceInformation());
    EXPECT_FALSE(fresh->getName().empty());
    EXPECT_EQ(fresh->getSpaceInformation(), problem_.setup->getSpaceInformation());
    EXPECT_GT(fresh->params().size(), 0u) << "settings must be declared with declareParam";
    fresh->setProblemDefinition(problem_.setup->getProblemDefinition());
    fresh->setup();
    EXPECT_TRUE(fresh->isSetup());
}

TEST_P(PlannerConformance, ParametersSettableByName)
{
    std::vector<std::string> names;
    planner_->params().getParamNames(names);
    for (const auto &name : names)
    {
        const std::string value = planner_->params()[name].getValue();
        EXPECT_TRUE(planner_->params().setParam(name, value)) << name << " = " << value;
        EXPECT_EQ(planner_->params()[name].getValue(), value) << name;
    }
    EXPECT_FALSE(planner_->params().setParam("no_such_parameter_xyz", "1"));
}

TEST_P(PlannerConformance, ParametersTakeBothEndsOfTheirDeclaredRange)
{
    // A declared range ("low:step:high", or a list "a,b") is what tools that sweep settings read (OMPL's
    // ParamSet, benchmark scripts): every end must be accepted. A setter that throws there escapes setParam(),
    // which only catches bad number formats, and aborts the sweep (angle_step's range once ended at 1.58,
    // beyond the pi/2 its setter allows). michi's planners only: OMPL 1.5.2's own fail it (KPIECE1 declares
    // border_fraction from 0, which its setter refuses).
    if (GetParam().planner.rfind("michi::", 0) != 0)
        GTEST_SKIP() << GetParam().planner << " is OMPL's";
    std::vector<std::string> names;
    planner_->params().getParamNames(names);
    for (const auto &name : names)
    {
        const std::string range = planner_->params()[name].getRangeSuggestion();
        const std::string before = planner_->params()[name].getValue();
        std::vector<std::string> ends;
        if (const auto colon = range.find(':'); colon != std::string::npos)
            ends = {range.substr(0, colon), range.substr(range.rfind(':') + 1)};
        else
            for (std::size_t from = 0; from <= range.size();)
            {
                const std::size_t comma = std::min(range.find(',', from), range.size());
                if (comma > from)
                    ends.push_back(range.substr(from, comma - from));
                from = comma + 1;
            }
        for (const auto &value : ends)
        {
            bool accepted = false;
            EXPECT_NO_THROW(accepted = planner_->params().setParam(name, value)) << name << " = " << value;
            EXPECT_TRUE(accepted) << name << " = " << value << " (declared range " << range << ")";
        }
        EXPECT_TRUE(planner_->params().setParam(name, before)) << name << " = " << before;
    }
}

TEST_P(PlannerConformance, SolveClearSolve)
{
    for (int round = 0; round < 2; ++round)
    {
        ASSERT_EQ(solve(), ompl::base::PlannerStatus::EXACT_SOLUTION) << "round " << round;
        auto &path = problem_.setup->getSolutionPath();
        ASSERT_GE(path.getStateCount(), 2u);
        const auto *si = problem_.setup->getSpaceInformation().get();
        EXPECT_TRUE(si->equalStates(path.getState(0), problem_.setup->getProblemDefinition()->getStartState(0)));
        EXPECT_TRUE(problem_.setup->getGoal()->isSatisfied(path.getStates().back()));
        EXPECT_TRUE(path.check()) << "round " << round;
        EXPECT_EQ(michi::test::independentPathCheck(path), "") << "round " << round;
        planner_->clear();
        problem_.setup->getProblemDefinition()->clearSolutionPaths();
    }
}

TEST_P(PlannerConformance, SolvesAgainWithoutClear)
{
    // As OMPL's planners do: a solve stopped at once, then solve() again without clear() (SimpleSetup::solve twice,
    // a retry with more time). ConcentricCircle and PathSeed answered "Invalid start" to every later solve: OMPL's
    // PlannerInputStates had handed the start out once (found 2026-12-07).
    problem_.setup->setup();
    const ompl::base::PlannerTerminationCondition done(
        []
        {
            return true;
        });
    EXPECT_NE(problem_.setup->solve(done), ompl::base::PlannerStatus::EXACT_SOLUTION);
    for (int round = 0; round < 2; ++round)
    {
        ASSERT_EQ(solve(), ompl::base::PlannerStatus::EXACT_SOLUTION) << "round " << round;
        EXPECT_EQ(michi::test::independentPathCheck(problem_.setup->getSolutionPath()), "") << "round " << round;
    }
}

TEST_P(PlannerConformance, ReturnsPromptlyWhenTerminated)
{
    problem_.setup->setup();
    const auto before = problem_.checker->queryCount();
    const ompl::base::PlannerTerminationCondition done(
        []
        {
            return true;
        });
    const auto status = planner_->solve(done);
    EXPECT_NE(status, ompl::base::PlannerStatus::EXACT_SOLUTION);
    // a planner that honours the condition checks at most the start, the goal and a few more states
    EXPECT_LE(problem_.checker->queryCount() - before, 50u);
}

TEST_P(PlannerConformance, ReturnsWithinATenthOfASecondOnAnUnsolvableProblem)
{
    // issue 13: on a problem with no solution (the goal walled in), solve() returns within 0.1 s of the moment its
    // termination condition becomes true. Setting up (roadmaps, maps, lattices built in setup()) is timed apart.
    using Clock = std::chrono::steady_clock;
    auto enclosed = michi::test::makeConformanceProblem(GetParam().checker, GetParam().problem, true);
    auto planner = michi::tools::allocatePlanner(GetParam().planner, enclosed.setup->getSpaceInformation());
    for (const auto &kv : GetParam().params)
        ASSERT_TRUE(planner->params().setParam(kv.first, kv.second)) << kv.first << " = " << kv.second;
    enclosed.setup->setPlanner(planner);
    const auto loadStart = Clock::now();
    enclosed.setup->setup();
    const double setupSeconds = std::chrono::duration<double>(Clock::now() - loadStart).count();
    const auto fire = Clock::now() + std::chrono::milliseconds(300);
    // Lateness in CPU time of this thread (the one solve() runs on), from the first time the condition answered
    // true: the work a planner does after being told to stop. Wall time also counts the time the scheduler gave other
    // processes, and on a loaded machine (load 10 on 2 cores) even RRTConnect came back 0.12 s late by the wall clock;
    // a generous wall-clock bound still catches a planner that does not stop. The condition may be evaluated on a
    // planner's own thread (PRM checks for solutions on one), so this thread's clock is read by its id.
    clockid_t solvingThread{};
    pthread_getcpuclockid(pthread_self(), &solvingThread);
    auto cpuOf = [solvingThread]
    {
        timespec t{};
        clock_gettime(solvingThread, &t);
        return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
    };
    std::atomic<double> cpuAtFire{-1.};
    const ompl::base::PlannerTerminationCondition ptc(
        [fire, &cpuAtFire, &cpuOf]
        {
            if (Clock::now() < fire)
                return false;
            double unset = -1.;
            cpuAtFire.compare_exchange_strong(unset, cpuOf());
            return true;
        });
    const auto status = planner->solve(ptc);
    const double late = std::chrono::duration<double>(Clock::now() - fire).count();
    const double lateCpu = cpuAtFire.load() < 0. ? 0. : cpuOf() - cpuAtFire.load();
    RecordProperty("setup_seconds", std::to_string(setupSeconds));
    RecordProperty("seconds_after_termination", std::to_string(late));
    RecordProperty("cpu_seconds_after_termination", std::to_string(lateCpu));
    EXPECT_NE(status, ompl::base::PlannerStatus::EXACT_SOLUTION) << "the goal is walled in";
    // a complete method (a lattice, an exhausted circle search) may report failure before the condition fires
    EXPECT_LT(lateCpu, 0.1) << GetParam() << " worked " << lateCpu << " s of CPU after its termination condition "
                            << "fired (setup " << setupSeconds << " s)";
    EXPECT_LT(late, 2.) << GetParam() << " returned " << late << " s after its termination condition fired";
}

TEST_P(PlannerConformance, ExportsPlannerData)
{
    ASSERT_EQ(solve(), ompl::base::PlannerStatus::EXACT_SOLUTION);
    ompl::base::PlannerData data(problem_.setup->getSpaceInformation());
    planner_->getPlannerData(data);
    EXPECT_GT(data.numVertices(), 1u);
    EXPECT_GE(data.numStartVertices(), 1u);
}

#endif
