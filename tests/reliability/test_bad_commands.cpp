// Issue 13 through the `michi` command, as a careless user would meet it: each bad input gives a one-line error
// naming the file (and key), a non-zero exit without a signal, and no output; a 10,000-obstacle map loads.
#include "support/MichiCommand.h"
#include "support/TestScenes.h"

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

namespace fs = boost::filesystem;
using michi::test::CommandRun;
using michi::test::runMichi;

namespace
{
    using michi::test::slurp;

    void spit(const fs::path &p, const std::string &text)
    {
        std::ofstream(p.string(), std::ios::binary) << text;
    }

    std::string lastLine(const std::string &output)
    {
        std::string s = output;
        while (!s.empty() && s.back() == '\n')
            s.pop_back();
        const auto nl = s.rfind('\n');
        return nl == std::string::npos ? s : s.substr(nl + 1);
    }

    /** A copy of problems/ to break. */
    class BadCommands : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            dir_ = fs::temp_directory_path() / fs::unique_path("michi-bad-%%%%%%%%");
            copyTree(michi::test::sourcePath("problems"), dir_ / "p");
        }
        void TearDown() override
        {
            fs::remove_all(dir_);
        }
        static void copyTree(const fs::path &from, const fs::path &to)
        {
            fs::create_directories(to);
            for (const auto &e : fs::directory_iterator(from))
            {
                if (fs::is_directory(e.path()))
                    copyTree(e.path(), to / e.path().filename());
                else
                    fs::copy_file(e.path(), to / e.path().filename());
            }
        }
        /** Runs michi; expects exit 1 or 2 (no signal), the last line naming \e fragment, no raw library text, and
            nothing written to --out. */
        void expectCleanError(const std::string &args, const std::string &fragment, const fs::path &out)
        {
            const CommandRun run = runMichi(args);
            EXPECT_TRUE(run.exitCode == 1 || run.exitCode == 2) << "exit " << run.exitCode << "\n" << run.output;
            const std::string last = lastLine(run.output);
            EXPECT_NE(last.find(fragment), std::string::npos) << last;
            EXPECT_FALSE(std::regex_search(last, std::regex("std::bad_alloc|basic_filebuf|boost::filesystem"))) << last;
            EXPECT_FALSE(fs::exists(out)) << out << " written";
            // no staging folder left beside the output (nor in the test's folder, when --out lies under a file)
            fs::path beside = out.parent_path();
            while (!fs::is_directory(beside))
                beside = beside.parent_path();
            for (const auto &e : fs::directory_iterator(beside))
                EXPECT_EQ(e.path().filename().string().find(".partial-"), std::string::npos) << e.path();
        }
        fs::path dir_;
    };

    const std::string PLAN = " --planner geometric::RRTConnect --time 0.3 --out ";
}  // namespace

TEST_F(BadCommands, UrdfCollisionOriginNanIsAnErrorNotAPathThroughAnObstacle)
{
    const fs::path urdf = dir_ / "p/robots/planar_2link.urdf";
    std::string text = slurp(urdf);
    const auto at = text.find("<origin xyz=\"0.2 0 0\"");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 21, "<origin xyz=\"nan 0 0\"");
    spit(urdf, text);
    expectCleanError("plan " + (dir_ / "p/planar_2link.yaml").string() + PLAN + (dir_ / "o").string(),
                     "planar_2link.urdf", dir_ / "o");
}

TEST_F(BadCommands, UrdfJointCycle)
{
    const fs::path urdf = dir_ / "p/robots/planar_2link.urdf";
    std::string text = slurp(urdf);
    text.replace(text.find("</robot>"), 8,
                 "<joint name=\"loop\" type=\"fixed\"><parent link=\"link2\"/><child link=\"link2\"/></joint></robot>");
    spit(urdf, text);
    expectCleanError("plan " + (dir_ / "p/planar_2link.yaml").string() + PLAN + (dir_ / "o").string(),
                     "planar_2link.urdf", dir_ / "o");
}

