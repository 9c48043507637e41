// Solve times of michi::ConcentricCircle against OMPL's RRTConnect (the baseline, same process, same context) on
// the problems of paper 000 (Google Benchmark; not part of ctest), with a plain timedPlannerTerminationCondition
// (no helper thread, unlike Planner::solve(t >= 1 s) and OMPL's Benchmark):
//   build/tests/micro/bench_concentric_circle --benchmark_min_time=2
// (planar_2link_jmap_clearance: with the clearance objective of michi bench --objective clearance, which adds
// ConcentricCircle's push away from obstacles; RRTConnect ignores objectives)
// Each iteration clears the planner and the solutions and solves once; RRTConnect's seed is fixed once, before the
// first benchmark (its time varies with the seed; ConcentricCircle is deterministic).
#include <michi/planners/concentric_circle/ConcentricCircle.h>
#include <michi/tools/bench/PlanningContext.h>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <benchmark/benchmark.h>

#include <map>
#include <memory>

namespace
{
    const std::string CLEARANCE = "+clearance";

    bool asksClearance(const std::string &name)
    {
        return name.size() > CLEARANCE.size() &&
               name.compare(name.size() - CLEARANCE.size(), CLEARANCE.size(), CLEARANCE) == 0;
    }

    michi::tools::Problem load(std::string name)
    {
        if (asksClearance(name))
            name.resize(name.size() - CLEARANCE.size());
        const auto colon = name.find(':');
        auto problem =
            michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/" + name.substr(0, colon) + ".yaml");
        if (colon != std::string::npos)
            problem.checker = name.substr(colon + 1);
        return problem;
    }

    struct Fixture
    {
        michi::tools::Problem problem;
        michi::tools::PlanningContext ctx;

        // name: a bundled problem, or "problem:checker" to run it with that checker (e.g. planar_2link:jmap);
        // "+clearance" at the end sets the clearance objective, as michi bench --objective clearance does
        explicit Fixture(const std::string &name) : problem(load(name)), ctx(michi::tools::makePlanningContext(problem))
        {
            if (asksClearance(name))
                ctx.setup->getProblemDefinition()->setOptimizationObjective(
                    std::make_shared<ompl::base::MaximizeMinClearanceObjective>(ctx.setup->getSpaceInformation()));
            ctx.setup->setup();
        }
    };

    Fixture &fixture(const std::string &name)
    {
        static std::map<std::string, std::unique_ptr<Fixture>> cache;
        auto &f = cache[name];
        if (!f)
            f = std::make_unique<Fixture>(name);
        return *f;
    }

    template <typename P>
    void solve(benchmark::State &bm, const std::string &name)
    {
        ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
        static const bool seeded = []
        {
            ompl::RNG::setSeed(1);
            return true;
        }();
        (void)seeded;
        auto &f = fixture(name);
        const auto si = f.ctx.setup->getSpaceInformation();
        auto planner = std::make_shared<P>(si);
        planner->setProblemDefinition(f.ctx.setup->getProblemDefinition());
        planner->setup();
        std::size_t solved = 0, runs = 0;
        for (auto _ : bm)
        {
            planner->clear();
            f.ctx.setup->getProblemDefinition()->clearSolutionPaths();
            const auto status = planner->solve(ompl::base::timedPlannerTerminationCondition(10.));
            solved += status == ompl::base::PlannerStatus::EXACT_SOLUTION;
            ++runs;
        }
        bm.counters["solved_fraction"] = static_cast<double>(solved) / std::max<std::size_t>(1, runs);
    }

    void rrtConnect(benchmark::State &bm, const std::string &name)
    {
        solve<ompl::geometric::RRTConnect>(bm, name);
    }

    void concentricCircle(benchmark::State &bm, const std::string &name)
    {
        solve<michi::planners::ConcentricCircle>(bm, name);
    }
}  // namespace

BENCHMARK_CAPTURE(rrtConnect, planar_2link_RRTConnect, std::string("planar_2link"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(concentricCircle, planar_2link_ConcentricCircle, std::string("planar_2link"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rrtConnect, planar_2link_jmap_RRTConnect, std::string("planar_2link:jmap"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(concentricCircle, planar_2link_jmap_ConcentricCircle, std::string("planar_2link:jmap"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rrtConnect, planar_2link_jmap_clearance_RRTConnect, std::string("planar_2link:jmap+clearance"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(concentricCircle, planar_2link_jmap_clearance_ConcentricCircle,
                  std::string("planar_2link:jmap+clearance"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rrtConnect, planar_3dof_hand_RRTConnect, std::string("planar_3dof_hand"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(concentricCircle, planar_3dof_hand_ConcentricCircle, std::string("planar_3dof_hand"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rrtConnect, arch_3dof_RRTConnect, std::string("arch_3dof"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(concentricCircle, arch_3dof_ConcentricCircle, std::string("arch_3dof"))
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
