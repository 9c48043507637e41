// Path seed library, fail-fast path check, repairs and the michi::PathSeed planner (paper 001).
#include "support/ConformanceProblem.h"
#include "support/TestScenes.h"

#include <michi/planners/path_seed/PathSeed.h>
#include <michi/planners/path_seed/PathSeedLibrary.h>
#include <michi/planners/path_seed/PathSeedRepair.h>
#include <michi/tools/problem/ExperienceQueries.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <boost/filesystem.hpp>

#include <atomic>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace fs = boost::filesystem;
namespace ob = ompl::base;
namespace og = ompl::geometric;
using michi::planners::PathSeed;
using michi::planners::PathSeedFileError;
using michi::planners::PathSeedLibrary;
using michi::planners::SeedVariant;

namespace
{
    Eigen::VectorXd vec(std::initializer_list<double> v)
    {
        Eigen::VectorXd out(v.size());
        int i = 0;
        for (double x : v)
            out[i++] = x;
        return out;
    }

    std::string tempFile(const std::string &name)
    {
        // one folder per test process, removed when it exits; a file name is used once per test
        static const michi::test::TempDir root("michi-path-seed");
        const fs::path dir = fs::path(root.path()) / fs::unique_path("%%%%%%");
        fs::create_directories(dir);
        return (dir / name).string();
    }

    void writeText(const std::string &file, const std::string &text)
    {
        std::ofstream out(file);
        out << text;
    }

    std::string loadError(const std::string &file)
    {
        try
        {
            PathSeedLibrary::load(file);
        }
        catch (const PathSeedFileError &e)
        {
            return e.what();
        }
        return "";
    }

    og::PathGeometric makePath(const ob::SpaceInformationPtr &si, const std::vector<std::vector<double>> &values)
    {
        og::PathGeometric path(si);
        ob::ScopedState<> s(si->getStateSpace());
        for (const auto &v : values)
        {
            s = v;
            path.append(s.get());
        }
        return path;
    }
}  // namespace

TEST(PathSeedLibrary, SavesAndLoadsTheSameSeeds)
{
    for (SeedVariant variant : {SeedVariant::BLOCKS, SeedVariant::ROTATION})
    {
        PathSeedLibrary lib(variant);
        ompl::RNG rng(2);
        for (int i = 0; i < 4; ++i)
        {
            std::vector<Eigen::VectorXd> path;
            for (int k = 0; k < 3 + i; ++k)
                path.push_back(vec({rng.uniformReal(-2, 2), rng.uniformReal(-2, 2), rng.uniformReal(-2, 2),
                                    rng.uniformReal(-2, 2), rng.uniformReal(-2, 2)}));
            lib.add(path);
        }
        const std::string file = tempFile("lib.seeds");
        lib.save(file);
        const auto loaded = PathSeedLibrary::load(file);
        ASSERT_EQ(loaded->size(), lib.size());
        EXPECT_EQ(loaded->variant(), variant);
        EXPECT_EQ(loaded->dimension(), 5u);
        const Eigen::VectorXd s = vec({0.1, 0.2, 0.3, 0.4, 0.5}), g = vec({-1, 1, -1, 1, -1});
        for (std::size_t i = 0; i < lib.size(); ++i)
        {
            const auto a = michi::planners::decodePath(lib.seed(i).code, s, g);
            const auto b = michi::planners::decodePath(loaded->seed(i).code, s, g);
            ASSERT_EQ(a.size(), b.size());
            for (std::size_t k = 0; k < a.size(); ++k)
                EXPECT_EQ((a[k] - b[k]).norm(), 0.);  // 17 significant digits: bit-exact
        }
    }
}

