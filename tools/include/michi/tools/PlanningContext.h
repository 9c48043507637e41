#ifndef MICHI_TOOLS_PLANNING_CONTEXT_
#define MICHI_TOOLS_PLANNING_CONTEXT_

#include <michi/tools/Problem.h>
#include <michi/validity/FclValidityChecker.h>
#include <michi/validity/JMapValidityChecker.h>

#include <ompl/geometric/SimpleSetup.h>

namespace michi
{
    namespace tools
    {
        /** \brief A problem made ready for OMPL: state space, FCL validity checker, the problem's motion
            validator (workspace-resolution by default), start and goal of one query. */
        struct PlanningContext
        {
            ompl::geometric::SimpleSetupPtr setup;
            validity::FclValidityCheckerPtr checker;  ///< the exact checker (also inside the J-map checker)
            /** \brief The J-map checker when the problem's collision.checker is "jmap" (then it is the space's
                state validity checker), else null. */
            std::shared_ptr<validity::JMapValidityChecker> jmap;
            validity::CollisionBodiesPtr bodies;
        };

        /** \brief The state space of a problem (joint space of the group, or SE(2) on the map's bounds). */
        ompl::base::StateSpacePtr makeStateSpace(const Problem &problem);

        /** \brief Build the context for query \e query. Throws ProblemError (key "start"/"goal" or
            "queries[i].start") when a start or goal is out of bounds or in collision, naming what collides. */
        PlanningContext makePlanningContext(const Problem &problem, std::size_t query = 0);

        /** \brief Set planner parameters by name; throws ProblemError naming the parameter and the planner's
            known parameters when one is unknown or rejects the value. */
        void applyPlannerParams(ompl::base::Planner &planner, const PlannerSpec &spec, const std::string &file);
    }  // namespace tools
}  // namespace michi

#endif
