#include "ProblemYaml.h"

#include <michi/tools/problem/MoveItImport.h>
#include <michi/tools/problem/MovingAiMap.h>

#include <boost/filesystem/path.hpp>

#include <cmath>
#include <limits>
#include <set>

using michi::validity::Obstacle;
using michi::validity::Shape;

namespace michi
{
    namespace tools
    {
        namespace problem_file
        {
            namespace
            {
                std::shared_ptr<const Shape> readShape(const Reader &r, const YAML::Node &o, const std::string &key)
                {
                    int kinds = 0;
                    for (const char *kind : {"box", "sphere", "cylinder", "capsule", "polygon", "mesh"})
                        kinds += o[kind] ? 1 : 0;
                    // Two shapes in one obstacle are refused, not resolved by whichever the code reads first.
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
                            const auto s = r.coordinates(o["box"], key + ".box", 3);
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
                                z = r.coordinates(p["z"], k + ".z", 2);
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
                    // Errors already naming file and key pass through; the others (a bad size, an unreadable mesh) get
                    // this key.
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

                void readMoveItSceneKey(const Reader &r, const YAML::Node &node, Problem &problem)
                {
                    // A robot model is passed so that objects in its root link's frame can be placed and the
                    // allowed-collision matrix can name its links.
                    const std::string path = r.path(node, "scene.moveit");
                    const MoveItScene moveit =
                        readMoveItScene(path, problem.model.get());  // errors name the scene file
                    try
                    {
                        problem.scene->add(moveit.obstacles);  // one broad-phase build; names the bad object
                    }
                    catch (const std::exception &e)
                    {
                        r.fail("scene.moveit", e.what());
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
                    if (!(resolution >= MIN_MAP_RESOLUTION && resolution <= MAX_MAP_RESOLUTION))
                        r.fail(key + ".resolution", MAP_RESOLUTION_RANGE);
                    const double height = r.number(node, "height", key, 1.);
                    if (!(height > 0.))
                        r.fail(key + ".height", "expected a positive number (metres)");
                    Eigen::Vector2d origin = Eigen::Vector2d::Zero();
                    if (node["origin"])
                    {
                        const auto o = r.coordinates(node["origin"], key + ".origin", 2);
                        origin = Eigen::Vector2d(o[0], o[1]);
                    }
                    const MovingAiMap map = readMovingAiMap(file);  // errors name the map file
                    try
                    {
                        problem.scene->add(movingAiObstacles(map, resolution, origin, height));
                    }
                    catch (const std::exception &e)
                    {
                        r.fail(key, e.what());
                    }
                    problem.grid.mapResolution = resolution;  // grid checker cells aligned with the map's
                    problem.grid.origin = origin;
                    problem.scene->setGridCellSize(resolution);
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
                        if (k != "file" && k != "bucket" && k != "buckets" && k != "count")
                            r.fail(sk + "." + k, "unknown key (expected file, bucket, buckets, count)");
                    }
                    const std::string scenFile = r.path(r.require(scen, "file", sk), sk + ".file");
                    int bucket = -1, lastBucket = -1;
                    auto bucketNumber = [&](const YAML::Node &n, const std::string &k)
                    {
                        // The bounds check comes before the cast: converting a double out of int's range is undefined
                        // behaviour.
                        const double b = r.number(n, k);
                        // MovingAI buckets are path lengths / 4: a few thousand at most; a cast of 2^31 would wrap
                        if (b < 0. || b != std::floor(b) || b > 1e6)
                            r.fail(k, "expected a bucket number (0, 1, ... 1000000)");
                        return static_cast<int>(b);
                    };
                    if (scen["bucket"] && scen["buckets"])
                        r.fail(sk + ".buckets", "give bucket or buckets, not both");
                    if (scen["bucket"])
                        bucket = lastBucket = bucketNumber(scen["bucket"], sk + ".bucket");
                    if (const YAML::Node range = scen["buckets"])
                    {
                        if (!range.IsSequence() || range.size() != 2)
                            r.fail(sk + ".buckets", "expected [first, last] (bucket numbers, inclusive)");
                        bucket = bucketNumber(range[0], sk + ".buckets[0]");
                        lastBucket = bucketNumber(range[1], sk + ".buckets[1]");
                        if (lastBucket < bucket)
                            r.fail(sk + ".buckets", "expected first <= last");
                    }
                    const unsigned int count = scen["count"] ? r.count(scen["count"], sk + ".count")
                                                             : std::numeric_limits<unsigned int>::max();
                    for (const auto &s : readMovingAiScenarios(scenFile))
                    {
                        if (bucket >= 0 && (s.bucket < bucket || s.bucket > lastBucket))
                            continue;
                        if (info.queries.size() >= count)
                            break;
                        const std::string line = "line " + std::to_string(s.line);
                        // A .scen file written for another map would put starts and goals in the wrong cells.
                        if (s.mapWidth != map.width || s.mapHeight != map.height)
                            throw ProblemError(scenFile, line,
                                               "map size " + std::to_string(s.mapWidth) + " x " +
                                                   std::to_string(s.mapHeight) + ", but '" + file + "' is " +
                                                   std::to_string(map.width) + " x " + std::to_string(map.height));
                        for (const auto &cell : {std::make_pair(s.startX, s.startY), std::make_pair(s.goalX, s.goalY)})
                            if (cell.first < 0 || cell.first >= map.width || cell.second < 0 ||
                                cell.second >= map.height)
                                throw ProblemError(scenFile, line,
                                                   "cell (" + std::to_string(cell.first) + ", " +
                                                       std::to_string(cell.second) + ") outside the map");
                        const Eigen::Vector2d a = movingAiCellCentre(map, s.startX, s.startY, resolution, origin);
                        const Eigen::Vector2d b = movingAiCellCentre(map, s.goalX, s.goalY, resolution, origin);
                        info.queries.push_back(
                            // MovingAI scenarios give cells only: start and goal face yaw 0, at their cells' centres.
                            Query{{a.x(), a.y(), 0.},
                                  {b.x(), b.y(), 0.},
                                  boost::filesystem::path(scenFile).filename().string() + " " + line,
                                  "scene.movingai.scenarios"});
                    }
                    if (info.queries.empty())
                        r.fail(sk, "no scenario in '" + scenFile + "'" +
                                       (bucket >= 0 ? " with bucket " + std::to_string(bucket) +
                                                          (lastBucket > bucket ? "-" + std::to_string(lastBucket) : "")
                                                    : std::string()));
                }
            }  // namespace

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
                    std::vector<Obstacle> listed;
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
                                // Reader::pose() rejects keys other than the pose's own, so the key frame's time is
                                // taken off first.
                                poseNode.remove("t");
                                tp.pose = r.pose(poseNode, tk);
                                obstacle.trajectory.push_back(tp);
                            }
                        }
                        listed.push_back(std::move(obstacle));
                    }
                    // One broad-phase build for the whole list (one per obstacle made a 23,000-box scene take
                    // minutes). Only when the list is refused is each obstacle tried alone, to name the bad one.
                    try
                    {
                        problem.scene->add(listed);
                    }
                    catch (const std::exception &refused)
                    {
                        const std::string why = refused.what();
                        validity::Scene probe;
                        for (std::size_t i = 0; i < listed.size(); ++i)
                        {
                            try
                            {
                                probe.add(listed[i]);
                            }
                            catch (const std::exception &e)
                            {
                                r.fail("scene.obstacles[" + std::to_string(i) + "]", e.what());
                            }
                        }
                        r.fail("scene.obstacles", why);  // refused as a list only: still named by the file
                    }
                }
                if (const YAML::Node map = scene["map"])
                {
                    const std::string key = "scene.map";
                    r.keys(map, key, {"pgm", "ros", "resolution", "origin", "height", "threshold"});
                    if (!map.IsMap())
                        r.fail(key, "expected a mapping (pgm or ros, ...)");
                    if (static_cast<bool>(map["pgm"]) == static_cast<bool>(map["ros"]))
                        r.fail(key, "expected exactly one of pgm (an image) and ros (a ROS map_server YAML file)");
                    const double height = r.number(map, "height", key, 1.);
                    if (!(height > 0.))
                        r.fail(key + ".height", "expected a positive number (metres)");
                    if (map["ros"])
                    {
                        // the map file gives the image, resolution, origin and thresholds
                        for (const char *k : {"resolution", "origin", "threshold"})
                            if (map[k])
                                r.fail(key + "." + k, "comes from the ROS map file (scene.map.ros); remove it here");
                        const std::string file = r.path(map["ros"], key + ".ros");
                        const RosMap ros = readRosMap(file, height);
                        try
                        {
                            problem.scene->add(ros.obstacles);
                        }
                        catch (const std::exception &e)
                        {
                            r.fail(key + ".ros", e.what());
                        }
                        problem.scene->setGridCellSize(ros.resolution);  // turned or not, gaps are whole cells wide
                        // A rotated map's cells do not line up with the x-y axes: the grid checker then keeps cells of
                        // its own.
                        if (ros.yaw == 0.)
                        {
                            problem.grid.mapResolution = ros.resolution;  // grid checker cells aligned with the map's
                            problem.grid.origin = ros.origin;
                        }
                    }
                    else
                    {
                        const std::string pgm = r.path(map["pgm"], key + ".pgm");
                        const double resolution = r.number(r.require(map, "resolution", key), key + ".resolution");
                        if (!(resolution >= MIN_MAP_RESOLUTION && resolution <= MAX_MAP_RESOLUTION))
                            r.fail(key + ".resolution", MAP_RESOLUTION_RANGE);
                        Eigen::Vector2d origin = Eigen::Vector2d::Zero();
                        if (map["origin"])
                        {
                            const auto o = r.coordinates(map["origin"], key + ".origin", 2);
                            origin = Eigen::Vector2d(o[0], o[1]);
                        }
                        const double threshold = r.number(map, "threshold", key, 0.5);
                        // 0 or below marks no pixel occupied (every wall gone), above 1 every pixel
                        if (!(threshold > 0. && threshold <= 1.))
                            r.fail(key + ".threshold",
                                   "expected a number in (0, 1] (a share of the image's maximum "
                                   "grey value), got " +
                                       std::to_string(threshold));
                        try
                        {
                            problem.scene->add(
                                validity::occupancyObstacles(pgm, resolution, origin, height, threshold));
                        }
                        catch (const std::exception &e)
                        {
                            r.fail(key + ".pgm", e.what());
                        }
                        problem.grid.mapResolution = resolution;  // grid checker cells aligned with the map's
                        problem.grid.origin = origin;
                        problem.scene->setGridCellSize(resolution);
                    }
                }
                if (const YAML::Node moveit = scene["moveit"])
                    readMoveItSceneKey(r, moveit, problem);
                if (const YAML::Node movingai = scene["movingai"])
                    readMovingAiKey(r, movingai, problem, gridMap);
                // A misspelt key would otherwise be ignored, and the scene would silently lose its obstacles.
                for (const auto &kv : scene)
                {
                    const std::string k = kv.first.as<std::string>();
                    if (k != "obstacles" && k != "map" && k != "moveit" && k != "movingai")
                        r.fail("scene." + k, "unknown key (expected obstacles, map, moveit, movingai)");
                }
            }
        }  // namespace problem_file
    }      // namespace tools
}  // namespace michi
