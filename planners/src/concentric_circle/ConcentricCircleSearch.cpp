#include <michi/planners/concentric_circle/ConcentricCircleSearch.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <queue>

namespace michi
{
    namespace planners
    {
        namespace
        {
            constexpr double INF = std::numeric_limits<double>::infinity();

            double segmentDistance(const Eigen::Vector2d &p, const Eigen::Vector2d &a, const Eigen::Vector2d &b)
            {
                const Eigen::Vector2d ab = b - a;
                const double len2 = ab.squaredNorm();
                const double t = len2 > 0. ? std::clamp((p - a).dot(ab) / len2, 0., 1.) : 0.;
                return (a + t * ab - p).norm();
            }

            /** the oval potential's obstacle term of edge AB at P */
            double repulsion(const Eigen::Vector2d &p, const Edge2 &e, double kObstacle)
            {
                // Paper 000: Dp = |PA| + |PB| - |AB| is constant on ellipses with foci A and B (hence "oval"), zero on
                // the edge itself; the floor keeps a point on the edge finite.
                const double dp = std::max((p - e.a).norm() + (p - e.b).norm() - (e.a - e.b).norm(), 1e-9);
                return kObstacle / (dp * dp);
            }
        }  // namespace

        ConcentricCircleSearch::ConcentricCircleSearch(const CircleMap &map, ConcentricCircleSettings settings)
            : map_(map), settings_(settings)
        {
            // Fewer than 4 points per circle cannot go round an obstacle; a zero spacing would never leave the start.
            if (settings_.candidates == "paper")
            {
                // Paper 000: every circle cut into the same number of points (72, every 5 degrees), one candidate
                // per free arc, its minimum-potential point.
                settings_.maxArcPoints = 0;
                settings_.arcEnds = false;
                settings_.pointSpacing = 0.;
            }
            settings_.divisions = std::max(settings_.divisions, 4);
            settings_.ringSpacing = std::max(settings_.ringSpacing, 1e-6);
        }

        Eigen::Vector2d ConcentricCircleSearch::image(const Eigen::Vector2d &from, const Eigen::Vector2d &to) const
        {
            Eigen::Vector2d r = to;
            for (int i = 0; i < 2; ++i)
                if (map_.wraps[i])
                {
                    const double period = map_.hi[i] - map_.lo[i];
                    // On a wrapping axis every point has images one period apart: links and distances use the image
                    // nearest to the other end, so a short way across +-pi is a short link.
                    r[i] -= period * std::round((r[i] - from[i]) / period);
                }
            return r;
        }

        int ConcentricCircleSearch::addNode(const Eigen::Vector2d &p, int set, int ring)
        {
            nodes_.push_back({p, set, ring, 0.});
            adjacency_.emplace_back();
            return static_cast<int>(nodes_.size()) - 1;
        }

        void ConcentricCircleSearch::addLink(int a, int b, bool unchecked)
        {
            for (const auto &e : adjacency_[a])
                if (e.to == b)
                    return;
            const double len = (image(nodes_[a].p, nodes_[b].p) - nodes_[a].p).norm();
            adjacency_[a].push_back({b, len, unchecked});
            adjacency_[b].push_back({a, len, unchecked});
            ++version_;
        }

        bool ConcentricCircleSearch::tryLink(int a, int b)
        {
            if (a == b)
                return false;
            const Eigen::Vector2d pa = nodes_[a].p, pb = image(pa, nodes_[b].p);
            if (!map_.isVisible(pa, pb))
                return false;
            addLink(a, b);
            return true;
        }

        void ConcentricCircleSearch::proposeLink(int a, int b)
        {
            if (a == b)
                return;
            // Links are proposed unchecked and tested only when a shortest path uses them (lazy, like LazyPRM): which
            // paths exist is unchanged, and most links are never tested (docs/concentric-circle.md: 185 instead of 1502
            // on planar_2link).
            addLink(a, b, true);
        }

        bool ConcentricCircleSearch::validateLink(int a, int b)
        {
            const auto &adjacent = adjacency_[a];
            for (std::size_t i = 0; i < adjacent.size(); ++i)
                if (adjacent[i].to == b)
                    return validateArc(a, i);
            return true;  // no such link: nothing to check (as for a checked one)
        }

