// Driving michi's non-stop replanner (paper 002) from your own robot loop: michi::planners::NonStopController.
//
// A point robot in the plane must cross from (0, 0) to (10, 0). Its world is your own OMPL StateValidityChecker (here:
// discs); a box slides into the robot's way while it drives. The loop below is what a robot's control loop does at
// 50 Hz on the wall clock: read the robot's measured state, hand the controller the newest observation of the world
// (10 Hz here), ask for the trajectory to follow, send it to the robot. Planning runs on the controller's own thread
// meanwhile: the robot keeps moving while a new path is found.
//
// Build: any CMake project with find_package(michi) and target_link_libraries(... michi::michi); in michi's own build
// it is the target example_nonstop_controller (run by ctest). Prints what happens and exits 0 when the robot reached
// its goal without touching an obstacle.
#include <michi/planners/dual_roadmap/NonStopController.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/util/Console.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <thread>
#include <vector>

namespace ob = ompl::base;
using michi::planners::NonStopController;
using michi::planners::NonStopExecutor;

// Your world model: discs (x, y, radius) as sensed at one moment; never changed once handed to the controller.
class DiscWorld : public ob::StateValidityChecker
{
public:
    DiscWorld(const ob::SpaceInformationPtr &si, std::vector<std::array<double, 3>> discs)
        : ob::StateValidityChecker(si), discs_(std::move(discs))
    {
    }
    bool isValid(const ob::State *s) const override
    {
        return si_->satisfiesBounds(s) && clearance(s) > robotRadius;
    }
    double clearance(const ob::State *s) const override
    {
        const double *q = s->as<ob::RealVectorStateSpace::StateType>()->values;
        double d = std::numeric_limits<double>::infinity();
        for (const auto &c : discs_)
            d = std::min(d, std::hypot(q[0] - c[0], q[1] - c[1]) - c[2]);
        return d;
    }
    static constexpr double robotRadius = 0.2;

private:
    std::vector<std::array<double, 3>> discs_;
};

int main()
{
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    auto space = std::make_shared<ob::RealVectorStateSpace>(2);
    ob::RealVectorBounds bounds(2);
    bounds.setLow(0, -1.);
    bounds.setHigh(0, 11.);
    bounds.setLow(1, -4.);
    bounds.setHigh(1, 4.);
    space->setBounds(bounds);

    michi::planners::NonStopControllerSettings settings;
    settings.motion.speed = 1.5;                    // m/s along the path
    settings.motion.deceleration = 2.;              // m/s^2
    settings.motion.stopMargin = 0.3;               // m kept between a stop and the obstacle
    settings.planningTime = 0.5;                    // s per query at most
    settings.horizon = 0.5;                         // s of trajectory returned per update
    settings.period = 0.02;                         // s between its samples
    settings.trackingTolerance = 0.1;               // m off the path before it is planned from where the robot is
    NonStopController controller(space, settings);  // DualRoadmap; pass an allocator for any other OMPL planner

    // The real world: the box (radius 0.6) slides from y = 3 down to y = 0 at x = 6 between t = 1 s and t = 3 s.
    auto boxAt = [](double t)
    {
        const double f = std::min(1., std::max(0., (t - 1.) / 2.));
        return std::array<double, 3>{6., 3. * (1. - f), 0.6};
    };
    auto observe = [&](double t)
    {
        controller.observeWorld(
            std::make_shared<DiscWorld>(controller.spaceInformation(), std::vector<std::array<double, 3>>{boxAt(t)}));
    };

    ob::ScopedState<> robot(space), goal(space);
    robot[0] = 0.;
    robot[1] = 0.;
    goal[0] = 10.;
    goal[1] = 0.;
    observe(0.);
    controller.start(robot.get(), goal.get());

    const double period = 0.02;  // the control loop: 50 Hz
    const auto begin = std::chrono::steady_clock::now();
    auto last = controller.state();
    bool touched = false;
    double detour = 0.;  // farthest from the straight line
    for (int tick = 0; tick < 1500 && !controller.finished(); ++tick)
    {
        std::this_thread::sleep_until(begin + std::chrono::duration<double>(period * tick));
        const double t = period * tick;
        if (tick % 5 == 0)  // a new observation every 0.1 s
            observe(t);
        // the measured state in, the trajectory out; this robot follows it perfectly (send it to your controller)
        const michi::planners::TimedPath trajectory = controller.update(robot.get(), t);
        const auto &next =
            trajectory.configurations.size() > 1 ? trajectory.configurations[1] : trajectory.configurations[0];
        robot[0] = next[0];
        robot[1] = next[1];
        detour = std::max(detour, std::fabs(robot[1]));
        const auto box = boxAt(t + period);
        if (std::hypot(robot[0] - box[0], robot[1] - box[1]) < box[2] + DiscWorld::robotRadius)
            touched = true;
        if (controller.state() != last)
        {
            last = controller.state();
            std::printf("t = %5.2f s  robot (%5.2f, %5.2f)  %s\n", t, robot[0], robot[1], NonStopExecutor::name(last));
        }
    }
    const auto &stats = controller.statistics();
    double worst = 0.;
    for (double s : stats.latencies)
        worst = std::max(worst, s);
    std::printf("queries %u, paths %u, stops %u, slowest query %.1f ms, detour %.2f m, %s, %s\n", stats.queries,
                stats.pathsFound, stats.stops, 1e3 * worst, detour,
                controller.finished() ? "goal reached" : "goal NOT reached",
                touched ? "TOUCHED the box" : "never touched the box");
    return controller.finished() && !touched ? 0 : 1;
}
