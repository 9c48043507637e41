#include "ProblemYaml.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace michi
{
    namespace tools
    {
        namespace problem_file
        {
            void readArm(const Reader &r, const YAML::Node &robot, Problem &problem, const MoveItRequest &request)
            {
                r.keys(robot, "robot",
                       {"type", "urdf", "srdf", "base_pose", "groups", "group", "fixed_joints", "allowed_collisions"});
                const std::string urdf = r.path(r.require(robot, "urdf", "robot"), "robot.urdf");
                problem.model = validity::RobotModel::fromUrdfFile(urdf);  // UrdfError names the URDF
                const auto &model = *problem.model;
                // Nothing to plan: every state space and checker below assumes at least one value.
                if (model.variableCount() == 0)
                    r.fail("robot.urdf", "robot '" + model.name() + "' has no movable joint");
                if (robot["base_pose"])
                    // Before anything reads the model: every link pose, bound and picture is in the world frame through
                    // the base pose.
                    problem.model->setBasePose(r.pose(robot["base_pose"], "robot.base_pose"));

                auto checkJoint = [&](const std::string &joint, const std::string &key)
                {
                    try
                    {
                        return model.variableIndex(joint);
                    }
                    catch (const std::out_of_range &e)
                    {
                        r.fail(key, e.what());
                    }
                };
                if (const YAML::Node groups = robot["groups"])
                {
                    if (!groups.IsMap())
                        r.fail("robot.groups", "expected a mapping of group name to a list of joint names");
                    for (const auto &kv : groups)
                    {
                        const std::string g = kv.first.as<std::string>();
                        const std::string key = "robot.groups." + g;
                        if (!kv.second.IsSequence() || kv.second.size() == 0)
                            r.fail(key, "expected a non-empty list of joint names");
                        for (std::size_t i = 0; i < kv.second.size(); ++i)
                        {
                            const std::string joint = r.text(kv.second[i], key + "[" + std::to_string(i) + "]");
                            checkJoint(joint, key + "[" + std::to_string(i) + "]");
                            // a joint listed twice would be two variables of one joint: states whose two copies
                            // disagree, written to paths under one name
                            const auto &listed = problem.groups[g];
                            if (std::find(listed.begin(), listed.end(), joint) != listed.end())
                                r.fail(key + "[" + std::to_string(i) + "]", "joint '" + joint + "' is listed twice");
                            problem.groups[g].push_back(joint);
                        }
                    }
                }
                if (robot["srdf"])
                {
                    // disabled pairs and groups of the SRDF; a group of robot.groups wins over one of the same name
                    const SrdfModel srdf = readSrdf(r.path(robot["srdf"], "robot.srdf"), model);
                    for (const auto &pair : srdf.disabledCollisions)
                        problem.model->allowCollision(pair.first, pair.second);
                    for (const auto &g : srdf.groups)
                        // emplace() keeps an existing entry, which is what makes robot.groups win.
                        problem.groups.emplace(g.first, g.second);
                }
                const std::string groupSources = robot["srdf"] ? "robot.groups or robot.srdf" : "robot.groups";
                if (robot["group"])
                {
                    if (problem.groups.empty())
                        r.fail("robot.group", "names a group but robot.groups is missing");
                    problem.group = r.text(robot["group"], "robot.group");
                    if (!problem.groups.count(problem.group))
                        r.fail("robot.group", "no group named '" + problem.group + "' in " + groupSources);
                }
                else if (!request.groupName.empty())
                {
                    problem.group = request.groupName;
                    if (!problem.groups.count(problem.group))
                        throw ProblemError(
                            request.file, "group_name",
                            "no group named '" + problem.group + "' in " + groupSources + " of '" + r.file() + "'");
                }
                else
                {
                    // No group anywhere: plan every movable joint, in the model's configuration order.
                    problem.groups["all"] = model.variableNames();
                    problem.group = "all";
                }
                for (const auto &joint : problem.groups[problem.group])
                    problem.groupVariables.push_back(model.variableIndex(joint));
                // A mimic joint (URDF <mimic>) follows the joint it names. Planned itself, it would be a dimension that
                // moves nothing real; with the joint it follows planned, its links would move where neither the
                // checkers' kinematics nor the motion validators' displacement bounds follow them.
                for (int v : problem.groupVariables)
                {
                    // equal limits are valid URDF (a joint that cannot move) but leave the planning space no interval
                    const auto &limited = model.variableJoint(static_cast<std::size_t>(v));
                    if (limited.type != validity::RobotJoint::Type::CONTINUOUS && !(limited.lower < limited.upper))
                        r.fail("robot.group",
                               "group '" + problem.group + "' plans joint '" + limited.name + "', whose limits in " +
                                   urdf + " leave it no motion (lower = upper = " + std::to_string(limited.lower) +
                                   "): give it a value in robot.fixed_joints or leave it out of the "
                                   "group");
                    const validity::RobotJoint *mimic = model.mimicTiedTo(static_cast<std::size_t>(v));
                    if (mimic == nullptr)
                        continue;
                    const auto &j = model.variableJoint(static_cast<std::size_t>(v));
                    if (mimic == &j)
                        r.fail("robot.group",
                               "group '" + problem.group + "' plans joint '" + j.name + "', which follows '" +
                                   model.joints()[j.mimic].name +
                                   "' (URDF <mimic>) and is not a joint of its own: leave it out of the group");
                    r.fail("robot.group", "group '" + problem.group + "' plans joint '" + j.name +
                                              "', which mimic joint '" + mimic->name +
                                              "' follows (URDF <mimic>): not supported; give '" + j.name +
                                              "' a value in robot.fixed_joints instead" +
                                              (problem.group == "all" && !robot["group"]
                                                   ? std::string(" (with no robot.group every movable "
                                                                 "joint is planned: name a group)")
                                                   : std::string()));
                }

                // joints outside the group: mid-range, or 0 when 0 is within the limits, unless given
                problem.fixedValues.assign(model.variableCount(), 0.);
                for (std::size_t v = 0; v < model.variableCount(); ++v)
                {
                    const auto &j = model.variableJoint(v);
                    if (j.lower > 0. || j.upper < 0.)
                        problem.fixedValues[v] = 0.5 * (j.lower + j.upper);
                }
                if (const YAML::Node fixed = robot["fixed_joints"])
                {
                    if (!fixed.IsMap())
                        r.fail("robot.fixed_joints", "expected a mapping of joint name to value");
                    for (const auto &kv : fixed)
                    {
                        const std::string joint = kv.first.as<std::string>();
                        const std::string key = "robot.fixed_joints." + joint;
                        const int v = checkJoint(joint, key);
                        if (const int m = model.variableJoint(static_cast<std::size_t>(v)).mimic; m >= 0)
                            r.fail(key, "joint '" + joint + "' follows '" + model.joints()[m].name +
                                            "' (URDF <mimic>): give '" + model.joints()[m].name + "' a value instead");
                        problem.fixedValues[v] = r.number(kv.second, key);
                        const auto &j = model.variableJoint(v);
                        if (j.type != validity::RobotJoint::Type::CONTINUOUS &&
                            (problem.fixedValues[v] < j.lower - 1e-9 || problem.fixedValues[v] > j.upper + 1e-9))
                            r.fail(key, "value outside the joint's limits [" + std::to_string(j.lower) + ", " +
                                            std::to_string(j.upper) + "]");
                    }
                }
                model.applyMimic(problem.fixedValues);
                if (const YAML::Node allowed = robot["allowed_collisions"])
                {
                    if (!allowed.IsSequence())
                        r.fail("robot.allowed_collisions", "expected a list of [link_a, link_b] pairs");
                    for (std::size_t i = 0; i < allowed.size(); ++i)
                    {
                        const std::string key = "robot.allowed_collisions[" + std::to_string(i) + "]";
                        if (!allowed[i].IsSequence() || allowed[i].size() != 2)
                            r.fail(key, "expected a pair [link_a, link_b]");
                        try
                        {
                            problem.model->allowCollision(r.text(allowed[i][0], key), r.text(allowed[i][1], key));
                        }
                        catch (const std::out_of_range &e)
                        {
                            r.fail(key, e.what());
                        }
                    }
                }
            }

            namespace
            {
                /** robot.motion of an SE2 robot: a model name, or {model, turn_weight, backward}. */
                void readSe2Motion(const Reader &r, const YAML::Node &n, Se2Motion &motion)
                {
                    if (!n)
                        return;
                    if (n.IsMap())
                        r.keys(n, "robot.motion", {"model", "turn_weight", "backward"});
                    // (a YAML::Node is a reference into the tree: initialise it, never assign to it)
                    const YAML::Node model = n.IsMap() ? r.require(n, "model", "robot.motion") : n;
                    if (n.IsMap())
                    {
                        motion.turnWeight = r.number(n, "turn_weight", "robot.motion", 0.);
                        if (!(motion.turnWeight > 0.) && n["turn_weight"])
                            r.fail("robot.motion.turn_weight", "expected a positive number (metres per radian)");
                        if (n["backward"])
                            motion.backward = r.flag(n["backward"], "robot.motion.backward");
                    }
                    const std::string key = n.IsMap() ? "robot.motion.model" : "robot.motion";
                    motion.model = r.text(model, key);
                    if (motion.model != "free" && motion.model != "turn_move_turn")
                        r.fail(key, "expected 'free' or 'turn_move_turn', got '" + motion.model + "'");
                }
            }  // namespace

            void readSe2(const Reader &r, const YAML::Node &robot, Problem &problem, bool mapBounds)
            {
                problem.kind = Problem::Kind::SE2;
                r.keys(robot, "robot", {"type", "footprint", "height", "bounds", "motion"});
                readSe2Motion(r, robot["motion"], problem.se2Motion);
                r.keys(robot["bounds"], "robot.bounds", {"x", "y"});
                problem.footprint = r.polygon(r.require(robot, "footprint", "robot"), "robot.footprint");
                try
                {
                    // Only for its checks (at least 3 points, a simple polygon): a bad footprint is reported here
                    // with its key, not later by the checker that builds the prism.
                    validity::triangulatePolygon(problem.footprint);
                }
                catch (const std::exception &e)
                {
                    r.fail("robot.footprint", e.what());
                }
                problem.footprintHeight = r.number(robot, "height", "robot", 1.);
                // the footprint becomes a prism from z = 0 to this height
                if (!(problem.footprintHeight > 0.))
                    r.fail("robot.height",
                           "expected a positive height in metres, got " + std::to_string(problem.footprintHeight));
                // A map problem may leave the bounds out: the map's extent gives them later.
                if (mapBounds && !robot["bounds"])
                    return;
                const YAML::Node bounds = r.require(robot, "bounds", "robot");
                const auto x = r.coordinates(r.require(bounds, "x", "robot.bounds"), "robot.bounds.x", 2);
                const auto y = r.coordinates(r.require(bounds, "y", "robot.bounds"), "robot.bounds.y", 2);
                if (!(x[0] < x[1]) || !(y[0] < y[1]))
                    r.fail("robot.bounds", "expected [min, max] with min < max");
                problem.se2Bounds = {{x[0], x[1], y[0], y[1]}};
            }
        }  // namespace problem_file
    }      // namespace tools
}  // namespace michi
