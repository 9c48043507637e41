#include <michi/planners/dual_roadmap/NonStopExecutor.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <time.h>

namespace michi
{
    namespace planners
    {
        namespace
        {
            // Tolerance on arc lengths: positions along the path are sums of distances, so comparisons with waypoint
            // arcs or the path's end must not depend on the last bits.
            const double EPS = 1e-9;

            /** CPU seconds the calling thread has used (POSIX thread CPU clock): a planner's cost that load from
                other processes on the machine does not inflate. */
            double threadCpuSeconds()
            {
                timespec ts{};
                clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
                return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
            }
        }  // namespace

        NonStopExecutor::NonStopExecutor(NonStopHooks hooks, NonStopSettings settings)
            : hooks_(std::move(hooks)), settings_(settings)
        {
            if (!hooks_.plan || !hooks_.distance || !hooks_.interpolate || !hooks_.firstInterference ||
                !hooks_.clearance)
                throw std::invalid_argument(
                    "NonStopExecutor: plan, distance, interpolate, firstInterference and "
                    "clearance hooks are required");
            // finite as well as in range: an infinite speed or deceleration makes every braking distance 0 or NaN, a
            // NaN margin every comparison false
            const auto positive = [](double v)
            {
                return std::isfinite(v) && v > 0.;
            };
            const auto notNegative = [](double v)
            {
                return std::isfinite(v) && v >= 0.;
            };
            if (!positive(settings_.speed) || !positive(settings_.deceleration))
                throw std::invalid_argument("NonStopExecutor: speed and deceleration must be positive and finite");
            if (!notNegative(settings_.safetyDistance) || !notNegative(settings_.stopMargin))
                throw std::invalid_argument(
                    "NonStopExecutor: safetyDistance and stopMargin must be finite and not negative");
            if (!notNegative(settings_.planningDelay) || !notNegative(settings_.cpuTimeScale))
                throw std::invalid_argument(
                    "NonStopExecutor: planningDelay and cpuTimeScale must be finite and not negative");
            if (settings_.retiming && (!positive(settings_.retimingHorizon) || !positive(settings_.retimingStep)))
                throw std::invalid_argument("NonStopExecutor: retimingHorizon and retimingStep must be positive");
            clearTiming();
            // Paper 002, Fig. 1: the planning thread is the executor's own; the caller's thread is the execution
            // thread. Started last, once every member it reads is set.
            thread_ = std::thread(
                [this]
                {
                    planningThread();
                });
        }

        NonStopExecutor::~NonStopExecutor()
        {
            {
                std::lock_guard<std::mutex> lock(mutex_);
                quit_ = true;
                // cancel_ makes a plan hook that is still running return, so join() does not wait for a whole planning
                // time.
                cancel_ = true;
            }
            cv_.notify_all();
            thread_.join();
        }

        const char *NonStopExecutor::name(ExecState s)
        {
            switch (s)
            {
                case ExecState::IDLE:
                    return "Idle";
                case ExecState::EXECUTE:
                    return "Execute";
                case ExecState::UPDATE_PROBLEM:
                    return "Update problem";
                case ExecState::REPLANNING:
                    return "Replanning";
                case ExecState::STOPPING:
                    return "Stopping";
                case ExecState::STOPPED:
                    return "Stopped";
                case ExecState::FINISHED:
                    return "Finished";
            }
            return "?";
        }

        const char *NonStopExecutor::name(PlanState s)
        {
            return s == PlanState::PLANNING ? "Planning" : "Wait query";
        }

        const char *NonStopExecutor::name(Signal s)
        {
            switch (s)
            {
                case Signal::START:
                    return "Start";
                case Signal::STOP:
                    return "Stop";
                case Signal::GEO_CHANGE:
                    return "Geo. change";
                case Signal::QUERY:
                    return "Query";
                case Signal::FINISHED:
                    return "Finished";
                case Signal::CANCELLED:
                    return "Cancelled";
                case Signal::PATH_FOUND:
                    return "Path found";
                case Signal::STEP:
                    return "Step";
            }
            return "?";
        }

