// Tests of the problem sources besides michi's own YAML: SRDF (robot.srdf), MoveIt PlanningScene (scene.moveit),
// MoveIt MotionPlanRequest (request, queries[i].request) and MovingAI grid maps (scene.movingai): what each gives
// (disabled pairs, groups, obstacle poses against hand-computed ones, start/goal, boxes over blocked cells), the
// ProblemError for malformed files (naming the file), and the bundled problems made from real data
// (panda_table_pick with MotionBenchMaker's table_pick scenes, movingai_arena).

#include "support/TestScenes.h"

#include <michi/tools/problem/MoveItImport.h>
#include <michi/tools/problem/MovingAiMap.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <map>
#include <set>

using namespace michi;
using tools::ProblemError;
using validity::Obstacle;
using validity::Shape;

namespace
{
    /** The ProblemError thrown by \e f; fails the test when \e f throws nothing or something else. */
    ProblemError problemError(const std::function<void()> &f)
    {
        try
        {
            f();
        }
        catch (const ProblemError &e)
        {
            return e;
        }
        catch (const std::exception &e)
        {
            ADD_FAILURE() << "expected a ProblemError, got: " << e.what();
            return ProblemError("", "", "");
        }
        ADD_FAILURE() << "expected a ProblemError, nothing was thrown";
        return ProblemError("", "", "");
    }

    /** Expect \e f to throw a ProblemError naming \e file whose key contains \e key and whose message is one
        line. */
    void expectProblemError(const std::function<void()> &f, const std::string &file, const std::string &key)
    {
        const ProblemError e = problemError(f);
        EXPECT_EQ(e.file(), file) << e.what();
        EXPECT_NE(e.key().find(key), std::string::npos) << "key '" << e.key() << "' lacks '" << key << "'";
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).rfind(file, 0), 0u) << e.what();
    }

    std::map<std::string, Obstacle> obstaclesByName(const validity::Scene &scene)
    {
        std::map<std::string, Obstacle> byName;
        for (const auto &o : scene.obstacles())
            byName[o.name] = o;
        return byName;
    }

    void expectPose(const Eigen::Isometry3d &actual, const Eigen::Isometry3d &expected)
    {
        EXPECT_TRUE(actual.translation().isApprox(expected.translation(), 1e-9))
            << actual.translation().transpose() << " vs " << expected.translation().transpose();
        EXPECT_TRUE(actual.linear().isApprox(expected.linear(), 1e-9)) << actual.linear() << "\nvs\n"
                                                                       << expected.linear();
    }

    /** A planar 3-link arm (links link1..link3 with joints joint1..joint3 about z, root base_link) and a tool
        link on a fixed joint, written to \e dir as arm.urdf. */
    std::string writeArm(const test::TempDir &dir)
    {
        std::string urdf = test::planarArmUrdf({0.5, 0.4, 0.3});
        const std::string tool = R"(
  <link name="tool"><collision><geometry><sphere radius="0.02"/></geometry></collision></link>
  <joint name="tool_joint" type="fixed"><parent link="link3"/><child link="tool"/><origin xyz="0.3 0 0"/></joint>
</robot>)";
        urdf.replace(urdf.rfind("</robot>"), std::string("</robot>").size(), tool);
        return dir.write("arm.urdf", urdf);
    }

    const char *ARM_SRDF = R"(<?xml version="1.0"?>
<robot name="planar_arm">
  <group name="arm"><chain base_link="base_link" tip_link="link2"/></group>
  <group name="wrist"><joint name="joint3"/></group>
  <group name="whole"><group name="arm"/><group name="by_link"/></group>
  <group name="by_link"><link name="link3"/><passive_joint name="tool_joint"/></group>
  <group name="tool_only"><joint name="tool_joint"/></group>
  <group_state group="arm" name="home"><joint name="joint1" value="0"/></group_state>
  <disable_collisions link1="link1" link2="link3" reason="Never"/>
  <disable_collisions link1="base_link" link2="tool" reason="Never"/>
</robot>
)";

    /** A PlanningScene with a box (object pose and primitive pose), a cylinder [height, radius], a sphere and a
        one-triangle mesh, and an allowed_collision_matrix naming robot links and an object. */
    const char *ARM_SCENE = R"(name: test
robot_state:
  joint_state: {name: [joint1], position: [1.0]}
allowed_collision_matrix:
  entry_names: [link1, link2, link3, crate]
  entry_values:
    - [false, true, false, true]
    - [true, false, true, false]
    - [false, true, false, true]
    - [true, false, true, false]
