#ifndef MICHI_TOOLS_REPLAN_COMMAND_
#define MICHI_TOOLS_REPLAN_COMMAND_

#include <michi/validity/scene/Scene.h>

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
            /** \brief Also write OUT/<problem>.html (viewer/ReplayPage.h): the first episode replayed in 3-D, one
                path per method (its executed motion on the simulated clock) and the moving obstacles where the
                simulation had them (of the first method's run, which obstacles_yield may have delayed). */
            bool html{false};
            std::ostream *progress{nullptr};
        };

        /** \brief `michi replan`: non-stop execution (NonStopExecutor) of the problem's query 0 among its moving
            obstacles, over \e episodes randomized episodes (each moving obstacle's timing shifted and its speed
            scaled, the same draws for every method), with the DualRoadmap planner and the baselines. Settings come
            from the problem file's `extras.replan` (docs/dual-roadmap.md). Writes OUT/replan.json (episodes,
            reached_goal, collisions, stops, deformations, replans, replan_latency_ms_median/_p95, ..., the same
            under "baselines"), OUT/episode/frame_*.svg (one episode of the first method) and with \e html
            OUT/<problem>.html (the first episode of every method, replayed); files appear only when
            complete. Throws ProblemError / std::runtime_error with a clear message on bad input. Returns the JSON
            text. */
        std::string runReplan(const ReplanOptions &options);

        /** \brief The moving obstacles (those with two or more key frames, in scene order) of problem file \e
            problemFile in episode \e episode (0-based) of runReplan() with seed \e seed: each one's key frames with
            its timing shifted and its speed scaled as that run draws them, before any obstacles_yield wait. Throws
            as runReplan() on a bad problem file. */
        std::vector<validity::Obstacle> replanEpisodeObstacles(const std::string &problemFile, unsigned int seed,
                                                               unsigned int episode);
    }  // namespace tools
}  // namespace michi

#endif
