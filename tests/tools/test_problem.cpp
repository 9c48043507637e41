// Problem files: every bundled problem loads with valid start and goal; malformed files give one-line errors that
// name the file and the key.
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <boost/filesystem.hpp>
#include "support/MichiCommand.h"

#include <gtest/gtest.h>

#include <fstream>
#include <typeinfo>

namespace fs = boost::filesystem;
using michi::tools::ProblemError;

namespace
{
    const char *ARM_URDF = R"(<robot name="two">
  <link name="base"/>
  <link name="l1"><collision><origin xyz="0.25 0 0" rpy="0 1.5707963 0"/>
    <geometry><cylinder radius="0.01" length="0.5"/></geometry></collision></link>
  <link name="l2"><collision><origin xyz="0.2 0 0" rpy="0 1.5707963 0"/>
    <geometry><cylinder radius="0.01" length="0.4"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-3.14" upper="3.14" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0.5 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
</robot>)";

    class ProblemFiles : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            dir_ = fs::temp_directory_path() / fs::unique_path("michi-problem-%%%%%%%%");
            fs::create_directories(dir_);
            write("arm.urdf", ARM_URDF);
        }
        void TearDown() override
        {
            fs::remove_all(dir_);
        }
        std::string write(const std::string &name, const std::string &text)
        {
            std::ofstream(dir_ / name) << text;
            return (dir_ / name).string();
        }
        /** A valid problem with \e replace substituted into it. */
        std::string problem(const std::string &extra = "", const std::string &start = "[0, 0]",
                            const std::string &goal = "[1, 1]")
        {
            return write("p.yaml",
                         "name: p\nrobot: {urdf: arm.urdf}\n"
                         "scene:\n  obstacles:\n    - {name: wall, box: [0.1, 0.1, 1], pose: {xyz: [0, 0.7, 0]}}\n"
                         "start: " +
                             start + "\ngoal: " + goal + "\n" + extra);
        }
        /** Load and return the error message; fails the test if loading succeeds. */
        std::string error(const std::string &path)
        {
            return michi::test::problemLoadError(path, true);
        }
        fs::path dir_;
    };
}  // namespace

TEST_F(ProblemFiles, ValidProblemLoads)
{
    const auto p = michi::tools::loadProblem(problem("benchmark: {time_limit: 2, runs: 3, seed: 7}\n"));
    EXPECT_EQ(p.name, "p");
    EXPECT_EQ(p.dimension(), 2u);
    EXPECT_EQ(p.queries.size(), 1u);
    EXPECT_EQ(p.benchmark.runs, 3u);
    EXPECT_DOUBLE_EQ(p.benchmark.timeLimit, 2.);
    EXPECT_EQ(p.benchmark.seed, 7u);
    EXPECT_EQ(p.scene->size(), 1u);
    EXPECT_EQ(p.planners.size(), 4u);  // the default stock planners
    auto ctx = michi::tools::makePlanningContext(p);
    EXPECT_EQ(ctx.setup->getStateSpace()->getDimension(), 2u);
}

TEST_F(ProblemFiles, PiFormsAndGroups)
{
    const auto p = michi::tools::loadProblem(problem("", "[pi/4, -0.5*pi]", "[-pi/3, 1]") +
                                             "");  // group defaults to all movable joints
    EXPECT_NEAR(p.queries[0].start[0], M_PI / 4, 1e-12);
    EXPECT_NEAR(p.queries[0].start[1], -M_PI / 2, 1e-12);
    EXPECT_NEAR(p.queries[0].goal[0], -M_PI / 3, 1e-12);
    const auto g = michi::tools::loadProblem(
        write("g.yaml",
              "robot: {urdf: arm.urdf, groups: {elbow: [j2]}, group: elbow, fixed_joints: {j1: 0.3}}\n"
              "start: [0.1]\ngoal: [1.2]\n"));
    EXPECT_EQ(g.name, "g");
    EXPECT_EQ(g.dimension(), 1u);
    EXPECT_EQ(g.groupVariables, std::vector<int>{1});
    EXPECT_DOUBLE_EQ(g.fixedValues[0], 0.3);
}

