#ifndef MICHI_TOOLS_CIRCLE_PICTURE_
#define MICHI_TOOLS_CIRCLE_PICTURE_

#include <michi/planners/concentric_circle/ConcentricCircle.h>

#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief What writeCircleSvg() draws besides the search. */
        struct CirclePictureOptions
        {
            std::string title;
            std::string axis1{"theta1"};
            std::string axis2{"theta2"};
            /** \brief Free / blocked background sampled on a grid of this many cells per axis with the map's own
                point test (0: none); J-map polygons are drawn as polygons instead. */
            int background{120};
            /** \brief Draw only this box of the map (lo.x, lo.y, hi.x, hi.y); empty: the map and every circle. */
            std::vector<double> view;
            int width{900};
            int height{760};
        };

        /** \brief The concentric-circle search of one stage as SVG, like the paper's Fig. 5: the map's
            obstacles, every circle (its free and blocked sample points), the candidates, the links between
            them, every path found (thin) and the chosen one (thick), start and goal. Written atomically; throws
            std::runtime_error naming the file when it cannot be written. */
        void writeCircleSvg(const planners::ConcentricCircle::Stage &stage, const std::string &file,
                            const CirclePictureOptions &options = {});
    }  // namespace tools
}  // namespace michi

#endif
