#include "viewer/ReplayJson.h"

#include <cmath>
#include <cstdio>

namespace michi
{
    namespace tools
    {
        namespace replay
        {
            void appendFixed(std::string &out, double value, int decimals)
            {
                if (!std::isfinite(value))
                    value = 0.;  // JSON has no NaN or infinity; nothing the page draws is infinite
                char buffer[64];
                int n = std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
                if (n <= 0 || n >= static_cast<int>(sizeof buffer))
                {
                    n = std::snprintf(buffer, sizeof buffer, "%.6g", value);
                    out.append(buffer, n);
                    return;
                }
                if (decimals > 0)
                {
                    // Trailing zeros dropped: most coordinates are short numbers, and every byte counts against the
                    // page's 5 MB bound.
                    while (n > 0 && buffer[n - 1] == '0')
                        --n;
                    if (n > 0 && buffer[n - 1] == '.')
                        --n;
                }
                std::string text(buffer, n);
                // A value that rounds to zero from below prints as -0; the same page should not differ by a sign that
                // means nothing.
                if (text == "-0")
                    text = "0";
                out += text;
            }

            void appendPrecise(std::string &out, double value)
            {
                if (!std::isfinite(value))
                    value = 0.;
                char buffer[64];
                // Ten significant digits for times and key frames, which the page interpolates between and must not
                // drift.
                const int n = std::snprintf(buffer, sizeof buffer, "%.10g", value);
                out.append(buffer, n);
            }

            namespace
            {
                /** The pose's rotation as a unit quaternion with a non-negative w: q and -q are the same rotation,
                    and a non-negative w keeps neighbouring frames' slerp short. */
                Eigen::Quaterniond rotation(const Eigen::Isometry3d &pose)
                {
                    Eigen::Quaterniond q(pose.linear());
                    q.normalize();
                    if (q.w() < 0.)
                        q.coeffs() = -q.coeffs();
                    return q;
                }
            }  // namespace

            void appendPoseValues(std::string &out, const Eigen::Isometry3d &pose)
            {
                const Eigen::Vector3d t = pose.translation();
                const Eigen::Quaterniond q = rotation(pose);
                for (int i = 0; i < 3; ++i)
                {
                    appendFixed(out, t[i], POSITION_DECIMALS);
                    out += ',';
                }
                appendFixed(out, q.x(), ROTATION_DECIMALS);
                out += ',';
                appendFixed(out, q.y(), ROTATION_DECIMALS);
                out += ',';
                appendFixed(out, q.z(), ROTATION_DECIMALS);
                out += ',';
                appendFixed(out, q.w(), ROTATION_DECIMALS);
            }

            void appendPrecisePoseValues(std::string &out, const Eigen::Isometry3d &pose)
            {
                const Eigen::Vector3d t = pose.translation();
                const Eigen::Quaterniond q = rotation(pose);
                const double values[7] = {t[0], t[1], t[2], q.x(), q.y(), q.z(), q.w()};
                for (int i = 0; i < 7; ++i)
                {
                    if (i)
                        out += ',';
                    appendPrecise(out, values[i]);
                }
            }

            void appendPose(std::string &out, const Eigen::Isometry3d &pose)
            {
                out += '[';
                appendPoseValues(out, pose);
                out += ']';
            }

            void appendPreciseArray(std::string &out, const std::vector<double> &values)
            {
                out += '[';
                for (std::size_t i = 0; i < values.size(); ++i)
                {
                    if (i)
                        out += ',';
                    appendPrecise(out, values[i]);
                }
                out += ']';
            }
        }  // namespace replay
    }      // namespace tools
}  // namespace michi