        NonStopExecutor::PlanState NonStopExecutor::planState() const
        {
            std::lock_guard<std::mutex> lock(mutex_);
            return busy_ || !queries_.empty() ? PlanState::PLANNING : PlanState::WAIT_QUERY;
        }

        void NonStopExecutor::planningThread()
        {
            std::unique_lock<std::mutex> lock(mutex_);
            while (true)
            {
                cv_.wait(lock,
                         [this]
                         {
                             return quit_ || !queries_.empty();
                         });
                if (quit_)
                    return;
                Query query = std::move(queries_.front());
                queries_.pop_front();
                busy_ = true;
                // Reset under the lock before planning starts: a cancel for this query can only arrive after this point
                // and is seen by the plan hook through the same flag.
                cancel_ = false;
                // The hook runs without the lock, so the execution thread keeps stepping (and may cancel) while the
                // planner works.
                lock.unlock();

                Reply reply;
                reply.id = query.id;
                const auto begin = std::chrono::steady_clock::now();
                const double cpuBegin = threadCpuSeconds();
                reply.found = hooks_.plan(query.from, query.goal, query.snapshot, cancel_, reply.path);
                reply.cpuSeconds = threadCpuSeconds() - cpuBegin;
                reply.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();

                lock.lock();
                // A cancelled plan may still return a path found before it noticed: it answers a question nobody asks
                // any more.
                if (cancel_ || reply.path.empty())
                    reply.found = false;
                replies_.push_back(std::move(reply));
                busy_ = false;
                cv_.notify_all();
            }
        }

        void NonStopExecutor::waitForPlanner()
        {
            std::unique_lock<std::mutex> lock(mutex_);
            cv_.wait(lock,
                     [this]
                     {
                         return queries_.empty() && !busy_;
                     });
        }

        bool NonStopExecutor::waitForPlanner(double seconds)
        {
            std::unique_lock<std::mutex> lock(mutex_);
            return cv_.wait_for(lock, std::chrono::duration<double>(seconds),
                                [this]
                                {
                                    return queries_.empty() && !busy_;
                                });
        }

        void NonStopExecutor::transition(ExecState to, Signal signal)
        {
            transitions_.push_back(Transition{exec_, signal, to});
            exec_ = to;
        }

        void NonStopExecutor::sendQuery(const Configuration &from, double planStartArc)
        {
            cancelQuery();
            Query query;
            query.from = from;
            query.goal = goal_;
            query.snapshot = hooks_.sensedWorld ? hooks_.sensedWorld() : 0;
            {
                std::lock_guard<std::mutex> lock(mutex_);
                query.id = ++nextId_;
                activeQuery_ = query.id;
                activeSentAt_ = time_;
                queries_.push_back(std::move(query));
            }
            cv_.notify_all();
            // Synchronous mode (reproducible simulations): the query is planned to its end here, so a later cancel
            // never interrupts the planner at a point that depends on wall-clock time.
            if (settings_.synchronous)
                waitForPlanner();
            // Where on the current path the new path will be joined: onPathFound() keeps the current path up to this
            // arc.
            planStartArc_ = planStartArc;
            pendingPath_ = false;
            ++stats_.queries;
            // Query is an internal signal that does not change the execution state; it is logged as a self-transition
            // so the record follows Fig. 1's signals.
            transitions_.push_back(Transition{exec_, Signal::QUERY, exec_});
        }

        void NonStopExecutor::cancelQuery()
        {
            if (activeQuery_ == 0)
                return;
            {
                std::lock_guard<std::mutex> lock(mutex_);
                // a query still waiting is dropped; the one being planned is told to stop
                for (auto it = queries_.begin(); it != queries_.end();)
                {
                    if (it->id == activeQuery_)
                    {
                        // An empty reply (not found) for a dropped query keeps "every query gets one reply";
                        // takeReplies() ignores it because activeQuery_ no longer names it.
                        Reply reply;
                        reply.id = it->id;
                        replies_.push_back(std::move(reply));
                        it = queries_.erase(it);
                    }
                    else
                        ++it;
                }
                if (busy_)
                    cancel_ = true;
            }
            activeQuery_ = 0;
            pendingPath_ = false;
            ++stats_.cancelled;
        }

