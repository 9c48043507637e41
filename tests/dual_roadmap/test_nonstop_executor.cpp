// Tests of michi::planners::NonStopExecutor (paper 002, Fig. 1): every transition of the execution state machine,
// driven by a simulated clock the test controls and a planner the test releases. The world is the plane: the robot is a
// point moving from (0, 0) to (10, 0); obstacles are boxes the test puts down and removes; the planner's path makes
// a detour through y = 2. Nothing here depends on timing (the planner thread is waited for, never raced against).
// Also built with -fsanitize=thread (CMake option MICHI_TSAN, see docs/dual-roadmap.md).
#include <michi/planners/dual_roadmap/NonStopExecutor.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <limits>
#include <mutex>

#include <time.h>

using michi::planners::Configuration;
using michi::planners::ConfigurationPath;
using michi::planners::NonStopExecutor;
using Exec = NonStopExecutor::ExecState;
using Sig = NonStopExecutor::Signal;

namespace
{
    struct Box
    {
        double x0, x1, y0, y1;
    };

    /** A planner the test holds until it says how the query ends. */
    struct Gate
    {
        std::mutex mutex;
        std::condition_variable cv;
        int released{0};     // number of queries allowed to finish
        bool succeed{true};  // how they finish
        int started{0};      // queries that reached the planner
        int sawCancel{0};    // queries that ended because they were cancelled
    };

    /** A disc moving along y at constant speed: at absolute time T its centre is (x, y0 + vy T); gone after
        \e until. */
    struct Crosser
    {
        double x, y0, vy, r;
        double until{std::numeric_limits<double>::infinity()};
    };

    struct World
    {
        std::vector<Box> boxes;  ///< what the spatial checks see (a crosser's predicted region is a box too)
        std::vector<Crosser> crossers;
        double now{0.};  ///< advanced by Harness::steps

        bool freeAt(const Configuration &q, double time) const
        {
            for (const auto &c : crossers)
                if (time <= c.until && std::hypot(q[0] - c.x, q[1] - (c.y0 + c.vy * time)) <= c.r)
                    return false;
            return true;
        }

        static double boxDistance(const Box &b, const Configuration &q)
        {
            const double dx = std::max({b.x0 - q[0], 0., q[0] - b.x1});
            const double dy = std::max({b.y0 - q[1], 0., q[1] - b.y1});
            return std::hypot(dx, dy);
        }
        double clearance(const Configuration &q) const
        {
            double d = std::numeric_limits<double>::infinity();
            for (const auto &b : boxes)
                d = std::min(d, boxDistance(b, q));
            return d;
        }
    };

    struct Harness
    {
        World world;
        Gate gate;
        std::unique_ptr<NonStopExecutor> exec;
        bool deformOk{false};
        int deformCalls{0};
        double burn{0.};  ///< CPU seconds the planner spends (spinning on its thread CPU clock) before it answers

        static double threadCpu()
        {
            timespec ts{};
            clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
            return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
        }

