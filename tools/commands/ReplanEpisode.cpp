#include "ReplanMethodRun.h"

#include <michi/planners/dual_roadmap/DualRoadmap.h>
#include <michi/planners/dual_roadmap/HandTaskMap.h>
#include <michi/tools/bench/PlannerRegistry.h>

#include <ompl/base/ScopedState.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <iostream>

namespace ob = ompl::base;

namespace michi
{
    namespace tools
    {
        namespace replan
        {
            MethodRun::MethodRun(const Problem &problem, const std::vector<validity::Obstacle> &statics,
                                 const std::vector<Mover> &movers, const ReplanSettings &settings, const Method &method)
                : problem_(problem), movers_(movers), settings_(settings), method_(method)
            {
                const int copies = static_cast<int>(settings.predictionCopies);
                // Separate sensed worlds for planning and for execution: the planning thread works in its own scene,
                // updated only with the snapshot of its Query, while the execution thread's scene follows every
                // sensing.
                planSensed_.build(statics, movers, copies, settings.predictionHorizon);
                execSensed_.build(statics, movers, copies, settings.predictionHorizon);
                // The movers' true shapes over the short escape horizon (not grown, not the long prediction): what a
                // crossing or an escape must really avoid.
                planNow_.build(statics, movers, 3, settings.escapeHorizon, false);
                moving_.build({}, movers, 3, settings.escapeHorizon, false);
                // The movers alone, grown by the margin, one copy each: put where their observed velocity takes them
                // at a given time, for the timed checks of retiming.
                timed_.build({}, movers, 1, 0.);
                // The true world, with the movers on their key frames: only collisions are judged here; no method ever
                // reads it.
                world_ = std::make_shared<validity::Scene>();
                for (const auto &o : statics)
                    world_->add(o);
                for (const auto &m : movers)
                {
                    validity::Obstacle o;
                    o.name = m.name;
                    o.shape = m.shape;
                    o.trajectory = m.trajectory;
                    world_->add(o);
                }
                for (const auto &m : movers)
                {
                    // one scene per mover (true shape), to ask whether it would move into a standing robot
                    auto scene = std::make_shared<validity::Scene>();
                    validity::Obstacle o;
                    o.name = m.name;
                    o.shape = m.shape;
                    o.pose = validity::Scene::poseAt(m.trajectory, 0.);
                    scene->add(o);
                    yieldScenes_.push_back(scene);
                    yieldCtx_.push_back(context(scene));
                }
                planCtx_ = context(planSensed_.scene);
                planNowCtx_ = context(planNow_.scene);
                execCtx_ = context(execSensed_.scene);
                worldCtx_ = context(world_);
                movingCtx_ = context(moving_.scene);
                timedCtx_ = context(timed_.scene);
                auto staticScene = std::make_shared<validity::Scene>();
                for (const auto &o : statics)
                    staticScene->add(o);
                staticCtx_ = context(staticScene);
                planner_ = allocatePlanner(method.planner, planCtx_.setup->getSpaceInformation());
                applyPlannerParams(*planner_, PlannerSpec{method.planner, method.params, {}}, problem.file);
                // the method's own settings win over extras.replan.dual_roadmap_params (named as such in errors)
                if (method.reuse == Method::Reuse::DUAL)
                {
                    std::map<std::string, std::string> extra;
                    for (const auto &kv : settings.dualParams)
                        if (method.params.count(kv.first) == 0)
                            extra.insert(kv);
                    applyPlannerParams(*planner_, PlannerSpec{method.planner, extra, {}}, problem.file,
                                       "extras.replan.dual_roadmap_params");
                }
                if (auto dual = std::dynamic_pointer_cast<planners::DualRoadmap>(planner_))
                {
                    auto scene = planSensed_.scene;
                    // DualRoadmap learns of a change from the planning scene's counter, checked at every solve().
                    dual->setSceneChangeCounter(
                        [scene]
                        {
                            return scene->changeCount();
                        });
                    // An arm: the task level's hand (used only with task_level 1)
                    dual->setTaskMap(
                        planners::handTaskMap(planCtx_.checker->bodies(), planCtx_.setup->getStateSpace()));
                }
            }

