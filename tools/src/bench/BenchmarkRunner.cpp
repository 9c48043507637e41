#include <michi/tools/bench/BenchmarkRunner.h>
#include "bench/BenchSession.h"
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
        double benchProperty(const ot::Benchmark::RunProperties &run, const std::string &key)
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
                   : problem.checker == "spheres"
                       ? std::string("sphere validity checker, certified sphere motion validator (paths certified "
                                     "with FCL afterwards)")
                   : problem.checker == "jmap"
                       ? "J-map validity checker, J-map motion validator (" + problem.motionValidator +
                             " for what the map cannot decide)"
                       : "FCL validity checker, " + problem.motionValidator + " motion validator")
               << ".";
            // planners[i].checker: runs named <planner>_<checker> used that checker and its motion validator
            // Planners given a checker of their own in the problem file carry its name as a suffix; the summary says
            // what each suffix means so the table reads on its own.
            if (compareChecker.empty())
                for (const char *checker : {"fcl", "jmap", "grid", "spheres"})
                {
                    const std::string suffix = std::string("_") + checker;
                    if (std::any_of(planners.begin(), planners.end(),
                                    [&](const PlannerSummary &p)
                                    {
                                        return p.name.size() > suffix.size() &&
                                               p.name.compare(p.name.size() - suffix.size(), suffix.size(), suffix) ==
                                                   0;
                                    }))
                        md << " Planners suffixed " << suffix << ": " << checker
                           << " validity checker and its motion validator (the problem's planners[i].checker).";
                }
            md << " Median time over all runs (failures count at the time they gave up); length"
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
            BenchSession session(problem, options);
            session.prepare();
            session.run();
            return session.report();
        }
    }  // namespace tools
}  // namespace michi
