// Tests of michi::planners::NonStopController (issue 18, item 4): paper 002's replanning driven from a user's robot
// loop, in OMPL terms. The world is the plane (a point robot in OMPL's RealVectorStateSpace) with the user's own
// validity checker (discs); the loop here advances its time in fixed steps and waits for the planner after each step,
// so outcomes do not depend on the machine's speed. Also run under ThreadSanitizer (MICHI_TSAN_TESTS).
#include <michi/planners/dual_roadmap/NonStopController.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

namespace ob = ompl::base;
using michi::planners::Configuration;
using michi::planners::NonStopController;
using michi::planners::NonStopControllerSettings;
using michi::planners::NonStopExecutor;
using michi::planners::TimedPath;
using Exec = NonStopExecutor::ExecState;

namespace
{
    struct Disc
    {
        double x, y, r;
    };

    /** The user's checker: discs in the plane, fixed once made (a new observation is a new checker). */
    class DiscWorld : public ob::StateValidityChecker
    {
    public:
        DiscWorld(const ob::SpaceInformationPtr &si, std::vector<Disc> discs)
            : ob::StateValidityChecker(si), discs_(std::move(discs))
        {
        }
        bool isValid(const ob::State *s) const override
        {
            return si_->satisfiesBounds(s) && clearance(s) > 0.;
        }
        double clearance(const ob::State *s) const override
        {
            const double *q = s->as<ob::RealVectorStateSpace::StateType>()->values;
            double d = std::numeric_limits<double>::infinity();
            for (const auto &c : discs_)
                d = std::min(d, std::hypot(q[0] - c.x, q[1] - c.y) - c.r);
            return d;
        }
        bool inside(const Configuration &q) const
        {
            for (const auto &c : discs_)
                if (std::hypot(q[0] - c.x, q[1] - c.y) < c.r)
                    return true;
            return false;
        }

    private:
        std::vector<Disc> discs_;
    };

    ob::StateSpacePtr plane()
    {
        auto space = std::make_shared<ob::RealVectorStateSpace>(2);
        ob::RealVectorBounds bounds(2);
        bounds.setLow(0, -1.);
        bounds.setHigh(0, 11.);
        bounds.setLow(1, -5.);
        bounds.setHigh(1, 5.);
        space->setBounds(bounds);
        return space;
    }

    NonStopControllerSettings settings()
    {
        NonStopControllerSettings s;
        s.motion.speed = 1.;
        s.motion.deceleration = 2.;
        s.motion.stopMargin = 0.2;
        s.planningTime = 2.;
        s.period = 0.05;
        s.horizon = 1.;
        return s;
    }

    /** The user's robot: it goes where the trajectory says it will be one loop period later (\e lag < 1: only
        that fraction of the way), with its state in an OMPL state. */
    struct Robot
    {
        ob::ScopedState<> state;
        explicit Robot(const ob::StateSpacePtr &space, double x, double y) : state(space)
        {
            state[0] = x;
            state[1] = y;
        }
        Configuration q() const
        {
            return {state[0], state[1]};
        }
        void follow(const TimedPath &trajectory, double lag = 1.)
        {
            ASSERT_GE(trajectory.configurations.size(), 2u);
            const auto &a = trajectory.configurations[0], &b = trajectory.configurations[1];
            state[0] = a[0] + lag * (b[0] - a[0]);
            state[1] = a[1] + lag * (b[1] - a[1]);
        }
    };

    struct Episode
    {
        double time{0.};
        bool reached{false};
        bool enteredObstacle{false};
        double largestSpeedChange{0.};  ///< between updates while moving
        double arrivalSpeed{0.};        ///< the last speed before the robot stood
        double largestStep{0.};
        double widest{0.};  ///< largest |y| the robot reached
    };