TEST(PathSeedLibrary, RefusesAPathWhoseSeedIsNotFinite)
{
    // Found by a tester's sweep: finite joint values of ~1e155 or more overflow a seed's length and deviation to
    // inf; add() kept it, save() wrote "seed 1 inf" and load() then refused the whole file (every seed lost).
    const std::vector<Eigen::VectorXd> overflowing = {vec({0, 0, 0}), vec({1e200, 0, 0}), vec({1, 1, 1})};
    for (SeedVariant variant : {SeedVariant::BLOCKS, SeedVariant::ROTATION})
    {
        PathSeedLibrary lib(variant);
        lib.add({vec({0, 0, 0}), vec({0.5, 1, 0}), vec({1, 1, 1})});
        try
        {
            lib.add(overflowing);
            ADD_FAILURE() << "a path whose seed is not finite was added";
        }
        catch (const std::invalid_argument &e)
        {
            EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
        }
        EXPECT_EQ(lib.size(), 1u);
        // what save() writes, load() reads back
        const std::string file = tempFile("finite.seeds");
        lib.save(file);
        EXPECT_EQ(loadError(file), "");
        EXPECT_EQ(PathSeedLibrary::load(file)->size(), 1u);
    }
}

TEST(PathSeedLibrary, BadFilesGiveClearErrors)
{
    EXPECT_NE(loadError("/no/such/file.seeds").find("cannot open"), std::string::npos);
    const std::string file = tempFile("bad.seeds");
    writeText(file, "hello 1\n");
    EXPECT_NE(loadError(file).find(file + ": line 1: not a path seed library"), std::string::npos) << loadError(file);
    writeText(file, "michi-path-seed-library 99\n");
    EXPECT_NE(loadError(file).find("line 1: unsupported version"), std::string::npos) << loadError(file);
    // a valid library, then cut short and then corrupted
    PathSeedLibrary lib;
    lib.add({vec({0, 0, 0}), vec({1, 1, 0}), vec({2, 0, 0})});
    lib.save(file);
    std::ifstream in(file);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    writeText(file, text.substr(0, text.find("deviation")));
    EXPECT_NE(loadError(file).find("unexpected end of file"), std::string::npos) << loadError(file);
    std::string corrupt = text;
    corrupt.replace(corrupt.find("ratio 1 ") + 8, 1, "x");
    writeText(file, corrupt);
    EXPECT_NE(loadError(file).find("'ratio': value 1 of 1 missing or not a finite number"), std::string::npos)
        << loadError(file);
    // the planner names the file too, and keeps its library
    auto problem = michi::test::makeConformanceProblem();
    PathSeed planner(problem.setup->getSpaceInformation());
    EXPECT_THROW(planner.setLibraryFile(file), PathSeedFileError);
    EXPECT_EQ(planner.experienceCount(), 0u);
}

TEST(PathSeedLibrary, CandidatesAreTheNearestQueries)
{
    PathSeedLibrary lib;
    for (double x : {0., 1., 2., 3.})
        lib.add({vec({x, 0, 0}), vec({x, 1, 0}), vec({x, 2, 0})});
    const auto c = lib.candidates(vec({2.1, 0, 0}), vec({2.1, 2, 0}), 2);
    ASSERT_EQ(c.size(), 2u);
    EXPECT_DOUBLE_EQ(c[0].start[0], 2.);
    EXPECT_DOUBLE_EQ(c[1].start[0], 3.);
    EXPECT_EQ(lib.candidates(vec({0, 0}), vec({0, 0}), 2).size(), 0u);  // wrong dimension: nothing
    EXPECT_THROW(lib.add({vec({0, 0}), vec({1, 1})}), std::invalid_argument);
}

