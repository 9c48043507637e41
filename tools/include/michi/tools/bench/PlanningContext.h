#ifndef MICHI_TOOLS_PLANNING_CONTEXT_
#define MICHI_TOOLS_PLANNING_CONTEXT_

#include <michi/tools/problem/Problem.h>
#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/jmap/JMapValidityChecker.h>
#include <michi/validity/grid/GridValidityChecker.h>
#include <michi/validity/spheres/SphereValidityChecker.h>

#include <ompl/geometric/SimpleSetup.h>

#include <map>
#include <string>
#include <vector>

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
            /** \brief The grid checker when the checker is "grid" (then it is the space's state validity
                checker and validity::GridMotionValidator its motion validator), else null. */
            std::shared_ptr<validity::GridValidityChecker> grid;
            /** \brief The sphere checker when the checker is "spheres" (validity::SphereMotionValidator certifies
                its motions), else null. */
            std::shared_ptr<validity::SphereValidityChecker> spheres;
            /** \brief The problem's collision.spheres.exact_states ("auto", "on", "off"): with "auto" every new
                query (setQuery()) decides it again from its own start and goal (chooseExactStates()). */
            std::string sphereExactStates{"auto"};
            std::string checkerName;  ///< the checker installed in the space ("fcl", "jmap", "grid")
            /** \brief The FCL-based motion validator of the problem's collision.motion_validator, whatever checker
                is installed: the reference a fast checker is compared with (bench --checker fcl,X,
                verify-checker). */
            ompl::base::MotionValidatorPtr referenceMotions;
            validity::CollisionBodiesPtr bodies;
            validity::ScenePtr scene;         ///< the scene checked (the problem's unless the options gave one)
            std::vector<double> fixedValues;  ///< the robot's other joints (ARM; the problem's unless given)
        };

        /** \brief What makePlanningContext() may take from elsewhere than the problem, so callers never copy a
            Problem to change one field. Empty members mean "as the problem says". */
        struct ContextOptions
        {
            std::size_t query{0};             ///< which of the problem's queries (ignored when start/goal given)
            std::vector<double> start, goal;  ///< a query of the caller's own (both or neither)
            std::string checker;              ///< one of checkerNames()
            std::string motionValidator;      ///< "workspace", "conservative" or "discrete"
            validity::ScenePtr scene;         ///< another scene (replanning's world at one moment)
            std::vector<double> fixedValues;  ///< the other joints' values (a dual-arm task's configuration)
        };

        /** \brief How far (metres) beyond the spheres' surface chooseExactStates() looks for the contacts of a
            query's start and goal that FCL settles: the obstacles near a grasp (the object, the shelf beside it),
            so that the states leading into it are settled too. */
        constexpr double EXACT_CONTACT_MARGIN = 0.05;

        /** \brief With the sphere checker: turn FCL's settling of the spheres' contacts (exact states) on or off
            for a query, as ctx.sphereExactStates says; "auto" turns it on only where the spheres reject \e start or
            \e goal (a grasp), which FCL has found free, and then only for the obstacles and self pairs the spheres
            touch within EXACT_CONTACT_MARGIN at the start and the goal
            (SphereValidityChecker::setExactContacts()); elsewhere the spheres decide, as in a query that needs no
            settling. No effect without the sphere checker. */
        void chooseExactStates(const PlanningContext &ctx, const std::vector<double> &start,
                               const std::vector<double> &goal);

        /** \brief The checkers makePlanningContext() can install: fcl, jmap, grid (docs/checking.md). */
        const std::vector<std::string> &checkerNames();

        /** \brief The state space of a problem (joint space of the group, or SE(2) on the map's bounds). */
        ompl::base::StateSpacePtr makeStateSpace(const Problem &problem);

        /** \brief Build the context for query \e query. Throws ProblemError (key "start"/"goal" or
            "queries[i].start") when a start or goal is out of bounds or in collision, naming what collides. */
        PlanningContext makePlanningContext(const Problem &problem, std::size_t query = 0);

        /** \brief The same with \e options in place of the problem's fields. Errors name the problem file; keys of a
            caller's own query are "start"/"goal". */
        PlanningContext makePlanningContext(const Problem &problem, const ContextOptions &options);

        /** \brief Why \e value lies outside an OMPL range suggestion ("lower:upper" or "lower:step:upper"), or ""
            when it lies inside or the suggestion is not numeric. */
        std::string outsideDeclaredRange(const std::string &value, const std::string &range);

        /** \brief Set planner parameters by name; throws ProblemError naming the parameter and the planner's
            known parameters when one is unknown or rejects the value.
            Values outside the parameter's declared range are rejected too. Errors name the key
            planners.NAME.params.PARAM, or \e keyPrefix.PARAM when the parameters come from elsewhere in the file. */
        void applyPlannerParams(ompl::base::Planner &planner, const PlannerSpec &spec, const std::string &file,
                                const std::string &keyPrefix = "");

        /** \brief Throws ProblemError (naming the key) for a planner that OMPL 1.5.2 crashes with on this problem:
            geometric::FMT and geometric::BFMT with the clearance objective, geometric::LBTRRT on the
            turn_move_turn state space. */
        void refuseKnownCrashes(const Problem &problem, const std::string &name,
                                const ompl::base::SpaceInformation &si);

        /** \brief The one way `plan`, `bench` and the method commands make a planner: the registry's allocator for
            \e name on \e si, then the parameters the problem's `planners:` entry of that name gives it, then
            \e extra (a command line's --set). Throws std::invalid_argument for an unknown name and ProblemError
            for a bad parameter or a pair refuseKnownCrashes() names. */
        ompl::base::PlannerPtr makePlanner(const Problem &problem, const std::string &name,
                                           const ompl::base::SpaceInformationPtr &si,
                                           const std::map<std::string, std::string> &extra = {});
    }  // namespace tools
}  // namespace michi

#endif
