// How much of a `michi bench` time is OMPL's Benchmark rather than the planner: a planner that works for a known time,
// run through the same Benchmark with the same request settings. OMPL 1.5.2's Benchmark hands every solve() a
// termination condition evaluated by a helper thread that sleeps in 1 ms steps, and books the time until that thread
// has been joined (docs/benchmarks.md), so every run carries up to about a millisecond that no planner can
// avoid. The summary reports it beside the medians, so that a reader of two sub-millisecond planners' times knows how
// much of each is the clock.
#include "bench/BenchSession.h"

#include <ompl/base/Planner.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;

namespace michi
{
    namespace tools
    {
        namespace
        {
            /** A planner that works (spins) for a given time, then gives up. It reports one progress property, as
                OMPL's planners do, so that the Benchmark starts its progress thread for it too. */
            class SpinningPlanner : public ob::Planner
            {
            public:
                SpinningPlanner(const ob::SpaceInformationPtr &si, double seconds)
                    : ob::Planner(si, "SpinningPlanner"), seconds_(seconds)
                {
                    addPlannerProgressProperty("iterations INTEGER",
                                               []
                                               {
                                                   return std::string("0");
                                               });
                }

                ob::PlannerStatus solve(const ob::PlannerTerminationCondition &ptc) override
                {
                    // busy, as a planner is: a sleeping one would leave the core to the Benchmark's threads (the
                    // condition is the termination thread's cached answer, one load)
                    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds_);
                    while (std::chrono::steady_clock::now() < end && !ptc)
                    {
                    }
                    return ob::PlannerStatus::TIMEOUT;
                }

            private:
                double seconds_;
            };
        }  // namespace

        std::vector<double> benchmarkClockTimes(double timeLimit, double memoryLimit, unsigned int runs,
                                                double workSeconds)
        {
            auto space = std::make_shared<ob::RealVectorStateSpace>(1);
            space->setBounds(0., 1.);
            og::SimpleSetup setup(space);
            setup.setStateValidityChecker(
                [](const ob::State *)
                {
                    return true;
                });
            ob::ScopedState<> start(space), goal(space);
            start[0] = 0.;
            goal[0] = 1.;
            setup.setStartAndGoalStates(start, goal);
            ot::Benchmark benchmark(setup, "clock floor");
            benchmark.addPlanner(std::make_shared<SpinningPlanner>(setup.getSpaceInformation(), workSeconds));
            // the request of the real runs (BenchRun.cpp): the same time limit, so the same termination thread; the
            // Benchmark's messages about this planner are not the user's business
            ot::Benchmark::Request request(timeLimit, memoryLimit, runs, 0.05, false, false, false);
            const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
            ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
            benchmark.benchmark(request);
            ompl::msg::setLogLevel(level);
            std::vector<double> times;
            for (const auto &p : benchmark.getRecordedExperimentData().planners)
                for (const auto &run : p.runs)
                {
                    const double t = benchProperty(run, "time REAL");
                    if (std::isfinite(t))
                        times.push_back(t);
                }
            return times;
        }
    }  // namespace tools
}  // namespace michi
