#ifndef MICHI_PLANNERS_DUAL_ROADMAP_NON_STOP_CONTROLLER_
#define MICHI_PLANNERS_DUAL_ROADMAP_NON_STOP_CONTROLLER_

#include <michi/planners/dual_roadmap/DualRoadmap.h>
#include <michi/planners/dual_roadmap/NonStopExecutor.h>

#include <ompl/base/Planner.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>

namespace michi
{
    namespace planners
    {
        struct NonStopControllerSettings
        {
            /** \brief Speed, deceleration, safety distance and stop margin of the robot's motion. planningDelay,
                cpuTimeScale and synchronous are for simulations on a simulated clock (`michi replan`); a robot's
                loop leaves them at their defaults. brakeAtEnd is always on: a trajectory ends at rest. */
            NonStopSettings motion;
            /** \brief Wall-clock seconds one query may plan. */
            double planningTime{0.5};
            /** \brief Path length (the space's distance) ahead of the robot checked against each observed world;
                infinity: the whole remaining path. */
            double lookahead{std::numeric_limits<double>::infinity()};
            /** \brief A measured state farther than this (the space's distance) from the path is off it: the robot
                stops following it and a path is planned from where it is. */
            double trackingTolerance{0.05};
            /** \brief The trajectory update() returns: seconds ahead and the time between its samples. */
            double horizon{1.};
            double period{0.05};
            /** \brief Resolution of the motion checks (OMPL's longest valid segment fraction). */
            double checkResolution{0.01};
            /** \brief Smooth every path found by a planner other than DualRoadmap (which smooths its own) with OMPL's
                PathSimplifier: redundant vertices, shortcuts. */
            bool simplify{true};
        };

        /** \brief Paper 002's non-stop replanning for a user's own robot loop, in OMPL terms: the robot's measured
            states and observations of the world go in, timed trajectory segments come out, and planning runs in
            parallel with the motion on a thread of its own.

            Any OMPL state space and any StateValidityChecker: an observation of the world is a validity checker for
            the world as sensed at that moment (the user's own: their obstacle geometry, their collision library),
            handed over and never changed after (the planning thread may still be using an older one). Each call
            of update() gives the measured state and the time; the controller moves its model of the robot by the
            time passed, puts it where the robot was measured (NonStopExecutor::track), and returns the motion it
            commands from now: configurations every `period` seconds over `horizon` seconds
            (NonStopExecutor::preview). The planner is DualRoadmap by default (any OMPL planner can be given);
            a DualRoadmap is told each world that changed, and where, when the observation says so, so it keeps what
            it proved elsewhere. Nothing here depends on michi's problem files, scenes or command line.

            Threads: observeWorld(), start(), update() and stop() are called from one thread (the robot's loop);
            the planner runs on the controller's planning thread. See docs/examples/nonstop_controller.cpp. */
        class NonStopController
        {
        public:
            using PlannerAllocator = std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr &)>;

            /** \param space the robot's state space (bounds set)
                \param allocator makes the planner on the planning side's SpaceInformation; empty: DualRoadmap.
                Throws std::invalid_argument on settings out of range (each must be finite). Sets \e space up (OMPL's
                StateSpace::setup() registers its projections): controllers that share one space are constructed on
                one thread. */
            explicit NonStopController(const ompl::base::StateSpacePtr &space, NonStopControllerSettings settings = {},
                                       PlannerAllocator allocator = {});
            ~NonStopController();
            NonStopController(const NonStopController &) = delete;
            NonStopController &operator=(const NonStopController &) = delete;

            /** \brief The robot loop's SpaceInformation (checks of the remaining path): the one to construct the
                world's validity checkers with. */
            const ompl::base::SpaceInformationPtr &spaceInformation() const
            {
                return execSi_;
            }

            /** \brief A new observation of the world: \e world answers validity (and, with a safety distance,
                clearance) for the world as sensed now, and is not changed afterwards. \e changed, when given, says
                which motions the change since the previous observation may affect (DualRoadmap keeps what it proved
                elsewhere); empty: anything may have changed. After start(), the remaining path is checked against
                it at once (paper 002's Geo. change). */
            void observeWorld(ompl::base::StateValidityCheckerPtr world, DualRoadmap::ChangeRegion changed = {});

            /** \brief Go from \e measured to \e goal (a world must have been observed). std::invalid_argument for a
                state with a value that is not a finite number, or a goal outside the space's bounds. A goal (or
                start) that the observed world blocks is not an error, since a mover may clear it: the controller
                holds the robot and asks the planner again at every observation (Statistics::failures counts the
                answers without a path). */
            void start(const ompl::base::State *measured, const ompl::base::State *goal);

            /** \brief The robot's state measured at \e time (seconds, any origin, never decreasing): returns the
                motion to follow from now (times relative to \e time). std::invalid_argument for a measured state
                with a value that is not a finite number (nothing moves then). */
            TimedPath update(const ompl::base::State *measured, double time);

            /** \brief Halt: cancel planning; update() then holds the robot where it is. */
            void stop();

            NonStopExecutor::ExecState state() const
            {
                return executor_->execState();
            }
            bool finished() const
            {
                return state() == NonStopExecutor::ExecState::FINISHED;
            }
            const NonStopExecutor::Statistics &statistics() const
            {
                return executor_->statistics();
            }
            /** \brief The path being followed, from the robot's position on it. */
            ConfigurationPath remainingPath() const
            {
                return executor_->remainingPath();
            }
            /** \brief Block for at most \e seconds until the planner is idle (tests, shutdown). */
            bool waitForPlanner(double seconds)
            {
                return executor_->waitForPlanner(seconds);
            }

        private:
            /** A validity checker that forwards to the observed world a thread last set (one per side, so neither
                SpaceInformation's checker is ever replaced). */
            class ObservedWorld;
            struct Observation
            {
                ompl::base::StateValidityCheckerPtr world;
                DualRoadmap::ChangeRegion changed;
            };

            NonStopHooks hooks();
            bool plan(const Configuration &from, const Configuration &goal, std::uint64_t snapshot,
                      const std::atomic<bool> &cancel, ConfigurationPath &path);
            Configuration toReals(const ompl::base::State *state) const;
            /** toReals() of a state the caller hands in; std::invalid_argument naming \e what when it is null or
                holds a value that is not a finite number */
            Configuration measuredReals(const ompl::base::State *state, const char *what) const;

            NonStopControllerSettings settings_;
            ompl::base::StateSpacePtr space_;
            ompl::base::SpaceInformationPtr execSi_;  ///< the robot loop's thread
            ompl::base::SpaceInformationPtr planSi_;  ///< the planning thread's
            ompl::base::PlannerPtr planner_;
            std::shared_ptr<ObservedWorld> execWorld_;
            std::shared_ptr<ObservedWorld> planWorld_;

            // execution thread: scratch states of the distance and interpolation hooks (no allocation per call)
            ompl::base::State *scratchA_{nullptr};
            ompl::base::State *scratchB_{nullptr};
            ompl::base::State *scratchOut_{nullptr};
            double time_{0.};
            bool haveTime_{false};

            std::mutex observationMutex_;
            std::map<std::uint64_t, Observation> observations_;  ///< not yet planned with, and the latest
            std::uint64_t observed_{0};                          ///< id of the latest observation
            std::uint64_t planned_{0};  ///< planning thread: the observation its last query planned in

            std::unique_ptr<NonStopExecutor> executor_;  ///< last: its planning thread uses everything above
        };
    }  // namespace planners
}  // namespace michi

#endif
