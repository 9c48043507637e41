#include <michi/planners/path_seed/PathSeedRepair.h>

#include <michi/validity/fcl/WorkspaceMotionValidator.h>

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace planners
    {
        namespace
        {
            /** Motions (a_i, b_i), endpoints already valid: the validator's intermediate states round-robin over the
                motions in bisection order (WorkspaceMotionValidator), else checkMotion one by one. Returns the
                index of an invalid motion, motions.size() when all are valid, or -1 when \e ptc fired. */
            long checkMotionsFailFast(const ob::SpaceInformationPtr &si,
                                      const std::vector<std::pair<const ob::State *, const ob::State *>> &motions,
                                      const ob::PlannerTerminationCondition &ptc, unsigned long &count,
                                      unsigned int threads, CheckThreads *pool)
            {
                const auto *wmv =
                    dynamic_cast<const validity::WorkspaceMotionValidator *>(si->getMotionValidator().get());
                if (!wmv)
                {
                    for (std::size_t i = 0; i < motions.size(); ++i)
                    {
                        if (ptc)
                            return -1;
                        if (!si->checkMotion(motions[i].first, motions[i].second))
                            return static_cast<long>(i);
                    }
                    return static_cast<long>(motions.size());
                }
                // the validator's own states (j / n, j = 1 .. n - 1, n = stepCount), bisection order per motion,
                // round-robin over the motions; the order does not depend on the results, so it is listed first
                struct Segment
                {
                    std::size_t index;
                    unsigned int n;
                    std::deque<std::pair<unsigned int, unsigned int>> intervals;
                };
                std::vector<Segment> segments;
                for (std::size_t i = 0; i < motions.size(); ++i)
                {
                    const unsigned int n = wmv->stepCount(motions[i].first, motions[i].second);
                    if (n > 1)
                        segments.push_back(Segment{i, n, {{1u, n - 1}}});
                }
                std::vector<std::pair<std::size_t, double>> items;  // (motion, fraction)
                // Bisection order, round-robin over all motions: every segment's middle is checked before any
                // segment's quarters, so a candidate that fails anywhere costs few checks (path-seed.md, "fail-fast").
                for (bool pending = true; pending;)
                {
                    pending = false;
                    for (auto &seg : segments)
                    {
                        while (!seg.intervals.empty() && seg.intervals.front().first > seg.intervals.front().second)
                            seg.intervals.pop_front();
                        if (seg.intervals.empty())
                            continue;
                        const auto [lo, hi] = seg.intervals.front();
                        seg.intervals.pop_front();
                        const unsigned int mid = (lo + hi) / 2;
                        items.emplace_back(seg.index, static_cast<double>(mid) / seg.n);
                        if (mid > lo)
                            seg.intervals.emplace_back(lo, mid - 1);
                        seg.intervals.emplace_back(mid + 1, hi);
                        pending = true;
                    }
                }
                // Threads claim the items in order from one counter, so the caller alone finishes a hand-out that a
                // helper joins late (or not at all: CheckThreads::share); the first failure stops all.
                const long all = static_cast<long>(motions.size());
                std::atomic<long> failed{all};
                std::atomic<bool> stopped{false};
                std::atomic<unsigned long> checked{0};
                std::atomic<std::size_t> next{0};
                auto work = [&]
                {
                    ob::State *state = si->allocState();
                    for (std::size_t i = next++; i < items.size(); i = next++)
                    {
                        if (failed.load() != all || stopped.load())
                            break;
                        if (ptc)
                        {
                            stopped = true;
                            break;
                        }
                        const auto &item = items[i];
                        si->getStateSpace()->interpolate(motions[item.first].first, motions[item.first].second,
                                                         item.second, state);
                        ++checked;
                        if (!si->isValid(state))
                        {
                            failed = static_cast<long>(item.first);
                            break;
                        }
                    }
                    si->freeState(state);
                };
                const std::size_t T = std::max<std::size_t>(1, std::min<std::size_t>(threads, items.size() / 8 + 1));
                if (pool != nullptr && T > 1 && T <= pool->helpers() + 1)
                    // the planner's own helpers: no thread started per hand-out, none waited for that has not begun
                    pool->share(static_cast<unsigned int>(T),
                                [&](unsigned int)
                                {
                                    work();
                                });
                else
                {
                    std::vector<std::thread> helpers;
                    for (std::size_t t = 1; t < T; ++t)
                        helpers.emplace_back(work);
                    work();
                    for (auto &h : helpers)
                        h.join();
                }
                count += checked.load();
                if (failed.load() != all)
                    return failed.load();
                return stopped.load() ? -1 : all;
            }
        }  // namespace

        bool checkPathFailFast(const ob::SpaceInformationPtr &si, const og::PathGeometric &path,
                               const ob::PlannerTerminationCondition &ptc, unsigned long *checks, unsigned int threads,
                               CheckThreads *pool)
        {
            const auto &states = const_cast<og::PathGeometric &>(path).getStates();  // OMPL 1.5: no const getStates()
            unsigned long count = 0;
            bool ok = true;
            for (const auto *s : states)
            {
                if (ptc)
                {
                    ok = false;
                    break;
                }
                ++count;
                // Waypoints before any motion: one state check each, and a waypoint in collision fails the candidate at
                // once.
                if (!si->satisfiesBounds(s) || !si->isValid(s))
                {
                    ok = false;
                    break;
                }
            }
            if (ok)
            {
                std::vector<std::pair<const ob::State *, const ob::State *>> motions;
                for (std::size_t i = 0; i + 1 < states.size(); ++i)
                    motions.emplace_back(states[i], states[i + 1]);
                ok = checkMotionsFailFast(si, motions, ptc, count, threads, pool) == static_cast<long>(motions.size());
            }
            if (checks)
                *checks += count;
            return ok;
        }

        std::size_t PathValidity::invalidStates() const
        {
            return std::count(state.begin(), state.end(), 0);
        }

        std::size_t PathValidity::invalidSegments() const
        {
            return std::count(segment.begin(), segment.end(), 0);
        }

        PathValidity checkPathFull(const ob::SpaceInformationPtr &si, const og::PathGeometric &path,
                                   const ob::PlannerTerminationCondition &ptc)
        {
            const auto &states = const_cast<og::PathGeometric &>(path).getStates();  // OMPL 1.5: no const getStates()
            PathValidity v;
            v.state.assign(states.size(), 0);
            v.segment.assign(states.empty() ? 0 : states.size() - 1, 0);
            for (std::size_t i = 0; i < states.size() && !ptc; ++i)
                v.state[i] = si->satisfiesBounds(states[i]) && si->isValid(states[i]);
            for (std::size_t i = 0; i + 1 < states.size() && !ptc; ++i)
                v.segment[i] = v.state[i] && v.state[i + 1] && si->checkMotion(states[i], states[i + 1]);
            return v;
        }

        bool stitchPaths(const ob::SpaceInformationPtr &si, const std::vector<og::PathGeometric> &paths,
                         const ob::PlannerTerminationCondition &ptc, og::PathGeometric &out, unsigned int neighbours,
                         unsigned long *checks, unsigned int threads, CheckThreads *pool)
        {
            if (paths.empty())
                return false;
            // vertices: 0 start, 1 goal, then the interior states of every path
            std::vector<const ob::State *> states{paths.front().getState(0),
                                                  paths.front().getState(paths.front().getStateCount() - 1)};
            std::vector<int> owner{-1, -1};
            // (a < b) pairs, sorted and made unique below. With a std::set here and Eigen vectors of dynamic size
            // for the distances the graph took 106-358 us of a stitching solve on the xArm6 (V = 65-155), with this
            // layout 79-240 us on the same queries.
            std::vector<std::pair<std::size_t, std::size_t>> edges;
            auto addEdge = [&](std::size_t a, std::size_t b)
            {
                if (a != b)
                    edges.emplace_back(std::min(a, b), std::max(a, b));
            };
            for (std::size_t p = 0; p < paths.size(); ++p)
            {
                const auto &path = paths[p];
                std::size_t previous = 0;
                for (std::size_t i = 1; i + 1 < path.getStateCount(); ++i)
                {
                    states.push_back(path.getState(i));
                    owner.push_back(static_cast<int>(p));
                    addEdge(previous, states.size() - 1);
                    previous = states.size() - 1;
                }
                addEdge(previous, 1);
            }
            const std::size_t V = states.size();
            // neighbours and edge weights by the Euclidean distance of the states' reals (a heuristic for the
            // search only; every edge used is checked by the motion validator): far cheaper than
            // StateSpace::distance on a compound joint space. One flat array, vertex after vertex.
            std::vector<double> reals;
            std::size_t dim = 0;
            {
                std::vector<double> r;
                for (std::size_t v = 0; v < V; ++v)
                {
                    si->getStateSpace()->copyToReals(r, states[v]);
                    dim = r.size();
                    reals.insert(reals.end(), r.begin(), r.end());
                }
            }
            const auto squaredDistance = [&](std::size_t a, std::size_t b)
            {
                const double *x = reals.data() + a * dim, *y = reals.data() + b * dim;
                double sum = 0.;
                for (std::size_t k = 0; k < dim; ++k)
                    sum += (x[k] - y[k]) * (x[k] - y[k]);
                return sum;
            };
            // each interior state to its nearest states of other paths: the k smallest (squared distance, vertex)
            // pairs, kept sorted by insertion (k is a handful)
            std::vector<std::pair<double, std::size_t>> nearest;
            for (std::size_t a = 2; a < V && neighbours > 0; ++a)
            {
                nearest.clear();
                for (std::size_t b = 2; b < V; ++b)
                {
                    if (owner[b] == owner[a])
                        continue;
                    const std::pair<double, std::size_t> item(squaredDistance(a, b), b);
                    if (nearest.size() == neighbours && !(item < nearest.back()))
                        continue;
                    if (nearest.size() == neighbours)
                        nearest.pop_back();
                    nearest.insert(std::upper_bound(nearest.begin(), nearest.end(), item), item);
                }
                for (const auto &n : nearest)
                    addEdge(a, n.second);
            }
            std::sort(edges.begin(), edges.end());
            edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
            std::vector<char> vertex(V, 0);  // 0 unknown, 1 valid, 2 invalid
            vertex[0] = vertex[1] = 1;       // start and goal are the query's
            unsigned long count = 0;
            // The graph is laid out once: edge e joins ends[e] with weight weight[e], and each vertex lists its
            // (neighbour, edge) pairs. A round's search skips refuted edges and vertices by their flags. Rebuilding a
            // Boost adjacency_list from the edge map every round was about a third of a stitching solve on the xArm6
            // (perf, docs/path-seed.md); the search is the same Dijkstra over the same weights.
            std::vector<std::pair<std::size_t, std::size_t>> ends;
            std::vector<char> state;  // per edge: 0 unknown, 1 valid, 2 invalid
            std::vector<double> weight;
            std::vector<std::vector<std::pair<std::size_t, std::size_t>>> adjacent(V);
            for (const auto &e : edges)
            {
                const std::size_t id = ends.size();
                ends.push_back(e);
                state.push_back(0);
                weight.push_back(std::sqrt(squaredDistance(e.first, e.second)));
                adjacent[e.first].emplace_back(e.second, id);
                adjacent[e.second].emplace_back(e.first, id);
            }
            const std::size_t none = std::numeric_limits<std::size_t>::max();
            std::vector<double> distance(V);
            std::vector<std::size_t> parentEdge(V), parent(V);
            using Entry = std::pair<double, std::size_t>;
            std::vector<Entry> heap;
            bool found = false;
            while (!found && !ptc)
            {
                // Dijkstra from the start over what is not known invalid (LazyPRM's scheme: the next shortest path
                // avoids what the last one refuted)
                std::fill(distance.begin(), distance.end(), std::numeric_limits<double>::infinity());
                std::fill(parentEdge.begin(), parentEdge.end(), none);
                distance[0] = 0.;
                heap.assign(1, Entry{0., 0});
                while (!heap.empty())
                {
                    std::pop_heap(heap.begin(), heap.end(), std::greater<>());
                    const auto [d, u] = heap.back();
                    heap.pop_back();
                    if (d > distance[u])
                        continue;  // a stale entry
                    if (u == 1)
                        break;  // the goal's distance is final
                    for (const auto &[w, e] : adjacent[u])
                    {
                        if (state[e] == 2 || vertex[w] == 2)
                            continue;
                        const double through = d + weight[e];
                        if (through < distance[w])
                        {
                            distance[w] = through;
                            parent[w] = u;
                            parentEdge[w] = e;
                            heap.emplace_back(through, w);
                            std::push_heap(heap.begin(), heap.end(), std::greater<>());
                        }
                    }
                }
                if (parentEdge[1] == none)
                    break;  // goal unreachable
                std::vector<std::size_t> route{1};
                std::vector<std::size_t> routeEdges;
                while (route.back() != 0)
                {
                    routeEdges.push_back(parentEdge[route.back()]);
                    route.push_back(parent[route.back()]);
                }
                std::reverse(route.begin(), route.end());
                std::reverse(routeEdges.begin(), routeEdges.end());
                // states first, then the unchecked edges as one path (fail-fast order)
                bool ok = true;
                for (std::size_t v : route)
                    if (vertex[v] == 0)
                    {
                        ++count;
                        vertex[v] = si->satisfiesBounds(states[v]) && si->isValid(states[v]) ? 1 : 2;
                        ok = ok && vertex[v] == 1;
                    }
                if (!ok)
                    continue;
                og::PathGeometric candidate(si);
                for (std::size_t v : route)
                    candidate.append(states[v]);
                std::vector<std::size_t> unknown;
                for (std::size_t e : routeEdges)
                    if (state[e] == 0)
                        unknown.push_back(e);
                // all unchecked edges at once, round-robin bisection
                std::vector<std::pair<const ob::State *, const ob::State *>> motions;
                for (std::size_t e : unknown)
                    motions.emplace_back(states[ends[e].first], states[ends[e].second]);
                const long failed = checkMotionsFailFast(si, motions, ptc, count, threads, pool);
                if (failed < 0)
                    break;
                const bool allValid = failed == static_cast<long>(motions.size());
                if (!allValid)
                    state[unknown[static_cast<std::size_t>(failed)]] = 2;
                else
                    for (std::size_t e : unknown)
                        state[e] = 1;
                if (allValid && !ptc)
                {
                    out = candidate;
                    found = true;
                }
            }
            if (checks)
                *checks += count;
            return found;
        }

        namespace
        {
            /** RRT-Connect from \e a to \e b; appends the states after \e a (b included) to \e out. */
            bool connect(const ob::SpaceInformationPtr &si, const ob::State *a, const ob::State *b, double range,
                         const ob::PlannerTerminationCondition &ptc, og::PathGeometric &out)
            {
                auto pdef = std::make_shared<ob::ProblemDefinition>(si);
                pdef->addStartState(a);
                auto goal = std::make_shared<ob::GoalState>(si);
                goal->setState(b);
                pdef->setGoal(goal);
                og::RRTConnect rrt(si);
                if (range > 0.)
                    rrt.setRange(range);
                rrt.setProblemDefinition(pdef);
                rrt.setup();
                if (rrt.solve(ptc) != ob::PlannerStatus::EXACT_SOLUTION)
                    return false;
                const auto *p = pdef->getSolutionPath()->as<og::PathGeometric>();
                for (std::size_t i = 1; i < p->getStateCount(); ++i)
                    out.append(p->getState(i));
                return true;
            }
        }  // namespace

        bool repairWithRRTConnect(const ob::SpaceInformationPtr &si, og::PathGeometric &path,
                                  const ob::PlannerTerminationCondition &ptc, double range, unsigned int shortcutSteps)
        {
            const PathValidity v = checkPathFull(si, path, ptc);
            const auto &states = const_cast<og::PathGeometric &>(path).getStates();  // OMPL 1.5: no const getStates()
            if (ptc || states.size() < 2 || !v.state.front() || !v.state.back())
                return false;
            og::PathGeometric out(si, states.front());
            std::size_t i = 0;
            while (i + 1 < states.size())
            {
                if (ptc)
                    return false;
                if (v.segment[i])
                {
                    out.append(states[i + 1]);
                    ++i;
                    continue;
                }
                // the invalid stretch ends at the next valid waypoint j
                std::size_t j = i + 1;
                while (!v.state[j])
                    ++j;
                // The straight motion first: one motion check, far cheaper than RRT-Connect when it works.
                if (si->checkMotion(states[i], states[j]))
                    out.append(states[j]);
                else if (!connect(si, states[i], states[j], range, ptc, out))
                    return false;
                i = j;
            }
            if (shortcutSteps > 0 && !ptc)
            {
                og::PathSimplifier simplifier(si);
                simplifier.shortcutPath(out, shortcutSteps, shortcutSteps);
            }
            path = out;
            return true;
        }
    }  // namespace planners
}  // namespace michi