        double NonStopExecutor::pathLength() const
        {
            return arc_.empty() ? 0. : arc_.back();
        }

        void NonStopExecutor::setPath(ConfigurationPath path)
        {
            path_ = std::move(path);
            arc_.assign(path_.size(), 0.);
            // arc_[i]: the path length from the first waypoint to waypoint i; the robot's position is the arc s_
            // along it.
            for (std::size_t i = 1; i < path_.size(); ++i)
                arc_[i] = arc_[i - 1] + hooks_.distance(path_[i - 1], path_[i]);
            s_ = 0.;
            crossUntil_ = -1.;
            if (!path_.empty())
                current_ = path_.front();
            clearTiming();  // a new path, a new timing
        }

        Configuration NonStopExecutor::at(double s) const
        {
            if (path_.empty())
                return current_;
            if (s <= 0.)
                return path_.front();
            if (s >= arc_.back())
                return path_.back();
            const auto it = std::upper_bound(arc_.begin(), arc_.end(), s);
            const std::size_t i = static_cast<std::size_t>(it - arc_.begin());  // arc_[i-1] <= s < arc_[i]
            // Repeated waypoints give a zero-length piece: take its first end rather than divide by zero.
            const double length = arc_[i] - arc_[i - 1];
            Configuration q;
            hooks_.interpolate(path_[i - 1], path_[i], length > 0. ? (s - arc_[i - 1]) / length : 0., q);
            return q;
        }

        ConfigurationPath NonStopExecutor::segment(double a, double b) const
        {
            ConfigurationPath out;
            out.push_back(at(a));
            // Backwards (b < a) walks the waypoints in reverse: the joined path of onPathFound() may start behind the
            // robot after a stop overshoots the planned start.
            if (b > a)
            {
                for (std::size_t i = 0; i < path_.size(); ++i)
                    if (arc_[i] > a + EPS && arc_[i] < b - EPS)
                        out.push_back(path_[i]);
            }
            else
            {
                for (std::size_t i = path_.size(); i-- > 0;)
                    if (arc_[i] < a - EPS && arc_[i] > b + EPS)
                        out.push_back(path_[i]);
            }
            // A zero-length segment is the single state at(a), not the same state twice.
            if (std::fabs(b - a) > EPS)
                out.push_back(at(b));
            return out;
        }

        ConfigurationPath NonStopExecutor::remainingPath() const
        {
            return segment(s_, pathLength());
        }

        void NonStopExecutor::start(const Configuration &current, const Configuration &goal)
        {
            if (exec_ != ExecState::IDLE && exec_ != ExecState::FINISHED)
                throw std::logic_error("NonStopExecutor::start: already running");
            goal_ = goal;
            velocity_ = 0.;
            setPath({current});
            transition(ExecState::STOPPED, Signal::START);
            sendQuery(current, 0.);
        }

        void NonStopExecutor::stop()
        {
            cancelQuery();
            velocity_ = 0.;
            setPath({current_});
            transition(ExecState::IDLE, Signal::STOP);
        }

