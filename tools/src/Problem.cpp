#include <michi/tools/Problem.h>

#include <michi/tools/ExperienceQueries.h>
#include <michi/tools/MoveItImport.h>
#include <michi/tools/MovingAiMap.h>

#include <yaml-cpp/yaml.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

namespace fs = boost::filesystem;
using michi::validity::Obstacle;
using michi::validity::Shape;

namespace michi
{
    namespace tools
    {
        namespace
        {
            /** Reads typed values out of a YAML tree and turns every mistake into a ProblemError naming the key. */
            class Reader
            {
            public:
                explicit Reader(std::string file) : file_(std::move(file))
                {
                }

                [[noreturn]] void fail(const std::string &key, const std::string &message) const
                {
                    throw ProblemError(file_, key, message);
                }

                YAML::Node require(const YAML::Node &map, const std::string &name, const std::string &key) const
                {
                    if (!map.IsMap())
                        fail(key, "expected a mapping");
                    const YAML::Node n = map[name];
                    if (!n)
                        fail(key.empty() ? name : key + "." + name, "missing (required)");
                    return n;
                }

                double number(const YAML::Node &n, const std::string &key) const
                {
                    if (!n.IsScalar())
                        fail(key, "expected a number");
                    const std::string text = n.Scalar();
                    // accept "pi", "-pi/2", "0.5*pi" as conveniences for joint values
                    try
                    {
                        return parseNumber(text);
                    }
                    catch (const std::exception &)
                    {
                        fail(key, "expected a number, got '" + text + "'");
                    }
                }

                double number(const YAML::Node &map, const std::string &name, const std::string &key,
                              double fallback) const
                {
                    const YAML::Node n = map[name];
                    return n ? number(n, key + "." + name) : fallback;
                }

                std::vector<double> numbers(const YAML::Node &n, const std::string &key, std::size_t size = 0) const
                {
                    if (!n.IsSequence())
                        fail(key, size ? "expected a list of " + std::to_string(size) + " numbers"
                                       : "expected a list of numbers");
                    if (size && n.size() != size)
                        fail(key, "expected " + std::to_string(size) + " numbers, got " + std::to_string(n.size()));
                    std::vector<double> values;
                    for (std::size_t i = 0; i < n.size(); ++i)
                        values.push_back(number(n[i], key + "[" + std::to_string(i) + "]"));
                    return values;
                }

                std::string text(const YAML::Node &n, const std::string &key) const
                {
                    if (!n.IsScalar())
                        fail(key, "expected a string");
                    return n.Scalar();
                }

                unsigned int count(const YAML::Node &n, const std::string &key) const
                {
                    const double v = number(n, key);
                    if (!(v >= 1.) || v != std::floor(v) || v > 1e9)
                        fail(key, "expected a positive integer");
                    return static_cast<unsigned int>(v);
                }

                bool flag(const YAML::Node &n, const std::string &key) const
                {
                    if (!n.IsScalar() || (n.Scalar() != "true" && n.Scalar() != "false"))
                        fail(key, "expected true or false");
                    return n.Scalar() == "true";
                }

                /** A path in the problem file, relative to the file's folder; must exist. */
                std::string path(const YAML::Node &n, const std::string &key) const
                {
                    const fs::path p = fs::path(text(n, key));
                    const fs::path full = p.is_absolute() ? p : fs::path(file_).parent_path() / p;
                    if (!fs::exists(full))
                        fail(key, "file '" + full.string() + "' does not exist");
                    return full.lexically_normal().string();
                }