world:
  collision_objects:
    - id: crate
      header: {frame_id: world}
      pose:
        position: [1, 0, 0]
        orientation: [0, 0, 0.7071067811865476, 0.7071067811865476]
      primitives:
        - type: box
          dimensions: [0.2, 0.3, 0.4]
      primitive_poses:
        - position: [0.5, 0, 0.1]
          orientation: [0, 0, 0, 1]
    - id: pole
      primitives:
        - {type: cylinder, dimensions: [0.8, 0.05]}
        - {type: sphere, dimensions: [0.1]}
      primitive_poses:
        - position: {x: 0, y: 1, z: 0.4}
          orientation: {x: 0.7071067811865476, y: 0, z: 0, w: 0.7071067811865476}
        - position: [0, 1, 0.9]
          orientation: [0, 0, 0, 0]
      meshes:
        - vertices: [{x: 0, y: 0, z: 0}, {x: 1, y: 0, z: 0}, {x: 0, y: 1, z: 0}]
          triangles: [{vertex_indices: [0, 1, 2]}]
      mesh_poses:
        - position: [0, 0, 2]
          orientation: [0, 0, 0, 1]
)";

    const char *ARM_REQUEST = R"(group_name: arm
start_state:
  joint_state:
    name: [finger, joint2, joint3, joint1]
    position: [0.3, -0.2, 0.7, 0.1]
goal_constraints:
  - joint_constraints:
      - {joint_name: joint2, position: 1.2, tolerance_above: 0.001, tolerance_below: 0.001, weight: 1}
      - {joint_name: joint1, position: -0.5}
)";

    /** Write a problem file \e yaml as problem.yaml in \e dir and load it. */
    tools::Problem loadYaml(const test::TempDir &dir, const std::string &yaml)
    {
        return tools::loadProblem(dir.write("problem.yaml", yaml));
    }
}  // namespace

TEST(ProblemSources, SrdfDisablesPairsAndDefinesGroups)
{
    test::TempDir dir("michi_srdf");
    writeArm(dir);
    dir.write("arm.srdf", ARM_SRDF);
    const auto problem = loadYaml(dir, R"(
robot:
  urdf: arm.urdf
  srdf: arm.srdf
  groups:
    wrist: [joint1]       # the problem file's group wins over the SRDF's of the same name
  group: arm
start: [0, 0]
goal: [1, 1]
)");
    const auto &model = *problem.model;
    EXPECT_TRUE(model.isCollisionAllowed(model.linkIndex("link1"), model.linkIndex("link3")));
    EXPECT_TRUE(model.isCollisionAllowed(model.linkIndex("base_link"), model.linkIndex("tool")));
    EXPECT_FALSE(model.isCollisionAllowed(model.linkIndex("link1"), model.linkIndex("tool")));
    for (const auto &pair : model.selfCollisionPairs())
        EXPECT_FALSE(std::minmax(pair.first, pair.second) ==
                     std::minmax(model.linkIndex("link1"), model.linkIndex("link3")));

    using Joints = std::vector<std::string>;
    EXPECT_EQ(problem.groups.at("arm"), (Joints{"joint1", "joint2"}));              // chain base_link..link2
    EXPECT_EQ(problem.groups.at("wrist"), (Joints{"joint1"}));                      // the YAML's
    EXPECT_EQ(problem.groups.at("by_link"), (Joints{"joint3"}));                    // parent joint of link3
    EXPECT_EQ(problem.groups.at("whole"), (Joints{"joint1", "joint2", "joint3"}));  // subgroups, defined later
    EXPECT_EQ(problem.groups.count("tool_only"), 0u) << "a group without movable joints cannot be planned";
    EXPECT_EQ(problem.group, "arm");
    EXPECT_EQ(problem.valueNames(), (Joints{"joint1", "joint2"}));

    // the reader on its own gives the SRDF's groups, including the one the YAML overrode
    const auto srdf = tools::readSrdf(dir.path() + "/arm.srdf", model);
    EXPECT_EQ(srdf.robotName, "planar_arm");
    EXPECT_EQ(srdf.groups.at("wrist"), (Joints{"joint3"}));
    ASSERT_EQ(srdf.disabledCollisions.size(), 2u);
    EXPECT_EQ(srdf.disabledCollisions[0], std::make_pair(std::string("link1"), std::string("link3")));
}

