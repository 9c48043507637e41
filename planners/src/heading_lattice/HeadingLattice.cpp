// HeadingLattice (paper 003): the planner's settings, setup, state and paths; the lattice itself is built and updated
// in HeadingLatticeBuild.cpp, searched in HeadingLatticeSearch.cpp.
#include <michi/planners/heading_lattice/HeadingLattice.h>
#include "HeadingLatticeCommon.h"

#include <michi/state_spaces/Angles.h>
#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/grid/GridValidityChecker.h>

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/goals/GoalStates.h>
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

        HeadingLattice::HeadingLattice(const ob::SpaceInformationPtr &si) : ob::Planner(si, "HeadingLattice")
        {
            specs_.approximateSolutions = false;
            specs_.optimizingPaths = false;
            specs_.multithreaded = false;
            specs_.directed = true;  // without reversing, lattice moves go forwards only
            specs_.recognizedGoal = ob::GOAL_SAMPLEABLE_REGION;

            declareParam<double>("cell_size", this, &HeadingLattice::setCellSize, &HeadingLattice::getCellSize,
                                 "0.:0.01:2.");
            declareParam<double>("angle_step", this, &HeadingLattice::setAngleStep, &HeadingLattice::getAngleStep,
                                 "0.05:0.01:1.57");
            declareParam<double>("connection_cells", this, &HeadingLattice::setConnectionCells,
                                 &HeadingLattice::getConnectionCells, "0.5:0.5:10.");
            declareParam<double>("heuristic_weight", this, &HeadingLattice::setHeuristicWeight,
                                 &HeadingLattice::getHeuristicWeight, "1.:0.05:3.");
            declareParam<bool>("shortcut", this, &HeadingLattice::setShortcut, &HeadingLattice::getShortcut, "0,1");
        }

        HeadingLattice::~HeadingLattice()
        {
            freeGraph();
        }

        void HeadingLattice::setCellSize(double size)
        {
            if (!(size >= 0.) || !std::isfinite(size))
                throw ompl::Exception(getName(), "cell_size must be positive, or 0 for automatic");
            cellSizeSetting_ = size;
            cellSize_ = size > 0. ? size : 0.25;  // the automatic choice is made by build()
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

        void HeadingLattice::setHeuristicWeight(double weight)
        {
            if (!(weight >= 1.) || !std::isfinite(weight))
                throw ompl::Exception(getName(), "heuristic_weight must be at least 1");
            heuristicWeight_ = weight;
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

        void HeadingLattice::freeQuery()
        {
            for (auto &q : queries_)
                si_->freeState(q.state);
            queries_.clear();
            direct_.clear();
            goalLinks_.clear();
        }

        void HeadingLattice::clearQuery()
        {
            freeQuery();
            rawPath_.clear();
            pis_.restart();
        }

        void HeadingLattice::freeGraph()
        {
            freeQuery();
            for (auto *s : exportStates_)
                si_->freeState(s);
            exportStates_.clear();
            if (scratch_ != nullptr)
                si_->freeState(scratch_);
            scratch_ = nullptr;
            for (auto *&m : motionScratch_)
            {
                if (m != nullptr)
                    si_->freeState(m);
                m = nullptr;
            }
            // groupFree_ and hGroups_ keep their memory: refilled (or restamped) by the next build, not paged in
            // again (Benchmark calls clear() before every run; on 64room they are 9 MB)
            groupFree_.clear();
            nodeState_.release();
            edgeState_.release();
            g_.release();
            parent_.release();
            stamp_.release();
            nodeIndex_.release();
            searchStamp_ = 0;
            hOpen_.clear();
            open_.clear();
            hReady_ = false;
            hGoals_.clear();
            nodeCount_ = groupCount_ = 0;
            built_ = false;
            rawPath_.clear();
            nodeListDirty_ = true;
        }

        void HeadingLattice::clear()
        {
            ob::Planner::clear();
            freeGraph();
            key_ = MapKey();
            boxes_.clear();
        }

        HeadingLattice::MapKey HeadingLattice::currentKey() const
        {
            MapKey key;
            key.checker = si_->getStateValidityChecker().get();
            key.motionValidator = si_->getMotionValidator().get();
            if (const auto *fcl =
                    dynamic_cast<const validity::FclValidityChecker *>(si_->getStateValidityChecker().get()))
                key.scene = fcl->scene().get();
            const auto *se2 = si_->getStateSpace()->as<ob::SE2StateSpace>();
            const auto &b = se2->getBounds();
            // the setting, not the spacing it resolved to: the same checker and scene resolve to the same spacing
            key.settings = {cellSizeSetting_, angleStep_, b.low[0], b.low[1], b.high[0], b.high[1]};
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

        void HeadingLattice::nodePosition(Vertex id, double &x, double &y) const
        {
            const std::uint32_t g = id / headings_;
            nodePosition(static_cast<long>(g / rows_), static_cast<long>(g % rows_), id % headings_, x, y);
        }

        void HeadingLattice::nodePosition(long i, long j, unsigned int k, double &x, double &y) const
        {
            const HeadingGeometry &r = geometry_[k];
            const double c = cellSize_;
            if (r.columns)
            {
                const double v = i * r.slope;
                x = x0_ + i * c;
                y = y0_ + c * (j + v - std::round(v));
            }
            else
            {
                const double v = j * r.slope;
                x = x0_ + c * (i + v - std::round(v));
                y = y0_ + j * c;
            }
        }

        void HeadingLattice::setNodeState(Vertex v, ob::State *state) const
        {
            if (isLattice(v))
            {
                double x, y;
                nodePosition(v, x, y);
                setState(state, x, y, geometry_[v % headings_].yaw);
            }
            else
                si_->copyState(state, queries_[v - nodeCount_].state);
        }

        bool HeadingLattice::nodeValid(Vertex id)
        {
            const std::uint8_t s = nodeState_[id];
            if (s != UNCHECKED && s != STALE)
                return s == VALID;
            const std::uint32_t g = id / headings_;
            return nodeValid(id, static_cast<long>(g / rows_), static_cast<long>(g % rows_), id % headings_);
        }

        bool HeadingLattice::nodeValid(Vertex id, long i, long j, unsigned int k)
        {
            std::uint8_t &s = nodeState_[id];
            if (s == UNCHECKED || s == STALE)
            {
                ++work_.nodeChecks;
                if (s == STALE)
                    ++work_.nodeRechecks;
                if (gridChecker_ != nullptr)
                {
                    // what satisfiesBounds() and isValid() of the node's state answer (a heading's yaw is inside
                    // SO(2)'s bounds), without the state: the 2-D heuristic's free-group tests make most node checks
                    double x, y;
                    nodePosition(i, j, k, x, y);
                    // RealVectorStateSpace::satisfiesBounds' tolerance
                    constexpr double EPS = std::numeric_limits<double>::epsilon();
                    const bool inside = !(x - EPS > xyBounds_[1] || x + EPS < xyBounds_[0] || y - EPS > xyBounds_[3] ||
                                          y + EPS < xyBounds_[2]);
                    const bool valid = inside && gridChecker_->isValidPose(x, y, geometry_[k].wrappedYaw);
                    s = valid ? VALID : INVALID;
                }
                else
                {
                    setNodeState(id, scratch_);
                    s = si_->satisfiesBounds(scratch_) && si_->isValid(scratch_) ? VALID : INVALID;
                }
                nodeListDirty_ = true;
            }
            return s == VALID;
        }

        int HeadingLattice::nodeStatusAt(double x, double y, unsigned int k) const
        {
            if (!built_ || k >= headings_)
                return 0;
            const long i = std::lround((x - x0_) / cellSize_), j = std::lround((y - y0_) / cellSize_);
            if (i < 0 || j < 0 || i >= static_cast<long>(columns_) || j >= static_cast<long>(rows_))
                return 0;
            return nodeState_.get((static_cast<std::size_t>(i) * rows_ + j) * headings_ + k);
        }

        std::int64_t HeadingLattice::driveNext(Vertex id) const
        {
            const std::uint32_t g = id / headings_;
            const unsigned int k = id % headings_;
            const long i = g / rows_, j = g % rows_;
            const HeadingGeometry &r = geometry_[k];
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
            if (ni < 0 || nj < 0 || ni >= static_cast<long>(columns_) || nj >= static_cast<long>(rows_))
                return -1;
            return (static_cast<std::int64_t>(ni) * rows_ + nj) * headings_ + k;
        }

        std::int64_t HeadingLattice::drivePrev(Vertex id) const
        {
            const std::uint32_t g = id / headings_;
            const unsigned int k = id % headings_;
            const long i = g / rows_, j = g % rows_;
            const HeadingGeometry &r = geometry_[k];
            long ni, nj;
            if (r.columns)
            {
                const long line = j - std::lround(i * r.slope);
                ni = i - r.forward;
                nj = line + std::lround(ni * r.slope);
            }
            else
            {
                const long line = i - std::lround(j * r.slope);
                nj = j - r.forward;
                ni = line + std::lround(nj * r.slope);
            }
            if (ni < 0 || nj < 0 || ni >= static_cast<long>(columns_) || nj >= static_cast<long>(rows_))
                return -1;
            return (static_cast<std::int64_t>(ni) * rows_ + nj) * headings_ + k;
        }

        void HeadingLattice::connectQueryState(QueryVertex &q)
        {
            // lattice nodes of the groups around the state within the radius, nearest (space's distance) first;
            // neither the nodes nor the joins are checked here: the search checks what it uses
            const auto *s = q.state->as<ob::SE2StateSpace::StateType>();
            q.nodes.clear();
            q.costs.clear();
            q.status.clear();
            std::vector<std::pair<double, Vertex>> candidates;
            const long span = static_cast<long>(std::ceil(q.radius / cellSize_)) + 1;
            const long ci = std::lround((s->getX() - x0_) / cellSize_);
            const long cj = std::lround((s->getY() - y0_) / cellSize_);
            for (long i = std::max(0L, ci - span); i <= std::min<long>(columns_ - 1, ci + span); ++i)
                for (long j = std::max(0L, cj - span); j <= std::min<long>(rows_ - 1, cj + span); ++j)
                    for (unsigned int k = 0; k < headings_; ++k)
                    {
                        const Vertex v = static_cast<Vertex>((i * rows_ + j) * headings_ + k);
                        double x, y;
                        nodePosition(v, x, y);
                        if (std::hypot(x - s->getX(), y - s->getY()) > q.radius)
                            continue;
                        setNodeState(v, scratch_);
                        candidates.emplace_back(
                            q.start ? si_->distance(q.state, scratch_) : si_->distance(scratch_, q.state), v);
                    }
            std::sort(candidates.begin(), candidates.end());
            for (const auto &cand : candidates)
            {
                q.nodes.push_back(cand.second);
                q.costs.push_back(cand.first);
                q.status.push_back(UNCHECKED);
            }
        }

        bool HeadingLattice::makePath(const std::vector<Vertex> &path, og::PathGeometric &out)
        {
            auto isTurn = [&](std::size_t p)
            {
                return isLattice(path[p]) && isLattice(path[p + 1]) && path[p] / headings_ == path[p + 1] / headings_;
            };
            auto countedCheck = [&](const ob::State *a, const ob::State *b)
            {
                ++work_.queryChecks;
                return si_->checkMotion(a, b);
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
                    const Node first = nodeOf(path[p]), final = nodeOf(path[e]);
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
                            setState(s, place.first, place.second, geometry_[path[r] % headings_].yaw);
                            good = countedCheck(prev, s);
                            run.push_back(s);
                            prev = s;
                        }
                        // and on to the next node (checked again from the place the next run chooses)
                        if (good && e + 1 < path.size())
                        {
                            setNodeState(path[e + 1], work);
                            good = countedCheck(prev, work);
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
                if (!countedCheck(last(), work))
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

        void HeadingLattice::shortcutPath(og::PathGeometric &path, const ob::PlannerTerminationCondition &ptc)
        {
            std::vector<ob::State *> &all = path.getStates();
            if (all.size() < 3)
                return;
            // The search below works on every state, also those in the middle of a straight run: a shortcut that
            // cuts a corner ends best part way along the next run (tried: runs merged to their ends first, which
            // saved checks but left the paths longer, docs/heading-lattice.md).
            const std::vector<ob::State *> states = all;
            const std::size_t n = states.size();
            // In a TurnMoveTurnStateSpace one motion of the space turns, drives and turns. In a plain SE(2) space a
            // motion interpolates position and yaw together (the robot would slide sideways while turning), so
            // there a shortcut is built as the lattice's own moves: turn in place to the drive's heading (or its
            // reverse where the lattice may reverse), drive straight, turn in place to the target's heading.
            const bool turnMoveTurn =
                dynamic_cast<const state_spaces::TurnMoveTurnStateSpace *>(si_->getStateSpace().get()) != nullptr;
            // length along the path up to each state: a shortcut i -> j is taken only when it is no longer than
            // the part it replaces (a turn-move-turn space is not metric, so this is not implied)
            std::vector<double> along(n, 0.);
            for (std::size_t k = 1; k < n; ++k)
                along[k] = along[k - 1] + si_->distance(states[k - 1], states[k]);
            ob::State *turnOut = si_->allocState(), *turnIn = si_->allocState();
            std::vector<ob::State *> via;  // the motion i -> j as states after i: [turnOut, turnIn,] j
            auto plan = [&](std::size_t i, std::size_t j)
            {
                via.clear();
                const auto *a = states[i]->as<ob::SE2StateSpace::StateType>();
                const auto *b = states[j]->as<ob::SE2StateSpace::StateType>();
                const double dx = b->getX() - a->getX(), dy = b->getY() - a->getY();
                if (!turnMoveTurn && std::hypot(dx, dy) > 1e-9)
                {
                    const double forwards = std::atan2(dy, dx), backwards = forwards + PI;  // setState() wraps
                    auto turn = [](double from, double to)
                    {
                        return std::abs(state_spaces::turnBetween(from, to));
                    };
                    double heading = forwards;
                    if (reversible_ && turn(a->getYaw(), backwards) + turn(backwards, b->getYaw()) <
                                           turn(a->getYaw(), forwards) + turn(forwards, b->getYaw()))
                        heading = backwards;
                    setState(turnOut, a->getX(), a->getY(), heading);
                    setState(turnIn, b->getX(), b->getY(), heading);
                    if (turn(a->getYaw(), heading) > 1e-12)
                        via.push_back(turnOut);
                    via.push_back(turnIn);
                    if (turn(heading, b->getYaw()) <= 1e-12)
                        via.back() = states[j];  // no turn at the end: the drive ends at j itself
                    else
                        via.push_back(states[j]);
                }
                else
                    via.push_back(states[j]);
            };
            auto joins = [&](std::size_t i, std::size_t j)
            {
                plan(i, j);
                double length = 0.;
                const ob::State *prev = states[i];
                for (const ob::State *v : via)
                {
                    length += si_->distance(prev, v);
                    prev = v;
                }
                if (length > along[j] - along[i] + 1e-9)
                    return false;
                prev = states[i];
                for (const ob::State *v : via)
                {
                    ++work_.shortcutChecks;
                    if (!si_->checkMotion(prev, v))
                        return false;
                    prev = v;
                }
                return true;
            };
            // Greedy from the start: from state i, the farthest j found by doubling the reach and then halving
            // between the last reach that joined and the first that did not. Whether i joins j is not monotone in
            // j, so this need not find the farthest j, but every motion taken is checked, and it costs a few
            // checks per kept state instead of one per pair.
            std::vector<ob::State *> out{states[0]};
            std::vector<char> used(n, 0);  // states that the new path keeps
            used[0] = 1;
            std::size_t i = 0;
            while (i + 1 < n)
            {
                if (ptc)
                {
                    // out of time: the rest of the path as it was
                    for (std::size_t k = i + 1; k < n; ++k)
                    {
                        out.push_back(states[k]);
                        used[k] = 1;
                    }
                    break;
                }
                std::size_t good = i + 1, bad = n;  // i joins good (a motion of the path); bad: past the end
                for (std::size_t reach = 2; i + reach < n; reach *= 2)
                {
                    if (!joins(i, i + reach))
                    {
                        bad = i + reach;
                        break;
                    }
                    good = i + reach;
                }
                if (bad == n && good != n - 1)
                {
                    if (joins(i, n - 1))
                        good = n - 1;
                    else
                        bad = n - 1;
                }
                while (bad - good > 1)
                {
                    const std::size_t mid = good + (bad - good) / 2;
                    if (joins(i, mid))
                        good = mid;
                    else
                        bad = mid;
                }
                if (good == i + 1)
                    out.push_back(states[good]);  // the path's own motion
                else
                {
                    plan(i, good);
                    for (ob::State *v : via)
                        out.push_back(v == states[good] ? v : si_->cloneState(v));
                }
                used[good] = 1;
                i = good;
            }
            si_->freeState(turnOut);
            si_->freeState(turnIn);
            for (std::size_t k = 0; k < n; ++k)
                if (!used[k])
                    si_->freeState(states[k]);
            all.swap(out);
        }

        ob::PlannerStatus HeadingLattice::solve(const ob::PlannerTerminationCondition &ptc)
        {
            checkValidity();
            if (!setup_)
                return ob::PlannerStatus::ABORT;  // not an SE(2) space (setup() said so)
            const WorkCounters before = work_;
            eagerTurns_ = false;  // turns lazy until one is refuted (turnFree())
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
                    OMPL_INFORM("%s: a different map or settings: laying out the lattice again", getName().c_str());
                // the query states are joined to the old lattice: take them in again
                clearQuery();
                build();
                key_ = key;
            }
            else
            {
                lastBuildTime_ = 0.;
                const std::uint64_t changes = checkerChanges();
                if (changes != sceneChanges_)
                {
                    update();
                    sceneChanges_ = changes;
                }
            }
            if (ptc)
                return ob::PlannerStatus::TIMEOUT;  // nothing checked yet

            const double radius = connectionCells_ * cellSize_;
            auto addQuery = [&](const ob::State *state, bool start)
            {
                QueryVertex q;
                q.state = si_->cloneState(state);
                q.start = start;
                q.radius = radius;
                connectQueryState(q);
                const auto v = static_cast<Vertex>(nodeCount_ + queries_.size());
                // a direct motion between a start and a goal that are close
                for (std::size_t o = 0; o < queries_.size(); ++o)
                {
                    if (queries_[o].start == start)
                        continue;
                    const ob::State *from = start ? state : queries_[o].state;
                    const ob::State *to = start ? queries_[o].state : state;
                    const double d = si_->distance(from, to);
                    const auto ov = static_cast<Vertex>(nodeCount_ + o);
                    if (d <= radius)
                        direct_.push_back(DirectEdge{start ? v : ov, start ? ov : v, d, UNCHECKED});
                }
                queries_.push_back(std::move(q));
            };
            while (const ob::State *st = pis_.nextStart())
                addQuery(st, true);
            if (std::none_of(queries_.begin(), queries_.end(),
                             [](const QueryVertex &q)
                             {
                                 return q.start;
                             }))
            {
                OMPL_ERROR("%s: no valid start state", getName().c_str());
                return ob::PlannerStatus::INVALID_START;
            }
            // Goals of fixed states that are all invalid: waiting cannot make one valid, and OMPL's nextGoal(ptc)
            // would wait for the whole time limit before the search said "no valid goal" (found 2026-12-07).
            {
                const ob::Goal *goal = pdef_->getGoal().get();
                bool fixed = false, anyValid = false;
                if (const auto *one = dynamic_cast<const ob::GoalState *>(goal))
                {
                    fixed = true;
                    anyValid = si_->isValid(one->getState());
                }
                else if (const auto *many = dynamic_cast<const ob::GoalStates *>(goal))
                {
                    fixed = true;
                    for (std::size_t i = 0; i < many->getStateCount() && !anyValid; ++i)
                        anyValid = si_->isValid(many->getState(i));
                }
                if (fixed && !anyValid)
                {
                    OMPL_ERROR("%s: no valid goal state", getName().c_str());
                    return ob::PlannerStatus::INVALID_GOAL;
                }
            }
            while (pis_.haveMoreGoalStates() && !ptc)
            {
                const ob::State *g = pis_.nextGoal(ptc);
                if (g == nullptr)
                    break;
                addQuery(g, false);
            }
            if (std::all_of(queries_.begin(), queries_.end(),
                            [](const QueryVertex &q)
                            {
                                return q.start;
                            }))
            {
                OMPL_ERROR("%s: no valid goal state", getName().c_str());
                return ob::PlannerStatus::INVALID_GOAL;
            }
            rebuildGoalLinks();

            while (!ptc)
            {
                prepareHeuristic();
                bool stopped = false;
                const std::vector<Vertex> path = search(ptc, stopped);
                if (stopped)
                    break;
                if (path.empty())
                {
                    // a start or goal none of whose joins is left: join it farther out (up to 3 doublings)
                    bool widened = false;
                    for (auto &q : queries_)
                    {
                        bool live = false;
                        for (std::size_t i = 0; i < q.nodes.size() && !live; ++i)
                            live = q.status[i] != INVALID && nodeState_.get(q.nodes[i]) != INVALID;
                        if (!live && q.attempts < 3)
                        {
                            q.radius *= 2.;
                            ++q.attempts;
                            connectQueryState(q);
                            widened = true;
                        }
                        else if (!live)
                            OMPL_WARN("%s: a %s cannot be joined to the lattice", getName().c_str(),
                                      q.start ? "start" : "goal");
                    }
                    if (widened)
                    {
                        rebuildGoalLinks();
                        continue;
                    }
                    OMPL_INFORM("%s: no path in the lattice (%llu nodes checked)", getName().c_str(),
                                static_cast<unsigned long long>(work_.nodeChecks));
                    return ob::PlannerStatus::ABORT;
                }
                if (!checkEdges(path, ptc, stopped))
                {
                    if (stopped)
                        break;
                    continue;
                }
                auto solution = std::make_shared<og::PathGeometric>(si_);
                if (!makePath(path, *solution))
                    continue;
                if (shortcut_)
                    shortcutPath(*solution, ptc);
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
                OMPL_INFORM(
                    "%s: path of %zu states, length %.4f (%llu searches, %llu expansions, %llu node and %llu "
                    "edge checks, %llu groups of the 2-D heuristic)",
                    getName().c_str(), solution->getStateCount(), solution->length(),
                    static_cast<unsigned long long>(work_.searches - before.searches),
                    static_cast<unsigned long long>(work_.expansions - before.expansions),
                    static_cast<unsigned long long>(work_.nodeChecks - before.nodeChecks),
                    static_cast<unsigned long long>(work_.edgeChecks - before.edgeChecks),
                    static_cast<unsigned long long>(work_.heuristicGroups - before.heuristicGroups));
                return ob::PlannerStatus::EXACT_SOLUTION;
            }
            return ob::PlannerStatus::TIMEOUT;
        }

        const std::vector<HeadingLattice::Node> &HeadingLattice::nodes() const
        {
            if (nodeListDirty_)
            {
                nodeList_.clear();
                nodeIndex_.assign(nodeCount_, ~0u);
                // only the pages of nodeState_ made so far hold checked nodes
                nodeState_.forEachPage(
                    [&](std::size_t first, const std::uint8_t *page)
                    {
                        for (std::size_t o = 0; o < nodeState_.PAGE && first + o < nodeCount_; ++o)
                            if (page[o] == VALID)
                            {
                                const auto v = static_cast<Vertex>(first + o);
                                nodeIndex_[v] = static_cast<std::uint32_t>(nodeList_.size());
                                nodeList_.push_back(nodeOf(v));
                            }
                    });
                nodeListDirty_ = false;
            }
            return nodeList_;
        }

        std::vector<std::pair<unsigned int, unsigned int>> HeadingLattice::latticeEdges() const
        {
            std::vector<std::pair<unsigned int, unsigned int>> edges;
            if (!built_)
                return edges;
            const auto &list = nodes();
            const unsigned int K = headings_;
            for (const Node &n : list)
            {
                const Vertex u = n.group * K + n.heading;
                const std::int64_t next = driveNext(u);
                if (next >= 0 && nodeState_.get(next) == VALID && (edgeState_.get(u) & 3) != INVALID)
                {
                    edges.emplace_back(nodeIndex_.get(u), nodeIndex_.get(next));
                    if (reversible_)
                        edges.emplace_back(nodeIndex_.get(next), nodeIndex_.get(u));
                }
                const Vertex up = (u / K) * K + (u % K + 1) % K;
                if (nodeState_.get(up) == VALID && (edgeState_.get(u) >> 2) != INVALID)
                {
                    edges.emplace_back(nodeIndex_.get(u), nodeIndex_.get(up));
                    edges.emplace_back(nodeIndex_.get(up), nodeIndex_.get(u));
                }
            }
            return edges;
        }

        void HeadingLattice::getPlannerData(ob::PlannerData &data) const
        {
            ob::Planner::getPlannerData(data);
            if (!built_)
                return;
            const auto &list = nodes();
            const std::size_t lattice = list.size(), n = lattice + queries_.size();
            // states for every vertex, owned here (PlannerData keeps pointers until decoupleFromPlanner())
            while (exportStates_.size() < n)
                exportStates_.push_back(si_->allocState());
            std::vector<unsigned int> index(n);
            for (std::size_t v = 0; v < lattice; ++v)
            {
                setState(exportStates_[v], list[v].x, list[v].y, geometry_[list[v].heading].yaw);
                index[v] = data.addVertex(ob::PlannerDataVertex(exportStates_[v], static_cast<int>(list[v].heading)));
            }
            for (std::size_t o = 0; o < queries_.size(); ++o)
            {
                si_->copyState(exportStates_[lattice + o], queries_[o].state);
                const ob::PlannerDataVertex vertex(exportStates_[lattice + o], -1);
                index[lattice + o] = queries_[o].start ? data.addStartVertex(vertex) : data.addGoalVertex(vertex);
            }
            for (const auto &e : latticeEdges())
            {
                const Node &a = list[e.first], &b = list[e.second];
                const double cost = a.group == b.group ? turnCost_ : geometry_[a.heading].length;
                data.addEdge(index[e.first], index[e.second], ob::PlannerDataEdge(), ob::Cost(cost));
            }
            for (std::size_t o = 0; o < queries_.size(); ++o)
            {
                const QueryVertex &q = queries_[o];
                for (std::size_t i = 0; i < q.nodes.size(); ++i)
                {
                    if (q.status[i] == INVALID || nodeState_.get(q.nodes[i]) != VALID)
                        continue;
                    const unsigned int node = index[nodeIndex_.get(q.nodes[i])], self = index[lattice + o];
                    data.addEdge(q.start ? self : node, q.start ? node : self, ob::PlannerDataEdge(),
                                 ob::Cost(q.costs[i]));
                }
            }
            for (const auto &d : direct_)
                if (d.status != INVALID)
                    data.addEdge(index[lattice + (d.from - nodeCount_)], index[lattice + (d.to - nodeCount_)],
                                 ob::PlannerDataEdge(), ob::Cost(d.cost));
        }
    }  // namespace planners
}  // namespace michi