            void MethodRun::setMoverTrajectory(std::size_t k, const std::vector<validity::TimedPose> &trajectory)
            {
                // Scene has no call that replaces a trajectory: the obstacle is removed and added again with it.
                world_->remove(movers_[k].name);
                validity::Obstacle o;
                o.name = movers_[k].name;
                o.shape = movers_[k].shape;
                o.trajectory = trajectory;
                world_->add(o);
            }

            void MethodRun::episode(const std::vector<std::vector<validity::TimedPose>> &trajectories, Results &results,
                                    std::vector<Frame> *frames, Trace *trace)
            {
                for (std::size_t k = 0; k < movers_.size(); ++k)
                    setMoverTrajectory(k, trajectories[k]);
                trajectories_ = trajectories;
                {
                    std::lock_guard<std::mutex> lock(snapshotMutex_);
                    // Snapshot ids from an earlier episode must not reach this episode's planner.
                    snapshots_.clear();
                }
                lastPoses_.clear();
                lastVelocities_.clear();

                NonStopExecutor exec(hooks(), executorSettings());
                double t = 0.;
                world_->setTime(0.);
                sense(0.);
                const auto &q = problem_.queries[0];
                exec.start(q.start, q.goal);
                const auto &worldSi = worldCtx_.setup->getSpaceInformation();
                ob::ScopedState<> prev(worldSi), cur(worldSi);
                toState(worldSi, q.start, prev.get());
                bool collided = false, reached = false;
                bool inContact = false;  // the previous step ended in collision (one contact is counted once)
                double nextSense = settings_.sensePeriod;
                std::vector<Configuration> executed{q.start};
                double nextFrame = 0.;
                // the movers where they are at time t, as the world checks the robot against them
                const auto record = [&](double time)
                {
                    trace->times.push_back(time);
                    trace->states.push_back(exec.configuration());
                    std::vector<Eigen::Isometry3d> poses;
                    for (const auto &tr : trajectories_)
                        poses.push_back(validity::Scene::poseAt(tr, time));
                    trace->poses.push_back(poses);
                };
                if (trace != nullptr)
                {
                    *trace = Trace{};
                    record(0.);
                    trace->states.back() = q.start;
                }
                while (t < settings_.episodeTime)
                {
                    // real_time 0 and clock cpu: the planner's time is charged on the simulated clock (fixed or
                    // its CPU time), so the simulation waits for it; clock wall: it runs on meanwhile
                    const bool charged = settings_.realTime <= 0. || settings_.cpuClock;
                    if (exec.planState() == NonStopExecutor::PlanState::PLANNING)
                    {
                        if (charged)
                            exec.waitForPlanner();
                        else
                            exec.waitForPlanner(settings_.dt * settings_.realTime);
                    }
                    t += settings_.dt;
                    if (settings_.obstaclesYield)
                        for (std::size_t k = 0; k < movers_.size(); ++k)
                        {
                            // a mover that would move into the robot (where it is, at prev) waits this step; the
                            // robot's own motion is checked below against the movers where they then are
                            const auto &ysi = yieldCtx_[k].setup->getSpaceInformation();
                            yieldScenes_[k]->setPose(movers_[k].name,
                                                     validity::Scene::poseAt(trajectories_[k], t - settings_.dt));
                            const bool before = ysi->isValid(prev.get());
                            yieldScenes_[k]->setPose(movers_[k].name, validity::Scene::poseAt(trajectories_[k], t));
                            if (!before || ysi->isValid(prev.get()))
                                continue;
                            // Waiting one step shifts every later key frame by dt: the mover resumes its path where it
                            // stopped.
                            for (auto &key : trajectories_[k])
                                key.time += settings_.dt;
                            setMoverTrajectory(k, trajectories_[k]);
                            ++results.obstacleWaits;
                        }
                    world_->setTime(t);
                    exec.step(settings_.dt);
                    toState(worldSi, exec.configuration(), cur.get());
                    // the swept motion of this step against the obstacles where they are now
                    const bool contact = !worldSi->isValid(prev.get()) || !worldSi->isValid(cur.get()) ||
                                         !worldSi->checkMotion(prev.get(), cur.get());
                    if (contact && !inContact)
                    {
                        // A new contact. The robot's fault unless it stood still during the step (then an obstacle
                        // drove into it); a moving robot hit from the side counts as its own: strict on purpose.
                        if (worldSi->distance(prev.get(), cur.get()) > 0.)
                            ++results.motionCollisions;
                        else
                            ++results.unavoidableCollisions;
                    }
                    inContact = contact;
                    if (contact)
                    {
                        if (!collided && std::getenv("MICHI_REPLAN_DEBUG") != nullptr)
                        {
                            const auto c = exec.configuration();
                            std::cerr << "\ncollision at t=" << t << " state "
                                      << NonStopExecutor::name(exec.execState()) << " q=(" << c[0] << "," << c[1] << ","
                                      << c[2] << ") v=" << exec.velocity() << ": "
                                      << worldCtx_.checker->describeCollision(c.data())
                                      << " | sensed: " << execCtx_.checker->describeCollision(c.data()) << "\n";
                            for (const auto &o : execSensed_.scene->obstacles())
                                std::cerr << "   " << o.name << " " << o.pose.translation().transpose() << "\n";
                            const auto &trs = exec.transitions();
                            for (std::size_t ti = trs.size() > 10 ? trs.size() - 10 : 0; ti < trs.size(); ++ti)
                                std::cerr << "  " << NonStopExecutor::name(trs[ti].from) << " -"
                                          << NonStopExecutor::name(trs[ti].signal) << "-> "
                                          << NonStopExecutor::name(trs[ti].to) << "\n";
                        }
                        collided = true;
                        ++results.collisionSteps;
                    }
                    worldSi->copyState(prev.get(), cur.get());
                    if (frames != nullptr)
                        executed.push_back(exec.configuration());
                    if (trace != nullptr)
                        record(t);
                    if (exec.execState() == NonStopExecutor::ExecState::FINISHED)
                    {
                        reached = true;
                        break;
                    }
                    // 1e-9: t is a sum of dt steps and would otherwise miss a sensing time by rounding.
                    if (t >= nextSense - 1e-9)
                    {
                        sense(t);
                        exec.geoChange();
                        nextSense += settings_.sensePeriod;
                        if (frames != nullptr && t >= nextFrame)
                        {
                            frames->push_back(Frame{t, executed, exec.remainingPath(), lastPoses_});
                            nextFrame += 1.;
                        }
                    }
                }
                if (frames != nullptr)
                    frames->push_back(Frame{t, executed, exec.remainingPath(), lastPoses_});
                exec.stop();
                // After stop(), wait for the planning thread: its query must not run into the next episode.
                exec.waitForPlanner();
                if (trace != nullptr)
                {
                    trace->trajectories = trajectories_;
                    trace->reached = reached;
                    trace->collided = collided;
                }

                const auto &st = exec.statistics();
                ++results.episodes;
                results.reached += reached ? 1 : 0;
                results.collisions += collided ? 1 : 0;
                results.stops += st.stops;
                results.deformations += st.deformations;
                results.retimings += st.retimings;
                results.replans += st.queries > 0 ? st.queries - 1 : 0;
                results.failures += st.failures;
                results.cancelled += st.cancelled;
                // the latency that counts is the one charged on the simulated clock: CPU time with clock cpu
                const bool cpu = settings_.realTime > 0. && settings_.cpuClock;
                for (std::size_t i = 0; i < st.latencies.size(); ++i)
                {
                    const double charged = cpu ? st.cpuLatencies[i] : st.latencies[i];
                    (i == 0 ? results.initialLatency : results.replanLatency).push_back(1000. * charged);
                    if (i > 0)
                    {
                        results.replanWall.push_back(1000. * st.latencies[i]);
                        results.replanCpu.push_back(1000. * st.cpuLatencies[i]);
                    }
                }
                if (reached)
                    results.timeToGoal.push_back(t);
                results.episodeEnd.push_back(t);
                if (auto dual = std::dynamic_pointer_cast<planners::DualRoadmap>(planner_))
                    results.learningEdges = dual->learningEdgeCount();
            }

