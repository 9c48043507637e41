#ifndef MICHI_PLANNERS_DUAL_ROADMAP_ROADMAP_SEARCH_
#define MICHI_PLANNERS_DUAL_ROADMAP_ROADMAP_SEARCH_

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief An undirected graph on flat arrays, made for DualRoadmap's repeated A* searches: per vertex one
            contiguous vector of arcs (neighbour, edge id, length), so the search's inner loop reads neither an edge
            record nor a state to know an arc's length; vertex and edge records (the template parameters) live in
            vectors indexed by id. Vertices and edges are only added; clear() forgets everything. (Replaces a
            Boost.Graph adjacency_list, whose undirected edge properties sit in a linked list: a cache miss per
            relaxed edge in the profile.) */
        template <typename VertexRecord, typename EdgeRecord>
        class FlatRoadmap
        {
        public:
            using Vertex = std::size_t;
            using Edge = std::size_t;
            struct Arc
            {
                Vertex to;
                Edge edge;
                double length;
            };

            Vertex addVertex()
            {
                vertices_.emplace_back();
                arcs_.emplace_back();
                return vertices_.size() - 1;
            }
            /** \brief The edge a - b of \e length, added without looking for an existing one (findEdge()). */
            Edge addEdge(Vertex a, Vertex b, double length)
            {
                edges_.emplace_back();
                ends_.emplace_back(a, b);
                const Edge e = edges_.size() - 1;
                arcs_[a].push_back(Arc{b, e, length});
                arcs_[b].push_back(Arc{a, e, length});
                return e;
            }
            /** \brief The edge a - b (second: it exists); scans the shorter arc list. */
            std::pair<Edge, bool> findEdge(Vertex a, Vertex b) const
            {
                const bool fromA = arcs_[a].size() <= arcs_[b].size();
                const Vertex other = fromA ? b : a;
                for (const Arc &arc : arcs_[fromA ? a : b])
                    if (arc.to == other)
                        return {arc.edge, true};
                return {0, false};
            }
            std::size_t vertexCount() const
            {
                return vertices_.size();
            }
            std::size_t edgeCount() const
            {
                return edges_.size();
            }
            VertexRecord &operator[](Vertex v)
            {
                return vertices_[v];
            }
            const VertexRecord &operator[](Vertex v) const
            {
                return vertices_[v];
            }
            EdgeRecord &edge(Edge e)
            {
                return edges_[e];
            }
            const EdgeRecord &edge(Edge e) const
            {
                return edges_[e];
            }
            /** \brief The two ends of \e e, in the order it was added. */
            const std::pair<Vertex, Vertex> &ends(Edge e) const
            {
                return ends_[e];
            }
            const std::vector<Arc> &arcs(Vertex v) const
            {
                return arcs_[v];
            }
            void clear()
            {
                vertices_.clear();
                edges_.clear();
                ends_.clear();
                arcs_.clear();
            }

        private:
            std::vector<VertexRecord> vertices_;
            std::vector<EdgeRecord> edges_;
            std::vector<std::pair<Vertex, Vertex>> ends_;
            std::vector<std::vector<Arc>> arcs_;
        };

        /** \brief A* whose buffers are kept from one search to the next: no allocation and no O(V) initialisation
            per search (a vertex's entries count only when stamped by the current search), so a search costs what
            it explores. Ties in f are broken by the smaller vertex id: the same graph gives the same path. */
        class RoadmapAStar
        {
        public:
            /** \brief Shortest path in \e graph (a FlatRoadmap) from \e start to the first vertex with
                isGoal(v), written to \e path (start first); false and \e path empty when none is reachable.
                cost(u, arc) is the arc's cost (>= its heuristic drop: h must be admissible and consistent for the
                path to be shortest), passable(arc) whether the search may take it (asked only when the arc would
                improve its end's cost), h(v) the heuristic. */
            template <typename Graph, typename IsGoal, typename Cost, typename Passable, typename Heuristic>
            bool search(const Graph &graph, std::size_t start, IsGoal isGoal, Cost cost, Passable passable, Heuristic h,
                        std::vector<std::size_t> &path)
            {
                path.clear();
                const std::size_t n = graph.vertexCount();
                if (stamp_.size() < n)
                {
                    stamp_.resize(n, 0);
                    closed_.resize(n, 0);
                    g_.resize(n, 0.);
                    pred_.resize(n, 0);
                }
                ++search_;
                expanded_ = 0;
                open_.clear();
                const auto later = std::greater<Item>();  // a min-heap on (f, vertex)
                stamp_[start] = search_;
                g_[start] = 0.;
                pred_[start] = start;
                open_.emplace_back(h(start), start);
                while (!open_.empty())
                {
                    std::pop_heap(open_.begin(), open_.end(), later);
                    const std::size_t u = open_.back().second;
                    open_.pop_back();
                    if (closed_[u] == search_)
                        continue;
                    closed_[u] = search_;
                    ++expanded_;
                    if (isGoal(u))
                    {
                        for (std::size_t v = u; v != start; v = pred_[v])
                            path.push_back(v);
                        path.push_back(start);
                        std::reverse(path.begin(), path.end());
                        return true;
                    }
                    const double gu = g_[u];
                    for (const auto &arc : graph.arcs(u))
                    {
                        const std::size_t w = arc.to;
                        if (closed_[w] == search_)
                            continue;
                        const double g = gu + cost(u, arc);
                        if (stamp_[w] == search_ && g >= g_[w])
                            continue;
                        if (!passable(arc))
                            continue;
                        stamp_[w] = search_;
                        g_[w] = g;
                        pred_[w] = u;
                        open_.emplace_back(g + h(w), w);
                        std::push_heap(open_.begin(), open_.end(), later);
                    }
                }
                return false;
            }
            /** \brief Vertices the last search expanded (closed), the goal included: its work. */
            std::size_t expanded() const
            {
                return expanded_;
            }
            /** \brief Forget the buffers (memory only: results do not depend on them). */
            void clear()
            {
                stamp_.clear();
                closed_.clear();
                g_.clear();
                pred_.clear();
                open_.clear();
                search_ = 0;
            }

        private:
            using Item = std::pair<double, std::size_t>;
            std::vector<std::uint64_t> stamp_, closed_;
            std::vector<double> g_;
            std::vector<std::size_t> pred_;
            std::vector<Item> open_;
            std::uint64_t search_{0};
            std::size_t expanded_{0};
        };
    }  // namespace planners
}  // namespace michi

#endif
