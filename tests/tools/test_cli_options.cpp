// The `michi` command line as a user (or a careless script) types it: help and version exit 0, every usage error
// exits 2 with one line that names the option, numbers never wrap, a bad --out is named before any work, and
// `--opt=value` works as `--opt value`. Everything here but the last tests stops before planning, so it is fast.
#include "support/MichiCommand.h"

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

namespace fs = boost::filesystem;

namespace
{
    using michi::test::CommandRun;
    using michi::test::problemFile;
    using michi::test::runMichi;

    const char *ALL_COMMANDS[] = {"bench",
                                  "plan",
                                  "circles",
                                  "jmap",
                                  "random-scenes",
                                  "lattice",
                                  "dualarm",
                                  "replan",
                                  "experience-queries",
                                  "path-seed-figure",
                                  "path-seed-library",
                                  "list-planners",
                                  "campaign"};

    std::size_t lines(const std::string &text)
    {
        return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    }

    class CliOptions : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            dir_ = fs::temp_directory_path() / fs::unique_path("michi-cli-options-%%%%%%%%");
            fs::create_directories(dir_);
        }
        void TearDown() override
        {
            fs::remove_all(dir_);
        }

        /** a usage error: exit code 2, one line that starts with `michi COMMAND:` and names \e option */
        void expectUsageError(const std::string &args, const std::string &command, const std::string &option)
        {
            const CommandRun run = runMichi(args);
            EXPECT_EQ(run.exitCode, 2) << args << "\n" << run.output;
            EXPECT_EQ(lines(run.output), 1u) << "one line: " << args << "\n" << run.output;
            EXPECT_EQ(run.output.rfind("michi " + command + ": ", 0), 0u) << run.output;
            EXPECT_NE(run.output.find(option), std::string::npos) << "names " << option << ": " << run.output;
            EXPECT_EQ(run.output.find("terminate"), std::string::npos) << run.output;
        }

        std::string out() const
        {
            return (dir_ / "out").string();
        }

        fs::path dir_;
    };
}  // namespace

TEST_F(CliOptions, HelpAndVersionExitZero)
{
    CommandRun run = runMichi("--help");
    EXPECT_EQ(run.exitCode, 0) << run.output;
    for (const char *command : ALL_COMMANDS)
        EXPECT_NE(run.output.find(command), std::string::npos) << "the table lists " << command;
    for (const char *command : ALL_COMMANDS)
    {
        run = runMichi(std::string(command) + " --help");
        EXPECT_EQ(run.exitCode, 0) << command << ": " << run.output;
        EXPECT_NE(run.output.find(command), std::string::npos) << run.output;
    }
    run = runMichi("bench --help");
    for (const char *option : {"--out", "--planners", "--runs", "--time", "--query", "--checker", "--verbose"})
        EXPECT_NE(run.output.find(option), std::string::npos) << option << " in " << run.output;
    run = runMichi("help plan");
    EXPECT_EQ(run.exitCode, 0);
    EXPECT_NE(run.output.find("--planner"), std::string::npos) << run.output;

    run = runMichi("--version");
    EXPECT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(std::regex_match(run.output, std::regex("michi [0-9]+\\.[0-9]+\\.[0-9]+\n"))) << run.output;
}

TEST_F(CliOptions, UnknownCommandsAndOptionsAreUsageErrors)
{
    CommandRun run = runMichi("frobnicate");
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_EQ(lines(run.output), 1u) << run.output;
    EXPECT_NE(run.output.find("frobnicate"), std::string::npos) << run.output;
    run = runMichi("");
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_EQ(lines(run.output), 1u) << run.output;

    const std::string p = problemFile("planar_2link");
    expectUsageError("bench " + p + " --out " + out() + " --frobnicate 3", "bench", "--frobnicate");
    expectUsageError("bench " + p + " --out " + out() + " --frobnicate=3", "bench", "--frobnicate");
    expectUsageError("bench " + p + " --out", "bench", "--out");                              // a missing value
    expectUsageError("bench " + p, "bench", "--out");                                         // a missing option
    expectUsageError("bench --out " + out(), "bench", "problem file");                        // a missing problem
    expectUsageError("plan " + p + " " + p + " --planner geometric::RRTConnect", "plan", p);  // one problem only
    expectUsageError("plan " + p + " --planner geometric::Nope", "plan", "geometric::Nope");
    expectUsageError("plan " + p + " --planner geometric::RRTConnect --checker jmpa", "plan", "--checker");
    expectUsageError("bench " + p + " --checker fcl,jmpa --out " + out(), "bench", "got 'fcl,jmpa'");
    expectUsageError("path-seed-library " + p + " --variant spiral --out " + out(), "path-seed-library", "--variant");
    expectUsageError("circles " + p + " --set divisions --out " + out(), "circles", "--set");
    // a parameter ConcentricCircle does not have is named by --set, not as a key of the problem file
    expectUsageError("circles " + p + " --set foo=1 --out " + out(), "circles", "--set foo: unknown parameter");
    expectUsageError("circles " + p + " --view 0,0,1 --out " + out(), "circles", "--view");
    expectUsageError("random-scenes --count 2 --out " + out() + " extra", "random-scenes", "extra");
    // the shard folders are named as the help names them, not by an internal field ("dirs is required")
    expectUsageError("campaign merge --out " + out(), "campaign", "DIR is required");
    EXPECT_FALSE(fs::exists(out()));
}