TEST_F(BadCommands, HugeObstacleCoordinate)
{
    const fs::path file = dir_ / "p/dynamic_mobile_passage.yaml";
    const std::string text = std::regex_replace(slurp(file), std::regex(R"(xyz:\s*\[[^\]]*\])"),
                                                "xyz: [1e308, 1e308, 1e308]", std::regex_constants::format_first_only);
    spit(file, text);
    expectCleanError("plan " + file.string() + PLAN + (dir_ / "o").string(), "dynamic_mobile_passage", dir_ / "o");
}

TEST_F(BadCommands, StlWithAnInfiniteVertex)
{
    const fs::path stl = dir_ / "p/meshes/ring.stl";
    spit(stl, std::regex_replace(slurp(stl), std::regex(R"((vertex\s+)(\S+))"), "$1inf",
                                 std::regex_constants::format_first_only));
    expectCleanError("plan " + (dir_ / "p/xarm6_ring.yaml").string() + PLAN + (dir_ / "o").string(), "ring.stl",
                     dir_ / "o");
}

TEST_F(BadCommands, PgmWhoseHeaderClaimsMoreThanItHolds)
{
    spit(dir_ / "p/maps/se2_corridor.pgm", std::string("P5\n50000 50000\n255\n\0\0", 21));
    expectCleanError("plan " + (dir_ / "p/se2_corridor_pgm.yaml").string() + PLAN + (dir_ / "o").string(),
                     "se2_corridor.pgm", dir_ / "o");
}

TEST_F(BadCommands, MoveItSceneThatIsAFolder)
{
    const fs::path file = dir_ / "p/panda_table_pick.yaml";
    spit(file, std::regex_replace(slurp(file), std::regex(R"((\n\s*moveit:\s*)\S+)"), "$1/"));
    expectCleanError("plan " + file.string() + PLAN + (dir_ / "o").string(), "scene.moveit", dir_ / "o");
}

TEST_F(BadCommands, OutputFolderUnderAFile)
{
    spit(dir_ / "afile", "");
    expectCleanError("bench " + (dir_ / "p/planar_2link.yaml").string() +
                         " --planners geometric::RRTConnect --runs 1 --time 0.1 --out " + (dir_ / "afile/sub").string(),
                     "afile", dir_ / "afile/sub");
}

TEST_F(BadCommands, TenThousandObstacleMapLoads)
{
    // a 141 x 141 checkerboard: 9,940 one-cell boxes (loading was quadratic: 28 s); the run ends normally
    std::string pgm = "P5\n141 141\n255\n";
    for (int y = 0; y < 141; ++y)
        for (int x = 0; x < 141; ++x)
            pgm += static_cast<char>((x + y) % 2 == 0 ? 0 : 255);
    spit(dir_ / "checker.pgm", pgm);
    spit(dir_ / "checker.yaml",
         "robot:\n  type: se2\n  footprint: [[-0.01, -0.01], [0.01, -0.01], [0.01, 0.01], "
         "[-0.01, 0.01]]\n  bounds: {x: [0, 20], y: [0, 20]}\nscene:\n  map: {pgm: checker.pgm, "
         "resolution: 0.05, origin: [10, 10]}\nstart: [1, 1, 0]\ngoal: [2, 2, 0]\n");
    const CommandRun run = runMichi("plan " + (dir_ / "checker.yaml").string() + PLAN + (dir_ / "o").string());
    EXPECT_EQ(run.exitCode, 0) << run.output;
}

// A bad-input sweep (2026-12-02) found these; each was a crash, a hang, output outside --out, a script line from a
// flag, geometry silently dropped or a raw library message.

TEST_F(BadCommands, GeometryThatWouldDropOutOfCheckingIsRefused)
{
    // a zero mesh scale flattens the ring into a point
    const fs::path ring = dir_ / "p/xarm6_ring.yaml";
    spit(ring, std::regex_replace(slurp(ring), std::regex(R"(mesh: \{file: meshes/ring.stl\})"),
                                  "mesh: {file: meshes/ring.stl, scale: [0, 1, 1]}"));
    expectCleanError("plan " + ring.string() + PLAN + (dir_ / "o").string(), "mesh scale", dir_ / "o");
    // a map threshold of 0 marks no pixel occupied: every wall gone
    const fs::path map = dir_ / "p/se2_corridor_pgm.yaml";
    const std::string mapText = slurp(map);
    spit(map, std::regex_replace(mapText, std::regex(R"(threshold: 0\.5)"), "threshold: 0"));
    expectCleanError("plan " + map.string() + PLAN + (dir_ / "o").string(), "scene.map.threshold", dir_ / "o");
    // a footprint prism of height 0
    spit(map, std::regex_replace(mapText, std::regex(R"(\n  height: 1)"), "\n  height: 0"));
    expectCleanError("plan " + map.string() + PLAN + (dir_ / "o").string(), "robot.height", dir_ / "o");
}

