#include <michi/planners/heading_lattice/HeadingLattice.h>

#include <michi/state_spaces/Angles.h>
#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/validity/fcl/FclValidityChecker.h>

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/util/Time.h>

#include <boost/graph/astar_search.hpp>
#include <boost/range/iterator_range.hpp>
#include <boost/math/constants/constants.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace planners
    {
        namespace
        {
            const double PI = boost::math::constants::pi<double>();

            using state_spaces::wrapAngle;

            /** Lattice geometry of one heading: the paper's equation (1) when |tan| <= 1 ("columns"), else (2). */
            struct HeadingRow
            {
                bool columns;  ///< |cos| >= |sin|: nodes at (x, y + x tan)
                double slope;  ///< tan (columns) or cot (rows)
                int forward;   ///< +1 / -1: sign of cos (columns) or sin (rows)
            };

            HeadingRow headingRow(double theta)
            {
                const double c = std::cos(theta), s = std::sin(theta);
                HeadingRow r;
                r.columns = std::abs(c) >= std::abs(s) - 1e-12;
                r.slope = r.columns ? s / c : c / s;
                r.forward = (r.columns ? c : s) > 0. ? 1 : -1;
                return r;
            }

            struct FoundGoal
            {
                std::size_t vertex;
            };
            struct Stopped
            {
            };
        }  // namespace

        HeadingLattice::HeadingLattice(const ob::SpaceInformationPtr &si) : ob::Planner(si, "HeadingLattice")
        {
            specs_.approximateSolutions = false;
            specs_.optimizingPaths = false;
            specs_.multithreaded = false;
            specs_.directed = true;  // without reversing, lattice moves go forwards only
            specs_.recognizedGoal = ob::GOAL_SAMPLEABLE_REGION;

            declareParam<double>("cell_size", this, &HeadingLattice::setCellSize, &HeadingLattice::getCellSize,
                                 "0.01:0.01:2.");
            declareParam<double>("angle_step", this, &HeadingLattice::setAngleStep, &HeadingLattice::getAngleStep,
                                 "0.05:0.01:1.58");
            declareParam<double>("connection_cells", this, &HeadingLattice::setConnectionCells,
                                 &HeadingLattice::getConnectionCells, "0.5:0.5:10.");
        }

        HeadingLattice::~HeadingLattice()
        {
            freeGraph();
        }

        void HeadingLattice::setCellSize(double size)
        {
            if (!(size > 0.) || !std::isfinite(size))
                throw ompl::Exception(getName(), "cell_size must be positive");
            cellSize_ = size;
        }

        void HeadingLattice::setAngleStep(double step)
        {
            if (!(step > 0.) || !(step <= PI / 2. + 1e-9))
                throw ompl::Exception(getName(), "angle_step must be in (0, pi/2]");
            angleStep_ = step;
        }

        void HeadingLattice::setConnectionCells(double cells)
        {
            if (!(cells > 0.) || !std::isfinite(cells))
                throw ompl::Exception(getName(), "connection_cells must be positive");
            connectionCells_ = cells;
        }

        double HeadingLattice::getHeadingStep() const
        {
            return headings_ > 0 ? 2. * PI / headings_ : angleStep_;
        }

        double HeadingLattice::headingAngle(unsigned int k) const
        {
            return wrapAngle(2. * PI * k / headings_);
        }

        void HeadingLattice::setup()
        {
            ob::Planner::setup();
            if (dynamic_cast<const ob::SE2StateSpace *>(si_->getStateSpace().get()) == nullptr)
            {
                OMPL_ERROR("%s: needs an SE(2) state space (TurnMoveTurnStateSpace or SE2StateSpace), got %s",
                           getName().c_str(), si_->getStateSpace()->getName().c_str());
                setup_ = false;
            }
        }

        void HeadingLattice::setProblemDefinition(const ob::ProblemDefinitionPtr &pdef)
        {
            ob::Planner::setProblemDefinition(pdef);
            clearQuery();
        }

        void HeadingLattice::clearQuery()
        {
            // query vertices are the last ones: drop their edges (and the edges into them), then the vertices
            const std::size_t lattice = nodes_.size();
            if (built_ && boost::num_vertices(graph_) > lattice)
            {
                for (std::size_t v = boost::num_vertices(graph_); v-- > lattice;)
                    boost::clear_out_edges(v, graph_);
                for (std::size_t u = 0; u < lattice; ++u)
                    boost::remove_out_edge_if(
                        u,
                        [&](const Graph::edge_descriptor &e)
                        {
                            return boost::target(e, graph_) >= lattice;
                        },
                        graph_);
                while (boost::num_vertices(graph_) > lattice)
                    boost::remove_vertex(boost::num_vertices(graph_) - 1, graph_);
            }
            for (auto *s : queryStates_)
                si_->freeState(s);
            queryStates_.clear();
            queryIsStart_.clear();
            rawPath_.clear();
            pis_.restart();
        }

        void HeadingLattice::freeGraph()
        {
            for (auto *s : queryStates_)
                si_->freeState(s);
            queryStates_.clear();
            queryIsStart_.clear();
            for (auto *s : exportStates_)
                si_->freeState(s);
            exportStates_.clear();
            graph_.clear();
            nodes_.clear();
            built_ = false;
            rawPath_.clear();
        }

        void HeadingLattice::clear()
        {
            ob::Planner::clear();
            freeGraph();
            key_ = MapKey();
        }

        HeadingLattice::MapKey HeadingLattice::currentKey() const
        {
            MapKey key;
            key.checker = si_->getStateValidityChecker().get();
            key.motionValidator = si_->getMotionValidator().get();
            if (const auto *fcl =
                    dynamic_cast<const validity::FclValidityChecker *>(si_->getStateValidityChecker().get()))
            {
                key.scene = fcl->scene().get();
                key.sceneChanges = fcl->scene() ? fcl->scene()->changeCount() : 0;
            }
            const auto *se2 = si_->getStateSpace()->as<ob::SE2StateSpace>();
            const auto &b = se2->getBounds();
            key.settings = {cellSize_, angleStep_, b.low[0], b.low[1], b.high[0], b.high[1]};
            if (const auto *tmt = dynamic_cast<const state_spaces::TurnMoveTurnStateSpace *>(se2))
            {
                key.settings.push_back(tmt->getTurnWeight());
                key.settings.push_back(tmt->getAllowBackward() ? 1. : 0.);
            }
            return key;
        }

        void HeadingLattice::setState(ob::State *state, double x, double y, double yaw) const
        {
            auto *s = state->as<ob::SE2StateSpace::StateType>();
            s->setXY(x, y);
            s->setYaw(wrapAngle(yaw));
        }

        void HeadingLattice::setNodeState(unsigned int vertex, ob::State *state) const
        {
            if (vertex < nodes_.size())
            {
                const Node &n = nodes_[vertex];
                setState(state, n.x, n.y, headingAngle(n.heading));
            }
            else
                si_->copyState(state, queryStates_[vertex - nodes_.size()]);
        }

        bool HeadingLattice::build(const ob::PlannerTerminationCondition &ptc)
        {
            freeGraph();
            const ompl::time::point started = ompl::time::now();
            const auto *se2 = si_->getStateSpace()->as<ob::SE2StateSpace>();
            const auto &b = se2->getBounds();
            const auto *tmt = dynamic_cast<const state_spaces::TurnMoveTurnStateSpace *>(se2);
            reversible_ = tmt == nullptr || tmt->getAllowBackward();
            headings_ = std::max(4u, static_cast<unsigned int>(std::lround(2. * PI / angleStep_)));
            x0_ = b.low[0];
            y0_ = b.low[1];
            const double c = cellSize_;
            columns_ = static_cast<unsigned int>(std::floor((b.high[0] - x0_) / c + 1e-9)) + 1;
            rows_ = static_cast<unsigned int>(std::floor((b.high[1] - y0_) / c + 1e-9)) + 1;
            const unsigned int K = headings_;
            std::vector<HeadingRow> hrows(K);
            for (unsigned int k = 0; k < K; ++k)
                hrows[k] = headingRow(headingAngle(k));

            // node (group (i, j), heading k): the heading's lattice point nearest to the grid point (i, j)
            auto position = [&](long i, long j, unsigned int k)
            {
                const HeadingRow &r = hrows[k];
                if (r.columns)
                {
                    const double v = i * r.slope;
                    return std::make_pair(x0_ + i * c, y0_ + c * (j + v - std::round(v)));
                }
                const double v = j * r.slope;
                return std::make_pair(x0_ + c * (i + v - std::round(v)), y0_ + j * c);
            };

            // nodes where the robot is free (the paper leaves out nodes on obstacles)
            const std::size_t groups = static_cast<std::size_t>(columns_) * rows_;
            std::vector<std::int32_t> vertexOf(groups * K, -1);
            ob::State *state = si_->allocState();
            ob::State *other = si_->allocState();
            {
                setState(state, 0.5 * (b.low[0] + b.high[0]), 0.5 * (b.low[1] + b.high[1]), 0.);
                setState(other, 0.5 * (b.low[0] + b.high[0]), 0.5 * (b.low[1] + b.high[1]), 2. * PI / K);
                turnCost_ = si_->distance(state, other);
            }
            bool stopped = false;
            for (unsigned int i = 0; i < columns_ && !stopped; ++i)
            {
                for (unsigned int j = 0; j < rows_; ++j)
                {
                    if (ptc)
                    {
                        stopped = true;
                        break;
                    }
                    for (unsigned int k = 0; k < K; ++k)
                    {
                        const auto p = position(i, j, k);
                        setState(state, p.first, p.second, headingAngle(k));
                        if (!si_->satisfiesBounds(state) || !si_->isValid(state))
                            continue;
                        const std::size_t g = static_cast<std::size_t>(i) * rows_ + j;
                        vertexOf[g * K + k] = static_cast<std::int32_t>(nodes_.size());
                        nodes_.push_back(Node{p.first, p.second, k, static_cast<unsigned int>(g)});
                    }
                }
            }
            si_->freeState(state);
            si_->freeState(other);
            if (stopped)
            {
                nodes_.clear();
                return false;
            }

            // edges: along each heading to the next lattice point (driving), between adjacent headings of a group
            // (turning in place); validity is checked lazily, when A* uses an edge
            graph_.clear();  // (no Graph(n) assignment: Boost copies graphs there, which trips -Wmaybe-uninitialized)
            for (std::size_t v = 0; v < nodes_.size(); ++v)
                boost::add_vertex(graph_);
            for (std::size_t v = 0; v < nodes_.size(); ++v)
            {
                const Node &n = nodes_[v];
                const long i = n.group / rows_, j = n.group % rows_;
                const unsigned int k = n.heading;
                const HeadingRow &r = hrows[k];
                long ni, nj;
                if (r.columns)
                {
                    const long line = j - std::lround(i * r.slope);
                    ni = i + r.forward;
                    nj = line + std::lround(ni * r.slope);
                }
                else
                {
                    const long line = i - std::lround(j * r.slope);
                    nj = j + r.forward;
                    ni = line + std::lround(nj * r.slope);
                }
                if (ni >= 0 && nj >= 0 && ni < static_cast<long>(columns_) && nj < static_cast<long>(rows_))
                {
                    const std::int32_t w = vertexOf[(static_cast<std::size_t>(ni) * rows_ + nj) * K + k];
                    if (w >= 0)
                    {
                        const double length =
                            c / (r.columns ? std::abs(std::cos(headingAngle(k))) : std::abs(std::sin(headingAngle(k))));
                        boost::add_edge(v, w, EdgeProperty{length, 0, 0}, graph_);
                        if (reversible_)
                            boost::add_edge(w, v, EdgeProperty{length, 0, 0}, graph_);
                    }
                }
                const std::int32_t t = vertexOf[static_cast<std::size_t>(n.group) * K + (k + 1) % K];
                if (t >= 0)
                {
                    boost::add_edge(v, t, EdgeProperty{turnCost_, 1, 0}, graph_);
                    boost::add_edge(t, v, EdgeProperty{turnCost_, 1, 0}, graph_);
                }
                if ((v & 4095) == 0 && ptc)
                {
                    graph_.clear();
                    nodes_.clear();
                    return false;
                }
            }
            built_ = true;
            ++buildCount_;
            lastBuildTime_ = ompl::time::seconds(ompl::time::now() - started);
            OMPL_INFORM("%s: lattice of %u x %u cells of %g m, %u headings: %zu free nodes, %zu edges (%.3f s)",
                        getName().c_str(), columns_, rows_, c, K, nodes_.size(), boost::num_edges(graph_),
                        lastBuildTime_);
            return true;
        }

        bool HeadingLattice::connectQueryState(const ob::State *query, bool start)
        {
            const auto *s = query->as<ob::SE2StateSpace::StateType>();
            const Vertex q = boost::add_vertex(graph_);
            queryStates_.push_back(si_->cloneState(query));
            queryIsStart_.push_back(start ? 1 : 0);
            ob::State *node = si_->allocState();
            bool joined = false;
            double radius = connectionCells_ * cellSize_;
            for (int attempt = 0; attempt < 4 && !joined; ++attempt, radius *= 2.)
            {
                // nodes of the groups around the state, nearest (in the space's distance) first
                std::vector<std::pair<double, Vertex>> candidates;
                const long span = static_cast<long>(std::ceil(radius / cellSize_)) + 1;
                const long ci = std::lround((s->getX() - x0_) / cellSize_);
                const long cj = std::lround((s->getY() - y0_) / cellSize_);
                // the nodes of a group are contiguous in vertex order: find them by binary search on the group
                for (long i = std::max(0L, ci - span); i <= std::min<long>(columns_ - 1, ci + span); ++i)
                    for (long j = std::max(0L, cj - span); j <= std::min<long>(rows_ - 1, cj + span); ++j)
                    {
                        const unsigned int g = static_cast<unsigned int>(i * rows_ + j);
                        auto it = std::lower_bound(nodes_.begin(), nodes_.end(), g,
                                                   [](const Node &n, unsigned int group)
                                                   {
                                                       return n.group < group;
                                                   });
                        for (; it != nodes_.end() && it->group == g; ++it)
                        {
                            if (std::hypot(it->x - s->getX(), it->y - s->getY()) > radius)
                                continue;
                            const auto v = static_cast<Vertex>(it - nodes_.begin());
                            setNodeState(v, node);
                            candidates.emplace_back(start ? si_->distance(query, node) : si_->distance(node, query), v);
                        }
                    }
                std::sort(candidates.begin(), candidates.end());
                for (const auto &cand : candidates)
                {
                    setNodeState(cand.second, node);
                    const bool ok = start ? si_->checkMotion(query, node) : si_->checkMotion(node, query);
                    if (!ok)
                        continue;
                    if (start)
                        boost::add_edge(q, cand.second, EdgeProperty{cand.first, 2, 1}, graph_);
                    else
                        boost::add_edge(cand.second, q, EdgeProperty{cand.first, 2, 1}, graph_);
                    joined = true;
                }
            }
            // a direct motion to the query states of the other kind nearby
            for (std::size_t o = 0; o + 1 < queryStates_.size(); ++o)
            {
                if (queryIsStart_[o] == (start ? 1 : 0))
                    continue;
                const ob::State *from = start ? query : queryStates_[o];
                const ob::State *to = start ? queryStates_[o] : query;
                const double d = si_->distance(from, to);
                if (d <= connectionCells_ * cellSize_ && si_->checkMotion(from, to))
                {
                    const Vertex ov = nodes_.size() + o;
                    boost::add_edge(start ? q : ov, start ? ov : q, EdgeProperty{d, 2, 1}, graph_);
                    joined = true;
                }
            }
            si_->freeState(node);
            return joined;
        }

        std::vector<HeadingLattice::Vertex> HeadingLattice::search(const ob::PlannerTerminationCondition &ptc,
                                                                   bool &stopped)
        {
            stopped = false;
            const std::size_t lattice = nodes_.size();
            // a source joined to every start at no cost (removed again below)
            const Vertex source = boost::add_vertex(graph_);
            std::vector<char> isGoal(boost::num_vertices(graph_), 0);
            std::vector<std::pair<double, double>> goals;
            for (std::size_t o = 0; o < queryStates_.size(); ++o)
            {
                const auto *s = queryStates_[o]->as<ob::SE2StateSpace::StateType>();
                if (queryIsStart_[o])
                    boost::add_edge(source, lattice + o, EdgeProperty{0., 2, 1}, graph_);
                else
                {
                    isGoal[lattice + o] = 1;
                    goals.emplace_back(s->getX(), s->getY());
                }
            }
            std::vector<std::pair<double, double>> where(boost::num_vertices(graph_));
            for (std::size_t v = 0; v < lattice; ++v)
                where[v] = {nodes_[v].x, nodes_[v].y};
            for (std::size_t o = 0; o < queryStates_.size(); ++o)
            {
                const auto *s = queryStates_[o]->as<ob::SE2StateSpace::StateType>();
                where[lattice + o] = {s->getX(), s->getY()};
            }
            where[source] = where.empty() ? std::make_pair(0., 0.) : where[0];

            // straight-line distance to the nearest goal: the drives a path needs at least (turns cost extra)
            struct Heuristic : boost::astar_heuristic<Graph, double>
            {
                const std::vector<std::pair<double, double>> *where, *goals;
                Vertex source;
                double operator()(Vertex v) const
                {
                    if (v == source)
                        return 0.;
                    double best = std::numeric_limits<double>::infinity();
                    for (const auto &g : *goals)
                        best = std::min(best, std::hypot((*where)[v].first - g.first, (*where)[v].second - g.second));
                    return best;
                }
            } heuristic;
            heuristic.where = &where;
            heuristic.goals = &goals;
            heuristic.source = source;

            struct Visitor : boost::default_astar_visitor
            {
                const std::vector<char> *isGoal;
                const ob::PlannerTerminationCondition *ptc;
                unsigned int *count;
                void examine_vertex(Vertex u, const Graph &) const
                {
                    if (u < isGoal->size() && (*isGoal)[u])
                        throw FoundGoal{u};
                    if ((++*count & 1023u) == 0 && (*ptc)())
                        throw Stopped{};
                }
            } visitor;
            unsigned int count = 0;
            visitor.isGoal = &isGoal;
            visitor.ptc = &ptc;
            visitor.count = &count;

            const std::size_t n = boost::num_vertices(graph_);
            std::vector<Vertex> predecessor(n);
            std::vector<double> distance(n), rank(n);
            std::vector<Vertex> path;
            try
            {
                boost::astar_search(
                    graph_, source, heuristic,
                    boost::predecessor_map(
                        boost::make_iterator_property_map(predecessor.begin(), boost::get(boost::vertex_index, graph_)))
                        .distance_map(boost::make_iterator_property_map(distance.begin(),
                                                                        boost::get(boost::vertex_index, graph_)))
                        .rank_map(
                            boost::make_iterator_property_map(rank.begin(), boost::get(boost::vertex_index, graph_)))
                        .weight_map(boost::get(&EdgeProperty::weight, graph_))
                        .visitor(visitor));
            }
            catch (const FoundGoal &found)
            {
                for (Vertex v = found.vertex; v != source; v = predecessor[v])
                    path.push_back(v);
                std::reverse(path.begin(), path.end());
            }
            catch (const Stopped &)
            {
                stopped = true;
            }
            boost::clear_out_edges(source, graph_);
            boost::remove_vertex(source, graph_);
            return path;
        }

        void HeadingLattice::removeEdgePair(Vertex a, Vertex b)
        {
            boost::remove_edge(a, b, graph_);
            if (reversible_ || (a < nodes_.size() && b < nodes_.size() && nodes_[a].group == nodes_[b].group))
                boost::remove_edge(b, a, graph_);
        }

        bool HeadingLattice::checkEdges(const std::vector<Vertex> &path)
        {
            bool all = true;
            ob::State *a = si_->allocState(), *b = si_->allocState(), *c = si_->allocState(), *d = si_->allocState();
            for (std::size_t p = 0; p + 1 < path.size(); ++p)
            {
                auto e = boost::edge(path[p], path[p + 1], graph_);
                if (!e.second || graph_[e.first].checked)
                    continue;
                setNodeState(path[p], a);
                setNodeState(path[p + 1], b);
                bool ok;
                if (graph_[e.first].kind == 1)
                {
                    // a turn in place between the headings, at both nodes' positions
                    const auto *sa = a->as<ob::SE2StateSpace::StateType>();
                    const auto *sb = b->as<ob::SE2StateSpace::StateType>();
                    setState(c, sa->getX(), sa->getY(), sb->getYaw());
                    setState(d, sb->getX(), sb->getY(), sa->getYaw());
                    ok = si_->checkMotion(a, c) && si_->checkMotion(d, b);
                }
                else
                    ok = si_->checkMotion(a, b);
                if (ok)
                {
                    graph_[e.first].checked = 1;
                    auto back = boost::edge(path[p + 1], path[p], graph_);
                    if (back.second && (reversible_ || graph_[e.first].kind == 1))
                        graph_[back.first].checked = 1;
                }
                else
                {
                    removeEdgePair(path[p], path[p + 1]);
                    all = false;
                }
            }
            for (auto *s : {a, b, c, d})
                si_->freeState(s);
            return all;
        }

        bool HeadingLattice::makePath(const std::vector<Vertex> &path, og::PathGeometric &out)
        {
            const std::size_t lattice = nodes_.size();
            auto isTurn = [&](std::size_t p)
            {
                return path[p] < lattice && path[p + 1] < lattice && nodes_[path[p]].group == nodes_[path[p + 1]].group;
            };
            ob::State *work = si_->allocState();
            std::vector<ob::State *> emitted;
            auto emit = [&](const ob::State *s)
            {
                emitted.push_back(si_->cloneState(s));
            };
            auto last = [&]() -> const ob::State *
            {
                return emitted.back();
            };
            bool ok = true;
            setNodeState(path[0], work);
            emit(work);
            std::size_t p = 1;
            while (p < path.size() && ok)
            {
                if (p + 1 < path.size() && isTurn(p))
                {
                    // a run of turns path[p] .. path[e] within one group: turn at one place instead
                    std::size_t e = p;
                    while (e + 1 < path.size() && isTurn(e))
                        ++e;
                    const Node &first = nodes_[path[p]], &final = nodes_[path[e]];
                    std::vector<std::pair<double, double>> places;
                    places.emplace_back(0.5 * (first.x + final.x), 0.5 * (first.y + final.y));  // the paper's centre
                    // where the line driven in on and the line driven out on meet
                    const double ta = headingAngle(first.heading), tb = headingAngle(final.heading);
                    const double det = std::cos(ta) * std::sin(tb) - std::sin(ta) * std::cos(tb);
                    if (std::abs(det) > 1e-6)
                    {
                        const double dx = final.x - first.x, dy = final.y - first.y;
                        const double s = (dx * std::sin(tb) - dy * std::cos(tb)) / det;
                        const double ix = first.x + s * std::cos(ta), iy = first.y + s * std::sin(ta);
                        if (std::hypot(ix - places[0].first, iy - places[0].second) <= 3. * cellSize_)
                            places.emplace_back(ix, iy);
                    }
                    bool placed = false;
                    for (const auto &place : places)
                    {
                        std::vector<ob::State *> run;
                        bool good = true;
                        const ob::State *prev = last();
                        for (std::size_t r = p; r <= e && good; ++r)
                        {
                            ob::State *s = si_->allocState();
                            setState(s, place.first, place.second, headingAngle(nodes_[path[r]].heading));
                            good = si_->checkMotion(prev, s);
                            run.push_back(s);
                            prev = s;
                        }
                        // and on to the next node (checked again from the place the next run chooses)
                        if (good && e + 1 < path.size())
                        {
                            setNodeState(path[e + 1], work);
                            good = si_->checkMotion(prev, work);
                        }
                        if (good)
                        {
                            emitted.insert(emitted.end(), run.begin(), run.end());
                            placed = true;
                            break;
                        }
                        for (auto *s : run)
                            si_->freeState(s);
                    }
                    if (!placed)
                    {
                        for (std::size_t r = p; r < e; ++r)
                            removeEdgePair(path[r], path[r + 1]);
                        ok = false;
                    }
                    p = e + 1;
                    continue;
                }
                setNodeState(path[p], work);
                if (!si_->checkMotion(last(), work))
                {
                    // only after a corrected turn can a drive fail here: do not use that drive again
                    removeEdgePair(path[p - 1], path[p]);
                    ok = false;
                    break;
                }
                emit(work);
                ++p;
            }
            si_->freeState(work);
            if (ok)
                for (auto *s : emitted)
                    out.append(s);
            for (auto *s : emitted)
                si_->freeState(s);
            return ok;
        }

        ob::PlannerStatus HeadingLattice::solve(const ob::PlannerTerminationCondition &ptc)
        {
            checkValidity();
            if (!setup_)
                return ob::PlannerStatus::ABORT;  // not an SE(2) space (setup() said so)
            auto *goal = dynamic_cast<ob::GoalSampleableRegion *>(pdef_->getGoal().get());
            if (goal == nullptr)
            {
                OMPL_ERROR("%s: unknown type of goal", getName().c_str());
                return ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE;
            }

            const MapKey key = currentKey();
            if (!built_ || !(key == key_))
            {
                if (built_)
                    OMPL_INFORM("%s: the map changed: building the lattice again", getName().c_str());
                // the query states are joined to the old graph: take them in again
                clearQuery();
                key_ = MapKey();
                if (!build(ptc))
                {
                    OMPL_INFORM("%s: stopped while building the lattice", getName().c_str());
                    return ob::PlannerStatus::TIMEOUT;
                }
                key_ = key;
            }
            else
                lastBuildTime_ = 0.;

            while (const ob::State *st = pis_.nextStart())
                if (!connectQueryState(st, true))
                    OMPL_WARN("%s: the start cannot be joined to the lattice", getName().c_str());
            if (std::find(queryIsStart_.begin(), queryIsStart_.end(), 1) == queryIsStart_.end())
            {
                OMPL_ERROR("%s: no valid start state", getName().c_str());
                return ob::PlannerStatus::INVALID_START;
            }
            while (pis_.haveMoreGoalStates() && !ptc)
            {
                const ob::State *g = pis_.nextGoal(ptc);
                if (g == nullptr)
                    break;
                if (!connectQueryState(g, false))
                    OMPL_WARN("%s: a goal cannot be joined to the lattice", getName().c_str());
            }
            if (std::find(queryIsStart_.begin(), queryIsStart_.end(), 0) == queryIsStart_.end())
            {
                OMPL_ERROR("%s: no valid goal state", getName().c_str());
                return ob::PlannerStatus::INVALID_GOAL;
            }

            while (!ptc)
            {
                bool stopped = false;
                const std::vector<Vertex> path = search(ptc, stopped);
                if (stopped)
                    break;
                if (path.empty())
                {
                    OMPL_INFORM("%s: no path in the lattice (%zu nodes)", getName().c_str(), nodes_.size());
                    return ob::PlannerStatus::ABORT;
                }
                if (!checkEdges(path))
                    continue;
                auto solution = std::make_shared<og::PathGeometric>(si_);
                if (!makePath(path, *solution))
                    continue;
                rawPath_.clear();
                ob::State *s = si_->allocState();
                std::vector<double> values;
                for (Vertex v : path)
                {
                    setNodeState(v, s);
                    si_->getStateSpace()->copyToReals(values, s);
                    rawPath_.push_back(values);
                }
                si_->freeState(s);
                pdef_->addSolutionPath(solution, false, 0., getName());
                OMPL_INFORM("%s: path of %zu states, length %.4f", getName().c_str(), solution->getStateCount(),
                            solution->length());
                return ob::PlannerStatus::EXACT_SOLUTION;
            }
            return ob::PlannerStatus::TIMEOUT;
        }

        std::vector<std::pair<unsigned int, unsigned int>> HeadingLattice::latticeEdges() const
        {
            std::vector<std::pair<unsigned int, unsigned int>> edges;
            if (!built_)
                return edges;
            // per vertex (boost::edges() trips GCC's -Wmaybe-uninitialized inside Boost)
            for (std::size_t u = 0; u < nodes_.size(); ++u)
                for (const auto &e : boost::make_iterator_range(boost::out_edges(u, graph_)))
                {
                    const auto v = boost::target(e, graph_);
                    if (v < nodes_.size())
                        edges.emplace_back(static_cast<unsigned int>(u), static_cast<unsigned int>(v));
                }
            return edges;
        }

        void HeadingLattice::getPlannerData(ob::PlannerData &data) const
        {
            ob::Planner::getPlannerData(data);
            if (!built_)
                return;
            const std::size_t n = boost::num_vertices(graph_);
            // states for every vertex, owned here (PlannerData keeps pointers until decoupleFromPlanner())
            while (exportStates_.size() < n)
                exportStates_.push_back(si_->allocState());
            for (std::size_t v = 0; v < n; ++v)
                setNodeState(static_cast<unsigned int>(v), exportStates_[v]);
            const std::size_t lattice = nodes_.size();
            std::vector<unsigned int> index(n);
            for (std::size_t v = 0; v < n; ++v)
            {
                const int tag = v < lattice ? static_cast<int>(nodes_[v].heading) : -1;
                const ob::PlannerDataVertex vertex(exportStates_[v], tag);
                if (v >= lattice && queryIsStart_[v - lattice])
                    index[v] = data.addStartVertex(vertex);
                else if (v >= lattice)
                    index[v] = data.addGoalVertex(vertex);
                else
                    index[v] = data.addVertex(vertex);
            }
            for (std::size_t u = 0; u < n; ++u)
                for (const auto &e : boost::make_iterator_range(boost::out_edges(u, graph_)))
                    data.addEdge(index[u], index[boost::target(e, graph_)], ob::PlannerDataEdge(),
                                 ob::Cost(graph_[e].weight));
        }
    }  // namespace planners
}  // namespace michi
