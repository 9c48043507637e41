#ifndef MICHI_TOOLS_SVG_PLOT_
#define MICHI_TOOLS_SVG_PLOT_

#include <michi/tools/problem/Problem.h>

#include <memory>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief A path to draw: states as the problem's values (joint values of the group, or x, y, yaw). */
        struct PlotPath
        {
            std::string label;  ///< legend text, e.g. the planner name
            std::vector<std::vector<double>> states;
        };

        /** \brief What a picture shows in place of the problem's own scene or query, so callers need not copy the
            Problem to change one field: a replanning frame's obstacles where they were at its time, an experience
            problem's held-out query. */
        struct PictureOverride
        {
            std::shared_ptr<const validity::Scene> scene;  ///< null: the problem's scene
            const Query *query{nullptr};                   ///< null: the problem's query number \e query
        };

        /** \brief Write an SVG picture of a problem and paths on it: the scene seen from above (x-y; for
            spatial arms a second panel seen from the side, x-z), the robot drawn at the start and goal of query
            \e query, and for every path the robot drawn at poses along it (arms: the links; SE2: the footprint)
            plus the trace of its end effector / reference point, one colour per path, with a legend. For robots
            with two planned values a third panel shows the paths in the configuration space. Writes to a
            temporary file and renames it, so a failure leaves nothing behind; throws std::runtime_error naming
            the file when it cannot be written. */
        void writeProblemSvg(const Problem &problem, const std::vector<PlotPath> &paths, const std::string &file,
                             std::size_t query = 0, const PictureOverride &override = {});

        /** \brief Render an SVG file to PNG with rsvg-convert (Debian librsvg2-bin, installed by scripts/setup.sh),
            \e width pixels wide. Returns false, writing nothing, when the converter is missing or fails. */
        bool svgToPng(const std::string &svg, const std::string &png, int width = 1600);
    }  // namespace tools
}  // namespace michi

#endif
