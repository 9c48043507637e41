// FlatRoadmap and RoadmapAStar (DualRoadmap's graph and search) against a plain Dijkstra written here, on random
// planar roadmaps: the same shortest-path costs, with and without an admissible heuristic, with impassable edges and
// vertices, and with buffers reused over many searches on a growing graph; with an inflated heuristic (weighted A*),
// a path within the weight of the shortest after fewer expansions.
#include <michi/planners/dual_roadmap/RoadmapSearch.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <queue>
#include <random>
#include <vector>

namespace
{
    struct Point
    {
        double x{0.}, y{0.};
        bool blocked{false};
    };
    struct Link
    {
        bool blocked{false};
        double factor{1.};  // cost = length * factor (>= 1: the Euclidean heuristic stays admissible)
    };
    using Roadmap = michi::planners::FlatRoadmap<Point, Link>;

    double dist(const Point &a, const Point &b)
    {
        return std::hypot(a.x - b.x, a.y - b.y);
    }

    // A random geometric graph: each vertex linked to the vertices within radius (once per pair).
    Roadmap randomRoadmap(std::mt19937 &rng, std::size_t n, double radius, double blockedFraction)
    {
        std::uniform_real_distribution<double> u(0., 1.);
        Roadmap g;
        for (std::size_t i = 0; i < n; ++i)
        {
            const auto v = g.addVertex();
            g[v].x = u(rng);
            g[v].y = u(rng);
            g[v].blocked = i > 1 && u(rng) < blockedFraction;  // 0 and 1 (start, goal) stay passable
        }
        for (std::size_t a = 0; a < n; ++a)
            for (std::size_t b = a + 1; b < n; ++b)
                if (dist(g[a], g[b]) < radius)
                {
                    const auto e = g.addEdge(a, b, dist(g[a], g[b]));
                    g.edge(e).blocked = u(rng) < blockedFraction;
                    g.edge(e).factor = u(rng) < 0.3 ? 1.5 : 1.;
                }
        return g;
    }

    // Reference: Dijkstra over the ends and records, not the arc lists.
    double dijkstra(const Roadmap &g, std::size_t start, std::size_t goal)
    {
        const double inf = std::numeric_limits<double>::infinity();
        std::vector<std::vector<std::pair<std::size_t, double>>> adj(g.vertexCount());
        for (std::size_t e = 0; e < g.edgeCount(); ++e)
        {
            const auto [a, b] = g.ends(e);
            if (g.edge(e).blocked || g[a].blocked || g[b].blocked)
                continue;
            const double c = dist(g[a], g[b]) * g.edge(e).factor;
            adj[a].emplace_back(b, c);
            adj[b].emplace_back(a, c);
        }
        std::vector<double> d(g.vertexCount(), inf);
        using Item = std::pair<double, std::size_t>;
        std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
        d[start] = 0.;
        open.emplace(0., start);
        while (!open.empty())
        {
            const auto [du, u] = open.top();
            open.pop();
            if (du > d[u])
                continue;
            for (const auto &[w, c] : adj[u])
                if (du + c < d[w])
                {
                    d[w] = du + c;
                    open.emplace(d[w], w);
                }
        }
        return d[goal];
    }

    // Cost of \e path in \e g, checking that it is a chain of existing, passable edges.
    double pathCost(const Roadmap &g, const std::vector<std::size_t> &path)
    {
        double c = 0.;
        for (std::size_t i = 0; i + 1 < path.size(); ++i)
        {
            const auto e = g.findEdge(path[i], path[i + 1]);
            EXPECT_TRUE(e.second);
            if (!e.second)
                return std::numeric_limits<double>::quiet_NaN();
            EXPECT_FALSE(g.edge(e.first).blocked);
            EXPECT_FALSE(g[path[i + 1]].blocked);
            c += dist(g[path[i]], g[path[i + 1]]) * g.edge(e.first).factor;
        }
        return c;
    }

    double searchCost(michi::planners::RoadmapAStar &astar, const Roadmap &g, std::size_t start, std::size_t goal,
                      bool heuristic, std::vector<std::size_t> &path)
    {
        const bool found = astar.search(
            g, start,
            [&](std::size_t v)
            {
                return v == goal;
            },
            [&](std::size_t, const Roadmap::Arc &arc)
            {
                return arc.length * g.edge(arc.edge).factor;
            },
            [&](const Roadmap::Arc &arc)
            {
                return !g.edge(arc.edge).blocked && !g[arc.to].blocked;
            },
            [&](std::size_t v)
            {
                return heuristic ? dist(g[v], g[goal]) : 0.;
            },
            path);
        if (!found)
        {
            EXPECT_TRUE(path.empty());
            return std::numeric_limits<double>::infinity();
        }
        EXPECT_EQ(path.front(), start);
        EXPECT_EQ(path.back(), goal);
        return pathCost(g, path);
    }
}  // namespace

