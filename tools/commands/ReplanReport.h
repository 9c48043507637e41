#ifndef MICHI_TOOLS_SRC_REPLAN_REPORT_
#define MICHI_TOOLS_SRC_REPLAN_REPORT_

// Private to michi_tools (not installed): the outputs of `michi replan`, OUT/replan.json (ReplanReport.cpp) and
// OUT/episode/frame_*.svg and OUT/<problem>.html (ReplanFrames.cpp).

#include "ReplanTypes.h"

#include <michi/tools/FileOutput.h>

#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace replan
        {
            /** The text of replan.json: the first method's results, the settings, and every other method under
                "baselines" with its median replanning latency as a ratio to the first method's. */
            std::string reportJson(const Problem &problem, unsigned int seed, const ReplanSettings &settings,
                                   const std::vector<Method> &methods, const std::vector<Results> &results);

            /** About \e count of \e frames (one episode), spread over it, as episode/frame_NN.svg in \e stage: the
                static obstacles, the moving ones where they were, the executed trajectory and the current plan. */
            void writeFrames(const StagedDirectory &stage, const Problem &problem,
                             const std::vector<validity::Obstacle> &statics, const std::vector<Mover> &movers,
                             const std::vector<Frame> &frames, double count);

            /** OUT/<problem>.html (viewer/ReplayPage.h) at \e file: one episode replayed in 3-D, one path per method
                (\e labels, \e traces: its executed motion on the simulated clock, every few simulation steps) and the
                moving obstacles' poses of the first trace sampled at the same steps as key frames. */
            void writeEpisodeReplay(const std::string &file, const Problem &problem,
                                    const std::vector<validity::Obstacle> &statics, const std::vector<Mover> &movers,
                                    const std::vector<std::string> &labels, const std::vector<Trace> &traces);
        }  // namespace replan
    }      // namespace tools
}  // namespace michi

#endif
