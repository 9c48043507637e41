#ifndef MICHI_TOOLS_DUAL_ARM_COMMAND_
#define MICHI_TOOLS_DUAL_ARM_COMMAND_

#include <michi/tools/problem/Problem.h>

#include <ostream>
#include <string>

namespace michi
{
    namespace tools
    {
        struct DualArmOptions
        {
            std::string outDir;
            double planningTime{0.};  ///< seconds per approach plan; 0: the problem's dual_arm.planning.time
            std::ostream *progress{nullptr};
            /** \brief Also write DIR/<problem>.html (viewer/ReplayPage.h): the stirring task replayed in 3-D, with the
                large arm at its type B configuration: the small arm's approach with and without the manipulability
                objective, then the stirring motion. */
            bool html{false};
        };

        /** \brief `michi dualarm`: the work-position analysis of paper 004 on a problem with a dual_arm section
            (docs/dual-arm.md): work spaces, common work space, manipulability area, type A and B positions, the
            stirring motion at B (and, for comparison, at A, chosen without manipulability), checked state by
            state with OMPL's motion validator, and the small arm's approach motions (home to the hand-over
            pose, home to the first stirring pose) planned with OMPL with and without ManipulabilityObjective.
            Writes DIR/dualarm.json, the pictures DIR/dualarm-*.svg + .png (and DIR/<problem>.html with
            options.html); files are staged and moved into
            DIR only when all are written. Returns the JSON text. */
        std::string runDualArm(const Problem &problem, const DualArmOptions &options);
    }  // namespace tools
}  // namespace michi

#endif