        explicit Harness(double safety = 0., double planningDelay = 0., bool synchronous = false,
                         double cpuTimeScale = 0.,
                         const std::function<void(michi::planners::NonStopSettings &)> &configure = {})
        {
            michi::planners::NonStopHooks hooks;
            hooks.distance = [](const Configuration &a, const Configuration &b)
            {
                return std::hypot(a[0] - b[0], a[1] - b[1]);
            };
            hooks.interpolate = [](const Configuration &a, const Configuration &b, double t, Configuration &out)
            {
                out = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
            };
            hooks.clearance = [this](const Configuration &q)
            {
                return world.clearance(q);
            };
            hooks.firstInterference = [this](const ConfigurationPath &path)
            {
                double arc = 0.;
                for (std::size_t i = 0; i + 1 < path.size(); ++i)
                {
                    const double len = std::hypot(path[i + 1][0] - path[i][0], path[i + 1][1] - path[i][1]);
                    const int n = std::max(1, static_cast<int>(len / 0.01));
                    for (int k = 0; k <= n; ++k)
                    {
                        const double t = static_cast<double>(k) / n;
                        const Configuration q{path[i][0] + t * (path[i + 1][0] - path[i][0]),
                                              path[i][1] + t * (path[i + 1][1] - path[i][1])};
                        if (world.clearance(q) <= 0.)
                            return arc + t * len;
                    }
                    arc += len;
                }
                return std::numeric_limits<double>::infinity();
            };
            hooks.deform = [this](ConfigurationPath &path)
            {
                ++deformCalls;
                if (!deformOk)
                    return false;
                // "deformed": a dent down to y = 1.7 between 1.5 m and 3 m ahead of the robot
                const double x0 = path.front()[0];
                path.insert(path.begin() + 1, {{x0 + 1.5, 2.}, {x0 + 1.8, 1.7}, {x0 + 2.7, 1.7}, {x0 + 3., 2.}});
                return true;
            };
            hooks.plan = [this](const Configuration &from, const Configuration &goal, std::uint64_t,
                                const std::atomic<bool> &cancel, ConfigurationPath &path)
            {
                std::unique_lock<std::mutex> lock(gate.mutex);
                ++gate.started;
                gate.cv.notify_all();
                while (gate.released == 0 && !cancel)
                    gate.cv.wait_for(lock, std::chrono::milliseconds(1));
                if (cancel)
                {
                    ++gate.sawCancel;
                    return false;
                }
                --gate.released;
                // real work, not a sleep: only CPU time is charged (cpuTimeScale)
                for (const double end = threadCpu() + burn; threadCpu() < end;)
                {
                }
                if (!gate.succeed)
                    return false;
                // a detour 2 m to the side of where the query starts
                path = {from, {from[0], from[1] + 2.}, {goal[0], from[1] + 2.}, goal};
                return true;
            };
            hooks.sensedWorld = []
            {
                return std::uint64_t(0);
            };
            hooks.freeInTime = [this](const ConfigurationPath &configurations, const std::vector<double> &times)
            {
                for (std::size_t k = 0; k < configurations.size(); ++k)
                    if (!world.freeAt(configurations[k], world.now + times[k]))
                        return false;
                return true;
            };
            michi::planners::NonStopSettings settings;
            settings.speed = 1.;
            settings.deceleration = 2.;  // braking distance at full speed: 0.25
            settings.safetyDistance = safety;
            settings.stopMargin = 0.1;
            settings.planningDelay = planningDelay;
            settings.synchronous = synchronous;
            settings.cpuTimeScale = cpuTimeScale;
            if (configure)
                configure(settings);
            exec = std::make_unique<NonStopExecutor>(hooks, settings);
        }

        /** Let one query finish (found or failed) and wait until its answer is queued. */
        void release(bool succeed = true)
        {
            {
                std::lock_guard<std::mutex> lock(gate.mutex);
                gate.released = 1;
                gate.succeed = succeed;
            }
            gate.cv.notify_all();
            exec->waitForPlanner();
        }
        void waitStarted(int n)
        {
            std::unique_lock<std::mutex> lock(gate.mutex);
            gate.cv.wait(lock,
                         [&]
                         {
                             return gate.started >= n;
                         });
        }
        void steps(int n, double dt = 0.01)
        {
            for (int i = 0; i < n; ++i)
            {
                world.now += dt;
                exec->step(dt);
            }
        }
        /** Start and get going on the straight path (the first query answered by a straight line). */
        void startStraight()
        {
            // the first path: straight, since nothing is in the way the planner's detour is not wanted: give a
            // box-free world and then replace the path by the direct one through a free Geo. change
            exec->start({0., 0.}, {10., 0.});
            release();
            exec->step(0.01);
        }
        /** Start on the planner's path (up to (0, 2), along y = 2, down to (10, 0)) and drive 3 s: at full speed
            along y = 2, near x = 0.75. Returns the robot's x. */
        double underWay()
        {
            startStraight();
            steps(300);
            return exec->configuration()[0];
        }
        bool saw(Exec from, Sig signal, Exec to) const
        {
            for (const auto &t : exec->transitions())
                if (t.from == from && t.signal == signal && t.to == to)
                    return true;
            return false;
        }
    };
}  // namespace

