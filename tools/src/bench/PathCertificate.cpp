#include <michi/tools/bench/PathCertificate.h>

#include <ompl/base/SpaceInformation.h>

#include <algorithm>
#include <cmath>

namespace michi
{
    namespace tools
    {
        PathCertificate certifyPath(const ompl::geometric::PathGeometric &path, const validity::FclValidityChecker &fcl,
                                    double fraction)
        {
            PathCertificate result;
            const auto &si = path.getSpaceInformation();
            const auto &space = si->getStateSpace();
            // A fraction of the planners' own resolution (ten times finer by default): a path a planner's validator let
            // through between its checks is re-checked between them. The floor keeps a zero-extent space from stepping
            // forever.
            const double step = std::max(1e-9, fraction * space->getLongestValidSegmentLength());
            std::vector<double> values;
            ompl::base::State *s = si->allocState();
            auto check = [&](const ompl::base::State *state, std::size_t segment, double t)
            {
                ++result.statesChecked;
                space->copyToReals(values, state);
                if (!si->satisfiesBounds(state))
                {
                    std::string at;
                    for (double v : values)
                        at += (at.empty() ? "" : ", ") + std::to_string(v);
                    result.reason = "segment " + std::to_string(segment) + " at " + std::to_string(t) +
                                    ": out of bounds (" + at + ")";
                    return false;
                }
                // Always FCL, whatever checker the planner used: a fast checker's mistake cannot certify its own path.
                const std::string hit = fcl.describeCollision(values.data());
                if (!hit.empty())
                    result.reason = "segment " + std::to_string(segment) + " at " + std::to_string(t) + ": " + hit;
                return hit.empty();
            };
            // The first state too: a motion validator takes its start as valid (OMPL's convention), so nothing else
            // checked it.
            bool ok = path.getStateCount() > 0 && check(path.getState(0), 0, 0.);
            for (std::size_t i = 0; ok && i + 1 < path.getStateCount(); ++i)
            {
                const auto *a = path.getState(i), *b = path.getState(i + 1);
                const std::size_t n =
                    std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(space->distance(a, b) / step)));
                for (std::size_t k = 1; ok && k <= n; ++k)
                {
                    const double t = static_cast<double>(k) / static_cast<double>(n);
                    if (k == n)
                    {
                        // The segment's end is the path's own state, not interpolate(a, b, 1): a + (b - a) * 1 can
                        // land an ulp past b, and past a joint limit when b sits on it (held-out IK goals clamped to
                        // a limit: every planner's valid path was refused as out of bounds).
                        ok = check(b, i, t);
                        break;
                    }
                    space->interpolate(a, b, t, s);
                    ok = check(s, i, t);
                }
            }
            if (path.getStateCount() == 0)
                result.reason = "empty path";
            si->freeState(s);
            result.certified = ok;
            return result;
        }
    }  // namespace tools
}  // namespace michi
