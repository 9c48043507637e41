// Random planar scenes (michi/tools/RandomPlanarScene.h, `michi random-scenes`): the polygon generator is
// reproducible and keeps the arm's base clear; a scene keeps its template's robot and settings and gets a valid
// start and goal; the command writes problem files that load, plan-ready, and that `michi jmap --verify` accepts with
// no unsafe state; bad arguments give one line, a non-zero exit and no output.
#include "support/MichiCommand.h"
#include "support/TestScenes.h"

#include <michi/tools/problem/GridReachability.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/validity/fcl/ConservativeMotionValidator.h>
#include <michi/tools/problem/RandomPlanarScene.h>

#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

using namespace michi;
namespace fs = std::filesystem;

namespace
{
    using michi::test::problemFile;
    using michi::test::slurp;

    /** the integer after "key": in a JSON text, -1 when missing */
    long jsonInteger(const std::string &json, const std::string &key)
    {
        std::smatch m;
        if (!std::regex_search(json, m, std::regex("\"" + key + "\": (-?[0-9]+)")))
            return -1;
        return std::stol(m[1]);
    }

    std::vector<std::string> entries(const fs::path &dir)
    {
        std::vector<std::string> names;
        for (const auto &e : fs::directory_iterator(dir))
            names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }
}  // namespace

TEST(RandomPolygons, ReproducibleAndClearOfTheBase)
{
    tools::RandomPolygonOptions options;
    options.count = 12;
    options.keepClearRadius = 0.3;
    options.keepClearCentre = {0.2, -0.1};
    const auto polygons = tools::randomPolygons(5, options);
    ASSERT_EQ(polygons.size(), 12u);
    EXPECT_EQ(tools::randomPolygons(5, options), polygons);
    EXPECT_NE(tools::randomPolygons(6, options), polygons);
    ompl::RNG rng(5);
    EXPECT_EQ(tools::randomPolygons(rng, options), polygons) << "the seed overload is a local RNG(seed)";
    // the tests' generator is this one
    EXPECT_EQ(test::randomPolygons(5, options), polygons);
    for (const auto &p : polygons)
    {
        EXPECT_GE(p.size(), 3u);
        EXPECT_LE(p.size(), 8u);
        EXPECT_GT(test::outlineArea(p), 0.);
        for (const auto &v : p)
            EXPECT_GE((v - options.keepClearCentre).norm(), options.keepClearRadius);
    }
    options.minSides = 2;
    EXPECT_THROW(tools::randomPolygons(5, options), std::invalid_argument);
}

TEST(GridComponents, SplitsAtAWallAndLinksFreeSpace)
{
    // a thin wall along the positive x axis: link 1 cannot pass theta1 = 0, and the joint limits do not wrap, so
    // theta1 > 0 and theta1 < 0 are two separate regions
    const auto setup = test::planarArmSetup({0.5, 0.4}, {test::boxOutline({0.15, -0.02}, {1.0, 0.02})});
    setup.si->setMotionValidator(std::make_shared<validity::ConservativeMotionValidator>(setup.si, setup.checker));
    const tools::GridComponents grid(setup.si, 0.05);
    EXPECT_TRUE(grid.reachable({1., 0.}, {2., 0.5}));
    EXPECT_TRUE(grid.reachable({-1., 0.}, {-2.5, -1.}));
    EXPECT_FALSE(grid.reachable({1., 0.}, {-1., 0.}));
    EXPECT_FALSE(tools::gridReachable(setup.si, {2., 0.}, {-2., 0.}, 0.05));
    EXPECT_TRUE(grid.attach({0., 0.}).empty()) << "a colliding state attaches to nothing";
    EXPECT_GE(grid.components(), 2);
    const auto arm3 = test::planarArmSetup({0.5, 0.4, 0.3}, {});
    EXPECT_THROW(tools::GridComponents(arm3.si, 0.05), std::invalid_argument);
}

