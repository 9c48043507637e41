// Dataset experience problems (issue 17): problems/mbm_<environment>.yaml names a MotionBenchMaker folder whose
// problems 0-49 train the experience planners and 50-99 are held out, each with its own scene.
#include "support/TestScenes.h"

#include <michi/planners/experience/ExperiencePeers.h>
#include <michi/planners/path_seed/PathSeed.h>
#include <michi/tools/bench/BenchmarkRunner.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/ExperienceDataset.h>
#include <michi/tools/problem/Problem.h>

#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>

namespace fs = boost::filesystem;
using michi::tools::loadProblem;
using michi::tools::Problem;

namespace
{
    const fs::path SOURCE = fs::path(MICHI_SOURCE_DIR) / "problems";

    std::set<std::string> names(const michi::validity::Scene &scene)
    {
        std::set<std::string> out;
        for (const auto &o : scene.obstacles())
            out.insert(o.name + "@" + std::to_string(o.pose.translation().x()));
        return out;
    }

    // mbm_table_pick.yaml written elsewhere with absolute paths and its experience key replaced
    std::string variant(const std::string &experience)
    {
        std::ifstream in((SOURCE / "mbm_table_pick.yaml").string());
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        for (const std::string key : {"urdf: ", "srdf: ", "moveit: ", "request: "})
        {
            const std::size_t at = text.find(key) + key.size();
            text.insert(at, SOURCE.string() + "/");
        }
        text = text.substr(0, text.find("\nexperience:") + 1) + experience + "\n";
        // one folder per test process, removed when it exits
        static const michi::test::TempDir root("michi-dataset");
        const fs::path dir = fs::path(root.path()) / fs::unique_path("%%%%%%");
        fs::create_directories(dir);
        const std::string file = (dir / "mbm.yaml").string();
        std::ofstream(file) << text;
        return file;
    }

    /** A table_pick variant trained on problems 0-1 (5 s each) and holding out \e heldOut. */
    std::string tablePick(const std::string &heldOut)
    {
        return variant("experience: {dataset: " + (SOURCE / "datasets/table_pick").string() +
                       ", training: 0-1, held_out: " + heldOut + ", training_time: 5}");
    }

    std::string error(const std::string &file, bool resolve = false)
    {
        try
        {
            const Problem p = loadProblem(file);
            if (resolve)
                michi::tools::loadExperienceDataset(p);
        }
        catch (const michi::tools::ProblemError &e)
        {
            return e.what();
        }
        return "";
    }
}  // namespace

TEST(ExperienceDataset, MbmProblemsSplitTheirFolderIntoTrainingAndHeldOut)
{
    for (const std::string env : {"table_pick", "bookshelf_small", "cage"})
    {
        const Problem problem = loadProblem((SOURCE / ("mbm_" + env + ".yaml")).string());
        ASSERT_FALSE(problem.experience.dataset.empty()) << env;
        EXPECT_TRUE(problem.experience.training.empty());
        EXPECT_TRUE(problem.experience.heldOut.empty());
        const auto sets = michi::tools::loadExperienceDataset(problem);
        ASSERT_EQ(sets.training.entries.size(), 50u) << env;
        ASSERT_EQ(sets.heldOut.entries.size(), 50u) << env;
        EXPECT_EQ(fs::path(sets.training.entries.front().problemFile).filename().string(), env + "_0001.yaml");
        EXPECT_EQ(fs::path(sets.training.entries.back().problemFile).filename().string(), env + "_0050.yaml");
        EXPECT_EQ(fs::path(sets.heldOut.entries.front().problemFile).filename().string(), env + "_0051.yaml");
        EXPECT_EQ(fs::path(sets.heldOut.entries.back().problemFile).filename().string(), env + "_0100.yaml");
        // disjoint: no held-out problem is trained on
        for (const auto &h : sets.heldOut.entries)
            for (const auto &t : sets.training.entries)
                EXPECT_NE(h.problemFile, t.problemFile);
    }
}

