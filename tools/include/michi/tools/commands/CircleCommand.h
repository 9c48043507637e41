#ifndef MICHI_TOOLS_CIRCLE_COMMAND_
#define MICHI_TOOLS_CIRCLE_COMMAND_

#include <michi/tools/problem/Problem.h>

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief Settings of runCircles(). */
        struct CircleOptions
        {
            std::string outDir;
            std::string checker;                        ///< "fcl" or "jmap"; empty: the problem's
            std::map<std::string, std::string> params;  ///< ConcentricCircle parameters by name
            double timeLimit{30.};
            std::size_t query{0};
            std::vector<double> view;         ///< picture box (xmin, ymin, xmax, ymax) of every stage; empty: all
            std::ostream *progress{nullptr};  ///< where the summary of a failed search goes, or nowhere
            bool html{false};                 ///< also write DIR/<problem>.html, a 3-D replay of the path
        };

        /** \brief `michi circles`: solve the problem once with michi::ConcentricCircle and draw the search:
            DIR/<problem>-cc-<stage>.svg for each stage (the paper's Fig. 5: circles, candidates, links, paths on
            the map) and DIR/<problem>-cc-robot.svg (Fig. 8: the robot along the chosen path, unsimplified), and with
            options.html DIR/<problem>.html (viewer/ReplayPage.h).
            Returns the text summary. Throws ProblemError (naming the file and key) on a bad problem or parameter,
            before anything is written; when no path is found, the stage pictures of the failed search are
            written, the summary goes to options.progress and std::runtime_error is thrown. */
        std::string runCircles(const Problem &problem, const CircleOptions &options);
    }  // namespace tools
}  // namespace michi

#endif