            PlanningContext MethodRun::context(const validity::ScenePtr &scene) const
            {
                ContextOptions options;
                options.scene = scene;
                try
                {
                    return makePlanningContext(problem_, options);
                }
                catch (const ProblemError &e)
                {
                    // The scene here holds the movers grown by the margin and their predicted copies ("name~k"), both
                    // FCL-free of the query's ends in the problem's own scene: an end that touches one of them is the
                    // margin's doing (or the prediction's), so name the key to change rather than only "start: in
                    // collision" (found 2026-12-07)
                    const std::string what = e.what();
                    const std::string head = e.file() + ": " + e.key() + ": ";
                    const bool mover = std::any_of(movers_.begin(), movers_.end(),
                                                   [&](const Mover &m)
                                                   {
                                                       return what.find("'" + m.name + "'") != std::string::npos ||
                                                              what.find("'" + m.name + "~") != std::string::npos;
                                                   });
                    if ((e.key() == "start" || e.key() == "goal") && mover)
                    {
                        std::ostringstream margin;
                        margin << settings_.margin;
                        throw ProblemError(
                            e.file(), "extras.replan.margin",
                            "the " + e.key() + " touches a moving obstacle grown by the margin of " + margin.str() +
                                " m, or one of its predicted copies (" +
                                (what.compare(0, head.size(), head) == 0 ? what.substr(head.size()) : what) +
                                "): a smaller margin, or a start and goal farther from the movers' paths");
                    }
                    throw;
                }
            }

