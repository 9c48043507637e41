#ifndef MICHI_PLANNERS_EXPERIENCE_PEERS_
#define MICHI_PLANNERS_EXPERIENCE_PEERS_

#include <michi/planners/ExperiencePlanner.h>

#include <ompl/base/Planner.h>

#include <memory>

namespace ompl
{
    namespace tools
    {
        class LightningDB;
    }  // namespace tools
}  // namespace ompl

namespace michi
{
    namespace planners
    {
        /**
           @anchor michiExperienceRace
           @par Short description
           OMPL's Lightning experience framework as a planner, so that OMPL's Benchmark can run it next to others
           and tools can train it (michi registers it as "experience::Lightning"). As ompl::tools::Lightning
           does, solve() runs the framework's retrieve-repair planner
           and RRT-Connect from scratch in parallel (ompl::tools::ParallelPlan) and stops at the first solution.
           The experience database is filled by addExperience() (training) and, with parameter learn, with
           solutions RRT-Connect found; clear() keeps it.
           @par External documentation
           D. Berenson, P. Abbeel, K. Goldberg, "A robot path planning framework that learns from experience",
           ICRA 2012 (Lightning). (Thunder, OMPL's other framework, was wrapped the same way but its
           retrieve-repair planner crashed michi bench on xarm6_ring with OMPL 1.5.2; see docs/path-seed.md.)
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

    }  // namespace planners
}  // namespace michi

#endif