        bool ConcentricCircleSearch::validateArc(int a, std::size_t i)
        {
            // The flag lives on both directions of the link: a set of unchecked pairs, looked up at every relaxation
            // of the searches, was about 3.5 % of a planar_2link J-map solve in perf, besides validateLink's own 4-5 %.
            Arc &arc = adjacency_[a][i];
            if (!arc.unchecked)
                return true;
            const int b = arc.to;
            arc.unchecked = false;
            for (auto &back : adjacency_[b])
                if (back.to == a)
                    back.unchecked = false;
            const Eigen::Vector2d pa = nodes_[a].p, pb = image(pa, nodes_[b].p);
            if (map_.isVisible(pa, pb))
                return true;
            removeLink(a, b);
            return false;
        }

        bool ConcentricCircleSearch::validatePath(const std::vector<int> &path)
        {
            for (std::size_t i = 1; i < path.size(); ++i)
                if (!validateLink(path[i - 1], path[i]))
                    return false;
            return true;
        }

        bool ConcentricCircleSearch::lazyConnect()
        {
            std::vector<double> dist;
            std::vector<int> parent;
            // every link of the path found has been checked (checkedSearch)
            return checkedSearch(0, 1, dist, parent);
        }

        void ConcentricCircleSearch::removeLink(int a, int b)
        {
            auto drop = [this](int from, int to)
            {
                auto &adj = adjacency_[from];
                adj.erase(std::remove_if(adj.begin(), adj.end(),
                                         [to](const Arc &e)
                                         {
                                             return e.to == to;
                                         }),
                          adj.end());
            };
            drop(a, b);
            drop(b, a);
            ++version_;
        }

        std::vector<std::pair<int, int>> ConcentricCircleSearch::links() const
        {
            std::vector<std::pair<int, int>> out;
            // Only checked links are exported: an unchecked one may cross an obstacle, and pictures and
            // PlannerData would show it as a way through.
            for (std::size_t a = 0; a < adjacency_.size(); ++a)
                for (const auto &e : adjacency_[a])
                    if (static_cast<int>(a) < e.to && !e.unchecked)
                        out.emplace_back(static_cast<int>(a), e.to);
            return out;
        }

        int ConcentricCircleSearch::addSet(int centre, int goal, double spacing, int divisions, bool cover)
        {
            CcSet set;
            set.centreNode = centre;
            set.goalNode = goal;
            set.spacing = spacing;
            set.divisions = divisions;
            const Eigen::Vector2d c = nodes_[centre].p;
            set.goalRadius = (image(c, nodes_[goal].p) - c).norm();
            // The ring that reaches the goal's radius; the 1e-9 keeps a goal exactly on a ring from needing one ring
            // more.
            set.goalRings = std::max(1, static_cast<int>(std::ceil(set.goalRadius / spacing - 1e-9)));
            double reach = 0.;
            if (cover)
            {
                Eigen::Vector2d far;
                // cover: rings out to the map's farthest corner from the centre (half a period on a wrapping axis,
                // beyond which the rings meet themselves), for paths that detour farther than the goal.
                for (int i = 0; i < 2; ++i)
                    far[i] = map_.wraps[i] ? 0.5 * (map_.hi[i] - map_.lo[i])
                                           : std::max(std::abs(c[i] - map_.lo[i]), std::abs(map_.hi[i] - c[i]));
                reach = far.norm();
            }
            set.maxRings = std::max(set.goalRings + 1, static_cast<int>(std::ceil(reach / spacing)));
            sets_.push_back(set);
            return static_cast<int>(sets_.size()) - 1;
        }

