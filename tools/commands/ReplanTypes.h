#ifndef MICHI_TOOLS_SRC_REPLAN_TYPES_
#define MICHI_TOOLS_SRC_REPLAN_TYPES_

// Private to michi_tools (not installed): what the pieces of `michi replan` share (ReplanCommand.cpp,
// ReplanSettings.cpp, ReplanMethods.cpp, ReplanEpisode.cpp, ReplanHooks.cpp, ReplanReport.cpp, ReplanFrames.cpp).

#include <michi/planners/dual_roadmap/InterferencePrediction.h>
#include <michi/planners/dual_roadmap/NonStopExecutor.h>
#include <michi/planners/dual_roadmap/PathDeformation.h>
#include <michi/tools/problem/Problem.h>

#include <Eigen/Geometry>

#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace replan
        {
            // paper 002's executor and path deformation live beside DualRoadmap (michi::planners), usable from a
            // user's own OMPL code; the scenario runner uses them by these names
            using planners::Configuration;
            using planners::ConfigurationPath;
            using planners::DeformationSettings;
            using planners::deformPath;
            using planners::NonStopExecutor;
            using planners::NonStopHooks;
            using planners::NonStopSettings;
            using planners::pointJacobian;

            /** extras.replan of the problem file (docs/dual-roadmap.md). */
            struct ReplanSettings
            {
                double dt{0.02};               ///< simulation step, seconds
                double sensePeriod{0.1};       ///< Geo. change every this many seconds
                double speed{1.};              ///< cruise speed along the path (state space distance / s)
                double deceleration{2.};       ///< and acceleration
                double safetyDistance{0.15};   ///< metres
                double margin{0.15};           ///< moving obstacles are grown by this for planning and checks
                double predictionHorizon{1.};  ///< seconds of constant-velocity prediction of moving obstacles
                double predictionCopies{3.};   ///< copies of each moving obstacle along the prediction
                double lookahead{4.};          ///< path length checked after a Geo. change
                double stopMargin{0.05};       ///< path length between the stop and the interference
                double planningTime{1.};       ///< seconds per query
                double episodeTime{60.};       ///< simulated seconds before an episode counts as failed
                double timingJitter{1.};       ///< moving obstacles start up to this many seconds earlier / later
                double speedJitter{0.3};       ///< and move up to this fraction faster / slower
                /** real_time > 0: planning takes time on the simulated clock, real_time simulated seconds per
                    second of planning, measured by `clock`. real_time 0: the old reproducible model: every query is
                    charged planning_delay simulated seconds, the simulation waits for the planner (in wall time)
                    before it steps on, and DualRoadmap stops after planning_work evaluations of its termination
                    condition (a work count, not wall time). */
                double realTime{1.};
                /** clock (with real_time > 0). cpu (true): each query is planned while the simulation waits and is
                    charged the CPU time the planning thread really spent (its thread CPU clock), every planner
                    limited to planning_time of that CPU time: outcomes follow from the planners' real cost and the
                    load of other processes does not count. wall (false): planner and simulation run concurrently,
                    the simulated clock following the wall clock. */
                bool cpuClock{true};
                double planningDelay{0.1};
                double planningWork{200000.};
                double escapeHorizon{0.};  ///< escapes avoid the obstacles' true shapes over this many seconds
                double crossTime{0.6};  ///< s: a robot inside a predicted region keeps going if it leaves it this fast
                bool deformation{true};
                /** retiming: paper 002's time-scale adaptation in the executor (NonStopSettings::retiming): a slower
                    speed or a wait on the current path before deforming or replanning, checked against the moving
                    obstacles' predicted motion over retiming_horizon seconds. */
                bool retiming{true};
                double retimingHorizon{5.};
                /** s: a timing must also miss the movers as predicted this much earlier and later (a mover a little
                    faster or slower than observed, or that turns, does not meet the robot on it) */
                double retimingSlack{0.3};
                /** obstacles_yield: a moving obstacle that would move into the robot waits (its key frames are
                    delayed by a step) instead; a robot that moves into an obstacle still collides. */
                bool obstaclesYield{false};
                DeformationSettings deform;
                double frames{8.};
                std::map<std::string, std::string> dualParams;  ///< dual_roadmap_params: set on both DualRoadmap runs
            };

            /** extras.replan of problem file \e file (defaults where absent); throws ProblemError. */
            ReplanSettings readSettings(const std::string &file);

            /** \e shape grown by \e m on every side (a moving obstacle, for planning and checks); \e file, \e key
                name it in the error for a shape that cannot be grown. */
            validity::ShapePtr grow(const validity::Shape &shape, double m, const std::string &file,
                                    const std::string &key);

            struct Mover
            {
                std::string name;
                validity::ShapePtr shape;
                validity::ShapePtr grown;
                std::vector<validity::TimedPose> trajectory;  ///< as in the file
            };

            /** The world as the robot senses it: static obstacles, and each moving obstacle grown by the margin
                and repeated along its observed velocity over the prediction horizon (planners::PredictedObstacles,
                paper 002's prediction, which a user's own OMPL code can use without this runner). */
            struct SensedWorld
            {
                validity::ScenePtr scene{std::make_shared<validity::Scene>()};
                std::unique_ptr<planners::PredictedObstacles> predicted;

                /** \e grown false: the movers' true shapes. */
                void build(const std::vector<validity::Obstacle> &statics, const std::vector<Mover> &movers, int n,
                           double h, bool grown = true)
                {
                    scene->add(statics);
                    predicted = std::make_unique<planners::PredictedObstacles>(scene, n, h);
                    for (const auto &m : movers)
                        predicted->add(m.name, grown ? m.grown : m.shape, validity::Scene::poseAt(m.trajectory, 0.));
                }
                void update(const std::vector<Mover> &movers, const std::vector<Eigen::Isometry3d> &poses,
                            const std::vector<Eigen::Vector3d> &velocities)
                {
                    std::vector<std::string> names;
                    names.reserve(movers.size());
                    for (const auto &m : movers)
                        names.push_back(m.name);
                    predicted->observe(names, poses, velocities);
                }
            };

            struct Snapshot
            {
                std::vector<Eigen::Isometry3d> poses;
                std::vector<Eigen::Vector3d> velocities;
            };

            struct Method
            {
                std::string id;  ///< for --methods
                std::string label;
                std::string planner;
                std::map<std::string, std::string> params;
                enum class Reuse
                {
                    SCRATCH,       ///< clear() before every query
                    KEEP_ROADMAP,  ///< LazyPRM: clearQuery() + clearValidity(), the roadmap stays
                    DUAL           ///< DualRoadmap: clear() keeps the learning roadmap
                } reuse{Reuse::SCRATCH};
                bool simplify{true};
                bool retiming{true};  ///< false: the ablation without time-scale adaptation
                bool nonStop{true};   ///< false: stop and replan (the executor brakes, then plans)
            };

            /** michi::DualRoadmap first, then the baselines. */
            std::vector<Method> allMethods();

            struct Results
            {
                unsigned int episodes{0}, reached{0}, collisions{0}, collisionSteps{0}, stops{0}, deformations{0},
                    replans{0}, cancelled{0}, failures{0}, obstacleWaits{0}, retimings{0};
                /** contacts (a step in collision after one free of it) while the robot moved: caused by its motion */
                unsigned int motionCollisions{0};
                /** contacts with a robot that stood still during the step: an obstacle drove into it */
                unsigned int unavoidableCollisions{0};
                std::vector<double> replanLatency;   ///< ms charged on the simulated clock (CPU with clock cpu)
                std::vector<double> replanWall;      ///< ms wall clock
                std::vector<double> replanCpu;       ///< ms planning-thread CPU time
                std::vector<double> initialLatency;  ///< ms
                std::vector<double> timeToGoal;      ///< simulated s
                std::vector<double> episodeEnd;      ///< simulated s at which each episode ended
                double wallSeconds{0.};
                std::size_t learningEdges{0};
            };

            /** One frame of the picture: time, robot trajectory so far, remaining plan, obstacle poses. */
            struct Frame
            {
                double time;
                std::vector<Configuration> executed;
                ConfigurationPath plan;
                std::vector<Eigen::Isometry3d> poses;
            };

            /** One method's episode as it was simulated, for the replay page (--html): the robot's configuration
                and every moving obstacle's pose at each simulation step (step 0: time 0, the start), and the
                movers' trajectories at the episode's end (obstacles_yield delays them as the episode runs), which
                give their poses after it. */
            struct Trace
            {
                std::vector<double> times;
                std::vector<Configuration> states;
                std::vector<std::vector<Eigen::Isometry3d>> poses;  ///< per step, one pose per mover
                std::vector<std::vector<validity::TimedPose>> trajectories;
                bool reached{false};
                bool collided{false};
            };
        }  // namespace replan
    }      // namespace tools
}  // namespace michi

#endif
