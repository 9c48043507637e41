// Tests of `michi replan` (paper 002): a short run writes replan.json with the required fields (also per baseline)
// and the episode's frames; bad input (no moving obstacle, bad extras.replan key, unknown method, bad --episodes)
// gives a clear error, a non-zero exit and no output directory.
#include "support/MichiCommand.h"
#include "support/TestScenes.h"

#include <boost/filesystem.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>
#include <sys/wait.h>

namespace fs = boost::filesystem;

namespace
{
    using michi::test::CommandRun;
    using michi::test::runMichi;

    std::string readFile(const std::string &path)
    {
        std::ifstream in(path);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }

    /** A copy of a bundled scenario with extras.replan.real_time 0 (planning charged a fixed time on the simulated
        clock, limited by a work count), written to \e dir: its episodes repeat from run to run. */
    std::string realTimeZeroCopy(michi::test::TempDir &dir, const std::string &problem)
    {
        std::string text = readFile(michi::test::sourcePath("problems/" + problem + ".yaml"));
        const auto realTime = text.find("real_time: 1");
        EXPECT_NE(realTime, std::string::npos) << problem;
        if (realTime != std::string::npos)
            text.replace(realTime, 12, "real_time: 0");
        return dir.write(problem + ".yaml", text);
    }
}  // namespace

TEST(ReplanCli, WritesResultsForMethodAndBaselines)
{
    michi::test::TempDir dir;
    const std::string out = dir.path() + "/run";
    const auto run = runMichi("replan " + michi::test::sourcePath("problems/dynamic_mobile_passage.yaml") +
                              " --episodes 2 --seed 3 --methods dual,dual-no-learning --out " + out);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string json = readFile(out + "/replan.json");
    for (const char *key : {"\"episodes\": 2", "\"reached_goal\"", "\"collisions\"", "\"stops\"", "\"deformations\"",
                            "\"replans\"", "\"replan_latency_ms_median\"", "\"replan_latency_ms_p95\"", "\"baselines\"",
                            "\"michi::DualRoadmap (no learning roadmap)\"", "\"median_latency_ratio_to_method\"",
                            "\"motion_collisions\"", "\"unavoidable_collisions\"", "\"real_time\": 1",
                            "\"clock\": \"cpu\"", "\"obstacles_yield\": false", "\"replan_cpu_ms_median\""})
        EXPECT_NE(json.find(key), std::string::npos) << key << " missing in\n" << json;
    EXPECT_TRUE(fs::exists(out + "/episode/frame_00.svg"));
    EXPECT_FALSE(fs::exists(out + ".partial"));
}

TEST(ReplanCli, BadInputIsRejectedAndWritesNothing)
{
    michi::test::TempDir dir;
    const std::string out = dir.path() + "/run";
    // a problem without moving obstacles
    auto run = runMichi("replan " + michi::test::sourcePath("problems/planar_2link.yaml") + " --out " + out);
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.output.find("moving obstacle"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out));

    // a misspelt setting
    const std::string source = readFile(michi::test::sourcePath("problems/dynamic_mobile_passage.yaml"));
    std::string bad = source;
    bad.replace(bad.find("    sense_period:"), 17, "    sense_periodd:");
    const std::string badFile = dir.write("bad.yaml", bad);
    run = runMichi("replan " + badFile + " --out " + out);
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.output.find("extras.replan.sense_periodd"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out));

    // values that would hang a run (a deformation point every nanometre) or leave the shapes' range
    for (const auto &[line, key] : std::vector<std::pair<std::string, std::string>>{
             {"    deformation_spacing: 1e-9\n", "extras.replan.deformation_spacing"},
             {"    margin: 1e9\n", "extras.replan.margin"}})
    {
        std::string extreme = source;
        const auto at = extreme.find("    margin:");
        extreme.replace(at, extreme.find('\n', at) - at + 1, line);
        run = runMichi("replan " + dir.write("extreme.yaml", extreme) + " --episodes 1 --out " + out);
        EXPECT_NE(run.exitCode, 0) << line;
        EXPECT_NE(run.output.find(key), std::string::npos) << run.output;
        EXPECT_FALSE(fs::exists(out));
    }

    run = runMichi("replan " + michi::test::sourcePath("problems/dynamic_mobile_passage.yaml") +
                   " --methods dual,nonsense --episodes 1 --out " + out);
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.output.find("nonsense"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out));

    run = runMichi("replan " + michi::test::sourcePath("problems/dynamic_mobile_passage.yaml") +
                   " --episodes 0 --out " + out);
    EXPECT_NE(run.exitCode, 0);
    EXPECT_FALSE(fs::exists(out));
}

TEST(ReplanCli, SameSeedGivesTheSameEpisodes)
{
    // extras.replan.real_time 0: planning is charged a fixed time on the simulated clock and limited by a work
    // count, so two runs with the same --seed have the same outcomes (wall-clock latencies aside). The scenario's
    // own setting (real_time 1, clock cpu) charges the CPU time really spent, which no two runs share exactly.
    michi::test::TempDir dir;
    const std::string file = realTimeZeroCopy(dir, "dynamic_mobile_passage");
    std::vector<std::string> outcomes;
    for (const char *name : {"/a", "/b"})
    {
        const auto run =
            runMichi("replan " + file + " --episodes 3 --seed 5 --methods dual --out " + dir.path() + name);
        ASSERT_EQ(run.exitCode, 0) << run.output;
        const std::string json = readFile(dir.path() + name + "/replan.json");
        std::string outcome;
        for (const char *key : {"\"reached_goal\"", "\"collisions\"", "\"stops\"", "\"deformations\"", "\"replans\"",
                                "\"replans_found\"", "\"cancelled_queries\"", "\"planning_failures\"",
                                "\"time_to_goal_s_median\"", "\"learning_edges\"", "\"episode_end_s\""})
        {
            const auto at = json.find(key);
            ASSERT_NE(at, std::string::npos) << key;
            outcome += json.substr(at, json.find('\n', at) - at) + "\n";
        }
        outcomes.push_back(outcome);
    }
    EXPECT_EQ(outcomes[0], outcomes[1]);
    EXPECT_NE(outcomes[0].find("\"replans\": "), std::string::npos);
}

TEST(ReplanCli, CorridorWithCrossingWalkersIsDrivenThroughWithoutCollision)
{
    // Issue 18's harder mobile scenario: four walkers cross a corridor and one walks down it towards the robot, none
    // of them yielding. With real_time 0 (a fixed charge per query, so the episode is the same on every run), one
    // episode per seed: DualRoadmap reaches the goal and nothing touches the robot.
    michi::test::TempDir dir;
    const std::string file = realTimeZeroCopy(dir, "dynamic_mobile_walkers");
    for (const char *seed : {"1", "2"})
    {
        SCOPED_TRACE(seed);
        const std::string out = dir.path() + "/run" + seed;
        const auto run = runMichi("replan " + file + " --episodes 1 --seed " + seed + " --methods dual --out " + out);
        ASSERT_EQ(run.exitCode, 0) << run.output;
        const std::string json = readFile(out + "/replan.json");
        for (const char *key : {"\"reached_goal\": 1,", "\"collisions\": 0,", "\"motion_collisions\": 0,",
                                "\"unavoidable_collisions\": 0,"})
            EXPECT_NE(json.find(key), std::string::npos) << key << " missing in\n" << json;
    }
}
