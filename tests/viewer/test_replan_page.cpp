// `michi replan --html` (issue 20): the replay page of a replan episode. The page is self-contained, holds every
// method's executed motion on the simulated clock, and the moving obstacles as key frames that are where the
// simulation's obstacle model had them (replanEpisodeObstacles: the episode's shifted, rescaled timings).
#include "support/MichiCommand.h"
#include "support/TestScenes.h"

#include <michi/tools/commands/ReplanCommand.h>
#include <michi/tools/problem/Problem.h>

#include <boost/filesystem.hpp>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = boost::filesystem;

namespace
{
    using michi::test::runMichi;

    std::string readFile(const std::string &path)
    {
        std::ifstream in(path);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }

    /** The page's data block, parsed (JSON is YAML). */
    YAML::Node pageData(const std::string &page)
    {
        const std::string open = "<script type=\"application/json\" id=\"michi-data\">";
        const auto from = page.find(open);
        EXPECT_NE(from, std::string::npos);
        const auto to = page.find("</script>", from);
        return YAML::Load(page.substr(from + open.size(), to - from - open.size()));
    }

    std::vector<double> numbers(const YAML::Node &node, std::size_t from = 0)
    {
        std::vector<double> v;
        for (std::size_t i = from; i < node.size(); ++i)
            v.push_back(node[i].as<double>());
        return v;
    }

    /** A key frame's pose [t, x, y, z, qx, qy, qz, qw] against \e pose: position and rotation within \e tolerance
        (the quaternion up to its sign). */
    void expectPose(const YAML::Node &key, const Eigen::Isometry3d &pose, double tolerance, const std::string &what)
    {
        const auto v = numbers(key, 1);
        ASSERT_EQ(v.size(), 7u) << what;
        for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(v[i], pose.translation()[i], tolerance) << what << " position " << i;
        Eigen::Quaterniond q(pose.linear());
        q.normalize();
        const double sign = q.x() * v[3] + q.y() * v[4] + q.z() * v[5] + q.w() * v[6] < 0. ? -1. : 1.;
        EXPECT_NEAR(sign * v[3], q.x(), tolerance) << what;
        EXPECT_NEAR(sign * v[4], q.y(), tolerance) << what;
        EXPECT_NEAR(sign * v[5], q.z(), tolerance) << what;
        EXPECT_NEAR(sign * v[6], q.w(), tolerance) << what;
    }
}  // namespace