        int ConcentricCircleSearch::sampleRing(int s, int k, const ompl::base::PlannerTerminationCondition &ptc)
        {
            CcSet &set = sets_[s];
            if (static_cast<int>(set.rings.size()) >= k)
                return set.rings[k - 1];
            // rings are sampled in order
            const int prevCount = static_cast<int>(set.rings.size());
            for (int j = prevCount + 1; j <= k; ++j)
            {
                CcRing ring;
                ring.set = s;
                ring.index = j;
                ring.radius = j * set.spacing;
                ring.centre = nodes_[set.centreNode].p;
                const Eigen::Vector2d towards = image(ring.centre, nodes_[set.goalNode].p) - ring.centre;
                // the first point faces the goal, so the straight way is always sampled
                const double phase = towards.norm() > 0. ? std::atan2(towards.y(), towards.x()) : 0.;
                // the paper's fixed number of points, or more on large circles so that neighbouring points stay
                // within pointSpacing of each other
                const double pointSpacing = settings_.pointSpacing * set.spacing / settings_.ringSpacing;
                const int n =
                    pointSpacing > 0.
                        ? std::max(set.divisions, static_cast<int>(std::ceil(2. * M_PI * ring.radius / pointSpacing)))
                        : set.divisions;
                ring.points.resize(n);
                ring.free.assign(n, 0);
                ring.potential.assign(n, 0.);
                if (ptc)
                    return -1;
                // J-map polygons: the circle's free arcs in one pass from its crossings with the polygon edges;
                // other maps: a point test per point.
                const bool arcs = map_.freeArcs(ring.centre, ring.radius, phase, n, ring.arc);
                if (!arcs)
                    ring.arc.clear();
                for (int i = 0; i < n; ++i)
                {
                    // ptc is checked every few points only: one point test is cheap next to evaluating the condition.
                    if (i % 8 == 0 && ptc)
                        return -1;
                    const double a = phase + 2. * M_PI * i / n;
                    ring.points[i] = ring.centre + ring.radius * Eigen::Vector2d(std::cos(a), std::sin(a));
                    ring.free[i] = (arcs ? ring.arc[i] >= 0 : map_.isFree(ring.points[i])) ? 1 : 0;
                }
                // chords of the blocked runs (at most 6 steps each): the obstacle edges the circles see
                int firstFree = -1;
                for (int i = 0; i < n && firstFree < 0; ++i)
                    if (ring.free[i])
                        firstFree = i;
                if (firstFree < 0)
                {
                    // A fully blocked circle: chords of at most six steps around the whole circle, so the potential
                    // sees the obstacle from every side; short chords stay close to the sampled circle.
                    for (int i = 0; i < n; i += 6)
                        ring.blockedEdges.push_back({ring.points[i], ring.points[std::min(i + 6, n) % n]});
                }
                else
                {
                    for (int step = 1; step <= n; ++step)
                    {
                        const int i = (firstFree + step) % n;
                        if (ring.free[i] || !ring.free[(i + n - 1) % n])
                            continue;
                        // a blocked run starts at i
                        int len = 0;
                        while (!ring.free[(i + len) % n])
                            ++len;
                        for (int from = 0; from < len; from += 6)
                        {
                            const int to = std::min(from + 6, len - 1);
                            ring.blockedEdges.push_back({ring.points[(i + from) % n], ring.points[(i + to) % n]});
                            if (to == len - 1)
                                break;
                        }
                    }
                }
                rings_.push_back(std::move(ring));
                sets_[s].rings.push_back(static_cast<int>(rings_.size()) - 1);
            }
            return sets_[s].rings[k - 1];
        }

        double ConcentricCircleSearch::potential(const Eigen::Vector2d &p, const Eigen::Vector2d &goal, int s,
                                                 int k) const
        {
            double phi = -settings_.kGoal / std::max((p - goal).norm(), 1e-9);
            // kept per thread: one evaluation per circle point the search looks at
            thread_local std::vector<Edge2> edges;
            edges.clear();
            if (!map_.obstacleEdges(p, settings_.potentialRange, edges))
            {
                // no polygons: the blocked runs of this circle and its neighbours stand for the obstacle edges
                const CcSet &set = sets_[s];
                // This ring and its neighbours only (both are sampled before a ring is linked): using every ring
                // would make a point's potential depend on how far the search had gone when it was evaluated.
                for (int j = std::max(1, k - 1); j <= std::min(k + 1, static_cast<int>(set.rings.size())); ++j)
                    for (const Edge2 &e : rings_[set.rings[j - 1]].blockedEdges)
                        if (segmentDistance(p, e.a, e.b) <= settings_.potentialRange)
                            edges.push_back(e);
            }
            for (const Edge2 &e : edges)
                phi += repulsion(p, e, settings_.kObstacle);
            return phi;
        }