TEST(NonStopExecutor, StartPathFoundExecuteFinished)
{
    Harness h;
    EXPECT_EQ(h.exec->execState(), Exec::IDLE);
    h.exec->start({0., 0.}, {10., 0.});
    EXPECT_EQ(h.exec->execState(), Exec::STOPPED);
    EXPECT_TRUE(h.saw(Exec::IDLE, Sig::START, Exec::STOPPED));
    EXPECT_TRUE(h.saw(Exec::STOPPED, Sig::QUERY, Exec::STOPPED));
    h.waitStarted(1);
    EXPECT_EQ(h.exec->planState(), NonStopExecutor::PlanState::PLANNING);
    h.steps(10);
    EXPECT_EQ(h.exec->execState(), Exec::STOPPED) << "no path yet: the robot waits";
    EXPECT_EQ(h.exec->configuration(), (Configuration{0., 0.}));
    h.release();
    EXPECT_EQ(h.exec->planState(), NonStopExecutor::PlanState::WAIT_QUERY);
    h.exec->step(0.01);
    EXPECT_EQ(h.exec->execState(), Exec::EXECUTE);
    EXPECT_TRUE(h.saw(Exec::STOPPED, Sig::PATH_FOUND, Exec::EXECUTE));
    h.steps(20000);
    EXPECT_EQ(h.exec->execState(), Exec::FINISHED);
    EXPECT_TRUE(h.saw(Exec::EXECUTE, Sig::FINISHED, Exec::FINISHED));
    EXPECT_NEAR(h.exec->configuration()[0], 10., 1e-9);
    EXPECT_NEAR(h.exec->configuration()[1], 0., 1e-9);
    EXPECT_EQ(h.exec->statistics().latencies.size(), 1u);
}

TEST(NonStopExecutor, GeoChangeWithFreePathGoesBackToExecute)
{
    Harness h;
    h.startStraight();
    h.world.boxes.push_back({3., 4., 5., 6.});  // far from the path (which runs along y = 2)
    h.exec->geoChange();
    EXPECT_TRUE(h.saw(Exec::EXECUTE, Sig::GEO_CHANGE, Exec::UPDATE_PROBLEM));
    EXPECT_TRUE(h.saw(Exec::UPDATE_PROBLEM, Sig::GEO_CHANGE, Exec::EXECUTE));
    EXPECT_EQ(h.exec->execState(), Exec::EXECUTE);
    EXPECT_EQ(h.exec->statistics().queries, 1u);
}

TEST(NonStopExecutor, InterferenceStartsReplanningFromTheStopPointWhileMoving)
{
    Harness h;
    const double x0 = h.underWay();
    h.world.boxes.push_back({x0 + 2., x0 + 3., 1.5, 2.5});  // 2 m ahead on the path
    h.exec->geoChange();
    EXPECT_EQ(h.exec->execState(), Exec::REPLANNING);
    EXPECT_TRUE(h.saw(Exec::UPDATE_PROBLEM, Sig::GEO_CHANGE, Exec::REPLANNING));
    EXPECT_EQ(h.exec->statistics().queries, 2u);
    h.steps(50);
    EXPECT_EQ(h.exec->execState(), Exec::REPLANNING) << "keeps moving while the planner works";
    EXPECT_GT(h.exec->velocity(), 0.9);
    h.release();
    h.exec->step(0.01);
    EXPECT_EQ(h.exec->execState(), Exec::EXECUTE);
    EXPECT_TRUE(h.saw(Exec::REPLANNING, Sig::PATH_FOUND, Exec::EXECUTE));
    // the new path avoids the box all the way to the goal
    for (int i = 0; i < 30000 && h.exec->execState() != Exec::FINISHED; ++i)
    {
        h.exec->step(0.01);
        ASSERT_GT(h.world.clearance(h.exec->configuration()), 0.) << "step " << i;
    }
    EXPECT_EQ(h.exec->execState(), Exec::FINISHED);
    EXPECT_EQ(h.exec->statistics().stops, 0u);
}