TEST(ProblemSources, MalformedSrdfNamesTheSrdf)
{
    test::TempDir dir("michi_bad_srdf");
    writeArm(dir);
    const auto model = validity::RobotModel::fromUrdfFile(dir.path() + "/arm.urdf");
    const std::map<std::string, std::pair<std::string, std::string>> cases{
        {"bad_xml", {"<robot name=\"x\"><group name=\"arm\"><joint name=\"joint1\"></group></robot>", "line"}},
        {"not_srdf", {"<model/>", "<model>"}},
        {"unknown_link",
         {"<robot><disable_collisions link1=\"link1\" link2=\"elbow\"/></robot>", "<disable_collisions> line 1"}},
        {"missing_attribute", {"<robot><disable_collisions link1=\"link1\"/></robot>", "<disable_collisions>"}},
        {"unknown_joint", {"<robot><group name=\"g\"><joint name=\"joint9\"/></group></robot>", "<joint>"}},
        {"chain_upside_down",
         {"<robot><group name=\"g\"><chain base_link=\"link3\" tip_link=\"link1\"/></group></robot>", "<chain>"}},
        {"unknown_subgroup", {"<robot><group name=\"g\"><group name=\"h\"/></group></robot>", "<group>"}},
        {"cyclic_subgroups",
         {"<robot><group name=\"g\"><group name=\"h\"/></group><group name=\"h\"><group name=\"g\"/></group></robot>",
          "<group>"}},
    };
    for (const auto &c : cases)
    {
        SCOPED_TRACE(c.first);
        const std::string path = dir.write(c.first + ".srdf", c.second.first);
        expectProblemError(
            [&]
            {
                tools::readSrdf(path, *model);
            },
            path, c.second.second);
    }
    // through a problem file the error still names the SRDF (and the unknown link)
    const std::string srdf = dir.path() + "/unknown_link.srdf";
    const ProblemError e = problemError(
        [&]
        {
            loadYaml(dir, "robot: {urdf: arm.urdf, srdf: unknown_link.srdf}\nstart: [0, 0, 0]\ngoal: [1, 1, 1]\n");
        });
    EXPECT_EQ(e.file(), srdf);
    EXPECT_NE(std::string(e.what()).find("'elbow'"), std::string::npos) << e.what();
    // a missing SRDF is the problem file's robot.srdf key
    expectProblemError(
        [&]
        {
            loadYaml(dir, "robot: {urdf: arm.urdf, srdf: none.srdf}\nstart: [0, 0, 0]\ngoal: [1, 1, 1]\n");
        },
        dir.path() + "/problem.yaml", "robot.srdf");
}

TEST(ProblemSources, MoveItSceneGivesObstaclesAtComposedPoses)
{
    test::TempDir dir("michi_moveit_scene");
    writeArm(dir);
    dir.write("scene.yaml", ARM_SCENE);
    const auto problem = loadYaml(dir, R"(
robot: {urdf: arm.urdf}
scene:
  moveit: scene.yaml
  obstacles:
    - {name: own, box: [0.1, 0.1, 0.1], pose: {xyz: [3, 3, 3]}}
start: [0, 0, 0]
goal: [1, 1, 1]
)");
    auto byName = obstaclesByName(*problem.scene);
    ASSERT_EQ(byName.size(), 5u);
    for (const char *name : {"own", "crate/0", "pole/0", "pole/1", "pole/mesh0"})
        ASSERT_EQ(byName.count(name), 1u) << name;

    // crate: object at (1, 0, 0) turned 90 deg about z; the box 0.5 m along the object's x and 0.1 m up
    const Obstacle &crate = byName["crate/0"];
    ASSERT_EQ(crate.shape->type(), Shape::Type::BOX);
    EXPECT_TRUE(crate.shape->size().isApprox(Eigen::Vector3d(0.2, 0.3, 0.4)));
    Eigen::Isometry3d expected = Eigen::Isometry3d::Identity();
    expected.translation() = Eigen::Vector3d(1., 0.5, 0.1);
    expected.linear() << 0., -1., 0., 1., 0., 0., 0., 0., 1.;
    expectPose(crate.pose, expected);

    // pole/0: cylinder dimensions are [height, radius]; turned 90 deg about x, so its axis (z) lies along -y
    const Obstacle &cylinder = byName["pole/0"];
    ASSERT_EQ(cylinder.shape->type(), Shape::Type::CYLINDER);
    EXPECT_DOUBLE_EQ(cylinder.shape->size().x(), 0.05);  // radius
    EXPECT_DOUBLE_EQ(cylinder.shape->size().z(), 0.8);   // length
    expected.translation() = Eigen::Vector3d(0., 1., 0.4);
    expected.linear() << 1., 0., 0., 0., 0., -1., 0., 1., 0.;
    expectPose(cylinder.pose, expected);
    EXPECT_TRUE((cylinder.pose.linear() * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d(0., -1., 0.)));

    // pole/1: a sphere of radius 0.1; an all-zero quaternion is the identity, as in MoveIt
    const Obstacle &sphere = byName["pole/1"];
    ASSERT_EQ(sphere.shape->type(), Shape::Type::SPHERE);
    EXPECT_DOUBLE_EQ(sphere.shape->size().x(), 0.1);
    expected.translation() = Eigen::Vector3d(0., 1., 0.9);
    expected.linear().setIdentity();
    expectPose(sphere.pose, expected);

    const Obstacle &mesh = byName["pole/mesh0"];
    ASSERT_EQ(mesh.shape->type(), Shape::Type::MESH);
    EXPECT_EQ(mesh.shape->triangles().size(), 1u);
    EXPECT_TRUE(mesh.pose.translation().isApprox(Eigen::Vector3d(0., 0., 2.)));

    // allowed_collision_matrix: link1-link2 and link2-link3 are allowed; the object "crate" is not a link
    const auto &model = *problem.model;
    EXPECT_TRUE(model.isCollisionAllowed(model.linkIndex("link2"), model.linkIndex("link3")));
    EXPECT_FALSE(model.isCollisionAllowed(model.linkIndex("link1"), model.linkIndex("link3")));
    // robot_state is not the start
    EXPECT_EQ(problem.queries[0].start, (std::vector<double>{0., 0., 0.}));
}