    /** The robot loop: update, follow, wait for the planner (so the run does not depend on the machine's speed);
        \e each is called before every update. */
    template <typename Each>
    Episode drive(NonStopController &controller, Robot &robot, const DiscWorld *const *world, double limit, Each each,
                  double lag = 1.)
    {
        Episode run;
        double lastSpeed = 0.;
        const double dt = 0.05;
        for (; run.time < limit && !controller.finished(); run.time += dt)
        {
            each(run.time);
            const Configuration before = robot.q();
            const TimedPath trajectory = controller.update(robot.state.get(), run.time);
            EXPECT_DOUBLE_EQ(trajectory.times.front(), 0.);
            // the speed law while moving; the last step, onto the goal, is judged by the speed it arrives from
            if (trajectory.speeds[0] > 0.)
                run.largestSpeedChange = std::max(run.largestSpeedChange, std::fabs(trajectory.speeds[0] - lastSpeed));
            else if (lastSpeed > 0.)
                run.arrivalSpeed = lastSpeed;
            lastSpeed = trajectory.speeds[0];
            for (std::size_t i = 1; i < trajectory.times.size(); ++i)
            {
                EXPECT_NEAR(trajectory.times[i] - trajectory.times[i - 1], 0.05, 1e-12);
                const auto &a = trajectory.configurations[i - 1], &b = trajectory.configurations[i];
                run.largestStep = std::max(run.largestStep, std::hypot(b[0] - a[0], b[1] - a[1]));
            }
            robot.follow(trajectory, lag);
            run.widest = std::max(run.widest, std::fabs(robot.q()[1]));
            if ((*world)->inside(robot.q()) || (*world)->inside(before))
                run.enteredObstacle = true;
            EXPECT_TRUE(controller.waitForPlanner(30.));
        }
        // at the goal, or (a robot slower than commanded) within the tracking tolerance of it
        run.reached = controller.finished() && std::hypot(robot.q()[0] - 10., robot.q()[1]) <= 0.05;
        return run;
    }

    struct Fixture
    {
        ob::StateSpacePtr space = plane();
        std::unique_ptr<NonStopController> controller;
        std::vector<std::shared_ptr<DiscWorld>> worlds;
        const DiscWorld *current{nullptr};

        explicit Fixture(NonStopControllerSettings s = settings(), NonStopController::PlannerAllocator a = {})
        {
            ompl::RNG::setSeed(7);
            controller = std::make_unique<NonStopController>(space, s, std::move(a));
        }
        void observe(std::vector<Disc> discs)
        {
            worlds.push_back(std::make_shared<DiscWorld>(controller->spaceInformation(), std::move(discs)));
            current = worlds.back().get();
            controller->observeWorld(worlds.back());
        }
        /** Observe \e discs, put the robot at the origin and start it towards (10, 0). */
        Robot begin(std::vector<Disc> discs = {})
        {
            observe(std::move(discs));
            Robot robot(space, 0., 0.);
            start(robot);
            return robot;
        }
        void start(Robot &robot)
        {
            ob::ScopedState<> goal(space);
            goal[0] = 10.;
            goal[1] = 0.;
            controller->start(robot.state.get(), goal.get());
        }
    };
}  // namespace

TEST(NonStopController, DrivesTheRobotToItsGoalAlongTrajectoriesThatEndAtRest)
{
    Fixture f;
    Robot robot = f.begin();
    const Episode run = drive(*f.controller, robot, &f.current, 60., [](double) {});
    EXPECT_TRUE(run.reached);
    EXPECT_FALSE(run.enteredObstacle);
    // bounded speed and acceleration: never more than the cruise speed per period, the speed changing by at most the
    // deceleration per loop step while moving; it arrives braked, from at most twice that (the discrete braking law
    // lands on the goal within a step or two of deceleration x dt; without braking it would drop from the cruise
    // speed, 1 m/s, to 0)
    EXPECT_LE(run.largestStep, 1. * 0.05 + 1e-9);
    EXPECT_LE(run.largestSpeedChange, 2. * 0.05 + 1e-9);
    EXPECT_GT(run.arrivalSpeed, 0.);
    EXPECT_LE(run.arrivalSpeed, 2. * 2. * 0.05 + 1e-9);
    // 10 m at 1 m/s with 0.25 s of speeding up and of braking: the run takes about 10.25 s, plus the first query
    EXPECT_GT(run.time, 10.);
    EXPECT_LT(run.time, 12.);
    EXPECT_EQ(f.controller->statistics().offPath, 0u);
}

TEST(NonStopController, ReplansAroundAnObstacleObservedOnItsWay)
{
    Fixture f;
    Robot robot = f.begin();
    bool observed = false;
    const Episode run = drive(*f.controller, robot, &f.current, 60.,
                              [&](double t)
                              {
                                  // a disc appears across the straight path once the robot is under way
                                  if (!observed && t >= 2.)
                                  {
                                      observed = true;
                                      f.observe({{6., 0., 1.}});
                                  }
                              });
    ASSERT_TRUE(observed);
    EXPECT_TRUE(run.reached);
    EXPECT_FALSE(run.enteredObstacle);
    const auto &stats = f.controller->statistics();
    EXPECT_GE(stats.queries, 2u);
    EXPECT_GE(stats.pathsFound, 2u);
    // non-stop: the robot did not halt for the new path (the obstacle was seen 3 m ahead, far beyond braking)
    EXPECT_EQ(stats.stops, 0u);
    // it went round the disc (never inside it, checked above)
    EXPECT_GT(run.widest, 0.9);
}