TEST_F(ProblemFiles, AliasesThatRepeatTheFileExponentiallyAreRefused)
{
    // ten levels of nine aliases each: 9^10 values in 400 bytes ("billion laughs"); the duplicate-key walk over them
    // ran for hours before it was bounded by the file's size
    std::string bomb = "a0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol]\n";
    for (int i = 1; i <= 10; ++i)
    {
        const std::string prev = "*a" + std::to_string(i - 1);
        bomb += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [";
        for (int k = 0; k < 9; ++k)
            bomb += (k ? ", " : "") + prev;
        bomb += "]\n";
    }
    const std::string message =
        error(write("bomb.yaml", bomb + "robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\n"));
    EXPECT_NE(message.find("bomb.yaml"), std::string::npos) << message;
    EXPECT_NE(message.find("aliases"), std::string::npos) << message;
    // an alias that reuses a value is fine
    const auto p =
        michi::tools::loadProblem(write("alias.yaml",
                                        "robot: {urdf: arm.urdf}\n"
                                        "scene:\n  obstacles:\n"
                                        "    - {name: a, box: &size [0.1, 0.1, 1], pose: {xyz: [0, 0.7, 0]}}\n"
                                        "    - {name: b, box: *size, pose: {xyz: [0, -0.7, 0]}}\n"
                                        "start: [0, 0]\ngoal: [1, 1]\n"));
    EXPECT_EQ(p.scene->size(), 2u);
}

TEST_F(ProblemFiles, ErrorsNameFileAndKey)
{
    struct Case
    {
        std::string yaml;
        std::string key;
    };
    const std::vector<Case> cases{
        {"name: x\nrobot: {urdf: arm.urdf}\nstart: [0, 0\n", "not valid YAML"},
        {"name: x\nstart: [0, 0]\ngoal: [1, 1]\n", "robot"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\nbogus: 1\n", "bogus"},
        {"robot: {urdf: missing.urdf}\nstart: [0, 0]\ngoal: [1, 1]\n", "robot.urdf"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0, 0]\ngoal: [1, 1]\n", "start"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 2.5]\ngoal: [1, 1]\n", "start[1]"},
        {"robot: {urdf: arm.urdf}\nstart: [0, zero]\ngoal: [1, 1]\n", "start[1]"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\n", "goal"},
        {"robot: {urdf: arm.urdf, group: arm}\nstart: [0, 0]\ngoal: [1, 1]\n", "robot.group"},
        {"robot: {urdf: arm.urdf, groups: {arm: [j9]}}\nstart: [0, 0]\ngoal: [1, 1]\n", "robot.groups.arm[0]"},
        {"robot: {urdf: arm.urdf, groups: {arm: [j1, j1]}, group: arm}\nstart: [0, 0]\ngoal: [1, 1]\n",
         "robot.groups.arm[1]"},
        {"robot: {urdf: arm.urdf}\nscene: {obstacles: [{name: a}]}\nstart: [0, 0]\ngoal: [1, 1]\n",
         "scene.obstacles[0]"},
        {"robot: {urdf: arm.urdf}\nscene: {obstacles: [{box: [1, -1, 1]}]}\nstart: [0, 0]\ngoal: [1, 1]\n",
         "scene.obstacles[0]"},
        {"robot: {urdf: arm.urdf}\nscene: {obstacles: [{polygon: {points: [[0, 0], [1, 1], [1, 0], [0, 1]]}}]}\n"
         "start: [0, 0]\ngoal: [1, 1]\n",
         "scene.obstacles[0]"},
        {"robot: {urdf: arm.urdf}\nscene: {map: {pgm: none.pgm, resolution: 0.1}}\nstart: [0, 0]\ngoal: [1, 1]\n",
         "scene.map.pgm"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\nbenchmark: {runs: -1}\n", "benchmark.runs"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\nbenchmark: {time_limit: 0}\n", "benchmark.time_limit"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\nplanners: [{params: {}}]\n", "planners[0].name"},
        {"robot: {urdf: arm.urdf}\nscene: {obstacles: [{box: [1, 1, 1], posee: {xyz: [0, 0, 0]}}]}\n"
         "start: [0, 0]\ngoal: [1, 1]\n",
         "scene.obstacles[0].posee"},
        {"robot: {urdf: arm.urdf}\nscene: {obstacles: [{box: [1, 1, 1], sphere: 1}]}\nstart: [0, 0]\ngoal: [1, 1]\n",
         "scene.obstacles[0]"},
        {"robot: {urdf: arm.urdf, base_pos: {xyz: [0, 0, 0]}}\nstart: [0, 0]\ngoal: [1, 1]\n", "robot.base_pos"},
        {"robot: {urdf: arm.urdf, fixed_joints: {j2: 7}, groups: {a: [j1]}, group: a}\nstart: [0]\ngoal: [1]\n",
         "robot.fixed_joints.j2"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\nbenchmark: {memory_limit: -5}\n",
         "benchmark.memory_limit"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\ncollision: {motion_validator: exact}\n",
         "collision.motion_validator"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\ncollision: {max_step: 0}\n", "collision.max_step"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\ncollision: {checker: spheres, spheres: {per_link: "
         "0}}\n",
         "collision.spheres.per_link"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\ncollision: {checker: spheres, spheres: {exact_states: "
         "sometimes}}\n",
         "collision.spheres.exact_states"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\ncollision: {checker: spheres, spheres: {urdf: "
         "no.urdf}}\n",
         "collision.spheres.urdf"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\ncollision: {checker: spheres, spheres: {urdf: "
         "arm.urdf}}\n",
         "collision.spheres.urdf"},
        {"robot: {urdf: arm.urdf}\nstart: [0, 0]\ngoal: [1, 1]\ncollision: {spheres: {budget: 3}}\n",
         "collision.spheres.budget"},
        {"robot: {type: se2, footprint: [[0, 0], [1, 0]], bounds: {x: [0, 1], y: [0, 1]}}\nstart: [0, 0, 0]\n"
         "goal: [1, 1, 0]\n",
         "robot.footprint"},
        {"robot: {type: se2, footprint: [[0, 0], [1, 0], [0, 1]], bounds: {x: [0, 1], y: [0, 1]}}\n"
         "start: [2, 0, 0]\ngoal: [1, 1, 0]\n",
         "start"},
    };
    for (std::size_t i = 0; i < cases.size(); ++i)
    {
        const std::string file = write("case" + std::to_string(i) + ".yaml", cases[i].yaml);
        const std::string what = error(file);
        EXPECT_NE(what.find(file), std::string::npos) << "case " << i << ": " << what;
        EXPECT_NE(what.find(cases[i].key), std::string::npos) << "case " << i << ": " << what;
    }
}

TEST_F(ProblemFiles, SphereBudgetIsTheProblems)
{
    // collision.spheres.per_link sets the sphere model's budget: one sphere per link, or many
    std::vector<std::size_t> counts;
    for (int perLink : {1, 8})
    {
        const auto p = michi::tools::loadProblem(
            problem("collision: {checker: spheres, spheres: {per_link: " + std::to_string(perLink) + "}}\n"));
        auto ctx = michi::tools::makePlanningContext(p);
        ASSERT_TRUE(ctx.spheres);
        counts.push_back(ctx.spheres->sphereCount());
    }
    EXPECT_EQ(counts[0], 2u);  // two links with geometry
    EXPECT_GT(counts[1], counts[0]);
    EXPECT_LE(counts[1], 16u);
}

TEST_F(ProblemFiles, MotionValidatorIsChosenByTheProblem)
{
    const std::map<std::string, std::string> expected{{"workspace", "WorkspaceMotionValidator"},
                                                      {"conservative", "ConservativeMotionValidator"},
                                                      {"discrete", "DiscreteMotionValidator"}};
    for (const auto &kv : expected)
    {
        const auto p = michi::tools::loadProblem(problem("collision: {motion_validator: " + kv.first + "}\n"));
        auto ctx = michi::tools::makePlanningContext(p);
        const auto *validator = ctx.setup->getSpaceInformation()->getMotionValidator().get();
        EXPECT_NE(std::string(typeid(*validator).name()).find(kv.second), std::string::npos) << kv.first;
    }
    EXPECT_EQ(michi::tools::loadProblem(problem()).motionValidator, "workspace");
}

TEST_F(ProblemFiles, BadUrdfNamesTheUrdf)
{
    write("bad.urdf",
          "<robot name=\"x\"><link name=\"a\"/><joint name=\"j\" type=\"revolute\"><parent link=\"a\"/>"
          "</joint></robot>");
    const std::string what = error(write("b.yaml", "robot: {urdf: bad.urdf}\nstart: [0, 0]\ngoal: [1, 1]\n"));
    EXPECT_NE(what.find("bad.urdf"), std::string::npos) << what;
}

TEST_F(ProblemFiles, AJointThatCannotMoveInTheGroupNamesTheUrdf)
{
    std::string urdf = ARM_URDF;
    urdf.replace(urdf.find("lower=\"-2\" upper=\"2\""), 20, "lower=\"1\" upper=\"1\"");
    write("stuck.urdf", urdf);
    const std::string what = error(write("s.yaml", "robot: {urdf: stuck.urdf}\nstart: [0, 1]\ngoal: [1, 1]\n"));
    EXPECT_NE(what.find("s.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("robot.group"), std::string::npos) << what;
    EXPECT_NE(what.find("stuck.urdf"), std::string::npos) << what;
    EXPECT_NE(what.find("j2"), std::string::npos) << what;
}

TEST_F(ProblemFiles, CollidingStartNamesWhatCollides)
{
    // j1 = pi/2 puts link l1 through the wall at (0, 0.7)? no: l1 reaches 0.5; the elbow link reaches 0.9
    const std::string what = error(problem("", "[1.5707963, 0]", "[0, 0]"));
    EXPECT_NE(what.find("start"), std::string::npos) << what;
    EXPECT_NE(what.find("in collision"), std::string::npos) << what;
    EXPECT_NE(what.find("wall"), std::string::npos) << what;
    EXPECT_NE(what.find("l2"), std::string::npos) << what;
}

TEST_F(ProblemFiles, UnknownPlannerParameterIsNamed)
{
    const auto p = michi::tools::loadProblem(problem());
    auto ctx = michi::tools::makePlanningContext(p);
    auto planner = michi::tools::allocatePlanner("geometric::RRTConnect", ctx.setup->getSpaceInformation());
    michi::tools::applyPlannerParams(*planner, {"geometric::RRTConnect", {{"range", "0.3"}}}, p.file);
    EXPECT_EQ(planner->params()["range"].getValue(), "0.3");
    try
    {
        michi::tools::applyPlannerParams(*planner, {"geometric::RRTConnect", {{"rnage", "0.3"}}}, p.file);
        ADD_FAILURE() << "unknown parameter accepted";
    }
    catch (const ProblemError &e)
    {
        EXPECT_NE(std::string(e.what()).find("rnage"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("range"), std::string::npos);  // lists the known ones
    }
    EXPECT_THROW(michi::tools::allocatePlanner("geometric::NoSuchPlanner", ctx.setup->getSpaceInformation()),
                 std::invalid_argument);
}

TEST(PlannerRegistry, BitStarHasNoProgressPropertiesThatRaceTheBenchmarkThread)
{
    // OMPL 1.5.2's BIT* "current graph vertices" progress property copies the nearest-neighbour structure while
    // the planner modifies it; Benchmark reads it from another thread, which crashed michi bench
    auto space = std::make_shared<ompl::base::RealVectorStateSpace>(2);
    space->setBounds(0., 1.);
    auto si = std::make_shared<ompl::base::SpaceInformation>(space);
    for (const char *name : {"geometric::BITstar", "geometric::ABITstar"})
    {
        const auto planner = michi::tools::allocatePlanner(name, si);
        const auto &progress = planner->getPlannerProgressProperties();
        EXPECT_EQ(progress.count("current graph vertices INTEGER"), 0u) << name;
        EXPECT_EQ(progress.count("current free states INTEGER"), 0u) << name;
        EXPECT_EQ(progress.count("state collision checks INTEGER"), 1u) << name;  // the safe ones stay
    }
    for (const auto &name : michi::tools::plannerNames())
        EXPECT_NE(michi::tools::allocatePlanner(name, si), nullptr) << name;
}

TEST(BundledProblems, LoadWithValidStartAndGoal)
{
    const fs::path dir = fs::path(MICHI_SOURCE_DIR) / "problems";
    int count = 0;
    for (const auto &entry : fs::directory_iterator(dir))
    {
        if (entry.path().extension() != ".yaml")
            continue;
        SCOPED_TRACE(entry.path().string());
        const auto problem = michi::tools::loadProblem(entry.path().string());
        for (std::size_t q = 0; q < problem.queries.size(); ++q)
            EXPECT_NO_THROW(michi::tools::makePlanningContext(problem, q)) << "query " << q;
        ++count;
    }
    EXPECT_GE(count, 4);  // planar_2link, planar_3dof_hand, xarm6_ring, se2_corridor at least
}

TEST_F(ProblemFiles, MimicJointsFollowTheirJointAndAreNeverPlanned)
{
    // j2 turns with j1 (URDF <mimic>), j3 is free
    std::string urdf = ARM_URDF;
    urdf.insert(urdf.find(R"(</joint>
</robot>)"),
                R"(<mimic joint="j1" multiplier="-2" offset="0.1"/>)");
    urdf.insert(urdf.find("</robot>"), R"(<link name="l3"/><joint name="j3" type="revolute"><parent link="l2"/>
    <child link="l3"/><origin xyz="0.4 0 0"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>)");
    write("mimic.urdf", urdf);
    const auto p = michi::tools::loadProblem(
        write("fixed.yaml",
              "robot: {urdf: mimic.urdf, groups: {wrist: [j3]}, group: wrist, fixed_joints: {j1: 0.3}}\n"
              "start: [0.1]\ngoal: [1.2]\n"));
    EXPECT_DOUBLE_EQ(p.fixedValues[0], 0.3);
    EXPECT_DOUBLE_EQ(p.fixedValues[1], -0.5);  // -2 * 0.3 + 0.1, where it stayed at 0 before
    const auto ctx = michi::tools::makePlanningContext(p);
    EXPECT_DOUBLE_EQ(ctx.fixedValues[1], -0.5);

    const std::vector<std::pair<std::string, std::string>> refused{
        // planned: a dimension that would move nothing real
        {"robot: {urdf: mimic.urdf, groups: {a: [j2, j3]}, group: a}\nstart: [0, 0]\ngoal: [1, 1]\n", "'j2'"},
        // the joint it follows planned: the mimic's link would move where no bound follows it
        {"robot: {urdf: mimic.urdf, groups: {a: [j1, j3]}, group: a}\nstart: [0, 0]\ngoal: [1, 1]\n", "'j1'"},
        // no group: every movable joint, j1 and j2 among them
        {"robot: {urdf: mimic.urdf}\nstart: [0, 0, 0]\ngoal: [1, 1, 1]\n", "robot.group"},
        // given a value of its own
        {"robot: {urdf: mimic.urdf, groups: {a: [j3]}, group: a, fixed_joints: {j2: 0.2}}\nstart: [0]\ngoal: [1]\n",
         "robot.fixed_joints.j2"},
    };
    for (std::size_t i = 0; i < refused.size(); ++i)
    {
        const std::string file = write("refused" + std::to_string(i) + ".yaml", refused[i].first);
        const std::string what = error(file);
        EXPECT_NE(what.find(file), std::string::npos) << i << ": " << what;
        EXPECT_NE(what.find(refused[i].second), std::string::npos) << i << ": " << what;
        EXPECT_NE(what.find("mimic"), std::string::npos) << i << ": " << what;
    }
}

TEST_F(ProblemFiles, PlannersOmplCrashesWithAreRefusedWithTheReason)
{
    // FMT* with the clearance objective segfaults in OMPL 1.5.2's destructor; LBTRRT aborts on the turn-move-turn
    // space. Both are refused when the planner is made, naming the file and the key; other pairs still work.
    auto p = michi::tools::loadProblem(problem());
    p.benchmark.objective = "clearance";
    auto ctx = michi::tools::makePlanningContext(p);
    const auto si = ctx.setup->getSpaceInformation();
    for (const char *name : {"geometric::FMT", "geometric::BFMT"})
        try
        {
            michi::tools::makePlanner(p, name, si);
            ADD_FAILURE() << name << " with the clearance objective was accepted";
        }
        catch (const michi::tools::ProblemError &e)
        {
            const std::string what = e.what();
            EXPECT_NE(what.find(p.file), std::string::npos) << what;
            EXPECT_NE(what.find("benchmark.objective"), std::string::npos) << what;
        }
    EXPECT_NE(michi::tools::makePlanner(p, "geometric::RRTstar", si), nullptr);
    p.benchmark.objective = "length";
    EXPECT_NE(michi::tools::makePlanner(p, "geometric::FMT", si), nullptr);
    EXPECT_NE(michi::tools::makePlanner(p, "geometric::LBTRRT", si), nullptr);  // a joint space: fine

    const auto corridor = michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/se2_corridor.yaml");
    auto se2 = michi::tools::makePlanningContext(corridor);
    EXPECT_THROW(michi::tools::makePlanner(corridor, "geometric::LBTRRT", se2.setup->getSpaceInformation()),
                 michi::tools::ProblemError);
}

TEST_F(ProblemFiles, MotionChecksThatWouldNeverEndAreRefusedNamingTheKey)
{
    // A motion check cannot be interrupted (planners read their termination condition between checks): settings under
    // which one motion tests billions of states hung `michi plan` past its time limit. Each is refused, naming the key.
    const auto refusedUnder = [&](const std::string &file, const std::string &key)
    {
        const std::string what = error(file);
        EXPECT_NE(what.find(key), std::string::npos) << what;
        EXPECT_NE(what.find("states"), std::string::npos) << what;
    };
    refusedUnder(problem("collision: {motion_validator: discrete, valid_segment_fraction: 1.0e-9}\n"),
                 "collision.valid_segment_fraction");
    const std::string se2 = "robot:\n  type: se2\n  footprint: [[-0.2, -0.1], [0.2, -0.1], [0.2, 0.1], [-0.2, 0.1]]\n";
    refusedUnder(write("far.yaml", se2 + "  bounds: {x: [-1.0e6, 1.0e6], y: [-1.0e6, 1.0e6]}\n"
                                         "start: [0, 0, 0]\ngoal: [1, 1, 0]\ncollision: {max_step: 0.0001}\n"),
                 "collision.max_step");
    refusedUnder(write("turn.yaml", se2 + "  bounds: {x: [0, 10], y: [0, 10]}\n"
                                          "  motion: {model: turn_move_turn, turn_weight: 1.0e12}\n"
                                          "start: [1, 1, 0]\ngoal: [2, 2, 0]\n"),
                 "robot.motion.turn_weight");
    // fine settings still load: the arm at the smallest max_step (0.1 mm) is about 60,000 states for its widest motion
    EXPECT_NO_THROW(
        michi::tools::makePlanningContext(michi::tools::loadProblem(problem("collision: {max_step: 0.0001}\n"))));
    EXPECT_NO_THROW(michi::tools::makePlanningContext(michi::tools::loadProblem(write(
        "tmt.yaml", se2 + "  bounds: {x: [0, 10], y: [0, 10]}\n  motion: {model: turn_move_turn, turn_weight: 5}\n"
                          "start: [1, 1, 0]\ngoal: [2, 2, 0]\n"))));
}

TEST(ProblemErrorText, IsOnePrintableLineWhateverItQuotes)
{
    // A message quotes what it read: the first "line" of a binary file reached the terminal as raw bytes.
    const std::string raw = std::string("map\x01\tline\nnext \xff\xfe caf\xc3\xa9 ") + std::string(5000, 'x');
    const ProblemError error("f.map", "header", "'" + raw + "': expected the MovingAI header");
    const std::string what = error.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(what.find('\t'), std::string::npos) << what;
    EXPECT_NE(what.find("map\\x01\\x09line\\x0Anext \\xFF\\xFE caf\xc3\xa9 "), std::string::npos) << what;
    EXPECT_LT(what.size(), 2100u);
    EXPECT_NE(what.find("more bytes)"), std::string::npos) << what;
    EXPECT_EQ(error.file(), "f.map");
    EXPECT_EQ(error.key(), "header");
    EXPECT_EQ(michi::tools::printableLine("plain text, metres \xc2\xb1 0.1"), "plain text, metres \xc2\xb1 0.1");
}

TEST(PlannerRegistry, StatusTextNamesEveryStatus)
{
    // OMPL 1.5.2's asString() calls ABORT "Unknown status", which `michi plan` printed for a lattice without a path
    for (int i = 1; i < ompl::base::PlannerStatus::TYPE_COUNT; ++i)
        EXPECT_NE(michi::tools::statusText(static_cast<ompl::base::PlannerStatus::StatusType>(i)), "Unknown status")
            << i;
    EXPECT_EQ(michi::tools::statusText(ompl::base::PlannerStatus::TIMEOUT), "Timeout");
}
