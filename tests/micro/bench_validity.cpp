// Micro-benchmarks of the collision stack on the bundled problems (Google Benchmark; not part of ctest).
//   build/tests/micro/bench_validity --benchmark_min_time=0.5
// Figures compare against a baseline measured in the same process: the FCL boolean check is the baseline of the
// clearance query, OMPL's DiscreteMotionValidator the baseline of michi's workspace and conservative validators,
// the conservative (exact, FCL) validator the baseline of the J-map motion validator (segments on the J-map).
#include "../../validity/src/spheres/SphereKinematics.h"

#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/ProblemJMap.h>
#include <michi/validity/fcl/ConservativeMotionValidator.h>
#include <michi/validity/jmap/JMapMotionValidator.h>
#include <michi/validity/fcl/WorkspaceMotionValidator.h>
#include <michi/validity/spheres/SphereMotionValidator.h>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include <benchmark/benchmark.h>

#include <array>
#include <mutex>

namespace
{
    struct Fixture
    {
        michi::tools::Problem problem;
        michi::tools::PlanningContext ctx;
        std::vector<ompl::base::State *> states;  // uniform samples, valid and invalid

        explicit Fixture(const std::string &name)
            : problem(michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/" + name + ".yaml"))
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

    void isValid(benchmark::State &bm, const std::string &name)
    {
        auto &f = fixture(name);
        std::size_t i = 0, valid = 0;
        for (auto _ : bm)
            valid += f.ctx.checker->isValid(f.states[i++ % f.states.size()]);
        bm.counters["valid_fraction"] = static_cast<double>(valid) / std::max<std::size_t>(1, i);
    }

    /** isValid from several threads at once (Google Benchmark's Threads): the state checks PathSeed's check_threads
        and Thunder's race share out. items_per_second over all threads, on real time, shows how they scale. The
        fixture is made before the threads start (thread 0 alone, then the others wait at the first iteration). */
    void isValidThreads(benchmark::State &bm, const std::string &name)
    {
        static std::mutex made;
        Fixture *f = nullptr;
        {
            std::lock_guard<std::mutex> lock(made);
            f = &fixture(name);
        }
        std::size_t i = static_cast<std::size_t>(bm.thread_index()) * 97, valid = 0, n = 0;
        for (auto _ : bm)
        {
            valid += f->ctx.checker->isValid(f->states[i++ % f->states.size()]);
            ++n;
        }
        bm.SetItemsProcessed(static_cast<std::int64_t>(n));
        benchmark::DoNotOptimize(valid);
    }

    /** The sphere checker of a fixture as `--checker spheres` makes it: SphereModel::enclose of the problem's
        robot (default budget), the wrist's self-pair tables and FCL for other overlapping self pairs. */
    std::shared_ptr<michi::validity::SphereValidityChecker> sphereChecker(Fixture &f)
    {
        static std::map<Fixture *, std::shared_ptr<michi::validity::SphereValidityChecker>> cache;
        auto &c = cache[&f];
        if (!c)
        {
            auto group = std::dynamic_pointer_cast<const michi::validity::RobotGroupBodies>(f.ctx.bodies);
            c = std::make_shared<michi::validity::SphereValidityChecker>(
                f.ctx.setup->getSpaceInformation(), group, michi::validity::SphereModel::enclose(*group->model()),
                f.ctx.scene, f.ctx.checker);
        }
        return c;
    }

    /** The same states as isValid, checked with the sphere checker: spheres and self-pair tables alone, or
        with FCL settling the states whose spheres touch (\e exact: collision.spheres.exact_states on). */
    void isValidSpheres(benchmark::State &bm, const std::string &name, bool exact)
    {
        auto &f = fixture(name);
        auto checker = sphereChecker(f);
        checker->setExactStates(exact);
        std::size_t i = 0, valid = 0;
        for (auto _ : bm)
            valid += checker->isValid(f.states[i++ % f.states.size()]);
        bm.counters["valid_fraction"] = static_cast<double>(valid) / std::max<std::size_t>(1, i);
    }

    /** The sphere checker's forward kinematics alone (every frame of the group, floats), on the same states: the
        part of a state check that does not depend on the scene. */
    void sphereKinematics(benchmark::State &bm, const std::string &name)
    {
        auto &f = fixture(name);
        auto group = std::dynamic_pointer_cast<const michi::validity::RobotGroupBodies>(f.ctx.bodies);
        const auto &vars = group->variables();
        std::vector<int> links;
        for (std::size_t l = 0; l < group->model()->links().size(); ++l)
            links.push_back(static_cast<int>(l));
        michi::validity::SphereKinematics kinematics(
            *group->model(), vars, group->fullConfiguration(std::vector<double>(vars.size(), 0.).data()), links);
        std::vector<michi::validity::FloatFrame> frames(kinematics.frameCount());
        std::vector<std::vector<double>> values;
        for (const auto *state : f.states)
        {
            values.emplace_back();
            f.ctx.setup->getStateSpace()->copyToReals(values.back(), state);
        }
        std::size_t i = 0;
        for (auto _ : bm)
        {
            kinematics.framesFloat(values[i++ % values.size()].data(), frames.data());
            benchmark::DoNotOptimize(frames.back().t);
        }
    }

    /** The context `--checker NAME` makes for a fixture's problem (grid, jmap, ...), made once per problem and
        checker. */
    michi::tools::PlanningContext &checkerContext(Fixture &f, const std::string &name, const std::string &checkerName)
    {
        static std::map<std::string, michi::tools::PlanningContext> contexts;
        const std::string key = name + "/" + checkerName;
        auto it = contexts.find(key);
        if (it == contexts.end())
        {
            michi::tools::ContextOptions options;
            options.checker = checkerName;
            it = contexts.emplace(key, michi::tools::makePlanningContext(f.problem, options)).first;
        }
        return it->second;
    }

    /** The same states as isValid, checked by the checker `--checker NAME` installs: the baseline is isValid on the
        same problem (FCL). */
    void isValidChecker(benchmark::State &bm, const std::string &name, const std::string &checkerName)
    {
        auto &f = fixture(name);
        const auto checker =
            checkerContext(f, name, checkerName).setup->getSpaceInformation()->getStateValidityChecker();
        std::size_t i = 0, valid = 0;
        for (auto _ : bm)
            valid += checker->isValid(f.states[i++ % f.states.size()]);
        bm.counters["valid_fraction"] = static_cast<double>(valid) / std::max<std::size_t>(1, i);
    }

    /** HeadingTable::freePose at the same states' poses: its two shortcuts (the pose's own cell occupied, an entry
        blocked at every pose) and otherwise the exact footprint test, which is what a free pose (most of them) and
        any pose the grid checker's summaries, table word and band leave open cost. */
    void gridExactTest(benchmark::State &bm, const std::string &name)
    {
        auto &f = fixture(name);
        const michi::validity::HeadingTable &table = checkerContext(f, name, "grid").grid->table();
        std::vector<std::array<double, 3>> poses;
        for (const auto *s : f.states)
        {
            const auto *se2 = s->as<ompl::base::SE2StateSpace::StateType>();
            poses.push_back({se2->getX(), se2->getY(), se2->getYaw()});
        }
        std::size_t i = 0, valid = 0;
        for (auto _ : bm)
        {
            const auto &p = poses[i++ % poses.size()];
            valid += table.freePose(p[0], p[1], p[2]);
        }
        bm.counters["valid_fraction"] = static_cast<double>(valid) / std::max<std::size_t>(1, i);
    }

    void clearance(benchmark::State &bm, const std::string &name)
    {
        auto &f = fixture(name);
        std::size_t i = 0;
        for (auto _ : bm)
            benchmark::DoNotOptimize(f.ctx.checker->clearance(f.states[i++ % f.states.size()]));
    }

    /** kind 0: OMPL's discrete, 1: conservative (FCL), 2: workspace, 3: J-map (conservative as its fallback),
        4: certified sphere motions (SphereMotionValidator);
        \e fraction: how far towards the next sample the motions go (planners mostly make short ones). */
    void motion(benchmark::State &bm, const std::string &name, int kind, double fraction = 0.1)
    {
        auto &f = fixture(name);
        auto si = f.ctx.setup->getSpaceInformation();
        std::shared_ptr<ompl::base::MotionValidator> validator;
        if (kind == 1)
            validator = std::make_shared<michi::validity::ConservativeMotionValidator>(si, f.ctx.checker);
        else if (kind == 2)
            validator = std::make_shared<michi::validity::WorkspaceMotionValidator>(si, f.ctx.checker, 0.01);
        else if (kind == 3)
        {
            auto jmap = michi::tools::makeJMapChecker(f.problem, f.ctx, f.problem.jmap);
            jmap->buildAll();  // the lazy tiles' build is not what is measured
            validator = std::make_shared<michi::validity::JMapMotionValidator>(
                si, jmap, std::make_shared<michi::validity::ConservativeMotionValidator>(si, f.ctx.checker));
        }
        else if (kind == 4)
            // the validator `--checker spheres` installs, in its own space information: its end-state check goes
            // to the sphere checker there (in the fixture's, to FCL: a fifth of the time measured before)
            validator = checkerContext(f, name, "spheres").setup->getSpaceInformation()->getMotionValidator();
        else
            validator = std::make_shared<ompl::base::DiscreteMotionValidator>(si);
        // motions between valid samples, by default short ones (a tenth of the way) as planners mostly make
        std::vector<std::pair<ompl::base::State *, ompl::base::State *>> motions;
        for (std::size_t a = 0; a + 1 < f.states.size() && motions.size() < 200; ++a)
            if (si->isValid(f.states[a]))
            {
                auto *b = si->allocState();
                si->getStateSpace()->interpolate(f.states[a], f.states[a + 1], fraction, b);
                if (si->isValid(b))
                    motions.emplace_back(f.states[a], b);
            }
        // acceptance over the distinct motions, once (the conservative validator may only accept fewer)
        std::size_t accepted = 0;
        auto spheres = std::dynamic_pointer_cast<michi::validity::SphereMotionValidator>(validator);
        const std::uint64_t piecesBefore = spheres ? spheres->checkCount() : 0;
        for (const auto &m : motions)
            accepted += validator->checkMotion(m.first, m.second);
        bm.counters["motions"] = static_cast<double>(motions.size());
        bm.counters["accepted"] = static_cast<double>(accepted);
        // the sphere validator's grown-sphere checks per motion: the work a motion costs in state checks
        if (spheres)
            bm.counters["pieces"] =
                static_cast<double>(spheres->checkCount() - piecesBefore) / static_cast<double>(motions.size());
        std::size_t i = 0;
        for (auto _ : bm)
        {
            const auto &m = motions[i++ % motions.size()];
            benchmark::DoNotOptimize(validator->checkMotion(m.first, m.second));
        }
    }

    /** RRTConnect from the problem's start to its goal, one solve per iteration (CPU time of solve() alone, with
        no OMPL Benchmark thread around it): \e spheres picks the sphere checker and its certified motions,
        otherwise FCL with the problem's motion validator. */
    void rrtConnect(benchmark::State &bm, const std::string &name, bool spheres)
    {
        auto &f = fixture(name);
        michi::tools::ContextOptions options;
        options.checker = spheres ? "spheres" : "";
        michi::tools::PlanningContext ctx = michi::tools::makePlanningContext(f.problem, options);
        auto csi = ctx.setup->getSpaceInformation();
        std::size_t solved = 0, runs = 0;
        ompl::RNG::setSeed(1);
        for (auto _ : bm)
        {
            ctx.setup->clear();
            ctx.setup->setPlanner(std::make_shared<ompl::geometric::RRTConnect>(csi));
            // a plain timed condition: solve(10.) would start and join OMPL's termination thread, about 1 ms of
            // waiting per run on this machine (DESIGN.md), more than a solve with spheres takes
            solved += ctx.setup->solve(ompl::base::timedPlannerTerminationCondition(10.)) ==
                      ompl::base::PlannerStatus::EXACT_SOLUTION;
            ++runs;
        }
        bm.counters["solved"] = static_cast<double>(solved) / std::max<std::size_t>(1, runs);
    }
}  // namespace

BENCHMARK_CAPTURE(isValid, planar_2link, std::string("planar_2link"));
BENCHMARK_CAPTURE(clearance, planar_2link, std::string("planar_2link"));
BENCHMARK_CAPTURE(motion, discrete_planar_2link, std::string("planar_2link"), 0);
BENCHMARK_CAPTURE(motion, workspace_planar_2link, std::string("planar_2link"), 2);
BENCHMARK_CAPTURE(motion, conservative_planar_2link, std::string("planar_2link"), 1);
BENCHMARK_CAPTURE(motion, jmap_planar_2link, std::string("planar_2link"), 3);
BENCHMARK_CAPTURE(motion, conservative_whole_way_planar_2link, std::string("planar_2link"), 1, 1.);
BENCHMARK_CAPTURE(motion, jmap_whole_way_planar_2link, std::string("planar_2link"), 3, 1.);
BENCHMARK_CAPTURE(isValid, xarm6_ring, std::string("xarm6_ring"));
BENCHMARK_CAPTURE(clearance, xarm6_ring, std::string("xarm6_ring"));
BENCHMARK_CAPTURE(motion, discrete_xarm6_ring, std::string("xarm6_ring"), 0);
BENCHMARK_CAPTURE(motion, workspace_xarm6_ring, std::string("xarm6_ring"), 2);
BENCHMARK_CAPTURE(motion, conservative_xarm6_ring, std::string("xarm6_ring"), 1);
BENCHMARK_CAPTURE(isValid, panda_table_pick, std::string("panda_table_pick"));
BENCHMARK_CAPTURE(isValidThreads, xarm6_ring, std::string("xarm6_ring"))->Threads(1)->Threads(2)->UseRealTime();
BENCHMARK_CAPTURE(isValidThreads, panda_table_pick, std::string("panda_table_pick"))
    ->Threads(1)
    ->Threads(2)
    ->UseRealTime();
BENCHMARK_CAPTURE(clearance, panda_table_pick, std::string("panda_table_pick"));
BENCHMARK_CAPTURE(motion, discrete_panda_table_pick, std::string("panda_table_pick"), 0);
BENCHMARK_CAPTURE(motion, workspace_panda_table_pick, std::string("panda_table_pick"), 2);
// the grid checker against FCL on a MovingAI map (same states)
BENCHMARK_CAPTURE(isValid, movingai_arena, std::string("movingai_arena"));
BENCHMARK_CAPTURE(isValidChecker, grid_movingai_arena, std::string("movingai_arena"), std::string("grid"));
BENCHMARK_CAPTURE(gridExactTest, movingai_arena, std::string("movingai_arena"));
BENCHMARK_CAPTURE(gridExactTest, movingai_64room, std::string("movingai_64room"));
BENCHMARK_CAPTURE(gridExactTest, ros_office, std::string("ros_office"));
// the sphere checker against the FCL ones above (same states, same motions)
BENCHMARK_CAPTURE(isValidSpheres, xarm6_ring, std::string("xarm6_ring"), false);
BENCHMARK_CAPTURE(isValidSpheres, panda_table_pick, std::string("panda_table_pick"), false);
BENCHMARK_CAPTURE(isValidSpheres, exact_xarm6_ring, std::string("xarm6_ring"), true);
BENCHMARK_CAPTURE(isValidSpheres, exact_panda_table_pick, std::string("panda_table_pick"), true);
BENCHMARK_CAPTURE(sphereKinematics, panda_table_pick, std::string("panda_table_pick"));
BENCHMARK_CAPTURE(motion, spheres_xarm6_ring, std::string("xarm6_ring"), 4);
BENCHMARK_CAPTURE(motion, spheres_panda_table_pick, std::string("panda_table_pick"), 4);
// planning: RRTConnect's solve() with FCL and with spheres
BENCHMARK_CAPTURE(rrtConnect, fcl_panda_table_pick, std::string("panda_table_pick"), false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rrtConnect, spheres_panda_table_pick, std::string("panda_table_pick"), true)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