TEST(NonStopExecutor, InterferenceGoneWhileReplanningCancelsAndContinues)
{
    Harness h;
    const double x0 = h.underWay();
    h.world.boxes.push_back({x0 + 2., x0 + 3., 1.5, 2.5});
    h.exec->geoChange();
    ASSERT_EQ(h.exec->execState(), Exec::REPLANNING);
    h.waitStarted(2);
    h.world.boxes.clear();
    h.exec->geoChange();
    EXPECT_EQ(h.exec->execState(), Exec::EXECUTE);
    EXPECT_TRUE(h.saw(Exec::REPLANNING, Sig::CANCELLED, Exec::REPLANNING));
    EXPECT_TRUE(h.saw(Exec::REPLANNING, Sig::GEO_CHANGE, Exec::EXECUTE));
    h.exec->waitForPlanner();
    EXPECT_EQ(h.gate.sawCancel, 1) << "the planner was told to stop";
    EXPECT_EQ(h.exec->remainingPath().back(), (Configuration{10., 0.})) << "original path kept";
    h.steps(30000);
    EXPECT_EQ(h.exec->execState(), Exec::FINISHED);
}

TEST(NonStopExecutor, NoPathByTheStopPointDeceleratesStopsAndResumes)
{
    Harness h;
    const double x0 = h.underWay();
    h.world.boxes.push_back({x0 + 2., x0 + 3., 1.5, 2.5});
    h.exec->geoChange();
    ASSERT_EQ(h.exec->execState(), Exec::REPLANNING);
    // stop point: 2 - 0.1 (margin) - 0.25 (braking) = 1.65 m ahead
    h.steps(170);
    EXPECT_EQ(h.exec->execState(), Exec::STOPPING);
    EXPECT_TRUE(h.saw(Exec::REPLANNING, Sig::STEP, Exec::STOPPING));
    h.steps(60);
    EXPECT_EQ(h.exec->execState(), Exec::STOPPED);
    EXPECT_TRUE(h.saw(Exec::STOPPING, Sig::STEP, Exec::STOPPED));
    EXPECT_EQ(h.exec->velocity(), 0.);
    EXPECT_GT(h.world.clearance(h.exec->configuration()), 0.05) << "stopped before the obstacle";
    EXPECT_EQ(h.exec->statistics().stops, 1u);
    h.release();
    h.exec->step(0.01);
    EXPECT_EQ(h.exec->execState(), Exec::EXECUTE);
    h.steps(30000);
    EXPECT_EQ(h.exec->execState(), Exec::FINISHED);
}

TEST(NonStopExecutor, PathFoundWhileStoppingIsTakenOnceStopped)
{
    Harness h;
    const double x0 = h.underWay();
    h.world.boxes.push_back({x0 + 2., x0 + 3., 1.5, 2.5});
    h.exec->geoChange();
    h.steps(172);
    ASSERT_EQ(h.exec->execState(), Exec::STOPPING);
    h.release();
    h.exec->step(0.01);
    EXPECT_EQ(h.exec->execState(), Exec::STOPPING);
    h.steps(60);
    EXPECT_TRUE(h.saw(Exec::STOPPED, Sig::PATH_FOUND, Exec::EXECUTE));
    h.steps(30000);
    EXPECT_EQ(h.exec->execState(), Exec::FINISHED);
}

