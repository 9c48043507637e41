#ifndef MICHI_TOOLS_DUAL_ARM_PICTURE_
#define MICHI_TOOLS_DUAL_ARM_PICTURE_

#include <michi/planners/dual_arm/DualArmWorkspace.h>

#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief A joint path to draw (small-arm joint values per state). */
        struct DualArmJointPlot
        {
            std::string label;
            std::vector<std::vector<double>> values;  ///< [state][joint]
        };

        /** \brief Pictures in the manner of paper 004's Fig. 4, 6 and 7, from a computed workspace:
            \e workspaceSvg: a horizontal slice at the type-B height and a vertical slice through it (each arm's
            work space, common work space, manipulability area, stirring area, positions A and B, mounts);
            \e manipulabilitySvg: the small arm's w on the same slices (heat map, threshold contour cells);
            \e stirringSvg: the small arm's joint angles along the stirring motions (one panel per plot).
            Throws std::runtime_error naming a file that cannot be written. */
        void writeDualArmPictures(const planners::DualArmWorkspace &ws, const std::string &workspaceSvg,
                                  const std::string &manipulabilitySvg, const std::string &stirringSvg,
                                  const std::vector<DualArmJointPlot> &stirring, const std::string &title);
    }  // namespace tools
}  // namespace michi

#endif
