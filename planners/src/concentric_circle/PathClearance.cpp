#include "PathClearance.h"

#include <algorithm>
#include <cmath>

namespace ob = ompl::base;

namespace michi
{
    namespace planners
    {
        namespace
        {
            double distanceAt(const validity::JMapValidityChecker &checker, double x, double y, double cap)
            {
                // A point inside a polygon has no clearance, whatever its distance to the boundary.
                const validity::JMap &tile = checker.tile(x);
                if (tile.collides(x, y))
                    return 0.;
                return tile.distanceToBoundary(x, y, cap);
            }
        }  // namespace

        double jmapClearance(const ob::SpaceInformation &si, const validity::JMapValidityChecker &checker,
                             const ob::State *state, double cap)
        {
            std::vector<double> v;
            si.getStateSpace()->copyToReals(v, state);
            return distanceAt(checker, v[0], v[1], cap);
        }

        double jmapPathClearance(const ob::SpaceInformation &si, const validity::JMapValidityChecker &checker,
                                 const std::vector<ob::State *> &states, double cap)
        {
            // Clearance is capped: the slab walk looks only within cap of the point, which bounds its cost.
            double worst = cap;
            ob::State *between = si.allocState();
            for (std::size_t i = 0; i < states.size(); ++i)
            {
                worst = std::min(worst, jmapClearance(si, checker, states[i], cap));
                if (i + 1 == states.size())
                    break;
                // the segment's interior at the resolution the motion validator samples a discrete check at
                const unsigned int n = si.getStateSpace()->validSegmentCount(states[i], states[i + 1]);
                for (unsigned int k = 1; k < n; ++k)
                {
                    si.getStateSpace()->interpolate(states[i], states[i + 1], static_cast<double>(k) / n, between);
                    worst = std::min(worst, jmapClearance(si, checker, between, cap));
                }
            }
            si.freeState(between);
            return worst;
        }

        int pushAwayFromObstacles(const ob::SpaceInformationPtr &si, std::vector<ob::State *> &states,
                                  const ob::PlannerTerminationCondition &ptc, int sweeps, double step)
        {
            if (states.size() < 3)
                return 0;
            const auto &space = si->getStateSpace();
            const auto &checker = si->getStateValidityChecker();
            ob::State *moved = si->allocState();
            ob::State *probe = si->allocState();
            std::vector<double> v, w;
            auto clearanceAt = [&](const std::vector<double> &values)
            {
                space->copyFromReals(probe, values);
                return si->satisfiesBounds(probe) && checker->isValid(probe) ? checker->clearance(probe) : 0.;
            };
            int kept = 0;
            for (int sweep = 0; sweep < sweeps && !ptc && step > 1e-3; ++sweep)
            {
                int keptThisSweep = 0;
                const double h = 0.25 * step;  // central differences, narrower than a step
                for (std::size_t i = 1; i + 1 < states.size() && !ptc; ++i)
                {
                    space->copyToReals(v, states[i]);
                    const double c0 = clearanceAt(v);
                    double g[2];
                    for (int a = 0; a < 2; ++a)
                    {
                        w = v;
                        w[a] = v[a] + h;
                        const double up = clearanceAt(w);
                        w[a] = v[a] - h;
                        g[a] = up - clearanceAt(w);
                    }
                    const double norm = std::hypot(g[0], g[1]);
                    if (!(norm > 1e-12))
                        continue;  // on a ridge of the clearance: nowhere better close by
                    w = v;
                    w[0] += step * g[0] / norm;
                    w[1] += step * g[1] / norm;
                    space->copyFromReals(moved, w);
                    // kept only if clearer, valid, and both motions pass: the path stays a valid path at every move
                    if (!si->satisfiesBounds(moved) || !checker->isValid(moved) || checker->clearance(moved) <= c0 ||
                        !si->checkMotion(states[i - 1], moved) || !si->checkMotion(moved, states[i + 1]))
                        continue;
                    si->copyState(states[i], moved);
                    ++keptThisSweep;
                }
                kept += keptThisSweep;
                // A sweep that moved nothing: the step is too long for what is left to gain, so halve it (down to
                // 1e-3).
                if (keptThisSweep == 0)
                    step *= 0.5;
            }
            si->freeState(probe);
            si->freeState(moved);
            return kept;
        }
    }  // namespace planners
}  // namespace michi