TEST(RandomPlanarScene, KeepsTheTemplateAndGetsAValidQuery)
{
    const tools::Problem arm = tools::loadProblem(problemFile("planar_2link"));
    const auto random = tools::randomPlanarScene(arm, 7);
    const tools::Problem &p = random.problem;
    EXPECT_EQ(p.name, "scene_7");
    ASSERT_EQ(random.polygons.size(), 6u);
    EXPECT_EQ(p.scene->size(), 6u);
    for (const auto &polygon : random.polygons)
        for (const auto &v : polygon)
            EXPECT_GE(v.norm(), 0.1) << "0.1 m around the base is kept free";
    // the template's robot and settings
    EXPECT_EQ(p.model, arm.model);
    EXPECT_EQ(p.groupVariables, arm.groupVariables);
    EXPECT_EQ(p.motionValidator, "conservative");
    EXPECT_EQ(p.benchmark.timeLimit, arm.benchmark.timeLimit);
    EXPECT_EQ(p.planners.size(), arm.planners.size());
    // one query, valid for FCL (makePlanningContext throws otherwise), start and goal at least 1 rad apart
    ASSERT_EQ(p.queries.size(), 1u);
    const auto &q = p.queries[0];
    EXPECT_GE(std::hypot(q.start[0] - q.goal[0], q.start[1] - q.goal[1]), 1.);
    const tools::PlanningContext ctx = tools::makePlanningContext(p);
    EXPECT_TRUE(ctx.checker->isValidConfiguration(q.start.data()));
    EXPECT_TRUE(ctx.checker->isValidConfiguration(q.goal.data()));
    // reproducible, and the polygons are the generator's for the scene seed
    const auto again = tools::randomPlanarScene(arm, 7);
    EXPECT_EQ(again.polygons, random.polygons);
    EXPECT_EQ(again.problem.queries[0].start, q.start);
    EXPECT_EQ(again.problem.queries[0].goal, q.goal);
    tools::RandomPolygonOptions options;
    options.count = 6;
    options.keepClearRadius = 0.1;
    EXPECT_EQ(tools::randomPolygons(7, options), random.polygons);
    EXPECT_NE(tools::randomPolygons(8, options), random.polygons);
    // a two-joint arm: the start and goal are linked through the grid with the problem's motion validator
    const tools::PlanningContext linked = tools::makePlanningContext(p);
    EXPECT_TRUE(tools::gridReachable(linked.setup->getSpaceInformation(), q.start, q.goal, 0.05));

    // a 3-joint planar arm works too; an SE(2) robot is refused
    const auto hand = tools::randomPlanarScene(tools::loadProblem(problemFile("planar_3dof_hand")), 3);
    EXPECT_EQ(hand.problem.queries[0].start.size(), 3u);
    EXPECT_NO_THROW(tools::makePlanningContext(hand.problem));
    EXPECT_THROW(tools::randomPlanarScene(tools::loadProblem(problemFile("se2_corridor")), 1), tools::ProblemError);
}

TEST(RandomPlanarScene, StartAndGoalHoldForEveryCheckerTheTemplatePlansWith)
{
    // planar_2link runs ConcentricCircle and RRTConnect on the J-map, whose conservative margin refuses some states
    // FCL calls free: scenes 101-103 drew such a start before the scene's checkers were asked too
    const tools::Problem arm = tools::loadProblem(problemFile("planar_2link"));
    ASSERT_TRUE(std::any_of(arm.planners.begin(), arm.planners.end(),
                            [](const tools::PlannerSpec &spec)
                            {
                                return spec.checker == "jmap";
                            }));
    for (std::uint_fast32_t seed : {101u, 102u, 103u})
    {
        const tools::Problem p = tools::randomPlanarScene(arm, seed).problem;
        const auto &q = p.queries.at(0);
        tools::ContextOptions options;
        options.checker = "jmap";
        const tools::PlanningContext ctx = tools::makePlanningContext(p, options);
        const auto si = ctx.setup->getSpaceInformation();
        ompl::base::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
        start = q.start;
        goal = q.goal;
        EXPECT_TRUE(si->isValid(start.get())) << "scene " << seed << ": the J-map refuses the start";
        EXPECT_TRUE(si->isValid(goal.get())) << "scene " << seed << ": the J-map refuses the goal";
        // and linked under the J-map's own motion validator, not only under FCL's
        EXPECT_TRUE(tools::gridReachable(si, q.start, q.goal, 0.05)) << "scene " << seed;
    }
}