TEST(NonStopController, FollowsARobotThatLagsBehindWithoutLeavingThePath)
{
    Fixture f;
    Robot robot = f.begin();
    const Episode run = drive(
        *f.controller, robot, &f.current, 60., [](double) {}, 0.6);
    // the model is put back where the robot is at every update: the robot arrives, later than commanded
    EXPECT_TRUE(run.reached);
    EXPECT_EQ(f.controller->statistics().offPath, 0u);
    EXPECT_GT(run.time, 12.);
}

TEST(NonStopController, AMeasuredStateOffThePathIsPlannedFrom)
{
    Fixture f;
    Robot robot = f.begin();
    bool pushed = false;
    const Episode run = drive(*f.controller, robot, &f.current, 60.,
                              [&](double t)
                              {
                                  // the robot is pushed 0.5 m sideways (the tolerance is 0.05 m)
                                  if (!pushed && t >= 3.)
                                  {
                                      pushed = true;
                                      robot.state[1] = 0.5;
                                  }
                              });
    EXPECT_TRUE(run.reached);
    EXPECT_EQ(f.controller->statistics().offPath, 1u);
    EXPECT_GE(f.controller->statistics().queries, 2u);
}

TEST(NonStopController, PlansWithAStockPlannerToo)
{
    Fixture f(settings(),
              [](const ob::SpaceInformationPtr &si)
              {
                  return std::make_shared<ompl::geometric::RRTConnect>(si);
              });
    Robot robot = f.begin({{5., 0., 1.5}});
    const Episode run = drive(*f.controller, robot, &f.current, 60., [](double) {});
    EXPECT_TRUE(run.reached);
    EXPECT_FALSE(run.enteredObstacle);
}

TEST(NonStopController, RejectsBadSettingsAndBadUse)
{
    auto space = plane();
    auto bad = settings();
    bad.trackingTolerance = 0.;
    EXPECT_THROW(NonStopController(space, bad), std::invalid_argument);
    bad = settings();
    bad.period = std::nan("");
    EXPECT_THROW(NonStopController(space, bad), std::invalid_argument);
    bad = settings();
    bad.motion.speed = -1.;
    EXPECT_THROW(NonStopController(space, bad), std::invalid_argument);
    EXPECT_THROW(NonStopController(nullptr, settings()), std::invalid_argument);

    NonStopController controller(space, settings());
    ob::ScopedState<> a(space), b(space);
    a[0] = 0.;
    a[1] = 0.;
    b[0] = 10.;
    b[1] = 0.;
    EXPECT_THROW(controller.start(a.get(), b.get()), std::logic_error);  // no world observed
    EXPECT_THROW(controller.observeWorld(nullptr), std::invalid_argument);
    // before start() the robot is held where it is measured, wherever that is
    controller.update(a.get(), 1.);
    b[0] = 3.;
    b[1] = 1.;
    const TimedPath hold = controller.update(b.get(), 1.5);
    ASSERT_FALSE(hold.configurations.empty());
    for (const auto &q : hold.configurations)
        EXPECT_EQ(q, (Configuration{3., 1.}));
    EXPECT_THROW(controller.update(a.get(), 1.), std::invalid_argument);  // time went back
    EXPECT_EQ(controller.state(), Exec::IDLE);
}

TEST(NonStopController, RefusesSettingsThatAreNotFiniteAndStatesThatAreNotNumbers)
{
    auto space = plane();
    const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
    // each accepted before: an infinite speed or deceleration made every braking distance 0 or NaN, an infinite
    // horizon a length_error in update(), a NaN margin every comparison false
    for (auto set :
         std::vector<std::function<void(NonStopControllerSettings &)>>{
             [&](NonStopControllerSettings &s)
             {
                 s.motion.speed = inf;
             },
             [&](NonStopControllerSettings &s)
             {
                 s.motion.deceleration = inf;
             },
             [&](NonStopControllerSettings &s)
             {
                 s.motion.stopMargin = -1.;
             },
             [&](NonStopControllerSettings &s)
             {
                 s.motion.stopMargin = nan;
             },
             [&](NonStopControllerSettings &s)
             {
                 s.motion.safetyDistance = nan;
             },
             [&](NonStopControllerSettings &s)
             {
                 s.planningTime = inf;
             },
             [&](NonStopControllerSettings &s)
             {
                 s.trackingTolerance = inf;
             },
             [&](NonStopControllerSettings &s)
             {
                 s.horizon = inf;
             },
             [&](NonStopControllerSettings &s)
             {
                 s.horizon = 1e9;
             },
             // refused by the executor after the controller had allocated states: they leaked (LeakSanitizer)
             [&](NonStopControllerSettings &s)
             {
                 s.motion.speed = 0.;
             }})
    {
        auto bad = settings();
        set(bad);
        EXPECT_THROW(NonStopController(space, bad), std::invalid_argument);
    }

    Fixture f;
    Robot robot = f.begin();
    ASSERT_TRUE(f.controller->waitForPlanner(30.));
    f.controller->update(robot.state.get(), 0.);
    // one NaN in a measurement went into the arc lengths, and the next update() aborted the process in an OMPL
    // assertion; now it is refused and the model of the robot stays where it was
    Robot lost(f.space, nan, 0.);
    EXPECT_THROW(f.controller->update(lost.state.get(), 0.05), std::invalid_argument);
    const TimedPath next = f.controller->update(robot.state.get(), 0.1);
    for (const auto &q : next.configurations)
        EXPECT_TRUE(std::isfinite(q[0]) && std::isfinite(q[1]));

    Fixture g;
    g.observe({});
    ob::ScopedState<> nanGoal(g.space), farGoal(g.space);
    nanGoal[0] = nan;
    nanGoal[1] = 0.;
    farGoal[0] = 50.;
    farGoal[1] = 0.;
    EXPECT_THROW(g.controller->start(robot.state.get(), nanGoal.get()), std::invalid_argument);
    EXPECT_THROW(g.controller->start(robot.state.get(), farGoal.get()), std::invalid_argument);
    EXPECT_EQ(g.controller->state(), Exec::IDLE);
}