TEST(PathSeedRepair, FailFastCheckAgreesWithPathCheck)
{
    // xarm6_ring: workspace motion validator, so the round-robin bisection order is used
    const auto problem = michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/xarm6_ring.yaml");
    const auto ctx = michi::tools::makePlanningContext(problem);
    const auto si = ctx.setup->getSpaceInformation();
    ompl::RNG::setSeed(4);
    auto sampler = si->allocValidStateSampler();
    michi::planners::CheckThreads helpers(1);
    int valid = 0, invalid = 0;
    for (int i = 0; i < 20; ++i)
    {
        og::PathGeometric path(si);
        ob::State *s = si->allocState();
        for (int k = 0; k < 3; ++k)
        {
            sampler->sample(s);
            path.append(s);
        }
        si->freeState(s);
        const bool fast = michi::planners::checkPathFailFast(si, path, ob::plannerNonTerminatingCondition());
        EXPECT_EQ(fast, path.check()) << i;
        // two threads sharing the checks: the same answer
        EXPECT_EQ(michi::planners::checkPathFailFast(si, path, ob::plannerNonTerminatingCondition(), nullptr, 2), fast)
            << i;
        // the same two threads kept as a planner keeps them (check_threads 2): the same answer, the same count
        unsigned long started = 0, kept = 0;
        michi::planners::checkPathFailFast(si, path, ob::plannerNonTerminatingCondition(), &started, 2);
        EXPECT_EQ(
            michi::planners::checkPathFailFast(si, path, ob::plannerNonTerminatingCondition(), &kept, 2, &helpers),
            fast)
            << i;
        if (fast)
            EXPECT_EQ(kept, started) << i;  // a valid path costs every check, however they are shared
        (fast ? valid : invalid)++;
    }
    EXPECT_GT(invalid, 0);
    // a known valid path: the main query's start and goal through a waypoint is at least checked consistently
    const auto v = michi::planners::checkPathFull(si, makePath(si, {problem.queries[0].start, problem.queries[0].goal}),
                                                  ob::plannerNonTerminatingCondition());
    EXPECT_EQ(v.state.size(), 2u);
    EXPECT_EQ(v.invalidStates(), 0u);
}

namespace
{
    /** For a job 0 that must see \e n jobs begun (helpers that do begin share the work): waits up to 10 s, so a
        helper that never comes fails the test instead of hanging it. */
    void awaitBegun(const std::atomic<int> &begun, int n)
    {
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (begun.load() < n && std::chrono::steady_clock::now() < until)
            std::this_thread::yield();
    }
}  // namespace

TEST(CheckThreads, EveryHandOutRunsEachJobAtMostOnceAndRethrowsAHelpersError)
{
    michi::planners::CheckThreads helpers(2, 0);  // no polling: helpers sleep between hand-outs
    EXPECT_EQ(helpers.helpers(), 2u);
    for (unsigned int round = 0; round < 200; ++round)
    {
        const unsigned int count = 1 + round % 3;
        std::vector<std::atomic<int>> ran(3);
        std::atomic<int> begun{0};
        helpers.share(count,
                      [&](unsigned int t)
                      {
                          ++begun;
                          ++ran[t];
                          if (t == 0)
                              awaitBegun(begun, static_cast<int>(count));
                      });
        // job 0 waited for the others: each index of the hand-out ran once, the others not at all
        for (unsigned int t = 0; t < 3; ++t)
            ASSERT_EQ(ran[t].load(), t < count ? 1 : 0) << "round " << round << " job " << t;
    }
    // more jobs than helpers + 1: the extra ones are not run
    std::atomic<int> jobs{0};
    helpers.share(5,
                  [&](unsigned int t)
                  {
                      ++jobs;
                      if (t == 0)
                          awaitBegun(jobs, 3);
                  });
    EXPECT_EQ(jobs.load(), 3);
    std::atomic<int> begun{0};
    EXPECT_THROW(helpers.share(3,
                               [&](unsigned int t)
                               {
                                   ++begun;
                                   if (t == 0)
                                       awaitBegun(begun, 3);
                                   if (t == 2)
                                       throw std::runtime_error("helper failed");
                               }),
                 std::runtime_error);
    // still usable after an error
    jobs = 0;
    helpers.share(3,
                  [&](unsigned int t)
                  {
                      ++jobs;
                      if (t == 0)
                          awaitBegun(jobs, 3);
                  });
    EXPECT_EQ(jobs.load(), 3);
}