        double ConcentricCircleSearch::potentialAt(const Eigen::Vector2d &p, const Eigen::Vector2d &goal) const
        {
            double phi = -settings_.kGoal / std::max((p - goal).norm(), 1e-9);
            std::vector<Edge2> edges;
            if (map_.obstacleEdges(p, settings_.potentialRange, edges))
                for (const Edge2 &e : edges)
                    phi += repulsion(p, e, settings_.kObstacle);
            return phi;
        }

        bool ConcentricCircleSearch::linkRing(int s, int k, const ompl::base::PlannerTerminationCondition &ptc)
        {
            if (sampleRing(s, k, ptc) < 0)
                return false;
            // The next ring is sampled first: its blocked runs enter this ring's potential (see potential()).
            if (k < sets_[s].maxRings && sampleRing(s, k + 1, ptc) < 0)
                return false;
            const int r = sets_[s].rings[k - 1];
            if (rings_[r].linked)
                return true;
            const CcSet set = sets_[s];
            const Eigen::Vector2d goal = image(nodes_[set.centreNode].p, nodes_[set.goalNode].p);
            const int n = static_cast<int>(rings_[r].points.size());
            // free arcs: maximal runs of free points (cyclic) that the map puts on one arc (an obstacle thinner than
            // the points' spacing splits an arc the map computed from the polygons); the minimum-potential point
            // of each is a candidate
            const std::vector<char> &freeMask = rings_[r].free;
            const std::vector<int> &arcOf = rings_[r].arc;
            auto sameArc = [&](int a, int b)
            {
                return freeMask[a] && freeMask[b] && (arcOf.empty() || arcOf[a] == arcOf[b]);
            };
            int firstBreak = -1;
            for (int i = 0; i < n && firstBreak < 0; ++i)
                if (!sameArc((i + n - 1) % n, i))
                    firstBreak = i;
            std::vector<std::vector<int>> arcs;
            if (firstBreak < 0)
            {
                arcs.emplace_back();
                for (int i = 0; i < n; ++i)
                    arcs.back().push_back(i);
            }
            else
            {
                for (int step = 0; step < n; ++step)
                {
                    const int i = (firstBreak + step) % n;
                    if (!freeMask[i])
                        continue;
                    if (!sameArc((i + n - 1) % n, i))
                        arcs.emplace_back();
                    arcs.back().push_back(i);
                }
            }
            // Candidates of each free arc, in order along it: the minimum-potential point of the arc (the paper);
            // with maxArcPoints > 0 a long arc is cut into pieces of at most that many points (an angle: finer
            // circles of a recursion get proportionally more points per piece), one minimum each; with arcEnds
            // the arc's two end points (next to the obstacles) as well. Neighbours along one arc are linked when
            // their chord is free, so chains can follow an arc around an obstacle.
            const int piecePoints = settings_.maxArcPoints > 0
                                        ? std::max(1, settings_.maxArcPoints * set.divisions / settings_.divisions)
                                        : n;
            auto candidate = [&](int i)
            {
                const int node = addNode(rings_[r].points[i], s, r);
                nodes_[node].potential = rings_[r].potential[i];
                rings_[r].candidates.push_back(node);
                return node;
            };
            std::vector<std::vector<int>> chains;
            for (const auto &arc : arcs)
            {
                if (ptc)
                    return false;
                const bool closed = static_cast<int>(arc.size()) == n;
                const bool ends = settings_.arcEnds && !closed && arc.size() >= 3;
                auto &phi = rings_[r].potential;
                std::vector<char> exact(arc.size(), 0);
                auto evaluate = [&](std::size_t j)
                {
                    if (!exact[j])
                        phi[arc[j]] = potential(rings_[r].points[arc[j]], goal, s, k);
                    exact[j] = 1;
                };
                // count pieces of equal size (rounded up), rather than full pieces plus a short remainder, so no piece
                // is a stub.
                const int count = (static_cast<int>(arc.size()) + piecePoints - 1) / piecePoints;
                const int size = (static_cast<int>(arc.size()) + count - 1) / count;
                std::vector<int> minima;
                std::vector<std::size_t> order;
                for (std::size_t from = 0; from < arc.size(); from += size)
                {
                    const std::size_t to = std::min(arc.size(), from + static_cast<std::size_t>(size));
                    // Branch and bound on equation (3): the repulsion terms are never negative (Kp >= 0), so the
                    // attraction -Kg / |PG| alone is a lower bound of a point's potential. Points are evaluated in the
                    // order of that bound, and once the bound exceeds the best potential found, no later point can
                    // be the minimum: its repulsion (the sight-line tests, most of the potential's cost on a J-map)
                    // is never computed, and it keeps the bound as its potential. The minimum, and which point it
                    // is (the first along the arc among equals), are exactly those of evaluating every point.
                    order.clear();
                    for (std::size_t j = from; j < to; ++j)
                    {
                        order.push_back(j);
                        if (!exact[j])
                            phi[arc[j]] = -settings_.kGoal / std::max((rings_[r].points[arc[j]] - goal).norm(), 1e-9);
                    }
                    const bool bound = settings_.kObstacle >= 0.;
                    std::stable_sort(order.begin(), order.end(),
                                     [&](std::size_t a, std::size_t b)
                                     {
                                         return phi[arc[a]] < phi[arc[b]];
                                     });
                    std::size_t best = to;
                    double bestPhi = INF;
                    for (const std::size_t j : order)
                    {
                        if (bound && phi[arc[j]] > bestPhi)
                            break;
                        evaluate(j);
                        if (phi[arc[j]] < bestPhi || (phi[arc[j]] == bestPhi && j < best))
                        {
                            bestPhi = phi[arc[j]];
                            best = j;
                        }
                    }
                    minima.push_back(arc[best]);
                }
                std::vector<int> chain;
                if (ends)
                {
                    // the end points are candidates whatever their potential; a node carries the exact value
                    evaluate(0);
                    evaluate(arc.size() - 1);
                    chain.push_back(candidate(arc.front()));
                }
                for (const int best : minima)
                {
                    if (ends && (best == arc.front() || best == arc.back()))
                        continue;  // already a candidate
                    chain.push_back(candidate(best));
                }
                if (ends)
                    chain.push_back(candidate(arc.back()));
                // A circle with no obstacle on it: its chain closes on itself.
                if (closed && chain.size() > 2)
                    chain.push_back(chain.front());
                chains.push_back(std::move(chain));
            }
            for (const auto &chain : chains)
                for (std::size_t j = 1; j < chain.size(); ++j)
                {
                    if (ptc)
                        return false;
                    proposeLink(chain[j - 1], chain[j]);
                }
            // links: to the centre (first circle) or to the candidates of the circle inside, and to the goal when
            // this circle is next to the goal's radius
            const std::vector<int> candidates = rings_[r].candidates;
            for (const int c : candidates)
            {
                if (ptc)
                    return false;
                if (k == 1)
                    proposeLink(set.centreNode, c);
                else
                    for (const int d : rings_[set.rings[k - 2]].candidates)
                    {
                        // with cut arcs, only candidates within two pieces' angle of each other are tried
                        if (settings_.maxArcPoints > 0)
                        {
                            const Eigen::Vector2d centre = rings_[r].centre;
                            const Eigen::Vector2d u = nodes_[c].p - centre, v = nodes_[d].p - centre;
                            const double angle = std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
                            // Two pieces' angle (at most a quarter turn each): a candidate far round the circle would
                            // make a long chord that mostly fails the visibility check, and trying every pair is
                            // quadratic in the candidates.
                            if (std::abs(angle) > 2. * 2. * M_PI * std::min(piecePoints, n / 4) / n + 1e-9)
                                continue;
                        }
                        proposeLink(d, c);
                    }
                // the paper's rule (the circle passes the goal), or the goal (another image of it on a wrapping
                // axis) lies within two spacings
                const Eigen::Vector2d pc = nodes_[c].p;
                if (std::abs(rings_[r].radius - set.goalRadius) <= set.spacing + 1e-12 ||
                    (image(pc, nodes_[set.goalNode].p) - pc).norm() <= 2. * set.spacing)
                    proposeLink(c, set.goalNode);
            }
            rings_[r].linked = true;
            return true;
        }