TEST(NonStopController, AWallSeenWhileStartingOffIsStoppedShortOf)
{
    // The robot is still speeding up (0.1 s after the start, about 0.2 m/s) when a wall across the whole plane is
    // observed. Its stop point was placed with the braking distance of that speed; it went on speeding up towards
    // its cruise speed of 1.5 m/s and, braking from there, stood 0.45 m inside the wall, and every trajectory it
    // returned from then on ran into the wall.
    auto s = settings();
    s.motion.speed = 1.5;
    s.motion.stopMargin = 0.;
    s.period = 0.02;
    Fixture f(s);
    Robot robot = f.begin();
    ASSERT_TRUE(f.controller->waitForPlanner(30.));
    std::vector<Disc> wall;
    for (double y = -5.; y <= 5.001; y += 0.25)
        wall.push_back({2.5, y, 0.5});  // the robot is a point: the discs are the wall grown by a radius
    int intoTheWall = 0;
    for (int tick = 0; tick <= 250; ++tick)
    {
        if (tick == 5)
            f.observe(wall);
        const TimedPath trajectory = f.controller->update(robot.state.get(), 0.02 * tick);
        if (tick >= 5)
            for (const auto &q : trajectory.configurations)
                intoTheWall += f.current->inside(q) ? 1 : 0;
        robot.follow(trajectory);
        ASSERT_TRUE(f.controller->waitForPlanner(30.));
    }
    EXPECT_EQ(intoTheWall, 0);
    EXPECT_FALSE(f.current->inside(robot.q())) << robot.q()[0] << ", " << robot.q()[1];
    EXPECT_EQ(f.controller->state(), Exec::STOPPED);  // no way round: it waits in front of the wall
}

TEST(NonStopController, APlannerSlowerThanTheSensorStillGetsItsPath)
{
    // The world, empty, is observed again every 0.1 s of wall time and the planner takes 0.15 s. A robot standing
    // at its start (a one-state path) saw each observation leave that "path" free, cancelled the query and sent a
    // new one: 52 queries, no path, in 5 s. Wall-clock time here is the condition that the bug needs; the
    // assertion is on the outcome, not on a time.
    auto slow = [](const ob::SpaceInformationPtr &si) -> ob::PlannerPtr
    {
        class Slow : public ompl::geometric::RRTConnect
        {
        public:
            using RRTConnect::RRTConnect;
            ob::PlannerStatus solve(const ob::PlannerTerminationCondition &ptc) override
            {
                std::this_thread::sleep_for(std::chrono::milliseconds(150));
                return RRTConnect::solve(ptc);
            }
        };
        return std::make_shared<Slow>(si);
    };
    Fixture f(settings(), slow);
    Robot robot = f.begin();
    const auto start = std::chrono::steady_clock::now();
    auto lastObservation = start;
    double t = 0.;
    while (!f.controller->finished() && std::chrono::steady_clock::now() - start < std::chrono::seconds(30))
    {
        const auto now = std::chrono::steady_clock::now();
        if (now - lastObservation >= std::chrono::milliseconds(100))
        {
            f.observe({});
            lastObservation = now;
        }
        robot.follow(f.controller->update(robot.state.get(), t));
        t += 0.05;  // a loop period of the settings' 0.05 s, run faster than real time
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    EXPECT_TRUE(f.controller->finished()) << f.controller->statistics().queries << " queries";
    EXPECT_GE(f.controller->statistics().pathsFound, 1u);
}
