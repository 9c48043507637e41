#include "ProblemYaml.h"

#include <michi/tools/problem/MoveItImport.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace michi
{
    namespace tools
    {
        namespace problem_file
        {
            void checkConfiguration(const Reader &r, const std::vector<double> &values, const std::string &key,
                                    const Problem &problem, bool indexKeys)
            {
                if (problem.kind == Problem::Kind::ARM)
                    for (std::size_t i = 0; i < values.size(); ++i)
                    {
                        const auto &joint = problem.model->variableJoint(problem.groupVariables[i]);
                        // 1e-9 of slack: a value written at the limit with a few digits (or computed, pi/2) may
                        // round just past it.
                        if (joint.type != validity::RobotJoint::Type::CONTINUOUS &&
                            (values[i] < joint.lower - 1e-9 || values[i] > joint.upper + 1e-9))
                        {
                            std::ostringstream msg;
                            msg << "joint '" << joint.name << "' value " << values[i] << " outside its limits ["
                                << joint.lower << ", " << joint.upper << "]";
                            r.fail(indexKeys ? key + "[" + std::to_string(i) + "]" : key, msg.str());
                        }
                    }
                else
                {
                    const auto &b = problem.se2Bounds;
                    if (values[0] < b[0] || values[0] > b[1] || values[1] < b[2] || values[1] > b[3])
                        r.fail(key, "position outside robot.bounds");
                }
            }

            std::vector<double> readConfiguration(const Reader &r, const YAML::Node &n, const std::string &key,
                                                  const Problem &problem)
            {
                const auto values = r.numbers(n, key, problem.dimension());
                checkConfiguration(r, values, key, problem);
                return values;
            }

            Query readRequestQuery(const Reader &r, const YAML::Node &node, const std::string &key, Problem &problem,
                                   const YAML::Node &robot, bool first)
            {
                if (problem.kind != Problem::Kind::ARM)
                    r.fail(key, "a MoveIt request needs a urdf robot");
                const MoveItRequest request = readMoveItRequest(r.path(node, key));
                const Reader rr(request.file);
                // Without robot.group, the first request's group_name chose the planned group; every later request must
                // plan the same group, or its joint values would be read for the wrong joints.
                if (!robot["group"] && !request.groupName.empty() && request.groupName != problem.group)
                    rr.fail("group_name", "'" + request.groupName + "' differs from the planned group '" +
                                              problem.group + "' (the first request's)");
                const auto joints = problem.valueNames();
                Query query;
                query.start = jointValues(joints, request.startNames, request.startPositions, request.file,
                                          "start_state.joint_state.name");
                std::vector<std::string> goalNames;
                std::vector<double> goalValues;
                for (const auto &c : request.goal)
                {
                    goalNames.push_back(c.first);
                    goalValues.push_back(c.second);
                }
                query.goal =
                    jointValues(joints, goalNames, goalValues, request.file, "goal_constraints[0].joint_constraints");
                checkConfiguration(rr, query.start, "start_state.joint_state", problem, false);
                checkConfiguration(rr, query.goal, "goal_constraints[0].joint_constraints", problem, false);
                if (!first)
                    return query;
                // The first request's start also fixes the joints outside the group (the rest of the robot where the
                // request puts it), unless robot.fixed_joints names them; later requests' values for those joints are
                // not read.
                const YAML::Node fixed = robot["fixed_joints"];
                for (std::size_t i = 0; i < request.startNames.size(); ++i)
                {
                    const std::string &joint = request.startNames[i];
                    if (std::find(joints.begin(), joints.end(), joint) != joints.end() ||
                        (fixed && fixed.IsMap() && fixed[joint]))
                        continue;
                    int v = -1;
                    try
                    {
                        v = problem.model->variableIndex(joint);
                    }
                    catch (const std::out_of_range &)
                    {
                        continue;  // a fixed joint of the URDF or not a joint of this robot (virtual joints)
                    }
                    const auto &j = problem.model->variableJoint(v);
                    const double value = request.startPositions[i];
                    if (j.type != validity::RobotJoint::Type::CONTINUOUS &&
                        (value < j.lower - 1e-9 || value > j.upper + 1e-9))
                    {
                        std::ostringstream msg;
                        msg << "joint '" << joint << "' value " << value << " outside its limits [" << j.lower << ", "
                            << j.upper << "]";
                        rr.fail("start_state.joint_state", msg.str());
                    }
                    problem.fixedValues[v] = value;
                }
                // the request's values for mimic joints give way to the joints they follow, as on the robot
                problem.model->applyMimic(problem.fixedValues);
                return query;
            }
        }  // namespace problem_file
    }      // namespace tools
}  // namespace michi
