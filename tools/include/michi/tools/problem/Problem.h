#ifndef MICHI_TOOLS_PROBLEM_
#define MICHI_TOOLS_PROBLEM_

#include <michi/validity/robot/CollisionBodies.h>
#include <michi/validity/jmap/JMapValidityChecker.h>
#include <michi/validity/grid/GridValidityChecker.h>
#include <michi/validity/robot/RobotModel.h>
#include <michi/validity/scene/Scene.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief \e text as one printable line: control characters and bytes that are not UTF-8 become \\xNN,
            and more than 2,000 bytes are cut with a note of how many were left out. Messages quote what they read,
            and a binary file's first "line" would otherwise reach the terminal raw. */
        std::string printableLine(const std::string &text);

        /** \brief A problem file (or a file it refers to) that cannot be used. what() is one printable line:
            "<file>: <key>: <what was expected>". */
        class ProblemError : public std::runtime_error
        {
        public:
            ProblemError(const std::string &file, const std::string &key, const std::string &message)
                : std::runtime_error(printableLine(file + (key.empty() ? "" : ": " + key) + ": " + message))
                , file_(file)
                , key_(key)
            {
            }
            const std::string &file() const
            {
                return file_;
            }
            const std::string &key() const
            {
                return key_;
            }

        private:
            std::string file_;
            std::string key_;
        };

        /** \brief A planner to run, by registry name, with parameters set by name through its ParamSet. */
        struct PlannerSpec
        {
            std::string name;
            std::map<std::string, std::string> params;
            /** \brief planners[i].checker: this planner's own checker in a benchmark (e.g. jmap for
                michi::ConcentricCircle, which plans on the J-map's polygons, beside stock planners on FCL);
                empty: the problem's collision.checker. The run is named <planner>_<checker>. */
            std::string checker;
        };

        struct Query
        {
            std::vector<double> start;
            std::vector<double> goal;
            std::string label;  ///< where it came from ("arena.map.scen line 12"); may be empty
            /** \brief Where the problem file gives it, for messages: "start/goal" (the top-level start and goal),
                "queries[1]", "request" or "queries[1].request" (a MoveIt request), "scene.movingai.scenarios";
                empty for a query made by a tool (queryEndKey() then counts it among the queries). */
            std::string key;
        };

        struct BenchmarkSettings
        {
            double timeLimit{5.};       ///< seconds per run
            double memoryLimit{4096.};  ///< MB
            unsigned int runs{10};
            unsigned int seed{1};  ///< ompl::RNG::setSeed before the first run
            bool simplify{true};   ///< simplify solutions as OMPL's Benchmark does by default
            /** \brief benchmark.queries: "" (every run plans one query), "all" or "A-B": run i plans query i of the
                selection, one run per query (a dataset run, tools/problem/Dataset.h). */
            std::string queries;
            /** \brief benchmark.objective: "" (each planner's default; OMPL's optimizing planners then minimise
                path length), "length" (ompl::base::PathLengthOptimizationObjective) or "clearance"
                (ompl::base::MaximizeMinClearanceObjective), set on the problem definition every planner shares. */
            std::string objective;
        };

        /** \brief How an SE2 robot moves between two states (robot.motion, docs/problem-format.md). */
        struct Se2Motion
        {
            /** \brief "free": OMPL's SE2StateSpace (straight lines in x, y, yaw); "turn_move_turn":
                state_spaces::TurnMoveTurnStateSpace (turn in place, drive straight, turn in place; paper 003). */
            std::string model{"free"};
            double turnWeight{0.};  ///< metres per radian of turning; 0: the footprint's circumradius
            bool backward{true};    ///< turn_move_turn: the robot may drive backwards
        };

        /** \brief Start/goal sets for experience planners (docs/path-seed.md), from the problem's `experience` key
            (read by readExperienceQueries(), ExperienceQueries.cpp). */
        struct ExperienceQueries
        {
            std::vector<Query> training;  ///< solved from scratch before a benchmark to train experience planners
            std::vector<Query> heldOut;   ///< run i of each planner in a benchmark plans heldOut[i mod size]
            double trainingTime{5.};      ///< seconds of RRT-Connect per training query
            std::string library;          ///< experience file given to experience planners before training
            /** \brief experience.learned_on: another problem file (the same joints, another robot or scene) whose
                training queries, solved on its robot in its scene, train the experience planners instead of this
                problem's own (a kinematic change: a library learned on one robot used on a changed one). */
            std::string learnedOn;
            std::string file;  ///< the file the queries came from
            /** \brief experience.dataset: a folder of problem files (tools/problem/ExperienceDataset.h), each
                problem with its own scene and query; empty when the queries come from experience.queries. */
            std::string dataset;
            std::string trainingProblems;  ///< experience.training: the folder's problems that train ("A-B", from 0)
            std::string heldOutProblems;   ///< experience.held_out: the folder's problems of the runs ("A-B")
        };

        /** \brief Everything a problem file says: robot, scene, queries, planners and benchmark settings.
            Robots are either a URDF arm (kind ARM, joints of one group planned, the others fixed) or a planar
            rigid body (kind SE2, a footprint polygon on a map). See docs/problem-format.md. */
        struct Problem
        {
            enum class Kind
            {
                ARM,
                SE2
            };
            std::string name;
            std::string file;  ///< the problem file, as given
            std::string description;
            Kind kind{Kind::ARM};

            // ARM
            validity::RobotModelPtr model;
            std::map<std::string, std::vector<std::string>> groups;  ///< named joint groups (arm, hand, ...)
            std::string group;                                       ///< the planned group's name
            std::vector<int> groupVariables;                         ///< planned joints, state order
            std::vector<double> fixedValues;                         ///< full configuration for other joints

            // SE2
            std::vector<Eigen::Vector2d> footprint;
            double footprintHeight{1.};
            std::array<double, 4> se2Bounds{{0., 1., 0., 1.}};  ///< x min, x max, y min, y max
            Se2Motion se2Motion;                                ///< robot.motion

            validity::ScenePtr scene;
            std::vector<Query> queries;  ///< at least one
            std::vector<PlannerSpec> planners;
            BenchmarkSettings benchmark;
            double validSegmentFraction{0.};  ///< 0: OMPL's default; else longestValidSegmentFraction
            /** \brief How motions are checked: "workspace" (validity::WorkspaceMotionValidator, checks at most
                maxStep metres apart, the default), "conservative" (validity::ConservativeMotionValidator, exact) or
                "discrete" (OMPL's DiscreteMotionValidator at validSegmentFraction). */
            std::string motionValidator{"workspace"};
            double maxStep{0.01};  ///< metres, for "workspace"
            /** \brief The state validity checker: "fcl" (validity::FclValidityChecker, the default), "jmap"
                (validity::JMapValidityChecker over the first two planned joints, paper 000), "grid"
                (validity::GridValidityChecker, SE2 robots) or "spheres" (validity::SphereValidityChecker, arms):
                docs/checking.md. */
            std::string checker{"fcl"};
            /** \brief For checker "spheres" (collision.spheres): the sphere model's budget per link, and a
                spherized URDF to start from (empty: spheres made from the robot's own geometry). */
            struct SphereSettings
            {
                int perLink{24};
                std::string spherizedUrdf;
                /** \brief Whether FCL settles states whose spheres touch (SphereValidityChecker::setExactStates):
                    "on", "off", or "auto": on only for a query whose start or goal the spheres reject and FCL
                    accepts (a hand at its grasp), so that such a query stays solvable. */
                std::string exactStates{"auto"};
            } spheres;
            validity::JMapCheckerSettings jmap;  ///< for checker "jmap" (collision.jmap)
            /** \brief For checker "grid" (collision.grid); a map scene (scene.map, scene.movingai) sets its
                mapResolution and origin so that table cells align with the map's. */
            validity::GridCheckerSettings grid;
            ExperienceQueries experience;  ///< training and held-out queries (experience), may be empty

            /** \brief Collision bodies of the planned robot (RobotGroupBodies or PlanarRigidBody). */
            validity::CollisionBodiesPtr bodies() const;
            /** \brief Dimension of a state (values in start / goal). */
            std::size_t dimension() const;
            /** \brief Names of the state's values ("joint1", ... or "x", "y", "yaw"). */
            std::vector<std::string> valueNames() const;
        };

        /** \brief Load a problem file. Paths inside it are relative to it. Throws ProblemError naming the file
            and key for anything malformed, validity::UrdfError (naming the URDF) for a bad robot. Start and goal
            are checked against joint limits here; against collisions by makePlanningContext(). */
        Problem loadProblem(const std::string &path);

        /** \brief The key that names the start or goal (\e end: "start" or "goal") of query \e query of \e problem
            in its file: "start", "queries[1].goal", "request" (a MoveIt request gives both),
            "scene.movingai.scenarios" (a map scenario: the query's label names the line); "queries[N].goal" for a
            query a tool made. */
        std::string queryEndKey(const Problem &problem, std::size_t query, const std::string &end);
    }  // namespace tools
}  // namespace michi

#endif
