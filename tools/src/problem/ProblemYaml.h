#ifndef MICHI_TOOLS_SRC_PROBLEM_YAML_
#define MICHI_TOOLS_SRC_PROBLEM_YAML_

// Private to michi_tools (not installed): the pieces of loadProblem() (Problem.cpp). The Reader is in
// ProblemYaml.cpp, the readers of the problem file's sections in ProblemRobot.cpp (robot), ProblemScene.cpp (scene),
// ProblemQueries.cpp (start, goal, request, queries) and ProblemSettings.cpp (planners, benchmark, collision).

#include <michi/tools/problem/MoveItImport.h>
#include <michi/tools/problem/Problem.h>

#include <yaml-cpp/yaml.h>

#include <array>
#include <set>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace problem_file
        {
            /** Metres per cell an occupancy map may have (PGM, MovingAI, ROS): a resolution of 1e-300 made a map
                1e-297 m wide that OMPL then refused with a message naming no key, or planned in. */
            constexpr double MIN_MAP_RESOLUTION = 1e-4;
            constexpr double MAX_MAP_RESOLUTION = 1000.;
            constexpr const char *MAP_RESOLUTION_RANGE = "expected a number of metres per cell in [0.0001, 1000]";

            /** \brief The one way michi reads a YAML file (problem, MoveIt scene and request, experience, replan
                settings): a regular file under the size limit, parsed once, duplicate keys rejected (yaml-cpp keeps
                the first and drops the rest silently). Throws ProblemError naming the file and the line. */
            YAML::Node loadYaml(const std::string &file);

            /** \brief The same file's top-level entry \e key (an undefined node when absent): a copy of that entry
                alone, so a section reader does not copy a scene of thousands of obstacles it never reads. */
            YAML::Node loadYamlSection(const std::string &file, const std::string &key);

            /** Reads typed values out of a YAML tree and turns every mistake into a ProblemError naming the key. */
            class Reader
            {
            public:
                explicit Reader(std::string file) : file_(std::move(file))
                {
                }

                [[noreturn]] void fail(const std::string &key, const std::string &message) const;

                YAML::Node require(const YAML::Node &map, const std::string &name, const std::string &key) const;

                double number(const YAML::Node &n, const std::string &key) const;

                double number(const YAML::Node &map, const std::string &name, const std::string &key,
                              double fallback) const;

                std::vector<double> numbers(const YAML::Node &n, const std::string &key, std::size_t size = 0) const;

                std::string text(const YAML::Node &n, const std::string &key) const;

                unsigned int count(const YAML::Node &n, const std::string &key) const;

                bool flag(const YAML::Node &n, const std::string &key) const;

                /** A path in the problem file, relative to the file's folder; must exist. */
                std::string path(const YAML::Node &n, const std::string &key) const;

                /** {xyz: [3], rpy: [3]} or {position: [3], orientation: [x, y, z, w]}. */
                Eigen::Isometry3d pose(const YAML::Node &n, const std::string &key) const;

                std::vector<Eigen::Vector2d> polygon(const YAML::Node &n, const std::string &key) const;

                /** A position or size in metres: a number within validity::MAX_COORDINATE (1e6 m). */
                double coordinate(const YAML::Node &n, const std::string &key) const;

                /** \e size coordinates (any number when 0). */
                std::vector<double> coordinates(const YAML::Node &n, const std::string &key,
                                                std::size_t size = 0) const;

                const std::string &file() const
                {
                    return file_;
                }

                static double parseNumber(std::string text);

                /** Every key of mapping \e n must be one of \e allowed (a misspelt key is an error, not ignored). */
                void keys(const YAML::Node &n, const std::string &key, const std::set<std::string> &allowed) const;

            private:
                std::string file_;
            };

            // ---------------------------------------------------------------- robot (ProblemRobot.cpp)

            /** \e request: the problem's first MoveIt request (empty when none); its group_name is the planned
                group when robot.group is not given. */
            void readArm(const Reader &r, const YAML::Node &robot, Problem &problem, const MoveItRequest &request);

            /** \e mapBounds: robot.bounds may be left out (the bounds of the scene's grid map are used then). */
            void readSe2(const Reader &r, const YAML::Node &robot, Problem &problem, bool mapBounds);

            // ---------------------------------------------------------------- scene (ProblemScene.cpp)

            /** What scene.movingai adds besides obstacles: the map's extent and the scenario queries. */
            struct GridMapInfo
            {
                bool present{false};
                std::array<double, 4> bounds{{0., 1., 0., 1.}};  ///< x min, x max, y min, y max
                std::vector<Query> queries;
            };

            void readScene(const Reader &r, const YAML::Node &scene, Problem &problem, GridMapInfo &gridMap);

            /** A ROS map_server map (RosMap.cpp): its YAML file's settings and the obstacles of its image. */
            struct RosMap
            {
                std::string image;  ///< the image's path
                double resolution{0.};
                Eigen::Vector2d origin{Eigen::Vector2d::Zero()};  ///< lower-left corner of the image
                double yaw{0.};                                   ///< the map's turn about the origin
                int width{0}, rows{0};
                std::size_t occupiedCells{0};  ///< occupied and unknown pixels (both are obstacles)
                std::vector<validity::Obstacle> obstacles;
            };

            /** Read a ROS map_server YAML file and its image; \e height: the boxes' height. Throws ProblemError
                naming the map file and its key. */
            RosMap readRosMap(const std::string &file, double height);

            // ---------------------------------------------------------------- queries (ProblemQueries.cpp)

            /** Joint limits (ARM) or bounds (SE2) of a configuration; \e indexKeys: name value i "key[i]". */
            void checkConfiguration(const Reader &r, const std::vector<double> &values, const std::string &key,
                                    const Problem &problem, bool indexKeys = true);

            std::vector<double> readConfiguration(const Reader &r, const YAML::Node &n, const std::string &key,
                                                  const Problem &problem);

            /** The start and goal of a MoveIt MotionPlanRequest for the planned group. \e first: the problem's
                first request, whose start state also fixes the robot's other joints it names (unless
                robot.fixed_joints gives them). */
            Query readRequestQuery(const Reader &r, const YAML::Node &node, const std::string &key, Problem &problem,
                                   const YAML::Node &robot, bool first);

            // ---------------------------------------------------------------- settings (ProblemSettings.cpp)

            void readPlanners(const Reader &r, const YAML::Node &list, Problem &problem);

            void readBenchmark(const Reader &r, const YAML::Node &b, Problem &problem);

            /** collision: checker, jmap, motion_validator, max_step, valid_segment_fraction (absent: defaults). */
            void readCollision(const Reader &r, const YAML::Node &c, Problem &problem);
        }  // namespace problem_file
    }      // namespace tools
}  // namespace michi

#endif
