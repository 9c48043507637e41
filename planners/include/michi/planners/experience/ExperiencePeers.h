#ifndef MICHI_PLANNERS_EXPERIENCE_PEERS_
#define MICHI_PLANNERS_EXPERIENCE_PEERS_

#include <michi/planners/experience/ExperiencePlanner.h>

#include <ompl/base/Planner.h>

#include <memory>

namespace ompl
{
    namespace tools
    {
        class LightningDB;
        class ThunderDB;
    }  // namespace tools
}  // namespace ompl

namespace michi
{
    namespace planners
    {
        /**
           @anchor michiExperienceRace
           @par Short description
           OMPL's experience frameworks as planners, so that OMPL's Benchmark can run them next to others and
           tools can train them (michi registers them as "experience::Lightning" and "experience::Thunder"). As
           ompl::tools::Lightning and ompl::tools::Thunder do, solve() runs the framework's retrieve-repair planner
           and RRT-Connect from scratch in parallel (ompl::tools::ParallelPlan) and stops at the first solution.
           The experience database is filled by addExperience() (training) and, with parameter learn, with
           solutions RRT-Connect found; clear() keeps it.
           @par External documentation
           D. Berenson, P. Abbeel, K. Goldberg, "A robot path planning framework that learns from experience",
           ICRA 2012 (Lightning). D. Coleman, I. A. Sucan, M. Moll, K. Okada, N. Correll, "Experience-based
           planning with sparse roadmap spanners", ICRA 2015 (Thunder).
        */
        class ExperienceRace : public ompl::base::Planner, public ExperiencePlanner
        {
        public:
            ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
            void clear() override;
            void setup() override;
            void getPlannerData(ompl::base::PlannerData &data) const override;

            /** \brief Learn solutions found from scratch (default: no, only training). */
            void setLearn(bool learn)
            {
                learn_ = learn;
            }
            bool getLearn() const
            {
                return learn_;
            }

        protected:
            ExperienceRace(const ompl::base::SpaceInformationPtr &si, const std::string &name);
            /** \brief A valid start and a valid goal state (any, for several): retrieve-repair needs both. */
            bool hasValidStartAndGoal() const;
            ompl::base::PlannerPtr retrieveRepair_;
            ompl::base::PlannerPtr scratch_;
            bool learn_{false};
        };

        /** \brief OMPL's Lightning (LightningDB + LightningRetrieveRepair) racing RRT-Connect. */
        class LightningPlanner : public ExperienceRace
        {
        public:
            explicit LightningPlanner(const ompl::base::SpaceInformationPtr &si);
            void addExperience(const ompl::geometric::PathGeometric &path) override;
            std::size_t experienceCount() const override;

        private:
            std::shared_ptr<ompl::tools::LightningDB> db_;
        };

        /** \brief OMPL's Thunder (ThunderDB on a SPARSdb roadmap + ThunderRetrieveRepair) racing RRT-Connect,
            with Thunder's default roadmap settings (stretch factor 1.2, sparse delta 0.05, dense delta 0.001 of the
            space's maximum extent). The SPARSdb roadmap searches with its own problem definition and dereferences
            its goal: training gives it each path's query, solve() the planner's (without, OMPL 1.5.2 crashes). */
        class ThunderPlanner : public ExperienceRace
        {
        public:
            explicit ThunderPlanner(const ompl::base::SpaceInformationPtr &si);
            ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
            void addExperience(const ompl::geometric::PathGeometric &path) override;
            std::size_t experienceCount() const override;
            /** \brief SPARSdb marks the roadmap edges it checks free or in collision and never checks them again:
                in a new scene those marks are stale (a stale "in collision" would hide a free edge), so they are
                cleared. */
            void sceneChanged() override;
            /** \brief Number of added paths whose start and goal the roadmap connected afterwards (SPARSdb's
                addPathToRoadmap succeeded); the others still added their states where the roadmap needed them. */
            std::size_t connectedExperienceCount() const
            {
                return connected_;
            }

        private:
            std::shared_ptr<ompl::tools::ThunderDB> db_;
            std::size_t connected_{0};
        };
    }  // namespace planners
}  // namespace michi

#endif