                /** {xyz: [3], rpy: [3]} or {position: [3], orientation: [x, y, z, w]}. */
                Eigen::Isometry3d pose(const YAML::Node &n, const std::string &key) const
                {
                    if (!n.IsMap())
                        fail(key, "expected a pose {xyz: [x, y, z], rpy: [roll, pitch, yaw]}");
                    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
                    for (const char *name : {"xyz", "position"})
                        if (n[name])
                        {
                            const auto v = numbers(n[name], key + "." + name, 3);
                            t.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
                        }
                    if (n["rpy"])
                    {
                        const auto r = numbers(n["rpy"], key + ".rpy", 3);
                        t.linear() = (Eigen::AngleAxisd(r[2], Eigen::Vector3d::UnitZ()) *
                                      Eigen::AngleAxisd(r[1], Eigen::Vector3d::UnitY()) *
                                      Eigen::AngleAxisd(r[0], Eigen::Vector3d::UnitX()))
                                         .toRotationMatrix();
                    }
                    else if (n["orientation"])
                    {
                        const auto q = numbers(n["orientation"], key + ".orientation", 4);
                        const Eigen::Quaterniond quat(q[3], q[0], q[1], q[2]);
                        if (quat.norm() < 1e-9)
                            fail(key + ".orientation", "quaternion has zero norm");
                        t.linear() = quat.normalized().toRotationMatrix();
                    }
                    for (const auto &kv : n)
                    {
                        const std::string k = kv.first.as<std::string>();
                        if (k != "xyz" && k != "position" && k != "rpy" && k != "orientation")
                            fail(key + "." + k, "unknown pose key (expected xyz/rpy or position/orientation)");
                    }
                    return t;
                }

                std::vector<Eigen::Vector2d> polygon(const YAML::Node &n, const std::string &key) const
                {
                    if (!n.IsSequence() || n.size() < 3)
                        fail(key, "expected a list of at least 3 [x, y] points");
                    std::vector<Eigen::Vector2d> points;
                    for (std::size_t i = 0; i < n.size(); ++i)
                    {
                        const auto p = numbers(n[i], key + "[" + std::to_string(i) + "]", 2);
                        points.emplace_back(p[0], p[1]);
                    }
                    return points;
                }

                const std::string &file() const
                {
                    return file_;
                }

                static double parseNumber(std::string text)
                {
                    text.erase(std::remove_if(text.begin(), text.end(), ::isspace), text.end());
                    double sign = 1.;
                    if (!text.empty() && (text[0] == '-' || text[0] == '+'))
                    {
                        sign = text[0] == '-' ? -1. : 1.;
                        text = text.substr(1);
                    }
                    const auto pi = text.find("pi");
                    if (pi == std::string::npos)
                    {
                        std::size_t used = 0;
                        const double v = std::stod(text, &used);
                        if (used != text.size() || !std::isfinite(v))
                            throw std::invalid_argument(text);
                        return sign * v;
                    }
                    // forms: pi, k*pi, pi/d, k*pi/d
                    double factor = 1., divisor = 1.;
                    const std::string before = text.substr(0, pi), after = text.substr(pi + 2);
                    if (!before.empty())
                    {
                        if (before.back() != '*')
                            throw std::invalid_argument(text);
                        factor = parseNumber(before.substr(0, before.size() - 1));
                    }
                    if (!after.empty())
                    {
                        if (after[0] != '/')
                            throw std::invalid_argument(text);
                        divisor = parseNumber(after.substr(1));
                        if (divisor == 0.)
                            throw std::invalid_argument(text);
                    }
                    return sign * factor * M_PI / divisor;
                }

                /** Every key of mapping \e n must be one of \e allowed (a misspelt key is an error, not ignored). */
                void keys(const YAML::Node &n, const std::string &key, const std::set<std::string> &allowed) const
                {
                    if (!n || !n.IsMap())  // absent (or not a mapping: the caller's own check reports that)
                        return;
                    for (const auto &kv : n)
                    {
                        const std::string k = kv.first.as<std::string>();
                        if (!allowed.count(k))
                        {
                            std::string list;
                            for (const auto &a : allowed)
                                list += (list.empty() ? "" : ", ") + a;
                            fail(key.empty() ? k : key + "." + k, "unknown key (expected one of " + list + ")");
                        }
                    }
                }

            private:
                std::string file_;
            };