TEST(NonStopExecutor, CloserThanSafetyDistanceStops)
{
    Harness h(0.5);
    const double x0 = h.underWay();
    h.world.boxes.push_back({x0 + 3., x0 + 4., 1.5, 2.5});
    h.exec->geoChange();
    ASSERT_EQ(h.exec->execState(), Exec::REPLANNING);
    // an obstacle comes up beside the robot (not on the path)
    h.world.boxes.push_back({x0 + 0.5, x0 + 0.7, 2.3, 2.5});
    h.steps(30);
    EXPECT_EQ(h.exec->execState(), Exec::STOPPING);
    h.steps(100);
    EXPECT_EQ(h.exec->execState(), Exec::STOPPED);
    h.exec->stop();
    EXPECT_TRUE(h.saw(Exec::STOPPED, Sig::STOP, Exec::IDLE));
}

TEST(NonStopExecutor, TooCloseToTheInterferenceBrakesAtOnce)
{
    Harness h;
    const double x0 = h.underWay();
    h.world.boxes.push_back({x0 + 0.3, x0 + 1., 1.5, 2.5});
    h.exec->geoChange();
    EXPECT_TRUE(h.saw(Exec::UPDATE_PROBLEM, Sig::GEO_CHANGE, Exec::STOPPING));
    h.steps(100);
    EXPECT_EQ(h.exec->execState(), Exec::STOPPED);
    EXPECT_GT(h.world.clearance(h.exec->configuration()), 0.);
}

TEST(NonStopExecutor, InterferenceGoneWhileStoppingOrStoppedContinues)
{
    for (const bool waitUntilStopped : {false, true})
    {
        Harness h;
        const double x0 = h.underWay();
        h.world.boxes.push_back({x0 + 0.3, x0 + 1., 1.5, 2.5});
        h.exec->geoChange();
        ASSERT_EQ(h.exec->execState(), Exec::STOPPING);
        if (waitUntilStopped)
            h.steps(100);
        const Exec before = h.exec->execState();
        EXPECT_EQ(before, waitUntilStopped ? Exec::STOPPED : Exec::STOPPING);
        h.world.boxes.clear();
        h.exec->geoChange();
        EXPECT_TRUE(h.saw(before, Sig::GEO_CHANGE, Exec::EXECUTE));
        h.steps(30000);
        EXPECT_EQ(h.exec->execState(), Exec::FINISHED);
    }
}

TEST(NonStopExecutor, SmallInterferenceIsDeformedWithoutAQuery)
{
    Harness h;
    h.deformOk = true;
    const double x0 = h.underWay();
    h.world.boxes.push_back({x0 + 2., x0 + 2.5, 1.9, 2.5});
    h.exec->geoChange();
    EXPECT_EQ(h.deformCalls, 1);
    EXPECT_EQ(h.exec->execState(), Exec::EXECUTE);
    EXPECT_TRUE(h.saw(Exec::UPDATE_PROBLEM, Sig::GEO_CHANGE, Exec::EXECUTE));
    EXPECT_EQ(h.exec->statistics().deformations, 1u);
    EXPECT_EQ(h.exec->statistics().queries, 1u);
    h.steps(30000);
    EXPECT_EQ(h.exec->execState(), Exec::FINISHED);
}

TEST(NonStopExecutor, FailedQueryIsRetriedAndStopCancels)
{
    Harness h;
    h.exec->start({0., 0.}, {10., 0.});
    h.release(false);
    h.exec->step(0.01);
    EXPECT_TRUE(h.saw(Exec::STOPPED, Sig::CANCELLED, Exec::STOPPED));
    EXPECT_EQ(h.exec->statistics().failures, 1u);
    EXPECT_EQ(h.exec->statistics().queries, 2u) << "asked again";
    h.waitStarted(2);
    h.exec->stop();
    EXPECT_EQ(h.exec->execState(), Exec::IDLE);
    h.exec->waitForPlanner();
    EXPECT_EQ(h.gate.sawCancel, 1);
    h.steps(10);
    EXPECT_EQ(h.exec->execState(), Exec::IDLE);
    // stop while executing
    h.exec->start({0., 0.}, {10., 0.});
    h.release();
    h.exec->step(0.01);
    ASSERT_EQ(h.exec->execState(), Exec::EXECUTE);
    h.exec->stop();
    EXPECT_TRUE(h.saw(Exec::EXECUTE, Sig::STOP, Exec::IDLE));
}