TEST(ExperienceDataset, BadKeysAreNamed)
{
    EXPECT_EQ(error(variant("experience: {dataset: " + (SOURCE / "datasets/table_pick").string() +
                            ", training: 0-1, held_out: 2-3}"),
                    true),
              "");
    EXPECT_NE(error(variant("experience: {dataset: " + (SOURCE / "datasets/table_pick").string() +
                            ", training: 0-10, held_out: 10-20}"))
                  .find("experience.held_out: overlaps experience.training"),
              std::string::npos);
    const std::string past = error(variant("experience: {dataset: " + (SOURCE / "datasets/table_pick").string() +
                                           ", training: 0-1, held_out: 50-120}"),
                                   true);
    EXPECT_NE(past.find("experience.held_out: problems 50-120 requested"), std::string::npos) << past;
    EXPECT_NE(error(variant("experience: {dataset: /nonexistent/folder, training: 0-1, held_out: 2-3}"))
                  .find("experience.dataset: expected a folder of problem files"),
              std::string::npos);
    EXPECT_NE(error(variant("experience: {dataset: " + (SOURCE / "datasets/table_pick").string() +
                            ", training: all, held_out: 2-3}"))
                  .find("experience.training: expected a range A-B"),
              std::string::npos);
    EXPECT_NE(error(variant("experience: {queries: q.yaml, training: 0-1}")).find("experience.training: only with"),
              std::string::npos);
}

TEST(ExperienceDataset, InstallsEachProblemsSceneAndTrainsEveryPlannerOnTheSamePaths)
{
    ompl::RNG::setSeed(4);
    const std::string file = tablePick("50-50");
    const Problem problem = loadProblem(file);
    const auto sets = michi::tools::loadExperienceDataset(problem);
    michi::tools::ContextOptions options;
    options.scene = michi::tools::copyScene(*problem.scene);
    const auto ctx = michi::tools::makePlanningContext(problem, options);
    const auto own = names(*problem.scene);

    // a training problem's scene replaces the context's; the problem's own scene is never touched
    const Problem first = loadProblem(sets.training.entries[0].problemFile);
    michi::tools::installDatasetQuery(problem, ctx, first, 0);
    EXPECT_EQ(names(*ctx.scene), names(*first.scene));
    EXPECT_NE(names(*ctx.scene), own);
    EXPECT_EQ(names(*problem.scene), own);

    const auto si = ctx.setup->getSpaceInformation();
    auto seeds = std::make_shared<michi::planners::PathSeed>(si);
    auto thunder = std::make_shared<michi::planners::ThunderPlanner>(si);
    auto lightning = std::make_shared<michi::planners::LightningPlanner>(si);
    const std::size_t learned =
        michi::tools::trainOnDataset(problem, ctx, sets.training, 5., {seeds, thunder, lightning}, nullptr);
    EXPECT_EQ(learned, 2u);  // both table_pick problems are solved by RRT-Connect in 5 s
    EXPECT_EQ(seeds->experienceCount(), learned);
    EXPECT_EQ(thunder->experienceCount(), learned);
    EXPECT_EQ(lightning->experienceCount(), learned);
    // training leaves its last problem's scene installed; the held-out problem then installs its own
    const Problem held = loadProblem(sets.heldOut.entries[0].problemFile);
    michi::tools::installDatasetQuery(problem, ctx, held, 0);
    EXPECT_EQ(names(*ctx.scene), names(*held.scene));
    thunder->sceneChanged();  // forgets its edge checks, keeps its paths
    EXPECT_EQ(thunder->experienceCount(), learned);
}

// michi plan: an experience planner learns what the problem teaches, then plans in the problem's own scene and query
TEST(ExperienceDataset, LearnBeforePlanningTrainsThenRestoresTheProblemsSceneAndQuery)
{
    ompl::RNG::setSeed(4);
    const std::string file = tablePick("50-50");
    const Problem problem = loadProblem(file);
    michi::tools::ContextOptions options;
    options.scene = michi::tools::copyScene(*problem.scene);
    const auto ctx = michi::tools::makePlanningContext(problem, options);
    const auto si = ctx.setup->getSpaceInformation();
    const auto pdef = ctx.setup->getProblemDefinition();
    std::vector<double> start, goal;
    si->getStateSpace()->copyToReals(start, pdef->getStartState(0));
    const auto own = names(*problem.scene);

    auto seeds = std::make_shared<michi::planners::PathSeed>(si);
    EXPECT_EQ(michi::tools::learnBeforePlanning(problem, ctx, seeds, 0, nullptr), 2u);
    EXPECT_EQ(seeds->experienceCount(), 2u);
    // the last training problem's scene and start were installed while learning; the problem's are back
    EXPECT_EQ(names(*ctx.scene), own);
    std::vector<double> after;
    si->getStateSpace()->copyToReals(after, ctx.setup->getProblemDefinition()->getStartState(0));
    EXPECT_EQ(after, start);

    // a planner that learns nothing is left alone; a context sharing the problem's scene is a programming error
    auto rrt = std::make_shared<ompl::geometric::RRTConnect>(si);
    EXPECT_EQ(michi::tools::learnBeforePlanning(problem, ctx, rrt, 0, nullptr), 0u);
    const auto shared = michi::tools::makePlanningContext(problem, 0);
    EXPECT_THROW(michi::tools::learnBeforePlanning(problem, shared, seeds, 0, nullptr), std::logic_error);
}

