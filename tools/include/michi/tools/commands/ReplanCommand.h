#ifndef MICHI_TOOLS_REPLAN_COMMAND_
#define MICHI_TOOLS_REPLAN_COMMAND_

#include <ostream>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        struct ReplanOptions
        {
            std::string problemFile;
            std::string outDir;
            unsigned int episodes{20};
            unsigned int seed{1};
            /** \brief Methods to run; empty: michi::DualRoadmap and every baseline (RRTConnect, PRM, LazyPRM keeping
                its roadmap, DualRoadmap without learning roadmap). */
            std::vector<std::string> methods;
            std::ostream *progress{nullptr};
        };

        /** \brief `michi replan`: non-stop execution (NonStopExecutor) of the problem's query 0 among its moving
            obstacles, over \e episodes randomized episodes (each moving obstacle's timing shifted and its speed
            scaled, the same draws for every method), with the DualRoadmap planner and the baselines. Settings come
            from the problem file's `extras.replan` (docs/dual-roadmap.md). Writes OUT/replan.json (episodes,
            reached_goal, collisions, stops, deformations, replans, replan_latency_ms_median/_p95, ..., the same
            under "baselines") and OUT/episode/frame_*.svg (one episode of DualRoadmap); files appear only when
            complete. Throws ProblemError / std::runtime_error with a clear message on bad input. Returns the JSON
            text. */
        std::string runReplan(const ReplanOptions &options);
    }  // namespace tools
}  // namespace michi

#endif