TEST(RoadmapSearch, FlatRoadmapKeepsEndsArcsAndFindsEdges)
{
    Roadmap g;
    for (int i = 0; i < 4; ++i)
        g.addVertex();
    const auto e01 = g.addEdge(0, 1, 1.);
    const auto e12 = g.addEdge(1, 2, 2.);
    EXPECT_EQ(g.vertexCount(), 4u);
    EXPECT_EQ(g.edgeCount(), 2u);
    EXPECT_EQ(g.findEdge(1, 0).first, e01);
    EXPECT_EQ(g.findEdge(2, 1).first, e12);
    EXPECT_TRUE(g.findEdge(0, 1).second);
    EXPECT_FALSE(g.findEdge(0, 2).second);
    EXPECT_FALSE(g.findEdge(3, 0).second);
    EXPECT_EQ(g.ends(e12), std::make_pair(std::size_t(1), std::size_t(2)));
    ASSERT_EQ(g.arcs(1).size(), 2u);
    EXPECT_EQ(g.arcs(1)[1].to, 2u);
    EXPECT_DOUBLE_EQ(g.arcs(1)[1].length, 2.);
    g.clear();
    EXPECT_EQ(g.vertexCount(), 0u);
    EXPECT_EQ(g.edgeCount(), 0u);
}

TEST(RoadmapSearch, AStarAgreesWithDijkstraOnRandomRoadmaps)
{
    std::mt19937 rng(7);
    michi::planners::RoadmapAStar astar;  // one search object for all graphs: reused buffers must not matter
    std::vector<std::size_t> path;
    int reachable = 0, unreachable = 0;
    for (int round = 0; round < 40; ++round)
    {
        const std::size_t n = 20 + static_cast<std::size_t>(round) * 5;
        const Roadmap g = randomRoadmap(rng, n, round % 2 ? 0.15 : 0.3, round % 2 ? 0.4 : 0.);
        const double expected = dijkstra(g, 0, 1);
        for (bool heuristic : {false, true})
        {
            const double got = searchCost(astar, g, 0, 1, heuristic, path);
            if (std::isinf(expected))
                EXPECT_TRUE(std::isinf(got)) << "round " << round;
            else
                EXPECT_NEAR(got, expected, 1e-9) << "round " << round << " heuristic " << heuristic;
        }
        (std::isinf(expected) ? unreachable : reachable)++;
    }
    EXPECT_GT(reachable, 10);  // the test covers both outcomes
    EXPECT_GT(unreachable, 0);
}

TEST(RoadmapSearch, RepeatedSearchesOnAGrowingRoadmapWithRefutedEdges)
{
    // DualRoadmap's pattern: search, refute an edge of the path, search again; add vertices, search again.
    std::mt19937 rng(3);
    Roadmap g = randomRoadmap(rng, 60, 0.25, 0.);
    michi::planners::RoadmapAStar astar;
    std::vector<std::size_t> path;
    std::uniform_real_distribution<double> u(0., 1.);
    for (int step = 0; step < 60; ++step)
    {
        const double expected = dijkstra(g, 0, 1);
        const double got = searchCost(astar, g, 0, 1, true, path);
        if (std::isinf(expected))
            EXPECT_TRUE(std::isinf(got));
        else
            EXPECT_NEAR(got, expected, 1e-9) << "step " << step;
        if (path.size() >= 2)
            g.edge(g.findEdge(path[path.size() / 2 - 1], path[path.size() / 2]).first).blocked = true;
        else
        {
            // no path: more vertices, linked to their neighbours
            for (int i = 0; i < 10; ++i)
            {
                const auto v = g.addVertex();
                g[v].x = u(rng);
                g[v].y = u(rng);
                for (std::size_t w = 0; w < v; ++w)
                    if (dist(g[v], g[w]) < 0.25)
                        g.addEdge(v, w, dist(g[v], g[w]));
            }
        }
    }
}

TEST(RoadmapSearch, WeightedHeuristicBoundsTheCostAndExpandsFewerVertices)
{
    // DualRoadmap's search_weight: the heuristic times w >= 1 (inconsistent, no vertex expanded twice) gives a path
    // costing at most w times the shortest, after fewer expansions: the point of the setting on large roadmaps.
    std::mt19937 rng(11);
    michi::planners::RoadmapAStar astar;
    std::vector<std::size_t> path;
    std::size_t plain = 0, weighted = 0;
    int compared = 0;
    for (int round = 0; round < 20; ++round)
    {
        const Roadmap g = randomRoadmap(rng, 400, 0.09, 0.);
        const double best = dijkstra(g, 0, 1);
        if (std::isinf(best))
            continue;
        for (const double w : {1., 2.})
        {
            ASSERT_TRUE(astar.search(
                g, 0,
                [](std::size_t v)
                {
                    return v == 1;
                },
                [&](std::size_t, const Roadmap::Arc &arc)
                {
                    return arc.length * g.edge(arc.edge).factor;
                },
                [](const Roadmap::Arc &)
                {
                    return true;
                },
                [&](std::size_t v)
                {
                    return w * dist(g[v], g[1]);
                },
                path));
            const double cost = pathCost(g, path);
            if (w == 1.)
                EXPECT_NEAR(cost, best, 1e-9) << "round " << round;
            EXPECT_LE(cost, w * best + 1e-9) << "round " << round << " weight " << w;
            EXPECT_GE(cost, best - 1e-9);
            (w == 1. ? plain : weighted) += astar.expanded();
        }
        ++compared;
    }
    EXPECT_GT(compared, 10);
    RecordProperty("expanded_plain", std::to_string(plain));
    RecordProperty("expanded_weight_2", std::to_string(weighted));
    EXPECT_LT(2 * weighted, plain) << "weight 2 expanded " << weighted << " vertices, weight 1 " << plain;
}