        std::vector<char> ConcentricCircleSearch::component(int from) const
        {
            std::vector<char> seen(nodes_.size(), 0);
            std::deque<int> open{from};
            seen[from] = 1;
            while (!open.empty())
            {
                const int v = open.front();
                open.pop_front();
                for (const auto &e : adjacency_[v])
                    if (!seen[e.to])
                    {
                        seen[e.to] = 1;
                        open.push_back(e.to);
                    }
            }
            return seen;
        }

        bool ConcentricCircleSearch::connected()
        {
            return lazyConnect();
        }

        bool ConcentricCircleSearch::checkedSearch(int source, int target, std::vector<double> &dist,
                                                   std::vector<int> &parent)
        {
            // Links are checked where they would shorten a node's distance, and a link that fails is removed there
            // and then, so one search settles every node on checked links only: its distances are those of the
            // graph without the links that fail. Checking the links of a finished tree or path instead (LazyPRM's
            // way) meant a search again after every pass with a failure: 39 Dijkstra and 53 A* runs per solve on
            // planar_2link, a quarter of the solve; a visibility check costs about as much as a relaxation here.
            dist.assign(nodes_.size(), INF);
            parent.assign(nodes_.size(), -1);
            const Eigen::Vector2d goal = target >= 0 ? nodes_[target].p : Eigen::Vector2d::Zero();
            // A* with the straight-line distance (to the nearest image on wrapping axes) as the heuristic: links are
            // straight segments of that length, so it never overestimates; Dijkstra (h = 0) for a whole tree.
            auto h = [&](int v)
            {
                return target >= 0 ? (image(goal, nodes_[v].p) - goal).norm() : 0.;
            };
            using Item = std::pair<double, int>;
            std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
            dist[source] = 0.;
            open.emplace(h(source), source);
            while (!open.empty())
            {
                const auto [f, v] = open.top();
                open.pop();
                if (v == target)
                    return true;
                // A stale queue entry (the node was reached more cheaply since it was pushed): lazy deletion instead
                // of a decrease-key heap.
                if (f > dist[v] + h(v) + 1e-12)
                    continue;
                auto &adjacent = adjacency_[v];
                for (std::size_t i = 0; i < adjacent.size();)
                {
                    const int u = adjacent[i].to;
                    const double d = dist[v] + adjacent[i].length;
                    if (d < dist[u])
                    {
                        // Out of time: stop before the next link check (in the projection modes a motion check,
                        // ring_spacing 0.005 ran 2.9 s past a 0.5 s limit). The search then reports no connection;
                        // a tree (target < 0) is left partial, which collectPaths() tolerates.
                        if (adjacent[i].unchecked && ptc_ != nullptr && (*ptc_)())
                            return false;
                        // A failed link leaves adjacency_[v] (order kept): the next link is now at i.
                        if (!validateArc(v, i))
                            continue;
                        dist[u] = d;
                        parent[u] = v;
                        open.emplace(d + h(u), u);
                    }
                    ++i;
                }
            }
            return target < 0;
        }

