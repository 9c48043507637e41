#ifndef MICHI_PLANNERS_EXPERIENCE_PLANNER_
#define MICHI_PLANNERS_EXPERIENCE_PLANNER_

#include <ompl/geometric/PathGeometric.h>

#include <string>

namespace michi
{
    namespace planners
    {
        /** \brief A planner that learns from solved paths (michi::planners::PathSeed, and OMPL's Lightning and
            Thunder as michi wraps them). Tools train such planners on a problem's training queries before a
            benchmark (`michi bench`, docs/path-seed.md); what a planner keeps survives clear(). */
        class ExperiencePlanner
        {
        public:
            virtual ~ExperiencePlanner() = default;
            /** \brief Learn from one solution path (start to goal, valid). */
            virtual void addExperience(const ompl::geometric::PathGeometric &path) = 0;
            /** \brief Number of experiences kept. */
            virtual std::size_t experienceCount() const = 0;
            /** \brief The scene changed (a dataset run installs each problem's own): forget whatever was learned
                about collisions in the old one. Experience itself (paths, seeds) is kept. */
            virtual void sceneChanged()
            {
            }
            /** \brief Add the experiences of a file in the planner's own format; false when the planner has no
                such format (the default). Throws for a file that cannot be read. */
            virtual bool loadExperience(const std::string & /*file*/)
            {
                return false;
            }
        };
    }  // namespace planners
}  // namespace michi

#endif