TEST(RandomScenesCommand, WritesScenesThatLoadAndPassTheJMapCheck)
{
    test::TempDir tmp("michi_random_scenes");
    const fs::path out = fs::path(tmp.path()) / "scenes";
    const std::string args =
        "random-scenes --count 2 --seed 11 --arm " + problemFile("planar_2link") + " --out " + out.string();
    const auto run = test::runMichi(args);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_EQ(entries(out), (std::vector<std::string>{"scene_11.yaml", "scene_12.yaml"}));
    EXPECT_EQ(entries(tmp.path()), std::vector<std::string>{"scenes"}) << "no staging folder left behind";
    const std::string first = slurp(out / "scene_11.yaml");

    // the files are the in-memory scenes, and ready for plan/bench
    const tools::Problem arm = tools::loadProblem(problemFile("planar_2link"));
    for (int seed : {11, 12})
    {
        const auto expected = tools::randomPlanarScene(arm, seed);
        const tools::Problem p = tools::loadProblem((out / ("scene_" + std::to_string(seed) + ".yaml")).string());
        EXPECT_EQ(p.name, "scene_" + std::to_string(seed));
        EXPECT_EQ(p.queries[0].start, expected.problem.queries[0].start) << "written with round-trip precision";
        EXPECT_EQ(p.queries[0].goal, expected.problem.queries[0].goal);
        EXPECT_EQ(p.scene->size(), 6u);
        EXPECT_EQ(p.motionValidator, "conservative");
        EXPECT_NO_THROW(tools::makePlanningContext(p));
    }

    // the check, small: no state the J-map calls valid collides (FCL)
    for (int seed : {11, 12})
    {
        const fs::path jm = fs::path(tmp.path()) / ("jmap_" + std::to_string(seed));
        const auto check = test::runMichi("jmap " + (out / ("scene_" + std::to_string(seed) + ".yaml")).string() +
                                          " --out " + jm.string() + " --verify 20000 --seed 1");
        ASSERT_EQ(check.exitCode, 0) << check.output;
        const std::string json = slurp(jm / "jmap.json");
        EXPECT_EQ(jsonInteger(json, "checked_states"), 20000);
        EXPECT_EQ(jsonInteger(json, "unsafe_states"), 0) << json;
        EXPECT_GT(jsonInteger(json, "false_invalid_states"), 0) << "the map is conservative, not exact";
    }

    // the same command writes the same file; a trailing slash on DIR changes nothing
    const auto rerun = test::runMichi("random-scenes --count 1 --seed 11 --arm " + problemFile("planar_2link") +
                                      " --out " + out.string() + "/");
    ASSERT_EQ(rerun.exitCode, 0) << rerun.output;
    EXPECT_EQ(slurp(out / "scene_11.yaml"), first);
    EXPECT_EQ(entries(tmp.path()).size(), 3u) << "scenes and the two jmap folders, no staging folder";
}

TEST(RandomScenesCommand, BadArgumentsGiveOneLineAndWriteNothing)
{
    test::TempDir tmp("michi_random_scenes_bad");
    const std::string out = (fs::path(tmp.path()) / "out").string();
    const std::string arm = " --arm " + problemFile("planar_2link");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"random-scenes --count 2" + arm, "needs --out"},
        {"random-scenes --count 0 --out " + out + arm, "--count: expected an integer in 1..100000, got '0'"},
        {"random-scenes --count abc --out " + out + arm, "--count: expected an integer in 1..100000, got 'abc'"},
        {"random-scenes --count 2x --out " + out + arm, "got '2x'"},
        {"random-scenes --seed -1 --out " + out + arm, "--seed: expected an integer in 0..4294967295, got '-1'"},
        {"random-scenes --polygons 5000 --out " + out + arm, "--polygons: expected an integer in 0..1000, got '5000'"},
        {"random-scenes --colour red --out " + out + arm, "unknown option --colour"},
        {"random-scenes extra --out " + out + arm, "unexpected argument 'extra'"},
        {"random-scenes --out " + out + arm + " --count", "option --count needs a value"},
        {"random-scenes --out " + out + " --arm " + (fs::path(tmp.path()) / "missing.yaml").string(), "missing.yaml"},
        {"random-scenes --out " + out + " --arm " + problemFile("se2_corridor"), "se2_corridor.yaml: robot"},
    };
    for (const auto &c : cases)
    {
        const auto run = test::runMichi(c.first);
        EXPECT_NE(run.exitCode, 0) << c.first;
        EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << c.first << "\n" << run.output;
        EXPECT_EQ(run.output.rfind("michi random-scenes: ", 0), 0u) << run.output;
        EXPECT_NE(run.output.find(c.second), std::string::npos) << c.first << "\n" << run.output;
        EXPECT_TRUE(entries(tmp.path()).empty()) << c.first << ": nothing written";
    }
}
