// One `michi bench` in three steps, run in order by runBenchmark() (BenchmarkRunner.cpp): prepare() makes the
// planning context, the planners with their checkers and the Benchmark with its pre-run event, and trains the
// experience planners (BenchPrepare.cpp); run() runs OMPL's Benchmark, certifying every path and keeping each
// planner's first one for the pictures (BenchRun.cpp); report() writes the log, the Planner Arena database, the
// summary and the pictures into the output folder, all or nothing (BenchReport.cpp). Private to michi_tools.
#ifndef MICHI_TOOLS_BENCH_SESSION_
#define MICHI_TOOLS_BENCH_SESSION_

#include <michi/tools/FileOutput.h>
#include <michi/tools/bench/BenchmarkRunner.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Dataset.h>
#include <michi/tools/problem/ExperienceDataset.h>

#include <ompl/tools/benchmark/Benchmark.h>

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief A run property as a number (NaN when missing or not a number). */
        double benchProperty(const ompl::tools::Benchmark::RunProperties &run, const std::string &key);

        /** \brief The times (seconds) OMPL's Benchmark books for a planner that works \e workSeconds and gives up,
            \e runs runs with the given request settings: what the Benchmark's own clock adds to a solve of that
            length (BenchmarkFloor.cpp). */
        std::vector<double> benchmarkClockTimes(double timeLimit, double memoryLimit, unsigned int runs,
                                                double workSeconds);

        class BenchSession
        {
        public:
            BenchSession(const Problem &problem, const BenchOptions &options) : problem(problem), options(options)
            {
            }
            BenchSession(const BenchSession &) = delete;
            BenchSession &operator=(const BenchSession &) = delete;

            void prepare();
            void run();
            BenchResult report();

        private:
            const Problem &problem;
            const BenchOptions &options;

            // prepare(): what is run
            double timeLimit{0.};
            unsigned int runs{0};
            Dataset dataset;  ///< a dataset run's queries (empty: every run plans one query)
            bool datasetRun{false};
            std::vector<PlannerSpec> specs;
            ContextOptions contextOptions;
            const std::string &compare{options.compareChecker};
            bool compareCheckers{false};
            std::string ownChecker;  ///< planners[i].checker other than FCL and the problem's
            PlanningContext ctx;
            ompl::base::SpaceInformationPtr si;
            /** checker and motion validator of each planner instance, installed by the pre-run event */
            std::map<const ompl::base::Planner *,
                     std::pair<ompl::base::StateValidityCheckerPtr, ompl::base::MotionValidatorPtr>>
                checking;
            std::unique_ptr<ompl::tools::Benchmark> benchmark;
            std::vector<ompl::base::PlannerPtr> planners;
            bool cycleHeldOut{false};
            /** an experience dataset run (ExperienceDataset.h): run i plans held-out problem i mod n in its scene */
            bool experienceDataset{false};
            ExperienceDataset experienceSets;
            std::vector<Problem> heldOutProblems;           ///< experienceSets.heldOut's problems, loaded once
            std::size_t heldOutFirst{0};                    ///< folder index of the first held-out problem
            std::map<std::string, std::size_t> heldOutRun;  ///< next held-out query of each planner
            std::map<const ompl::base::Planner *, std::size_t> datasetNext;  ///< next dataset entry of each planner
            std::map<const ompl::base::Planner *, std::size_t> runQuery;     ///< query of the run in progress

            // run(): the events' state
            std::mutex pathMutex;
            std::map<std::string, PlotPath> firstPaths;  ///< each planner's first certified path
            std::size_t done{0};
            std::unique_ptr<StagedDirectory> staging;
        };
    }  // namespace tools
}  // namespace michi

#endif