TEST(NonStopExecutor, PlanningDelayIsChargedOnTheSimulatedClockAndSynchronousQueriesRunToTheEnd)
{
    Harness h(0., 0.5, true);
    {
        std::lock_guard<std::mutex> lock(h.gate.mutex);
        h.gate.released = 1;  // the planner may answer the first query at once
    }
    h.exec->start({0., 0.}, {10., 0.});
    // synchronous: the query has been planned when start() returns
    EXPECT_EQ(h.exec->planState(), NonStopExecutor::PlanState::WAIT_QUERY);
    EXPECT_EQ(h.gate.started, 1);
    h.steps(49);  // 0.49 s of simulated time: the answer is not due yet
    EXPECT_EQ(h.exec->execState(), Exec::STOPPED);
    EXPECT_EQ(h.exec->configuration(), (Configuration{0., 0.}));
    h.steps(1);  // 0.5 s: due
    EXPECT_EQ(h.exec->execState(), Exec::EXECUTE);
    EXPECT_TRUE(h.saw(Exec::STOPPED, Sig::PATH_FOUND, Exec::EXECUTE));
}

TEST(NonStopExecutor, CpuTimeOfAQueryIsChargedOnTheSimulatedClock)
{
    // real_time with clock cpu: the answer is due once the simulated clock has advanced by the CPU time the planner
    // really spent (at least burn; the spinning stops right after it, so far below 0.5 s)
    Harness h(0., 0., true, 1.);
    h.burn = 0.1;
    {
        std::lock_guard<std::mutex> lock(h.gate.mutex);
        h.gate.released = 1;
    }
    h.exec->start({0., 0.}, {10., 0.});
    EXPECT_EQ(h.exec->planState(), NonStopExecutor::PlanState::WAIT_QUERY);
    h.steps(9);  // 0.09 s of simulated time, less than the CPU time spent: not due
    EXPECT_EQ(h.exec->execState(), Exec::STOPPED);
    EXPECT_EQ(h.exec->configuration(), (Configuration{0., 0.}));
    h.steps(41);  // 0.5 s
    EXPECT_EQ(h.exec->execState(), Exec::EXECUTE);
    ASSERT_EQ(h.exec->statistics().cpuLatencies.size(), 1u);
    EXPECT_GE(h.exec->statistics().cpuLatencies[0], 0.1);
}

namespace
{
    /** A harness with time-scale adaptation (retiming) checked over 6 s, so that the whole crossing below is seen. */
    Harness retimingHarness(bool retiming)
    {
        return Harness(0., 0., false, 0.,
                       [retiming](michi::planners::NonStopSettings &s)
                       {
                           s.retiming = retiming;
                           s.retimingHorizon = 6.;
                       });
    }

    /** \e n steps of 0.01 s; false (and where) at the first one that puts the robot into a crosser. */
    ::testing::AssertionResult stepsClearOfCrossers(Harness &h, int n)
    {
        for (int i = 0; i < n; ++i)
        {
            h.steps(1);
            if (!h.world.freeAt(h.exec->configuration(), h.world.now))
                return ::testing::AssertionFailure() << "inside a crosser at t " << h.world.now;
        }
        return ::testing::AssertionSuccess();
    }

    /** The robot at full speed on y = 2; a disc (radius 0.3) crosses the path 3 m ahead, upwards at 1 m/s, reaching
        y = 2 just when the robot would at full speed. Its predicted region (what the spatial check sees) is a box. */
    double crossAhead(Harness &h, double vy = 1.)
    {
        const double x0 = h.underWay();
        EXPECT_NEAR(h.exec->configuration()[1], 2., 1e-9);
        EXPECT_NEAR(h.exec->velocity(), 1., 1e-9);
        h.world.crossers.push_back({x0 + 3., 2. - 3. * vy - vy * h.world.now, vy, 0.3});
        h.world.boxes.push_back({x0 + 2.7, x0 + 3.3, 0.5, 3.5});
        h.exec->geoChange();
        return x0;
    }
}  // namespace

