// Micro-benchmarks of the manipulability criterion (paper 004) on the bundled dual-arm problem (Google Benchmark;
// not part of ctest):
//   build/tests/micro/bench_manipulability --benchmark_min_time=0.5
// Baselines measured in the same process: the FCL validity check of a state (what every planner pays anyway) for
// ManipulabilityObjective::stateCost, and OMPL's PathLengthOptimizationObjective::motionCost for the objective's
// motion cost (trapezoid rule, and subdivided with interpolate).
#include <michi/planners/dual_arm/ManipulabilityObjective.h>
#include <michi/tools/problem/DualArmProblem.h>
#include <michi/tools/bench/PlanningContext.h>

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/util/RandomNumbers.h>

#include <benchmark/benchmark.h>

namespace
{
    struct Fixture
    {
        michi::tools::Problem problem;
        michi::tools::PlanningContext ctx;
        std::vector<ompl::base::State *> states;
        std::shared_ptr<michi::planners::ManipulabilityObjective> manipulability, interpolated;
        std::shared_ptr<ompl::base::PathLengthOptimizationObjective> length;

        Fixture()
            : problem(michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/dual_arm.yaml"))
            , ctx(michi::tools::makePlanningContext(problem))
        {
            ompl::RNG::setSeed(7);
            auto si = ctx.setup->getSpaceInformation();
            auto sampler = si->allocStateSampler();
            for (int i = 0; i < 512; ++i)
            {
                states.push_back(si->allocState());
                sampler->sampleUniform(states.back());
            }
            const auto spec = michi::tools::loadDualArmSpec(problem);
            const michi::planners::ArmChain small(problem.model, spec.small.tip, spec.small.toolPoint);
            manipulability = std::make_shared<michi::planners::ManipulabilityObjective>(
                si, small, problem.groupVariables, problem.fixedValues, spec.settings.rows, spec.settings.threshold);
            interpolated = std::make_shared<michi::planners::ManipulabilityObjective>(
                si, small, problem.groupVariables, problem.fixedValues, spec.settings.rows, spec.settings.threshold,
                1e-6, true);
            length = std::make_shared<ompl::base::PathLengthOptimizationObjective>(si);
        }
    };

    Fixture &fixture()
    {
        static Fixture f;
        return f;
    }

    void fclIsValid(benchmark::State &bm)
    {
        auto &f = fixture();
        std::size_t i = 0;
        for (auto _ : bm)
            benchmark::DoNotOptimize(f.ctx.checker->isValid(f.states[i++ % f.states.size()]));
    }

    void manipulabilityStateCost(benchmark::State &bm)
    {
        auto &f = fixture();
        std::size_t i = 0;
        for (auto _ : bm)
            benchmark::DoNotOptimize(f.manipulability->stateCost(f.states[i++ % f.states.size()]));
    }

    template <int Which>
    void motionCost(benchmark::State &bm)
    {
        auto &f = fixture();
        const ompl::base::OptimizationObjective *objective =
            Which == 0   ? static_cast<const ompl::base::OptimizationObjective *>(f.length.get())
            : Which == 1 ? f.manipulability.get()
                         : f.interpolated.get();
        std::size_t i = 0;
        for (auto _ : bm)
        {
            benchmark::DoNotOptimize(
                objective->motionCost(f.states[i % f.states.size()], f.states[(i + 1) % f.states.size()]));
            ++i;
        }
    }
}  // namespace

BENCHMARK(fclIsValid);
BENCHMARK(manipulabilityStateCost);
BENCHMARK_TEMPLATE(motionCost, 0)->Name("motionCost/path_length");
BENCHMARK_TEMPLATE(motionCost, 1)->Name("motionCost/manipulability_trapezoid");
BENCHMARK_TEMPLATE(motionCost, 2)->Name("motionCost/manipulability_interpolated");
BENCHMARK_MAIN();
