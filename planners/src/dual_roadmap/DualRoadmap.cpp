#include <michi/planners/dual_roadmap/DualRoadmap.h>
#include <michi/validity/InputFile.h>

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/tools/config/SelfConfig.h>
#include <ompl/util/Exception.h>

#include <boost/graph/astar_search.hpp>

#include <algorithm>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace planners
    {
        namespace
        {
            // First word of a saved learning roadmap, followed by the format version (docs/dual-roadmap.md,
            // "DualRoadmap").
            const char *FILE_MAGIC = "michi-dual-roadmap";
        }  // namespace

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
        }

        void DualRoadmap::freeWorking()
        {
            for (auto v : boost::make_iterator_range(boost::vertices(graph_)))
                if (graph_[v].state != nullptr)
                    si_->freeState(graph_[v].state);
            graph_.clear();
            if (nn_)
                nn_->clear();
            startVertices_.clear();
            goalVertices_.clear();
        }

        void DualRoadmap::clear()
        {
            Planner::clear();
            freeWorking();
            changed_ = true;
            haveCount_ = false;
            seeded_ = 0;
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
            for (auto v : boost::make_iterator_range(boost::vertices(graph_)))
                graph_[v].learnId = -1;
        }

        void DualRoadmap::notifySceneChanged()
        {
            changed_ = true;
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
            return boost::num_vertices(graph_);
        }

        std::size_t DualRoadmap::workingEdgeCount() const
        {
            return boost::num_edges(graph_);
        }

        DualRoadmap::Vertex DualRoadmap::addWorkingVertex(ob::State *state, long learnId)
        {
            const Vertex v = boost::add_vertex(graph_);
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
            // k + 1: v is already in nn_ and is its own nearest neighbour.
            nn_->nearestK(v, k_ + 1, neighbours);
            for (Vertex n : neighbours)
            {
                if (n == v)
                    continue;
                const double d = si_->distance(graph_[v].state, graph_[n].state);
                if (d > range)
                    continue;
                auto e = boost::add_edge(v, n, graph_);
                if (e.second)
                {
                    graph_[e.first].weight = d;
                    graph_[e.first].checked = false;
                }
            }
        }

        void DualRoadmap::rebuildWorking(const ob::PlannerTerminationCondition &ptc)
        {
            freeWorking();
            seeded_ = 0;
            if (!useLearning_ || learnEdges_.empty())
                return;
            // Paper 002, Fig. 2: after a change the working roadmap is cleared and seeded with randomly chosen local
            // paths of the learning roadmap. Only seedEdges_ of them, so seeding costs a bounded number of checks
            // however much has been learned.
            // random choice of learning edges, re-checked in the current scene
            std::vector<std::size_t> order(learnEdges_.size());
            for (std::size_t i = 0; i < order.size(); ++i)
                order[i] = i;
            // Fisher-Yates shuffle through rng_ (not std::shuffle), so that ompl::RNG::setSeed() reproduces the choice.
            for (std::size_t i = order.size(); i > 1; --i)
                std::swap(order[i - 1], order[rng_.uniformInt(0, static_cast<int>(i - 1))]);
            std::map<std::size_t, Vertex> inWorking;
            // A learning state shared by several chosen edges is checked and added once.
            std::map<std::size_t, bool> stateValid;
            auto valid = [&](std::size_t id)
            {
                auto it = stateValid.find(id);
                if (it != stateValid.end())
                    return it->second;
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
                inWorking[id] = v;
                return v;
            };
            const std::size_t tries = std::min<std::size_t>(seedEdges_, order.size());
            for (std::size_t i = 0; i < tries && !ptc; ++i)
            {
                const auto &edge = learnEdges_[order[i]];
                if (!valid(edge.first) || !valid(edge.second))
                    continue;
                // Both end states are always checked (cheap, and an invalid vertex would poison every edge it has); the
                // motion is checked here only without lazy seeding, else later and only if a candidate path uses it.
                if (!lazySeeding_ && !si_->checkMotion(learnStates_[edge.first], learnStates_[edge.second]))
                    continue;
                const Vertex a = vertexFor(edge.first);
                const Vertex b = vertexFor(edge.second);
                auto e = boost::add_edge(a, b, graph_);
                if (e.second)
                {
                    graph_[e.first].weight = si_->distance(graph_[a].state, graph_[b].state);
                    graph_[e.first].checked = !lazySeeding_;
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

        namespace
        {
            // Thrown by the A* visitor to stop at the first goal vertex examined: Boost's astar_search has no early
            // exit, and the search would otherwise settle the whole component.
            struct FoundGoal
            {
            };
        }  // namespace

        std::vector<DualRoadmap::Vertex> DualRoadmap::shortestPath(Vertex start, const std::vector<Vertex> &goals) const
        {
            const std::size_t n = boost::num_vertices(graph_);
            std::vector<Vertex> pred(n);
            std::vector<double> dist(n);
            std::vector<char> isGoal(n, 0);
            for (Vertex g : goals)
                isGoal[g] = 1;

            struct Heuristic : public boost::astar_heuristic<Graph, double>
            {
                const DualRoadmap *self;
                const std::vector<Vertex> *goals;
                // Admissible: the distance to the nearest goal never exceeds the path length through the roadmap's
                // edges, whose weights are the same distances.
                double operator()(Vertex v) const
                {
                    double best = std::numeric_limits<double>::infinity();
                    for (Vertex g : *goals)
                        best = std::min(best, self->si_->distance(self->graph_[v].state, self->graph_[g].state));
                    return best;
                }
            };
            struct Visitor : public boost::default_astar_visitor
            {
                const std::vector<char> *isGoal;
                Vertex *found;
                void examine_vertex(Vertex u, const Graph &) const
                {
                    if ((*isGoal)[u])
                    {
                        *found = u;
                        throw FoundGoal();
                    }
                }
            };
            Heuristic h;
            h.self = this;
            h.goals = &goals;
            Vertex found = start;
            Visitor vis;
            vis.isGoal = &isGoal;
            vis.found = &found;
            bool reached = false;
            try
            {
                boost::astar_search(graph_, start, h,
                                    boost::predecessor_map(&pred[0])
                                        .distance_map(&dist[0])
                                        .weight_map(boost::get(&EdgeProperties::weight, graph_))
                                        .visitor(vis));
            }
            catch (const FoundGoal &)
            {
                reached = true;
            }
            std::vector<Vertex> path;
            if (!reached)
                return path;
            for (Vertex v = found; v != start; v = pred[v])
            {
                path.push_back(v);
                // A vertex that is its own predecessor was never reached from start: no path (guards against an endless
                // walk).
                if (pred[v] == v)
                    return {};
            }
            path.push_back(start);
            std::reverse(path.begin(), path.end());
            return path;
        }

        bool DualRoadmap::validatePath(const std::vector<Vertex> &path, const ob::PlannerTerminationCondition &ptc)
        {
            for (std::size_t i = 0; i + 1 < path.size(); ++i)
            {
                if (ptc)
                    return false;
                auto e = boost::edge(path[i], path[i + 1], graph_);
                if (!e.second)
                    return false;
                if (graph_[e.first].checked)
                    continue;
                if (si_->checkMotion(graph_[path[i]].state, graph_[path[i + 1]].state))
                {
                    graph_[e.first].checked = true;
                    // Paper 002: every edge newly proved valid in the working roadmap is added to the learning roadmap.
                    learnEdge(path[i], path[i + 1]);
                }
                else
                {
                    // An invalid edge is removed for good (in this scene), so the next search finds another candidate
                    // path. Edges checked valid before the failing one stay checked and are already learned.
                    boost::remove_edge(e.first, graph_);
                    return false;
                }
            }
            return true;
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

            if (sceneChanged())
            {
                rebuildWorking(ptc);
                OMPL_DEBUG("%s: scene changed, working roadmap seeded with %zu learning edges", getName().c_str(),
                           seeded_);
            }
            // every solve() is a query of its own: start and goal states are taken afresh (in the same scene the
            // working roadmap, with the previous queries' vertices, is kept)
            startVertices_.clear();
            goalVertices_.clear();
            pis_.restart();

            while (const ob::State *st = pis_.nextStart())
                startVertices_.push_back(addWorkingVertex(si_->cloneState(st), -1));
            if (startVertices_.empty())
            {
                OMPL_ERROR("%s: There are no valid initial states!", getName().c_str());
                return ob::PlannerStatus::INVALID_START;
            }
            for (Vertex v : startVertices_)
                connectLazily(v);
            if (goal->maxSampleCount() == 0 || !goal->couldSample())
            {
                OMPL_ERROR("%s: Insufficient states in sampleable goal region", getName().c_str());
                return ob::PlannerStatus::INVALID_GOAL;
            }

            ob::State *sample = si_->allocState();
            std::vector<Vertex> path;
            bool solved = false;
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
                        const Vertex v = addWorkingVertex(si_->cloneState(g), -1);
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
                        path = shortestPath(s, goalVertices_);
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
                // expand: a batch of uniform valid samples, connected lazily
                // A batch rather than one sample per round: each round repeats the A* search over the whole roadmap,
                // which would otherwise dominate once the roadmap is large.
                for (unsigned int i = 0; i < batchSize_ && !ptc; ++i)
                {
                    sampler_->sampleUniform(sample);
                    if (!si_->isValid(sample))
                        continue;
                    connectLazily(addWorkingVertex(si_->cloneState(sample), -1));
                }
            }
            si_->freeState(sample);
            if (!solved)
                return ob::PlannerStatus::TIMEOUT;

            auto result = std::make_shared<og::PathGeometric>(si_);
            for (Vertex v : path)
                result->append(graph_[v].state);
            // Paper 002: found paths are smoothed (redundant parts removed) before they are executed. The simplifier's
            // motions are checked by the motion validator, so the result stays valid.
            if (smooth_ && result->getStateCount() > 2)
            {
                og::PathSimplifier simplifier(si_, pdef_->getGoal());
                simplifier.reduceVertices(*result);
                simplifier.shortcutPath(*result);
            }
            pdef_->addSolutionPath(result, false, 0., getName());
            return ob::PlannerStatus::EXACT_SOLUTION;
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
            for (auto e : boost::make_iterator_range(boost::edges(graph_)))
            {
                const ob::PlannerDataVertex a(graph_[boost::source(e, graph_)].state, 0);
                const ob::PlannerDataVertex b(graph_[boost::target(e, graph_)].state, 0);
                data.addEdge(a, b);
                data.addEdge(b, a);
            }
            for (auto v : boost::make_iterator_range(boost::vertices(graph_)))
                data.addVertex(ob::PlannerDataVertex(graph_[v].state, 0));
            for (const auto &e : learnEdges_)
            {
                const ob::PlannerDataVertex a(learnStates_[e.first], 1);
                const ob::PlannerDataVertex b(learnStates_[e.second], 1);
                data.addEdge(a, b);
                data.addEdge(b, a);
            }
        }

        void DualRoadmap::saveLearningRoadmap(const std::string &file) const
        {
            const auto &space = si_->getStateSpace();
            std::ostringstream out;
            // 17 significant digits: every double reads back exactly, so a loaded roadmap has the same states as the
            // saved one.
            out.precision(17);
            out << FILE_MAGIC << " 1\n";
            std::vector<double> reals;
            {
                ob::State *probe = si_->allocState();  // the number of reals in a state
                space->copyToReals(reals, probe);
                si_->freeState(probe);
            }
            out << "space " << space->getDimension() << " " << reals.size() << " " << space->getName() << "\n";
            out << "vertices " << learnStates_.size() << "\n";
            for (const auto *s : learnStates_)
            {
                space->copyToReals(reals, s);
                for (std::size_t i = 0; i < reals.size(); ++i)
                    out << (i ? " " : "") << reals[i];
                out << "\n";
            }
            out << "edges " << learnEdges_.size() << "\n";
            for (const auto &e : learnEdges_)
                out << e.first << " " << e.second << "\n";
            // Written to a sibling file and renamed: a failed or interrupted write never leaves a truncated roadmap
            // under the file's name.
            const std::string tmp = file + ".tmp";
            {
                std::ofstream f(tmp);
                if (!f || !(f << out.str()) || !f.flush())
                    throw std::runtime_error(file + ": cannot write the learning roadmap");
            }
            if (std::rename(tmp.c_str(), file.c_str()) != 0)
            {
                std::remove(tmp.c_str());
                throw std::runtime_error(file + ": cannot write the learning roadmap");
            }
        }

        void DualRoadmap::loadLearningRoadmap(const std::string &file)
        {
            validity::requireInputFile(file);
            std::ifstream in(file);
            if (!in)
                throw std::runtime_error(file + ": cannot read the learning roadmap");
            auto fail = [&](const std::string &what)
            {
                throw std::runtime_error(file + ": " + what);
            };
            const auto &space = si_->getStateSpace();
            std::string magic, word, name;
            int version = 0;
            unsigned int dimension = 0;
            std::size_t realCount = 0;
            if (!(in >> magic >> version) || magic != FILE_MAGIC || version != 1)
                fail("not a DualRoadmap learning roadmap (expected '" + std::string(FILE_MAGIC) + " 1')");
            if (!(in >> word >> dimension >> realCount >> name) || word != "space")
                fail("expected 'space DIMENSION REALS NAME'");
            std::vector<double> reals;
            {
                ob::State *probe = si_->allocState();  // the number of reals in a state
                space->copyToReals(reals, probe);
                si_->freeState(probe);
            }
            // The space's name is written for people but not compared: the same robot may be set up under another name.
            // Dimension and number of reals are what copyFromReals() depends on.
            if (dimension != space->getDimension() || realCount != reals.size())
                fail("made for a space of dimension " + std::to_string(dimension) + " (" + std::to_string(realCount) +
                     " reals), this one has dimension " + std::to_string(space->getDimension()) + " (" +
                     std::to_string(reals.size()) + " reals)");
            std::size_t nv = 0, ne = 0;
            if (!(in >> word >> nv) || word != "vertices")
                fail("expected 'vertices N'");
            const std::size_t nr = reals.size();
            std::vector<ob::State *> states;
            auto freeAll = [&]
            {
                for (auto *s : states)
                    si_->freeState(s);
            };
            for (std::size_t i = 0; i < nv; ++i)
            {
                for (std::size_t j = 0; j < nr; ++j)
                    if (!(in >> reals[j]))
                    {
                        freeAll();
                        fail("vertex " + std::to_string(i) + ": expected " + std::to_string(nr) + " numbers");
                    }
                states.push_back(si_->allocState());
                space->copyFromReals(states.back(), reals);
            }
            std::vector<std::pair<std::size_t, std::size_t>> edges;
            if (!(in >> word >> ne) || word != "edges")
            {
                freeAll();
                fail("expected 'edges N'");
            }
            for (std::size_t i = 0; i < ne; ++i)
            {
                std::size_t a = 0, b = 0;
                if (!(in >> a >> b) || a >= nv || b >= nv || a == b)
                {
                    freeAll();
                    fail("edge " + std::to_string(i) + ": expected two different vertex indices below " +
                         std::to_string(nv));
                }
                edges.emplace_back(std::min(a, b), std::max(a, b));
            }
            // Nothing is changed until the whole file has been read and checked: a bad file leaves the old learning
            // roadmap as it was.
            clearLearningRoadmap();
            learnStates_ = std::move(states);
            for (const auto &e : edges)
                if (learnEdgeSet_.insert(e).second)
                    learnEdges_.push_back(e);
            learningEdgeCountAtomic_ = learnEdges_.size();
            changed_ = true;  // the working roadmap holds ids of the old learning roadmap
        }
    }  // namespace planners
}  // namespace michi
