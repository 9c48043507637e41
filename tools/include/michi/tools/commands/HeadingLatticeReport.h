#ifndef MICHI_TOOLS_HEADING_LATTICE_REPORT_
#define MICHI_TOOLS_HEADING_LATTICE_REPORT_

#include <michi/tools/problem/Problem.h>

#include <ostream>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief Settings of `michi lattice` (runHeadingLatticeReport()). */
        struct HeadingLatticeReportOptions
        {
            std::string outDir;                      ///< where lattice.md and the pictures go
            std::vector<double> cellSizes{0.25};     ///< cell_size values, metres
            std::vector<double> angleSteps{0.3927};  ///< angle_step values, radians
            double timeLimit{60.};                   ///< per solve (plain timed termination condition, no thread)
            bool pictures{true};                     ///< write the pictures (for the first cell size and angle step)
            bool html{false};  ///< write outDir/<problem>.html, a 3-D replay of the first solved path (ReplayPage.h)
            std::ostream *progress{nullptr};
        };

        /** \brief Build michi::planners::HeadingLattice on \e problem for every cell size and angle step, solve
            query 0 (build + search), then query 1 (or query 0 again) on the kept graph, and report node and edge
            counts, build time, query times and path length as a Markdown table (returned and written to
            outDir/lattice.md). With pictures: outDir/lattice.svg (the nodes of every heading around the first turn
            of the path, the paper's Fig. 1), groups.svg (each heading-0 node joined to its group), correction.svg
            (the path before and after the correction, Figs. 2-3) and path.svg (the robot along the path, Fig. 4).
            Throws ProblemError for a problem that is not SE2; every file is written atomically. */
        std::string runHeadingLatticeReport(const Problem &problem, const HeadingLatticeReportOptions &options);

        /** \brief "0.5,0.25,0.1" as numbers; throws std::invalid_argument naming \e option for anything that is not a
            positive number. */
        std::vector<double> parseNumberList(const std::string &text, const std::string &option);
    }  // namespace tools
}  // namespace michi

#endif
