#ifndef MICHI_PLANNERS_DUAL_ROADMAP_NON_STOP_EXECUTOR_
#define MICHI_PLANNERS_DUAL_ROADMAP_NON_STOP_EXECUTOR_

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief A configuration (a state's reals) and a path of them. */
        using Configuration = std::vector<double>;
        using ConfigurationPath = std::vector<Configuration>;

        /** \brief What the executor needs of the robot, the sensed world and the planner. plan() runs on the
            planning thread, everything else on the execution thread (the caller of the executor's methods). */
        struct NonStopHooks
        {
            /** \brief Plan from \e from to \e goal in the world as sensed when the query was made; return false when
                no path was found (time limit) or \e cancel became true. \e snapshot is what sensedWorld() returned
                when the query was sent. A path that does not end at the goal (an escape) is followed to its end,
                then the robot waits there and queries again. */
            std::function<bool(const Configuration &from, const Configuration &goal, std::uint64_t snapshot,
                               const std::atomic<bool> &cancel, ConfigurationPath &path)>
                plan;
            /** \brief An id of the world as sensed now, handed to plan() with a query (e.g. the simulation time). */
            std::function<std::uint64_t()> sensedWorld;
            /** \brief Distance between configurations and interpolation (the state space's). */
            std::function<double(const Configuration &, const Configuration &)> distance;
            std::function<void(const Configuration &, const Configuration &, double, Configuration &)> interpolate;
            /** \brief Arc length (in distance()) along \e path to the first predicted interference with the sensed
                world; +infinity when the path is free. */
            std::function<double(const ConfigurationPath &path)> firstInterference;
            /** \brief Distance of the robot at \e q to the nearest obstacle of the sensed world (metres). */
            std::function<double(const Configuration &q)> clearance;
            /** \brief Optional: deform \e path (starting at the robot) away from the obstacles; true when the deformed
                path is free, false to fall back to replanning (then \e path is unchanged). */
            std::function<bool(ConfigurationPath &path)> deform;
            /** \brief Optional (paper 002's temporal adaptation: a time axis given to the path): is the motion
                through \e configurations, the robot at configurations[k] at times[k] (seconds from now, the first 0),
                free of the moving obstacles, each where its predicted motion takes it at that time? */
            std::function<bool(const ConfigurationPath &configurations, const std::vector<double> &times)> freeInTime;
        };

        struct NonStopSettings
        {
            double speed{1.};           ///< cruise speed along the path (distance() units per second)
            double deceleration{2.};    ///< also the acceleration (units per second squared)
            double safetyDistance{0.};  ///< metres: closer than this while no new path exists -> decelerate, stop
            double stopMargin{0.};      ///< path length kept between the stop point and the interference
            /** \brief Simulated seconds charged for every query: a planner's answer is taken only once the
                simulated clock has advanced this far past the Query (0: as soon as it arrives). With a caller that
                waits for the planner before every step, this makes runs independent of the wall clock. */
            double planningDelay{0.};
            /** \brief Every Query is planned to its end before it returns (the execution thread waits), so a later
                cancel never interrupts a planner halfway, at a wall-clock dependent point: with planningDelay > 0
                and a planner whose work does not depend on wall time, runs are reproducible. */
            bool synchronous{false};
            /** \brief Simulated seconds charged per second of CPU time the plan hook really took on the planning thread
                (its thread CPU clock, so other processes on the machine do not count); 0: none. The answer is
                taken only once the simulated clock has advanced planningDelay + this x that CPU time past the Query.
                With synchronous, a simulation whose outcomes follow from the planner's real cost, reproducible up
                to that time. */
            double cpuTimeScale{0.};
            /** \brief Slow down before the end of a path so the robot arrives there at rest (at most the
                deceleration), as a real robot must; false: it runs into the end at speed and stops there, the model
                of `michi replan`'s simulations. */
            bool brakeAtEnd{false};
            /** \brief Time-scale adaptation (needs NonStopHooks::freeInTime): when the world changes and the path
                meets an obstacle's predicted region, first look for a timing of the same path that misses the
                obstacles in time (full speed, 3/4, 1/2, 1/4 of it, or a wait of 0.5, 1 or 2 s, checked every
                retimingStep seconds) and takes the robot past every predicted interference within retimingHorizon
                seconds, before deforming or replanning. With it, a robot that would have to brake inside an
                obstacle's predicted region (already in the way of an obstacle that has not come yet) first looks
                for a crossing: the path at full speed up to where a stop fits before the next interference, free of
                the obstacles in time; it replans from there instead of standing in the obstacle's way. */
            bool retiming{false};
            double retimingHorizon{2.};
            double retimingStep{0.1};
            /** \brief false: the stop-and-replan baseline: a path that meets an obstacle is not followed on while a
                new one is planned; the robot brakes at once and the query is sent once it stands (no deformation,
                no retiming). */
            bool nonStop{true};
        };

        /** \brief The motion the executor plans for the robot from now on: configurations at times (seconds from
            now, the first at 0) and the speed along the path there (distance() units per second). */
        struct TimedPath
        {
            std::vector<double> times;
            ConfigurationPath configurations;
            std::vector<double> speeds;
        };

        /** \brief Non-stop planning and execution (paper 002, Fig. 1): a planning thread and an execution thread
            driven by signals. External: Start, Stop, Geo. change; internal: Query, Finished, Cancelled, Path
            found. The execution thread is the caller's: it calls start(), stop(), geoChange() and step(dt), which
            advances a simulated clock the caller controls; the planning thread is owned by the executor.

            Execution states: IDLE, EXECUTE (following the path), UPDATE_PROBLEM (checking the remaining path after
            a Geo. change; transient), REPLANNING (moving on while the planner works on a new path from the point
            where a safe stop would begin), STOPPING (decelerating: the stop point was reached or an obstacle came
            closer than the safety distance before a new path existed), STOPPED (waiting for a path), FINISHED.
            Planning states: WAIT_QUERY, PLANNING.

            In UPDATE_PROBLEM a predicted interference is first handed to hooks.deform (small interference), and
            only when that fails does a Query go to the planner. If a later Geo. change shows the interference gone
            while replanning, the query is cancelled and the original path continues. */
        class NonStopExecutor
        {
        public:
            enum class ExecState
            {
                IDLE,
                EXECUTE,
                UPDATE_PROBLEM,
                REPLANNING,
                STOPPING,
                STOPPED,
                FINISHED
            };
            enum class PlanState
            {
                WAIT_QUERY,
                PLANNING
            };
            enum class Signal
            {
                START,
                STOP,
                GEO_CHANGE,
                QUERY,
                FINISHED,
                CANCELLED,
                PATH_FOUND,
                STEP  ///< not a signal of the paper: a clock tick moved the robot (stop point, safety, goal)
            };
            struct Transition
            {
                ExecState from;
                Signal signal;
                ExecState to;
            };
            struct Statistics
            {
                unsigned int queries{0};
                unsigned int pathsFound{0};
                unsigned int cancelled{0};  ///< queries cancelled (interference gone) or failed
                unsigned int failures{0};   ///< queries the planner gave up on
                unsigned int deformations{0};
                unsigned int stops{0};          ///< times the robot came to a halt waiting for a path
                std::vector<double> latencies;  ///< wall-clock seconds from Query to Path found
                /** planning-thread CPU seconds of the same queries (the plan hook's, on its thread CPU clock) */
                std::vector<double> cpuLatencies;
                unsigned int offPath{0};    ///< measured states (track()) farther from the path than the tolerance
                unsigned int retimings{0};  ///< Geo. changes answered by a new timing of the same path
            };

            NonStopExecutor(NonStopHooks hooks, NonStopSettings settings);
            ~NonStopExecutor();
            NonStopExecutor(const NonStopExecutor &) = delete;
            NonStopExecutor &operator=(const NonStopExecutor &) = delete;

            /** \brief Start: the robot is at \e current and must reach \e goal; a Query for the first path is sent. */
            void start(const Configuration &current, const Configuration &goal);
            /** \brief Stop (external): halt at once, cancel planning, go IDLE. */
            void stop();
            /** \brief Geo. change (external): the world changed; check the remaining path. */
            void geoChange();
            /** \brief Advance the simulated clock by \e dt: take in the planner's signals, move the robot. */
            void step(double dt);
            /** \brief A measured configuration of the robot (closed loop): the robot's position on the path becomes
                the arc nearest \e measured (looked for within the tolerance plus a second of travel either side of
                where the model has it). Farther than \e tolerance (> 0) from the path, the robot is off it: the
                executor stops following it and plans again from \e measured (STOPPED). A robot slower than
                commanded is still on its way when the model reached the goal: FINISHED only holds while it is within
                the tolerance of the goal. Returns whether the robot was on the path. Call it after step(). */
            bool track(const Configuration &measured, double tolerance);
            /** \brief The motion the executor will command over the next \e horizon seconds, sampled every \e period
                seconds, if nothing changes (no new path, no Geo. change): the same speed law as step(), the stop at
                the replanning stop point, the end of the path. Does not change the executor. */
            TimedPath preview(double horizon, double period) const;
            /** \brief Block until the planning thread has nothing to do and its signals are queued (tests). */
            void waitForPlanner();
            /** \brief The same for at most \e seconds of wall-clock time; true when the planner is idle. */
            bool waitForPlanner(double seconds);

            ExecState execState() const
            {
                return exec_;
            }
            PlanState planState() const;
            double time() const
            {
                return time_;
            }
            double velocity() const
            {
                return velocity_;
            }
            const Configuration &configuration() const
            {
                return current_;
            }
            /** \brief The path being followed, from the robot's configuration. */
            ConfigurationPath remainingPath() const;
            const std::vector<Transition> &transitions() const
            {
                return transitions_;
            }
            const Statistics &statistics() const
            {
                return stats_;
            }

            static const char *name(ExecState s);
            static const char *name(PlanState s);
            static const char *name(Signal s);

        private:
            struct Query
            {
                std::uint64_t id{0};
                Configuration from;
                Configuration goal;
                std::uint64_t snapshot{0};
            };
            struct Reply
            {
                std::uint64_t id{0};
                bool found{false};
                ConfigurationPath path;
                double seconds{0.};
                double cpuSeconds{0.};  ///< the planning thread's CPU time for this query
            };

            void planningThread();
            void sendQuery(const Configuration &from, double planStartArc);
            void cancelQuery();
            void transition(ExecState to, Signal signal);
            void updateProblem();
            void takeReplies();
            void onPathFound(Reply &reply);
            /** \brief Advance arc \e s and speed \e v by \e dt in state \e state (the speed law of step() and
                preview()). */
            void advance(ExecState state, double &s, double &v, double dt, double cap, bool hold) const;
            /** \brief Time-scale adaptation: a speed cap or a wait under which the rest of the path is free in time
                (NonStopSettings::retiming); false when none is or it is off. */
            bool retime();
            /** \brief Retiming of a stop: the robot is in (or at) an obstacle's predicted region, where braking
                would leave it standing in the obstacle's way. When the path at full speed, within retimingHorizon
                seconds, leaves every predicted region with room to stop before the next and is free of the obstacles
                in time on the way, crossUntil_ becomes the arc where that crossing ends and the room (path length
                after it, +infinity when the rest of the path is free) is returned; otherwise -1. */
            double crossing();
            /** \brief Back to full speed, no wait. */
            void clearTiming()
            {
                speedCap_ = settings_.speed;
                holdUntil_ = -1.;
            }
            /** \brief Configuration at arc length \e s of path_ (clamped). */
            Configuration at(double s) const;
            /** \brief The part of path_ between arc lengths \e a and \e b (in that direction). */
            ConfigurationPath segment(double a, double b) const;
            void setPath(ConfigurationPath path);
            double pathLength() const;
            double brakingDistance() const
            {
                return velocity_ * velocity_ / (2. * settings_.deceleration);
            }

            /** Brake now (REPLANNING): the robot at \e s going \e v would pass the stop point within the next step of
                \e dt (braking only once past it stopped the robot up to half a step beyond the room left). */
            bool mustBrake(double s, double v, double dt) const;

            /** How far the robot may still drive before it must brake to stand within \e limit (arc length ahead of
                it). Until it brakes it keeps speeding up towards the cruise speed (advance()), so the braking
                distance is the one of the speed it will have there, not of its speed now: with the latter, a robot
                that saw an obstacle while starting off braked too late and stopped inside it. */
            double roomBeforeBraking(double limit) const
            {
                const double a = settings_.deceleration, v = velocity_;
                const double cruise = std::max(v, settings_.speed);
                // speeding up all the way: x + (v^2 + 2 a x) / (2 a) = limit
                const double x = 0.5 * (limit - v * v / (2. * a));
                if (v * v + 2. * a * x <= cruise * cruise)
                    return x;
                return limit - cruise * cruise / (2. * a);  // at cruise speed before it brakes
            }

            NonStopHooks hooks_;
            NonStopSettings settings_;

            // execution thread only
            ExecState exec_{ExecState::IDLE};
            double time_{0.};
            double velocity_{0.};
            Configuration current_;
            Configuration goal_;
            ConfigurationPath path_;   ///< being followed
            std::vector<double> arc_;  ///< cumulative arc length of path_
            double s_{0.};             ///< robot's arc position on path_
            double stopArc_{0.};       ///< REPLANNING: where the safe stop begins
            double crossUntil_{-1.};   ///< crossing a predicted region at full speed up to this arc (crossing())
            double planStartArc_{0.};  ///< arc of path_ the outstanding query plans from
            double speedCap_{0.};      ///< retiming: cruise speed on the current path
            double holdUntil_{-1.};    ///< retiming: simulated time until which the robot stands
            std::uint64_t activeQuery_{0};
            double activeSentAt_{0.};  ///< simulated time the outstanding query was sent
            bool pendingPath_{false};
            ConfigurationPath pending_;
            std::vector<Transition> transitions_;
            Statistics stats_;

            // shared with the planning thread
            mutable std::mutex mutex_;
            std::condition_variable cv_;
            std::deque<Query> queries_;
            std::deque<Reply> replies_;
            std::atomic<bool> cancel_{false};
            bool quit_{false};
            bool busy_{false};
            std::uint64_t nextId_{0};
            std::thread thread_;
        };
    }  // namespace planners
}  // namespace michi

#endif