TEST(NonStopExecutor, RetimingSlowsDownForACrossingObstacleInsteadOfReplanning)
{
    auto h = retimingHarness(true);
    crossAhead(h);
    // at full speed the robot would meet the disc; at 3/4 of it the disc has passed: no query, no deformation
    EXPECT_EQ(h.exec->execState(), Exec::EXECUTE);
    EXPECT_EQ(h.exec->statistics().retimings, 1u);
    EXPECT_EQ(h.exec->statistics().queries, 1u);
    EXPECT_EQ(h.deformCalls, 0);
    h.steps(100);
    EXPECT_NEAR(h.exec->velocity(), 0.75, 1e-9);
    // and it goes through where the disc was, never touching it
    ASSERT_TRUE(stepsClearOfCrossers(h, 600));
    EXPECT_EQ(h.gate.started, 1);
}

TEST(NonStopExecutor, WithoutRetimingTheSameCrossingIsReplanned)
{
    auto h = retimingHarness(false);
    crossAhead(h);
    EXPECT_EQ(h.exec->execState(), Exec::REPLANNING);
    EXPECT_EQ(h.exec->statistics().retimings, 0u);
    EXPECT_EQ(h.exec->statistics().queries, 2u);
}

TEST(NonStopExecutor, RetimingWaitsForAnObstacleThatLeaves)
{
    // A disc (radius 0.3 m) stands on the path 1 m ahead and is gone 2.45 s from now; the spatial prediction is its
    // box. At any speed the robot would reach it while it is there (at 1/4 speed, x0 + 0.75 after 2.4 s); stopping,
    // waiting until 2 s and starting again, the robot reaches x0 + 0.7 after 2.67 s: only that wait is free.
    auto h = retimingHarness(true);
    const double x0 = h.underWay();
    h.world.crossers.push_back({x0 + 1., 2., 0., 0.3, h.world.now + 2.45});
    h.world.boxes.push_back({x0 + 0.7, x0 + 1.3, 1.7, 2.3});
    h.exec->geoChange();
    EXPECT_EQ(h.exec->execState(), Exec::EXECUTE);
    EXPECT_EQ(h.exec->statistics().retimings, 1u);
    h.steps(60);
    EXPECT_NEAR(h.exec->velocity(), 0., 1e-9) << "standing while it waits";
    ASSERT_TRUE(stepsClearOfCrossers(h, 400));
    EXPECT_GT(h.exec->velocity(), 0.9) << "going again at full speed";
    EXPECT_EQ(h.exec->statistics().queries, 1u);
}

TEST(NonStopExecutor, RetimingFallsBackToReplanningWhenNoTimingIsFree)
{
    auto h = retimingHarness(true);
    const double x0 = h.underWay();
    h.world.crossers.push_back({x0 + 3., 2., 0., 0.3});  // standing on the path
    h.world.boxes.push_back({x0 + 2.7, x0 + 3.3, 1.7, 2.3});
    h.exec->geoChange();
    EXPECT_EQ(h.exec->execState(), Exec::REPLANNING);
    EXPECT_EQ(h.exec->statistics().retimings, 0u);
}

