// The `michi` command as a user runs it: bench writes the OMPL log, the Planner Arena database, the summary and
// a picture; plan writes a path that an independent re-check accepts; bad input gives a one-line error naming the
// file, a non-zero exit and no output.
#include "support/MichiCommand.h"
#include <michi/tools/problem/PathFile.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>

namespace fs = boost::filesystem;

namespace
{
    using michi::test::CommandRun;
    using michi::test::problemFile;
    using michi::test::runMichi;
    using michi::test::slurp;

    class Cli : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            dir_ = fs::temp_directory_path() / fs::unique_path("michi-cli-%%%%%%%%");
            fs::create_directories(dir_);
        }
        void TearDown() override
        {
            fs::remove_all(dir_);
        }
        fs::path dir_;
    };
}  // namespace

TEST_F(Cli, BenchWritesLogDatabaseSummaryAndPicture)
{
    const fs::path out = dir_ / "bench";
    const CommandRun run =
        runMichi("bench " + problemFile("planar_2link") +
                 " --planners geometric::RRTConnect,geometric::PRM --runs 3 --time 1 --out " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("[6/6]"), std::string::npos) << "progress lines expected: " << run.output;
    const std::string log = slurp(out / "planar_2link.log");
    EXPECT_NE(log.find("geometric_RRTConnect"), std::string::npos);
    EXPECT_NE(log.find("geometric_PRM"), std::string::npos);
    EXPECT_NE(log.find("3 runs"), std::string::npos) << "OMPL log format: '<n> runs' per planner";
    EXPECT_EQ(slurp(out / "planar_2link.db").rfind("SQLite format 3", 0), 0u);
    const std::string summary = slurp(out / "summary.md");
    EXPECT_NE(summary.find("| geometric_RRTConnect | 3 |"), std::string::npos) << summary;
    // the Benchmark's own share of every time, measured in the same command, is reported beside the medians, and
    // its planner stays out of the user's log and database
    std::smatch clock;
    ASSERT_TRUE(
        std::regex_search(summary, clock,
                          std::regex("a planner that works 0.5 ms is booked ([0-9.e+-]+) ms, one that returns at "
                                     "once ([0-9.e+-]+) ms \\(medians of 15 runs")))
        << summary;
    // booked at least the time it worked (no timing decides the test beyond that)
    EXPECT_GE(std::stod(clock[1].str()), 0.5);
    EXPECT_GT(std::stod(clock[2].str()), 0.);
    EXPECT_EQ(log.find("SpinningPlanner"), std::string::npos);
    EXPECT_EQ(slurp(out / "planar_2link.db").find("SpinningPlanner"), std::string::npos);
    const std::string svg = slurp(out / "planar_2link.svg");
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    EXPECT_NE(svg.find("RRTConnect"), std::string::npos);
    // the PNG rendering (rsvg-convert, installed by scripts/setup.sh)
    EXPECT_EQ(slurp(out / "planar_2link.png").substr(1, 3), "PNG");
    // no staging folder left behind
    for (const auto &entry : fs::directory_iterator(dir_))
        EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
}

TEST_F(Cli, BenchComparesBothCheckersInOneRun)
{
    const fs::path out = dir_ / "both";
    const CommandRun run =
        runMichi("bench " + problemFile("planar_2link") +
                 " --planners geometric::RRTConnect --runs 2 --time 1 --checker fcl,jmap --out " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string summary = slurp(out / "summary.md");
    EXPECT_NE(summary.find("| geometric_RRTConnect | 2 | 100 % |"), std::string::npos) << summary;
    EXPECT_NE(summary.find("| geometric_RRTConnect_jmap | 2 | 100 % |"), std::string::npos) << summary;
    EXPECT_NE(slurp(out / "planar_2link.log").find("geometric_RRTConnect_jmap"), std::string::npos);
    const CommandRun typo =
        runMichi("bench " + problemFile("planar_2link") + " --checker fcl,jmpa --out " + (dir_ / "typo").string());
    EXPECT_EQ(typo.exitCode, 2) << typo.output;
    EXPECT_NE(typo.output.find("expected one of fcl, jmap, grid, spheres or fcl,X"), std::string::npos) << typo.output;
    EXPECT_FALSE(fs::exists(dir_ / "typo"));
    // an SE(2) problem has no J-map: a clear error, nothing written
    const fs::path se2 = dir_ / "se2";
    const CommandRun bad = runMichi("bench " + problemFile("se2_corridor") +
                                    " --runs 1 --time 1 --checker fcl,jmap --out " + se2.string());
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_LT(bad.exitCode, 128) << bad.output;
    EXPECT_FALSE(fs::exists(se2));
}

TEST_F(Cli, BadProblemAndBadUrdfWriteNothing)
{
    std::ofstream(dir_ / "broken.yaml") << "name: broken\nrobot: {urdf: nowhere.urdf}\nstart: [0, 0\n";
    std::ofstream(dir_ / "badurdf.yaml") << "name: badurdf\nrobot: {urdf: bad.urdf}\nstart: [0, 0]\ngoal: [1, 1]\n";
    std::ofstream(dir_ / "bad.urdf")
        << "<robot name=\"x\"><link name=\"a\"/><joint name=\"j\" type=\"revolute\"><parent link=\"a\"/></joint>"
           "</robot>\n";
    for (const std::string name : {"broken", "badurdf"})
    {
        const fs::path out = dir_ / ("out-" + name);
        const CommandRun run =
            runMichi("bench " + (dir_ / (name + ".yaml")).string() + " --runs 1 --time 1 --out " + out.string());
        EXPECT_GT(run.exitCode, 0) << run.output;
        EXPECT_LT(run.exitCode, 128) << "crashed: " << run.output;
        EXPECT_NE(run.output.find(name == "broken" ? "broken.yaml" : "bad.urdf"), std::string::npos) << run.output;
        EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << "one line: " << run.output;
        EXPECT_FALSE(fs::exists(out)) << run.output;
    }
}

TEST_F(Cli, BadPlannerNameAndOptionsAreRejected)
{
    CommandRun run = runMichi("bench " + problemFile("planar_2link") + " --planners geometric::Nope --runs 1 --out " +
                              (dir_ / "x").string());
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.output.find("geometric::Nope"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir_ / "x"));
    run = runMichi("bench " + problemFile("planar_2link") + " --runs many --out " + (dir_ / "y").string());
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.output.find("--runs"), std::string::npos) << run.output;
    run = runMichi("frobnicate");
    EXPECT_EQ(run.exitCode, 2);
}

