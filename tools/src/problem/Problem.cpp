#include <michi/tools/problem/Problem.h>
#include <michi/validity/InputFile.h>

#include "ProblemYaml.h"

#include <michi/tools/problem/ExperienceQueries.h>
#include <michi/tools/problem/MoveItImport.h>

#include <algorithm>
#include <yaml-cpp/yaml.h>

#include <boost/filesystem.hpp>

#include <set>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        std::string printableLine(const std::string &text)
        {
            constexpr std::size_t MAX_BYTES = 2000;
            const auto *bytes = reinterpret_cast<const unsigned char *>(text.data());
            const std::size_t n = text.size();
            std::string out;
            std::size_t i = 0;
            while (i < n && out.size() < MAX_BYTES)
            {
                const unsigned char c = bytes[i];
                // a printable ASCII character, or a whole UTF-8 sequence (lead byte, then continuation bytes)
                std::size_t length = 0;
                if (c >= 0x20 && c < 0x7f)
                    length = 1;
                else if (c >= 0xc2 && c <= 0xdf)
                    length = 2;
                else if (c >= 0xe0 && c <= 0xef)
                    length = 3;
                else if (c >= 0xf0 && c <= 0xf4)
                    length = 4;
                bool whole = length > 0 && i + length <= n;
                for (std::size_t k = 1; whole && k < length; ++k)
                    whole = (bytes[i + k] & 0xc0) == 0x80;
                if (whole)
                {
                    out.append(text, i, length);
                    i += length;
                    continue;
                }
                static const char *hex = "0123456789ABCDEF";
                out += "\\x";
                out += hex[c >> 4];
                out += hex[c & 15];
                ++i;
            }
            if (i < n)
                out += " ... (" + std::to_string(n - i) + " more bytes)";
            return out;
        }

        validity::CollisionBodiesPtr Problem::bodies() const
        {
            if (kind == Kind::SE2)
                return std::make_shared<validity::PlanarRigidBody>(footprint, 0., footprintHeight);
            return std::make_shared<validity::RobotGroupBodies>(model, groupVariables, fixedValues);
        }

        std::size_t Problem::dimension() const
        {
            return kind == Kind::SE2 ? 3 : groupVariables.size();
        }

        std::vector<std::string> Problem::valueNames() const
        {
            if (kind == Kind::SE2)
                return {"x", "y", "yaw"};
            std::vector<std::string> names;
            for (int v : groupVariables)
                names.push_back(model->variableJoint(v).name);
            return names;
        }

        Problem loadProblem(const std::string &path)
        {
            using namespace problem_file;  // the Reader and the section readers (ProblemYaml.h)
            Reader r(path);
            const YAML::Node root = loadYaml(path);  // errors name the file (and line)
            if (!root.IsMap())
                r.fail("", "expected a mapping at the top level (name, robot, scene, start, goal, ...)");
            // dual_arm: read by DualArmProblem.cpp; experience: by ExperienceQueries.cpp
            static const std::set<std::string> known{"name",      "description", "robot",    "scene",     "start",
                                                     "goal",      "request",     "queries",  "planners",  "benchmark",
                                                     "collision", "extras",      "dual_arm", "experience"};
            for (const auto &kv : root)
                if (!known.count(kv.first.as<std::string>()))
                    r.fail(kv.first.as<std::string>(), "unknown top-level key");

            Problem problem;
            problem.file = path;
            problem.name = root["name"] ? r.text(root["name"], "name") : fs::path(path).stem().string();
            if (root["name"])
            {
                // The name becomes part of output file names (DIR/<name>-<planner>.path, DIR/<name>.db): a '/' or
                // a leading '.' would write outside DIR, a control character would break the logs.
                const std::string &n = problem.name;
                const bool control = std::any_of(n.begin(), n.end(),
                                                 [](char c)
                                                 {
                                                     return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
                                                 });
                if (n.empty() || n.size() > 128 || n.front() == '.' || n.find_first_of("/\\") != std::string::npos ||
                    control)
                    r.fail("name",
                           "expected 1 to 128 characters without '/', '\\' or control characters, not "
                           "starting with '.' (it names the output files)");
            }
            if (root["description"])
                problem.description = r.text(root["description"], "description");

            const YAML::Node robot = r.require(root, "robot", "");
            if (!robot.IsMap())
                r.fail("robot", "expected a mapping (urdf: ... or type: se2)");
            const std::string type = robot["type"] ? r.text(robot["type"], "robot.type") : "urdf";

            // the first MoveIt request (top-level request, else the first query's) may name the planned group
            YAML::Node firstRequest;
            std::string firstRequestKey;
            if (root["request"])
            {
                if (root["start"] || root["goal"])
                    r.fail("request", "give either request or start and goal, not both");
                firstRequest = root["request"];
                firstRequestKey = "request";
            }
            else if (root["queries"] && root["queries"].IsSequence())
                for (std::size_t i = 0; i < root["queries"].size() && firstRequestKey.empty(); ++i)
                    if (root["queries"][i].IsMap() && root["queries"][i]["request"])
                    {
                        firstRequest = root["queries"][i]["request"];
                        firstRequestKey = "queries[" + std::to_string(i) + "].request";
                    }
            MoveItRequest request;
            // Read before the robot: without robot.group, the request's group_name decides which joints are planned.
            if (!firstRequestKey.empty() && (type == "urdf" || type == "arm"))
                request = readMoveItRequest(r.path(firstRequest, firstRequestKey));

            const YAML::Node sceneNode = root["scene"];
            // A MovingAI map knows its own extent, so an SE2 robot's bounds may be left out; they are taken from the
            // map below.
            const bool gridMap = sceneNode && sceneNode.IsMap() && sceneNode["movingai"];
            if (type == "urdf" || type == "arm")
                readArm(r, robot, problem, request);
            else if (type == "se2")
                readSe2(r, robot, problem, gridMap);
            else
                r.fail("robot.type", "expected 'urdf' or 'se2', got '" + type + "'");

            GridMapInfo gridMapInfo;
            readScene(r, sceneNode, problem, gridMapInfo);
            if (problem.kind == Problem::Kind::SE2 && !robot["bounds"])
                problem.se2Bounds = gridMapInfo.bounds;  // readSe2 required them unless there is a grid map
            for (const auto &q : gridMapInfo.queries)
                for (const auto *values : {&q.start, &q.goal})
                    checkConfiguration(r, *values, "scene.movingai.scenarios", problem);

            std::vector<Query> requestQuery;
            if (root["request"])
            {
                requestQuery.push_back(readRequestQuery(r, root["request"], "request", problem, robot, true));
                requestQuery.back().key = "request";
            }
            if (root["queries"])
            {
                const YAML::Node q = root["queries"];
                if (!q.IsSequence() || q.size() == 0)
                    r.fail("queries", "expected a non-empty list of {start, goal} or {request}");
                for (std::size_t i = 0; i < q.size(); ++i)
                {
                    const std::string key = "queries[" + std::to_string(i) + "]";
                    if (q[i].IsMap() && q[i]["request"])
                    {
                        if (q[i]["start"] || q[i]["goal"])
                            r.fail(key, "give either request or start and goal, not both");
                        problem.queries.push_back(readRequestQuery(r, q[i]["request"], key + ".request", problem, robot,
                                                                   key + ".request" == firstRequestKey));
                        problem.queries.back().key = key + ".request";
                        continue;
                    }
                    problem.queries.push_back(
                        Query{readConfiguration(r, r.require(q[i], "start", key), key + ".start", problem),
                              readConfiguration(r, r.require(q[i], "goal", key), key + ".goal", problem), "", key});
                }
            }
            // Query order: the top-level request or start/goal is query 0, then the file's queries, then the map's
            // scenarios, so query 0 is what michi plan and the pictures use by default.
            problem.queries.insert(problem.queries.end(), gridMapInfo.queries.begin(), gridMapInfo.queries.end());
            if (!requestQuery.empty())
                problem.queries.insert(problem.queries.begin(), requestQuery.front());
            else if (root["start"] || root["goal"] || problem.queries.empty())
            {
                const auto start = readConfiguration(r, r.require(root, "start", ""), "start", problem);
                const auto goal = readConfiguration(r, r.require(root, "goal", ""), "goal", problem);
                problem.queries.insert(problem.queries.begin(), Query{start, goal, "", "start/goal"});
            }
            readPlanners(r, root["planners"], problem);
            readBenchmark(r, root["benchmark"], problem);
            readCollision(r, root["collision"], problem);
            problem.experience = readExperienceQueries(path, problem);  // ExperienceQueries.cpp
            return problem;
        }

        std::string queryEndKey(const Problem &problem, std::size_t query, const std::string &end)
        {
            // Query i is not queries[i] of the file when a top-level start and goal (or request) come first, and a
            // map scenario has no key of its own: a message must name what the user can find in the file.
            const std::string key = query < problem.queries.size() ? problem.queries[query].key : std::string();
            if (key == "start/goal")
                return end;
            if (key.empty())
                return "queries[" + std::to_string(query) + "]." + end;
            if (key == "request" || key.find(".request") != std::string::npos)
                return key;
            if (key == "scene.movingai.scenarios")  // the label names the scenario file's line
                return key + " (" + problem.queries[query].label + ")." + end;
            return key + "." + end;
        }
    }  // namespace tools
}  // namespace michi