TEST_F(BadCommands, UrdfNestedThousandsDeepOrWithAHugeAxis)
{
    // TinyXML recursed once per level and overflowed the stack (a segfault)
    std::string deep = "<robot name=\"deep\"><link name=\"base\"/>";
    for (int i = 0; i < 20000; ++i)
        deep += "<a>";
    for (int i = 0; i < 20000; ++i)
        deep += "</a>";
    spit(dir_ / "p/robots/planar_2link.urdf", deep + "</robot>\n");
    expectCleanError("plan " + (dir_ / "p/planar_2link.yaml").string() + PLAN + (dir_ / "o").string(),
                     "nested more than", dir_ / "o");
    // an axis of length 1e300: its norm overflowed, and the joint silently never moved (no path)
    const fs::path urdf = dir_ / "p/robots/planar_2link_axis.urdf";
    fs::copy_file(michi::test::sourcePath("problems/robots/planar_2link.urdf"), urdf);
    spit(urdf, std::regex_replace(slurp(urdf), std::regex(R"(<axis xyz="0 0 1"/>)"), R"(<axis xyz="0 0 1e300"/>)"));
    const fs::path problem = dir_ / "p/planar_2link_axis.yaml";
    spit(problem, std::regex_replace(slurp(dir_ / "p/planar_2link.yaml"), std::regex(R"(planar_2link\.urdf)"),
                                     "planar_2link_axis.urdf"));
    const CommandRun run = runMichi("plan " + problem.string() + PLAN + (dir_ / "axis").string());
    EXPECT_EQ(run.exitCode, 0) << run.output;
}

TEST_F(BadCommands, NamesAndFlagsThatWouldWriteOutsideTheirPlace)
{
    // a problem name with a path in it wrote DIR/../../x-<planner>.path
    const fs::path file = dir_ / "p/planar_2link.yaml";
    spit(file, std::regex_replace(slurp(file), std::regex(R"(\nname: planar_2link)"), "\nname: ../../escaped"));
    expectCleanError("plan " + file.string() + PLAN + (dir_ / "o").string(), "name", dir_ / "o");
    for (const auto &e : fs::directory_iterator(dir_))
        EXPECT_EQ(e.path().filename().string().find("escaped"), std::string::npos) << e.path();
    // a newline in --partition became a command of the sbatch script
    const fs::path campaign = dir_ / "c.yaml";
    spit(campaign, "name: c\nruns: 1\nproblems: [" + (dir_ / "p/se2_corridor.yaml").string() +
                       "]\nplanners: [geometric::RRTConnect]\ncheckers: [fcl]\n");
    expectCleanError("campaign slurm " + campaign.string() + " --shards 2 --out " + (dir_ / "s").string() +
                         " --partition $'a\\nrm -rf /tmp/x'",
                     "--partition", dir_ / "s");
    // a billion runs were listed in memory before any ran
    spit(campaign, std::regex_replace(slurp(campaign), std::regex(R"(runs: 1)"), "runs: 1000000000"));
    expectCleanError("campaign plan " + campaign.string(), "runs", dir_ / "never");
}