        void NonStopExecutor::geoChange()
        {
            if (exec_ == ExecState::IDLE || exec_ == ExecState::FINISHED)
                return;
            takeReplies();
            // Paper 002, "Update problem": the remaining path is checked against the changed world; hit is the arc
            // length (from the robot) to the first predicted interference, infinite when the path stays free.
            const double hit = hooks_.firstInterference(remainingPath());
            const bool free = std::isinf(hit);
            switch (exec_)
            {
                case ExecState::EXECUTE:
                {
                    transition(ExecState::UPDATE_PROBLEM, Signal::GEO_CHANGE);
                    if (free)
                    {
                        clearTiming();
                        transition(ExecState::EXECUTE, Signal::GEO_CHANGE);
                        return;
                    }
                    // Paper 002's temporal adaptation: the same path at another speed, or after a wait, may miss the
                    // moving obstacles in time; neither deformation nor the planner is needed then.
                    if (settings_.nonStop && retime())
                    {
                        transition(ExecState::EXECUTE, Signal::GEO_CHANGE);
                        return;
                    }
                    if (!settings_.nonStop)
                    {
                        // stop and replan: brake now, the query goes when the robot stands (step())
                        stopArc_ = s_;
                        transition(ExecState::STOPPING, Signal::GEO_CHANGE);
                        return;
                    }
                    // Braking needs the braking distance of the speed the robot will have then, and stopMargin keeps
                    // the stop short of the interference: the robot can run on for room before it must start to brake,
                    // which is the time the planner gets.
                    const double room = roomBeforeBraking(hit - settings_.stopMargin);
                    if (room <= EPS)
                    {
                        // A stop here would leave the robot in (or at) an obstacle's predicted region, in its way: a
                        // crossing at full speed that is free in time goes first.
                        const double after = crossing();
                        if (std::isinf(after))
                        {
                            transition(ExecState::EXECUTE, Signal::GEO_CHANGE);
                            return;
                        }
                        if (after > EPS)
                        {
                            stopArc_ = crossUntil_ + after;
                            transition(ExecState::REPLANNING, Signal::GEO_CHANGE);
                            sendQuery(at(stopArc_), stopArc_);
                            return;
                        }
                    }
                    // Paper 002, Fig. 3: small interference is first handled by deforming the path, without calling the
                    // roadmap.
                    if (hooks_.deform)
                    {
                        ConfigurationPath deformed = remainingPath();
                        if (hooks_.deform(deformed))
                        {
                            setPath(std::move(deformed));
                            ++stats_.deformations;
                            transition(ExecState::EXECUTE, Signal::GEO_CHANGE);
                            return;
                        }
                    }
                    crossUntil_ = -1.;
                    if (room > EPS)
                    {
                        // replan from the point where a safe stop would begin, and keep moving until there
                        stopArc_ = s_ + room;
                        transition(ExecState::REPLANNING, Signal::GEO_CHANGE);
                        sendQuery(at(stopArc_), stopArc_);
                    }
                    else
                    {
                        // too close already: brake now and plan from where the robot will stand
                        stopArc_ = s_;
                        const double stand = std::min(pathLength(), s_ + brakingDistance());
                        transition(ExecState::STOPPING, Signal::GEO_CHANGE);
                        sendQuery(at(stand), stand);
                    }
                    return;
                }
                case ExecState::REPLANNING:
                case ExecState::STOPPING:
                case ExecState::STOPPED:
                    // the predicted interference is gone, or (retiming) the original path misses the obstacles at a
                    // slower speed or after a wait: cancel replanning, go on with the original path. A robot standing
                    // at the end of a path that stops short of the goal has nothing to go on with: its query stays
                    // (cancelling it on every observation starved a planner slower than the sensor's period).
                    if ((free && pathLength() - s_ > EPS) || (settings_.nonStop && retime()))
                    {
                        if (free)
                            clearTiming();
                        cancelQuery();
                        transitions_.push_back(Transition{exec_, Signal::CANCELLED, exec_});
                        transition(ExecState::EXECUTE, Signal::GEO_CHANGE);
                        return;
                    }
                    // The obstacle may have come closer while planning: the stop point only ever moves nearer,
                    // unless a stop now would leave the robot in an obstacle's way and a crossing is free in time
                    // (the stop point moves to after the crossing, and the query with it).
                    if (exec_ == ExecState::REPLANNING)
                    {
                        const double room = roomBeforeBraking(hit - settings_.stopMargin);
                        const double after = room <= EPS && settings_.nonStop ? crossing() : -1.;
                        if (std::isinf(after))
                        {
                            // the crossing leads onto a free path: the query is not needed any more
                            cancelQuery();
                            transitions_.push_back(Transition{exec_, Signal::CANCELLED, exec_});
                            transition(ExecState::EXECUTE, Signal::GEO_CHANGE);
                            return;
                        }
                        if (after > EPS)
                        {
                            stopArc_ = crossUntil_ + after;
                            // a query from inside the crossing would be answered with a path joined there
                            if (planStartArc_ < crossUntil_ - EPS)
                                sendQuery(at(stopArc_), stopArc_);
                        }
                        else if (room < stopArc_ - s_ - EPS)
                        {
                            stopArc_ = s_ + std::max(0., room);
                            crossUntil_ = -1.;
                        }
                    }
                    if (exec_ == ExecState::STOPPED && activeQuery_ == 0)
                        sendQuery(current_, s_);
                    return;
                default:
                    return;
            }
        }

