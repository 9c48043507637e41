// Solve times of michi::HeadingLattice against OMPL's RRTConnect on a grid map problem's queries (Google Benchmark;
// not part of ctest), with a plain timedPlannerTerminationCondition: no termination thread, so no ~1 ms steps of
// OMPL's Benchmark clock (DESIGN.md) in the figures. Each iteration plans the next query of the problem after
// clear(), as a `michi bench --queries all` run does; the problem's checker and HeadingLattice's parameters apply.
//   build/tests/micro/bench_heading_lattice [PROBLEM.yaml [CHECKER]] [--benchmark_filter=Heading]
// (default: problems/movingai_64room.yaml; scripts/rooms_map.py OUT writes a held-out map and OUT/rooms.yaml). Each
// planner runs three passes over the queries (a fixed iteration count, so that both are timed on the same set).
#include <michi/planners/heading_lattice/HeadingLattice.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/ExperienceQueries.h>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <benchmark/benchmark.h>

#include <memory>
#include <string>

namespace
{
    struct Fixture
    {
        michi::tools::Problem problem;
        michi::tools::PlanningContext ctx;

        Fixture(const std::string &file, const std::string &checker)
            : problem(load(file, checker)), ctx(michi::tools::makePlanningContext(problem))
        {
            ctx.setup->setup();
        }

        static michi::tools::Problem load(const std::string &file, const std::string &checker)
        {
            auto problem = michi::tools::loadProblem(file);
            if (!checker.empty())
                problem.checker = checker;
            return problem;
        }
    };

    void solveQueries(benchmark::State &bm, Fixture *f, const std::string &planner)
    {
        ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
        const auto si = f->ctx.setup->getSpaceInformation();
        const auto pdef = f->ctx.setup->getProblemDefinition();
        auto p = michi::tools::makePlanner(f->problem, planner, si);
        p->setProblemDefinition(pdef);
        p->setup();
        std::size_t solved = 0, runs = 0;
        for (auto _ : bm)
        {
            bm.PauseTiming();
            michi::tools::setQuery(f->ctx, f->problem.queries[runs % f->problem.queries.size()]);
            p->clear();
            pdef->clearSolutionPaths();
            bm.ResumeTiming();
            solved += p->solve(ompl::base::timedPlannerTerminationCondition(10.)) ==
                      ompl::base::PlannerStatus::EXACT_SOLUTION;
            ++runs;
        }
        bm.counters["solved_fraction"] = static_cast<double>(solved) / std::max<std::size_t>(1, runs);
        // the lattice's work per query, beside its time: what a change to the search saves shows here first
        if (const auto *lattice = dynamic_cast<const michi::planners::HeadingLattice *>(p.get()))
        {
            const auto &w = lattice->work();
            const double n = static_cast<double>(std::max<std::size_t>(1, runs));
            bm.counters["expansions"] = static_cast<double>(w.expansions) / n;
            bm.counters["heuristic_groups"] = static_cast<double>(w.heuristicGroups) / n;
            bm.counters["shortcut_checks"] = static_cast<double>(w.shortcutChecks) / n;
            bm.counters["node_checks"] = static_cast<double>(w.nodeChecks) / n;
            bm.counters["edge_checks"] = static_cast<double>(w.edgeChecks) / n;
            bm.counters["searches"] = static_cast<double>(w.searches) / n;
        }
    }
}  // namespace

int main(int argc, char **argv)
{
    benchmark::Initialize(&argc, argv);
    ompl::RNG::setSeed(1);  // once: RRTConnect's time varies with the seed (HeadingLattice is deterministic)
    const std::string file = argc > 1 ? argv[1] : std::string(MICHI_SOURCE_DIR) + "/problems/movingai_64room.yaml";
    static Fixture fixture(file, argc > 2 ? argv[2] : "");
    const auto queries = static_cast<benchmark::IterationCount>(fixture.problem.queries.size());
    for (const std::string planner : {"michi::HeadingLattice", "geometric::RRTConnect"})
        // whole passes over the queries, so every planner is timed on the same set
        benchmark::RegisterBenchmark(planner.c_str(), solveQueries, &fixture, planner)
            ->Iterations(queries * 3)
            ->Unit(benchmark::kMillisecond);
    benchmark::RunSpecifiedBenchmarks();
    return 0;
}