TEST_F(BadCommands, KeysParametersAndListsAreReadAsWritten)
{
    const fs::path file = dir_ / "p/planar_2link.yaml";
    const std::string original = slurp(file);
    // a list as a mapping key: yaml-cpp's "bad conversion" without a file name
    spit(file, original + "extras:\n  ? [a, b]\n  : 1\n");
    expectCleanError("plan " + file.string() + PLAN + (dir_ / "o").string(), "a key must be a plain name", dir_ / "o");
    // a planner listed twice: plan took the last silently
    const std::regex first(R"(\n  - geometric::RRTConnect\n  - geometric::PRM\n)");
    spit(file, std::regex_replace(original, first, "\n  - geometric::PRM\n  - geometric::PRM\n"));
    expectCleanError("plan " + file.string() + PLAN + (dir_ / "o").string(), "listed twice", dir_ / "o");
    // a flag parameter given 2, an integer given 8.5: OMPL took them (as true, as 8)
    spit(file, std::regex_replace(original, first,
                                  "\n  - {name: geometric::RRTConnect, params: {intermediate_states: 2}}\n"
                                  "  - geometric::PRM\n"));
    expectCleanError("bench " + file.string() + " --runs 1 --time 0.1 --out " + (dir_ / "o").string(),
                     "intermediate_states", dir_ / "o");
    spit(file, std::regex_replace(original, first,
                                  "\n  - geometric::RRTConnect\n"
                                  "  - {name: geometric::PRM, params: {max_nearest_neighbors: 8.5}}\n"));
    expectCleanError("bench " + file.string() + " --runs 1 --time 0.1 --out " + (dir_ / "o").string(),
                     "max_nearest_neighbors", dir_ / "o");
    // range: pi/4 passes michi's range check; OMPL's setter could not read it ("Failed converting string")
    spit(file, std::regex_replace(original, first,
                                  "\n  - {name: geometric::RRTConnect, params: {range: pi/4}}\n"
                                  "  - geometric::PRM\n"));
    const CommandRun run = runMichi("plan " + file.string() + PLAN + (dir_ / "pi").string());
    EXPECT_EQ(run.exitCode, 0) << run.output;
    // an empty name in a list flag was dropped
    spit(file, original);
    expectCleanError(
        "bench " + file.string() + " --planners geometric::RRTConnect,, --runs 1 --out " + (dir_ / "o").string(),
        "--planners", dir_ / "o");
}

TEST_F(BadCommands, InputsThatWereAcceptedAsIfTheyMeantSomething)
{
    // an SRDF passive joint that is no joint of the robot (MoveIt's top-level form)
    const fs::path srdf = dir_ / "p/robots/panda/panda.srdf";
    const std::string srdfText = slurp(srdf);
    spit(srdf, std::regex_replace(srdfText, std::regex("</robot>"), "<passive_joint name=\"nojoint\"/></robot>"));
    const std::string problem = (dir_ / "p/panda_table_pick.yaml").string();
    expectCleanError("plan " + problem + PLAN + (dir_ / "o").string(), "nojoint", dir_ / "o");
    spit(srdf, srdfText);
    // a MoveIt request constraining one joint twice, with two values
    const fs::path request = dir_ / "p/moveit/table_pick/request0001.yaml";
    const std::string requestText = slurp(request);
    spit(request, std::regex_replace(requestText, std::regex("joint_name: panda_joint3"), "joint_name: panda_joint2"));
    expectCleanError("plan " + problem + PLAN + (dir_ / "o").string(), "constrained twice", dir_ / "o");
    spit(request, requestText);
    // a spherized URDF of another robot: no link matched, so every link was covered from its own geometry and the
    // file silently did nothing
    const std::string problemText = slurp(problem);
    spit(problem, problemText + "collision:\n  checker: spheres\n  spheres: {urdf: robots/xarm6.urdf}\n");
    expectCleanError("plan " + problem + PLAN + (dir_ / "o").string(), "names none of the links", dir_ / "o");
    spit(problem, problemText);
    // a seed library learned from no training query at all
    expectCleanError(
        "path-seed-library " + (dir_ / "p/planar_2link.yaml").string() + " --out " + (dir_ / "lib.seeds").string(),
        "no training queries", dir_ / "lib.seeds");
    // nor from training queries none of which was solved (found by a tester's sweep: "seeds 0", exit 0): no
    // time to solve any, in a problem with training queries and in a dataset problem
    const fs::path ring = dir_ / "p/xarm6_ring.yaml", table = dir_ / "p/mbm_table_pick.yaml";
    spit(ring, std::regex_replace(slurp(ring), std::regex("training_time: 5"), "training_time: 1.0e-9"));
    spit(table,
         std::regex_replace(std::regex_replace(slurp(table), std::regex("training_time: 5"), "training_time: 1.0e-9"),
                            std::regex("training: 0-49"), "training: 0-1"));
    for (const auto &[problem, expected] :
         {std::make_pair(ring, std::string("none of the 60 training queries")),
          std::make_pair(table, std::string("none of the 2 training problems of table_pick"))})
    {
        const CommandRun run =
            runMichi("path-seed-library " + problem.string() + " --out " + (dir_ / "lib.seeds").string());
        EXPECT_EQ(run.exitCode, 1) << run.output;
        const std::string last = lastLine(run.output);
        EXPECT_NE(last.find(expected), std::string::npos) << last;
        EXPECT_NE(last.find("1e-09 s each"), std::string::npos) << last;
        EXPECT_FALSE(fs::exists(dir_ / "lib.seeds")) << run.output;
    }
}