            std::shared_ptr<const Shape> readShape(const Reader &r, const YAML::Node &o, const std::string &key)
            {
                int kinds = 0;
                for (const char *kind : {"box", "sphere", "cylinder", "capsule", "polygon", "mesh"})
                    kinds += o[kind] ? 1 : 0;
                if (kinds > 1)
                    r.fail(key, "more than one shape given (one of box, sphere, cylinder, capsule, polygon, mesh)");
                for (const char *kind : {"cylinder", "capsule"})
                    r.keys(o[kind], key + "." + kind, {"radius", "length"});
                r.keys(o["polygon"], key + ".polygon", {"points", "z"});
                r.keys(o["mesh"], key + ".mesh", {"file", "scale"});
                try
                {
                    if (o["box"])
                    {
                        const auto s = r.numbers(o["box"], key + ".box", 3);
                        return Shape::box(Eigen::Vector3d(s[0], s[1], s[2]));
                    }
                    if (o["sphere"])
                        return Shape::sphere(r.number(o["sphere"], key + ".sphere"));
                    for (const char *kind : {"cylinder", "capsule"})
                        if (o[kind])
                        {
                            const std::string k = key + "." + kind;
                            const double radius = r.number(r.require(o[kind], "radius", k), k + ".radius");
                            const double length = r.number(r.require(o[kind], "length", k), k + ".length");
                            return std::string(kind) == "cylinder" ? Shape::cylinder(radius, length)
                                                                   : Shape::capsule(radius, length);
                        }
                    if (o["polygon"])
                    {
                        const std::string k = key + ".polygon";
                        const YAML::Node p = o["polygon"];
                        const auto points = r.polygon(r.require(p, "points", k), k + ".points");
                        std::vector<double> z{-0.5, 0.5};
                        if (p["z"])
                            z = r.numbers(p["z"], k + ".z", 2);
                        return Shape::prism(points, z[0], z[1]);
                    }
                    if (o["mesh"])
                    {
                        const std::string k = key + ".mesh";
                        const std::string file = r.path(r.require(o["mesh"], "file", k), k + ".file");
                        Eigen::Vector3d scale = Eigen::Vector3d::Ones();
                        if (o["mesh"]["scale"])
                        {
                            const auto s = r.numbers(o["mesh"]["scale"], k + ".scale", 3);
                            scale = Eigen::Vector3d(s[0], s[1], s[2]);
                        }
                        return Shape::meshFromFile(file, scale);
                    }
                }
                catch (const ProblemError &)
                {
                    throw;
                }
                catch (const std::exception &e)
                {
                    r.fail(key, e.what());
                }
                r.fail(key, "expected one of box, sphere, cylinder, capsule, polygon, mesh");
            }

            /** What scene.movingai adds besides obstacles: the map's extent and the scenario queries. */
            struct GridMapInfo
            {
                bool present{false};
                std::array<double, 4> bounds{{0., 1., 0., 1.}};  ///< x min, x max, y min, y max
                std::vector<Query> queries;
            };

            void readMoveItSceneKey(const Reader &r, const YAML::Node &node, Problem &problem)
            {
                const std::string path = r.path(node, "scene.moveit");
                const MoveItScene moveit = readMoveItScene(path, problem.model.get());  // errors name the scene file
                for (auto &o : moveit.obstacles)
                {
                    const std::string name = o.name;
                    try
                    {
                        problem.scene->add(std::move(o));
                    }
                    catch (const std::exception &e)
                    {
                        r.fail("scene.moveit", "object '" + name + "': " + e.what());
                    }
                }
                for (const auto &pair : moveit.allowedCollisions)
                    problem.model->allowCollision(pair.first, pair.second);  // robot links, checked by the reader
            }