TEST(CheckThreads, ShareSkipsHelpersThatHaveNotBegunAndNeverRunsAJobAfterItReturns)
{
    for (unsigned int spin : {0u, 200u})
    {
        michi::planners::CheckThreads helpers(1, spin);
        for (unsigned int round = 0; round < 300; ++round)
        {
            // the jobs claim items from one counter: whoever runs, every item is done exactly once
            const std::size_t n = round % 4 == 0 ? 1 : 64;
            std::vector<std::atomic<int>> done(n);
            std::atomic<std::size_t> next{0};
            std::atomic<bool> returned{false}, lateJob{false};
            std::atomic<int> ran{0};
            helpers.share(2,
                          [&](unsigned int)
                          {
                              ++ran;
                              if (returned.load())
                                  lateJob = true;
                              for (std::size_t i = next++; i < n; i = next++)
                                  ++done[i];
                          });
            returned = true;
            for (std::size_t i = 0; i < n; ++i)
                ASSERT_EQ(done[i].load(), 1) << "spin " << spin << " round " << round << " item " << i;
            ASSERT_GE(ran.load(), 1);
            ASSERT_LE(ran.load(), 2);
            ASSERT_FALSE(lateJob.load()) << "a helper began after share() returned";
        }
        // a helper that begins while the caller's job runs does share the work: here the caller's job waits for it
        std::atomic<int> began{0};
        std::atomic<std::size_t> next{0};
        std::vector<std::atomic<int>> done(64);
        helpers.share(2,
                      [&](unsigned int t)
                      {
                          ++began;
                          if (t == 0)
                              awaitBegun(began, 2);
                          for (std::size_t i = next++; i < done.size(); i = next++)
                              ++done[i];
                      });
        EXPECT_EQ(began.load(), 2) << "spin " << spin;
        for (auto &d : done)
            EXPECT_EQ(d.load(), 1);
    }
}

TEST(PathSeedRepair, RRTConnectRepairsAnInvalidStretch)
{
    ompl::RNG::setSeed(3);
    auto problem = michi::test::makeConformanceProblem();
    problem.setup->setup();
    const auto si = problem.setup->getSpaceInformation();
    // the straight motion from start to goal sweeps link 2 through the upper-right box
    auto path = makePath(si, {{0.2, 0.3}, {0.7, -0.05}, {1.2, -0.4}});
    EXPECT_FALSE(path.check());
    const auto before = michi::planners::checkPathFull(si, path, ob::plannerNonTerminatingCondition());
    EXPECT_GT(before.invalidStates() + before.invalidSegments(), 0u);
    ASSERT_TRUE(michi::planners::repairWithRRTConnect(si, path, ob::timedPlannerTerminationCondition(10.)));
    EXPECT_TRUE(path.check());
    EXPECT_EQ(michi::test::independentPathCheck(path), "");
    EXPECT_TRUE(si->equalStates(path.getState(0), problem.setup->getProblemDefinition()->getStartState(0)));
}