TEST_F(BadCommands, SettingsThatHungOrBlamedTheWrongKey)
{
    // Found by the bad-input sweep of 2026-12-07 (docs/reliability.md). One motion check cannot be interrupted, so
    // a setting that made it test billions of states hung `michi plan` far past --time.
    const fs::path corridor = dir_ / "p/se2_corridor.yaml";
    const std::string corridorText = slurp(corridor);
    spit(corridor, std::regex_replace(corridorText, std::regex("\nrobot:\n"),
                                      "\ncollision: {motion_validator: discrete, valid_segment_fraction: 1.0e-12}\n"
                                      "robot:\n"));
    expectCleanError("plan " + corridor.string() + PLAN + (dir_ / "o").string(), "collision.valid_segment_fraction",
                     dir_ / "o");
    spit(corridor, std::regex_replace(corridorText, std::regex("motion: turn_move_turn"),
                                      "motion: {model: turn_move_turn, turn_weight: 1.0e12}"));
    expectCleanError("plan " + corridor.string() + PLAN + (dir_ / "o").string(), "robot.motion.turn_weight",
                     dir_ / "o");
    // a tiny turn weight makes every motion's checks far denser (its turns take a tiny share of the distance): the
    // weight is to blame, not collision.max_step and robot.bounds (found 2026-12-07)
    spit(corridor, std::regex_replace(corridorText, std::regex("motion: turn_move_turn"),
                                      "motion: {model: turn_move_turn, turn_weight: 1.0e-6}"));
    expectCleanError("plan " + corridor.string() + PLAN + (dir_ / "o").string(), "robot.motion.turn_weight",
                     dir_ / "o");
    spit(corridor, corridorText);
    // an unknown planner on the command line is a usage error (exit 2), named by its flag, not the problem's key
    const CommandRun run =
        runMichi("bench " + corridor.string() + " --planners geometric::Foo --runs 1 --out " + (dir_ / "o").string());
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(lastLine(run.output).find("--planners: unknown planner 'geometric::Foo'"), std::string::npos)
        << run.output;
    EXPECT_FALSE(fs::exists(dir_ / "o"));
    // the dual-arm planner is checked when the file is read (it was found unknown after the work-space maps)
    const fs::path dualArm = dir_ / "p/dual_arm.yaml";
    spit(dualArm,
         std::regex_replace(slurp(dualArm), std::regex("planner: geometric::RRTstar"), "planner: geometric::Foo"));
    expectCleanError("dualarm " + dualArm.string() + " --out " + (dir_ / "o").string(), "dual_arm.planning.planner",
                     dir_ / "o");
    // DualRoadmap's settings under extras.replan are named there, not under planners
    const fs::path passage = dir_ / "p/dynamic_mobile_passage.yaml";
    spit(passage, std::regex_replace(slurp(passage), std::regex("dual_roadmap_params: \\{edge_probes"),
                                     "dual_roadmap_params: {edge_probs"));
    expectCleanError("replan " + passage.string() + " --episodes 1 --methods dual --out " + (dir_ / "o").string(),
                     "extras.replan.dual_roadmap_params.edge_probs", dir_ / "o");
    // a margin that grows a walker's predicted copy over the start is the margin's key, not "start: in collision"
    // (found 2026-12-07)
    spit(passage, std::regex_replace(slurp(passage), std::regex("dual_roadmap_params: \\{edge_probs"),
                                     "dual_roadmap_params: {edge_probes"));
    spit(passage, std::regex_replace(slurp(passage), std::regex("\n    margin: [0-9.]+"), "\n    margin: 3"));
    expectCleanError("replan " + passage.string() + " --episodes 1 --methods dual --out " + (dir_ / "o").string(),
                     "extras.replan.margin: the start touches a moving obstacle grown by the margin of 3 m",
                     dir_ / "o");
    // a tiny lattice angle step is blamed on itself, not on cell_size
    expectCleanError("lattice " + corridor.string() + " --angle-steps 1e-9 --out " + (dir_ / "o").string(),
                     "raise angle_step", dir_ / "o");
    // a map resolution of 1e-300 made a map 1e-297 m wide: OMPL's error without a key (MovingAI), or a plan in it (PGM)
    for (const char *name : {"movingai_64room.yaml", "se2_corridor_pgm.yaml"})
    {
        const fs::path map = dir_ / "p" / name;
        spit(map, std::regex_replace(slurp(map), std::regex("\n    resolution: [0-9.]+"), "\n    resolution: 1e-300"));
        expectCleanError("plan " + map.string() + PLAN + (dir_ / "o").string(),
                         ".resolution: expected a number of metres", dir_ / "o");
    }
    // a planner that cannot plan for the robot is refused, not run to "no path"
    expectCleanError("plan " + (dir_ / "p/planar_2link.yaml").string() +
                         " --planner michi::HeadingLattice --time 0.3 --out " + (dir_ / "o").string(),
                     "robot.type", dir_ / "o");
    // nor are the first setting's pictures left behind when a later one fails
    expectCleanError("lattice " + corridor.string() + " --cell-sizes 0.25,1e-7 --out " + (dir_ / "o").string(),
                     "raise cell_size", dir_ / "o");
}