TEST(ProblemSources, MoveItSceneFrameIsTheRobotBaseOrAFixedFrame)
{
    test::TempDir dir("michi_moveit_frames");
    writeArm(dir);
    const std::string path = dir.write("scene.yaml", R"(
fixed_frame_transforms:
  - child_frame_id: table
    transform: {translation: [0, 0, 1], rotation: [0, 0, 1, 0]}
world:
  collision_objects:
    - id: on_base
      header: {frame_id: base_link}
      primitives: [{type: sphere, dimensions: [0.1]}]
      primitive_poses: [{position: [1, 0, 0], orientation: [0, 0, 0, 1]}]
    - id: on_table
      header: {frame_id: table}
      primitives: [{type: 1, dimensions: [0.1, 0.1, 0.1]}]
      primitive_poses: [{position: [1, 0, 0], orientation: [0, 0, 0, 1]}]
)");
    auto model = validity::RobotModel::fromUrdfFile(dir.path() + "/arm.urdf");
    Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
    base.translation() = Eigen::Vector3d(0., 2., 0.);
    model->setBasePose(base);
    const auto scene = tools::readMoveItScene(path, model.get());
    ASSERT_EQ(scene.obstacles.size(), 2u);
    EXPECT_TRUE(scene.obstacles[0].pose.translation().isApprox(Eigen::Vector3d(1., 2., 0.)));
    EXPECT_TRUE(scene.obstacles[1].pose.translation().isApprox(Eigen::Vector3d(-1., 0., 1.)));  // 180 deg about z
    EXPECT_EQ(scene.obstacles[1].shape->type(), Shape::Type::BOX);                              // type by number
}

