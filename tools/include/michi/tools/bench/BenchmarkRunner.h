#ifndef MICHI_TOOLS_BENCHMARK_RUNNER_
#define MICHI_TOOLS_BENCHMARK_RUNNER_

#include <michi/tools/problem/Problem.h>
#include <michi/tools/pictures/SvgPlot.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief Overrides of a problem's benchmark settings (0 / empty: keep the problem's). */
        struct BenchOptions
        {
            std::vector<std::string> planners;
            unsigned int runs{0};
            double timeLimit{0.};
            std::size_t query{0};
            bool heldOut{true};  ///< cycle the problem's held-out experience queries (if any) instead of \e query
            /** \brief Non-empty (a name of checkerNames() other than fcl): run every planner twice in the same
                Benchmark, with the FCL checker and the problem's motion validator, and with this checker and its
                motion validator (planner names suffixed "_<checker>": "_jmap", "_grid"), so the two are compared
                under the same conditions. */
            std::string compareChecker;
            /** \brief "all" or "A-B": a dataset run (Dataset.h): run i of every planner plans query i of the
                selection, one run per query (runs is then the number of queries); each run's query index is
                recorded in the log (run property "query"). Empty: the problem's benchmark.queries. */
            std::string queries;
            std::string outDir;
            /** \brief Also write `<name>.html`, a 3-D replay of each planner's first solution (viewer/ReplayPage.h). */
            bool html{false};
            std::ostream *progress{nullptr};  ///< progress lines (stderr in the command), or none
        };

        /** \brief Per-planner figures of one benchmark, as in summary.md. */
        struct PlannerSummary
        {
            std::string name;  ///< as OMPL's Benchmark names it (geometric_RRTConnect)
            unsigned int runs{0};
            unsigned int solved{0};
            /** \brief Solved runs whose path FCL re-checked on the real geometry (run property certified_paths);
                a path that fails is counted as not solved, so this equals \e solved. */
            unsigned int certified{0};
            double medianTime{0.};       ///< over all runs, seconds
            double medianLength{0.};     ///< over solved runs, NaN if none
            double medianClearance{0.};  ///< over solved runs, NaN if none
        };

        struct BenchResult
        {
            std::string log;
            std::string database;
            std::string summary;
            std::string summaryText;  ///< what summary.md holds (printed by `michi bench` without reading it back)
            std::string picture;
            std::string page;  ///< the replay page, when BenchOptions::html (else empty)
            std::vector<PlannerSummary> planners;
            std::vector<PlotPath> paths;  ///< one solution per planner that solved
        };

        /** \brief Run OMPL's Benchmark over the planners on query \e options.query of \e problem and write, in
            options.outDir: `<name>.log` (OMPL's log format), `<name>.db` (Debian's ompl_benchmark_statistics,
            for Planner Arena), `summary.md`, `<name>.svg` (one solution of each planner) and its PNG rendering
           `<name>.png`. Everything is checked (planner names, parameters, start and goal) before the first run, and the
           files are written to a staging folder and moved into outDir only when all of them exist: on failure nothing
           is left behind. Throws ProblemError / std::runtime_error. */
        BenchResult runBenchmark(const Problem &problem, const BenchOptions &options);

        /** \brief Markdown table of planner summaries. */
        std::string summaryMarkdown(const Problem &problem, const std::vector<PlannerSummary> &planners,
                                    double timeLimit, unsigned int runs, const std::string &compareChecker = "");
    }  // namespace tools
}  // namespace michi

#endif