        bool ConcentricCircleSearch::collectPaths()
        {
            paths_.clear();
            if (!lazyConnect())
                return false;
            std::vector<double> distS, distG;
            std::vector<int> parS, parG;
            std::vector<std::pair<double, std::vector<int>>> found;
            auto fromStart = [&](int v)
            {
                std::vector<int> p;
                for (int u = v; u >= 0; u = parS[u])
                    p.push_back(u);
                std::reverse(p.begin(), p.end());
                return p;
            };
            auto toGoal = [&](int v)
            {
                std::vector<int> p;
                for (int u = v; u >= 0; u = parG[u])
                    p.push_back(u);
                return p;
            };
            // a new path (no node twice, not yet found) whose links all pass the visibility check
            auto add = [&](std::vector<int> p)
            {
                if (p.size() < 2 || p.front() != 0 || p.back() != 1)
                    return true;
                std::vector<int> sorted = p;
                std::sort(sorted.begin(), sorted.end());
                // Joining a start path and a goal path can visit a node twice (a loop): not a path the paper would
                // draw.
                if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
                    return true;
                for (const auto &f : found)
                    if (f.second == p)
                        return true;
                if (!validatePath(p))
                    return false;
                double len = 0.;
                for (std::size_t i = 1; i < p.size(); ++i)
                    len += (image(nodes_[p[i - 1]].p, nodes_[p[i]].p) - nodes_[p[i - 1]].p).norm();
                found.emplace_back(len, std::move(p));
                return true;
            };
            // Shortest-path trees from the start and from the goal, recomputed only when a link was removed since
            // (a failed check): every attempt below needs the current tree, and most attempts change nothing.
            unsigned long versionS = version_ - 1, versionG = version_ - 1;
            auto treeS = [&]
            {
                if (versionS != version_)
                    checkedSearch(0, -1, distS, parS);
                versionS = version_;
            };
            auto treeG = [&]
            {
                if (versionG != version_)
                    checkedSearch(1, -1, distG, parG);
                versionG = version_;
            };
            treeS();
            add(fromStart(1));
            // alternatives: the shortest path through each link of the goal and through each link of the start
            // (left and right of an obstacle, ...); a path whose link fails its check is looked for again
            std::vector<int> goalLinks, startLinks;
            for (const auto &e : adjacency_[1])
                goalLinks.push_back(e.to);
            for (const auto &e : adjacency_[0])
                startLinks.push_back(e.to);
            // Each attempt re-runs Dijkstra after a failed check removed a link; 8 bounds the work per goal link.
            for (const int v : goalLinks)
                for (int attempt = 0; attempt < 8 && static_cast<int>(found.size()) < settings_.maxPaths; ++attempt)
                {
                    treeS();
                    if (distS[v] == INF || std::none_of(adjacency_[v].begin(), adjacency_[v].end(),
                                                        [](const Arc &e)
                                                        {
                                                            return e.to == 1;
                                                        }))
                        break;
                    auto p = fromStart(v);
                    p.push_back(1);
                    if (add(p))
                        break;
                }
            for (const int u : startLinks)
                for (int attempt = 0; attempt < 8 && static_cast<int>(found.size()) < settings_.maxPaths; ++attempt)
                {
                    treeG();
                    if (distG[u] == INF || std::none_of(adjacency_[u].begin(), adjacency_[u].end(),
                                                        [](const Arc &e)
                                                        {
                                                            return e.to == 0;
                                                        }))
                        break;
                    auto p = toGoal(u);
                    p.insert(p.begin(), 0);
                    if (add(p))
                        break;
                }
            std::stable_sort(found.begin(), found.end(),
                             [](const auto &a, const auto &b)
                             {
                                 return a.first < b.first;
                             });
            for (std::size_t i = 0; i < found.size() && static_cast<int>(i) < settings_.maxPaths; ++i)
                paths_.push_back(found[i].second);
            return !paths_.empty();
        }

