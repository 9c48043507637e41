// Micro-benchmark of path seed decoding (paper 001: decoding took 2.32 ms on average in the authors' ROS
// implementation). A 6-joint, 20-waypoint seed decoded for new random start/goal pairs, both variants; encoding
// of the same path as a reference in the same process.
//   build/tests/micro/bench_path_seed --benchmark_min_time=0.5
#include <michi/planners/path_seed/PathSeedCodec.h>

#include <ompl/util/RandomNumbers.h>

#include <benchmark/benchmark.h>

namespace
{
    using michi::planners::SeedVariant;

    Eigen::VectorXd randomJoints(ompl::RNG &rng)
    {
        Eigen::VectorXd v(6);
        for (int i = 0; i < 6; ++i)
            v[i] = rng.uniformReal(-3., 3.);
        return v;
    }

    std::vector<Eigen::VectorXd> randomPath(ompl::RNG &rng)
    {
        std::vector<Eigen::VectorXd> path;
        for (int i = 0; i < 22; ++i)  // start, 20 waypoints, goal
            path.push_back(randomJoints(rng));
        return path;
    }

    void decode(benchmark::State &state, SeedVariant variant)
    {
        ompl::RNG rng(1);
        const auto seed = michi::planners::encodePath(randomPath(rng), variant);
        std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> queries;
        for (int i = 0; i < 100; ++i)  // 100 new start/goal pairs, as in the paper
            queries.emplace_back(randomJoints(rng), randomJoints(rng));
        std::size_t i = 0;
        for (auto _ : state)
        {
            const auto &q = queries[i++ % queries.size()];
            auto path = michi::planners::decodePath(seed, q.first, q.second);
            benchmark::DoNotOptimize(path.data());
        }
    }

    void encode(benchmark::State &state, SeedVariant variant)
    {
        ompl::RNG rng(1);
        const auto path = randomPath(rng);
        for (auto _ : state)
        {
            auto seed = michi::planners::encodePath(path, variant);
            benchmark::DoNotOptimize(seed.ratio.data());
        }
    }
}  // namespace

BENCHMARK_CAPTURE(decode, blocks_6joints_20waypoints, SeedVariant::BLOCKS);
BENCHMARK_CAPTURE(decode, rotation_6joints_20waypoints, SeedVariant::ROTATION);
BENCHMARK_CAPTURE(encode, blocks_6joints_20waypoints, SeedVariant::BLOCKS);
BENCHMARK_CAPTURE(encode, rotation_6joints_20waypoints, SeedVariant::ROTATION);

BENCHMARK_MAIN();
