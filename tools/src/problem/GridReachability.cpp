#include <michi/tools/problem/GridReachability.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <cmath>
#include <deque>
#include <stdexcept>

namespace ob = ompl::base;

namespace michi
{
    namespace tools
    {
        GridComponents::GridComponents(const ob::SpaceInformationPtr &si, double step) : si_(si)
        {
            const auto *space = dynamic_cast<const ob::RealVectorStateSpace *>(si->getStateSpace().get());
            if (space == nullptr || space->getDimension() != 2 || !(step > 0.))
                throw std::invalid_argument("GridComponents needs a 2-D RealVectorStateSpace and a positive step");
            bounds_ = space->getBounds();
            // floor: cells are at least step wide, so a cell centre never lies outside the bounds.
            nx_ = static_cast<int>(std::floor((bounds_.high[0] - bounds_.low[0]) / step));
            ny_ = static_cast<int>(std::floor((bounds_.high[1] - bounds_.low[1]) / step));
            if (nx_ < 1 || ny_ < 1)
                throw std::invalid_argument("GridComponents: the step is larger than the space");
            a_ = si->allocState();
            b_ = si->allocState();
            // Validity of every cell centre first, then the flood fill: a neighbour pair is joined only when both
            // centres are valid and the motion validator accepts the straight motion between them, so a component is a
            // set of states really connected (at this resolution) under the problem's own checker.
            std::vector<char> valid(nx_ * ny_, 0);
            for (int i = 0; i < nx_; ++i)
                for (int j = 0; j < ny_; ++j)
                {
                    set(a_, value(0, i), value(1, j));
                    valid[i * ny_ + j] = si->isValid(a_) ? 1 : 0;
                }
            label_.assign(nx_ * ny_, -1);
            for (int c0 = 0; c0 < nx_ * ny_; ++c0)
            {
                if (!valid[c0] || label_[c0] >= 0)
                    continue;
                std::deque<int> open{c0};
                label_[c0] = components_;
                while (!open.empty())
                {
                    const int c = open.front();
                    open.pop_front();
                    const int i = c / ny_, j = c % ny_;
                    // 4-connected: each join is one straight motion along an axis that the motion validator checks.
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
                        label_[n] = components_;
                        open.push_back(n);
                    }
                }
                ++components_;
            }
        }

        GridComponents::~GridComponents()
        {
            si_->freeState(a_);
            si_->freeState(b_);
        }

        std::vector<int> GridComponents::attach(const std::vector<double> &q) const
        {
            std::vector<int> out;
            const int ci =
                static_cast<int>(std::floor((q[0] - bounds_.low[0]) / (bounds_.high[0] - bounds_.low[0]) * nx_));
            const int cj =
                static_cast<int>(std::floor((q[1] - bounds_.low[1]) / (bounds_.high[1] - bounds_.low[1]) * ny_));
            set(a_, q[0], q[1]);
            // A query state rarely sits on a cell centre: it attaches to every component it reaches by a valid straight
            // motion to one of the 3 x 3 nearest cell centres (it may touch several, e.g. in a narrow passage).
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

        bool GridComponents::reachable(const std::vector<double> &start, const std::vector<double> &goal) const
        {
            const auto from = attach(start), to = attach(goal);
            // Any shared component proves a path (query -> centre -> grid -> centre -> query); no shared one says only
            // that none was found at this resolution.
            for (const int f : from)
                for (const int t : to)
                    if (f == t)
                        return true;
            return false;
        }

        double GridComponents::value(int axis, int i) const
        {
            const int n = axis ? ny_ : nx_;
            return bounds_.low[axis] + (i + 0.5) * (bounds_.high[axis] - bounds_.low[axis]) / n;
        }

        void GridComponents::set(ob::State *s, double x, double y) const
        {
            s->as<ob::RealVectorStateSpace::StateType>()->values[0] = x;
            s->as<ob::RealVectorStateSpace::StateType>()->values[1] = y;
        }

        bool gridReachable(const ob::SpaceInformationPtr &si, const std::vector<double> &start,
                           const std::vector<double> &goal, double step)
        {
            return GridComponents(si, step).reachable(start, goal);
        }
    }  // namespace tools
}  // namespace michi