TEST(ProblemSources, MalformedMoveItSceneNamesTheScene)
{
    test::TempDir dir("michi_bad_scene");
    writeArm(dir);
    auto object = [](const std::string &body)
    {
        return "world:\n  collision_objects:\n    - id: thing\n" + body;
    };
    const std::string pose = "      primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n";
    const std::map<std::string, std::pair<std::string, std::string>> cases{
        {"unknown_type",
         {object("      primitives: [{type: torus, dimensions: [1, 2]}]\n" + pose),
          "world.collision_objects[0].primitives[0].type"}},
        {"cone", {object("      primitives: [{type: cone, dimensions: [1, 2]}]\n" + pose), "primitives[0].type"}},
        {"box_dimensions",
         {object("      primitives: [{type: box, dimensions: [1, 2]}]\n" + pose), "primitives[0].dimensions"}},
        {"negative_radius",
         {object("      primitives: [{type: sphere, dimensions: [-1]}]\n" + pose), "primitives[0].dimensions[0]"}},
        {"missing_poses", {object("      primitives: [{type: sphere, dimensions: [1]}]\n"), "primitive_poses"}},
        {"unknown_frame",
         {object("      header: {frame_id: kitchen}\n      primitives: [{type: sphere, dimensions: [1]}]\n" + pose),
          "header.frame_id"}},
        {"link_frame",
         {object("      header: {frame_id: link2}\n      primitives: [{type: sphere, dimensions: [1]}]\n" + pose),
          "header.frame_id"}},
        {"no_id", {"world:\n  collision_objects:\n    - primitives: []\n", "world.collision_objects[0].id"}},
        {"bad_quaternion",
         {object("      primitives: [{type: sphere, dimensions: [1]}]\n      primitive_poses: [{orientation: [0, 0, "
                 "1]}]\n"),
          "primitive_poses[0].orientation"}},
        {"acm_rows",
         {"allowed_collision_matrix: {entry_names: [link1, link2], entry_values: [[false, true]]}\n",
          "allowed_collision_matrix.entry_values"}},
        {"not_yaml", {"world: [unclosed\n", ""}},
    };
    for (const auto &c : cases)
    {
        SCOPED_TRACE(c.first);
        const std::string path = dir.write(c.first + ".yaml", c.second.first);
        expectProblemError(
            [&]
            {
                loadYaml(dir, "robot: {urdf: arm.urdf}\nscene: {moveit: " + c.first +
                                  ".yaml}\nstart: [0, 0, 0]\ngoal: [1, 1, 1]\n");
            },
            path, c.second.second);
    }
}

TEST(ProblemSources, MoveItRequestGivesStartGoalGroupAndFixedJoints)
{
    test::TempDir dir("michi_request");
    writeArm(dir);
    dir.write("arm.srdf", ARM_SRDF);
    dir.write("request.yaml", ARM_REQUEST);
    const auto problem = loadYaml(dir, R"(
robot: {urdf: arm.urdf, srdf: arm.srdf}
request: request.yaml
)");
    EXPECT_EQ(problem.group, "arm");  // group_name, a group of the SRDF
    ASSERT_EQ(problem.queries.size(), 1u);
    EXPECT_EQ(problem.queries[0].start, (std::vector<double>{0.1, -0.2}));
    EXPECT_EQ(problem.queries[0].goal, (std::vector<double>{-0.5, 1.2}));
    // joint3 is named in the start state but not planned: it is fixed there; "finger" is no joint of the robot
    EXPECT_DOUBLE_EQ(problem.fixedValues[problem.model->variableIndex("joint3")], 0.7);

    // robot.fixed_joints wins over the request's start state
    const auto fixed = loadYaml(dir,
                                "robot: {urdf: arm.urdf, srdf: arm.srdf, fixed_joints: {joint3: 0.2}}\n"
                                "request: request.yaml\n");
    EXPECT_EQ(fixed.group, "arm");
    EXPECT_DOUBLE_EQ(fixed.fixedValues[fixed.model->variableIndex("joint3")], 0.2);

    // robot.group wins over group_name; queries may mix start/goal and requests
    std::string three = ARM_REQUEST;
    three += "      - {joint_name: joint3, position: 0.25}\n";
    dir.write("request3.yaml", three);
    const auto second = loadYaml(dir, R"(
robot:
  urdf: arm.urdf
  srdf: arm.srdf
  group: whole
queries:
  - start: [0, 0, 0]
    goal: [0.5, 0.5, 0.5]
  - request: request3.yaml
)");
    EXPECT_EQ(second.group, "whole");
    ASSERT_EQ(second.queries.size(), 2u);
    EXPECT_EQ(second.queries[1].start, (std::vector<double>{0.1, -0.2, 0.7}));
    EXPECT_EQ(second.queries[1].goal, (std::vector<double>{-0.5, 1.2, 0.25}));
    // "whole" needs joint3 in the goal, which request.yaml lacks
    const auto groupOfThree = [&]
    {
        loadYaml(dir, "robot: {urdf: arm.urdf, srdf: arm.srdf, group: whole}\nrequest: request.yaml\n");
    };
    expectProblemError(groupOfThree, dir.path() + "/request.yaml", "goal_constraints[0].joint_constraints");
}