            void readMovingAiKey(const Reader &r, const YAML::Node &node, Problem &problem, GridMapInfo &info)
            {
                const std::string key = "scene.movingai";
                if (!node.IsMap())
                    r.fail(key, "expected a mapping {map: FILE.map, resolution, height, origin, scenarios}");
                for (const auto &kv : node)
                {
                    const std::string k = kv.first.as<std::string>();
                    if (k != "map" && k != "resolution" && k != "height" && k != "origin" && k != "scenarios")
                        r.fail(key + "." + k, "unknown key (expected map, resolution, height, origin, scenarios)");
                }
                const std::string file = r.path(r.require(node, "map", key), key + ".map");
                const double resolution = r.number(node, "resolution", key, 1.);
                if (!(resolution > 0.))
                    r.fail(key + ".resolution", "expected a positive number (metres per cell)");
                const double height = r.number(node, "height", key, 1.);
                if (!(height > 0.))
                    r.fail(key + ".height", "expected a positive number (metres)");
                Eigen::Vector2d origin = Eigen::Vector2d::Zero();
                if (node["origin"])
                {
                    const auto o = r.numbers(node["origin"], key + ".origin", 2);
                    origin = Eigen::Vector2d(o[0], o[1]);
                }
                const MovingAiMap map = readMovingAiMap(file);  // errors name the map file
                for (auto &o : movingAiObstacles(map, resolution, origin, height))
                {
                    const std::string name = o.name;
                    try
                    {
                        problem.scene->add(std::move(o));
                    }
                    catch (const std::exception &e)
                    {
                        r.fail(key, "cells '" + name + "': " + e.what());
                    }
                }
                info.present = true;
                info.bounds = {{origin.x(), origin.x() + map.width * resolution, origin.y(),
                                origin.y() + map.height * resolution}};

                const YAML::Node scen = node["scenarios"];
                if (!scen)
                    return;
                const std::string sk = key + ".scenarios";
                if (problem.kind != Problem::Kind::SE2)
                    r.fail(sk, "scenarios become SE2 queries: needs robot.type se2");
                if (!scen.IsMap())
                    r.fail(sk, "expected a mapping {file: FILE.scen, bucket, count}");
                for (const auto &kv : scen)
                {
                    const std::string k = kv.first.as<std::string>();
                    if (k != "file" && k != "bucket" && k != "count")
                        r.fail(sk + "." + k, "unknown key (expected file, bucket, count)");
                }
                const std::string scenFile = r.path(r.require(scen, "file", sk), sk + ".file");
                int bucket = -1;
                if (scen["bucket"])
                {
                    const double b = r.number(scen["bucket"], sk + ".bucket");
                    if (b < 0. || b != std::floor(b))
                        r.fail(sk + ".bucket", "expected a bucket number (0, 1, ...)");
                    bucket = static_cast<int>(b);
                }
                const unsigned int count =
                    scen["count"] ? r.count(scen["count"], sk + ".count") : std::numeric_limits<unsigned int>::max();
                for (const auto &s : readMovingAiScenarios(scenFile))
                {
                    if (bucket >= 0 && s.bucket != bucket)
                        continue;
                    if (info.queries.size() >= count)
                        break;
                    const std::string line = "line " + std::to_string(s.line);
                    if (s.mapWidth != map.width || s.mapHeight != map.height)
                        throw ProblemError(scenFile, line,
                                           "map size " + std::to_string(s.mapWidth) + " x " +
                                               std::to_string(s.mapHeight) + ", but '" + file + "' is " +
                                               std::to_string(map.width) + " x " + std::to_string(map.height));
                    for (const auto &cell : {std::make_pair(s.startX, s.startY), std::make_pair(s.goalX, s.goalY)})
                        if (cell.first < 0 || cell.first >= map.width || cell.second < 0 || cell.second >= map.height)
                            throw ProblemError(scenFile, line,
                                               "cell (" + std::to_string(cell.first) + ", " +
                                                   std::to_string(cell.second) + ") outside the map");
                    const Eigen::Vector2d a = movingAiCellCentre(map, s.startX, s.startY, resolution, origin);
                    const Eigen::Vector2d b = movingAiCellCentre(map, s.goalX, s.goalY, resolution, origin);
                    info.queries.push_back(Query{{a.x(), a.y(), 0.}, {b.x(), b.y(), 0.}});
                }
                if (info.queries.empty())
                    r.fail(sk, "no scenario in '" + scenFile + "'" +
                                   (bucket >= 0 ? " with bucket " + std::to_string(bucket) : std::string()));
            }

