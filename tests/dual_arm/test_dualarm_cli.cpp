// `michi dualarm` as a user runs it (on a coarse grid so it takes a few seconds): it writes dualarm.json with the
// work positions and the stirring motion's manipulability, and the pictures; a problem without a dual_arm section
// or with a misspelt key gives a one-line error naming the file and key, a non-zero exit and no output folder; an
// analysis that finds no work position says why; a rerun without --html removes the earlier run's replay page.
#include "support/MichiCommand.h"
#include "support/TestScenes.h"

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

namespace fs = boost::filesystem;

namespace
{
    using michi::test::CommandRun;
    using michi::test::runMichi;
    using michi::test::slurp;

    /** The bundled dual_arm problem, made coarse and quick, written to \e dir; \e edit and \e edit2 change its text. */
    std::string quickProblem(const fs::path &dir, const std::pair<std::string, std::string> &edit = {},
                             const std::pair<std::string, std::string> &edit2 = {})
    {
        std::string text = slurp(michi::test::sourcePath("problems/dual_arm.yaml"));
        auto replace = [&text](const std::string &from, const std::string &to)
        {
            const auto at = text.find(from);
            EXPECT_NE(at, std::string::npos) << from;
            if (at != std::string::npos)
                text.replace(at, from.size(), to);
        };
        replace("urdf: robots/dual_arm.urdf", "urdf: " + michi::test::sourcePath("problems/robots/dual_arm.urdf"));
        replace("resolution: 0.02", "resolution: 0.04");
        replace("seed_samples: 3000", "seed_samples: 1500");
        replace("planning: {planner: geometric::RRTstar, time: 2}",
                "planning: {planner: geometric::RRTstar, time: 0.2}");
        for (const auto *e : {&edit, &edit2})
            if (!e->first.empty())
                replace(e->first, e->second);
        const fs::path file = dir / "dual_arm_quick.yaml";
        std::ofstream(file.string()) << text;
        return file.string();
    }

    double number(const std::string &json, const std::string &key)
    {
        std::smatch m;
        const std::regex re("\"" + key + "\": ([-0-9.eE+]+)");
        EXPECT_TRUE(std::regex_search(json, m, re)) << key;
        return m.empty() ? 0. : std::stod(m[1]);
    }

    class DualArmCli : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            dir_ = fs::temp_directory_path() / fs::unique_path("michi-dualarm-%%%%%%");
            fs::create_directories(dir_);
        }
        void TearDown() override
        {
            fs::remove_all(dir_);
        }
        fs::path dir_;
    };
}  // namespace

TEST_F(DualArmCli, WritesPositionsStirringAndPictures)
{
    const fs::path out = dir_ / "out";
    const auto run = runMichi("dualarm " + quickProblem(dir_) + " --out " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string json = slurp(out / "dualarm.json");
    for (const char *key : {"type_a_position", "type_b_position", "common_workspace_volume_m3", "threshold",
                            "min_manipulability_stirring", "joint_motion_stirring"})
        EXPECT_NE(json.find(std::string("\"") + key + "\""), std::string::npos) << key;
    EXPECT_GT(number(json, "common_workspace_volume_m3"), 0.);
    EXPECT_GE(number(json, "min_manipulability_stirring"), number(json, "threshold"));
    EXPECT_NEAR(number(json, "threshold"), 0.004, 1e-12);
    for (const char *name : {"dualarm-workspace", "dualarm-manipulability", "dualarm-stirring"})
    {
        EXPECT_TRUE(fs::exists(out / (std::string(name) + ".svg"))) << name;
        EXPECT_TRUE(fs::exists(out / (std::string(name) + ".png"))) << name;
    }
}

TEST_F(DualArmCli, BadProblemNamesFileAndKeyAndWritesNothing)
{
    const fs::path out = dir_ / "out";
    const std::string noSection = michi::test::sourcePath("problems/planar_2link.yaml");
    auto run = runMichi("dualarm " + noSection + " --out " + out.string());
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.output.find(noSection + ": dual_arm: missing"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out));

    const std::string misspelt = quickProblem(dir_, {"seeds_per_cell: 4", "seeds_per_cel: 4"});
    run = runMichi("dualarm " + misspelt + " --out " + out.string());
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.output.find(misspelt + ": dual_arm.seeds_per_cel: unknown key"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out));

    run = runMichi("dualarm " + misspelt);
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.output.find("dualarm needs --out DIR"), std::string::npos) << run.output;
}

TEST_F(DualArmCli, FailedAnalysisSaysWhyAndWritesNothing)
{
    const fs::path out = dir_ / "out";
    // A 1.5 m stirring square cannot be drawn anywhere. The threshold reads as a number (it was "w > 0.000000" for
    // 1e-9), and the reason the square failed is given, not only the manipulability explanation.
    const std::string bigSquare = quickProblem(dir_, {"threshold: 0.004", "threshold: 0.000000001"},
                                               {"stirring: {side: 0.03, step: 0.0025}", "stirring: {side: 1.5}"});
    auto run = runMichi("dualarm " + bigSquare + " --out " + out.string());
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.output.find("manipulability area (w > 1e-09)"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("cannot complete the stirring square of side 1.5 m (first: the small arm"),
              std::string::npos)
        << run.output;
    EXPECT_FALSE(fs::exists(out));

    // The large arm's "tip" at its mount reaches no cell: no cell is reached by both arms, which is not "both reach
    // 0 but collide there".
    const std::string noLargeArm =
        quickProblem(dir_, {"tip: large_tip", "tip: large_base"}, {"perpendicular_to: [0, 0, 1]", "along: [0, 0, 1]"});
    run = runMichi("dualarm " + noLargeArm + " --out " + out.string());
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.output.find("no common work space (large arm reaches 0 cells"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("no cell is reached by both"), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("collide"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(DualArmCli, RerunWithoutHtmlRemovesTheEarlierReplayPage)
{
    const fs::path out = dir_ / "out";
    const std::string problem = quickProblem(dir_);
    const fs::path page = out / "dual_arm.html";
    auto run = runMichi("dualarm " + problem + " --out " + out.string() + " --html");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    ASSERT_TRUE(fs::exists(page));
    // the page of the first run would show that run's motions beside the second run's results
    run = runMichi("dualarm " + problem + " --out " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(fs::exists(out / "dualarm.json"));
    EXPECT_FALSE(fs::exists(page));
    // a file of that name that michi did not write stays
    std::ofstream(page.string()) << "<html>my notes</html>\n";
    run = runMichi("dualarm " + problem + " --out " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_EQ(slurp(page), "<html>my notes</html>\n");
}
