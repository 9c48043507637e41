#ifndef MICHI_TOOLS_JMAP_SETUP_
#define MICHI_TOOLS_JMAP_SETUP_

#include <michi/tools/bench/PlanningContext.h>
#include <michi/validity/jmap/JMapValidityChecker.h>

namespace michi
{
    namespace tools
    {
        /** \brief The J-map of a problem's arm: axes over the first two joints of the planned group (the other
            joints at their fixed values), and a factory of interval sources over any theta1 range: exact planar
            geometry (PlanarIntervalSource) when every joint rotates about z, else the certified FCL sweep
            (FclIntervalSource). For a group of more than two joints the planar map is the paper's arm map: the
            links the other group joints move (the hand) are left out of it. */
        struct JMapProblem
        {
            validity::JMapAxes axes;
            validity::JMapValidityChecker::SourceFactory makeSource;
            bool planar{false};
            bool coversRobot{false};     ///< the map sees every link the planned group moves
            validity::PlanarArmPtr arm;  ///< planar arms only
            std::vector<int> armLinks;   ///< planar: PlanarArm links in the map
            double handLength{0.};       ///< planar: reach of the left-out links beyond the arm (0: no hand)
        };

        /** \brief Throws ProblemError (key "robot") when the problem is not an arm with at least two planned
            joints. */
        JMapProblem makeJMapProblem(const Problem &problem, const PlanningContext &ctx);

        /** \brief A J-map validity checker for the context's space (FCL checker of the context as the exact one). */
        validity::JMapValidityCheckerPtr makeJMapChecker(const Problem &problem, const PlanningContext &ctx,
                                                         const validity::JMapCheckerSettings &settings);
    }  // namespace tools
}  // namespace michi

#endif