TEST(ProblemSources, MalformedMoveItRequestNamesTheRequest)
{
    test::TempDir dir("michi_bad_request");
    writeArm(dir);
    dir.write("arm.srdf", ARM_SRDF);
    const std::string start = "start_state:\n  joint_state: {name: [joint1, joint2], position: [0, 0]}\n";
    const std::string goal =
        "goal_constraints:\n  - joint_constraints: [{joint_name: joint1, position: 0}, "
        "{joint_name: joint2, position: 3.5}]\n";
    const std::map<std::string, std::pair<std::string, std::string>> cases{
        {"no_goal", {"group_name: arm\n" + start, "goal_constraints"}},
        {"empty_goal", {"group_name: arm\n" + start + "goal_constraints: []\n", "goal_constraints"}},
        {"pose_goal",
         {"group_name: arm\n" + start + "goal_constraints:\n  - position_constraints: [{link_name: link3}]\n",
          "goal_constraints[0].joint_constraints"}},
        {"no_start", {"group_name: arm\n" + goal, "start_state"}},
        {"short_positions",
         {"group_name: arm\nstart_state:\n  joint_state: {name: [joint1, joint2], position: [0]}\n" + goal,
          "start_state.joint_state.position"}},
        {"missing_joint",
         {"group_name: arm\nstart_state:\n  joint_state: {name: [joint1], position: [0]}\n" + goal,
          "start_state.joint_state.name"}},
        {"unknown_group", {"group_name: legs\n" + start + goal, "group_name"}},
        {"goal_outside_limits", {"group_name: arm\n" + start + goal, "goal_constraints[0].joint_constraints"}},
    };
    for (const auto &c : cases)
    {
        SCOPED_TRACE(c.first);
        const std::string path = dir.write(c.first + ".yaml", c.second.first);
        expectProblemError(
            [&]
            {
                loadYaml(dir, "robot: {urdf: arm.urdf, srdf: arm.srdf}\nrequest: " + c.first + ".yaml\n");
            },
            path, c.second.second);
    }
    // request and start/goal together: the problem file's error
    dir.write("good.yaml", "group_name: arm\n" + start +
                               "goal_constraints:\n  - joint_constraints: [{joint_name: joint1, position: 0}, "
                               "{joint_name: joint2, position: 1}]\n");
    expectProblemError(
        [&]
        {
            loadYaml(dir,
                     "robot: {urdf: arm.urdf, srdf: arm.srdf}\nrequest: good.yaml\nstart: [0, 0]\ngoal: [1, "
                     "1]\n");
        },
        dir.path() + "/problem.yaml", "request");
    const auto ok = loadYaml(dir, "robot: {urdf: arm.urdf, srdf: arm.srdf}\nrequest: good.yaml\n");
    EXPECT_EQ(ok.queries[0].goal, (std::vector<double>{0., 1.}));
}

TEST(ProblemSources, MovingAiMapGivesBoxesExactlyOverBlockedCells)
{
    test::TempDir dir("michi_movingai");
    // CRLF line ends, as the benchmark's files have
    const std::string path = dir.write("grid.map",
                                       "type octile\r\nheight 3\r\nwidth 4\r\nmap\r\n"
                                       ".@@.\r\n"
                                       "T..S\r\n"
                                       "..GW\r\n");
    const auto map = tools::readMovingAiMap(path);
    EXPECT_EQ(map.width, 4);
    EXPECT_EQ(map.height, 3);
    const double r = 0.5;
    const auto boxes = tools::movingAiObstacles(map, r, Eigen::Vector2d(10., 20.), 2.);
    ASSERT_EQ(boxes.size(), 3u);  // row 0: one run of two cells; row 1: one cell; row 2: one cell
    // row 0 (the top, y from 21.0 to 21.5): columns 1-2
    EXPECT_EQ(boxes[0].name, "cells_r0_c1");
    EXPECT_TRUE(boxes[0].shape->size().isApprox(Eigen::Vector3d(1.0, 0.5, 2.)));
    EXPECT_TRUE(boxes[0].pose.translation().isApprox(Eigen::Vector3d(11.0, 21.25, 1.)));
    EXPECT_TRUE(boxes[1].shape->size().isApprox(Eigen::Vector3d(0.5, 0.5, 2.)));
    EXPECT_TRUE(boxes[1].pose.translation().isApprox(Eigen::Vector3d(10.25, 20.75, 1.)));
    EXPECT_TRUE(boxes[2].pose.translation().isApprox(Eigen::Vector3d(11.75, 20.25, 1.)));

    // every cell centre is inside a box exactly when the cell is blocked
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x)
        {
            const Eigen::Vector2d c = tools::movingAiCellCentre(map, x, y, r, Eigen::Vector2d(10., 20.));
            int inside = 0;
            for (const auto &b : boxes)
            {
                const Eigen::Vector3d local = b.pose.inverse() * Eigen::Vector3d(c.x(), c.y(), 1.);
                inside += (local.cwiseAbs().array() < 0.5 * b.shape->size().array()).all();
            }
            EXPECT_EQ(inside, map.blocked(x, y) ? 1 : 0) << "cell " << x << ", " << y;
        }
    EXPECT_TRUE(map.blocked(3, 2));   // W
    EXPECT_FALSE(map.blocked(3, 1));  // S: swamp, passable
}

