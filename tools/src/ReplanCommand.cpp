#include <michi/tools/ReplanCommand.h>

#include <michi/planners/DualRoadmap.h>
#include <michi/tools/FileOutput.h>
#include <michi/tools/NonStopExecutor.h>
#include <michi/tools/PathDeformation.h>
#include <michi/tools/PlannerRegistry.h>
#include <michi/tools/PlanningContext.h>
#include <michi/tools/Problem.h>
#include <michi/tools/SvgPlot.h>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/util/RandomNumbers.h>

#include <boost/filesystem.hpp>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace
        {
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
                double realTime{1.};           ///< while planning, simulated time follows the wall clock times this
                /** real_time 0: reproducible runs. Every query is charged planning_delay simulated seconds, the
                    simulation waits for the planner (in wall time) before it steps on, and the planner stops after
                    planning_work evaluations of its termination condition (a work count, not wall time). */
                double planningDelay{0.1};
                double planningWork{200000.};
                double escapeHorizon{0.};  ///< escapes avoid the obstacles' true shapes over this many seconds
                double crossTime{0.6};  ///< s: a robot inside a predicted region keeps going if it leaves it this fast
                bool deformation{true};
                /** obstacles_yield: a moving obstacle that would move into the robot waits (its key frames are
                    delayed by a step) instead; a robot that moves into an obstacle still collides. */
                bool obstaclesYield{false};
                DeformationSettings deform;
                double frames{8.};
                std::map<std::string, std::string> dualParams;  ///< dual_roadmap_params: set on both DualRoadmap runs
            };

            [[noreturn]] void fail(const std::string &file, const std::string &key, const std::string &what)
            {
                throw ProblemError(file, key, what);
            }

            ReplanSettings readSettings(const std::string &file)
            {
                ReplanSettings s;
                YAML::Node root;
                try
                {
                    root = YAML::LoadFile(file);
                }
                catch (const std::exception &e)
                {
                    fail(file, "", std::string("cannot read: ") + e.what());
                }
                const YAML::Node extras = root["extras"];
                if (!extras || !extras.IsMap() || !extras["replan"])
                    return s;
                const YAML::Node r = extras["replan"];
                if (!r.IsMap())
                    fail(file, "extras.replan", "expected a mapping");
                std::map<std::string, double *> numbers{
                    {"dt", &s.dt},
                    {"sense_period", &s.sensePeriod},
                    {"speed", &s.speed},
                    {"deceleration", &s.deceleration},
                    {"safety_distance", &s.safetyDistance},
                    {"margin", &s.margin},
                    {"prediction_horizon", &s.predictionHorizon},
                    {"prediction_copies", &s.predictionCopies},
                    {"lookahead", &s.lookahead},
                    {"stop_margin", &s.stopMargin},
                    {"planning_time", &s.planningTime},
                    {"episode_time", &s.episodeTime},
                    {"timing_jitter", &s.timingJitter},
                    {"speed_jitter", &s.speedJitter},
                    {"real_time", &s.realTime},
                    {"planning_delay", &s.planningDelay},
                    {"planning_work", &s.planningWork},
                    {"escape_horizon", &s.escapeHorizon},
                    {"cross_time", &s.crossTime},
                    {"deformation_distance", &s.deform.startDistance},
                    {"deformation_window", &s.deform.window},
                    {"deformation_spacing", &s.deform.spacing},
                    {"frames", &s.frames},
                };
                std::string expected;
                for (const auto &kv : numbers)
                    expected += kv.first + ", ";
                expected += "deformation, obstacles_yield, dual_roadmap_params";
                for (const auto &kv : r)
                {
                    const std::string key = kv.first.as<std::string>();
                    const std::string path = "extras.replan." + key;
                    if (key == "dual_roadmap_params")
                    {
                        if (!kv.second.IsMap())
                            fail(file, path, "expected a mapping of DualRoadmap parameter names to values");
                        for (const auto &p : kv.second)
                            s.dualParams[p.first.as<std::string>()] = p.second.as<std::string>();
                        continue;
                    }
                    if (key == "deformation" || key == "obstacles_yield")
                    {
                        try
                        {
                            (key == "deformation" ? s.deformation : s.obstaclesYield) = kv.second.as<bool>();
                        }
                        catch (const std::exception &)
                        {
                            fail(file, path, "expected true or false");
                        }
                        continue;
                    }
                    auto it = numbers.find(key);
                    if (it == numbers.end())
                        fail(file, path, "unknown key (expected " + expected + ")");
                    double v = 0.;
                    try
                    {
                        v = kv.second.as<double>();
                    }
                    catch (const std::exception &)
                    {
                        fail(file, path, "expected a number");
                    }
                    const bool mayBeZero = key == "safety_distance" || key == "margin" || key == "timing_jitter" ||
                                           key == "speed_jitter" || key == "real_time" || key == "stop_margin" ||
                                           key == "prediction_horizon" || key == "frames" || key == "escape_horizon" ||
                                           key == "cross_time" || key == "planning_delay";
                    if (!std::isfinite(v) || v < 0. || (!mayBeZero && v == 0.))
                        fail(file, path, mayBeZero ? "expected a number >= 0" : "expected a number > 0");
                    *it->second = v;
                }
                if (s.speedJitter >= 1.)
                    fail(file, "extras.replan.speed_jitter", "expected a fraction below 1");
                if (s.predictionCopies < 1.)
                    fail(file, "extras.replan.prediction_copies", "expected at least 1");
                return s;
            }

            validity::ShapePtr grow(const validity::Shape &shape, double m, const std::string &file,
                                    const std::string &key)
            {
                const Eigen::Vector3d &z = shape.size();
                switch (shape.type())
                {
                    case validity::Shape::Type::BOX:
                        return validity::Shape::box(z + Eigen::Vector3d::Constant(2. * m));
                    case validity::Shape::Type::SPHERE:
                        return validity::Shape::sphere(z.x() + m);
                    case validity::Shape::Type::CYLINDER:
                        return validity::Shape::cylinder(z.x() + m, z.z() + 2. * m);
                    case validity::Shape::Type::CAPSULE:
                        return validity::Shape::capsule(z.x() + m, z.z());
                    default:
                        fail(file, key,
                             "a moving obstacle must be a box, sphere, cylinder or capsule for michi replan "
                             "(it is grown by extras.replan.margin), got " +
                                 shape.describe());
                }
            }

            struct Mover
            {
                std::string name;
                validity::ShapePtr shape;
                validity::ShapePtr grown;
                std::vector<validity::TimedPose> trajectory;  ///< as in the file
            };

            /** The world as the robot senses it: static obstacles, and each moving obstacle grown by the margin
                and repeated along its observed velocity over the prediction horizon. */
            struct SensedWorld
            {
                validity::ScenePtr scene{std::make_shared<validity::Scene>()};
                int copies{1};
                double horizon{0.};

                /** \e grown false: the movers' true shapes. */
                void build(const std::vector<validity::Obstacle> &statics, const std::vector<Mover> &movers, int n,
                           double h, bool grown = true)
                {
                    copies = n;
                    horizon = h;
                    for (const auto &o : statics)
                        scene->add(o);
                    for (const auto &m : movers)
                        for (int i = 0; i < copies; ++i)
                        {
                            validity::Obstacle o;
                            o.name = m.name + "~" + std::to_string(i);
                            o.shape = grown ? m.grown : m.shape;
                            o.pose = validity::Scene::poseAt(m.trajectory, 0.);
                            scene->add(o);
                        }
                }
                void update(const std::vector<Mover> &movers, const std::vector<Eigen::Isometry3d> &poses,
                            const std::vector<Eigen::Vector3d> &velocities)
                {
                    for (std::size_t k = 0; k < movers.size(); ++k)
                        for (int i = 0; i < copies; ++i)
                        {
                            Eigen::Isometry3d pose = poses[k];
                            const double f = copies > 1 ? static_cast<double>(i) / (copies - 1) : 0.;
                            pose.translation() += velocities[k] * horizon * f;
                            scene->setPose(movers[k].name + "~" + std::to_string(i), pose);
                        }
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
            };

            std::vector<Method> allMethods()
            {
                return {
                    {"dual", "michi::DualRoadmap", "michi::DualRoadmap", {}, Method::Reuse::DUAL, false},
                    {"rrtconnect", "geometric::RRTConnect", "geometric::RRTConnect", {}, Method::Reuse::SCRATCH, true},
                    {"prm", "geometric::PRM", "geometric::PRM", {}, Method::Reuse::SCRATCH, true},
                    {"lazyprm",
                     "geometric::LazyPRM (roadmap kept)",
                     "geometric::LazyPRM",
                     {},
                     Method::Reuse::KEEP_ROADMAP,
                     true},
                    {"dual-no-learning",
                     "michi::DualRoadmap (no learning roadmap)",
                     "michi::DualRoadmap",
                     {{"use_learning", "0"}},
                     Method::Reuse::DUAL,
                     false},
                };
            }

            struct Results
            {
                unsigned int episodes{0}, reached{0}, collisions{0}, collisionSteps{0}, stops{0}, deformations{0},
                    replans{0}, cancelled{0}, failures{0}, obstacleWaits{0};
                std::vector<double> replanLatency;   ///< ms
                std::vector<double> initialLatency;  ///< ms
                std::vector<double> timeToGoal;      ///< simulated s
                std::vector<double> episodeEnd;      ///< simulated s at which each episode ended
                double wallSeconds{0.};
                std::size_t learningEdges{0};
            };

            double percentile(std::vector<double> v, double p)
            {
                if (v.empty())
                    return std::numeric_limits<double>::quiet_NaN();
                std::sort(v.begin(), v.end());
                const std::size_t rank = static_cast<std::size_t>(std::ceil(p / 100. * static_cast<double>(v.size())));
                return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
            }

            std::string num(double v)
            {
                if (!std::isfinite(v))
                    return "null";
                std::ostringstream s;
                s << std::setprecision(6) << v;
                return s.str();
            }

            /** One frame of the picture: time, robot trajectory so far, remaining plan, obstacle poses. */
            struct Frame
            {
                double time;
                std::vector<Configuration> executed;
                ConfigurationPath plan;
                std::vector<Eigen::Isometry3d> poses;
            };

            /** Everything one method needs over all episodes. */
            class MethodRun
            {
            public:
                MethodRun(const Problem &problem, const std::vector<validity::Obstacle> &statics,
                          const std::vector<Mover> &movers, const ReplanSettings &settings, const Method &method)
                    : problem_(problem), movers_(movers), settings_(settings), method_(method)
                {
                    const int copies = static_cast<int>(settings.predictionCopies);
                    planSensed_.build(statics, movers, copies, settings.predictionHorizon);
                    execSensed_.build(statics, movers, copies, settings.predictionHorizon);
                    planNow_.build(statics, movers, 3, settings.escapeHorizon, false);
                    moving_.build({}, movers, 3, settings.escapeHorizon, false);
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
                    planner_ = allocatePlanner(method.planner, planCtx_.setup->getSpaceInformation());
                    std::map<std::string, std::string> params = method.params;
                    if (method.reuse == Method::Reuse::DUAL)
                        for (const auto &kv : settings.dualParams)
                            params.insert(kv);
                    applyPlannerParams(*planner_, PlannerSpec{method.planner, params}, problem.file);
                    if (auto dual = std::dynamic_pointer_cast<planners::DualRoadmap>(planner_))
                    {
                        auto scene = planSensed_.scene;
                        dual->setSceneChangeCounter(
                            [scene]
                            {
                                return scene->changeCount();
                            });
                    }
                }

                /** Run one episode whose moving obstacles follow \e trajectories. */
                void episode(const std::vector<std::vector<validity::TimedPose>> &trajectories, Results &results,
                             std::vector<Frame> *frames)
                {
                    for (std::size_t k = 0; k < movers_.size(); ++k)
                    {
                        world_->remove(movers_[k].name);
                        validity::Obstacle o;
                        o.name = movers_[k].name;
                        o.shape = movers_[k].shape;
                        o.trajectory = trajectories[k];
                        world_->add(o);
                    }
                    trajectories_ = trajectories;
                    {
                        std::lock_guard<std::mutex> lock(snapshotMutex_);
                        snapshots_.clear();
                    }
                    lastPoses_.clear();

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
                    double nextSense = settings_.sensePeriod;
                    std::vector<Configuration> executed{q.start};
                    double nextFrame = 0.;
                    while (t < settings_.episodeTime)
                    {
                        const bool reproducible = settings_.realTime <= 0.;
                        if (exec.planState() == NonStopExecutor::PlanState::PLANNING)
                        {
                            if (reproducible)
                                exec.waitForPlanner();  // the planner's time is charged on the simulated clock
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
                                for (auto &key : trajectories_[k])
                                    key.time += settings_.dt;
                                world_->remove(movers_[k].name);
                                validity::Obstacle o;
                                o.name = movers_[k].name;
                                o.shape = movers_[k].shape;
                                o.trajectory = trajectories_[k];
                                world_->add(o);
                                ++results.obstacleWaits;
                            }
                        world_->setTime(t);
                        exec.step(settings_.dt);
                        toState(worldSi, exec.configuration(), cur.get());
                        // the swept motion of this step against the obstacles where they are now
                        if (!worldSi->isValid(prev.get()) || !worldSi->isValid(cur.get()) ||
                            !worldSi->checkMotion(prev.get(), cur.get()))
                        {
                            if (!collided && std::getenv("MICHI_REPLAN_DEBUG") != nullptr)
                            {
                                const auto c = exec.configuration();
                                std::cerr << "\ncollision at t=" << t << " state "
                                          << NonStopExecutor::name(exec.execState()) << " q=(" << c[0] << "," << c[1]
                                          << "," << c[2] << ") v=" << exec.velocity() << ": "
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
                        if (exec.execState() == NonStopExecutor::ExecState::FINISHED)
                        {
                            reached = true;
                            break;
                        }
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
                    exec.waitForPlanner();

                    const auto &st = exec.statistics();
                    ++results.episodes;
                    results.reached += reached ? 1 : 0;
                    results.collisions += collided ? 1 : 0;
                    results.stops += st.stops;
                    results.deformations += st.deformations;
                    results.replans += st.queries > 0 ? st.queries - 1 : 0;
                    results.failures += st.failures;
                    results.cancelled += st.cancelled;
                    for (std::size_t i = 0; i < st.latencies.size(); ++i)
                        (i == 0 ? results.initialLatency : results.replanLatency).push_back(1000. * st.latencies[i]);
                    if (reached)
                        results.timeToGoal.push_back(t);
                    results.episodeEnd.push_back(t);
                    if (auto dual = std::dynamic_pointer_cast<planners::DualRoadmap>(planner_))
                        results.learningEdges = dual->learningEdgeCount();
                }

            private:
                PlanningContext context(const validity::ScenePtr &scene) const
                {
                    Problem p = problem_;
                    p.scene = scene;
                    return makePlanningContext(p, 0);
                }

                static void toState(const ob::SpaceInformationPtr &si, const Configuration &q, ob::State *s)
                {
                    si->getStateSpace()->copyFromReals(s, q);
                    si->getStateSpace()->enforceBounds(s);
                }
                static Configuration toReals(const ob::SpaceInformationPtr &si, const ob::State *s)
                {
                    Configuration q;
                    si->getStateSpace()->copyToReals(q, s);
                    return q;
                }

                /** Arc length to the first interference of \e path (its first state valid) within \e lookahead. */
                static double firstInterferenceFree(const ob::SpaceInformationPtr &esi, const ConfigurationPath &path,
                                                    double lookahead)
                {
                    ob::ScopedState<> a(esi), b(esi);
                    toState(esi, path[0], a.get());
                    double arc = 0.;
                    for (std::size_t i = 1; i < path.size() && arc < lookahead; ++i)
                    {
                        toState(esi, path[i], b.get());
                        const double len = esi->distance(a.get(), b.get());
                        std::pair<ob::State *, double> last(nullptr, 0.);
                        if (!esi->satisfiesBounds(b.get()) || !esi->checkMotion(a.get(), b.get(), last))
                            return arc + last.second * len;
                        arc += len;
                        esi->copyState(a.get(), b.get());
                    }
                    return std::numeric_limits<double>::infinity();
                }

                NonStopSettings executorSettings() const
                {
                    NonStopSettings s;
                    s.speed = settings_.speed;
                    s.deceleration = settings_.deceleration;
                    s.safetyDistance = settings_.safetyDistance;
                    s.stopMargin = settings_.stopMargin;
                    if (settings_.realTime <= 0.)
                    {
                        s.planningDelay = settings_.planningDelay;
                        s.synchronous = true;
                    }
                    return s;
                }

                /** Sense the world at time t: obstacle poses and velocities (from the previous sensing). */
                void sense(double t)
                {
                    Snapshot snap;
                    for (std::size_t k = 0; k < movers_.size(); ++k)
                    {
                        const Eigen::Isometry3d pose = validity::Scene::poseAt(trajectories_[k], t);
                        Eigen::Vector3d v = Eigen::Vector3d::Zero();
                        if (lastPoses_.size() == movers_.size() && t > lastSenseTime_)
                            v = (pose.translation() - lastPoses_[k].translation()) / (t - lastSenseTime_);
                        snap.poses.push_back(pose);
                        snap.velocities.push_back(v);
                    }
                    lastPoses_ = snap.poses;
                    lastSenseTime_ = t;
                    execSensed_.update(movers_, snap.poses, snap.velocities);
                    moving_.update(movers_, snap.poses, snap.velocities);
                    std::lock_guard<std::mutex> lock(snapshotMutex_);
                    snapshots_[++snapshotId_] = std::move(snap);
                }

                NonStopHooks hooks()
                {
                    NonStopHooks h;
                    const auto esi = execCtx_.setup->getSpaceInformation();
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
                    const double crossDistance = settings_.speed * settings_.crossTime;
                    h.firstInterference = [this, esi, msi, lookahead, crossDistance](const ConfigurationPath &path)
                    {
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
                                        if (!msi->checkMotion(y.get(), x.get()))
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
                                if (!msi->checkMotion(a.get(), b.get()))
                                    return 0.;
                                arc += esi->distance(a.get(), b.get());
                                esi->copyState(a.get(), b.get());
                            }
                            if (!esi->isValid(a.get()))
                                return 0.;
                            first = target + 1;
                        }
                        for (std::size_t i = first; i < path.size() && arc < lookahead; ++i)
                        {
                            toState(esi, path[i], b.get());
                            const double len = esi->distance(a.get(), b.get());
                            std::pair<ob::State *, double> last(nullptr, 0.);
                            if (!esi->satisfiesBounds(b.get()) || !esi->checkMotion(a.get(), b.get(), last))
                                return arc + last.second * len;
                            arc += len;
                            esi->copyState(a.get(), b.get());
                        }
                        return inf;
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
                    const auto psi = planCtx_.setup->getSpaceInformation();
                    h.plan = [this, psi](const Configuration &from, const Configuration &goal, std::uint64_t id,
                                         const std::atomic<bool> &cancel, ConfigurationPath &path)
                    {
                        Snapshot snap;
                        {
                            std::lock_guard<std::mutex> lock(snapshotMutex_);
                            snap = snapshots_.at(id);
                        }
                        planSensed_.update(movers_, snap.poses, snap.velocities);
                        planNow_.update(movers_, snap.poses, snap.velocities);
                        ob::ScopedState<> s(psi), g(psi);
                        toState(psi, from, s.get());
                        toState(psi, goal, g.get());
                        ConfigurationPath prefix;
                        if (!psi->isValid(s.get()))
                        {
                            // escape: the start is within the margin of a (predicted) obstacle; move first, along
                            // a straight motion free of the obstacles as they are, to a nearby state outside it
                            if (!escape(s.get(), cancel))
                                return false;
                            prefix.push_back(from);
                            {
                                std::lock_guard<std::mutex> lock(escapeMutex_);
                                escapeTargets_.push_back(toReals(psi, s.get()));
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
                                planner_->clear();
                                break;
                        }
                        planner_->setProblemDefinition(pdef);
                        if (!planner_->isSetup())
                            planner_->setup();
                        // reproducible runs: DualRoadmap stops after a work count (evaluations of the condition:
                        // one per search, lazy edge check and sample) instead of wall time, with 10 x planning_time
                        // as a wall-clock backstop; the baselines keep planning_time (their work per evaluation
                        // differs too much for one count to be fair)
                        const bool counted = settings_.realTime <= 0. && method_.reuse == Method::Reuse::DUAL;
                        const unsigned long work = counted ? static_cast<unsigned long>(settings_.planningWork)
                                                           : std::numeric_limits<unsigned long>::max();
                        std::atomic<unsigned long> evaluations{0};  // PRM evaluates it in two threads
                        const ob::PlannerTerminationCondition ptc = ob::plannerOrTerminationCondition(
                            ob::timedPlannerTerminationCondition(settings_.planningTime * (counted ? 10. : 1.)),
                            ob::PlannerTerminationCondition(
                                [&cancel, &evaluations, work]
                                {
                                    return cancel.load() || ++evaluations > work;
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

                /** Replace \e s by a state valid in the planning scene reached from it by a motion that is free in
                    the world as it is now (planning thread). */
                bool escape(ob::State *s, const std::atomic<bool> &cancel)
                {
                    const auto psi = planCtx_.setup->getSpaceInformation();
                    const auto nsi = planNowCtx_.setup->getSpaceInformation();
                    if (!nsi->isValid(s))
                        return false;
                    if (!escapeSampler_)
                        escapeSampler_ = psi->allocStateSampler();
                    ob::ScopedState<> near(psi);
                    const double extent = psi->getMaximumExtent();
                    for (int i = 0; i < 400 && !cancel; ++i)
                    {
                        const double radius = extent * 0.01 * (1. + i / 40);
                        escapeSampler_->sampleUniformNear(near.get(), s, radius);
                        if (psi->isValid(near.get()) && nsi->checkMotion(s, near.get()))
                        {
                            psi->copyState(s, near.get());
                            return true;
                        }
                    }
                    return false;
                }

                const Problem &problem_;
                std::vector<Mover> movers_;
                ob::StateSamplerPtr escapeSampler_;
                std::mutex escapeMutex_;
                std::vector<Configuration> escapeTargets_;  ///< the last escapes the planning thread made
                ReplanSettings settings_;
                Method method_;
                SensedWorld planSensed_, execSensed_, planNow_;
                validity::ScenePtr world_;
                SensedWorld moving_;  ///< the movers only, true shapes over escape_horizon (clearance, deformation)
                PlanningContext planCtx_, planNowCtx_, execCtx_, worldCtx_, movingCtx_;
                ob::PlannerPtr planner_;
                std::vector<std::vector<validity::TimedPose>> trajectories_;
                std::vector<validity::ScenePtr> yieldScenes_;
                std::vector<PlanningContext> yieldCtx_;
                std::vector<Eigen::Isometry3d> lastPoses_;
                double lastSenseTime_{0.};
                std::mutex snapshotMutex_;
                std::map<std::uint64_t, Snapshot> snapshots_;
                std::uint64_t snapshotId_{0};
            };

            void writeResults(std::ostream &out, const Results &r, const std::string &indent)
            {
                out << indent << "\"episodes\": " << r.episodes << ",\n"
                    << indent << "\"reached_goal\": " << r.reached << ",\n"
                    << indent << "\"collisions\": " << r.collisions << ",\n"
                    << indent << "\"collision_steps\": " << r.collisionSteps << ",\n"
                    << indent << "\"stops\": " << r.stops << ",\n"
                    << indent << "\"deformations\": " << r.deformations << ",\n"
                    << indent << "\"replans\": " << r.replans << ",\n"
                    << indent << "\"replans_found\": " << r.replanLatency.size() << ",\n"
                    << indent << "\"cancelled_queries\": " << r.cancelled << ",\n"
                    << indent << "\"planning_failures\": " << r.failures << ",\n"
                    << indent << "\"obstacle_waits\": " << r.obstacleWaits << ",\n"
                    << indent << "\"replan_latency_ms_median\": " << num(percentile(r.replanLatency, 50.)) << ",\n"
                    << indent << "\"replan_latency_ms_p95\": " << num(percentile(r.replanLatency, 95.)) << ",\n"
                    << indent << "\"initial_plan_ms_median\": " << num(percentile(r.initialLatency, 50.)) << ",\n"
                    << indent << "\"time_to_goal_s_median\": " << num(percentile(r.timeToGoal, 50.)) << ",\n"
                    << indent << "\"learning_edges\": " << r.learningEdges << ",\n"
                    << indent << "\"episode_end_s\": [";
                for (std::size_t i = 0; i < r.episodeEnd.size(); ++i)
                    out << (i > 0 ? ", " : "") << num(r.episodeEnd[i]);
                out << "],\n" << indent << "\"wall_seconds\": " << num(r.wallSeconds);
            }
        }  // namespace

        std::string runReplan(const ReplanOptions &options)
        {
            if (options.episodes == 0)
                throw std::invalid_argument("--episodes must be a positive integer");
            // before anything draws a seed from OMPL's seed generator: then every planner's and sampler's random
            // numbers follow from --seed (reproducible runs, extras.replan.real_time 0)
            ompl::RNG::setSeed(options.seed);
            const Problem problem = loadProblem(options.problemFile);
            const ReplanSettings settings = readSettings(options.problemFile);

            std::vector<validity::Obstacle> statics;
            std::vector<Mover> movers;
            const auto obstacles = problem.scene->obstacles();
            for (std::size_t i = 0; i < obstacles.size(); ++i)
            {
                const auto &o = obstacles[i];
                if (o.trajectory.size() < 2)
                {
                    validity::Obstacle s = o;
                    if (!s.trajectory.empty())
                        s.pose = s.trajectory.front().pose;
                    s.trajectory.clear();
                    statics.push_back(s);
                    continue;
                }
                Mover m;
                m.name = o.name;
                m.shape = o.shape;
                m.grown = grow(*o.shape, settings.margin, problem.file, "scene.obstacles (" + o.name + ")");
                m.trajectory = o.trajectory;
                movers.push_back(m);
            }
            if (movers.empty())
                throw ProblemError(problem.file, "scene.obstacles",
                                   "michi replan needs a moving obstacle (one with a trajectory of two or more key "
                                   "frames)");

            std::vector<Method> methods;
            const auto all = allMethods();
            if (options.methods.empty())
                methods = all;
            else
                for (const auto &name : options.methods)
                {
                    auto it = std::find_if(all.begin(), all.end(),
                                           [&](const Method &m)
                                           {
                                               return m.id == name || m.label == name;
                                           });
                    if (it == all.end())
                    {
                        std::string known;
                        for (const auto &m : all)
                            known += (known.empty() ? "" : ", ") + m.id;
                        throw std::invalid_argument("unknown method '" + name + "' (known: " + known + ")");
                    }
                    methods.push_back(*it);
                }

            // the episodes' obstacle timings: the same draws for every method
            std::vector<std::vector<std::vector<validity::TimedPose>>> episodes(options.episodes);
            for (unsigned int e = 0; e < options.episodes; ++e)
            {
                ompl::RNG rng(options.seed * 100003u + e);
                for (const auto &m : movers)
                {
                    const double shift = rng.uniformReal(-settings.timingJitter, settings.timingJitter);
                    const double speed = rng.uniformReal(1. - settings.speedJitter, 1. + settings.speedJitter);
                    const double t0 = m.trajectory.front().time;
                    std::vector<validity::TimedPose> tr = m.trajectory;
                    for (auto &k : tr)
                        k.time = std::max(0., t0 + shift) + (k.time - t0) / speed;
                    episodes[e].push_back(tr);
                }
            }

            std::vector<Results> results(methods.size());
            std::vector<Frame> frames;
            for (std::size_t mi = 0; mi < methods.size(); ++mi)
            {
                MethodRun run(problem, statics, movers, settings, methods[mi]);
                const auto begin = std::chrono::steady_clock::now();
                for (unsigned int e = 0; e < options.episodes; ++e)
                {
                    run.episode(episodes[e], results[mi], mi == 0 && e == 0 ? &frames : nullptr);
                    if (options.progress != nullptr)
                        *options.progress << "\r" << methods[mi].label << ": episode " << (e + 1) << "/"
                                          << options.episodes << std::flush;
                }
                results[mi].wallSeconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
                if (options.progress != nullptr)
                    *options.progress << "\n";
            }

            std::ostringstream json;
            json << "{\n  \"scenario\": " << jsonString(problem.name)
                 << ",\n  \"problem\": " << jsonString(problem.file) << ",\n  \"seed\": " << options.seed
                 << ",\n  \"method\": " << jsonString(methods[0].label) << ",\n";
            writeResults(json, results[0], "  ");
            json << ",\n  \"settings\": {\"dt\": " << num(settings.dt)
                 << ", \"sense_period\": " << num(settings.sensePeriod) << ", \"speed\": " << num(settings.speed)
                 << ", \"deceleration\": " << num(settings.deceleration)
                 << ", \"safety_distance\": " << num(settings.safetyDistance)
                 << ", \"margin\": " << num(settings.margin)
                 << ", \"prediction_horizon\": " << num(settings.predictionHorizon)
                 << ", \"planning_time\": " << num(settings.planningTime)
                 << ", \"real_time\": " << num(settings.realTime)
                 << ", \"planning_delay\": " << num(settings.planningDelay)
                 << ", \"planning_work\": " << num(settings.planningWork)
                 << ", \"episode_time\": " << num(settings.episodeTime)
                 << ", \"timing_jitter\": " << num(settings.timingJitter)
                 << ", \"speed_jitter\": " << num(settings.speedJitter)
                 << ", \"deformation\": " << (settings.deformation ? "true" : "false")
                 << ", \"obstacles_yield\": " << (settings.obstaclesYield ? "true" : "false") << "},\n";
            json << "  \"baselines\": {";
            for (std::size_t mi = 1; mi < methods.size(); ++mi)
            {
                json << (mi > 1 ? "," : "") << "\n    " << jsonString(methods[mi].label) << ": {\n";
                writeResults(json, results[mi], "      ");
                const double ratio =
                    percentile(results[mi].replanLatency, 50.) / percentile(results[0].replanLatency, 50.);
                json << ",\n      \"median_latency_ratio_to_method\": " << num(ratio) << "\n    }";
            }
            json << "\n  }\n}\n";

            // staged output: nothing in DIR unless everything was written (an old episode/ folder is replaced)
            StagedDirectory stage(options.outDir);
            fs::create_directories(stage.path("episode"));
            const std::size_t want = std::max<std::size_t>(1, static_cast<std::size_t>(settings.frames));
            std::vector<std::size_t> chosen;
            for (std::size_t i = 0; i < want && !frames.empty(); ++i)
                chosen.push_back(frames.size() == 1 ? 0 : i * (frames.size() - 1) / std::max<std::size_t>(1, want - 1));
            chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
            int n = 0;
            for (std::size_t idx : chosen)
            {
                const Frame &f = frames[idx];
                Problem p = problem;
                p.scene = std::make_shared<validity::Scene>();
                for (const auto &o : statics)
                    p.scene->add(o);
                for (std::size_t k = 0; k < movers.size(); ++k)
                {
                    validity::Obstacle o;
                    o.name = movers[k].name;
                    o.shape = movers[k].shape;
                    o.pose = k < f.poses.size() ? f.poses[k] : validity::Scene::poseAt(movers[k].trajectory, 0.);
                    p.scene->add(o);
                }
                std::ostringstream name;
                name << "frame_" << std::setw(2) << std::setfill('0') << n++ << ".svg";
                std::ostringstream label;
                label << std::fixed << std::setprecision(1) << "t = " << f.time << " s: executed";
                std::vector<PlotPath> paths{PlotPath{label.str(), f.executed}};
                if (f.plan.size() > 1)
                    paths.push_back(PlotPath{"current plan", f.plan});
                writeProblemSvg(p, paths, (stage.path("episode") / name.str()).string());
            }
            writeAtomically(json.str(), stage.path("replan.json").string());
            stage.commit();
            return json.str();
        }
    }  // namespace tools
}  // namespace michi
