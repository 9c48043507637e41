#include <michi/tools/bench/BenchmarkRunner.h>
#include <michi/tools/bench/PathCertificate.h>
#include <michi/tools/problem/Dataset.h>
#include <michi/tools/problem/ExperienceQueries.h>
#include <michi/tools/FileOutput.h>

#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/viewer/ReplayPage.h>

#include <ompl/geometric/PathGeometric.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/RandomNumbers.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <mutex>
#include <sstream>

namespace fs = boost::filesystem;
namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;

namespace michi
{
    namespace tools
    {
        namespace
        {
            double median(std::vector<double> v)
            {
                if (v.empty())
                    return std::nan("");
                std::sort(v.begin(), v.end());
                const std::size_t n = v.size();
                return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
            }

            double property(const ot::Benchmark::RunProperties &run, const std::string &key)
            {
                auto it = run.find(key);
                if (it == run.end() || it->second.empty())
                    return std::nan("");
                try
                {
                    return std::stod(it->second);
                }
                catch (const std::exception &)
                {
                    return std::nan("");
                }
            }
        }  // namespace

        std::string summaryMarkdown(const Problem &problem, const std::vector<PlannerSummary> &planners,
                                    double timeLimit, unsigned int runs, const std::string &compareChecker)
        {
            std::ostringstream md;
            md << "# " << problem.name << "\n\n";
            if (!problem.description.empty())
                md << problem.description << "\n\n";
            md << "OMPL Benchmark, " << runs << " runs per planner, time limit " << timeLimit << " s per run, "
               << (compareChecker == "jmap"
                       ? "FCL validity checker and " + problem.motionValidator +
                             " motion validator; planners suffixed _jmap: J-map validity checker and J-map "
                             "motion validator (" +
                             problem.motionValidator + " where the map cannot decide)"
                   : !compareChecker.empty() ? "FCL validity checker and " + problem.motionValidator +
                                                   " motion validator; planners suffixed _" + compareChecker + ": " +
                                                   compareChecker + " validity checker and its motion validator"
                   : problem.checker == "grid" ? std::string("grid validity checker, grid motion validator")
                   : problem.checker == "jmap"
                       ? "J-map validity checker, J-map motion validator (" + problem.motionValidator +
                             " for what the map cannot decide)"
                       : "FCL validity checker, " + problem.motionValidator + " motion validator")
               << ". Median time over all runs (failures count at the time they gave up); length"
                  " and clearance over solved runs.\n\n";
            md << "| planner | runs | success | certified paths | median time (s) | median length | median clearance "
                  "|\n";
            md << "|---|---:|---:|---:|---:|---:|---:|\n";
            auto num = [](double v, int precision)
            {
                if (std::isnan(v))
                    return std::string("–");
                std::ostringstream s;
                s << std::setprecision(precision) << v;
                return s.str();
            };
            for (const auto &p : planners)
                md << "| " << p.name << " | " << p.runs << " | " << num(100. * p.solved / std::max(1u, p.runs), 3)
                   << " % | " << p.certified << "/" << p.solved << " | " << num(p.medianTime, 4) << " | "
                   << num(p.medianLength, 4) << " | " << num(p.medianClearance, 3) << " |\n";
            return md.str();
        }

