#ifndef MICHI_TOOLS_PATH_SEED_FIGURE_
#define MICHI_TOOLS_PATH_SEED_FIGURE_

#include <michi/tools/problem/Problem.h>

#include <string>

namespace michi
{
    namespace tools
    {
        /** \brief `michi path-seed-figure` (docs/path-seed.md, like the paper's Fig. 7): RRT-Connect solves training
            query \e training of the problem (simplified, \e seed for the RNG), the path is encoded as a path seed
            (\e variant "blocks" or "rotation") and decoded for the start and goal of held-out query \e heldOut.
            Writes an SVG (SvgPlot: robot at the held-out query's start and goal, end-effector traces) of the
            original path, the seed decoded for its own query (which reproduces it) and the seed decoded for the
            held-out query, and returns a short report (lengths, reproduction error, validity of the decoded path). */
        std::string writePathSeedFigure(const Problem &problem, std::size_t training, std::size_t heldOut,
                                        const std::string &variant, unsigned int seed, const std::string &file);
    }  // namespace tools
}  // namespace michi

#endif
