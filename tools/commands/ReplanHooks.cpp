#include "ReplanMethodRun.h"

#include <michi/planners/dual_roadmap/DualRoadmap.h>
#include <michi/planners/dual_roadmap/InterferencePrediction.h>
#include <michi/tools/commands/CpuBudget.h>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>

#include <pthread.h>
#include <time.h>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace tools
    {
        namespace replan
        {
            void MethodRun::toState(const ob::SpaceInformationPtr &si, const Configuration &q, ob::State *s)
            {
                si->getStateSpace()->copyFromReals(s, q);
                si->getStateSpace()->enforceBounds(s);
            }
            Configuration MethodRun::toReals(const ob::SpaceInformationPtr &si, const ob::State *s)
            {
                Configuration q;
                si->getStateSpace()->copyToReals(q, s);
                return q;
            }

            namespace
            {
                /** Radius of the circle round \e shape's outline in the plane: upright shapes (their z axis vertical)
                    by their cross-section, which is what an SE(2) robot meets (its height is not compared: the
                    region stays conservative); others by their bounding sphere. */
                double planarRadius(const validity::Shape &shape, const Eigen::Isometry3d &pose)
                {
                    if (std::fabs(pose.linear()(2, 2)) < 1. - 1e-9)
                        return shape.boundingRadius();
                    const Eigen::Vector3d &z = shape.size();
                    switch (shape.type())
                    {
                        case validity::Shape::Type::BOX:
                            return 0.5 * std::hypot(z.x(), z.y());
                        case validity::Shape::Type::SPHERE:
                        case validity::Shape::Type::CYLINDER:
                        case validity::Shape::Type::CAPSULE:
                            return z.x();
                        default:
                            return shape.boundingRadius();
                    }
                }

                /** The predicted copies of the moving obstacles (names "<mover>~<i>") as circles (x, y, bounding
                    radius) in the plane: what a change of the sensed world can touch. */
                std::vector<Eigen::Vector3d> copyCircles(const validity::Scene &scene)
                {
                    std::vector<Eigen::Vector3d> out;
                    // visited in place: a copy of the scene's obstacles (names, shapes, trajectories) twice per query
                    // was a measurable part of a replan's latency
                    scene.forEachObstacle(
                        [&](const validity::Obstacle &o)
                        {
                            // Only the predicted copies ("<mover>~<i>") move between queries; the static scene never
                            // changes the region.
                            if (o.name.find('~') != std::string::npos)
                                out.emplace_back(o.pose.translation().x(), o.pose.translation().y(),
                                                 planarRadius(*o.shape, o.pose));
                        });
                    return out;
                }

                /** For an SE(2) robot of circumradius \e radius: the motion a -> b (its centre on the segment, the
                    body within \e radius of it, for OMPL's SE(2) and turn-move-turn motions alike) may be affected
                    when a circle comes within reach of the segment. */
                planners::DualRoadmap::ChangeRegion se2Region(std::vector<Eigen::Vector3d> circles, double radius,
                                                              const ob::StateSpacePtr &space)
                {
                    return [circles = std::move(circles), radius, space](const ob::State *a, const ob::State *b)
                    {
                        // x and y read in place: this runs for every stale record a search meets, so no copy
                        const Eigen::Vector2d pa(*space->getValueAddressAtIndex(a, 0),
                                                 *space->getValueAddressAtIndex(a, 1));
                        const Eigen::Vector2d d = Eigen::Vector2d(*space->getValueAddressAtIndex(b, 0),
                                                                  *space->getValueAddressAtIndex(b, 1)) -
                                                  pa;
                        const double dd = d.squaredNorm();
                        for (const auto &c : circles)
                        {
                            const Eigen::Vector2d p(c.x(), c.y());
                            const double t = dd > 0. ? std::clamp((p - pa).dot(d) / dd, 0., 1.) : 0.;
                            // 1 mm of slack for rounding: conservative
                            if ((pa + t * d - p).norm() <= radius + c.z() + 1e-3)
                                return true;
                        }
                        return false;
                    };
                }
            }  // namespace

            double MethodRun::firstInterferenceFree(const ob::SpaceInformationPtr &esi, const ConfigurationPath &path,
                                                    double lookahead)
            {
                return planners::firstInterference(esi, path, lookahead);  // paper 002's check, public in planners
            }

            NonStopHooks MethodRun::hooks()
            {
                NonStopHooks h;
                const auto esi = execCtx_.setup->getSpaceInformation();
                // The executor knows the world only through these hooks (configurations as plain vectors), so it can be
                // tested with a fake world and stays free of OMPL.
                h.sensedWorld = [this]
                {
                    std::lock_guard<std::mutex> lock(snapshotMutex_);
                    return snapshotId_;
                };
                h.distance = [esi](const Configuration &a, const Configuration &b)
                {
                    ob::ScopedState<> sa(esi), sb(esi);
                    toState(esi, a, sa.get());
                    toState(esi, b, sb.get());
                    return esi->distance(sa.get(), sb.get());
                };
                h.interpolate = [esi](const Configuration &a, const Configuration &b, double f, Configuration &out)
                {
                    ob::ScopedState<> sa(esi), sb(esi), so(esi);
                    toState(esi, a, sa.get());
                    toState(esi, b, sb.get());
                    esi->getStateSpace()->interpolate(sa.get(), sb.get(), f, so.get());
                    out = toReals(esi, so.get());
                };
                const double lookahead = settings_.lookahead;
                const auto msi = movingCtx_.setup->getSpaceInformation();
                const auto ssi = staticCtx_.setup->getSpaceInformation();
                const double crossDistance = settings_.speed * settings_.crossTime;
                h.firstInterference = [this, esi, msi, ssi, lookahead, crossDistance](const ConfigurationPath &path)
                {
                    // Inside a predicted region the sensed scene says "blocked" everywhere, so a crossing or an
                    // escape is checked against the obstacles as they are: the movers (msi) and the static world
                    // (ssi). The movers alone let a deformed crossing through a bin wall (2026-12-06: one motion
                    // collision on dynamic_reach_bin, seed 3).
                    const auto freeNow = [&msi, &ssi](const ob::State *from, const ob::State *to)
                    {
                        return msi->checkMotion(from, to) && ssi->checkMotion(from, to);
                    };
                    const double inf = std::numeric_limits<double>::infinity();
                    if (path.empty())
                        return inf;
                    ob::ScopedState<> a(esi), b(esi);
                    toState(esi, path[0], a.get());
                    double arc = 0.;
                    std::size_t first = 1;
                    if (!esi->isValid(a.get()))
                    {
                        // the robot is already within the margin of a (predicted) obstacle: only an escape the
                        // planner made (its target within the next waypoints), reached without touching the
                        // obstacles as they are, is acceptable
                        std::size_t target = 0;
                        {
                            std::lock_guard<std::mutex> lock(escapeMutex_);
                            for (std::size_t k = 1; k < std::min<std::size_t>(path.size(), 3) && target == 0; ++k)
                                for (const auto &e : escapeTargets_)
                                    if (e == path[k])
                                        target = k;
                        }
                        if (target == 0)
                        {
                            // not an escape: the robot may still be crossing the (predicted) way of an obstacle
                            // that is not there yet; keep going if the path leaves the predicted region within
                            // crossDistance, free of the obstacles as they are (braking there would be worse)
                            double along = 0.;
                            ob::ScopedState<> c(esi);
                            esi->copyState(c.get(), a.get());
                            for (std::size_t k = 1; k < path.size() && along <= crossDistance; ++k)
                            {
                                toState(esi, path[k], b.get());
                                const double len = esi->distance(c.get(), b.get());
                                const int n = std::max(1, static_cast<int>(std::ceil(len / 0.02)));
                                ob::ScopedState<> x(esi), y(esi);
                                esi->copyState(y.get(), c.get());
                                for (int i = 1; i <= n; ++i)
                                {
                                    esi->getStateSpace()->interpolate(c.get(), b.get(), static_cast<double>(i) / n,
                                                                      x.get());
                                    if (!freeNow(y.get(), x.get()))
                                        return 0.;
                                    along += len / n;
                                    esi->copyState(y.get(), x.get());
                                    if (esi->isValid(x.get()))
                                    {
                                        // out of the predicted region: check the rest of the path from here
                                        ConfigurationPath rest{toReals(esi, x.get())};
                                        for (std::size_t r = k; r < path.size(); ++r)
                                            rest.push_back(path[r]);
                                        const double more = firstInterferenceFree(esi, rest, lookahead - along);
                                        return std::isinf(more) ? more : along + more;
                                    }
                                    if (along > crossDistance)
                                        return 0.;
                                }
                                esi->copyState(c.get(), b.get());
                            }
                            return 0.;
                        }
                        for (std::size_t k = 1; k <= target; ++k)
                        {
                            toState(esi, path[k], b.get());
                            if (!freeNow(a.get(), b.get()))
                                return 0.;
                            arc += esi->distance(a.get(), b.get());
                            esi->copyState(a.get(), b.get());
                        }
                        if (!esi->isValid(a.get()))
                            return 0.;
                        first = target + 1;
                    }
                    // the rest of the path, from where the robot is, against the static world
                    ConfigurationPath rest{toReals(esi, a.get())};
                    rest.insert(rest.end(), path.begin() + static_cast<std::ptrdiff_t>(std::min(first, path.size())),
                                path.end());
                    const double more = firstInterferenceFree(esi, rest, lookahead - arc);
                    return std::isinf(more) ? more : arc + more;
                };
                auto movingChecker = movingCtx_.checker;
                h.clearance = [movingChecker](const Configuration &q)
                {
                    return movingChecker->clearanceConfiguration(q.data());
                };
                if (settings_.deformation)
                {
                    auto distance = h.distance;
                    auto interpolate = h.interpolate;
                    auto interference = h.firstInterference;
                    const DeformationSettings ds = settings_.deform;
                    h.deform = [=](ConfigurationPath &path)
                    {
                        auto accept = [&](const ConfigurationPath &p)
                        {
                            ConfigurationPath norm = p;
                            ob::ScopedState<> s(esi);
                            for (auto &q : norm)
                            {
                                toState(esi, q, s.get());
                                q = toReals(esi, s.get());
                            }
                            // A deformed path is accepted only if it is free of the predicted world over the lookahead,
                            // as a new plan would have to be; otherwise the executor replans.
                            return std::isinf(interference(norm));
                        };
                        if (!deformPath(path, *movingChecker, distance, interpolate, accept, ds))
                            return false;
                        ob::ScopedState<> s(esi);
                        for (auto &q : path)
                        {
                            toState(esi, q, s.get());
                            q = toReals(esi, s.get());
                        }
                        return true;
                    };
                }
                if (settings_.retiming && method_.retiming)
                {
                    const auto tsi = timedCtx_.setup->getSpaceInformation();
                    const double slack = settings_.retimingSlack;
                    h.freeInTime =
                        [this, tsi, slack](const ConfigurationPath &configurations, const std::vector<double> &times)
                    {
                        if (lastPoses_.size() != movers_.size() || lastVelocities_.size() != movers_.size())
                            return false;
                        // At each time, the movers (grown by the margin) where their observed velocity takes them
                        // then, and retiming_slack earlier and later: the state, and the motions to it and from it,
                        // are checked against them, so every piece of the motion is checked at both its ends'
                        // times. In between a mover is within half a step's travel of one of those places, which
                        // the margin covers up to margin / (step / 2) (4 m/s for the mobile scenarios' 0.2 m, 1 m/s
                        // for the bin's 0.05 m, whose parts move at 0.26 m/s at most with the speed jitter).
                        ob::ScopedState<> previous(tsi), state(tsi), next(tsi);
                        const double shifts[] = {0., -slack, slack};
                        std::vector<std::string> names;
                        for (const auto &mover : movers_)
                            names.push_back(mover.name);
                        std::vector<Eigen::Isometry3d> poses(movers_.size());
                        for (std::size_t k = 0; k < configurations.size(); ++k)
                            for (int i = 0; i < (slack > 0. ? 3 : 1); ++i)
                            {
                                for (std::size_t m = 0; m < movers_.size(); ++m)
                                {
                                    poses[m] = lastPoses_[m];
                                    poses[m].translation() += lastVelocities_[m] * std::max(0., times[k] + shifts[i]);
                                }
                                // all movers at once: one broad-phase refit per time, not one per copy
                                timed_.predicted->observe(names, poses, lastVelocities_);
                                toState(tsi, configurations[k], state.get());
                                if (!tsi->isValid(state.get()))
                                    return false;
                                if (k > 0)
                                {
                                    toState(tsi, configurations[k - 1], previous.get());
                                    if (!tsi->checkMotion(previous.get(), state.get()))
                                        return false;
                                }
                                if (k + 1 < configurations.size())
                                {
                                    toState(tsi, configurations[k + 1], next.get());
                                    if (!tsi->checkMotion(state.get(), next.get()))
                                        return false;
                                }
                            }
                        return true;
                    };
                }
                const auto psi = planCtx_.setup->getSpaceInformation();
                h.plan = [this, psi](const Configuration &from, const Configuration &goal, std::uint64_t id,
                                     const std::atomic<bool> &cancel, ConfigurationPath &path)
                {
                    Snapshot snap;
                    {
                        std::lock_guard<std::mutex> lock(snapshotMutex_);
                        // The world as sensed when this Query was sent: the planner plans in its own copy, so the
                        // planning thread never sees the scene change under it.
                        snap = snapshots_.at(id);
                    }
                    // DualRoadmap on an SE(2) robot is told where the sensed world changed since its last query (the
                    // moved copies, before and after), so it keeps what it proved elsewhere (the issue: each query
                    // re-checked everything); other robots: the whole scene counts as changed
                    auto dual = std::dynamic_pointer_cast<planners::DualRoadmap>(planner_);
                    const bool region = dual && problem_.kind == Problem::Kind::SE2;
                    std::vector<Eigen::Vector3d> before;
                    if (region)
                        before = copyCircles(*planSensed_.scene);
                    planSensed_.update(movers_, snap.poses, snap.velocities);
                    if (region)
                    {
                        const auto after = copyCircles(*planSensed_.scene);
                        std::vector<Eigen::Vector3d> moved;
                        for (std::size_t i = 0; i < after.size(); ++i)
                            if (i >= before.size() || before[i] != after[i])
                            {
                                if (i < before.size())
                                    moved.push_back(before[i]);
                                moved.push_back(after[i]);
                            }
                        double radius = 0.;
                        for (const auto &p : problem_.footprint)
                            radius = std::max(radius, p.norm());
                        dual->notifySceneChanged(se2Region(std::move(moved), radius, psi->getStateSpace()));
                    }
                    ob::ScopedState<> s(psi), g(psi);
                    toState(psi, from, s.get());
                    toState(psi, goal, g.get());
                    ConfigurationPath prefix;
                    if (!psi->isValid(s.get()))
                    {
                        // escape: the start is within the margin of a (predicted) obstacle; move first, along
                        // a straight motion free of the obstacles as they are, to a nearby state outside it. The
                        // world as it is now is brought up to this snapshot only here, where escape() reads it.
                        planNow_.update(movers_, snap.poses, snap.velocities);
                        if (!escape(s.get(), cancel))
                            return false;
                        prefix.push_back(from);
                        {
                            std::lock_guard<std::mutex> lock(escapeMutex_);
                            escapeTargets_.push_back(toReals(psi, s.get()));
                            // Only the last few escapes matter: firstInterference() looks for them among a path's next
                            // waypoints.
                            if (escapeTargets_.size() > 8)
                                escapeTargets_.erase(escapeTargets_.begin());
                        }
                        if (!psi->isValid(g.get()))
                        {
                            // the goal is taken for now: just get out of the way and wait there
                            path = prefix;
                            path.push_back(toReals(psi, s.get()));
                            return true;
                        }
                    }
                    if (!psi->isValid(g.get()))
                        return false;
                    auto pdef = std::make_shared<ob::ProblemDefinition>(psi);
                    pdef->setStartAndGoalStates(s, g);
                    switch (method_.reuse)
                    {
                        case Method::Reuse::SCRATCH:
                            planner_->clear();
                            break;
                        case Method::Reuse::KEEP_ROADMAP:
                            if (auto lazy = std::dynamic_pointer_cast<og::LazyPRM>(planner_))
                            {
                                lazy->clearQuery();
                                lazy->clearValidity();
                            }
                            break;
                        case Method::Reuse::DUAL:
                            // nothing: solve() takes the new query and keeps its working roadmap (re-checked
                            // lazily after a scene change); clear() would throw it away every query
                            break;
                    }
                    planner_->setProblemDefinition(pdef);
                    if (!planner_->isSetup())
                        planner_->setup();
                    // reproducible runs: DualRoadmap stops after a work count (evaluations of the condition:
                    // one per search, lazy edge check and sample) instead of wall time, with 10 x planning_time
                    // as a wall-clock backstop; the baselines keep planning_time (their work per evaluation
                    // differs too much for one count to be fair)
                    // as the baselines; clock cpu: every planner gets planning_time of this thread's CPU time (the
                    // time charged on the simulated clock), with 10 x that of wall clock as a backstop
                    const bool counted = settings_.realTime <= 0. && method_.reuse == Method::Reuse::DUAL;
                    const bool cpuLimit = settings_.realTime > 0. && settings_.cpuClock;
                    const unsigned long work = counted ? static_cast<unsigned long>(settings_.planningWork)
                                                       : std::numeric_limits<unsigned long>::max();
                    std::atomic<unsigned long> evaluations{0};  // PRM evaluates it in two threads
                    // this (planning) thread's CPU clock, readable from PRM's other thread too
                    clockid_t cpuClock{};
                    pthread_getcpuclockid(pthread_self(), &cpuClock);
                    const auto cpuNow = [cpuClock]
                    {
                        timespec ts{};
                        clock_gettime(cpuClock, &ts);
                        return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
                    };
                    // the budget reads the CPU clock (a system call) only when it could have run out (CpuBudget.h)
                    CpuBudget budget(
                        cpuLimit ? settings_.planningTime : std::numeric_limits<double>::infinity(), cpuNow,
                        []
                        {
                            return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
                                .count();
                        });
                    const ob::PlannerTerminationCondition ptc = ob::plannerOrTerminationCondition(
                        ob::timedPlannerTerminationCondition(settings_.planningTime * (counted || cpuLimit ? 10. : 1.)),
                        ob::PlannerTerminationCondition(
                            [&cancel, &evaluations, work, cpuLimit, &budget]
                            {
                                return cancel.load() || ++evaluations > work || (cpuLimit && budget.spent());
                            }));
                    const auto solveBegin = std::chrono::steady_clock::now();
                    const bool solved = planner_->solve(ptc) == ob::PlannerStatus::EXACT_SOLUTION;
                    if (!solved && std::getenv("MICHI_REPLAN_DEBUG") != nullptr)
                        std::cerr
                            << "\nno path: " << evaluations.load() << " evaluations of the termination "
                            << "condition in "
                            << std::chrono::duration<double>(std::chrono::steady_clock::now() - solveBegin).count()
                            << " s\n";
                    if (!solved || cancel)
                        return false;
                    auto solution = std::dynamic_pointer_cast<og::PathGeometric>(pdef->getSolutionPath());
                    if (!solution)
                        return false;
                    og::PathGeometric p(*solution);
                    // Baselines get smoothing too, inside the measured latency, so methods compare on paths of the same
                    // kind.
                    if (method_.simplify && p.getStateCount() > 2)
                    {
                        og::PathSimplifier simplifier(psi);
                        simplifier.reduceVertices(p);
                        simplifier.shortcutPath(p);
                    }
                    path = prefix;
                    for (std::size_t i = 0; i < p.getStateCount(); ++i)
                        path.push_back(toReals(psi, p.getState(i)));
                    return true;
                };
                return h;
            }

            bool MethodRun::escape(ob::State *s, const std::atomic<bool> &cancel)
            {
                const auto psi = planCtx_.setup->getSpaceInformation();
                const auto nsi = planNowCtx_.setup->getSpaceInformation();
                // Inside an obstacle as it is now (not only its prediction): no motion out of it can be certified.
                if (!nsi->isValid(s))
                    return false;
                if (!escapeSampler_)
                    escapeSampler_ = psi->allocStateSampler();
                ob::ScopedState<> near(psi);
                const double extent = psi->getMaximumExtent();
                for (int i = 0; i < 400 && !cancel; ++i)
                {
                    // Nearest first: the radius grows by 1 % of the space's extent every 40 tries, so the escape is as
                    // short as the samples allow.
                    const double radius = extent * 0.01 * (1. + i / 40);
                    escapeSampler_->sampleUniformNear(near.get(), s, radius);
                    // The target must be outside the predicted world, and the motion to it free of the obstacles as
                    // they are now.
                    if (psi->isValid(near.get()) && nsi->checkMotion(s, near.get()))
                    {
                        psi->copyState(s, near.get());
                        return true;
                    }
                }
                return false;
            }
        }  // namespace replan
    }      // namespace tools
}  // namespace michi