TEST(ProblemSources, MovingAiSceneAndScenariosInAProblem)
{
    test::TempDir dir("michi_movingai_problem");
    dir.write("grid.map", "type octile\nheight 3\nwidth 4\nmap\n.@@.\nT...\n..GW\n");
    dir.write("grid.map.scen",
              "version 1\n"
              "0\tgrid.map\t4\t3\t0\t0\t3\t0\t4\n"
              "1\tgrid.map\t4\t3\t1\t2\t3\t1\t2.41421\n"
              "1\tgrid.map\t4\t3\t0\t2\t3\t0\t4.41421\n");
    const auto problem = loadYaml(dir, R"(
robot:
  type: se2
  footprint: [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]]
scene:
  movingai: {map: grid.map, resolution: 0.5, scenarios: {file: grid.map.scen, bucket: 1}}
)");
    EXPECT_EQ(problem.scene->size(), 3u);
    EXPECT_EQ(problem.se2Bounds, (std::array<double, 4>{{0., 2., 0., 1.5}}));  // from the map
    ASSERT_EQ(problem.queries.size(), 2u);
    EXPECT_EQ(problem.queries[0].start, (std::vector<double>{0.75, 0.25, 0.}));  // cell (1, 2): bottom row
    EXPECT_EQ(problem.queries[0].goal, (std::vector<double>{1.75, 0.75, 0.}));
    EXPECT_EQ(problem.queries[1].start, (std::vector<double>{0.25, 0.25, 0.}));
    for (std::size_t q = 0; q < problem.queries.size(); ++q)
        EXPECT_NO_THROW(tools::makePlanningContext(problem, q));

    // explicit start/goal come first; count limits the scenarios
    const auto counted = loadYaml(dir, R"(
robot:
  type: se2
  footprint: [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]]
  bounds: {x: [0, 2], y: [0, 1.5]}
scene:
  movingai: {map: grid.map, resolution: 0.5, scenarios: {file: grid.map.scen, count: 1}}
start: [0.25, 0.25, 0]
goal: [0.75, 0.75, 0]
)");
    ASSERT_EQ(counted.queries.size(), 2u);
    EXPECT_EQ(counted.queries[1].goal, (std::vector<double>{1.75, 1.25, 0.}));  // bucket 0: cell (3, 0)
}

TEST(ProblemSources, MalformedMovingAiFilesNameTheFile)
{
    test::TempDir dir("michi_bad_movingai");
    const std::map<std::string, std::pair<std::string, std::string>> cases{
        {"wrong_type", {"type hexagonal\nheight 1\nwidth 1\nmap\n.\n", "header.type"}},
        {"no_type", {"height 1\nwidth 1\nmap\n.\n", "header.type"}},
        {"bad_height", {"type octile\nheight two\nwidth 1\nmap\n.\n", "header.height"}},
        {"no_width", {"type octile\nheight 1\nmap\n.\n", "header.width"}},
        {"no_map_line", {"type octile\nheight 1\nwidth 1\n", "header"}},
        {"unknown_line", {"type octile\nheight 1\nwidth 1\ndepth 3\nmap\n.\n", "header"}},
        {"short_row", {"type octile\nheight 2\nwidth 3\nmap\n...\n..\n", "row 1"}},
        {"missing_row", {"type octile\nheight 2\nwidth 3\nmap\n...\n", "row 1"}},
        {"extra_row", {"type octile\nheight 1\nwidth 3\nmap\n...\n...\n", "row 1"}},
        {"unknown_character", {"type octile\nheight 1\nwidth 3\nmap\n.x.\n", "row 0"}},
    };
    for (const auto &c : cases)
    {
        SCOPED_TRACE(c.first);
        const std::string path = dir.write(c.first + ".map", c.second.first);
        expectProblemError(
            [&]
            {
                tools::readMovingAiMap(path);
            },
            path, c.second.second);
        expectProblemError(
            [&]
            {
                loadYaml(dir, "robot: {type: se2, footprint: [[0, 0], [0.1, 0], [0, 0.1]]}\nscene: {movingai: {map: " +
                                  c.first + ".map}}\nstart: [0.5, 0.5, 0]\ngoal: [0.5, 0.5, 0]\n");
            },
            path, c.second.second);
    }
    const std::string scen = dir.write("bad.scen", "version 1\n0\tgrid.map\t4\t3\t0\n");
    expectProblemError(
        [&]
        {
            tools::readMovingAiScenarios(scen);
        },
        scen, "line 2");
    const std::string version = dir.write("old.scen", "version 2\n");
    expectProblemError(
        [&]
        {
            tools::readMovingAiScenarios(version);
        },
        version, "version");
}

