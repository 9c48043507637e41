// experience.learned_on (issue 17 part 3, a kinematic change): the experience planners of xarm6_ring_tool (the
// xArm6 holding a tool) learn the training queries of another problem (the plain xArm6), solved on that robot;
// every experience planner gets the same paths; a problem that plans other joints is refused, naming the key.
#include <michi/planners/experience/ExperiencePeers.h>
#include <michi/planners/path_seed/PathSeed.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/ExperienceQueries.h>

#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace tools = michi::tools;
namespace fs = std::filesystem;

namespace
{
    const std::string PROBLEMS = std::string(MICHI_SOURCE_DIR) + "/problems/";

    std::string slurp(const std::string &file)
    {
        std::ifstream in(file);
        std::ostringstream s;
        s << in.rdbuf();
        return s.str();
    }

    void replace(std::string &text, const std::string &from, const std::string &to)
    {
        const auto at = text.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        text.replace(at, from.size(), to);
    }

    /** xarm6_ring copied to \e file with absolute paths, its experience key's queries line replaced by \e experience.
     */
    void writePlainProblem(const fs::path &file, const std::string &experience)
    {
        std::string plain = slurp(PROBLEMS + "xarm6_ring.yaml");
        replace(plain, "urdf: robots/", "urdf: " + PROBLEMS + "robots/");
        replace(plain, "file: meshes/", "file: " + PROBLEMS + "meshes/");
        replace(plain, "  queries: experience/ring_task_queries.yaml\n", experience);
        replace(plain, "training_time: 5", "training_time: 2");
        std::ofstream(file) << plain;
    }
}  // namespace

TEST(ExperienceLearnedOn, EveryExperiencePlannerLearnsTheOtherRobotsPaths)
{
    ompl::RNG::setSeed(5);
    // the plain xArm6 with two training queries of its own (a copy of xarm6_ring with absolute paths)
    const fs::path dir = fs::temp_directory_path() / "michi_learned_on_test";
    fs::create_directories(dir);
    std::string queries =
        "training:\n"
        "  - {start: [-0.601689, -0.040466, -1.123125, 0.299424, 1.041653, -0.062052], goal: "
        "[-0.011209, 0.582275, -1.248146, 0.034631, -0.863073, 0.002455]}\n"
        "  - {start: [1.219012, 0.397488, -0.802238, -0.136170, 0.535546, 0.102317], goal: "
        "[0.036707, 0.623765, -1.354721, -0.143245, -0.707137, 0.047612]}\n"
        "held_out: []\n";
    std::ofstream(dir / "queries.yaml") << queries;
    writePlainProblem(dir / "plain.yaml", "  queries: " + (dir / "queries.yaml").string() + "\n");

    auto problem = tools::loadProblem(PROBLEMS + "xarm6_ring_tool.yaml");
    ASSERT_FALSE(problem.experience.learnedOn.empty());  // the bundled problem learns on xarm6_ring
    EXPECT_TRUE(problem.experience.training.empty());
    problem.experience.learnedOn = (dir / "plain.yaml").string();
    const auto ctx = tools::makePlanningContext(problem, 0);
    const auto si = ctx.setup->getSpaceInformation();
    auto lightning = std::make_shared<michi::planners::LightningPlanner>(si);
    auto thunder = std::make_shared<michi::planners::ThunderPlanner>(si);
    auto pathSeed = std::make_shared<michi::planners::PathSeed>(si);
    const std::size_t learned = tools::trainExperiencePlanners(problem, ctx, {lightning, thunder, pathSeed}, nullptr);
    EXPECT_EQ(learned, 2u);
    EXPECT_EQ(lightning->experienceCount(), 2u);
    EXPECT_EQ(thunder->experienceCount(), 2u);
    EXPECT_EQ(pathSeed->experienceCount(), 2u);

    // a problem of other joints cannot lend its experience
    problem.experience.learnedOn = PROBLEMS + "planar_2link.yaml";
    try
    {
        tools::trainExperiencePlanners(problem, ctx, {lightning}, nullptr);
        ADD_FAILURE() << "planar_2link's experience was taken for the xArm6";
    }
    catch (const tools::ProblemError &e)
    {
        EXPECT_EQ(e.key(), "experience.learned_on") << e.what();
    }
    fs::remove_all(dir);
}

TEST(ExperienceLearnedOn, ABadLearnedOnOrLibraryNamesItsKey)
{
    const fs::path dir = fs::temp_directory_path() / "michi_learned_on_keys_test";
    fs::create_directories(dir);
    const std::string queries = "  queries: " + PROBLEMS + "experience/ring_task_queries.yaml\n";
    auto expectError = [&](const std::string &experience, const std::string &key, const std::string &words)
    {
        writePlainProblem(dir / "p.yaml", experience);
        try
        {
            tools::loadProblem((dir / "p.yaml").string());
            ADD_FAILURE() << "no error for: " << experience;
        }
        catch (const tools::ProblemError &e)
        {
            EXPECT_EQ(e.key(), key) << e.what();
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
    };
    expectError(queries + "  learned_on: " + (dir / "none.yaml").string() + "\n", "experience.learned_on",
                "expected an existing problem file");
    expectError(queries + "  learned_on: " + (dir / "p.yaml").string() + "\n", "experience.learned_on",
                "names this problem itself");
    // the queries file has training queries of its own: one set or the other
    expectError(queries + "  learned_on: " + PROBLEMS + "xarm6_ring.yaml\n", "experience.learned_on",
                "has training queries too");
    expectError(queries + "  library: " + (dir / "none.seeds").string() + "\n", "experience.library",
                "expected an existing experience file");
    fs::remove_all(dir);
}
