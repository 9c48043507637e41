#include <michi/planners/experience/ExperiencePeers.h>

#include <ompl/base/PlannerData.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/experience/LightningRetrieveRepair.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/goals/GoalStates.h>
#include <ompl/geometric/planners/experience/ThunderRetrieveRepair.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/tools/lightning/LightningDB.h>
#include <ompl/tools/multiplan/ParallelPlan.h>
#include <ompl/tools/thunder/SPARSdb.h>
#include <ompl/tools/thunder/ThunderDB.h>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace planners
    {
        ExperienceRace::ExperienceRace(const ob::SpaceInformationPtr &si, const std::string &name)
            : ob::Planner(si, name)
        {
            specs_.approximateSolutions = false;
            // The race runs the retrieve-repair planner and RRT-Connect in two threads (ompl::tools::ParallelPlan).
            specs_.multithreaded = true;
            specs_.recognizedGoal = ob::GOAL_SAMPLEABLE_REGION;
            declareParam<bool>("learn", this, &ExperienceRace::setLearn, &ExperienceRace::getLearn, "0,1");
        }

        void ExperienceRace::setup()
        {
            Planner::setup();
        }

        void ExperienceRace::clear()
        {
            Planner::clear();
            if (retrieveRepair_)
                retrieveRepair_->clear();
            // The experience database is kept: like OMPL's Lightning and Thunder, clear() forgets one query, not what
            // was learned.
            scratch_.reset();
        }

        ob::PlannerStatus ExperienceRace::solve(const ob::PlannerTerminationCondition &ptc)
        {
            checkValidity();
            if (ptc)
                return ob::PlannerStatus::TIMEOUT;
            // A fresh planner per query: a tree left over from an earlier query would make the race depend on the query
            // order.
            scratch_ = std::make_shared<og::RRTConnect>(si_);
            scratch_->setProblemDefinition(pdef_);
            scratch_->setup();
            retrieveRepair_->setProblemDefinition(pdef_);
            if (!retrieveRepair_->isSetup())
                retrieveRepair_->setup();
            // as ompl::tools::Lightning / Thunder: both in parallel, stop at the first solution
            ompl::tools::ParallelPlan race(pdef_);
            // With an empty database retrieve-repair can only fail: racing it would take CPU from the planner that can
            // succeed. Nor is it raced without a valid start and goal: OMPL 1.5.2's Lightning/ThunderRetrieveRepair
            // pass the null state PlannerInputStates then gives to the database (a crash, seen with a grasp goal the
            // sphere checker rejects); RRT-Connect alone reports the invalid start or goal as OMPL's planners do.
            if (experienceCount() > 0 && hasValidStartAndGoal())
                race.addPlanner(retrieveRepair_);
            race.addPlanner(scratch_);
            const ob::PlannerStatus status = race.solve(ptc, false);
            // Only paths planned from scratch are learned (as Lightning and Thunder do): a repaired path is already
            // close to one in the database. reduceVertices keeps a stored path short without changing where it goes.
            if (learn_ && status == ob::PlannerStatus::EXACT_SOLUTION && !pdef_->getSolutions().empty() &&
                pdef_->getSolutions().front().plannerName_ == scratch_->getName())
            {
                og::PathGeometric path(*pdef_->getSolutionPath()->as<og::PathGeometric>());
                og::PathSimplifier(si_).reduceVertices(path);
                addExperience(path);
            }
            return status;
        }

        bool ExperienceRace::hasValidStartAndGoal() const
        {
            bool start = false;
            for (unsigned int i = 0; i < pdef_->getStartStateCount() && !start; ++i)
                start = si_->isValid(pdef_->getStartState(i));
            const ob::Goal *goal = pdef_->getGoal().get();
            if (const auto *one = dynamic_cast<const ob::GoalState *>(goal))
                return start && si_->isValid(one->getState());
            if (const auto *several = dynamic_cast<const ob::GoalStates *>(goal))
            {
                for (std::size_t i = 0; i < several->getStateCount(); ++i)
                    if (si_->isValid(several->getState(i)))
                        return start;
                return false;
            }
            // other goals (regions): sampled by retrieve-repair as OMPL does
            return start && goal != nullptr;
        }

        void ExperienceRace::getPlannerData(ob::PlannerData &data) const
        {
            Planner::getPlannerData(data);
            if (scratch_)
                scratch_->getPlannerData(data);
            if (retrieveRepair_)
                retrieveRepair_->getPlannerData(data);
        }

        LightningPlanner::LightningPlanner(const ob::SpaceInformationPtr &si)
            : ExperienceRace(si, "Lightning"), db_(std::make_shared<ompl::tools::LightningDB>(si->getStateSpace()))
        {
            retrieveRepair_ = std::make_shared<og::LightningRetrieveRepair>(si, db_);
        }

        void LightningPlanner::addExperience(const og::PathGeometric &path)
        {
            og::PathGeometric copy(path);
            double insertionTime = 0.;
            db_->addPath(copy, insertionTime);
        }

        std::size_t LightningPlanner::experienceCount() const
        {
            return db_->getExperiencesCount();
        }

        ThunderPlanner::ThunderPlanner(const ob::SpaceInformationPtr &si)
            : ExperienceRace(si, "Thunder"), db_(std::make_shared<ompl::tools::ThunderDB>(si->getStateSpace()))
        {
            retrieveRepair_ = std::make_shared<og::ThunderRetrieveRepair>(si, db_);
        }

        void ThunderPlanner::addExperience(const og::PathGeometric &path)
        {
            if (path.getStateCount() < 2)
                return;
            if (!db_->getSPARSdb())
            {
                // as ompl::tools::Thunder::setup() does
                auto spars = std::make_shared<og::SPARSdb>(si_);
                spars->setProblemDefinition(std::make_shared<ob::ProblemDefinition>(si_));
                spars->setup();
                // SPARSdb settings as ompl::tools::Thunder::setup() sets them, so this planner and OMPL's Thunder keep
                // the same roadmap.
                spars->setStretchFactor(1.2);
                spars->setSparseDeltaFraction(0.05);
                spars->setDenseDeltaFraction(0.001);
                db_->setSPARSdb(spars);
            }
            // SPARSdb's roadmap search (lazyCollisionSearch) reads the goal of its own problem definition: with
            // none it dereferences a null goal (the crash under michi bench); give it the path's own query
            auto pdef = std::make_shared<ob::ProblemDefinition>(si_);
            pdef->setStartAndGoalStates(path.getState(0), path.getState(path.getStateCount() - 1));
            db_->getSPARSdb()->setProblemDefinition(pdef);
            og::PathGeometric copy(path);
            double insertionTime = 0.;
            if (db_->addPath(copy, insertionTime))
                ++connected_;
        }

        ob::PlannerStatus ThunderPlanner::solve(const ob::PlannerTerminationCondition &ptc)
        {
            // as ompl::tools::Thunder::setup() does: the roadmap searches with the query's problem definition
            if (db_->getSPARSdb() && pdef_)
                db_->getSPARSdb()->setProblemDefinition(pdef_);
            return ExperienceRace::solve(ptc);
        }

        void ThunderPlanner::sceneChanged()
        {
            if (db_->getSPARSdb())
                db_->getSPARSdb()->clearEdgeCollisionStates();
        }

        std::size_t ThunderPlanner::experienceCount() const
        {
            // every path given to the roadmap (ThunderDB counts them whether or not they connected)
            return static_cast<std::size_t>(db_->getNumPathsInserted());
        }
    }  // namespace planners
}  // namespace michi