            NonStopSettings MethodRun::executorSettings() const
            {
                NonStopSettings s;
                s.speed = settings_.speed;
                s.deceleration = settings_.deceleration;
                s.safetyDistance = settings_.safetyDistance;
                s.stopMargin = settings_.stopMargin;
                s.retiming = settings_.retiming && method_.retiming;
                s.retimingHorizon = settings_.retimingHorizon;
                s.nonStop = method_.nonStop;
                if (settings_.realTime <= 0.)
                {
                    s.planningDelay = settings_.planningDelay;
                    s.synchronous = true;
                }
                else if (settings_.cpuClock)
                {
                    // every query planned to its end while the world waits, then charged what it really cost
                    s.cpuTimeScale = settings_.realTime;
                    s.synchronous = true;
                }
                return s;
            }

            void MethodRun::sense(double t)
            {
                Snapshot snap;
                for (std::size_t k = 0; k < movers_.size(); ++k)
                {
                    const Eigen::Isometry3d pose = validity::Scene::poseAt(trajectories_[k], t);
                    Eigen::Vector3d v = Eigen::Vector3d::Zero();
                    if (lastPoses_.size() == movers_.size() && t > lastSenseTime_)
                        // Velocity from the last two sensings (finite differences): the prediction never reads the key
                        // frames ahead.
                        v = (pose.translation() - lastPoses_[k].translation()) / (t - lastSenseTime_);
                    snap.poses.push_back(pose);
                    snap.velocities.push_back(v);
                }
                lastPoses_ = snap.poses;
                lastVelocities_ = snap.velocities;
                lastSenseTime_ = t;
                execSensed_.update(movers_, snap.poses, snap.velocities);
                moving_.update(movers_, snap.poses, snap.velocities);
                std::lock_guard<std::mutex> lock(snapshotMutex_);
                snapshots_[++snapshotId_] = std::move(snap);
            }
        }  // namespace replan
    }      // namespace tools
}  // namespace michi