            void readScene(const Reader &r, const YAML::Node &scene, Problem &problem, GridMapInfo &gridMap)
            {
                problem.scene = std::make_shared<validity::Scene>();
                if (!scene)
                    return;
                if (!scene.IsMap())
                    r.fail("scene", "expected a mapping with obstacles, map, moveit and/or movingai");
                if (const YAML::Node list = scene["obstacles"])
                {
                    if (!list.IsSequence())
                        r.fail("scene.obstacles", "expected a list");
                    std::set<std::string> names;
                    for (std::size_t i = 0; i < list.size(); ++i)
                    {
                        const std::string key = "scene.obstacles[" + std::to_string(i) + "]";
                        const YAML::Node o = list[i];
                        if (!o.IsMap())
                            r.fail(key, "expected a mapping");
                        r.keys(
                            o, key,
                            {"name", "box", "sphere", "cylinder", "capsule", "polygon", "mesh", "pose", "trajectory"});
                        Obstacle obstacle;
                        obstacle.name = o["name"] ? r.text(o["name"], key + ".name") : "obstacle" + std::to_string(i);
                        if (!names.insert(obstacle.name).second)
                            r.fail(key + ".name", "duplicate obstacle name '" + obstacle.name + "'");
                        obstacle.shape = readShape(r, o, key);
                        if (o["pose"])
                            obstacle.pose = r.pose(o["pose"], key + ".pose");
                        if (const YAML::Node traj = o["trajectory"])
                        {
                            if (!traj.IsSequence() || traj.size() < 1)
                                r.fail(key + ".trajectory", "expected a list of {t, xyz, rpy} key frames");
                            for (std::size_t k = 0; k < traj.size(); ++k)
                            {
                                const std::string tk = key + ".trajectory[" + std::to_string(k) + "]";
                                validity::TimedPose tp;
                                tp.time = r.number(r.require(traj[k], "t", tk), tk + ".t");
                                YAML::Node poseNode = YAML::Clone(traj[k]);
                                poseNode.remove("t");
                                tp.pose = r.pose(poseNode, tk);
                                obstacle.trajectory.push_back(tp);
                            }
                        }
                        problem.scene->add(std::move(obstacle));
                    }
                }
                if (const YAML::Node map = scene["map"])
                {
                    const std::string key = "scene.map";
                    r.keys(map, key, {"pgm", "resolution", "origin", "height", "threshold"});
                    const std::string pgm = r.path(r.require(map, "pgm", key), key + ".pgm");
                    const double resolution = r.number(r.require(map, "resolution", key), key + ".resolution");
                    if (!(resolution > 0.))
                        r.fail(key + ".resolution", "expected a positive number (metres per cell)");
                    Eigen::Vector2d origin = Eigen::Vector2d::Zero();
                    if (map["origin"])
                    {
                        const auto o = r.numbers(map["origin"], key + ".origin", 2);
                        origin = Eigen::Vector2d(o[0], o[1]);
                    }
                    const double height = r.number(map, "height", key, 1.);
                    const double threshold = r.number(map, "threshold", key, 0.5);
                    try
                    {
                        for (auto &o : validity::occupancyObstacles(pgm, resolution, origin, height, threshold))
                            problem.scene->add(std::move(o));
                    }
                    catch (const std::exception &e)
                    {
                        r.fail(key + ".pgm", e.what());
                    }
                }
                if (const YAML::Node moveit = scene["moveit"])
                    readMoveItSceneKey(r, moveit, problem);
                if (const YAML::Node movingai = scene["movingai"])
                    readMovingAiKey(r, movingai, problem, gridMap);
                for (const auto &kv : scene)
                {
                    const std::string k = kv.first.as<std::string>();
                    if (k != "obstacles" && k != "map" && k != "moveit" && k != "movingai")
                        r.fail("scene." + k, "unknown key (expected obstacles, map, moveit, movingai)");
                }
            }

