// The replay page's data and file (tools/viewer/ReplayPage.h): what michi computes for the page, checked without a
// browser (tests/viewer/browser_replay.js checks the page in chromium).
#include <michi/tools/viewer/ReplayPage.h>
#include <michi/tools/problem/Problem.h>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <memory>
#include <regex>
#include <string>
#include <vector>

using michi::tools::PlotPath;
using michi::tools::Problem;

namespace
{
    Problem load(const std::string &name)
    {
        return michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/" + name + ".yaml");
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

    std::vector<double> lerp(const std::vector<double> &a, const std::vector<double> &b, double s)
    {
        std::vector<double> v(a.size());
        for (std::size_t i = 0; i < a.size(); ++i)
            v[i] = a[i] + s * (b[i] - a[i]);
        return v;
    }
}  // namespace

TEST(ReplayPage, ArmPageHoldsTheWaypointsAndMichisLinkPoses)
{
    const Problem problem = load("panda_table_pick");
    const auto &q = problem.queries.front();
    const PlotPath path{"geometric::RRTConnect", {q.start, lerp(q.start, q.goal, 0.3), q.goal}};
    const std::string page = michi::tools::replayPage(problem, {path});

    // self-contained: three.js inlined, nothing fetched
    EXPECT_NE(page.find("REVISION=\"111\""), std::string::npos);
    EXPECT_FALSE(std::regex_search(page, std::regex("(src|href)=[\"']?https?://", std::regex::icase)));

    const YAML::Node data = pageData(page);
    ASSERT_EQ(data["paths"].size(), 1u);
    const YAML::Node p = data["paths"][0];
    EXPECT_EQ(p["label"].as<std::string>(), "geometric::RRTConnect");
    ASSERT_EQ(p["waypoints"].size(), 3u);
    const std::size_t frames = p["times"].size();
    EXPECT_GT(frames, 100u);  // interpolated, not only the waypoints
    EXPECT_EQ(p["states"].size(), frames);
    EXPECT_EQ(p["poses"].size(), frames);
    for (std::size_t i = 1; i < frames; ++i)
        EXPECT_GE(p["times"][i].as<double>(), p["times"][i - 1].as<double>());
    EXPECT_NEAR(p["times"][frames - 1].as<double>(), 10., 1e-6);  // the longest path plays in the default 10 s

    // waypoint k's frame holds state k (to the page's 10 digits) and the bodies at michi's forward kinematics
    const auto bodies = data["bodies"];
    for (std::size_t k = 0; k < 3; ++k)
    {
        const std::size_t frame = p["waypoints"][k].as<std::size_t>();
        for (std::size_t i = 0; i < problem.dimension(); ++i)
            EXPECT_NEAR(p["states"][frame][i].as<double>(), path.states[k][i], 1e-9);
        std::vector<double> full = problem.fixedValues;
        full.resize(problem.model->variableCount(), 0.);
        for (std::size_t i = 0; i < problem.dimension(); ++i)
            full[problem.groupVariables[i]] = path.states[k][i];
        const auto poses = problem.model->forwardKinematics(full);
        for (std::size_t b = 0; b < bodies.size(); ++b)
        {
            const int link = problem.model->linkIndex(bodies[b]["name"].as<std::string>());
            ASSERT_GE(link, 0);
            const Eigen::Vector3d t = poses[link].translation();
            for (int i = 0; i < 3; ++i)
                EXPECT_NEAR(p["poses"][frame][7 * b + i].as<double>(), t[i], 1e-4) << bodies[b]["name"];
            const Eigen::Quaterniond expected(poses[link].linear());
            const Eigen::Quaterniond got(
                p["poses"][frame][7 * b + 6].as<double>(), p["poses"][frame][7 * b + 3].as<double>(),
                p["poses"][frame][7 * b + 4].as<double>(), p["poses"][frame][7 * b + 5].as<double>());
            EXPECT_LT(got.angularDistance(expected), 1e-4) << bodies[b]["name"];
        }
    }
    EXPECT_GE(data["endBody"].as<int>(), 0);
    EXPECT_GT(data["obstacles"].size(), 0u);
}

TEST(ReplayPage, BenchPageOfASevenJointArmWithSixPlannersStaysUnderFiveMegabytes)
{
    const Problem problem = load("panda_table_pick");
    const auto &q = problem.queries.front();
    std::vector<PlotPath> paths;
    for (int p = 0; p < 6; ++p)
    {
        PlotPath path{"planner" + std::to_string(p), {q.start}};
        // long, winding paths: 30 waypoints each, so the bound holds for more than toy paths
        for (int k = 1; k < 30; ++k)
            path.states.push_back(lerp(q.start, q.goal, 0.5 + 0.5 * std::sin(0.7 * k + p)));
        path.states.push_back(q.goal);
        paths.push_back(path);
    }
    const std::string page = michi::tools::replayPage(problem, paths);
    EXPECT_LT(page.size(), 5u * 1024 * 1024);
    EXPECT_EQ(pageData(page)["paths"].size(), 6u);
}

TEST(ReplayPage, Se2MapIsOneImageAndTheFootprintFollowsThePath)
{
    const Problem problem = load("se2_corridor_pgm");
    const auto &q = problem.queries.front();
    const PlotPath path{"p", {q.start, q.goal}};
    const YAML::Node data = pageData(michi::tools::replayPage(problem, {path}));
    ASSERT_TRUE(data["map"].IsMap());
    const long cells = data["map"]["width"].as<long>() * data["map"]["height"].as<long>();
    long covered = 0, occupied = 0;
    for (std::size_t i = 0; i < data["map"]["runs"].size(); ++i)
    {
        covered += data["map"]["runs"][i].as<long>();
        if (i % 2 == 1)
            occupied += data["map"]["runs"][i].as<long>();
    }
    EXPECT_EQ(covered, cells);
    EXPECT_GT(occupied, cells / 10);          // the walls fill most of the 10 m square
    EXPECT_EQ(data["obstacles"].size(), 0u);  // no box per row run of cells
    ASSERT_EQ(data["bodies"].size(), 1u);
    const YAML::Node last = data["paths"][0]["poses"][data["paths"][0]["poses"].size() - 1];
    EXPECT_NEAR(last[0].as<double>(), q.goal[0], 1e-4);
    EXPECT_NEAR(last[1].as<double>(), q.goal[1], 1e-4);
    // yaw pi/2 about z: quaternion (0, 0, sin(pi/4), cos(pi/4))
    EXPECT_NEAR(last[5].as<double>(), std::sin(q.goal[2] / 2), 1e-4);
    EXPECT_NEAR(last[6].as<double>(), std::cos(q.goal[2] / 2), 1e-4);
}

TEST(ReplayPage, RejectsAStateOfTheWrongDimension)
{
    const Problem problem = load("se2_corridor");
    EXPECT_THROW(michi::tools::replayData(problem, {PlotPath{"bad", {{1., 2.}}}}), std::invalid_argument);
}

TEST(ReplayPage, TimedPathKeepsItsClockAndItsStates)
{
    // a path with its own times (a replan episode's executed motion): every state a frame at its time, none added,
    // beside a path timed by length as usual
    const Problem problem = load("se2_corridor");
    const auto &q = problem.queries.front();
    const PlotPath executed{"executed", {q.start, lerp(q.start, q.goal, 0.25), q.goal}};
    const PlotPath planned{"planned", {q.start, q.goal}};
    michi::tools::ReplayOptions options;
    options.times = {{0., 0.5, 42.25}, {}};
    const YAML::Node data = pageData(michi::tools::replayPage(problem, {executed, planned}, options));
    ASSERT_EQ(data["paths"].size(), 2u);
    const YAML::Node p = data["paths"][0];
    ASSERT_EQ(p["times"].size(), 3u);
    ASSERT_EQ(p["waypoints"].size(), 3u);
    for (std::size_t k = 0; k < 3; ++k)
    {
        EXPECT_DOUBLE_EQ(p["times"][k].as<double>(), options.times[0][k]);
        EXPECT_EQ(p["waypoints"][k].as<std::size_t>(), k);
        for (std::size_t i = 0; i < problem.dimension(); ++i)
            EXPECT_NEAR(p["states"][k][i].as<double>(), executed.states[k][i], 1e-9);
    }
    const YAML::Node other = data["paths"][1];
    EXPECT_GT(other["times"].size(), 100u);
    EXPECT_NEAR(other["times"][other["times"].size() - 1].as<double>(), 10., 1e-6);  // by length, as before

    // times that do not fit the paths are refused
    options.times = {{0., 1.}};  // one entry for two paths
    EXPECT_THROW(michi::tools::replayData(problem, {executed, planned}, options), std::invalid_argument);
    options.times = {{0., 1.}, {}};  // two times for three states
    EXPECT_THROW(michi::tools::replayData(problem, {executed, planned}, options), std::invalid_argument);
    options.times = {{0., 2., 1.}, {}};  // going back
    EXPECT_THROW(michi::tools::replayData(problem, {executed, planned}, options), std::invalid_argument);
}

TEST(ReplayPage, DecimatesABigMeshAndWritesASharedShapeOnce)
{
    // a scene of our own: two obstacles sharing one finely tessellated sheet (0.5 m square, 2 x 150 x 150 triangles)
    Problem problem = load("se2_corridor");
    problem.scene = std::make_shared<michi::validity::Scene>();
    std::vector<Eigen::Vector3d> vertices;
    std::vector<Eigen::Vector3i> triangles;
    const int n = 150;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            vertices.emplace_back(0.5 * i / n, 0.5 * j / n, 0.);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
            const int a = j * (n + 1) + i;
            triangles.emplace_back(a, a + 1, a + n + 2);
            triangles.emplace_back(a, a + n + 2, a + n + 1);
        }
    const auto sheet = michi::validity::Shape::mesh(vertices, triangles);
    for (int k = 0; k < 2; ++k)
    {
        michi::validity::Obstacle o;
        o.name = "sheet" + std::to_string(k);
        o.shape = sheet;
        o.pose.translation() = Eigen::Vector3d(2. + k, 5., 0.);
        problem.scene->add(o);
    }
    const YAML::Node data = YAML::Load(michi::tools::replayData(problem, {PlotPath{"p", {{1.5, 2., 0.}}}}));
    ASSERT_EQ(data["obstacles"].size(), 2u);
    EXPECT_EQ(data["obstacles"][0]["shape"].as<int>(), data["obstacles"][1]["shape"].as<int>());
    const YAML::Node mesh = data["shapes"][data["obstacles"][0]["shape"].as<int>()];
    ASSERT_EQ(mesh["type"].as<std::string>(), "mesh");
    const std::size_t kept = mesh["triangles"].size() / 3;
    EXPECT_LE(kept, 20000u);
    EXPECT_GT(kept, 2000u);  // still the sheet, not a handful of triangles
    // clustered vertices stay within the sheet's bounds, indices within the vertices
    const std::size_t count = mesh["vertices"].size() / 3;
    for (std::size_t v = 0; v < count; ++v)
    {
        EXPECT_GE(mesh["vertices"][3 * v].as<double>(), -1e-4);
        EXPECT_LE(mesh["vertices"][3 * v].as<double>(), 0.5 + 1e-4);
    }
    for (std::size_t t = 0; t < mesh["triangles"].size(); ++t)
        EXPECT_LT(mesh["triangles"][t].as<std::size_t>(), count);
}