TEST_F(CliOptions, RandomScenesWithoutArmOutsideTheCheckoutNamesArm)
{
    // the default --arm is problems/planar_2link.yaml of the current folder, else the installed copy beside the
    // executable (share/michi/problems); the build tree has neither
    const fs::path before = fs::current_path();
    fs::current_path(dir_);
    expectUsageError("random-scenes --count 1 --out " + out(), "random-scenes", "--arm");
    fs::current_path(before);
    EXPECT_FALSE(fs::exists(out()));
}

TEST_F(CliOptions, IntegersAreCheckedNotWrapped)
{
    const std::string p = problemFile("planar_2link");
    // 4294967297 = 2^32 + 1 would wrap to 1 through an unsigned int; 1e12 is not an integer literal
    for (const std::string runs : {"4294967297", "1e12", "0", "-1", "2.5", "many", "", "18446744073709551617"})
        expectUsageError("bench " + p + " --out " + out() + " --runs '" + runs + "'", "bench", "--runs");
    expectUsageError("replan " + p + " --out " + out() + " --episodes 4294967297", "replan", "--episodes");
    // unknown, repeated (a duplicate key in replan.json) or no method names: usage errors of --methods (found
    // 2026-12-07: exit 1, a duplicate key, and "" taken as every method)
    const std::string passage = problemFile("dynamic_mobile_passage");
    for (const std::string methods : {"foo", "dual,dual", "dual,rrtconnect,rrtconnect", ""})
        expectUsageError("replan " + passage + " --out " + out() + " --episodes 1 --methods '" + methods + "'",
                         "replan", "--methods");
    expectUsageError("random-scenes --out " + out() + " --count 1e12", "random-scenes", "--count");
    expectUsageError("random-scenes --out " + out() + " --seed 4294967296", "random-scenes", "--seed");
    expectUsageError("random-scenes --out " + out() + " --seed 4294967295 --count 2", "random-scenes", "--seed");
    expectUsageError("random-scenes --out " + out() + " --polygons 1001", "random-scenes", "--polygons");
    expectUsageError("plan " + p + " --planner geometric::RRTConnect --seed 4294967296", "plan", "--seed");
    expectUsageError("plan " + p + " --planner geometric::RRTConnect --query 4294967296", "plan", "--query");
    expectUsageError("jmap " + p + " --out " + out() + " --verify 1e12", "jmap", "--verify");
    expectUsageError("jmap " + p + " --out " + out() + " --verify 100000001", "jmap", "--verify");
    expectUsageError("experience-queries " + p + " --out " + out() + " --count 1e12", "experience-queries", "--count");
    expectUsageError("experience-queries " + p + " --out " + out() + " --count 10 --training 11", "experience-queries",
                     "--training");
    // the message says what was expected and what was given
    const CommandRun run = runMichi("bench " + p + " --out " + out() + " --runs 1e12");
    EXPECT_NE(run.output.find("expected an integer in 1..100000, got '1e12'"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out()));
}

TEST_F(CliOptions, NumbersMustBeFiniteAndInRange)
{
    const std::string p = problemFile("planar_2link");
    for (const std::string time : {"inf", "-inf", "nan", "0", "-1", "1e7", "1e400", "pi/0", "abc"})
        expectUsageError("plan " + p + " --planner geometric::RRTConnect --time " + time, "plan", "--time");
    expectUsageError("bench " + p + " --out " + out() + " --time=inf", "bench", "--time");
    expectUsageError("lattice " + p + " --out " + out() + " --cell-sizes 0.5,inf", "lattice", "--cell-sizes");
    expectUsageError("lattice " + p + " --out " + out() + " --angle-steps 0.1,", "lattice", "--angle-steps");
    // beyond pi/2, which the planner refuses: a usage error naming the range the planner takes (it failed the run)
    expectUsageError("lattice " + p + " --out " + out() + " --angle-steps 2", "lattice", "<= 1.5708");
    expectUsageError("experience-queries " + p + " --out " + out() + " --start-spread nan", "experience-queries",
                     "--start-spread");
    // task regions replace the perturbation: a spread beside them is a usage error naming both
    expectUsageError("experience-queries " + p + " --out " + out() + " --regions r.yaml --goal-spread 0.1",
                     "experience-queries", "--regions");
    expectUsageError("dualarm " + p + " --out " + out() + " --time 0", "dualarm", "--time");
    EXPECT_FALSE(fs::exists(out()));
}

