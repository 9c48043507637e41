#ifndef MICHI_TOOLS_VIEWER_REPLAY_PAGE_
#define MICHI_TOOLS_VIEWER_REPLAY_PAGE_

#include <michi/tools/pictures/SvgPlot.h>
#include <michi/tools/problem/Problem.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief How a replay page plays its paths (docs/viewer.md). */
        struct ReplayOptions
        {
            /** \brief Seconds the longest path takes to play; every path moves at the same speed in state space, so
                a shorter path arrives sooner. */
            double duration{10.};
            /** \brief About how many frames a path is cut into (plus its waypoints, which are always frames): the
                page interpolates between frames, so this bounds the page's size, not its smoothness. */
            std::size_t frames{200};
            /** \brief ARM: the full configuration whose joints outside the planned group the page shows (a dual-arm
                task's other arm); empty: the problem's fixedValues. */
            std::vector<double> fixedValues;
            /** \brief Empty, or one entry per path: empty for a path timed as above, else the time (seconds) of each
                of the path's states, non-decreasing. Such a path plays on that clock (e.g. the executed motion of a
                `michi replan` episode, whose moving obstacles' key frames are on the same clock): every state is a
                frame and a waypoint, none is added, and \e duration and \e frames do not apply to it. */
            std::vector<std::vector<double>> times;
            /** \brief The obstacles the page shows in place of the problem's scene (a `michi replan` episode's
                obstacles with their key frames); null: the problem's scene. */
            std::shared_ptr<const validity::Scene> scene;
        };

        /** \brief Text that every replay page contains (the format of its data block). */
        extern const char *const REPLAY_PAGE_MARK;

        /** \brief The data a replay page shows, as JSON: the scene (obstacle shapes and poses, moving obstacles'
            key frames, an occupancy map as an image), the robot's collision geometry and, for every path, its
            waypoints and the poses of every moving body at each interpolated frame. michi computes every pose
            (forward kinematics of the problem's URDF, or the SE(2) footprint's placement) so the page needs no
            robot model and shows exactly the geometry the checker saw. Paths are states as in PlotPath
            (Problem::valueNames() order), interpolated with the problem's own state space
            (makeStateSpace()). Moving obstacles' key frames are written with full precision (10 digits). Throws
            std::invalid_argument for a path whose states have the wrong dimension, or times (ReplayOptions::times)
            that do not match the paths. */
        std::string replayData(const Problem &problem, const std::vector<PlotPath> &paths,
                               const ReplayOptions &options = {});

        /** \brief One self-contained HTML page (three.js and the page's script inlined, no network reference)
            that replays \e paths on \e problem: play/pause, a time slider, a colour and a toggle per path, the
            end-effector trace and an orbit camera. window.michiViewer is its API for scripts and tests. */
        std::string replayPage(const Problem &problem, const std::vector<PlotPath> &paths,
                               const ReplayOptions &options = {});

        /** \brief replayPage() written to \e file atomically (all or nothing). */
        void writeReplayPage(const Problem &problem, const std::vector<PlotPath> &paths, const std::string &file,
                             const ReplayOptions &options = {});
    }  // namespace tools
}  // namespace michi

#endif