namespace
{
    /** The robot at full speed on y = 2 is already inside the predicted region of a disc (radius 0.3) that comes up
        from below at x0 + 0.5 with \e vy m/s, 1.5 m below the path now: braking (0.25 m) would leave it standing in
        the disc's way. A second disc stands on the path 5 m ahead, so no timing of the path gets past every predicted
        interference (retime() fails) and a Geo. change must stop or cross. Geo. changes every 0.1 s over \e n steps;
        false at the first step that puts the robot into a disc. */
    ::testing::AssertionResult inTheWayOfACrosser(Harness &h, double vy, int n)
    {
        const double x0 = h.underWay();
        h.world.crossers.push_back({x0 + 0.5, 0.5 - vy * h.world.now, vy, 0.3});
        h.world.boxes.push_back({x0 - 0.2, x0 + 0.8, 0.2, 3.5});
        h.world.crossers.push_back({x0 + 5., 2., 0., 0.3});
        h.world.boxes.push_back({x0 + 4.7, x0 + 5.3, 1.7, 2.3});
        for (int i = 0; i < n; ++i)
        {
            if (i % 10 == 0)
                h.exec->geoChange();
            h.steps(1);
            if (!h.world.freeAt(h.exec->configuration(), h.world.now))
                return ::testing::AssertionFailure()
                       << "inside a disc at t " << h.world.now << ", x " << h.exec->configuration()[0] - x0 << " m on";
        }
        return ::testing::AssertionSuccess();
    }
}  // namespace

TEST(NonStopExecutor, RetimingCrossesAnObstaclesWayInsteadOfStoppingInIt)
{
    auto h = retimingHarness(true);
    // the disc reaches the path in 3 s; at full speed the robot is out of its region in under a second
    ASSERT_TRUE(inTheWayOfACrosser(h, 0.5, 600));
    EXPECT_TRUE(h.saw(Exec::UPDATE_PROBLEM, Sig::GEO_CHANGE, Exec::REPLANNING));
    EXPECT_FALSE(h.saw(Exec::UPDATE_PROBLEM, Sig::GEO_CHANGE, Exec::STOPPING));
    EXPECT_EQ(h.exec->statistics().retimings, 0u) << "no timing gets past the standing disc";
    // it stops for the planner short of the standing disc, having crossed the first one's way
    EXPECT_EQ(h.exec->execState(), Exec::STOPPED);
    EXPECT_GT(h.exec->configuration()[0], 3.);
}

TEST(NonStopExecutor, WithoutRetimingTheRobotStopsInTheObstaclesWay)
{
    // the same scene without the time-scale adaptation: it brakes at once and the disc runs into it
    auto h = retimingHarness(false);
    EXPECT_FALSE(inTheWayOfACrosser(h, 0.5, 400));
    EXPECT_TRUE(h.saw(Exec::UPDATE_PROBLEM, Sig::GEO_CHANGE, Exec::STOPPING));
}

TEST(NonStopExecutor, RetimingDoesNotCrossWhereTheObstacleComesFirst)
{
    // a disc fast enough (3 m/s) to reach the path before the robot is across: crossing is not free in time, so
    // the robot brakes (and a disc that fast reaches it either way)
    auto h = retimingHarness(true);
    inTheWayOfACrosser(h, 3., 1);
    EXPECT_TRUE(h.saw(Exec::UPDATE_PROBLEM, Sig::GEO_CHANGE, Exec::STOPPING));
    EXPECT_FALSE(h.saw(Exec::UPDATE_PROBLEM, Sig::GEO_CHANGE, Exec::REPLANNING));
}

TEST(NonStopExecutor, StopAndReplanBrakesFirstAndPlansOnceStanding)
{
    Harness h(0., 0., false, 0.,
              [](michi::planners::NonStopSettings &s)
              {
                  s.nonStop = false;
              });
    const double x0 = h.underWay();
    h.world.boxes.push_back({x0 + 2., x0 + 3., 1.5, 2.5});  // 2 m ahead: a non-stop executor would move on
    h.exec->geoChange();
    EXPECT_EQ(h.exec->execState(), Exec::STOPPING);
    EXPECT_EQ(h.exec->statistics().queries, 1u) << "no query while moving";
    h.steps(60);  // braking from 1 m/s at 2 m/s^2 takes 0.5 s
    EXPECT_EQ(h.exec->execState(), Exec::STOPPED);
    EXPECT_EQ(h.exec->statistics().queries, 2u) << "the query once it stands";
    EXPECT_EQ(h.exec->statistics().stops, 1u);
    h.waitStarted(2);
    h.release();
    h.exec->step(0.01);
    EXPECT_EQ(h.exec->execState(), Exec::EXECUTE);
}