TEST_F(BadCommands, BinaryFilesAreQuotedAsOnePrintableLine)
{
    // a binary file where a MovingAI map is expected: the error quoted its first "line", raw bytes and all
    std::string bytes;
    for (int i = 0; i < 4000; ++i)
        bytes += static_cast<char>((i * 7919 + 13) % 256);
    const fs::path map = dir_ / "p/maps/movingai/arena.map";
    spit(map, bytes);
    const CommandRun run = runMichi("plan " + (dir_ / "p/movingai_arena.yaml").string() + PLAN + (dir_ / "o").string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    const std::string last = lastLine(run.output);
    EXPECT_NE(last.find("arena.map: header"), std::string::npos) << last;
    EXPECT_LT(last.size(), 400u) << last;
    for (const char c : last)
        EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f) << "a control byte in: " << last;
    EXPECT_FALSE(fs::exists(dir_ / "o"));
}

TEST_F(BadCommands, PlanRefusesAPathThatFclDoesNotCertify)
{
    // Found by the exploratory sweep of 2026-12-07 (docs/reliability.md): `michi plan` wrote, with exit code 0, paths
    // that the sampling motion validator let through a corner of a blocked cell, where `michi bench` counted the same
    // path as a failure. Here a wall 2 cm thick spans the whole room and the validator checks states 1 m of robot
    // motion apart: every path it accepts crosses the wall, so plan must refuse it and write nothing.
    const fs::path problem = dir_ / "wall.yaml";
    spit(problem,
         "name: wall\n"
         "robot:\n"
         "  type: se2\n"
         "  footprint: [[-0.05, -0.05], [0.05, -0.05], [0.05, 0.05], [-0.05, 0.05]]\n"
         "  bounds: {x: [0, 3], y: [0, 1]}\n"
         "collision: {motion_validator: workspace, max_step: 1.0}\n"
         "scene:\n"
         "  obstacles:\n"
         "    - name: wall\n"
         "      box: [0.02, 2, 1]\n"
         "      pose: {xyz: [1.2, 0.5, 0.5]}\n"
         "start: [0.5, 0.5, 0]\n"
         "goal: [2.5, 0.5, 0]\n"
         "planners: [geometric::RRTConnect]\n"
         "benchmark: {time_limit: 1, runs: 1}\n");
    const CommandRun run = runMichi("plan " + problem.string() + " --planner geometric::RRTConnect --time 1 --out " +
                                    (dir_ / "o").string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    const std::string last = lastLine(run.output);
    EXPECT_NE(last.find("NOT certified by FCL"), std::string::npos) << run.output;
    EXPECT_NE(last.find("'wall'"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir_ / "o"));
}

TEST_F(BadCommands, OutputsReplaceOnlyWhatMichiWrote)
{
    // Found by the exploratory sweep of 2026-12-07: a folder that had the name of an output file was deleted with
    // everything in it, and a rerun of `michi replan` deleted a user's file kept in the episode folder.
    const fs::path out = dir_ / "o";
    const fs::path clash = out / "planar_2link-geometric__RRTConnect.svg";
    fs::create_directories(clash);
    spit(clash / "notes.txt", "mine\n");
    const CommandRun plan = runMichi("plan " + (dir_ / "p/planar_2link.yaml").string() + PLAN + out.string());
    EXPECT_EQ(plan.exitCode, 1) << plan.output;
    EXPECT_NE(lastLine(plan.output).find("is in the way"), std::string::npos) << plan.output;
    EXPECT_EQ(slurp(clash / "notes.txt"), "mine\n");
    EXPECT_FALSE(fs::exists(out / "planar_2link-geometric__RRTConnect.path"));

    // a folder michi wrote is replaced by the next run, but not once a user has put a file of their own in it
    const std::string replan = "replan " + (dir_ / "p/dynamic_mobile_passage.yaml").string() +
                               " --episodes 1 --methods dual --out " + (dir_ / "r").string();
    ASSERT_EQ(runMichi(replan).exitCode, 0);
    ASSERT_TRUE(fs::is_directory(dir_ / "r/episode"));
    const CommandRun again = runMichi(replan);
    EXPECT_EQ(again.exitCode, 0) << again.output;
    spit(dir_ / "r/episode/mynotes.txt", "mine\n");
    const CommandRun third = runMichi(replan);
    EXPECT_EQ(third.exitCode, 1) << third.output;
    EXPECT_NE(lastLine(third.output).find("holds files michi did not write"), std::string::npos) << third.output;
    EXPECT_EQ(slurp(dir_ / "r/episode/mynotes.txt"), "mine\n");
}

TEST_F(BadCommands, AQueryEndTheFastCheckerRefusesIsNamedBeforePlanning)
{
    // Found by the exploratory sweep of 2026-12-07: with the J-map checker a start free for FCL but refused by the
    // conservative map showed only as OMPL's "Invalid start" after the time limit; the grid checker already warned.
    // table_pick 6's goal (a grasp) is refused by the spheres alone (exact_states off) and free for FCL.
    const fs::path problem = dir_ / "p/datasets/table_pick/table_pick_0006.yaml";
    spit(problem, slurp(problem) + "collision:\n  checker: spheres\n  spheres: {exact_states: off}\n");
    const CommandRun run = runMichi("plan " + problem.string() + PLAN + (dir_ / "o").string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find("goal ("), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("is free for FCL but the spheres checker, which is conservative, calls it invalid"),
              std::string::npos)
        << run.output;
    EXPECT_EQ(run.output.find("start ("), std::string::npos) << run.output;  // the ready pose is free for both
    EXPECT_FALSE(fs::exists(dir_ / "o"));
}

TEST_F(BadCommands, AQueryIsNamedByItsKeyInTheFileNotByItsIndex)
{
    // Found by the campaign sweep of 2026-12-07: with a top-level start and goal before a queries list, query i of
    // the problem is queries[i - 1] of the file, but messages named queries[i] (a key the file may not have) and
    // blamed queries[0] for the top-level start.
    const fs::path arm = dir_ / "p/planar_2link.yaml";
    std::string text = slurp(arm);
    const auto start = text.find("\nstart:") + 1;
    ASSERT_NE(start, std::string::npos + 1);
    // [1, 1] puts link 2 into the upper L (the sweep's case)
    text.replace(start, text.find('\n', start) - start, "start: [1, 1]");
    spit(arm, text + "queries:\n  - {start: [0.1, 0.2], goal: [-2.5, 0.4]}\n  - {start: [0.1, 0.2], goal: [1, 1]}\n");
    expectCleanError("plan " + arm.string() + PLAN + (dir_ / "o").string(), ": start: in collision", dir_ / "o");
    expectCleanError("plan " + arm.string() + " --query 2" + PLAN + (dir_ / "o").string(),
                     ": queries[1].goal: in collision", dir_ / "o");
}
