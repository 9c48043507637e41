// Statistical check of the conservative J-map (label `slow`): on the 50 random planar scenes of
// scripts/jmap_random_scenes.sh (seeds 1-50 of `michi random-scenes`: the planar_2link arm among 6 random polygons)
// the J-map checker never calls a state valid that FCL calls invalid. Each scene goes through the same code as
// `michi jmap SCENE --verify N --seed 1` (runJMapReport), so the counts equal the script's for the same N.
// MICHI_JMAP_VERIFY sets N (default 200000; the figure is 1000000: scripts/jmap_random_scenes.sh 50 1000000,
// or `MICHI_JMAP_VERIFY=1000000 ctest --test-dir build -L slow -R JMapRandomScenes`).
#include "support/TestScenes.h"

#include <michi/tools/commands/JMapReport.h>
#include <michi/tools/problem/RandomPlanarScene.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>

using namespace michi;

namespace
{
    /** the number after "key": in a JSON text */
    double jsonNumber(const std::string &json, const std::string &key)
    {
        std::smatch m;
        if (!std::regex_search(json, m, std::regex("\"" + key + "\": ([-+0-9.eE]+)")))
            throw std::runtime_error("no " + key + " in " + json);
        return std::stod(m[1]);
    }
}  // namespace

TEST(JMapRandomScenes, NoUnsafeStateOnFiftyScenes)
{
    const char *env = std::getenv("MICHI_JMAP_VERIFY");
    const long perScene = env != nullptr ? std::atol(env) : 200000;
    ASSERT_GT(perScene, 0);
    const tools::Problem arm = tools::loadProblem(test::sourcePath("problems/planar_2link.yaml"));
    test::TempDir tmp("michi_slow_jmap");
    double checked = 0., unsafe = 0., falseInvalid = 0., invalid = 0.;
    for (unsigned int seed = 1; seed <= 50; ++seed)
    {
        const auto scene = tools::randomPlanarScene(arm, seed);
        tools::JMapReportOptions options;
        options.outDir = tmp.path() + "/scene_" + std::to_string(seed);
        options.verify = static_cast<std::uint64_t>(perScene);
        options.seed = 1;
        const std::string json = tools::runJMapReport(scene.problem, options);
        const double sceneUnsafe = jsonNumber(json, "unsafe_states");
        EXPECT_EQ(sceneUnsafe, 0.) << "scene " << seed << ": the J-map calls colliding states valid\n" << json;
        checked += jsonNumber(json, "checked_states");
        unsafe += sceneUnsafe;
        falseInvalid += jsonNumber(json, "false_invalid_states");
        invalid += jsonNumber(json, "fcl_invalid_fraction") * perScene;
    }
    EXPECT_EQ(checked, 50. * perScene);
    EXPECT_EQ(unsafe, 0.);
    RecordProperty("checked_states", std::to_string(checked));
    RecordProperty("false_invalid_fraction", std::to_string(falseInvalid / checked));
    std::cout << "checked " << static_cast<long>(checked) << " states on 50 scenes: unsafe " << unsafe
              << ", false invalid " << falseInvalid / checked << ", colliding " << invalid / checked << std::endl;
}