        void NonStopExecutor::takeReplies()
        {
            std::deque<Reply> replies;
            {
                std::lock_guard<std::mutex> lock(mutex_);
                replies.swap(replies_);
            }
            for (auto &reply : replies)
            {
                if (reply.id != activeQuery_)
                    continue;  // a cancelled query's answer
                // planningDelay charges simulated time for planning, so results do not depend on how fast this machine
                // plans; cpuTimeScale adds what the planner really spent, so a slow planner costs the robot time.
                const double due = activeSentAt_ + settings_.planningDelay + settings_.cpuTimeScale * reply.cpuSeconds;
                if (time_ < due - EPS)
                {
                    // not yet due on the simulated clock: keep it for a later step
                    std::lock_guard<std::mutex> lock(mutex_);
                    replies_.push_front(std::move(reply));
                    continue;
                }
                activeQuery_ = 0;
                if (!reply.found)
                {
                    ++stats_.failures;
                    transitions_.push_back(Transition{exec_, Signal::CANCELLED, exec_});
                    // try again: from the robot when it stands, else from the stop point
                    // A retry starts from where the robot will be when it could take the new path, as the first query
                    // did.
                    if (exec_ == ExecState::STOPPED)
                        sendQuery(current_, s_);
                    else if (exec_ == ExecState::REPLANNING)
                        sendQuery(at(stopArc_), stopArc_);
                    else if (exec_ == ExecState::STOPPING)
                        sendQuery(at(std::min(pathLength(), s_ + brakingDistance())),
                                  std::min(pathLength(), s_ + brakingDistance()));
                    continue;
                }
                stats_.latencies.push_back(reply.seconds);
                stats_.cpuLatencies.push_back(reply.cpuSeconds);
                onPathFound(reply);
            }
        }

        void NonStopExecutor::onPathFound(Reply &reply)
        {
            if (exec_ == ExecState::STOPPING)
            {
                // finish the stop first (the new path may start behind the robot)
                pendingPath_ = true;
                pending_ = std::move(reply.path);
                return;
            }
            // The new path starts at the replanning start (the stop point): the robot keeps the old path up to there
            // and goes on with the new one, so it never has to stand still for the planner.
            ConfigurationPath candidate = segment(s_, planStartArc_);
            for (std::size_t i = 1; i < reply.path.size(); ++i)
                candidate.push_back(reply.path[i]);
            // A one-state plan: the robot is already where the planner started, so that state is the whole
            // continuation.
            if (reply.path.size() == 1)
                candidate.push_back(reply.path[0]);
            ++stats_.pathsFound;
            // The planner saw the world as it was when the query was sent; the obstacles may have moved since.
            double hit = hooks_.firstInterference(candidate);
            double crossEnd = -1.;
            if (!std::isinf(hit) && exec_ == ExecState::REPLANNING && crossUntil_ > s_ + EPS &&
                planStartArc_ >= crossUntil_ - EPS)
            {
                // The robot is crossing a predicted region, a motion checked in time (crossing()) that the new path
                // keeps: the new path must be free from where the crossing ends.
                ConfigurationPath rest = segment(crossUntil_, planStartArc_);
                rest.insert(rest.end(), reply.path.begin() + 1, reply.path.end());
                hit = hooks_.firstInterference(rest);
                crossEnd = crossUntil_ - s_;
            }
            if (!std::isinf(hit))
            {
                // the world moved on while planning: ask again
                transitions_.push_back(Transition{exec_, Signal::PATH_FOUND, exec_});
                if (exec_ == ExecState::REPLANNING)
                    sendQuery(at(stopArc_), stopArc_);
                else if (exec_ == ExecState::STOPPED)
                    sendQuery(current_, s_);
                return;
            }
            setPath(std::move(candidate));
            crossUntil_ = crossEnd;  // the crossing goes on along the new path (it starts at the robot)
            transition(ExecState::EXECUTE, Signal::PATH_FOUND);
        }