TEST(ReplanPage, ReplaysTheEpisodeWithTheSimulatedObstacleMotion)
{
    michi::test::TempDir dir;
    // obstacles_yield off (the scenario's setting): then the obstacles follow the episode's timings exactly (with
    // it, they wait for a robot in their way, which only the simulation knows)
    std::string text = readFile(michi::test::sourcePath("problems/dynamic_mobile_passage.yaml"));
    const auto yield = text.find("obstacles_yield: true");
    if (yield != std::string::npos)
        text.replace(yield, 21, "obstacles_yield: false");
    ASSERT_NE(text.find("obstacles_yield: false"), std::string::npos);
    const std::string file = dir.write("passage.yaml", text);
    const std::string out = dir.path() + "/run";
    const auto run =
        runMichi("replan " + file + " --episodes 2 --seed 3 --methods dual,rrtconnect --html --out " + out);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const michi::tools::Problem problem = michi::tools::loadProblem(file);
    const std::string pagePath = out + "/" + problem.name + ".html";
    ASSERT_TRUE(fs::exists(pagePath)) << run.output;
    EXPECT_NE(run.output.find(pagePath), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out + ".partial"));
    const std::string page = readFile(pagePath);

    // self-contained: three.js inlined, nothing fetched
    EXPECT_NE(page.find("REVISION=\"111\""), std::string::npos);
    EXPECT_FALSE(std::regex_search(page, std::regex("(src|href)=[\"']?https?://", std::regex::icase)));

    const YAML::Node data = pageData(page);
    // one path per method: its executed motion, on the simulated clock
    ASSERT_EQ(data["paths"].size(), 2u);
    EXPECT_EQ(data["paths"][0]["label"].as<std::string>().rfind("michi::DualRoadmap: ", 0), 0u);
    EXPECT_EQ(data["paths"][1]["label"].as<std::string>().rfind("geometric::RRTConnect: ", 0), 0u);
    const auto &query = problem.queries.front();
    const double dt = 0.02, speed = 1.;  // the file's extras.replan.dt and speed
    double end = 0.;
    for (std::size_t m = 0; m < 2; ++m)
    {
        const YAML::Node p = data["paths"][m];
        const std::string label = p["label"].as<std::string>();
        const std::size_t frames = p["times"].size();
        ASSERT_GT(frames, 10u) << label;
        ASSERT_EQ(p["states"].size(), frames);
        ASSERT_EQ(p["poses"].size(), frames);
        EXPECT_EQ(p["waypoints"].size(), frames);  // every executed state is michi's own, none interpolated
        EXPECT_EQ(p["times"][0].as<double>(), 0.);
        for (std::size_t i = 0; i < query.start.size(); ++i)
            EXPECT_NEAR(p["states"][0][i].as<double>(), query.start[i], 1e-9) << label;
        for (std::size_t k = 1; k < frames; ++k)
        {
            const double t0 = p["times"][k - 1].as<double>(), t1 = p["times"][k].as<double>();
            ASSERT_GT(t1, t0) << label << " frame " << k;
            // frames fall on simulation steps, and the robot moved no faster than its cruise speed
            EXPECT_NEAR(t1 / dt, std::round(t1 / dt), 1e-6) << label << " frame " << k;
            const auto a = numbers(p["states"][k - 1]), b = numbers(p["states"][k]);
            EXPECT_LE(std::hypot(b[0] - a[0], b[1] - a[1]), speed * (t1 - t0) + 1e-6) << label << " frame " << k;
            // the footprint is drawn where the executed state puts it
            EXPECT_NEAR(p["poses"][k][0].as<double>(), b[0], 1e-4) << label;
            EXPECT_NEAR(p["poses"][k][1].as<double>(), b[1], 1e-4) << label;
        }
        if (label.find("reached the goal") != std::string::npos)
            for (std::size_t i = 0; i < query.goal.size(); ++i)
                EXPECT_NEAR(p["states"][frames - 1][i].as<double>(), query.goal[i], 1e-6) << label;
        end = std::max(end, p["times"][frames - 1].as<double>());
    }

    // the moving obstacles: key frames at the frames' times, where the episode's obstacle model has them
    const auto movers = michi::tools::replanEpisodeObstacles(file, 3, 0);
    ASSERT_FALSE(movers.empty());
    std::size_t checked = 0;
    bool moved = false;
    for (const auto &mover : movers)
    {
        YAML::Node keys;
        for (const auto &o : data["obstacles"])
            if (o["name"].as<std::string>() == mover.name)
                keys = o["trajectory"];
        ASSERT_TRUE(keys.IsDefined() && keys.size() > 10u) << mover.name;
        EXPECT_EQ(keys[0][0].as<double>(), 0.);
        EXPECT_NEAR(keys[keys.size() - 1][0].as<double>(), end, 1e-9) << mover.name;
        for (std::size_t k = 0; k < keys.size(); ++k)
        {
            const double t = keys[k][0].as<double>();
            expectPose(keys[k], michi::validity::Scene::poseAt(mover.trajectory, t), 1e-6,
                       mover.name + " at t = " + std::to_string(t));
            ++checked;
        }
        // two times, a third and two thirds into the episode: the obstacle is elsewhere
        const auto a = numbers(keys[keys.size() / 3], 1), b = numbers(keys[2 * keys.size() / 3], 1);
        moved = moved || std::hypot(a[0] - b[0], a[1] - b[1]) > 0.1;
    }
    EXPECT_GT(checked, 20u);
    EXPECT_TRUE(moved) << "no moving obstacle moved between a third and two thirds of the episode";
}

TEST(ReplanPage, ArmEpisodeOfTheBundledProblem)
{
    // the bundled file as it is (real time, obstacles_yield off): a 7-joint arm, one method
    michi::test::TempDir dir;
    const std::string out = dir.path() + "/run";
    const auto run = runMichi("replan " + michi::test::sourcePath("problems/dynamic_reach_box.yaml") +
                              " --episodes 1 --methods dual --html --out " + out);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string page = readFile(out + "/dynamic_reach_box.html");
    ASSERT_FALSE(page.empty());
    const YAML::Node data = pageData(page);
    ASSERT_EQ(data["paths"].size(), 1u);
    const YAML::Node p = data["paths"][0];
    const std::size_t bodies = data["bodies"].size();
    ASSERT_GT(bodies, 0u);
    ASSERT_GT(p["poses"].size(), 1u);
    EXPECT_EQ(p["poses"][0].size(), 7 * bodies);
    std::size_t moving = 0;
    for (const auto &o : data["obstacles"])
        moving += o["trajectory"].size() > 1 ? 1 : 0;
    EXPECT_GT(moving, 0u);
}

TEST(ReplanPage, BadInputWritesNoPage)
{
    michi::test::TempDir dir;
    const std::string out = dir.path() + "/run";
    // a problem without moving obstacles: a clear error, a non-zero exit and nothing written
    const auto run =
        runMichi("replan " + michi::test::sourcePath("problems/planar_2link.yaml") + " --html --out " + out);
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.output.find("moving obstacle"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out + ".partial"));
}
