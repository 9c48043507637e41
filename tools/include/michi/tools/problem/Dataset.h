#ifndef MICHI_TOOLS_PROBLEM_DATASET_
#define MICHI_TOOLS_PROBLEM_DATASET_

#include <michi/tools/problem/Problem.h>

#include <cstddef>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        struct PlanningContext;

        /** \brief Which of a problem's queries a dataset takes: all of them, or indices first..last (inclusive). */
        struct QuerySelection
        {
            bool all{true};
            std::size_t first{0};
            std::size_t last{0};
        };

        /** \brief "all", "A-B" or "A" as a selection; std::invalid_argument (one line, what was expected)
            otherwise. */
        QuerySelection parseQuerySelection(const std::string &text);

        /** \brief One planning query of a dataset: query \e query of the problem in \e problemFile. */
        struct DatasetEntry
        {
            std::string problemFile;
            std::size_t query{0};
            std::string label;        ///< "movingai_arena #3 (arena.map.scen line 41)"
            std::string problemName;  ///< the problem's name (an OMPL log's experiment name)
        };

        /** \brief A named list of queries, each a query of a problem file: what `michi bench --queries`,
            `benchmark: {queries: ...}`, the experience planners' query sets and campaigns run, one run per entry.
            A MovingAI .scen bucket is one dataset (the problem's queries); a folder of problem files is another. */
        struct Dataset
        {
            std::string name;
            std::vector<DatasetEntry> entries;
        };

        /** \brief The dataset of \e problem's queries that \e selection takes. Throws ProblemError (key
            "benchmark.queries") when the selection names a query the problem does not have. */
        Dataset datasetOf(const Problem &problem, const QuerySelection &selection);

        /** \brief Every problem file (*.yaml) of \e folder, sorted by name, with the queries \e selection takes
            of each (loaded to count them). Throws ProblemError for a bad file, std::runtime_error for a folder that
            does not exist or holds no problem file. */
        Dataset loadDatasetFolder(const std::string &folder, const QuerySelection &selection = QuerySelection());

        /** \brief Check every entry's start and goal against the context's bounds and FCL before any run
            (entries of \e problem only); throws ProblemError naming queries[i].start / goal. */
        void checkDatasetQueries(const Problem &problem, const PlanningContext &ctx, const Dataset &dataset);
    }  // namespace tools
}  // namespace michi

#endif
