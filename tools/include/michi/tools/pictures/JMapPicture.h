#ifndef MICHI_TOOLS_JMAP_PICTURE_
#define MICHI_TOOLS_JMAP_PICTURE_

#include <michi/validity/jmap/JMap.h>

#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief What writeJMapSvg() draws besides the map. */
        struct JMapPictureOptions
        {
            std::string title;            ///< top line; empty: none
            std::string axis1{"theta1"};  ///< axis names (joint names)
            std::string axis2{"theta2"};
            validity::JMapPtr grown;             ///< grown J-map (drawn under the map), may be null
            validity::MultiPolygon2 bottleneck;  ///< grown - plain, drawn on top
            std::vector<double> start;           ///< (theta1, theta2) marks; empty: none
            std::vector<double> goal;
            std::vector<std::vector<double>> path;  ///< a path in the map plane, may be empty
            bool cellIntervals{false};              ///< also draw every column's conservative intervals (thin boxes)
            int width{900};                         ///< picture size in pixels (plot area plus margins)
            int height{700};
        };

        /** \brief Write the J-map as SVG, like the paper's Fig. 1(c) / 7(a): theta1 on x, theta2 on y over the
            map's ranges (axes with ticks in radians), the true collision intervals of every slice as thin
            vertical segments, the polygons over them (semi-transparent), the grown map (outlined when a bottleneck
            is given, since the bottleneck fills grown - plain) and the bottleneck in other colours, start and goal, a
           legend. Writes FILE.tmp and renames it; throws std::runtime_error naming the file when it cannot be written.
         */
        void writeJMapSvg(const validity::JMap &map, const std::string &file, const JMapPictureOptions &options = {});
    }  // namespace tools
}  // namespace michi

#endif