        bool NonStopExecutor::mustBrake(double s, double v, double dt) const
        {
            // advance() lowers the speed before it moves, so braking from v covers v^2 / (2 a) - v dt / 2: a robot
            // that starts to brake before the stop point stands within the braking distance the stop point left
            return s + v * dt >= stopArc_ - EPS;
        }

        void NonStopExecutor::step(double dt)
        {
            time_ += dt;
            if (exec_ == ExecState::IDLE || exec_ == ExecState::FINISHED)
                return;
            takeReplies();
            // a wait holds the steps that begin before its end (as retime() and preview() count them)
            advance(exec_, s_, velocity_, dt, speedCap_, time_ - dt < holdUntil_);
            current_ = at(s_);

            if (exec_ == ExecState::EXECUTE && s_ >= pathLength() - EPS)
            {
                velocity_ = 0.;
                cancelQuery();
                // The path's end is the goal only for a complete plan; 1e-6 absorbs interpolation rounding at the end
                // of the path.
                if (hooks_.distance(current_, goal_) <= 1e-6)
                {
                    transition(ExecState::FINISHED, Signal::FINISHED);
                    return;
                }
                // the end of a partial path (an escape that did not reach the goal): wait there for a path
                transition(ExecState::STOPPED, Signal::STEP);
                sendQuery(current_, s_);
                return;
            }
            // Paper 002: keep moving while replanning unless the robot comes closer than the safety distance or
            // reaches the point where braking must begin.
            // A crossing (crossing()) was checked in time against the obstacles' motion: braking in it
            // because one is near would stop the robot in its way.
            if (exec_ == ExecState::REPLANNING &&
                (mustBrake(s_, velocity_, dt) ||
                 (s_ >= crossUntil_ && hooks_.clearance(current_) < settings_.safetyDistance)))
                transition(ExecState::STOPPING, Signal::STEP);
            if (exec_ == ExecState::STOPPING && velocity_ <= 0.)
            {
                ++stats_.stops;
                transition(ExecState::STOPPED, Signal::STEP);
                if (pendingPath_)
                {
                    pendingPath_ = false;
                    Reply reply;
                    reply.path = std::move(pending_);
                    onPathFound(reply);
                }
                else if (activeQuery_ == 0)
                    sendQuery(current_, s_);
            }
        }
        void NonStopExecutor::advance(ExecState state, double &s, double &v, double dt, double cap, bool hold) const
        {
            const double length = pathLength();
            switch (state)
            {
                case ExecState::EXECUTE:
                case ExecState::REPLANNING:
                {
                    // Towards the cruise speed (a retiming's cap, 0 while it waits), speeding up and slowing down at
                    // the deceleration's rate: one rate, so braking distances and start-up are symmetric.
                    const double target = hold ? 0. : std::min(settings_.speed, cap);
                    v = v < target ? std::min(target, v + settings_.deceleration * dt)
                                   : std::max(target, v - settings_.deceleration * dt);
                    // At most the speed from which the robot still stops at the path's end, losing deceleration x dt
                    // per step of this length: n such steps cover a dt^2 n (n + 1) / 2, so v = n a dt with n solving
                    // that for the distance left. It arrives braked, within a step or two of a dt (two when a
                    // measured robot moved the model between steps, track()).
                    if (settings_.brakeAtEnd && dt > 0.)
                    {
                        const double unit = settings_.deceleration * dt * dt;
                        const double n = 0.5 * (std::sqrt(1. + 8. * std::max(0., length - s) / unit) - 1.);
                        // and no faster than lands on the end in this step
                        v = std::min({v, n * settings_.deceleration * dt, std::max(0., length - s) / dt});
                    }
                    break;
                }
                case ExecState::STOPPING:
                    v = std::max(0., v - settings_.deceleration * dt);
                    break;
                default:
                    v = 0.;
            }
            // Explicit Euler on the arc length; clamped so a large dt never runs past the path's end.
            s = std::min(length, s + v * dt);
        }

