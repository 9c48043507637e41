#include <michi/planners/dual_roadmap/InterferencePrediction.h>
#include <michi/planners/dual_roadmap/NonStopController.h>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace planners
    {
        class NonStopController::ObservedWorld : public ob::StateValidityChecker
        {
        public:
            explicit ObservedWorld(const ob::SpaceInformationPtr &si) : ob::StateValidityChecker(si)
            {
            }
            void set(ob::StateValidityCheckerPtr world)
            {
                world_ = std::move(world);
            }
            // Nothing is valid before a world was observed.
            bool isValid(const ob::State *state) const override
            {
                return world_ && world_->isValid(state);
            }
            double clearance(const ob::State *state) const override
            {
                return world_ ? world_->clearance(state) : 0.;
            }

        private:
            ob::StateValidityCheckerPtr world_;
        };

        NonStopController::NonStopController(const ob::StateSpacePtr &space, NonStopControllerSettings settings,
                                             PlannerAllocator allocator)
            : settings_(std::move(settings)), space_(space)
        {
            if (!space_)
                throw std::invalid_argument("NonStopController: no state space");
            const auto &s = settings_;
            const auto finite = [](double v)
            {
                return std::isfinite(v);
            };
            if (!(s.planningTime > 0. && finite(s.planningTime)) ||
                !(s.trackingTolerance > 0. && finite(s.trackingTolerance)) || !(s.period > 0. && finite(s.period)) ||
                !(s.horizon >= 0. && finite(s.horizon)) || !(s.lookahead > 0.) ||
                !(s.checkResolution > 0. && s.checkResolution <= 1.))
                throw std::invalid_argument(
                    "NonStopController: planningTime, trackingTolerance and period must be positive and finite, "
                    "lookahead positive, horizon finite and not negative, checkResolution in (0, 1]");
            // update() returns horizon / period + 1 samples every call
            if (s.horizon / s.period > 1e6)
                throw std::invalid_argument("NonStopController: horizon / period gives more than 10^6 samples");
            settings_.motion.brakeAtEnd = true;  // a robot's trajectory ends at rest
            // Two SpaceInformation on one space: the robot loop's thread checks paths against the newest world while
            // the planning thread plans in the world of its query.
            for (auto *si : {&execSi_, &planSi_})
            {
                *si = std::make_shared<ob::SpaceInformation>(space_);
                auto world = std::make_shared<ObservedWorld>(*si);
                (*si)->setStateValidityChecker(world);
                (*si)->setStateValidityCheckingResolution(s.checkResolution);
                (*si)->setup();
                (si == &execSi_ ? execWorld_ : planWorld_) = world;
            }
            planner_ = allocator ? allocator(planSi_) : std::make_shared<DualRoadmap>(planSi_);
            if (!planner_)
                throw std::invalid_argument("NonStopController: the planner allocator returned no planner");
            if (auto dual = std::dynamic_pointer_cast<DualRoadmap>(planner_))
                // the observation a query plans in: a new one is a new scene (notified with its region in plan())
                dual->setSceneChangeCounter(
                    [this]
                    {
                        return planned_;
                    });
            // Here, not on the planning thread: setup() may set the shared space up again.
            planner_->setup();
            // the executor first: it refuses bad motion settings, and states allocated before a throw would leak
            executor_ = std::make_unique<NonStopExecutor>(hooks(), settings_.motion);
            scratchA_ = space_->allocState();
            scratchB_ = space_->allocState();
            scratchOut_ = space_->allocState();
        }

        NonStopController::~NonStopController()
        {
            executor_.reset();  // joins the planning thread before anything it uses goes
            space_->freeState(scratchA_);
            space_->freeState(scratchB_);
            space_->freeState(scratchOut_);
        }

        Configuration NonStopController::toReals(const ob::State *state) const
        {
            Configuration q;
            space_->copyToReals(q, state);
            return q;
        }

        Configuration NonStopController::measuredReals(const ob::State *state, const char *what) const
        {
            if (state == nullptr)
                throw std::invalid_argument(std::string("NonStopController: no ") + what);
            Configuration q = toReals(state);
            // A NaN went on into the arc lengths and from there into an index: an OMPL assertion aborted the process
            // one update later.
            for (const double v : q)
                if (!std::isfinite(v))
                    throw std::invalid_argument(std::string("NonStopController: the ") + what +
                                                " has a value that is not a finite number");
            return q;
        }

        void NonStopController::observeWorld(ob::StateValidityCheckerPtr world, DualRoadmap::ChangeRegion changed)
        {
            if (!world)
                throw std::invalid_argument("NonStopController::observeWorld: no validity checker");
            execWorld_->set(world);
            {
                std::lock_guard<std::mutex> lock(observationMutex_);
                observations_[++observed_] = Observation{std::move(world), std::move(changed)};
            }
            executor_->geoChange();
        }

        void NonStopController::start(const ob::State *measured, const ob::State *goal)
        {
            {
                std::lock_guard<std::mutex> lock(observationMutex_);
                if (observed_ == 0)
                    throw std::logic_error("NonStopController::start: no world observed yet (observeWorld)");
            }
            Configuration from = measuredReals(measured, "measured state"), to = measuredReals(goal, "goal");
            if (!space_->satisfiesBounds(goal))
                throw std::invalid_argument("NonStopController::start: the goal is outside the state space's bounds");
            executor_->start(std::move(from), std::move(to));
        }

        TimedPath NonStopController::update(const ob::State *measured, double time)
        {
            if (!std::isfinite(time) || (haveTime_ && time < time_))
                throw std::invalid_argument("NonStopController::update: the time must be finite and never decrease");
            Configuration robot = measuredReals(measured, "measured state");  // before anything moves
            const double dt = haveTime_ ? time - time_ : 0.;
            time_ = time;
            haveTime_ = true;
            // the model first moves as commanded, then goes where the robot really is
            executor_->step(dt);
            executor_->track(robot, settings_.trackingTolerance);
            return executor_->preview(settings_.horizon, settings_.period);
        }

        void NonStopController::stop()
        {
            executor_->stop();
        }

        NonStopHooks NonStopController::hooks()
        {
            NonStopHooks h;
            h.sensedWorld = [this]
            {
                std::lock_guard<std::mutex> lock(observationMutex_);
                return observed_;
            };
            // distance and interpolate run on the robot loop's thread only: its scratch states
            h.distance = [this](const Configuration &a, const Configuration &b)
            {
                space_->copyFromReals(scratchA_, a);
                space_->copyFromReals(scratchB_, b);
                return space_->distance(scratchA_, scratchB_);
            };
            h.interpolate = [this](const Configuration &a, const Configuration &b, double t, Configuration &out)
            {
                space_->copyFromReals(scratchA_, a);
                space_->copyFromReals(scratchB_, b);
                space_->interpolate(scratchA_, scratchB_, t, scratchOut_);
                space_->copyToReals(out, scratchOut_);
            };
            h.firstInterference = [this](const ConfigurationPath &path)
            {
                return firstInterference(execSi_, path, settings_.lookahead);
            };
            h.clearance = [this](const Configuration &q)
            {
                // asked only to compare with the safety distance; a checker without clearance() says 0
                if (!(settings_.motion.safetyDistance > 0.))
                    return std::numeric_limits<double>::infinity();
                space_->copyFromReals(scratchA_, q);
                return execWorld_->clearance(scratchA_);
            };
            h.plan = [this](const Configuration &from, const Configuration &goal, std::uint64_t snapshot,
                            const std::atomic<bool> &cancel, ConfigurationPath &path)
            {
                return plan(from, goal, snapshot, cancel, path);
            };
            return h;
        }

        bool NonStopController::plan(const Configuration &from, const Configuration &goal, std::uint64_t snapshot,
                                     const std::atomic<bool> &cancel, ConfigurationPath &path)
        {
            // planning thread
            ob::StateValidityCheckerPtr world;
            std::vector<DualRoadmap::ChangeRegion> changes;
            {
                std::lock_guard<std::mutex> lock(observationMutex_);
                const auto it = observations_.find(snapshot);
                if (it == observations_.end())
                    return false;
                world = it->second.world;
                // every world observed since the last query's is a change; the older ones are no longer needed
                for (auto c = observations_.upper_bound(planned_); c != observations_.end() && c->first <= snapshot;
                     ++c)
                    changes.push_back(c->second.changed);
                observations_.erase(observations_.begin(), it);
            }
            planWorld_->set(world);
            auto dual = std::dynamic_pointer_cast<DualRoadmap>(planner_);
            if (snapshot != planned_)
            {
                if (dual)
                    for (auto &change : changes)
                        dual->notifySceneChanged(std::move(change));  // an empty one: the whole scene
                else
                    planner_->clear();  // a planner without memory across worlds starts afresh
            }
            else if (!dual)
                planner_->clear();  // a new query: OMPL's planners keep their trees for the previous one otherwise
            planned_ = snapshot;

            ob::ScopedState<> start(planSi_), target(planSi_);
            space_->copyFromReals(start.get(), from);
            space_->copyFromReals(target.get(), goal);
            if (!planSi_->isValid(start.get()) || !planSi_->isValid(target.get()))
                return false;  // the executor asks again (the world moves on)
            auto pdef = std::make_shared<ob::ProblemDefinition>(planSi_);
            pdef->setStartAndGoalStates(start, target);
            planner_->setProblemDefinition(pdef);
            const ob::PlannerTerminationCondition ptc = ob::plannerOrTerminationCondition(
                ob::timedPlannerTerminationCondition(settings_.planningTime), ob::PlannerTerminationCondition(
                                                                                  [&cancel]
                                                                                  {
                                                                                      return cancel.load();
                                                                                  }));
            if (planner_->solve(ptc) != ob::PlannerStatus::EXACT_SOLUTION || cancel)
                return false;
            auto solution = std::dynamic_pointer_cast<og::PathGeometric>(pdef->getSolutionPath());
            if (!solution)
                return false;
            og::PathGeometric p(*solution);
            // DualRoadmap smooths its own paths (paper 002: redundant parts removed); smoothing them again would
            // only repeat its motion checks
            if (settings_.simplify && !dual && p.getStateCount() > 2)
            {
                og::PathSimplifier simplifier(planSi_);
                simplifier.reduceVertices(p);
                simplifier.shortcutPath(p);
            }
            path.clear();
            for (std::size_t i = 0; i < p.getStateCount(); ++i)
                path.push_back(toReals(p.getState(i)));
            return true;
        }
    }  // namespace planners
}  // namespace michi
