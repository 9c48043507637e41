#ifndef MICHI_TOOLS_SRC_VIEWER_REPLAY_JSON_
#define MICHI_TOOLS_SRC_VIEWER_REPLAY_JSON_

// Private to michi_tools: how the replay page's JSON writes numbers and poses (ReplayJson.cpp). Numbers are
// quantised here because they are most of the page's size: a bench page of a 7-joint arm with six planners must stay
// under 5 MB (issue 20).

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace replay
        {
            /** Positions to 0.1 mm: far below what a screen shows of a robot cell, and 4 digits after the point. */
            constexpr int POSITION_DECIMALS = 4;
            /** Quaternion components to 1e-5 (an angle error below 0.002 degrees). */
            constexpr int ROTATION_DECIMALS = 5;

            /** \e value with at most \e decimals digits after the point, trailing zeros and "-0" dropped. */
            void appendFixed(std::string &out, double value, int decimals);

            /** \e value exactly enough to read back within 1e-9 relative (states, times): "%.10g". */
            void appendPrecise(std::string &out, double value);

            /** "[x,y,z,qx,qy,qz,qw]": the order three.js's Vector3 / Quaternion take. */
            void appendPose(std::string &out, const Eigen::Isometry3d &pose);

            /** x,y,z,qx,qy,qz,qw without brackets, for flat per-frame arrays. */
            void appendPoseValues(std::string &out, const Eigen::Isometry3d &pose);

            /** As appendPoseValues but every number precise (appendPrecise): a moving obstacle's key frames, which a
                replan page samples from the simulation and a test compares with it within 1e-6. */
            void appendPrecisePoseValues(std::string &out, const Eigen::Isometry3d &pose);

            /** "[a,b,...]" of precise numbers. */
            void appendPreciseArray(std::string &out, const std::vector<double> &values);
        }  // namespace replay
    }      // namespace tools
}  // namespace michi

#endif