TEST(PathSeedPlanner, RecallsALearnedPathForANearbyQuery)
{
    ompl::RNG::setSeed(5);
    auto problem = michi::test::makeConformanceProblem();
    auto si = problem.setup->getSpaceInformation();
    auto planner = std::make_shared<PathSeed>(si);
    planner->setRace(false);
    problem.setup->setPlanner(planner);
    ASSERT_EQ(problem.setup->solve(10.), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(planner->getLastSource(), "scratch");
    EXPECT_EQ(planner->experienceCount(), 1u);  // learned
    // the same query again: the seed decodes to the learned path, which is valid
    planner->clear();
    problem.setup->getProblemDefinition()->clearSolutionPaths();
    ASSERT_EQ(problem.setup->solve(10.), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(planner->getLastSource(), "recall");
    EXPECT_EQ(planner->experienceCount(), 1u);  // a valid recall is not learned again
    // a nearby query: recalled or repaired, never from scratch, and valid
    planner->clear();
    ob::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
    start = std::vector<double>{0.25, 0.25};
    goal = std::vector<double>{1.15, -0.35};
    problem.setup->setStartAndGoalStates(start, goal);
    ASSERT_EQ(problem.setup->solve(10.), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_NE(planner->getLastSource(), "scratch");
    EXPECT_TRUE(problem.setup->getSolutionPath().check());
    EXPECT_EQ(michi::test::independentPathCheck(problem.setup->getSolutionPath()), "");
    // the library survives clear() and can be saved and loaded by parameter
    const std::string file = tempFile("conformance.seeds");
    planner->saveLibrary(file);
    auto other = std::make_shared<PathSeed>(si);
    ASSERT_TRUE(other->params().setParam("library_file", file));
    EXPECT_EQ(other->experienceCount(), planner->experienceCount());
}

TEST(ExperienceQueries, BadFilesAreNamedWithTheirKey)
{
    // xarm6_ring.yaml with absolute paths, written elsewhere, pointing at experience files we break on purpose
    const fs::path source = fs::path(MICHI_SOURCE_DIR) / "problems";
    std::ifstream in((source / "xarm6_ring.yaml").string());
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const std::string key : {"urdf: ", "file: "})  // the robot's URDF and the ring's mesh
    {
        const std::size_t at = text.find(key + (key == "urdf: " ? "robots/" : "meshes/")) + key.size();
        text.insert(at, source.string() + "/");
    }
    const std::string problemFile = tempFile("ring.yaml");
    const fs::path dir = fs::path(problemFile).parent_path();
    auto withQueries = [&](const std::string &queries)
    {
        std::string t = text;
        const std::string key = "experience/ring_task_queries.yaml";
        t.replace(t.find(key), key.size(), "queries.yaml");
        writeText(problemFile, t);
        writeText((dir / "queries.yaml").string(), queries);
    };
    auto error = [&]() -> std::string
    {
        try
        {
            michi::tools::loadProblem(problemFile);
        }
        catch (const michi::tools::ProblemError &e)
        {
            return e.what();
        }
        return "";
    };
    withQueries(
        "training: []\nheld_out:\n  - {start: [0, 0, 0, 0, 0, 0], goal: [0, 0.6842, -1.4954, 0, -0.7596, 0]}\n");
    ASSERT_EQ(error(), "");
    const auto problem = michi::tools::loadProblem(problemFile);
    EXPECT_EQ(problem.experience.training.size(), 0u);
    ASSERT_EQ(problem.experience.heldOut.size(), 1u);
    withQueries("held_out:\n  - {start: [0, 0, 0], goal: [0, 0, 0, 0, 0, 0]}\n");
    EXPECT_NE(error().find("held_out[0].start: expected 6 numbers, got 3"), std::string::npos) << error();
    withQueries("held_out:\n  - {start: [9, 0, 0, 0, 0, 0], goal: [0, 0, 0, 0, 0, 0]}\n");
    EXPECT_NE(error().find("held_out[0].start[0]: value 9 outside the limits"), std::string::npos) << error();
    withQueries("trainig: []\n");
    EXPECT_NE(error().find("trainig: unknown key"), std::string::npos) << error();
    fs::remove(dir / "queries.yaml");
    EXPECT_NE(error().find("experience.queries: file"), std::string::npos) << error();
    // a held-out goal in collision is found before a benchmark: find a colliding state, then use it
    withQueries("held_out:\n  - {start: [0, 0, 0, 0, 0, 0], goal: [0, 0, 0, 0, 0, 0]}\n");
    const auto p2 = michi::tools::loadProblem(problemFile);
    const auto ctx = michi::tools::makePlanningContext(p2);
    ompl::RNG rng(9);
    std::vector<double> colliding(6);
    do
        for (int k = 0; k < 6; ++k)
            colliding[k] = rng.uniformReal(-1., 1.);
    while (ctx.checker->describeCollision(colliding.data()).empty());
    std::ostringstream q;
    q << "held_out:\n  - {start: [0, 0, 0, 0, 0, 0], goal: [";
    for (int k = 0; k < 6; ++k)
        q << (k ? ", " : "") << std::setprecision(17) << colliding[k];
    q << "]}\n";
    withQueries(q.str());
    const auto p3 = michi::tools::loadProblem(problemFile);
    try
    {
        michi::tools::checkHeldOutQueries(p3, ctx);
        ADD_FAILURE() << "a colliding held-out goal was accepted";
    }
    catch (const michi::tools::ProblemError &e)
    {
        EXPECT_NE(std::string(e.what()).find("held_out[0].goal: in collision"), std::string::npos) << e.what();
    }
}

TEST(PathSeedPlanner, CheckThreadsBeyondTheirRangeAreRefused)
{
    // Found 2026-12-07 through the C++ API: check_threads 100000 (or -1, which wraps) started helper threads until
    // std::system_error ended the process.
    auto space = std::make_shared<ompl::base::RealVectorStateSpace>(2);
    space->setBounds(-1., 1.);
    auto si = std::make_shared<ompl::base::SpaceInformation>(space);
    michi::planners::PathSeed planner(si);
    EXPECT_THROW(planner.setCheckThreads(100000), ompl::Exception);
    EXPECT_THROW(planner.params().setParam("check_threads", "-1"), ompl::Exception);
    EXPECT_TRUE(planner.params().setParam("check_threads", "8"));
    EXPECT_EQ(planner.getCheckThreads(), 8u);
}

TEST(PathSeedPlanner, LibraryFileAndVariantAgreeWhicheverIsSetFirst)
{
    // Found by a tester's sweep: OMPL applies a problem's params in name order, so library_file was loaded
    // before variant, and a variant other than the file's replaced the loaded library with an empty one: every run
    // planned from scratch while the settings still named the library file.
    auto space = std::make_shared<ob::RealVectorStateSpace>(3);
    space->setBounds(-2., 2.);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    std::map<SeedVariant, std::string> files;
    for (SeedVariant variant : {SeedVariant::BLOCKS, SeedVariant::ROTATION})
    {
        PathSeedLibrary lib(variant);
        lib.add({vec({0, 0, 0}), vec({0.5, 1, 0}), vec({1, 1, 1})});
        lib.add({vec({1, 0, 0}), vec({0.5, 1, 1}), vec({-1, 1, 1})});
        // named without the variants' names, so that a message naming them does not find them in the file's name
        files[variant] = tempFile(variant == SeedVariant::BLOCKS ? "b.seeds" : "r.seeds");
        lib.save(files[variant]);
    }
    for (const auto &[fileVariant, file] : files)
        for (SeedVariant wanted : {SeedVariant::BLOCKS, SeedVariant::ROTATION})
            for (bool fileFirst : {true, false})
            {
                const std::string name = michi::planners::seedVariantName(wanted);
                SCOPED_TRACE(michi::planners::seedVariantName(fileVariant) + " file, variant " + name +
                             (fileFirst ? ", library_file first" : ", variant first"));
                PathSeed planner(si);
                std::string error;
                try
                {
                    for (const std::string key :
                         {fileFirst ? "library_file" : "variant", fileFirst ? "variant" : "library_file"})
                        EXPECT_TRUE(planner.params().setParam(key, key == "variant" ? name : file));
                }
                catch (const ompl::Exception &e)
                {
                    error = e.what();
                }
                if (fileVariant == wanted)
                {
                    EXPECT_EQ(error, "");
                    EXPECT_EQ(planner.experienceCount(), 2u);  // the file's seeds are in use
                    EXPECT_EQ(planner.getVariant(), name);
                    EXPECT_EQ(planner.getLibraryFile(), file);
                }
                else
                {
                    // refused, naming the file and both variants
                    EXPECT_NE(error.find(file), std::string::npos) << error;
                    EXPECT_NE(error.find(michi::planners::seedVariantName(fileVariant)), std::string::npos) << error;
                    EXPECT_NE(error.find(name), std::string::npos) << error;
                }
                // never a planner that names a library file and holds other seeds than the file's
                if (!planner.getLibraryFile().empty())
                {
                    EXPECT_EQ(planner.experienceCount(), 2u);
                    EXPECT_EQ(planner.getVariant(), michi::planners::seedVariantName(fileVariant));
                }
            }
    // all params at once, as michi bench sets them (ParamSet::setParams goes in name order)
    PathSeed planner(si);
    EXPECT_THROW(planner.params().setParams({{"variant", "rotation"}, {"library_file", files[SeedVariant::BLOCKS]}}),
                 ompl::Exception);
    // without a library file the variant starts an empty library of its own, as before
    PathSeed fresh(si);
    fresh.setLibrary(PathSeedLibrary::load(files[SeedVariant::BLOCKS]));
    fresh.setVariant("rotation");
    EXPECT_EQ(fresh.getVariant(), "rotation");
    EXPECT_EQ(fresh.experienceCount(), 0u);
}