TEST_F(CliOptions, ExperienceQueriesOfAnSe2ProblemAreWrittenOrRefusedWithAReason)
{
    // An SE(2) problem has no URDF joints: perturbed queries are checked against its bounds (this crashed once,
    // reading joint limits of a robot model it does not have); task regions need an arm and say so.
    const std::string p = problemFile("se2_corridor");
    const std::string file = (dir_ / "q.yaml").string();
    const CommandRun made = runMichi("experience-queries " + p + " --out " + file + " --count 4 --training 2");
    ASSERT_EQ(made.exitCode, 0) << made.output;
    std::ifstream in(file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("training:\n  - {start: ["), std::string::npos) << text;
    EXPECT_NE(text.find("held_out:\n  - {start: ["), std::string::npos) << text;
    const std::string regions = (dir_ / "r.yaml").string();
    std::ofstream(regions) << "tip_link: x\n";
    const CommandRun refused =
        runMichi("experience-queries " + p + " --out " + (dir_ / "r-out.yaml").string() + " --regions " + regions);
    EXPECT_EQ(refused.exitCode, 1) << refused.output;
    EXPECT_NE(refused.output.find("task regions need an arm"), std::string::npos) << refused.output;
    EXPECT_FALSE(fs::exists(dir_ / "r-out.yaml"));
}

TEST_F(CliOptions, BadOutputPathsAreNamedBeforeAnyWork)
{
    const std::string p = problemFile("planar_2link");
    const fs::path file = dir_ / "afile";
    std::ofstream(file.string()) << "not a folder\n";
    for (const std::string &args :
         {"bench " + p + " --runs 1 --time 1 --out " + (file / "sub").string(),
          "plan " + p + " --planner geometric::RRTConnect --time 1 --out " + (file / "sub" / "deeper").string(),
          "jmap " + p + " --out " + file.string(), "random-scenes --count 1 --out " + (file / "x").string(),
          "experience-queries " + p + " --out " + (file / "queries.yaml").string()})
    {
        const CommandRun run = runMichi(args);
        EXPECT_NE(run.exitCode, 0) << args << "\n" << run.output;
        EXPECT_LT(run.exitCode, 128) << "crashed: " << run.output;
        EXPECT_EQ(lines(run.output), 1u) << "one line: " << run.output;
        EXPECT_NE(run.output.find("afile"), std::string::npos) << run.output;
        EXPECT_EQ(run.output.find("boost::filesystem"), std::string::npos) << run.output;
    }
    // a file output that is a folder
    const CommandRun run = runMichi("path-seed-library " + p + " --out " + dir_.string());
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(run.output.find("--out"), std::string::npos) << run.output;
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(std::ifstream(file.string()).rdbuf()), {}), "not a folder\n");
}

TEST_F(CliOptions, EqualsFormAndProblemFileNumbers)
{
    // --opt=value and --opt value alike; the time as a problem file writes it (pi/2 s)
    const CommandRun run = runMichi("plan " + problemFile("planar_2link") +
                                    " --planner=geometric::RRTConnect --time=pi/2 --seed=7 --query 0 --out=" + out());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(fs::exists(fs::path(out()) / "planar_2link-geometric__RRTConnect.path")) << run.output;
    EXPECT_TRUE(fs::exists(fs::path(out()) / "planar_2link-geometric__RRTConnect.svg")) << run.output;
}

TEST_F(CliOptions, FailedRunsExitOneWithOneLine)
{
    std::ofstream((dir_ / "broken.yaml").string()) << "name: broken\nstart: [0, 0\n";
    const CommandRun run = runMichi("plan " + (dir_ / "broken.yaml").string() + " --planner geometric::RRTConnect");
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_EQ(lines(run.output), 1u) << run.output;
    EXPECT_EQ(run.output.rfind("michi plan: ", 0), 0u) << run.output;
    EXPECT_NE(run.output.find("broken.yaml"), std::string::npos) << run.output;
}
