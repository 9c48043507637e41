// DualRoadmap's lazy checking (paper 002: the working roadmap's edges are checked only where a candidate path
// goes): a candidate path's states, probes and motions, re-checks limited to the parts a recorded change can
// touch, and the shortcuts of a found path. The search and the roadmaps are in DualRoadmap.cpp.
#include <michi/planners/dual_roadmap/DualRoadmap.h>

#include <algorithm>
#include <utility>
#include <vector>

namespace ob = ompl::base;

namespace michi
{
    namespace planners
    {
        bool DualRoadmap::validatePath(const std::vector<Vertex> &path, const ob::PlannerTerminationCondition &ptc)
        {
            // States first (one check each, and an invalid one rules out all its edges), then motions, in order.
            // Every state of the path is checked before giving up: a moved obstacle usually covers several
            // vertices of a candidate path, and each found at once saves a search (the profile's top item).
            bool statesValid = true;
            for (Vertex v : path)
            {
                if (knownValid(v))
                    continue;
                if (ptc)
                    return false;
                ++work_.stateChecks;
                if (!si_->isValid(graph_[v].state))
                {
                    graph_[v].invalidIn = epoch_;  // impassable in this scene, so the next search goes round it
                    graph_[v].refutedIn = epoch_;
                    graph_[v].validIn = 0;
                    statesValid = false;
                    continue;
                }
                graph_[v].validIn = epoch_;
                graph_[v].invalidIn = 0;
            }
            if (!statesValid)
                return false;
            // then a few states inside every unproved motion, for the same reason (setEdgeProbes())
            bool probesValid = true;
            for (std::size_t i = 0; i + 1 < path.size() && edgeProbes_ > 0; ++i)
            {
                if (ptc)
                    return false;
                const auto e = graph_.findEdge(path[i], path[i + 1]);
                if (!e.second || knownValidEdge(e.first) || knownInvalidEdge(e.first))
                    continue;
                if (refutedByProbes(path[i], path[i + 1]))
                {
                    refuteEdge(e.first);
                    probesValid = false;
                }
            }
            if (!probesValid)
                return false;
            for (std::size_t i = 0; i + 1 < path.size(); ++i)
            {
                if (ptc)
                    return false;
                const auto e = graph_.findEdge(path[i], path[i + 1]);
                if (!e.second || knownInvalidEdge(e.first))
                    return false;
                if (knownValidEdge(e.first))
                    continue;
                if (checkEdgeMotion(e.first, path[i], path[i + 1]))
                    acceptEdge(e.first, path[i], path[i + 1]);
                else
                {
                    // Invalid in this scene only: the edge stays (a moving obstacle may leave it free again), the
                    // next search avoids it. Edges checked valid before the failing one stay checked and learned.
                    refuteEdge(e.first);
                    return false;
                }
            }
            return true;
        }

        bool DualRoadmap::motionValid(Vertex a, Vertex b)
        {
            const auto e = addEdgeOnce(a, b);
            if (!e.second)
            {
                if (knownValidEdge(e.first))
                    return true;
                // a shortcut refuted a short while ago is not tried again while its record is stale (smoothing
                // is optional work; the walker that blocked it most likely still does)
                if (knownInvalidEdge(e.first) || recentlyRefuted(graph_.edge(e.first).refutedIn))
                    return false;
            }
            if (!refutedByProbes(a, b))
            {
                if (checkEdgeMotion(e.first, a, b))
                {
                    acceptEdge(e.first, a, b);
                    return true;
                }
            }
            refuteEdge(e.first);
            return false;
        }

