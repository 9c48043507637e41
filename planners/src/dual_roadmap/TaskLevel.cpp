#include "TaskLevel.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace michi
{
    namespace planners
    {
        void TaskLevel::begin(const Eigen::Vector3d &from, const Eigen::Vector3d &to, double cell, double margin)
        {
            from_ = from;
            to_ = to;
            if (!from.allFinite() || !to.allFinite() || !(cell > 0.) || !(margin >= 0.))
            {
                // no hand (a NaN from the task map): no grid, and route() finds nothing
                valid_.clear();
                invalid_.clear();
                roundValid_.clear();
                roundInvalid_.clear();
                return;
            }
            const Eigen::Vector3d lo = from.cwiseMin(to).array() - margin;
            const Eigen::Vector3d hi = from.cwiseMax(to).array() + margin;
            // A route is searched once per expansion round of a query: the grid stays small (a 1 m box at 5 cm is
            // 8,000 cells), larger cells when the box is large.
            const double side = (hi - lo).maxCoeff();
            cell_ = std::max(cell, side / 32.);
            origin_ = lo;
            std::size_t total = 1;
            for (int a = 0; a < 3; ++a)
            {
                n_[a] = std::max(1, static_cast<int>(std::ceil((hi[a] - lo[a]) / cell_)));
                total *= static_cast<std::size_t>(n_[a]);
            }
            valid_.assign(total, 0);
            invalid_.assign(total, 0);
            roundValid_.assign(total, 0);
            roundInvalid_.assign(total, 0);
        }

        long TaskLevel::cellOf(const Eigen::Vector3d &p) const
        {
            long index = 0;
            for (int a = 2; a >= 0; --a)
            {
                const double f = std::floor((p[a] - origin_[a]) / cell_);
                // a NaN fails both tests too
                if (!(f >= 0. && f < n_[a]))
                    return -1;
                index = index * n_[a] + static_cast<long>(f);
            }
            return index;
        }

        Eigen::Vector3d TaskLevel::centre(long c) const
        {
            const long i = c % n_[0], j = (c / n_[0]) % n_[1], k = c / (static_cast<long>(n_[0]) * n_[1]);
            return origin_ + cell_ * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
        }

        void TaskLevel::count(std::vector<std::uint16_t> &counts, long cell)
        {
            if (cell < 0)
                return;
            auto &n = counts[static_cast<std::size_t>(cell)];
            if (n < std::numeric_limits<std::uint16_t>::max())
                ++n;
        }

        void TaskLevel::mark(const Eigen::Vector3d &hand, bool valid)
        {
            if (!valid_.empty())
                count(valid ? valid_ : invalid_, cellOf(hand));
        }

        void TaskLevel::beginRound()
        {
            std::fill(roundValid_.begin(), roundValid_.end(), 0);
            std::fill(roundInvalid_.begin(), roundInvalid_.end(), 0);
        }

        void TaskLevel::markRound(const Eigen::Vector3d &hand, bool valid)
        {
            if (!valid_.empty())
                count(valid ? roundValid_ : roundInvalid_, cellOf(hand));
        }

        bool TaskLevel::blocked(const Eigen::Vector3d &p) const
        {
            const long c = valid_.empty() ? -1 : cellOf(p);
            return c >= 0 && blockedCell(static_cast<std::size_t>(c));
        }

        bool TaskLevel::route(double blockedCost, std::vector<Eigen::Vector3d> &waypoints)
        {
            waypoints.clear();
            if (valid_.empty())
                return false;
            // below 1 a blocked cell would be cheaper than its length and the straight distance no longer admissible
            blockedCost = std::max(1., blockedCost);
            const long start = cellOf(from_), goal = cellOf(to_);
            // begin() made the box hold both ends; a NaN hand is the only way out
            if (start < 0 || goal < 0)
                return false;
            const std::size_t total = valid_.size();
            g_.assign(total, std::numeric_limits<double>::infinity());
            pred_.assign(total, -1);
            closed_.assign(total, 0);
            const Eigen::Vector3d target = centre(goal);
            using Item = std::pair<double, long>;
            std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
            g_[static_cast<std::size_t>(start)] = 0.;
            open.emplace((centre(start) - target).norm(), start);
            const long nx = n_[0], ny = n_[1], nz = n_[2];
            while (!open.empty())
            {
                const long u = open.top().second;
                open.pop();
                if (closed_[static_cast<std::size_t>(u)] != 0)
                    continue;
                closed_[static_cast<std::size_t>(u)] = 1;
                if (u == goal)
                    break;
                const long i = u % nx, j = (u / nx) % ny, k = u / (nx * ny);
                for (long dk = -1; dk <= 1; ++dk)
                    for (long dj = -1; dj <= 1; ++dj)
                        for (long di = -1; di <= 1; ++di)
                        {
                            const long a = i + di, b = j + dj, c = k + dk;
                            if ((di == 0 && dj == 0 && dk == 0) || a < 0 || b < 0 || c < 0 || a >= nx || b >= ny ||
                                c >= nz)
                                continue;
                            const long w = a + nx * (b + ny * c);
                            if (closed_[static_cast<std::size_t>(w)] != 0)
                                continue;
                            const auto sw = static_cast<std::size_t>(w);
                            // a step into a blocked cell costs more, never less, than its length: the straight
                            // distance stays an admissible heuristic
                            const double step = cell_ * std::sqrt(static_cast<double>(di * di + dj * dj + dk * dk)) *
                                                (blockedCell(sw) ? blockedCost : 1.);
                            const double g = g_[static_cast<std::size_t>(u)] + step;
                            if (g >= g_[sw])
                                continue;
                            g_[sw] = g;
                            pred_[sw] = u;
                            open.emplace(g + (centre(w) - target).norm(), w);
                        }
            }
            // every cell is reachable (blocked cells only cost more): the goal's cell was reached
            std::vector<long> cells;
            for (long c = goal; c != -1; c = pred_[static_cast<std::size_t>(c)])
                cells.push_back(c);
            std::reverse(cells.begin(), cells.end());
            waypoints.push_back(from_);
            for (std::size_t m = 1; m + 1 < cells.size(); ++m)
                waypoints.push_back(centre(cells[m]));
            waypoints.push_back(to_);
            return true;
        }
    }  // namespace planners
}  // namespace michi