        BenchResult runBenchmark(const Problem &problem, const BenchOptions &options)
        {
            if (options.outDir.empty())
                throw std::invalid_argument("no output folder given");
            const double timeLimit = options.timeLimit > 0. ? options.timeLimit : problem.benchmark.timeLimit;
            unsigned int runs = options.runs > 0 ? options.runs : problem.benchmark.runs;
            // a dataset run: run i of every planner plans query i of the selection
            const std::string queries = !options.queries.empty() ? options.queries : problem.benchmark.queries;
            Dataset dataset;
            if (!queries.empty())
            {
                try
                {
                    dataset = datasetOf(problem, parseQuerySelection(queries));
                }
                catch (const std::invalid_argument &e)
                {
                    throw ProblemError(problem.file, "benchmark.queries", e.what());
                }
                if (dataset.entries.empty())
                    throw ProblemError(problem.file, "benchmark.queries", "selects no query");
                runs = static_cast<unsigned int>(dataset.entries.size());
            }
            const bool datasetRun = !dataset.entries.empty();
            std::vector<PlannerSpec> specs;
            if (options.planners.empty())
                specs = problem.planners;
            else
                for (const auto &name : options.planners)
                {
                    auto it = std::find_if(problem.planners.begin(), problem.planners.end(),
                                           [&](const PlannerSpec &s)
                                           {
                                               return s.name == name;
                                           });
                    specs.push_back(it != problem.planners.end() ? *it : PlannerSpec{name, {}});
                }

            ompl::RNG::setSeed(problem.benchmark.seed);
            ContextOptions contextOptions;
            contextOptions.query = datasetRun ? dataset.entries.front().query : options.query;
            const std::string &compare = options.compareChecker;
            const bool compareCheckers = !compare.empty();
            if (compare == "fcl")
                throw std::invalid_argument("compareChecker: name a checker other than fcl");
            if (compareCheckers)
                contextOptions.checker = compare;  // the context then holds both checkers and both motion validators
            // planners[i].checker: planners on their own checker beside the others (compare mode runs every planner
            // on both checkers, so there it is not needed). A context holds FCL and at most one other checker.
            std::string ownChecker;
            if (!compareCheckers)
                for (std::size_t i = 0; i < specs.size(); ++i)
                {
                    const std::string &c = specs[i].checker;
                    if (c.empty() || c == problem.checker || c == "fcl")
                        continue;
                    if (problem.checker != "fcl" || (!ownChecker.empty() && c != ownChecker))
                        throw ProblemError(problem.file, "planners[" + std::to_string(i) + "].checker",
                                           "a benchmark runs FCL and at most one other checker (here " +
                                               (problem.checker != "fcl" ? problem.checker : ownChecker) + ")");
                    ownChecker = c;
                }
            if (!ownChecker.empty())
                contextOptions.checker = ownChecker;
            PlanningContext ctx = makePlanningContext(problem, contextOptions);  // checks start and goal
            auto si = ctx.setup->getSpaceInformation();
            if (datasetRun)
                checkDatasetQueries(problem, ctx, dataset);
            // checker and motion validator of each planner instance (compareCheckers: FCL ones, then the other's)
            std::map<const ob::Planner *, std::pair<ob::StateValidityCheckerPtr, ob::MotionValidatorPtr>> checking;
            const ob::StateValidityCheckerPtr fastChecker = si->getStateValidityChecker();
            const ob::MotionValidatorPtr fastMotions = si->getMotionValidator();
            const ob::MotionValidatorPtr fclMotions = ctx.referenceMotions;

            ot::Benchmark benchmark(*ctx.setup, problem.name);
            std::vector<ob::PlannerPtr> planners;
            for (const auto &spec : specs)
            {
                auto make = [&]
                {
                    try
                    {
                        return makePlanner(problem, spec.name, si, spec.params);
                    }
                    catch (const std::invalid_argument &e)
                    {
                        throw ProblemError(problem.file, "planners", e.what());
                    }
                };
                ob::PlannerPtr planner = make();
                if (!compareCheckers)
                {
                    // the context's installed checker is the problem's, or ownChecker (then FCL is the default)
                    const std::string installed = ownChecker.empty() ? problem.checker : ownChecker;
                    const std::string wanted = spec.checker.empty() ? problem.checker : spec.checker;
                    if (wanted != problem.checker)
                        planner->setName(planner->getName() + "_" + wanted);
                    if (installed != problem.checker || wanted != problem.checker)
                        checking[planner.get()] =
                            wanted == installed ? std::make_pair(fastChecker, fastMotions)
                                                : std::make_pair(ob::StateValidityCheckerPtr(ctx.checker), fclMotions);
                    benchmark.addPlanner(planner);
                    planners.push_back(planner);
                    continue;
                }
                benchmark.addPlanner(planner);
                planners.push_back(planner);
                checking[planner.get()] = {ctx.checker, fclMotions};
                auto withFast = make();
                withFast->setName(withFast->getName() + "_" + compare);
                benchmark.addPlanner(withFast);
                planners.push_back(withFast);
                checking[withFast.get()] = {fastChecker, fastMotions};
            }
            benchmark.addExperimentParameter("query", "INTEGER", std::to_string(options.query));
            // experience planners learn the training queries' solutions before the runs (not timed); run i of every
            // planner plans held-out query i mod n (docs/path-seed.md, ExperienceQueries.h)
            const auto &heldOut = problem.experience.heldOut;
            std::map<std::string, std::size_t> heldOutRun;
            const bool cycleHeldOut = options.heldOut && !heldOut.empty() && !datasetRun;
            std::map<const ob::Planner *, std::size_t> datasetNext;  // next dataset entry of each planner
            std::map<const ob::Planner *, std::size_t> runQuery;     // query of the run in progress
            if (datasetRun)
            {
                benchmark.addExperimentParameter("dataset", "VARCHAR(128)", dataset.name);
                benchmark.addExperimentParameter("dataset_queries", "INTEGER", std::to_string(dataset.entries.size()));
            }
            if (cycleHeldOut)
            {
                checkHeldOutQueries(problem, ctx);
                benchmark.addExperimentParameter("held_out_queries", "INTEGER", std::to_string(heldOut.size()));
            }
            if (cycleHeldOut || !checking.empty() || datasetRun)
                benchmark.setPreRunEvent(
                    [&](const ob::PlannerPtr &planner)
                    {
                        if (datasetRun)
                        {
                            const auto &entry = dataset.entries[datasetNext[planner.get()]++ % dataset.entries.size()];
                            runQuery[planner.get()] = entry.query;
                            setQuery(ctx, problem.queries[entry.query]);
                        }
                        if (cycleHeldOut)
                            setQuery(ctx, heldOut[heldOutRun[planner->getName()]++ % heldOut.size()]);
                        const auto it = checking.find(planner.get());
                        if (it != checking.end())
                        {
                            // SimpleSetup::setup() sets the space information up again before the run
                            si->setStateValidityChecker(it->second.first);
                            si->setMotionValidator(it->second.second);
                        }
                    });
            if (compareCheckers)
                benchmark.addExperimentParameter("checkers", "VARCHAR(32)", "fcl," + compare);
            trainExperiencePlanners(problem, ctx, planners, options.progress);
            benchmark.addExperimentParameter("seed", "INTEGER", std::to_string(problem.benchmark.seed));

            BenchResult result;
            std::mutex pathMutex;
            std::map<std::string, PlotPath> firstPaths;
            const std::size_t totalRuns = planners.size() * runs;
            std::size_t done = 0;
            std::ostream *progress = options.progress;
            benchmark.setPostRunEvent(
                [&](const ob::PlannerPtr &planner, ot::Benchmark::RunProperties &run)
                {
                    std::lock_guard<std::mutex> lock(pathMutex);
                    ++done;
                    if (datasetRun)
                        run["query INTEGER"] = std::to_string(runQuery[planner.get()]);
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
                            if (progress)
                                *progress << "michi bench: " << planner->getName() << ": path NOT certified by FCL ("
                                          << certificate.reason << "): counted as a failure" << std::endl;
                        }
                    }
                    run["certified_paths INTEGER"] = solved ? "1" : "0";
                    if (progress)
                        *progress << "michi bench: [" << done << "/" << totalRuns << "] " << planner->getName() << ": "
                                  << (solved ? "solved" : "not solved") << " in " << std::setprecision(3)
                                  << property(run, "time REAL") << " s" << std::endl;
                    if (!solved || firstPaths.count(planner->getName()))
                        return;
                    if (datasetRun && runQuery[planner.get()] != contextOptions.query)
                        return;  // the picture shows the first query's paths
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

            StagedDirectory staging(options.outDir);
            if (progress)
                *progress << "michi bench: " << problem.name << ": " << planners.size() << " planners x " << runs
                          << " runs, " << timeLimit << " s each" << std::endl;
            // saveConsoleOutput=false: OMPL would otherwise leave a .console file in the working directory
            ot::Benchmark::Request request(timeLimit, problem.benchmark.memoryLimit, runs, 0.05, false, false,
                                           problem.benchmark.simplify);
            benchmark.benchmark(request);

            const fs::path log = staging.path(problem.name + ".log");
            if (!benchmark.saveResultsToFile(log.string().c_str()))
                throw std::runtime_error(log.string() + ": cannot write the benchmark log");
            const fs::path db = staging.path(problem.name + ".db");
            const fs::path statsLog = staging.path("ompl_benchmark_statistics.out");
            const std::string command = "ompl_benchmark_statistics " + shellQuote(log.string()) + " -d " +
                                        shellQuote(db.string()) + " > " + shellQuote(statsLog.string()) + " 2>&1";
            const int rc = std::system(command.c_str());
            if (rc != 0 || !fs::exists(db))
            {
                std::ifstream in(statsLog.string());
                std::string line, last;
                while (std::getline(in, line))
                    if (!line.empty())
                        last = line;
                throw std::runtime_error("ompl_benchmark_statistics failed (exit " + std::to_string(rc) + "): " + last +
                                         " (is the ompl-demos package installed?)");
            }
            fs::remove(statsLog);

            const auto &experiment = benchmark.getRecordedExperimentData();
            for (const auto &p : experiment.planners)
            {
                PlannerSummary s;
                s.name = p.name;
                std::vector<double> times, lengths, clearances;
                for (const auto &run : p.runs)
                {
                    ++s.runs;
                    times.push_back(property(run, "time REAL"));
                    if (property(run, "solved BOOLEAN") == 1.)
                    {
                        ++s.solved;
                        s.certified += property(run, "certified_paths INTEGER") == 1. ? 1 : 0;
                        lengths.push_back(property(run, "solution length REAL"));
                        clearances.push_back(property(run, "solution clearance REAL"));
                    }
                }
                s.medianTime = median(times);
                s.medianLength = median(lengths);
                s.medianClearance = median(clearances);
                result.planners.push_back(s);
            }
            const fs::path summary = staging.path("summary.md");
            {
                std::ostringstream out;
                out << summaryMarkdown(problem, result.planners, timeLimit, runs, compare);
                if (datasetRun)
                    out << "\nDataset " << dataset.name << ": run i of every planner planned query i ("
                        << dataset.entries.size() << " queries, " << dataset.entries.front().label << " to "
                        << dataset.entries.back().label << "); the log's run property `query` names it.\n";
                result.summaryText = out.str();
                writeAtomically(result.summaryText, summary.string());
            }
            for (const auto &planner : planners)
                if (firstPaths.count(planner->getName()))
                    result.paths.push_back(firstPaths[planner->getName()]);
            const fs::path picture = staging.path(problem.name + ".svg");
            writeProblemSvg(problem, result.paths, picture.string(), contextOptions.query);
            if (!svgToPng(picture.string(), staging.path(problem.name + ".png").string()) && progress)
                *progress << "michi bench: no PNG copy of the picture (rsvg-convert from librsvg2-bin is missing)"
                          << std::endl;
            const fs::path page = staging.path(problem.name + ".html");
            if (options.html)
                writeReplayPage(problem, result.paths, page.string());

            staging.commit();
            const fs::path out = staging.out();
            result.log = (out / log.filename()).string();
            result.database = (out / db.filename()).string();
            result.summary = (out / summary.filename()).string();
            result.picture = (out / picture.filename()).string();
            if (options.html)
                result.page = (out / page.filename()).string();
            return result;
        }
    }  // namespace tools
}  // namespace michi