            /** \e request: the problem's first MoveIt request (empty when none); its group_name is the planned
                group when robot.group is not given. */
            void readJMapSettings(const Reader &r, const YAML::Node &n, const std::string &key,
                                  validity::JMapCheckerSettings &settings)
            {
                if (!n.IsMap())
                    r.fail(key, "expected a mapping (mode, slices, tiles, tolerance, fallback_band)");
                r.keys(n, key, {"mode", "slices", "tiles", "tolerance", "fallback_band"});
                if (n["mode"])
                {
                    const std::string mode = r.text(n["mode"], key + ".mode");
                    if (mode == "conservative")
                        settings.mode = validity::JMapCheckerSettings::Mode::CONSERVATIVE;
                    else if (mode == "exact_fallback")
                        settings.mode = validity::JMapCheckerSettings::Mode::EXACT_FALLBACK;
                    else
                        r.fail(key + ".mode", "expected conservative or exact_fallback, got '" + mode + "'");
                }
                if (n["slices"])
                    settings.map.slices = static_cast<int>(r.count(n["slices"], key + ".slices"));
                if (n["tiles"])
                    settings.tiles = static_cast<int>(r.count(n["tiles"], key + ".tiles"));
                if (settings.tiles > settings.map.slices)
                    r.fail(key + ".tiles", "must not exceed slices");
                settings.map.tolerance = r.number(n, "tolerance", key, settings.map.tolerance);
                if (!(settings.map.tolerance > 0.))
                    r.fail(key + ".tolerance", "expected a positive number of radians");
                settings.fallbackBand = r.number(n, "fallback_band", key, settings.fallbackBand);
                if (!(settings.fallbackBand >= 0.))
                    r.fail(key + ".fallback_band", "expected a non-negative number of radians");
            }

            void readArm(const Reader &r, const YAML::Node &robot, Problem &problem, const MoveItRequest &request)
            {
                r.keys(robot, "robot",
                       {"type", "urdf", "srdf", "base_pose", "groups", "group", "fixed_joints", "allowed_collisions"});
                const std::string urdf = r.path(r.require(robot, "urdf", "robot"), "robot.urdf");
                problem.model = validity::RobotModel::fromUrdfFile(urdf);  // UrdfError names the URDF
                const auto &model = *problem.model;
                if (model.variableCount() == 0)
                    r.fail("robot.urdf", "robot '" + model.name() + "' has no movable joint");
                if (robot["base_pose"])
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
                    problem.groups["all"] = model.variableNames();
                    problem.group = "all";
                }
                for (const auto &joint : problem.groups[problem.group])
                    problem.groupVariables.push_back(model.variableIndex(joint));

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
                        problem.fixedValues[v] = r.number(kv.second, key);
                        const auto &j = model.variableJoint(v);
                        if (j.type != validity::RobotJoint::Type::CONTINUOUS &&
                            (problem.fixedValues[v] < j.lower - 1e-9 || problem.fixedValues[v] > j.upper + 1e-9))
                            r.fail(key, "value outside the joint's limits [" + std::to_string(j.lower) + ", " +
                                            std::to_string(j.upper) + "]");
                    }
                }
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

