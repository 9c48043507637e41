#include "bench/BenchSession.h"

#include <michi/tools/bench/PathCertificate.h>
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/tools/problem/ExperienceQueries.h>
#include <michi/planners/path_seed/PathSeed.h>

#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <iomanip>

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;

namespace michi
{
    namespace tools
    {
        void BenchSession::run()
        {
            const std::size_t totalRuns = planners.size() * runs;
            std::ostream *progress = options.progress;
            benchmark->setPostRunEvent(
                [this, totalRuns, progress](const ob::PlannerPtr &planner, ot::Benchmark::RunProperties &run)
                {
                    std::lock_guard<std::mutex> lock(pathMutex);
                    ++done;
                    if (datasetRun)
                        run["query INTEGER"] = std::to_string(runQuery[planner.get()]);
                    if (experienceDataset)  // the held-out problem's index in the dataset folder
                        run["held_out_problem INTEGER"] = std::to_string(heldOutFirst + runQuery[planner.get()]);
                    // where PathSeed's path came from (recall, stitch, repair, scratch) and the checks it spent on
                    // its seeds: what docs/path-seed.md's tables break its times down by
                    if (const auto *seeds = dynamic_cast<const planners::PathSeed *>(planner.get()))
                    {
                        run["path_seed_source VARCHAR(16)"] = seeds->getLastSource();
                        run["path_seed_checks INTEGER"] = std::to_string(seeds->getLastRecallChecks());
                    }
                    bool solved = run.count("solved BOOLEAN") && run["solved BOOLEAN"] == "1";
                    if (solved)
                    {
                        // every returned path is re-checked with FCL on the real geometry at a fine step; one
                        // that fails is not a solution (a fast checker's mistake is never reported as solved)
                        const auto pdef = planner->getProblemDefinition();
                        const auto solution = pdef ? pdef->getSolutionPath() : nullptr;
                        const auto *geometric = solution ? solution->as<og::PathGeometric>() : nullptr;
                        const PathCertificate certificate =
                            geometric ? certifyPath(*geometric, *ctx.checker) : PathCertificate{};
                        if (!certificate.certified)
                        {
                            solved = false;
                            run["solved BOOLEAN"] = "0";
                            // OMPL's own check (path->check() with the planner's checker) said correct: FCL says not
                            run["correct solution BOOLEAN"] = "0";
                            if (progress)
                                *progress << "michi bench: " << planner->getName() << ": path NOT certified by FCL ("
                                          << certificate.reason << "): counted as a failure" << std::endl;
                        }
                    }
                    run["certified_paths INTEGER"] = solved ? "1" : "0";
                    if (progress)
                        *progress << "michi bench: [" << done << "/" << totalRuns << "] " << planner->getName() << ": "
                                  << (solved ? "solved" : "not solved") << " in " << std::setprecision(3)
                                  << benchProperty(run, "time REAL") << " s" << std::endl;
                    if (!solved || firstPaths.count(planner->getName()))
                        return;
                    if (datasetRun && runQuery[planner.get()] != contextOptions.query)
                        return;  // the picture shows the first query's paths
                    if (experienceDataset && runQuery[planner.get()] != 0)
                        return;  // and the first held-out problem's (drawn in the problem's own scene)
                    const auto pdef = planner->getProblemDefinition();
                    if (!pdef || !pdef->hasExactSolution())
                        return;
                    auto *path = pdef->getSolutionPath()->as<og::PathGeometric>();
                    PlotPath plot;
                    plot.label = planner->getName();
                    for (const auto *s : path->getStates())
                    {
                        std::vector<double> values;
                        si->getStateSpace()->copyToReals(values, s);
                        plot.states.push_back(values);
                    }
                    firstPaths[planner->getName()] = plot;
                });

            staging = std::make_unique<StagedDirectory>(options.outDir);
            if (progress)
                *progress << "michi bench: " << problem.name << ": " << planners.size() << " planners x " << runs
                          << " runs, " << timeLimit << " s each" << std::endl;
            // saveConsoleOutput=false: OMPL would otherwise leave a .console file in the working directory
            ot::Benchmark::Request request(timeLimit, problem.benchmark.memoryLimit, runs, 0.05, false, false,
                                           problem.benchmark.simplify);
            benchmark->benchmark(request);
            if (experienceDataset)  // the pictures are drawn in the problem's own scene
                installScene(problem, ctx, problem);
        }
    }  // namespace tools
}  // namespace michi