        bool ConcentricCircleSearch::run(const Eigen::Vector2d &start, const Eigen::Vector2d &goal,
                                         const ompl::base::PlannerTerminationCondition &ptc)
        {
            ptc_ = &ptc;
            const bool found = runCircles(start, goal, ptc);
            ptc_ = nullptr;
            return found;
        }

        bool ConcentricCircleSearch::runCircles(const Eigen::Vector2d &start, const Eigen::Vector2d &goal,
                                                const ompl::base::PlannerTerminationCondition &ptc)
        {
            nodes_.clear();
            rings_.clear();
            sets_.clear();
            adjacency_.clear();
            paths_.clear();
            tried_.clear();
            recursions_ = 0;
            addNode(start, -1, -1);
            addNode(image(start, goal), -1, -1);
            if (ptc || !map_.isFree(nodes_[0].p) || !map_.isFree(nodes_[1].p))
                return false;
            proposeLink(0, 1);  // the straight segment, when free, is one of the paths
            // 1. the paper's circles: from the start until the goal is reached
            const int main = addSet(0, 1, settings_.ringSpacing, settings_.divisions, settings_.outerRings);
            for (int k = 1; k <= sets_[main].goalRings + 1 && k <= sets_[main].maxRings; ++k)
                if (!linkRing(main, k, ptc))
                    return collectPaths();
            // 2. more circles around the start until they cover the map
            for (int k = sets_[main].goalRings + 2; !connected() && k <= sets_[main].maxRings; ++k)
                if (!linkRing(main, k, ptc))
                    return collectPaths();
            // 3. recursion: the closest pair of unlinked nodes (one reached from the start, one reaching the goal)
            //    becomes a new start and goal, with finer circles
            std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> triedPositions;
            while (!connected() && recursions_ < settings_.maxRecursions && !ptc)
            {
                const std::vector<char> fromS = component(0), fromG = component(1);
                int bestA = -1, bestB = -1;
                double bestD = INF;
                // a pair next to one already tried (both ends within two spacings) would repeat it: skipped
                auto nearTried = [&](const Eigen::Vector2d &pa, const Eigen::Vector2d &pb)
                {
                    const double near = 2. * settings_.ringSpacing;
                    for (const auto &t : triedPositions)
                        if (((t.first - pa).norm() < near && (t.second - pb).norm() < near))
                            return true;
                    return false;
                };
                for (std::size_t a = 0; a < nodes_.size(); ++a)
                    if (fromS[a])
                        for (std::size_t b = 0; b < nodes_.size(); ++b)
                            if (fromG[b] && !tried_.count({static_cast<int>(a), static_cast<int>(b)}) &&
                                !nearTried(nodes_[a].p, nodes_[b].p))
                            {
                                const double d = (image(nodes_[a].p, nodes_[b].p) - nodes_[a].p).norm();
                                if (d < bestD)
                                {
                                    bestD = d;
                                    bestA = static_cast<int>(a);
                                    bestB = static_cast<int>(b);
                                }
                            }
                if (bestA < 0)
                    break;
                tried_.insert({bestA, bestB});
                triedPositions.emplace_back(nodes_[bestA].p, nodes_[bestB].p);
                ++recursions_;
                if (tryLink(bestA, bestB))
                    continue;  // the new start sees the new goal
                // finer circles as the recursions go on (1/2, 1/4, 1/8 of the spacing, as many more points), and
                // centred alternately on the goal's side and on the start's side: a goal at the end of a narrow
                // channel is found from its own circles, whose small radii see the channel's way out
                // The level grows every second recursion (one from each side) and stops at 1/8: finer circles cost as
                // many more points per ring as they gain in resolution.
                const int level = std::min((recursions_ + 1) / 2, 3);
                const double spacing = settings_.ringSpacing / (1 << level);
                const int divisions = settings_.divisions * (1 << level);
                const bool fromGoalSide = recursions_ % 2 == 1;
                const int s = fromGoalSide ? addSet(bestB, bestA, spacing, divisions, false)
                                           : addSet(bestA, bestB, spacing, divisions, false);
                for (int k = 1; k <= sets_[s].goalRings + 2 && k <= sets_[s].maxRings; ++k)
                    if (!linkRing(s, k, ptc))
                        return collectPaths();
            }
            return collectPaths();
        }

        std::vector<Eigen::Vector2d> ConcentricCircleSearch::pathPoints(std::size_t i) const
        {
            std::vector<Eigen::Vector2d> out;
            const auto &path = paths_.at(i);
            for (std::size_t j = 0; j < path.size(); ++j)
            {
                if (j == 0)
                {
                    out.push_back(nodes_[path[0]].p);
                    continue;
                }
                const Eigen::Vector2d from = out.back();
                const Eigen::Vector2d to = image(from, nodes_[path[j]].p);
                for (const auto &b : map_.breakpoints(from, to))
                    out.push_back(b);
                out.push_back(to);
            }
            return out;
        }

        double ConcentricCircleSearch::pathLength(std::size_t i) const
        {
            const auto pts = pathPoints(i);
            double len = 0.;
            for (std::size_t j = 1; j < pts.size(); ++j)
                len += (pts[j] - pts[j - 1]).norm();
            return len;
        }
    }  // namespace planners
}  // namespace michi