TEST(ReplayPage, ShowsTheOtherJointsAtTheGivenConfiguration)
{
    // dual_arm: the small arm is planned, the large arm's links are drawn once where its joints put them
    const Problem problem = load("dual_arm");
    const PlotPath path{"p", {problem.queries.front().start}};
    const YAML::Node asLoaded = YAML::Load(michi::tools::replayData(problem, {path}));
    michi::tools::ReplayOptions options;
    options.fixedValues = problem.fixedValues;
    options.fixedValues.resize(problem.model->variableCount(), 0.);
    std::size_t changed = 0;
    for (std::size_t v = 0; v < options.fixedValues.size(); ++v)
        if (std::find(problem.groupVariables.begin(), problem.groupVariables.end(), static_cast<int>(v)) ==
            problem.groupVariables.end())
        {
            options.fixedValues[v] += 0.5;  // every joint of the other arm
            ++changed;
        }
    ASSERT_GT(changed, 0u);
    const YAML::Node moved = YAML::Load(michi::tools::replayData(problem, {path}, options));
    ASSERT_EQ(moved["fixedParts"].size(), asLoaded["fixedParts"].size());
    double largest = 0.;
    for (std::size_t i = 0; i < moved["fixedParts"].size(); ++i)
        for (int k = 0; k < 3; ++k)
            largest = std::max(largest, std::abs(moved["fixedParts"][i][1][k].as<double>() -
                                                 asLoaded["fixedParts"][i][1][k].as<double>()));
    EXPECT_GT(largest, 0.05);  // the other arm's links moved
    // the planned arm's bodies do not depend on the other joints (each arm hangs from the base)
    EXPECT_EQ(moved["paths"][0]["poses"][0].as<std::vector<double>>(),
              asLoaded["paths"][0]["poses"][0].as<std::vector<double>>());
}