TEST(ProblemSources, BundledPandaTablePickLoadsWithValidStartAndGoal)
{
    const std::string path = test::sourcePath("problems/panda_table_pick.yaml");
    const auto problem = tools::loadProblem(path);
    EXPECT_EQ(problem.group, "panda_arm");  // from the request's group_name, defined by the SRDF's chain
    const std::vector<std::string> arm{"panda_joint1", "panda_joint2", "panda_joint3", "panda_joint4",
                                       "panda_joint5", "panda_joint6", "panda_joint7"};
    EXPECT_EQ(problem.valueNames(), arm);
    EXPECT_EQ(problem.scene->size(), 12u);  // MotionBenchMaker's table_pick: 12 boxes and cylinders
    const auto &model = *problem.model;
    EXPECT_TRUE(model.isCollisionAllowed(model.linkIndex("panda_link0"), model.linkIndex("panda_link2")));  // SRDF
    EXPECT_TRUE(model.isCollisionAllowed(model.linkIndex("panda_link3"), model.linkIndex("panda_hand")));
    ASSERT_EQ(problem.queries.size(), 1u);
    EXPECT_EQ(problem.queries[0].start, (std::vector<double>{0, -0.785, 0, -2.356, 0, 1.571, 0.785}));
    const auto ctx = tools::makePlanningContext(problem, 0);  // throws when start or goal collides
    EXPECT_TRUE(ctx.checker->isValidConfiguration(problem.queries[0].start.data()));
    EXPECT_TRUE(ctx.checker->isValidConfiguration(problem.queries[0].goal.data()));
}

TEST(ProblemSources, BundledTablePickScenesAndRequestsAreValidPairs)
{
    // every copied MotionBenchMaker scene with its own request: a problem whose start and goal are valid
    test::TempDir dir("michi_table_pick");
    for (const char *n : {"0001", "0002", "0003", "0004", "0005"})
    {
        SCOPED_TRACE(n);
        const std::string problems = test::sourcePath("problems");
        const auto problem =
            loadYaml(dir, "robot:\n  urdf: " + problems + "/robots/panda/panda.urdf\n  srdf: " + problems +
                              "/robots/panda/panda.srdf\nscene:\n  moveit: " + problems + "/moveit/table_pick/scene" +
                              n + ".yaml\nrequest: " + problems + "/moveit/table_pick/request" + n + ".yaml\n");
        EXPECT_EQ(problem.dimension(), 7u);
        EXPECT_NO_THROW(tools::makePlanningContext(problem, 0));
    }
}

TEST(ProblemSources, BundledMovingAiArenaLoads)
{
    const auto problem = tools::loadProblem(test::sourcePath("problems/movingai_arena.yaml"));
    EXPECT_EQ(problem.kind, tools::Problem::Kind::SE2);
    const std::array<double, 4> bounds{{0., 4.9, 0., 4.9}};  // 49 cells of 0.1 m
    for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(problem.se2Bounds[i], bounds[i], 1e-12);
    ASSERT_EQ(problem.queries.size(), 3u);
    // arena.map.scen, bucket 15, first line: start cell (1, 3), goal cell (41, 47)
    EXPECT_NEAR(problem.queries[0].start[0], 0.15, 1e-12);
    EXPECT_NEAR(problem.queries[0].start[1], 4.55, 1e-12);
    EXPECT_NEAR(problem.queries[0].goal[0], 4.15, 1e-12);
    EXPECT_NEAR(problem.queries[0].goal[1], 0.15, 1e-12);
    for (std::size_t q = 0; q < problem.queries.size(); ++q)
        EXPECT_NO_THROW(tools::makePlanningContext(problem, q));
}