            /** \e mapBounds: robot.bounds may be left out (the bounds of the scene's grid map are used then). */
            void readSe2(const Reader &r, const YAML::Node &robot, Problem &problem, bool mapBounds)
            {
                problem.kind = Problem::Kind::SE2;
                r.keys(robot, "robot", {"type", "footprint", "height", "bounds", "motion"});
                readSe2Motion(r, robot["motion"], problem.se2Motion);
                r.keys(robot["bounds"], "robot.bounds", {"x", "y"});
                problem.footprint = r.polygon(r.require(robot, "footprint", "robot"), "robot.footprint");
                try
                {
                    validity::triangulatePolygon(problem.footprint);
                }
                catch (const std::exception &e)
                {
                    r.fail("robot.footprint", e.what());
                }
                problem.footprintHeight = r.number(robot, "height", "robot", 1.);
                if (mapBounds && !robot["bounds"])
                    return;
                const YAML::Node bounds = r.require(robot, "bounds", "robot");
                const auto x = r.numbers(r.require(bounds, "x", "robot.bounds"), "robot.bounds.x", 2);
                const auto y = r.numbers(r.require(bounds, "y", "robot.bounds"), "robot.bounds.y", 2);
                if (!(x[0] < x[1]) || !(y[0] < y[1]))
                    r.fail("robot.bounds", "expected [min, max] with min < max");
                problem.se2Bounds = {{x[0], x[1], y[0], y[1]}};
            }

