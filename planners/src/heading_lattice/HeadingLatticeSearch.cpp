// HeadingLattice, second half: the A* search over the implicit lattice, its 2-D Dijkstra heuristic kept per goal,
// and the lazily checked, cached edges (the planner's state, setup and paths are in HeadingLattice.cpp).
#include <michi/planners/heading_lattice/HeadingLattice.h>
#include "HeadingLatticeCommon.h"

#include <michi/state_spaces/Angles.h>
#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/grid/GridValidityChecker.h>
#include <michi/validity/grid/HeadingTable.h>

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/util/Time.h>

#include <boost/math/constants/constants.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <array>
#include <map>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace planners
    {
        void HeadingLattice::resetHeuristic()
        {
            if (hReady_ || !hOpen_.empty())
                newHeuristicStamp();
            hOpen_.clear();
            hReady_ = false;
        }

        void HeadingLattice::newHeuristicStamp()
        {
            if (++hStamp_ >= (1u << 30))
            {
                // the stamps would wrap into old ones: clear every entry once
                std::fill(hGroups_.begin(), hGroups_.end(), GroupEntry{std::numeric_limits<float>::infinity(), 0u});
                hStamp_ = 1;
            }
        }

        float HeadingLattice::groupToStart(std::uint32_t g) const
        {
            // Group g is grid point (g / rows, g % rows), the same order as node ids ((i rows + j) K + k).
            return groupToStart(static_cast<long>(g / rows_), static_cast<long>(g % rows_));
        }

        float HeadingLattice::groupToStart(long i, long j) const
        {
            const double x = x0_ + static_cast<double>(i) * cellSize_;
            const double y = y0_ + static_cast<double>(j) * cellSize_;
            double d = INF;
            for (std::size_t i = 0; i + 1 < hStarts_.size(); i += 2)
            {
                const double dx = x - hStarts_[i], dy = y - hStarts_[i + 1];
                d = std::min(d, dx * dx + dy * dy);  // squared; std::hypot is slow and overflow cannot happen here
            }
            d = std::sqrt(d);
            // rounded down a little, so that float rounding cannot make it exceed a path of steps
            return d == INF ? 0.f : static_cast<float>(d * (1. - 1e-6));
        }

        void HeadingLattice::aimHeuristic()
        {
            std::vector<double> starts;
            for (const auto &q : queries_)
                if (q.start)
                {
                    const auto *s = q.state->as<ob::SE2StateSpace::StateType>();
                    starts.insert(starts.end(), {s->getX(), s->getY()});
                }
            if (starts == hStarts_)
                return;
            hStarts_ = starts;
            // the open groups' priorities follow the new starts; closed groups keep their exact distances (an
            // entry of a group reached twice is recomputed twice; the second is skipped as closed when popped)
            for (auto &e : hOpen_)
                e = groupKey(hDist(keyGroup(e)) + groupToStart(keyGroup(e)), keyGroup(e));
            keyHeapMake(hOpen_);
        }

        double HeadingLattice::groupDistance(std::uint32_t g, const ob::PlannerTerminationCondition &ptc, bool &stopped)
        {
            // a resumable search over the groups (8-connected, steps of c and c sqrt 2) from the groups joined to
            // a goal, through groups with at least one free node (checked here, cached for the search). It is A*
            // directed at the starts (Silver's reverse resumable A*): the straight line to the start is a
            // consistent heuristic, so a group is closed with its exact distance, and the groups near the line
            // from the goal to the start (those the lattice search asks for) close long before the rest of the
            // map would in a plain Dijkstra
            const unsigned int K = headings_;
            auto isFree = [&](std::uint32_t group, long i, long j)
            {
                std::uint8_t &f = groupFree_[group];
                if (f == 0)
                {
                    f = 2;
                    for (unsigned int k = 0; k < K; ++k)
                        if (nodeValid(group * K + k, i, j, k))
                        {
                            f = 1;
                            break;
                        }
                }
                return f == 1;
            };
            const double c = cellSize_, diagonal = cellSize_ * std::sqrt(2.);
            unsigned int count = 0;
            while (hState(g) != 2 && !hOpen_.empty())
            {
                if ((++count & 255u) == 0 && ptc())
                {
                    stopped = true;
                    return 0.;
                }
                const std::uint64_t top = keyHeapPop(hOpen_);
                const std::uint32_t u = keyGroup(top);
                const long i = u / rows_, j = u % rows_;
                const float du = hDist(u);
                if (hState(u) == 2 || keyPriority(top) > du + groupToStart(i, j))
                    continue;  // closed, or a better way to it was found after this entry
                setHState(u, 2);
                ++work_.heuristicGroups;
                for (int di = -1; di <= 1; ++di)
                    for (int dj = -1; dj <= 1; ++dj)
                    {
                        if (di == 0 && dj == 0)
                            continue;
                        const long ni = i + di, nj = j + dj;
                        if (ni < 0 || nj < 0 || ni >= static_cast<long>(columns_) || nj >= static_cast<long>(rows_))
                            continue;
                        const auto w = static_cast<std::uint32_t>(ni * rows_ + nj);
                        if (hState(w) == 2)
                            continue;
                        const float d = static_cast<float>(du + (di != 0 && dj != 0 ? diagonal : c));
                        if (d < hDist(w) && isFree(w, ni, nj))
                        {
                            setHGroup(w, d, 1);
                            keyHeapPush(hOpen_, groupKey(d + groupToStart(ni, nj), w));
                        }
                    }
            }
            return hState(g) == 2 ? hDist(g) : INF;
        }

        double HeadingLattice::heuristic(Vertex v, const ob::PlannerTerminationCondition &ptc, bool &stopped)
        {
            if (!isLattice(v))
                return 0.;
            double x, y;
            nodePosition(v, x, y);
            double euclid = INF;
            // drives and the join to a goal cost at least the straight-line distance (turns: see build())
            for (std::size_t i = 0; i + 2 < hGoals_.size(); i += 3)
            {
                const double dx = x - hGoals_[i], dy = y - hGoals_[i + 1];
                euclid = std::min(euclid, dx * dx + dy * dy);  // squared (std::hypot is slow)
            }
            euclid = std::sqrt(euclid);
            // A group the 2-D search cannot reach from any goal has no path at all: infinity prunes it, and a walled-in
            // goal is reported at once instead of after the whole lattice.
            const double grid = groupDistance(v / headings_, ptc, stopped);
            if (grid == INF)
                return INF;
            return heuristicWeight_ * (std::max({0., euclidWeight_ * euclid, grid / OCTILE_EXCESS - cellSize_}) +
                                       turnTerm_[v % headings_]);
        }

        void HeadingLattice::rebuildGoalLinks()
        {
            goalLinks_.clear();
            for (std::uint32_t qi = 0; qi < queries_.size(); ++qi)
                if (!queries_[qi].start)
                    for (std::uint32_t ci = 0; ci < queries_[qi].nodes.size(); ++ci)
                        goalLinks_.push_back({queries_[qi].nodes[ci], {qi, ci}});
            std::sort(goalLinks_.begin(), goalLinks_.end());
        }

        void HeadingLattice::prepareHeuristic()
        {
            std::vector<double> goals;
            for (const auto &q : queries_)
                if (!q.start)
                {
                    const auto *s = q.state->as<ob::SE2StateSpace::StateType>();
                    goals.insert(goals.end(), {s->getX(), s->getY(), q.radius});
                }
            // The turning still to do: a path from heading k ends at a goal's heading, so it turns at least the
            // angle between them, on turn edges (turnCost_ a step) or in the join to the goal (which costs at least
            // as much a radian in both spaces). A turn edge also moves the position, by up to shift_, which the
            // straight-line part of the heuristic may count (euclidWeight_ shift_ <= turnCost_); so each step of
            // turning may add only what is left of its cost, turnCost_ - shift_ (0 where a turn is cheaper than
            // the shift, as for small robots in a turn-move-turn space), and the heuristic stays consistent.
            const unsigned int K = headings_;
            const double step = 2. * PI / K;
            const double perRadian = std::max(0., turnCost_ - euclidWeight_ * shift_) / step;
            turnTerm_.assign(K, 0.);
            if (perRadian > 0.)
                for (unsigned int k = 0; k < K; ++k)
                {
                    double least = INF;
                    for (const auto &q : queries_)
                        if (!q.start)
                        {
                            const double yaw = q.state->as<ob::SE2StateSpace::StateType>()->getYaw();
                            least = std::min(least, std::abs(state_spaces::turnBetween(yaw, geometry_[k].yaw)));
                        }
                    // rounded down a little, as the other parts, so that float rounding cannot break the bound
                    turnTerm_[k] = least == INF ? 0. : perRadian * least * (1. - 1e-9);
                }
            if (hReady_ && goals == hGoals_)
            {
                aimHeuristic();  // kept: the same goals on the same map, maybe another start
                return;
            }
            resetHeuristic();
            hGoals_ = goals;
            hStarts_.clear();
            for (const auto &q : queries_)
                if (q.start)
                {
                    const auto *s = q.state->as<ob::SE2StateSpace::StateType>();
                    hStarts_.insert(hStarts_.end(), {s->getX(), s->getY()});
                }
            for (const auto &q : queries_)
                if (!q.start)
                    for (Vertex v : q.nodes)
                    {
                        const std::uint32_t g = v / headings_;
                        if (hState(g) == 0)
                        {
                            setHGroup(g, 0.f, 1);
                            keyHeapPush(hOpen_, groupKey(groupToStart(g), g));
                        }
                    }
            hReady_ = true;
        }

        std::uint8_t *HeadingLattice::edgeSlot(Vertex a, Vertex b, int &shift)
        {
            shift = 0;
            if (isLattice(a) && isLattice(b))
            {
                const unsigned int K = headings_;
                // Same group: a turn. Its two bits (shift 2) sit in the slot of heading k of the pair (k, k + 1 mod K),
                // beside the two bits of that node's drive.
                if (a / K == b / K)
                {
                    shift = 2;
                    if (b % K == (a % K + 1) % K)
                        return &edgeState_[a];
                    if (a % K == (b % K + 1) % K)
                        return &edgeState_[b];
                    return nullptr;
                }
                // A drive is stored with the node it leaves forwards, so both directions of one drive share a slot.
                if (driveNext(a) == static_cast<std::int64_t>(b))
                    return &edgeState_[a];
                if (driveNext(b) == static_cast<std::int64_t>(a))
                    return &edgeState_[b];
                return nullptr;
            }
            if (!isLattice(a) && !isLattice(b))
            {
                for (auto &d : direct_)
                    if (d.from == a && d.to == b)
                        return &d.status;
                return nullptr;
            }
            QueryVertex &q = query(isLattice(a) ? b : a);
            const Vertex node = isLattice(a) ? a : b;
            for (std::size_t i = 0; i < q.nodes.size(); ++i)
                if (q.nodes[i] == node)
                    return &q.status[i];
            return nullptr;
        }

        HeadingLattice::Node HeadingLattice::nodeOf(Vertex v) const
        {
            Node n;
            nodePosition(v, n.x, n.y);
            n.heading = v % headings_;
            n.group = v / headings_;
            return n;
        }

        bool HeadingLattice::checkEdgeMotion(Vertex a, Vertex b)
        {
            ob::State *sa = motionScratch_[0], *sb = motionScratch_[1];
            setNodeState(a, sa);
            setNodeState(b, sb);
            if (isLattice(a) && isLattice(b) && a / headings_ == b / headings_)
            {
                // a turn in place between the headings, at both nodes' positions
                ++work_.edgeChecks;
                ob::State *c = motionScratch_[2], *d = motionScratch_[3];
                const auto *pa = sa->as<ob::SE2StateSpace::StateType>();
                const auto *pb = sb->as<ob::SE2StateSpace::StateType>();
                setState(c, pa->getX(), pa->getY(), pb->getYaw());
                setState(d, pb->getX(), pb->getY(), pa->getYaw());
                return si_->checkMotion(sa, c) && si_->checkMotion(d, sb);
            }
            ++(isLattice(a) && isLattice(b) ? work_.edgeChecks : work_.queryChecks);
            return si_->checkMotion(sa, sb);
        }

        bool HeadingLattice::turnFree(Vertex lower, Vertex upper)
        {
            // Lazy by default: a turn counts as free until a path uses it (checkEdges). Once a turn was refuted in this
            // query (a long robot turning near walls: on a cave map 327 of 348 refuted edges were turns, and each
            // refutation cost a whole new search), turns are decided when the search meets them: free at once where
            // the grid table vouches for every yaw the turn sweeps at both nodes' cells (valid entries: every pose of
            // the cell and bin is free), else by their motion check.
            const int state = (edgeState_.get(lower) >> 2) & 3;
            if (!eagerTurns_ || gridChecker_ == nullptr || state == VALID)
                return true;
            const validity::HeadingTable &table = gridChecker_->table();
            const validity::OccupancyGrid &grid = table.grid();
            const double inverse = 1. / grid.resolution;  // the table's own arithmetic (freeOnGrid)
            const int bins = table.headings();
            const int first = table.headingBin(geometry_[lower % headings_].wrappedYaw);
            const int last = table.headingBin(geometry_[upper % headings_].wrappedYaw);
            bool vouched = true;
            for (const Vertex v : {lower, upper})
            {
                double x, y;
                nodePosition(v, x, y);
                const double fx = (x - grid.origin.x()) * inverse, fy = (y - grid.origin.y()) * inverse;
                const int i = static_cast<int>(fx), j = static_cast<int>(fy);
                // the turn sweeps the closed interval between the two headings, which these bins cover (bin k: the
                // yaws within half a step of its centre, both ends included)
                for (int b = first; vouched; b = (b + 1) % bins)
                {
                    vouched = fx >= 0. && fy >= 0. && table.valid(i, j, b);
                    if (b == last)
                        break;
                }
            }
            const bool ok = vouched || checkEdgeMotion(lower, upper);
            int shift;
            std::uint8_t *slot = edgeSlot(lower, upper, shift);
            *slot = static_cast<std::uint8_t>((*slot & ~(3 << shift)) | ((ok ? VALID : INVALID) << shift));
            return ok;
        }

        std::vector<HeadingLattice::Vertex> HeadingLattice::search(const ob::PlannerTerminationCondition &ptc,
                                                                   bool &stopped)
        {
            stopped = false;
            ++work_.searches;
            const std::size_t n = static_cast<std::size_t>(nodeCount_) + queries_.size();
            // Stamps instead of clearing: an entry counts only when stamped in this search, so a search costs what it
            // touches, not the size of the lattice; the top bit marks it expanded. A wrapped stamp forces one real
            // clear.
            constexpr std::uint32_t EXPANDED = 0x80000000u;
            if (g_.size() < n || ++searchStamp_ == EXPANDED)
            {
                // room for a few more query vertices, so that new queries on the kept lattice keep the pages
                g_.assign(n + 64, 0.f);
                parent_.assign(n + 64, 0);
                stamp_.assign(n + 64, 0);
                searchStamp_ = 1;
            }
            open_.clear();
            auto less = [](const OpenEntry &a, const OpenEntry &b)
            {
                return heapLess(a.f, a.g, b.f, b.g);
            };
            auto relax = [&](Vertex u, Vertex w, double cost)
            {
                const float ng = static_cast<float>(g_[u] + cost);
                const std::uint32_t seen = stamp_[w];
                // An expanded node is not opened again (weighted A* without re-expansions: the path still costs at
                // most heuristic_weight times the shortest, Likhachev et al., ARA*, NIPS 2003). Reopening expanded
                // the nodes near a goal up to 22 times each, five times the nodes it expanded
                // (docs/heading-lattice.md).
                if (seen == (searchStamp_ | EXPANDED) || (seen == searchStamp_ && !(ng < g_[w])))
                    return;
                const double h = heuristic(w, ptc, stopped);
                if (stopped || h == INF)
                    return;
                stamp_[w] = searchStamp_;
                g_[w] = ng;
                parent_[w] = u;
                open_.push_back(OpenEntry{static_cast<float>(ng + h), ng, w});
                std::push_heap(open_.begin(), open_.end(), less);
            };
            for (std::size_t qi = 0; qi < queries_.size(); ++qi)
                if (queries_[qi].start)
                {
                    const auto v = static_cast<Vertex>(nodeCount_ + qi);
                    stamp_[v] = searchStamp_;
                    g_[v] = 0.f;
                    parent_[v] = v;
                    open_.push_back(OpenEntry{0.f, 0.f, v});
                    std::push_heap(open_.begin(), open_.end(), less);
                }
            const unsigned int K = headings_;
            unsigned int count = 0;
            while (!open_.empty())
            {
                if ((++count & 255u) == 0 && ptc())
                {
                    stopped = true;
                    return {};
                }
                std::pop_heap(open_.begin(), open_.end(), less);
                const OpenEntry e = open_.back();
                open_.pop_back();
                if (e.g > g_[e.v] || stamp_[e.v] == (searchStamp_ | EXPANDED))
                    continue;  // a better way to it was found after this entry, or it was expanded
                const Vertex u = e.v;
                stamp_[u] = searchStamp_ | EXPANDED;
                ++work_.expansions;
                if (!isLattice(u))
                {
                    const QueryVertex &q = query(u);
                    if (!q.start)
                    {
                        std::vector<Vertex> path;
                        for (Vertex v = u;; v = parent_[v])
                        {
                            path.push_back(v);
                            if (parent_[v] == v)
                                break;
                        }
                        std::reverse(path.begin(), path.end());
                        return path;
                    }
                    for (std::size_t i = 0; i < q.nodes.size() && !stopped; ++i)
                        // Unchecked joins and edges count as valid (lazy): checkEdges() decides them when a path uses
                        // them.
                        if (q.status[i] != INVALID && nodeValid(q.nodes[i]))
                            relax(u, q.nodes[i], q.costs[i]);
                    for (const auto &d : direct_)
                        if (d.from == u && d.status != INVALID && !stopped)
                            relax(u, d.to, d.cost);
                }
                else
                {
                    const std::uint32_t group = u / K;
                    const unsigned int k = u % K;
                    const double length = geometry_[k].length;
                    const std::int64_t next = driveNext(u);
                    if (next >= 0 && (edgeState_.get(u) & 3) != INVALID && nodeValid(static_cast<Vertex>(next)))
                        relax(u, static_cast<Vertex>(next), length);
                    if (reversible_ && !stopped)
                    {
                        const std::int64_t prev = drivePrev(u);
                        if (prev >= 0 && (edgeState_.get(prev) & 3) != INVALID && nodeValid(static_cast<Vertex>(prev)))
                            relax(u, static_cast<Vertex>(prev), length);
                    }
                    const Vertex up = group * K + (k + 1) % K, down = group * K + (k + K - 1) % K;
                    if (!stopped && (edgeState_.get(u) >> 2) != INVALID && nodeValid(up) && turnFree(u, up))
                        relax(u, up, turnCost_);
                    if (!stopped && (edgeState_.get(down) >> 2) != INVALID && nodeValid(down) && turnFree(down, u))
                        relax(u, down, turnCost_);
                    auto it = std::lower_bound(goalLinks_.begin(), goalLinks_.end(),
                                               std::make_pair(u, std::make_pair(0u, 0u)));
                    for (; it != goalLinks_.end() && it->first == u && !stopped; ++it)
                    {
                        const QueryVertex &q = queries_[it->second.first];
                        if (q.status[it->second.second] != INVALID)
                            relax(u, static_cast<Vertex>(nodeCount_ + it->second.first), q.costs[it->second.second]);
                    }
                }
                if (stopped)
                    return {};
            }
            return {};
        }

        void HeadingLattice::removeEdgePair(Vertex a, Vertex b)
        {
            int shift;
            if (std::uint8_t *slot = edgeSlot(a, b, shift))
                *slot = static_cast<std::uint8_t>((*slot & ~(3 << shift)) | (INVALID << shift));
        }

        bool HeadingLattice::checkEdges(const std::vector<Vertex> &path, const ob::PlannerTerminationCondition &ptc,
                                        bool &stopped)
        {
            stopped = false;
            for (std::size_t p = 0; p + 1 < path.size(); ++p)
            {
                int shift;
                std::uint8_t *slot = edgeSlot(path[p], path[p + 1], shift);
                const int before = slot == nullptr ? VALID : (*slot >> shift) & 3;
                // Known edges are not checked again; the search never returns a path over an INVALID one.
                if (before == VALID || before == INVALID)
                    continue;
                if (before == STALE)
                    ++work_.edgeRechecks;
                if (ptc())
                {
                    stopped = true;
                    return false;
                }
                const std::uint8_t status = checkEdgeMotion(path[p], path[p + 1]) ? VALID : INVALID;
                slot = edgeSlot(path[p], path[p + 1], shift);
                *slot = static_cast<std::uint8_t>((*slot & ~(3 << shift)) | (status << shift));
                if (status != VALID)
                {
                    // a refuted turn: from now on this query's searches check turns as they meet them
                    if (isLattice(path[p]) && isLattice(path[p + 1]) && path[p] / headings_ == path[p + 1] / headings_)
                        eagerTurns_ = true;
                    return false;
                }
            }
            return true;
        }
    }  // namespace planners
}  // namespace michi
