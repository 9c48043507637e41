#include <michi/tools/problem/Dataset.h>
#include <michi/tools/bench/PlanningContext.h>

#include <ompl/base/ScopedState.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <stdexcept>

namespace fs = boost::filesystem;
namespace ob = ompl::base;

namespace michi
{
    namespace tools
    {
        namespace
        {
            std::size_t index(const std::string &text, const std::string &whole)
            {
                // Digits only (stoul would take a sign or spaces) and at most 9, so the index fits any size_t.
                if (text.empty() || text.size() > 9 ||
                    !std::all_of(text.begin(), text.end(),
                                 [](char c)
                                 {
                                     return c >= '0' && c <= '9';
                                 }))
                    throw std::invalid_argument("expected all, A-B or A (query indices from 0), got '" + whole + "'");
                return static_cast<std::size_t>(std::stoul(text));
            }
        }  // namespace

        QuerySelection parseQuerySelection(const std::string &text)
        {
            QuerySelection s;
            if (text == "all")
                return s;
            s.all = false;
            const auto dash = text.find('-');
            s.first = index(text.substr(0, dash), text);
            s.last = dash == std::string::npos ? s.first : index(text.substr(dash + 1), text);
            if (s.last < s.first)
                throw std::invalid_argument("a range A-B needs A <= B, got '" + text + "'");
            return s;
        }

        Dataset datasetOf(const Problem &problem, const QuerySelection &selection)
        {
            Dataset d;
            d.name = problem.name;
            const std::size_t n = problem.queries.size();
            std::size_t first = 0, last = n == 0 ? 0 : n - 1;
            if (!selection.all)
            {
                if (selection.last >= n)
                    throw ProblemError(problem.file, "benchmark.queries",
                                       "queries " + std::to_string(selection.first) + "-" +
                                           std::to_string(selection.last) + " requested, the problem has " +
                                           std::to_string(n) + " (0-" + std::to_string(n - 1) + ")");
                first = selection.first;
                last = selection.last;
                d.name += "[" + std::to_string(first) + "-" + std::to_string(last) + "]";
            }
            for (std::size_t i = first; i <= last && i < n; ++i)
            {
                const std::string &label = problem.queries[i].label;
                d.entries.push_back(DatasetEntry{
                    problem.file, i,
                    problem.name + " #" + std::to_string(i) + (label.empty() ? std::string() : " (" + label + ")"),
                    problem.name});
            }
            return d;
        }

        Dataset loadDatasetFolder(const std::string &folder, const QuerySelection &selection)
        {
            if (!fs::is_directory(folder))
                throw std::runtime_error(folder + ": not a folder of problem files");
            std::vector<std::string> files;
            for (const auto &e : fs::directory_iterator(folder))
                if (fs::is_regular_file(e.path()) && e.path().extension() == ".yaml")
                    files.push_back(e.path().string());
            // Directory order differs between file systems: sorted, entry i is the same problem on every machine, which
            // the experience sets (training: 0-49) rely on.
            std::sort(files.begin(), files.end());
            if (files.empty())
                throw std::runtime_error(folder + ": holds no problem file (*.yaml)");
            Dataset d;
            d.name = fs::path(folder).filename().string();
            // A folder given with a trailing '/' has an empty (or ".") last component: name it by its parent's name.
            if (d.name.empty() || d.name == ".")
                d.name = fs::path(folder).parent_path().filename().string();
            for (const auto &f : files)
            {
                const Dataset one = datasetOf(loadProblem(f), selection);
                d.entries.insert(d.entries.end(), one.entries.begin(), one.entries.end());
            }
            return d;
        }

        void checkDatasetQueries(const Problem &problem, const PlanningContext &ctx, const Dataset &dataset)
        {
            const auto space = ctx.setup->getStateSpace();
            const auto si = ctx.setup->getSpaceInformation();
            for (const auto &entry : dataset.entries)
            {
                if (entry.problemFile != problem.file || entry.query >= problem.queries.size())
                    throw ProblemError(entry.problemFile, "queries",
                                       "dataset entry '" + entry.label + "' is not a query of " + problem.file);
                const Query &q = problem.queries[entry.query];
                for (const auto *values : {&q.start, &q.goal})
                {
                    const std::string k = queryEndKey(problem, entry.query, values == &q.start ? "start" : "goal");
                    ob::ScopedState<> state(space);
                    space->copyFromReals(state.get(), *values);
                    // Wraps continuous joints into [-pi, pi) first, as the planners will see the state.
                    space->enforceBounds(state.get());
                    if (!si->satisfiesBounds(state.get()))
                        throw ProblemError(problem.file, k, "outside the state space bounds (" + entry.label + ")");
                    const std::string collision = ctx.checker->describeCollision(values->data());
                    if (!collision.empty())
                        throw ProblemError(problem.file, k, "in collision: " + collision + " (" + entry.label + ")");
                }
            }
        }
    }  // namespace tools
}  // namespace michi
