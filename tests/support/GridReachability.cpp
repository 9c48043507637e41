#include "support/GridReachability.h"

#include <michi/tools/problem/GridReachability.h>
#include <michi/validity/fcl/ConservativeMotionValidator.h>

#include <ompl/base/ScopedState.h>
#include <ompl/util/RandomNumbers.h>

#include <cmath>

namespace ob = ompl::base;

namespace michi
{
    namespace test
    {
        ArmQuery reachableArmQuery(std::uint_fast32_t seed, double step)
        {
            RandomPolygonOptions options;
            options.count = 6;
            options.keepClearRadius = 0.1;
            ArmQuery q;
            q.setup = planarArmSetup({0.5, 0.4}, randomPolygons(seed, options));
            const auto &si = q.setup.si;
            // the exact (conservative-advancement) motion validator, for the grid and for the planners
            si->setMotionValidator(std::make_shared<validity::ConservativeMotionValidator>(si, q.setup.checker));
            tools::GridComponents grid(si, step);
            ompl::RNG rng(7000 + seed);
            ob::State *a = si->allocState(), *b = si->allocState();
            for (int attempt = 0; attempt < 200 && !q.found; ++attempt)
            {
                const std::vector<double> s{rng.uniformReal(-M_PI, M_PI), rng.uniformReal(-M_PI, M_PI)};
                const std::vector<double> g{rng.uniformReal(-M_PI, M_PI), rng.uniformReal(-M_PI, M_PI)};
                if (std::hypot(s[0] - g[0], s[1] - g[1]) < 1.)
                    continue;
                si->getStateSpace()->copyFromReals(a, s);
                si->getStateSpace()->copyFromReals(b, g);
                if (!si->isValid(a) || !si->isValid(b) || si->checkMotion(a, b))
                    continue;
                if (!grid.reachable(s, g))
                    continue;
                q.start = s;
                q.goal = g;
                q.found = true;
            }
            si->freeState(a);
            si->freeState(b);
            return q;
        }

        ompl::geometric::SimpleSetupPtr armQuerySetup(const ArmQuery &query)
        {
            const auto &si = query.setup.si;
            auto ss = std::make_shared<ompl::geometric::SimpleSetup>(si);
            ob::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
            si->getStateSpace()->copyFromReals(start.get(), query.start);
            si->getStateSpace()->copyFromReals(goal.get(), query.goal);
            ss->setStartAndGoalStates(start, goal);
            return ss;
        }
    }  // namespace test
}  // namespace michi