        bool NonStopExecutor::retime()
        {
            if (!settings_.retiming || !hooks_.freeInTime || pathLength() - s_ <= EPS)
                return false;
            // Fastest first: full speed (the obstacle may pass before the robot comes), slower, then waits.
            struct Timing
            {
                double cap, wait;
            };
            static const Timing timings[] = {{1., 0.},  {0.75, 0.}, {0.5, 0.}, {0.25, 0.},
                                             {1., 0.5}, {1., 1.},   {1., 2.},  {1., 4.}};
            const double step = settings_.retimingStep;
            const int samples = std::max(1, static_cast<int>(std::ceil(settings_.retimingHorizon / step - 1e-9)));
            ConfigurationPath configurations;
            std::vector<double> times;
            for (const Timing &timing : timings)
            {
                const double cap = timing.cap * settings_.speed;
                double s = s_, v = velocity_;
                configurations.assign(1, current_);
                times.assign(1, 0.);
                for (int i = 1; i <= samples && s < pathLength() - EPS; ++i)
                {
                    advance(ExecState::EXECUTE, s, v, step, cap, step * (i - 1) < timing.wait);
                    configurations.push_back(at(s));
                    times.push_back(step * i);
                }
                // Accepted only if it takes the robot past every predicted interference within the horizon (the
                // rest of the path from where it then is meets none), and misses the obstacles on the way in time: a
                // crawl that merely has not reached a standing obstacle by the horizon is no timing.
                if (std::isinf(hooks_.firstInterference(segment(s, pathLength()))) &&
                    hooks_.freeInTime(configurations, times))
                {
                    speedCap_ = cap;
                    holdUntil_ = time_ + timing.wait;
                    ++stats_.retimings;
                    return true;
                }
            }
            return false;
        }

        double NonStopExecutor::crossing()
        {
            crossUntil_ = -1.;
            if (!settings_.retiming || !hooks_.freeInTime)
                return -1.;
            const double step = settings_.retimingStep;
            const int samples = std::max(1, static_cast<int>(std::ceil(settings_.retimingHorizon / step - 1e-9)));
            ConfigurationPath configurations{current_};
            std::vector<double> times{0.};
            double s = s_, v = velocity_;
            for (int i = 1; i <= samples && s < pathLength() - EPS; ++i)
            {
                advance(ExecState::EXECUTE, s, v, step, settings_.speed, false);
                configurations.push_back(at(s));
                times.push_back(step * i);
                // Out of every predicted region once a stop fits before the next interference: the crossing ends here
                // and the planner gets until that stop, as after any Geo. change.
                const double room = hooks_.firstInterference(segment(s, pathLength())) - settings_.stopMargin -
                                    v * v / (2. * settings_.deceleration);
                if (room > EPS)
                {
                    if (!hooks_.freeInTime(configurations, times))
                        return -1.;
                    crossUntil_ = s;
                    clearTiming();
                    return std::isinf(room) ? room : std::min(room, pathLength() - s);
                }
            }
            return -1.;
        }