        bool DualRoadmap::checkEdgeMotion(Edge e, Vertex a, Vertex b)
        {
            const ob::State *sa = graph_[a].state, *sb = graph_[b].state;
            const std::uint64_t since = graph_.edge(e).provedIn;
            // Parts only when every change since the proof is on record with its region (an empty region, or one
            // older than the history, may have changed anything).
            bool local = recheckDepth_ > 0 && since != 0 && since < epoch_ && epoch_ - since <= history_.size();
            for (std::size_t i = history_.size() - (local ? epoch_ - since : 0); local && i < history_.size(); ++i)
                local = static_cast<bool>(history_[i]);
            if (!local)
            {
                ++work_.motionChecks;
                return si_->checkMotion(sa, sb);
            }
            thread_local std::vector<std::pair<double, double>> parts;
            parts.clear();
            affectedParts(since, a, b, 0., 1., recheckDepth_, parts);
            const auto &space = si_->getStateSpace();
            ob::State *from = part_[0], *to = part_[1], *mid = part_[2], *ref = part_[3];
            const double tolerance = 1e-9 * std::max(1., si_->distance(sa, sb));
            for (const auto &part : parts)
            {
                if (part.first <= 0. && part.second >= 1.)
                {
                    ++work_.motionChecks;
                    return si_->checkMotion(sa, sb);
                }
                space->interpolate(sa, sb, part.first, from);
                space->interpolate(sa, sb, part.second, to);
                // The part checked must be the stretch of this motion: true of geodesic interpolation (real vectors,
                // SO(2), SE(2), SE(3)), not of every space; where the middles differ, the whole motion is checked.
                space->interpolate(from, to, 0.5, mid);
                space->interpolate(sa, sb, 0.5 * (part.first + part.second), ref);
                ++work_.motionChecks;
                if (si_->distance(mid, ref) > tolerance)
                    return si_->checkMotion(sa, sb);
                // checkMotion() does not check its first state (OMPL's convention): the part's own start is new
                if (part.first > 0.)
                {
                    ++work_.stateChecks;
                    if (!si_->isValid(from))
                        return false;
                }
                if (!si_->checkMotion(from, to))
                    return false;
            }
            return true;
        }

        void DualRoadmap::affectedParts(std::uint64_t since, Vertex a, Vertex b, double t0, double t1,
                                        unsigned int depth, std::vector<std::pair<double, double>> &parts)
        {
            const auto &space = si_->getStateSpace();
            ob::State *from = part_[0], *to = part_[1];
            space->interpolate(graph_[a].state, graph_[b].state, t0, from);
            space->interpolate(graph_[a].state, graph_[b].state, t1, to);
            if (unaffectedSince(since, from, to))
                return;
            if (depth == 0)
            {
                if (!parts.empty() && parts.back().second == t0)
                    parts.back().second = t1;  // one check over adjacent affected parts
                else
                    parts.emplace_back(t0, t1);
                return;
            }
            const double tm = 0.5 * (t0 + t1);
            affectedParts(since, a, b, t0, tm, depth - 1, parts);
            affectedParts(since, a, b, tm, t1, depth - 1, parts);
        }

        void DualRoadmap::acceptEdge(Edge e, Vertex a, Vertex b)
        {
            graph_.edge(e).validIn = graph_.edge(e).provedIn = epoch_;
            graph_.edge(e).invalidIn = 0;
            // Paper 002: every edge newly proved valid in the working roadmap is added to the learning roadmap.
            learnEdge(a, b);
        }

        void DualRoadmap::refuteEdge(Edge e)
        {
            graph_.edge(e).invalidIn = epoch_;
            graph_.edge(e).refutedIn = epoch_;
            graph_.edge(e).validIn = 0;
            graph_.edge(e).provedIn = 0;
        }

        bool DualRoadmap::refutedByProbes(Vertex a, Vertex b)
        {
            // van der Corput order: 1/2, 1/4, 3/4, 1/8, ...: spread over the motion whatever their number
            for (unsigned int k = 1; k <= edgeProbes_; ++k)
            {
                double t = 0., f = 0.5;
                for (unsigned int bits = k; bits != 0; bits >>= 1, f *= 0.5)
                    if (bits & 1u)
                        t += f;
                si_->getStateSpace()->interpolate(graph_[a].state, graph_[b].state, t, probe_);
                ++work_.stateChecks;
                if (!si_->isValid(probe_))
                    return true;
            }
            return false;
        }

        std::vector<DualRoadmap::Vertex> DualRoadmap::shortcut(const std::vector<Vertex> &path,
                                                               const ob::PlannerTerminationCondition &ptc)
        {
            std::vector<Vertex> out{path.front()};
            // No shortcut longer than the roadmap's own edges (range_fraction): the long ones, across the map,
            // were mostly refuted (3-4 failed checks of 6 m on average per query on dynamic_mobile_passage), and a
            // long edge kept in the roadmap crosses some change region at almost every query, to be re-checked.
            const double range = rangeFraction_ * si_->getMaximumExtent();
            std::size_t i = 0;
            while (i + 1 < path.size())
            {
                std::size_t next = i + 1;
                // the far end first, then halfway, ...: O(log n) checks per kept vertex; each proved (or refuted)
                // shortcut is recorded in the roadmap, so the next query's search takes it without a check
                for (std::size_t step = path.size() - 1 - i; step > 1 && !ptc; step /= 2)
                    if (si_->distance(graph_[path[i]].state, graph_[path[i + step]].state) <= range &&
                        motionValid(path[i], path[i + step]))
                    {
                        next = i + step;
                        break;
                    }
                out.push_back(path[next]);
                i = next;
            }
            return out;
        }

    }  // namespace planners
}  // namespace michi
