#include "support/GridReachability.h"

#include <michi/validity/ConservativeMotionValidator.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/util/RandomNumbers.h>

#include <cmath>
#include <deque>

namespace ob = ompl::base;

namespace michi
{
    namespace test
    {
        namespace
        {
            /** connected components of the grid (4-neighbours joined by valid motions) */
            class GridComponents
            {
            public:
                GridComponents(const ob::SpaceInformationPtr &si, double step)
                    : si_(si), bounds_(si->getStateSpace()->as<ob::RealVectorStateSpace>()->getBounds())
                {
                    nx_ = static_cast<int>(std::floor((bounds_.high[0] - bounds_.low[0]) / step));
                    ny_ = static_cast<int>(std::floor((bounds_.high[1] - bounds_.low[1]) / step));
                    a_ = si->allocState();
                    b_ = si->allocState();
                    std::vector<char> valid(nx_ * ny_, 0);
                    for (int i = 0; i < nx_; ++i)
                        for (int j = 0; j < ny_; ++j)
                        {
                            set(a_, value(0, i), value(1, j));
                            valid[i * ny_ + j] = si->isValid(a_) ? 1 : 0;
                        }
                    label_.assign(nx_ * ny_, -1);
                    int next = 0;
                    for (int c0 = 0; c0 < nx_ * ny_; ++c0)
                    {
                        if (!valid[c0] || label_[c0] >= 0)
                            continue;
                        std::deque<int> open{c0};
                        label_[c0] = next;
                        while (!open.empty())
                        {
                            const int c = open.front();
                            open.pop_front();
                            const int i = c / ny_, j = c % ny_;
                            const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
                            for (int k = 0; k < 4; ++k)
                            {
                                const int ii = i + di[k], jj = j + dj[k];
                                if (ii < 0 || jj < 0 || ii >= nx_ || jj >= ny_)
                                    continue;
                                const int n = ii * ny_ + jj;
                                if (!valid[n] || label_[n] >= 0)
                                    continue;
                                set(a_, value(0, i), value(1, j));
                                set(b_, value(0, ii), value(1, jj));
                                if (!si->checkMotion(a_, b_))
                                    continue;
                                label_[n] = next;
                                open.push_back(n);
                            }
                        }
                        ++next;
                    }
                }
                ~GridComponents()
                {
                    si_->freeState(a_);
                    si_->freeState(b_);
                }
                /** components of the grid points near q that q reaches in a straight motion */
                std::vector<int> attach(const std::vector<double> &q)
                {
                    std::vector<int> out;
                    const int ci = static_cast<int>(
                        std::floor((q[0] - bounds_.low[0]) / (bounds_.high[0] - bounds_.low[0]) * nx_));
                    const int cj = static_cast<int>(
                        std::floor((q[1] - bounds_.low[1]) / (bounds_.high[1] - bounds_.low[1]) * ny_));
                    set(a_, q[0], q[1]);
                    for (int i = ci - 1; i <= ci + 1; ++i)
                        for (int j = cj - 1; j <= cj + 1; ++j)
                            if (i >= 0 && j >= 0 && i < nx_ && j < ny_ && label_[i * ny_ + j] >= 0)
                            {
                                set(b_, value(0, i), value(1, j));
                                if (si_->checkMotion(a_, b_))
                                    out.push_back(label_[i * ny_ + j]);
                            }
                    return out;
                }
                bool reachable(const std::vector<double> &start, const std::vector<double> &goal)
                {
                    const auto from = attach(start), to = attach(goal);
                    for (const int f : from)
                        for (const int t : to)
                            if (f == t)
                                return true;
                    return false;
                }

            private:
                double value(int axis, int i) const
                {
                    const int n = axis ? ny_ : nx_;
                    return bounds_.low[axis] + (i + 0.5) * (bounds_.high[axis] - bounds_.low[axis]) / n;
                }
                static void set(ob::State *s, double x, double y)
                {
                    s->as<ob::RealVectorStateSpace::StateType>()->values[0] = x;
                    s->as<ob::RealVectorStateSpace::StateType>()->values[1] = y;
                }
                ob::SpaceInformationPtr si_;
                ob::RealVectorBounds bounds_;
                int nx_{0}, ny_{0};
                std::vector<int> label_;
                ob::State *a_, *b_;
            };
        }  // namespace

        bool gridReachable(const ob::SpaceInformationPtr &si, const std::vector<double> &start,
                           const std::vector<double> &goal, double step)
        {
            GridComponents grid(si, step);
            return grid.reachable(start, goal);
        }

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
            GridComponents grid(si, step);
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
    }  // namespace test
}  // namespace michi
