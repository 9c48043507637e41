#include <michi/planners/dual_roadmap/DualRoadmap.h>

#include "DominantDirections.h"
#include "TaskLevel.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/tools/config/SelfConfig.h>
#include <ompl/util/Exception.h>

#include <algorithm>
#include <limits>
#include <map>
#include <numeric>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace planners
    {
        DualRoadmap::DualRoadmap(const ob::SpaceInformationPtr &si) : ob::Planner(si, "DualRoadmap")
        {
            specs_.approximateSolutions = false;
            specs_.optimizingPaths = false;
            specs_.multithreaded = false;
            // Goal states become roadmap vertices, so the goal must be able to give states (as for PRM and LazyPRM).
            specs_.recognizedGoal = ob::GOAL_SAMPLEABLE_REGION;

            declareParam<bool>("use_learning", this, &DualRoadmap::setUseLearning, &DualRoadmap::getUseLearning, "0,1");
            declareParam<unsigned int>("seed_edges", this, &DualRoadmap::setSeedEdges, &DualRoadmap::getSeedEdges,
                                       "0:10:2000");
            declareParam<unsigned int>("max_nearest_neighbors", this, &DualRoadmap::setMaxNearestNeighbors,
                                       &DualRoadmap::getMaxNearestNeighbors, "1:1:50");
            declareParam<double>("range_fraction", this, &DualRoadmap::setRangeFraction, &DualRoadmap::getRangeFraction,
                                 "0.01:0.01:1.");
            declareParam<unsigned int>("batch_size", this, &DualRoadmap::setBatchSize, &DualRoadmap::getBatchSize,
                                       "1:1:500");
            declareParam<bool>("smooth", this, &DualRoadmap::setSmooth, &DualRoadmap::getSmooth, "0,1");
            declareParam<bool>("lazy_seeding", this, &DualRoadmap::setLazySeeding, &DualRoadmap::getLazySeeding, "0,1");
            declareParam<unsigned int>("max_learning_edges", this, &DualRoadmap::setMaxLearningEdges,
                                       &DualRoadmap::getMaxLearningEdges, "0:1000:1000000");
            declareParam<double>("unknown_edge_penalty", this, &DualRoadmap::setUnknownEdgePenalty,
                                 &DualRoadmap::getUnknownEdgePenalty, "1.:0.5:10.");
            declareParam<double>("refuted_edge_penalty", this, &DualRoadmap::setRefutedEdgePenalty,
                                 &DualRoadmap::getRefutedEdgePenalty, "1.:0.5:20.");
            declareParam<unsigned int>("max_working_vertices", this, &DualRoadmap::setMaxWorkingVertices,
                                       &DualRoadmap::getMaxWorkingVertices, "10:10:1000000");
            declareParam<bool>("restart_when_full", this, &DualRoadmap::setRestartWhenFull,
                               &DualRoadmap::getRestartWhenFull, "0,1");
            declareParam<double>("search_weight", this, &DualRoadmap::setSearchWeight, &DualRoadmap::getSearchWeight,
                                 "1.:0.5:10.");
            declareParam<unsigned int>("edge_probes", this, &DualRoadmap::setEdgeProbes, &DualRoadmap::getEdgeProbes,
                                       "0:1:" + std::to_string(MAX_EDGE_PROBES));
            declareParam<unsigned int>("recheck_depth", this, &DualRoadmap::setRecheckDepth,
                                       &DualRoadmap::getRecheckDepth, "0:1:10");
            declareParam<unsigned int>("dominant_dofs", this, &DualRoadmap::setDominantDofs,
                                       &DualRoadmap::getDominantDofs, "0:1:10");
            declareParam<bool>("task_level", this, &DualRoadmap::setTaskLevel, &DualRoadmap::getTaskLevel, "0,1");
            declareParam<double>("task_cell", this, &DualRoadmap::setTaskCell, &DualRoadmap::getTaskCell,
                                 "0.01:0.01:0.5");

            // Benchmark reads progress properties from its own thread while solve() runs: hence the atomic copy of the
            // count.
            addPlannerProgressProperty("learning edges INTEGER",
                                       [this]
                                       {
                                           return std::to_string(learningEdgeCountAtomic_.load());
                                       });
        }

        DualRoadmap::~DualRoadmap()
        {
            freeWorking();
            clearLearningRoadmap();
            if (probe_ != nullptr)
                si_->freeState(probe_);
            for (auto *st : part_)
                if (st != nullptr)
                    si_->freeState(st);
        }

        void DualRoadmap::setup()
        {
            Planner::setup();
            if (!nn_)
            {
                nn_.reset(ompl::tools::SelfConfig::getDefaultNearestNeighbors<Vertex>(this));
                nn_->setDistanceFunction(
                    [this](const Vertex a, const Vertex b)
                    {
                        return si_->distance(graph_[a].state, graph_[b].state);
                    });
            }
            if (!sampler_)
                sampler_ = si_->allocStateSampler();
            if (probe_ == nullptr)
                probe_ = si_->allocState();
            if (taskLevel_ && !taskMap_)
                OMPL_WARN("%s: task_level is on but no task map is installed (setTaskMap): samples stay uniform",
                          getName().c_str());
            for (auto &st : part_)
                if (st == nullptr)
                    st = si_->allocState();
        }

        void DualRoadmap::freeWorking()
        {
            for (Vertex v = 0; v < graph_.vertexCount(); ++v)
                if (graph_[v].state != nullptr)
                    si_->freeState(graph_[v].state);
            graph_.clear();
            if (nn_)
                nn_->clear();
            startVertices_.clear();
            goalVertices_.clear();
            queryHistory_.clear();
            learnedWorkingEdges_ = 0;
            vertexHand_.clear();
            // vertex ids are used again from 0: no cached heuristic may be taken for a new vertex
            heuristicGoals_.clear();
            ++goalSet_;
        }

        void DualRoadmap::clear()
        {
            Planner::clear();
            freeWorking();
            changed_ = true;
            haveCount_ = false;
            seeded_ = 0;
            refill_ = false;
        }

        void DualRoadmap::clearLearningRoadmap()
        {
            // The learning roadmap outlives clear() on purpose (paper 002: it accumulates experience over scenes, as
            // OMPL's experience planners keep their database); only this call or loadLearningRoadmap() forgets it.
            for (auto *s : learnStates_)
                si_->freeState(s);
            learnStates_.clear();
            learnEdges_.clear();
            learnEdgeSet_.clear();
            learningEdgeCountAtomic_ = 0;
            // Working vertices that pointed into the forgotten learning roadmap must not be learned under their old
            // ids.
            for (Vertex v = 0; v < graph_.vertexCount(); ++v)
                graph_[v].learnId = -1;
        }

        void DualRoadmap::notifySceneChanged()
        {
            notifySceneChanged(ChangeRegion());
        }

        void DualRoadmap::notifySceneChanged(ChangeRegion affects)
        {
            std::lock_guard<std::mutex> lock(regionMutex_);
            // two changes before one solve(): their union is the change (either may affect a motion)
            if (haveRegion_ && pendingRegion_ && affects)
            {
                ChangeRegion first = std::move(pendingRegion_);
                pendingRegion_ = [first, affects](const ob::State *a, const ob::State *b)
                {
                    return first(a, b) || affects(a, b);
                };
            }
            else if (!haveRegion_ || !affects)
                pendingRegion_ = std::move(affects);
            haveRegion_ = true;
            changed_ = true;
        }

        bool DualRoadmap::unaffectedSince(std::uint64_t since, const ob::State *a, const ob::State *b) const
        {
            // history_.back() led to epoch_, history_[i] to epoch_ - (size - 1 - i)
            if (since == 0 || since >= epoch_ || epoch_ - since > history_.size())
                return since == epoch_;
            for (std::size_t i = history_.size() - (epoch_ - since); i < history_.size(); ++i)
                if (!history_[i] || history_[i](a, b))
                    return false;
            return true;
        }

        bool DualRoadmap::renewProof(std::uint64_t &stamp, const ob::State *a, const ob::State *b) const
        {
            // carried over when no change since touched it; else forgotten, so it is not asked again
            stamp = unaffectedSince(stamp, a, b) ? epoch_ : 0;
            return stamp == epoch_;
        }

        void DualRoadmap::setSceneChangeCounter(std::function<std::uint64_t()> counter)
        {
            counter_ = std::move(counter);
            haveCount_ = false;
        }

        bool DualRoadmap::sceneChanged()
        {
            // exchange: a notifySceneChanged() from another thread between the read and the reset is not lost.
            bool changed = changed_.exchange(false);
            if (counter_)
            {
                const std::uint64_t count = counter_();
                if (!haveCount_ || count != lastCount_)
                    changed = true;
                lastCount_ = count;
                haveCount_ = true;
            }
            else
                changed = true;  // nobody tells us: trust nothing from an earlier solve()
            return changed;
        }

        std::size_t DualRoadmap::workingVertexCount() const
        {
            return graph_.vertexCount();
        }

        std::size_t DualRoadmap::workingEdgeCount() const
        {
            return graph_.edgeCount();
        }

        DualRoadmap::Vertex DualRoadmap::addWorkingVertex(ob::State *state, long learnId)
        {
            const Vertex v = graph_.addVertex();
            graph_[v].state = state;
            graph_[v].learnId = learnId;
            nn_->add(v);
            return v;
        }

        void DualRoadmap::connectLazily(Vertex v)
        {
            // Edges are only added, not checked (LazyPRM's scheme): validatePath() checks the ones a candidate path
            // uses, so the k-nearest query stays cheap. The range bound keeps long edges, which are rarely valid in
            // clutter, out of the graph.
            const double range = rangeFraction_ * si_->getMaximumExtent();
            std::vector<Vertex> neighbours;
            // OMPL's GNAT breaks ties in distance by the address of its element (its queue holds pairs of distance and
            // pointer), so which of several equally near vertices it returned, and in what order, followed where the
            // process had allocated memory: runs of one seed differed between builds and under other malloc settings
            // (docs/dual-roadmap.md). The neighbours are ordered by distance and vertex id instead, and asked for
            // again, more of them, while a tie spans the k-th distance (copies of one state tie in numbers).
            thread_local std::vector<std::pair<double, Vertex>> near;
            for (std::size_t ask = k_ + 5;; ask *= 2)
            {
                nn_->nearestK(v, ask, neighbours);
                near.clear();
                for (Vertex n : neighbours)
                    if (n != v)  // v is already in nn_ and is its own nearest neighbour
                        near.emplace_back(si_->distance(graph_[v].state, graph_[n].state), n);
                std::sort(near.begin(), near.end());
                // every vertex as near as the k-th is among those returned: all were, or a farther one was
                if (k_ == 0 || neighbours.size() < ask || near.size() <= k_ || near.back().first > near[k_ - 1].first)
                    break;
            }
            if (near.size() > k_)
                near.resize(k_);
            for (const auto &[d, n] : near)
            {
                if (d > range)
                    continue;
                addEdgeOnce(v, n);  // validity unknown (epochs 0) until a candidate path uses it
            }
        }

        std::pair<DualRoadmap::Edge, bool> DualRoadmap::addEdgeOnce(Vertex a, Vertex b)
        {
            // the flat graph allows parallel edges, so uniqueness is kept here; degrees are about 2k, so the lookup is
            // short
            const auto e = graph_.findEdge(a, b);
            if (e.second)
                return {e.first, false};
            return {graph_.addEdge(a, b, si_->distance(graph_[a].state, graph_[b].state)), true};
        }

        DualRoadmap::Vertex DualRoadmap::addQueryVertex(const ob::State *state)
        {
            // The same goal (or start) query after query is one vertex, not a pile of duplicates that would crowd every
            // k-nearest query around it.
            for (Vertex n : queryHistory_)
                if (si_->distance(graph_[n].state, state) <= 0.)
                {
                    graph_[n].validIn = epoch_;  // the planner's input states are valid
                    graph_[n].invalidIn = 0;
                    return n;
                }
            const Vertex v = addWorkingVertex(si_->cloneState(state), -1);
            graph_[v].validIn = epoch_;
            return v;
        }

        DualRoadmap::Vertex DualRoadmap::rememberQueryVertex(Vertex v)
        {
            // most recently used last: a goal asked query after query is never pushed out by the starts
            const auto it = std::find(queryHistory_.begin(), queryHistory_.end(), v);
            if (it != queryHistory_.end())
                queryHistory_.erase(it);
            queryHistory_.push_back(v);
            if (queryHistory_.size() > 8)
                queryHistory_.erase(queryHistory_.begin());
            return v;
        }

        void DualRoadmap::seedWorking(const std::vector<const ob::State *> &near,
                                      const ob::PlannerTerminationCondition &ptc)
        {
            seeded_ = 0;
            if (!useLearning_ || learnEdges_.empty() || seedEdges_ == 0)
                return;
            // Paper 002, Fig. 2: a new working roadmap starts from local paths of the learning roadmap. Those nearest
            // the query's start and goal first (the issue with random ones: most lay far from the query and cost
            // checks for nothing). Only into an empty working roadmap: a scene change keeps the roadmap (solve()).
            std::vector<double> key(learnStates_.size(), std::numeric_limits<double>::infinity());
            for (std::size_t i = 0; i < learnStates_.size(); ++i)
                for (const auto *q : near)
                    key[i] = std::min(key[i], si_->distance(learnStates_[i], q));
            std::vector<std::size_t> order(learnEdges_.size());
            std::iota(order.begin(), order.end(), std::size_t(0));
            const auto edgeKey = [&](std::size_t i)
            {
                return std::min(key[learnEdges_[i].first], key[learnEdges_[i].second]);
            };
            const std::size_t tries = std::min<std::size_t>(seedEdges_, order.size());
            // ties broken by index: the same roadmap and query give the same seeds
            std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(tries), order.end(),
                              [&](std::size_t a, std::size_t b)
                              {
                                  const double ka = edgeKey(a), kb = edgeKey(b);
                                  return ka < kb || (ka == kb && a < b);
                              });
            std::map<std::size_t, Vertex> inWorking;
            // A learning state shared by several chosen edges is checked and added once.
            std::map<std::size_t, bool> stateValid;
            auto valid = [&](std::size_t id)
            {
                if (lazySeeding_)
                    return true;  // checked on a candidate path, like every other vertex
                auto it = stateValid.find(id);
                if (it != stateValid.end())
                    return it->second;
                ++work_.stateChecks;
                const bool ok = si_->isValid(learnStates_[id]);
                stateValid[id] = ok;
                return ok;
            };
            auto vertexFor = [&](std::size_t id)
            {
                auto it = inWorking.find(id);
                if (it != inWorking.end())
                    return it->second;
                const Vertex v = addWorkingVertex(si_->cloneState(learnStates_[id]), static_cast<long>(id));
                if (!lazySeeding_)
                    graph_[v].validIn = epoch_;
                inWorking[id] = v;
                return v;
            };
            for (std::size_t i = 0; i < tries && !ptc; ++i)
            {
                const auto &edge = learnEdges_[order[i]];
                if (!valid(edge.first) || !valid(edge.second))
                    continue;
                if (!lazySeeding_)
                {
                    ++work_.motionChecks;
                    if (!si_->checkMotion(learnStates_[edge.first], learnStates_[edge.second]))
                        continue;
                }
                const Vertex a = vertexFor(edge.first);
                const Vertex b = vertexFor(edge.second);
                auto e = addEdgeOnce(a, b);
                if (e.second)
                {
                    graph_.edge(e.first).learned = true;
                    if (!lazySeeding_)
                        graph_.edge(e.first).validIn = graph_.edge(e.first).provedIn = epoch_;
                    ++learnedWorkingEdges_;
                    ++seeded_;
                }
            }
            // seeded vertices also get lazy edges to their neighbours, so the local paths join up
            std::vector<Vertex> seededVertices;
            for (const auto &kv : inWorking)
                seededVertices.push_back(kv.second);
            for (Vertex v : seededVertices)
            {
                if (ptc)
                    break;
                connectLazily(v);
            }
        }

        void DualRoadmap::shortestPath(Vertex start, const std::vector<Vertex> &goals, std::vector<Vertex> &path)
        {
            // A* on the flat graph with buffers kept between searches (RoadmapAStar), lazily re-validated records,
            // and the heuristic computed once per vertex and goal set (a query repeats its search after every
            // refuted edge, with the same goals).
            const std::size_t n = graph_.vertexCount();
            if (heuristicStamp_.size() < n)
            {
                heuristicStamp_.resize(n, 0);
                heuristic_.resize(n, 0.);
            }
            // The cache holds while the goal vertices stay the same: replanning to one goal, query after query (the
            // goal state is one vertex, addQueryVertex), reuses it; vertices added since are computed on demand.
            if (goals != heuristicGoals_)
            {
                heuristicGoals_ = goals;
                ++goalSet_;
            }
            // The distance to the nearest goal is admissible and consistent (it never exceeds the path length through
            // the roadmap's edges, whose lengths are the same distances); times the search weight, the path found
            // costs at most that many times the shortest (weighted A*, no vertex expanded twice).
            const auto h = [&](Vertex v)
            {
                if (heuristicStamp_[v] != goalSet_)
                {
                    double best = std::numeric_limits<double>::infinity();
                    for (Vertex g : goals)
                        best = std::min(best, si_->distance(graph_[v].state, graph_[g].state));
                    // weighted A* (setSearchWeight): the stored heuristic is the inflated one
                    heuristic_[v] = searchWeight_ * best;
                    heuristicStamp_[v] = goalSet_;
                }
                return heuristic_[v];
            };
            const auto isGoal = [&](Vertex v)
            {
                return std::find(goals.begin(), goals.end(), v) != goals.end();
            };
            // Unknown motions cost more than proved ones: the search prefers what needs no check, so after a local
            // change the path goes round rather than through what must be re-checked (still A*: the heuristic never
            // exceeds the lengths, which only grow)
            // An unknown edge refuted a short while ago (or into a state refuted then) costs more again: the moving
            // obstacle that blocked it most likely still does.
            const auto cost = [&](Vertex, const Graph::Arc &arc)
            {
                if (knownValidEdge(arc.edge))
                    return arc.length;
                const bool refuted = recentlyRefuted(graph_.edge(arc.edge).refutedIn) ||
                                     (recentlyRefuted(graph_[arc.to].refutedIn) && !knownValid(arc.to));
                return arc.length * unknownPenalty_ * (refuted ? refutedPenalty_ : 1.);
            };
            // impassable in this scene: found invalid (now, or earlier and untouched by the changes since)
            const auto passable = [&](const Graph::Arc &arc)
            {
                return !knownInvalidEdge(arc.edge) && !knownInvalid(arc.to);
            };
            astar_.search(graph_, start, isGoal, cost, passable, h, path);
            work_.expansions += astar_.expanded();
        }

        long DualRoadmap::learnVertex(Vertex v)
        {
            if (graph_[v].learnId < 0)
            {
                graph_[v].learnId = static_cast<long>(learnStates_.size());
                learnStates_.push_back(si_->cloneState(graph_[v].state));
            }
            return graph_[v].learnId;
        }

        void DualRoadmap::learnEdge(Vertex a, Vertex b)
        {
            // The cap bounds memory and the size of saved files in long runs; edges found later are simply not learned.
            if (!useLearning_ || learnEdges_.size() >= maxLearningEdges_)
                return;
            std::size_t la = static_cast<std::size_t>(learnVertex(a));
            std::size_t lb = static_cast<std::size_t>(learnVertex(b));
            // Undirected edges are stored with the smaller index first, so learnEdgeSet_ finds (a, b) and (b, a) alike.
            if (la > lb)
                std::swap(la, lb);
            if (learnEdgeSet_.insert({la, lb}).second)
            {
                learnEdges_.emplace_back(la, lb);
                learningEdgeCountAtomic_ = learnEdges_.size();
            }
            const auto e = graph_.findEdge(a, b);
            if (e.second && !graph_.edge(e.first).learned)
            {
                graph_.edge(e.first).learned = true;
                ++learnedWorkingEdges_;
            }
        }

        ob::PlannerStatus DualRoadmap::solve(const ob::PlannerTerminationCondition &ptc)
        {
            checkValidity();
            auto *goal = dynamic_cast<ob::GoalSampleableRegion *>(pdef_->getGoal().get());
            if (goal == nullptr)
            {
                OMPL_ERROR("%s: Unknown type of goal", getName().c_str());
                return ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE;
            }

            work_ = Work{};
            taskBegun_ = false;  // the task level's grid belongs to one query
            if (sceneChanged())
            {
                // the change joins the history (its region, or "everything"); records older than the history are
                // stale, newer ones are carried over where no later change touched them (knownValid())
                {
                    std::lock_guard<std::mutex> lock(regionMutex_);
                    history_.push_back(haveRegion_ ? pendingRegion_ : ChangeRegion());
                    haveRegion_ = false;
                    pendingRegion_ = nullptr;
                }
                if (history_.size() > 32)
                    history_.pop_front();
                ++epoch_;
                // The ablation (no learning) and lazy_seeding = 0 start from an empty working roadmap at every
                // change; otherwise the roadmap is kept and re-checked lazily where candidate paths go: no work
                // proportional to its size, none away from the query.
                if (!useLearning_ || !lazySeeding_)
                    freeWorking();
                seeded_ = learnedWorkingEdges_;
                OMPL_DEBUG("%s: scene changed, %zu learning edges in the working roadmap", getName().c_str(), seeded_);
            }
            // A query that filled the roadmap and still failed (a door or walker closing the only passage) leaves
            // thousands of vertices behind; kept, they made every later search expand a thousand of them (the
            // walkers' passage: median latency 0.69 -> 0.39-0.50 ms over 4 seeds x 25 episodes when dropped). The next
            // query starts afresh, seeded from the learning roadmap near it.
            if (refill_)
            {
                refill_ = false;
                freeWorking();
            }
            // every solve() is a query of its own: start and goal states are taken afresh (the working roadmap,
            // with the previous queries' vertices, is kept)
            startVertices_.clear();
            goalVertices_.clear();
            pis_.restart();

            std::vector<ob::State *> starts;
            while (const ob::State *st = pis_.nextStart())
                starts.push_back(si_->cloneState(st));
            const auto freeStarts = [&]
            {
                for (auto *st : starts)
                    si_->freeState(st);
            };
            if (starts.empty())
            {
                OMPL_ERROR("%s: There are no valid initial states!", getName().c_str());
                return ob::PlannerStatus::INVALID_START;
            }
            if (goal->maxSampleCount() == 0 || !goal->couldSample())
            {
                freeStarts();
                OMPL_ERROR("%s: Insufficient states in sampleable goal region", getName().c_str());
                return ob::PlannerStatus::INVALID_GOAL;
            }
            // a working roadmap kept from earlier queries may be started afresh once in this query when it is full
            bool mayRestart = restartWhenFull_ && graph_.vertexCount() > 0;
            const auto seedIfEmpty = [&](const std::vector<const ob::State *> &goalStates)
            {
                if (graph_.vertexCount() != 0)
                    return;
                // an empty working roadmap: seeded from the learning roadmap near the query (a goal sample, valid
                // or not, only orders the seeds)
                std::vector<const ob::State *> near(starts.begin(), starts.end());
                ob::State *g = nullptr;
                if (goalStates.empty())
                {
                    g = si_->allocState();
                    goal->sampleGoal(g);
                    near.push_back(g);
                }
                near.insert(near.end(), goalStates.begin(), goalStates.end());
                seedWorking(near, ptc);
                if (g != nullptr)
                    si_->freeState(g);
            };
            seedIfEmpty({});
            for (auto *st : starts)
                startVertices_.push_back(rememberQueryVertex(addQueryVertex(st)));
            for (Vertex v : startVertices_)
                connectLazily(v);

            ob::State *sample = si_->allocState();
            std::vector<Vertex> path;
            bool solved = false;
            bool dominantFound = false;  // findDominantDirections() for this query, at its first batch
            dominant_.resize(0, 0);
            while (!ptc && !solved)
            {
                // more goal states while the goal region has them
                if (goalVertices_.empty() || pis_.haveMoreGoalStates())
                {
                    // Without any goal vertex there is nothing to search for: wait (until ptc) for the goal region's
                    // first sample. Later goal states are taken only when available at once, so sampling the goal never
                    // blocks the search.
                    const ob::State *g = goalVertices_.empty() ? pis_.nextGoal(ptc) : pis_.nextGoal();
                    if (g != nullptr)
                    {
                        const Vertex v = rememberQueryVertex(addQueryVertex(g));
                        goalVertices_.push_back(v);
                        connectLazily(v);
                    }
                    if (goalVertices_.empty())
                        continue;
                }
                for (Vertex s : startVertices_)
                {
                    if (ptc || solved)
                        break;
                    // search, check the edges of the candidate path lazily, repeat until one holds or none is left
                    while (!ptc)
                    {
                        ++work_.searches;
                        shortestPath(s, goalVertices_, path);
                        if (path.empty())
                            break;
                        if (validatePath(path, ptc))
                        {
                            solved = true;
                            break;
                        }
                    }
                }
                if (solved || ptc)
                    break;
                if (graph_.vertexCount() >= maxWorkingVertices_)
                {
                    // Full. A roadmap kept over many queries and scene changes (the walkers' corridor: half of the
                    // queries failed here, each after 30-90 ms) is crowded with vertices of places and scenes the
                    // robot has left, and a larger bound only made every search slower. So once per query a kept
                    // roadmap starts afresh, as the paper builds a working roadmap: seeded from the learning
                    // roadmap near this query, with room to sample. A roadmap this query filled itself means no
                    // path in this scene now (setMaxWorkingVertices).
                    if (!mayRestart)
                        break;
                    mayRestart = false;
                    ++restarts_;
                    std::vector<const ob::State *> goalStates;
                    for (Vertex v : goalVertices_)
                        goalStates.push_back(si_->cloneState(graph_[v].state));
                    freeWorking();
                    seedIfEmpty(goalStates);
                    for (auto *st : starts)
                        startVertices_.push_back(rememberQueryVertex(addQueryVertex(st)));
                    for (Vertex v : startVertices_)
                        connectLazily(v);
                    for (const auto *gs : goalStates)
                    {
                        const Vertex v = rememberQueryVertex(addQueryVertex(gs));
                        goalVertices_.push_back(v);
                        connectLazily(v);
                        si_->freeState(const_cast<ob::State *>(gs));
                    }
                    continue;
                }
                // expand: a batch of uniform valid samples, connected lazily
                // A batch rather than one sample per round: each round repeats the A* search over the whole roadmap,
                // which would otherwise dominate once the roadmap is large.
                if (dominantDofs_ > 0 && !dominantFound && !goalVertices_.empty())
                {
                    dominantFound = true;
                    findDominantDirections(starts.front(), graph_[goalVertices_.front()].state);
                }
                // with the task level, half of the batch along the hand's route (the rest keeps the search
                // complete)
                const bool alongTask = taskLevel_ && taskMap_ && !goalVertices_.empty();
                if (alongTask)
                    expandAlongTaskRoute(starts.front(), graph_[goalVertices_.front()].state, ptc);
                for (unsigned int i = alongTask ? batchSize_ / 2 : 0; i < batchSize_ && !ptc; ++i)
                {
                    // with dominant directions, every other sample narrowed to them (the rest keep the search
                    // complete)
                    if (dominant_.cols() > 0 && i % 2 == 0)
                        sampleDominant(sample);
                    else
                        sampler_->sampleUniform(sample);
                    ++work_.samples;
                    ++work_.stateChecks;
                    if (!si_->isValid(sample))
                    {
                        if (alongTask)
                        {
                            Eigen::Vector3d hand;
                            taskMap_(sample, hand, nullptr);
                            task_->mark(hand, false);
                        }
                        continue;
                    }
                    const Vertex v = addWorkingVertex(si_->cloneState(sample), -1);
                    graph_[v].validIn = epoch_;
                    connectLazily(v);
                }
            }
            si_->freeState(sample);
            freeStarts();
            if (!solved)
            {
                refill_ = restartWhenFull_ && graph_.vertexCount() >= maxWorkingVertices_;  // see above
                // TIMEOUT only when the time ran out; a query that ended on a full working roadmap gave up (it was
                // reported as a timeout after 0.07 ms with max_working_vertices 1)
                return ptc ? ob::PlannerStatus::TIMEOUT : ob::PlannerStatus::ABORT;
            }

            // Paper 002: found paths are smoothed (redundant parts removed) before they are executed. Every shortcut
            // is a motion checked by the motion validator, so the result stays valid.
            if (smooth_ && path.size() > 2)
                path = shortcut(path, ptc);
            auto result = std::make_shared<og::PathGeometric>(si_);
            for (Vertex v : path)
                result->append(graph_[v].state);
            pdef_->addSolutionPath(result, false, 0., getName());
            return ob::PlannerStatus::EXACT_SOLUTION;
        }

        void DualRoadmap::findDominantDirections(const ob::State *start, const ob::State *goal)
        {
            dominant_.resize(0, 0);
            const auto &space = si_->getStateSpace();
            const unsigned int dim = space->getDimension();
            // Enough experience to tell directions apart: a few local paths per direction.
            if (!useLearning_ || learnEdges_.size() < 4 * static_cast<std::size_t>(dominantDofs_) ||
                dominantDofs_ >= dim)
                return;
            // The learning roadmap's local paths nearest the query: its dominant motions there (paper 002: the
            // dominant DOF of the change, here of the query's region).
            std::vector<double> key(learnStates_.size());
            for (std::size_t i = 0; i < learnStates_.size(); ++i)
                key[i] = std::min(si_->distance(learnStates_[i], start), si_->distance(learnStates_[i], goal));
            std::vector<std::size_t> order(learnEdges_.size());
            std::iota(order.begin(), order.end(), std::size_t(0));
            const std::size_t used = std::min<std::size_t>(order.size(), 200);
            std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(used), order.end(),
                              [&](std::size_t a, std::size_t b)
                              {
                                  const double ka = std::min(key[learnEdges_[a].first], key[learnEdges_[a].second]);
                                  const double kb = std::min(key[learnEdges_[b].first], key[learnEdges_[b].second]);
                                  return ka < kb || (ka == kb && a < b);
                              });
            std::vector<double> a, b;
            space->copyToReals(a, learnStates_[0]);
            const Eigen::Index n = static_cast<Eigen::Index>(a.size());
            Eigen::MatrixXd motions(static_cast<Eigen::Index>(used), n), states(2 * static_cast<Eigen::Index>(used), n);
            for (std::size_t r = 0; r < used; ++r)
            {
                space->copyToReals(a, learnStates_[learnEdges_[order[r]].first]);
                space->copyToReals(b, learnStates_[learnEdges_[order[r]].second]);
                const auto row = static_cast<Eigen::Index>(r);
                for (Eigen::Index j = 0; j < n; ++j)
                {
                    motions(row, j) = b[static_cast<std::size_t>(j)] - a[static_cast<std::size_t>(j)];
                    states(2 * row, j) = a[static_cast<std::size_t>(j)];
                    states(2 * row + 1, j) = b[static_cast<std::size_t>(j)];
                }
            }
            dominant_ = dominantDirections(motions, states, dominantDofs_);
            space->copyToReals(dominantFrom_, start);
            space->copyToReals(dominantTo_, goal);
        }

        void DualRoadmap::sampleDominant(ob::State *state)
        {
            // a point of the start-goal line, then Gaussian steps along the dominant directions only
            if (!rng_)
                rng_ = std::make_unique<ompl::RNG>();
            const double u = rng_->uniform01();
            dominantSample_.resize(dominantFrom_.size());  // kept: no allocation per sample
            for (std::size_t j = 0; j < dominantSample_.size(); ++j)
                dominantSample_[j] = dominantFrom_[j] + u * (dominantTo_[j] - dominantFrom_[j]);
            for (Eigen::Index c = 0; c < dominant_.cols(); ++c)
            {
                const double step = rng_->gaussian01();
                for (std::size_t j = 0; j < dominantSample_.size(); ++j)
                    dominantSample_[j] += step * dominant_(static_cast<Eigen::Index>(j), c);
            }
            si_->getStateSpace()->copyFromReals(state, dominantSample_);
            si_->enforceBounds(state);
        }

        void DualRoadmap::getPlannerData(ob::PlannerData &data) const
        {
            Planner::getPlannerData(data);
            // Tag 0: the working roadmap (this scene); tag 1: the learning roadmap. Edges are added both ways because
            // PlannerData is directed and the roadmaps are not.
            for (Vertex v : startVertices_)
                data.addStartVertex(ob::PlannerDataVertex(graph_[v].state, 0));
            for (Vertex v : goalVertices_)
                data.addGoalVertex(ob::PlannerDataVertex(graph_[v].state, 0));
            for (Edge e = 0; e < graph_.edgeCount(); ++e)
            {
                const ob::PlannerDataVertex a(graph_[graph_.ends(e).first].state, 0);
                const ob::PlannerDataVertex b(graph_[graph_.ends(e).second].state, 0);
                data.addEdge(a, b);
                data.addEdge(b, a);
            }
            for (Vertex v = 0; v < graph_.vertexCount(); ++v)
                data.addVertex(ob::PlannerDataVertex(graph_[v].state, 0));
            for (const auto &e : learnEdges_)
            {
                const ob::PlannerDataVertex a(learnStates_[e.first], 1);
                const ob::PlannerDataVertex b(learnStates_[e.second], 1);
                data.addEdge(a, b);
                data.addEdge(b, a);
            }
        }
    }  // namespace planners
}  // namespace michi
