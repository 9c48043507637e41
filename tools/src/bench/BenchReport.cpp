#include "bench/BenchSession.h"

#include <michi/tools/bench/PathCertificate.h>
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/tools/problem/ExperienceQueries.h>

#include <michi/tools/viewer/ReplayPage.h>

#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <boost/filesystem.hpp>
#include <iomanip>

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;

namespace michi
{
    namespace tools
    {
        namespace fs = boost::filesystem;

        namespace
        {
            /** Runs of each clock-floor planner (about a millisecond each), and how long the working one works
                (seconds): a solve shorter than the termination thread's 1 ms sleep step, as many are. */
            constexpr unsigned int CLOCK_FLOOR_RUNS = 15;
            constexpr double CLOCK_FLOOR_WORK = 0.0005;

            double median(std::vector<double> v)
            {
                if (v.empty())
                    return std::nan("");
                std::sort(v.begin(), v.end());
                const std::size_t n = v.size();
                return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
            }
        }  // namespace

        BenchResult BenchSession::report()
        {
            const fs::path log = staging->path(problem.name + ".log");
            if (!benchmark->saveResultsToFile(log.string().c_str()))
                throw std::runtime_error(log.string() + ": cannot write the benchmark log");
            // Debian's ompl_benchmark_statistics makes the database Planner Arena reads; without -a it starts a new
            // one, which is what a fresh staging folder wants.
            const fs::path db = staging->path(problem.name + ".db");
            const fs::path statsLog = staging->path("ompl_benchmark_statistics.out");
            const std::string command = "ompl_benchmark_statistics " + shellQuote(log.string()) + " -d " +
                                        shellQuote(db.string()) + " > " + shellQuote(statsLog.string()) + " 2>&1";
            const int rc = std::system(command.c_str());
            if (rc != 0 || !fs::exists(db))
            {
                throw std::runtime_error("ompl_benchmark_statistics failed (exit " + std::to_string(rc) + "): " +
                                         lastLine(statsLog.string()) + " (is the ompl-demos package installed?)");
            }
            fs::remove(statsLog);

            BenchResult result;
            std::ostream *progress = options.progress;
            const auto &experiment = benchmark->getRecordedExperimentData();
            for (const auto &p : experiment.planners)
            {
                PlannerSummary s;
                s.name = p.name;
                std::vector<double> times, lengths, clearances;
                for (const auto &run : p.runs)
                {
                    ++s.runs;
                    // Every run's time, failures at the time they gave up: a median over solved runs only would flatter
                    // a planner that often fails.
                    times.push_back(benchProperty(run, "time REAL"));
                    if (benchProperty(run, "solved BOOLEAN") == 1.)
                    {
                        ++s.solved;
                        s.certified += benchProperty(run, "certified_paths INTEGER") == 1. ? 1 : 0;
                        lengths.push_back(benchProperty(run, "solution length REAL"));
                        clearances.push_back(benchProperty(run, "solution clearance REAL"));
                    }
                }
                s.medianTime = median(times);
                s.medianLength = median(lengths);
                s.medianClearance = median(clearances);
                result.planners.push_back(s);
            }
            const fs::path summary = staging->path("summary.md");
            {
                std::ostringstream out;
                out << summaryMarkdown(problem, result.planners, timeLimit, runs, compare);
                // after the runs, so that it cannot disturb them (the Benchmark reads OMPL's seed)
                const double atOnce =
                    median(benchmarkClockTimes(timeLimit, problem.benchmark.memoryLimit, CLOCK_FLOOR_RUNS, 0.));
                const double working = median(
                    benchmarkClockTimes(timeLimit, problem.benchmark.memoryLimit, CLOCK_FLOOR_RUNS, CLOCK_FLOOR_WORK));
                if (std::isfinite(atOnce) && std::isfinite(working))
                    out << "\nBenchmark's own clock: a planner that works " << 1e3 * CLOCK_FLOOR_WORK
                        << " ms is booked " << std::setprecision(3) << 1e3 * working << " ms, one that returns at once "
                        << 1e3 * atOnce << " ms (medians of " << CLOCK_FLOOR_RUNS
                        << " runs each through the same OMPL Benchmark and time limit, after the runs above). OMPL "
                           "books a run when its termination-condition thread has been joined, at the end of that "
                           "thread's sleep step of 1 ms, so every time above includes up to about that much; "
                           "medians within a few times of it say more about that clock than about the planners "
                           "(docs/benchmarks.md: how to time them on a plain clock).\n";
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
            const fs::path picture = staging->path(problem.name + ".svg");
            writeProblemSvg(problem, result.paths, picture.string(), contextOptions.query);
            if (!svgToPng(picture.string(), staging->path(problem.name + ".png").string()) && progress)
                *progress << "michi bench: no PNG copy of the picture (rsvg-convert from librsvg2-bin is missing)"
                          << std::endl;
            const fs::path page = staging->path(problem.name + ".html");
            if (options.html)
                writeReplayPage(problem, result.paths, page.string());

            // Everything was written into the staging folder first: the outputs appear together or not at all.
            staging->commit();
            const fs::path out = staging->out();
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