        bool NonStopExecutor::track(const Configuration &measured, double tolerance)
        {
            if (!(tolerance > 0.))
                throw std::invalid_argument("NonStopExecutor::track: the tolerance must be positive");
            if (exec_ == ExecState::IDLE || path_.empty())
            {
                setPath({measured});  // held where it is (preview() commands the path's states)
                return true;
            }
            // The robot may lag or lead the model (it is not the model): it is looked for along the arcs it can
            // have covered in a second at cruise speed, beyond the tolerance, either side of the model's position;
            // first every quarter tolerance, then by golden sections round the nearest sample.
            const double window = tolerance + settings_.speed;
            const double a = std::max(0., s_ - window), b = std::min(pathLength(), s_ + window);
            const int n = std::clamp(static_cast<int>(std::ceil((b - a) / (0.25 * tolerance))), 1, 64);
            const double h = (b - a) / n;
            double best = s_, bestDistance = hooks_.distance(measured, at(s_));
            for (int i = 0; i <= n; ++i)
            {
                const double arc = a + h * i;
                const double d = hooks_.distance(measured, at(arc));
                if (d < bestDistance)
                {
                    bestDistance = d;
                    best = arc;
                }
            }
            double lo = std::max(a, best - h), hi = std::min(b, best + h);
            const double ratio = 0.5 * (std::sqrt(5.) - 1.);
            for (int i = 0; i < 24 && hi - lo > EPS; ++i)
            {
                const double m1 = hi - ratio * (hi - lo), m2 = lo + ratio * (hi - lo);
                if (hooks_.distance(measured, at(m1)) <= hooks_.distance(measured, at(m2)))
                    hi = m2;
                else
                    lo = m1;
            }
            const double refined = 0.5 * (lo + hi);
            const double refinedDistance = hooks_.distance(measured, at(refined));
            if (refinedDistance < bestDistance)
            {
                bestDistance = refinedDistance;
                best = refined;
            }
            if (bestDistance <= tolerance)
            {
                // The model may have reached the goal before the robot (a robot slower than commanded): the goal is
                // reached when the robot is within the tolerance of it, until then the path goes on.
                if (exec_ == ExecState::FINISHED)
                {
                    if (hooks_.distance(measured, goal_) <= tolerance)
                        return true;
                    transition(ExecState::EXECUTE, Signal::STEP);
                }
                s_ = best;
                current_ = at(s_);
                return true;
            }
            ++stats_.offPath;
            // Waiting for a path from where it stood: the query goes on (the answer is joined from the measured
            // state, whose motion to the new path is checked like every new path's).
            if (exec_ == ExecState::STOPPED && path_.size() == 1 && activeQuery_ != 0)
            {
                setPath({measured});
                return false;
            }
            // Off the path: nothing the executor planned starts where the robot is. Plan again from there.
            cancelQuery();
            velocity_ = 0.;
            setPath({measured});
            transition(ExecState::STOPPED, Signal::STEP);
            sendQuery(measured, 0.);
            return false;
        }

        TimedPath NonStopExecutor::preview(double horizon, double period) const
        {
            if (!(period > 0.) || !(horizon >= 0.))
                throw std::invalid_argument(
                    "NonStopExecutor::preview: the period must be positive, the horizon not "
                    "negative");
            TimedPath out;
            ExecState state = exec_;
            double s = s_, v = velocity_;
            const int samples = static_cast<int>(std::floor(horizon / period + 1e-9));
            out.times.reserve(static_cast<std::size_t>(samples) + 1);
            out.configurations.reserve(static_cast<std::size_t>(samples) + 1);
            out.speeds.reserve(static_cast<std::size_t>(samples) + 1);
            out.times.push_back(0.);
            out.configurations.push_back(current_);
            out.speeds.push_back(v);
            for (int i = 1; i <= samples; ++i)
            {
                advance(state, s, v, period, speedCap_, time_ + period * i - period < holdUntil_);
                // the transitions of step() that follow from the motion alone
                if (state == ExecState::REPLANNING && mustBrake(s, v, period))
                    state = ExecState::STOPPING;
                if ((state == ExecState::STOPPING && v <= 0.) ||
                    (state == ExecState::EXECUTE && s >= pathLength() - EPS))
                {
                    state = ExecState::STOPPED;
                    v = 0.;
                }
                out.times.push_back(period * i);
                out.configurations.push_back(at(s));
                out.speeds.push_back(v);
            }
            return out;
        }
    }  // namespace planners
}  // namespace michi