TEST_F(Cli, PlanWritesAValidPath)
{
    const CommandRun run = runMichi("plan " + problemFile("planar_2link") +
                                    " --planner geometric::RRTConnect --time 5 --out " + dir_.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const fs::path pathFile = dir_ / "planar_2link-geometric__RRTConnect.path";
    ASSERT_TRUE(fs::exists(pathFile)) << run.output;
    EXPECT_TRUE(fs::exists(dir_ / "planar_2link-geometric__RRTConnect.svg"));
    const auto states = michi::tools::readPathFile(pathFile.string());
    ASSERT_GE(states.size(), 2u);
    // re-check the written path with a fresh checker at 1/10 of the planning resolution
    const auto problem = michi::tools::loadProblem(problemFile("planar_2link"));
    auto ctx = michi::tools::makePlanningContext(problem);
    for (std::size_t i = 0; i < problem.dimension(); ++i)
    {
        EXPECT_NEAR(states.front()[i], problem.queries[0].start[i], 1e-9);
        EXPECT_NEAR(states.back()[i], problem.queries[0].goal[i], 1e-9);
    }
    for (std::size_t k = 0; k + 1 < states.size(); ++k)
        for (int s = 0; s <= 200; ++s)
        {
            std::vector<double> q(states[k].size());
            for (std::size_t i = 0; i < q.size(); ++i)
                q[i] = states[k][i] + (states[k + 1][i] - states[k][i]) * s / 200.;
            ASSERT_TRUE(ctx.checker->isValidConfiguration(q.data())) << "segment " << k << " step " << s;
        }
}

TEST_F(Cli, PlanFailsClearlyWhenNoPathExists)
{
    // the goal region is walled off: a box around the arm's tip at the goal configuration
    std::ofstream(dir_ / "arm.urdf") << R"(<robot name="one"><link name="base"/>
      <link name="l1"><collision><origin xyz="0.25 0 0" rpy="0 1.5707963 0"/>
        <geometry><cylinder radius="0.01" length="0.5"/></geometry></collision></link>
      <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
        <limit lower="-3" upper="3" effort="1" velocity="1"/></joint></robot>)";
    std::ofstream(dir_ / "blocked.yaml") << "robot: {urdf: arm.urdf}\nscene:\n  obstacles:\n"
                                            "    - {name: a, box: [0.05, 0.2, 1], pose: {xyz: [0.3, 0.15, 0]}}\n"
                                            "    - {name: b, box: [0.05, 0.2, 1], pose: {xyz: [0.3, -0.15, 0]}}\n"
                                            "start: [1.5]\ngoal: [0]\nbenchmark: {time_limit: 0.5}\n";
    const CommandRun run = runMichi("plan " + (dir_ / "blocked.yaml").string() +
                                    " --planner geometric::RRTConnect --out " + (dir_ / "out").string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find("no path"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "blocked-geometric__RRTConnect.path"));
}

TEST_F(Cli, ListPlannersShowsStockPlanners)
{
    const CommandRun run = runMichi("list-planners");
    ASSERT_EQ(run.exitCode, 0);
    for (const char *name : {"geometric::RRTConnect", "geometric::PRM", "geometric::LazyPRM", "geometric::RRTstar",
                             "geometric::BITstar", "geometric::KPIECE1"})
        EXPECT_NE(run.output.find(name), std::string::npos) << name;
}