TEST(ExperienceDataset, ADatasetProblemWithAnotherRobotIsRefused)
{
    const Problem problem = loadProblem((SOURCE / "mbm_table_pick.yaml").string());
    michi::tools::ContextOptions options;
    options.scene = michi::tools::copyScene(*problem.scene);
    const auto ctx = michi::tools::makePlanningContext(problem, options);
    const Problem ring = loadProblem((SOURCE / "xarm6_ring.yaml").string());
    try
    {
        michi::tools::installScene(problem, ctx, ring);
        FAIL() << "an xArm6 problem was installed in a Panda dataset";
    }
    catch (const michi::tools::ProblemError &e)
    {
        EXPECT_NE(std::string(e.what()).find("xarm6_ring.yaml: robot: plans other joints"), std::string::npos)
            << e.what();
    }
}

TEST(ExperienceDataset, ADatasetProblemWhoseRobotHoldsAToolIsRefused)
{
    // The same seven joints, but a box grasped in the hand (panda_grasp.urdf): the entry was planned with the
    // dataset problem's bare Panda, and its paths reported solved and certified through the tool.
    const Problem problem = loadProblem((SOURCE / "mbm_table_pick.yaml").string());
    michi::tools::ContextOptions options;
    options.scene = michi::tools::copyScene(*problem.scene);
    const auto ctx = michi::tools::makePlanningContext(problem, options);
    std::ifstream in((SOURCE / "datasets/table_pick/table_pick_0001.yaml").string());
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string dir = (SOURCE / "datasets/table_pick").string() + "/";
    for (const std::string key : {"urdf: ", "srdf: ", "moveit: ", "request: "})
        text.insert(text.find(key) + key.size(), dir);
    static const michi::test::TempDir root("michi-dataset-robot");
    const std::string same = (fs::path(root.path()) / "same.yaml").string();
    std::ofstream(same) << text;
    const std::string urdf = "robots/panda/panda.urdf";
    text.replace(text.find(urdf), urdf.size(), "robots/panda/panda_grasp.urdf");
    const std::string tool = (fs::path(root.path()) / "tool.yaml").string();
    std::ofstream(tool) << text;

    // the same robot loaded from another problem file is one robot
    EXPECT_NO_THROW(michi::tools::installScene(problem, ctx, loadProblem(same)));
    try
    {
        michi::tools::installScene(problem, ctx, loadProblem(tool));
        FAIL() << "a Panda holding a tool was installed in a dataset of the bare Panda";
    }
    catch (const michi::tools::ProblemError &e)
    {
        EXPECT_NE(std::string(e.what()).find("tool.yaml: robot: differs from"), std::string::npos) << e.what();
    }
}

TEST(ExperienceDataset, BenchRunsEachHeldOutProblemOncePerPlanner)
{
    ompl::RNG::setSeed(5);
    const std::string file = tablePick("50-51");
    const Problem problem = loadProblem(file);
    michi::tools::BenchOptions options;
    options.planners = {"michi::PathSeed", "geometric::RRTConnect"};
    options.timeLimit = 10.;
    options.outDir = (fs::path(file).parent_path() / "out").string();
    const auto result = michi::tools::runBenchmark(problem, options);
    ASSERT_EQ(result.planners.size(), 2u);
    for (const auto &p : result.planners)
        EXPECT_EQ(p.runs, 2u) << p.name;  // runs = held-out problems
    // run i of every planner planned held-out problem 50 + i (the run property held_out_problem)
    const std::string command = "sqlite3 '" + result.database +
                                "' \"select p.name, held_out_problem from runs join plannerConfigs p on "
                                "p.id = runs.plannerid order by runs.id\" 2>&1";
    std::string rows;
    if (FILE *pipe = popen(command.c_str(), "r"))
    {
        char buffer[256];
        while (fgets(buffer, sizeof buffer, pipe))
            rows += buffer;
        pclose(pipe);
    }
    EXPECT_EQ(rows, "geometric_PathSeed|50\ngeometric_PathSeed|51\ngeometric_RRTConnect|50\ngeometric_RRTConnect|51\n");
}