            /** Joint limits (ARM) or bounds (SE2) of a configuration; \e indexKeys: name value i "key[i]". */
            void checkConfiguration(const Reader &r, const std::vector<double> &values, const std::string &key,
                                    const Problem &problem, bool indexKeys = true)
            {
                if (problem.kind == Problem::Kind::ARM)
                    for (std::size_t i = 0; i < values.size(); ++i)
                    {
                        const auto &joint = problem.model->variableJoint(problem.groupVariables[i]);
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

            /** The start and goal of a MoveIt MotionPlanRequest for the planned group. \e first: the problem's
                first request, whose start state also fixes the robot's other joints it names (unless
                robot.fixed_joints gives them). */
            Query readRequestQuery(const Reader &r, const YAML::Node &node, const std::string &key, Problem &problem,
                                   const YAML::Node &robot, bool first)
            {
                if (problem.kind != Problem::Kind::ARM)
                    r.fail(key, "a MoveIt request needs a urdf robot");
                const MoveItRequest request = readMoveItRequest(r.path(node, key));
                const Reader rr(request.file);
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
                return query;
            }

            void readPlanners(const Reader &r, const YAML::Node &list, Problem &problem)
            {
                if (!list)
                {
                    for (const char *name :
                         {"geometric::RRTConnect", "geometric::PRM", "geometric::RRTstar", "geometric::BITstar"})
                        problem.planners.push_back(PlannerSpec{name, {}});
                    return;
                }
                if (!list.IsSequence() || list.size() == 0)
                    r.fail("planners", "expected a non-empty list of planner names or {name, params}");
                for (std::size_t i = 0; i < list.size(); ++i)
                {
                    const std::string key = "planners[" + std::to_string(i) + "]";
                    PlannerSpec spec;
                    if (list[i].IsScalar())
                        spec.name = list[i].Scalar();
                    else if (list[i].IsMap())
                    {
                        spec.name = r.text(r.require(list[i], "name", key), key + ".name");
                        if (const YAML::Node params = list[i]["params"])
                        {
                            if (!params.IsMap())
                                r.fail(key + ".params", "expected a mapping of parameter name to value");
                            for (const auto &kv : params)
                                spec.params[kv.first.as<std::string>()] =
                                    r.text(kv.second, key + ".params." + kv.first.as<std::string>());
                        }
                    }
                    else
                        r.fail(key, "expected a planner name or {name, params}");
                    problem.planners.push_back(spec);
                }
            }

            void readBenchmark(const Reader &r, const YAML::Node &b, Problem &problem)
            {
                if (!b)
                    return;
                if (!b.IsMap())
                    r.fail("benchmark", "expected a mapping (time_limit, runs, memory_limit, seed, simplify)");
                auto &s = problem.benchmark;
                for (const auto &kv : b)
                {
                    const std::string k = kv.first.as<std::string>(), key = "benchmark." + k;
                    if (k == "time_limit")
                    {
                        s.timeLimit = r.number(kv.second, key);
                        if (!(s.timeLimit > 0.))
                            r.fail(key, "expected a positive number of seconds");
                    }
                    else if (k == "memory_limit")
                    {
                        s.memoryLimit = r.number(kv.second, key);
                        if (!(s.memoryLimit > 0.))
                            r.fail(key, "expected a positive number of megabytes");
                    }
                    else if (k == "runs")
                        s.runs = r.count(kv.second, key);
                    else if (k == "seed")
                        s.seed = r.count(kv.second, key);
                    else if (k == "simplify")
                        s.simplify = r.flag(kv.second, key);
                    else
                        r.fail(key, "unknown key (expected time_limit, runs, memory_limit, seed, simplify)");
                }
            }
        }  // namespace

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
            Reader r(path);
            if (!fs::is_regular_file(path))
                r.fail("", "no such problem file");
            YAML::Node root;
            try
            {
                root = YAML::LoadFile(path);
            }
            catch (const YAML::Exception &e)
            {
                r.fail("", "not valid YAML (line " + std::to_string(e.mark.line + 1) + ", column " +
                               std::to_string(e.mark.column + 1) + "): " + e.msg);
            }
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
            if (!firstRequestKey.empty() && (type == "urdf" || type == "arm"))
                request = readMoveItRequest(r.path(firstRequest, firstRequestKey));

            const YAML::Node sceneNode = root["scene"];
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
                requestQuery.push_back(readRequestQuery(r, root["request"], "request", problem, robot, true));
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
                        continue;
                    }
                    problem.queries.push_back(
                        Query{readConfiguration(r, r.require(q[i], "start", key), key + ".start", problem),
                              readConfiguration(r, r.require(q[i], "goal", key), key + ".goal", problem)});
                }
            }
            problem.queries.insert(problem.queries.end(), gridMapInfo.queries.begin(), gridMapInfo.queries.end());
            if (!requestQuery.empty())
                problem.queries.insert(problem.queries.begin(), requestQuery.front());
            else if (root["start"] || root["goal"] || problem.queries.empty())
            {
                const auto start = readConfiguration(r, r.require(root, "start", ""), "start", problem);
                const auto goal = readConfiguration(r, r.require(root, "goal", ""), "goal", problem);
                problem.queries.insert(problem.queries.begin(), Query{start, goal});
            }
            readPlanners(r, root["planners"], problem);
            readBenchmark(r, root["benchmark"], problem);
            if (const YAML::Node c = root["collision"])
            {
                if (!c.IsMap())
                    r.fail("collision", "expected a mapping (motion_validator, max_step, valid_segment_fraction)");
                for (const auto &kv : c)
                {
                    const std::string k = kv.first.as<std::string>(), key = "collision." + k;
                    if (k == "valid_segment_fraction")
                    {
                        problem.validSegmentFraction = r.number(kv.second, key);
                        if (problem.validSegmentFraction <= 0. || problem.validSegmentFraction >= 1.)
                            r.fail(key, "expected a number in (0, 1)");
                    }
                    else if (k == "max_step")
                    {
                        problem.maxStep = r.number(kv.second, key);
                        if (!(problem.maxStep > 0.))
                            r.fail(key, "expected a positive number of metres");
                    }
                    else if (k == "motion_validator")
                    {
                        problem.motionValidator = r.text(kv.second, key);
                        if (problem.motionValidator != "workspace" && problem.motionValidator != "conservative" &&
                            problem.motionValidator != "discrete")
                            r.fail(key, "expected workspace, conservative or discrete, got '" +
                                            problem.motionValidator + "'");
                    }
                    else if (k == "checker")
                    {
                        problem.checker = r.text(kv.second, key);
                        if (problem.checker != "fcl" && problem.checker != "jmap")
                            r.fail(key, "expected fcl or jmap, got '" + problem.checker + "'");
                    }
                    else if (k == "jmap")
                        readJMapSettings(r, kv.second, key, problem.jmap);
                    else
                        r.fail(key,
                               "unknown key (expected checker, jmap, motion_validator, max_step, "
                               "valid_segment_fraction)");
                }
            }
            problem.experience = readExperienceQueries(path, problem);  // ExperienceQueries.cpp
            return problem;
        }
    }  // namespace tools
}  // namespace michi
