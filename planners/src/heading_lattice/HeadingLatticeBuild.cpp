// HeadingLattice, the lattice itself: its extent and groups from the space and the scene (build()), and what a
// scene change forgets (update(): only nodes and edges near the obstacles that moved). The planner's state, setup
// and paths are in HeadingLattice.cpp, the search in HeadingLatticeSearch.cpp.
#include <michi/planners/heading_lattice/HeadingLattice.h>
#include "HeadingLatticeCommon.h"

#include <michi/state_spaces/Angles.h>
#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/grid/GridValidityChecker.h>

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/util/Time.h>

#include <algorithm>
#include <sstream>
#include <cmath>
#include <limits>
#include <array>
#include <map>

namespace ob = ompl::base;

namespace michi
{
    namespace planners
    {
        const validity::Scene *HeadingLattice::checkedScene() const
        {
            const auto *checker = si_->getStateValidityChecker().get();
            if (const auto *fcl = dynamic_cast<const validity::FclValidityChecker *>(checker))
                return fcl->scene().get();
            if (const auto *grid = dynamic_cast<const validity::GridValidityChecker *>(checker))
                return grid->scene().get();
            return nullptr;
        }

        std::uint64_t HeadingLattice::checkerChanges() const
        {
            const auto *checker = si_->getStateValidityChecker().get();
            if (const auto *fcl = dynamic_cast<const validity::FclValidityChecker *>(checker))
                return fcl->scene() ? fcl->scene()->changeCount() : 0;
            // A grid checker answers from its table until refresh() rasterises the changed scene again: the
            // scene's own count would run ahead of what the nodes can be checked against.
            if (const auto *grid = dynamic_cast<const validity::GridValidityChecker *>(checker))
                return grid->refreshCount();
            return 0;
        }

        std::vector<HeadingLattice::ObstacleBox> HeadingLattice::sceneBoxes() const
        {
            std::vector<ObstacleBox> boxes;
            const validity::Scene *scene = checkedScene();
            if (scene == nullptr)
                return boxes;
            for (const auto &o : scene->obstacles())
            {
                ObstacleBox b{o.name, {INF, INF, -INF, -INF}};
                auto add = [&](const Eigen::Vector3d &local)
                {
                    const Eigen::Vector3d w = o.pose * local;
                    b.box[0] = std::min(b.box[0], w.x());
                    b.box[1] = std::min(b.box[1], w.y());
                    b.box[2] = std::max(b.box[2], w.x());
                    b.box[3] = std::max(b.box[3], w.y());
                };
                const auto &shape = *o.shape;
                if (shape.type() == validity::Shape::Type::PRISM)
                {
                    for (const auto &p : shape.outline())
                    {
                        add(Eigen::Vector3d(p.x(), p.y(), shape.size().x()));
                        add(Eigen::Vector3d(p.x(), p.y(), shape.size().y()));
                    }
                }
                else if (shape.type() == validity::Shape::Type::BOX)
                {
                    const Eigen::Vector3d h = 0.5 * shape.size();
                    for (int c = 0; c < 8; ++c)
                        add(Eigen::Vector3d((c & 1) ? h.x() : -h.x(), (c & 2) ? h.y() : -h.y(),
                                            (c & 4) ? h.z() : -h.z()));
                }
                else
                {
                    const double r = shape.boundingRadius();
                    const Eigen::Vector3d t = o.pose.translation();
                    b.box[0] = t.x() - r;
                    b.box[1] = t.y() - r;
                    b.box[2] = t.x() + r;
                    b.box[3] = t.y() + r;
                }
                if (!o.trajectory.empty())  // a moving obstacle: anywhere its key frames take it
                    for (const auto &kf : o.trajectory)
                    {
                        const double r = shape.boundingRadius();
                        const Eigen::Vector3d t = kf.pose.translation();
                        b.box[0] = std::min(b.box[0], t.x() - r);
                        b.box[1] = std::min(b.box[1], t.y() - r);
                        b.box[2] = std::max(b.box[2], t.x() + r);
                        b.box[3] = std::max(b.box[3], t.y() + r);
                    }
                boxes.push_back(std::move(b));
            }
            std::sort(boxes.begin(), boxes.end(),
                      [](const ObstacleBox &a, const ObstacleBox &b)
                      {
                          return a.name < b.name;
                      });
            return boxes;
        }

        double HeadingLattice::fclReach() const
        {
            // no point of the robot moves farther than pi R in a turn by pi (the robot's displacement bound)
            const auto *fcl = dynamic_cast<const validity::FclValidityChecker *>(si_->getStateValidityChecker().get());
            if (fcl == nullptr || !fcl->bodies())
                return 0.;
            const double from[3] = {0., 0., 0.}, to[3] = {0., 0., PI};
            return fcl->bodies()->displacementBound(from, to) / PI;
        }

        double HeadingLattice::automaticCellSize() const
        {
            // The map's cell and the robot's reach, from whichever of michi's checkers the space information has.
            double mapCell = 0., reach = fclReach();
            const auto *checker = si_->getStateValidityChecker().get();
            if (const auto *fcl = dynamic_cast<const validity::FclValidityChecker *>(checker))
                mapCell = fcl->scene() ? fcl->scene()->gridCellSize() : 0.;
            else if (const auto *grid = dynamic_cast<const validity::GridValidityChecker *>(checker))
            {
                if (grid->scene())
                    mapCell = grid->scene()->gridCellSize();
                for (const auto &p : grid->footprint())
                    reach = std::max(reach, p.norm());
            }
            // The paper's 0.25 m where nothing says the gaps are finer. On a map they are whole cells: with half a
            // cell between rows, a one-cell door has a row through its middle (a held-out rooms map of 0.1 m cells
            // and two-cell doors: 0.25 m left 8 of 20 scenarios unsolved, 0.05 m none). Not below the robot's reach:
            // a robot larger than the cells passes only gaps of several cells, and finer rows multiplied the nodes
            // (ros_office, 0.05 m cells, a 0.36 m reach: 0.18 m rows took 24 ms a query against 13 ms at 0.25 m).
            constexpr double paperCell = 0.25;
            if (!(mapCell > 0.))
                return paperCell;
            return std::min(paperCell, std::max(0.5 * mapCell, reach));
        }

        void HeadingLattice::build()
        {
            freeGraph();
            const ompl::time::point started = ompl::time::now();
            const auto *se2 = si_->getStateSpace()->as<ob::SE2StateSpace>();
            const auto &b = se2->getBounds();
            const auto *tmt = dynamic_cast<const state_spaces::TurnMoveTurnStateSpace *>(se2);
            reversible_ = tmt == nullptr || tmt->getAllowBackward();
            x0_ = b.low[0];
            y0_ = b.low[1];
            if (cellSizeSetting_ <= 0.)
                cellSize_ = automaticCellSize();
            const double c = cellSize_;
            // counted in doubles first: a tiny cell_size or angle_step would overflow the integer counts
            const double headings = std::max(4., std::round(2. * PI / angleStep_));
            const double columns = std::floor((b.high[0] - x0_) / c + 1e-9) + 1.;
            const double rows = std::floor((b.high[1] - y0_) / c + 1e-9) + 1.;
            const double ids = columns * rows * headings;
            if (!(ids < 2e9))
            {
                std::ostringstream what;
                what << "the lattice would have " << columns << " x " << rows << " cells x " << headings
                     << " headings, over 2e9 nodes: raise "
                     << (headings > columns * rows ? "angle_step (now " : "cell_size (now ")
                     << (headings > columns * rows ? angleStep_ : c) << ")";
                throw ompl::Exception(getName(), what.str());
            }
            headings_ = static_cast<unsigned int>(headings);
            columns_ = static_cast<unsigned int>(columns);
            rows_ = static_cast<unsigned int>(rows);
            groupCount_ = columns_ * rows_;
            nodeCount_ = groupCount_ * headings_;
            const unsigned int K = headings_;
            geometry_.resize(K);
            for (unsigned int k = 0; k < K; ++k)
            {
                const double theta = headingAngle(k);
                const double cs = std::cos(theta), sn = std::sin(theta);
                HeadingGeometry &r = geometry_[k];
                r.columns = std::abs(cs) >= std::abs(sn) - 1e-12;
                r.slope = r.columns ? sn / cs : cs / sn;
                r.forward = (r.columns ? cs : sn) > 0. ? 1 : -1;
                r.length = c / (r.columns ? std::abs(cs) : std::abs(sn));
                r.yaw = theta;
                r.wrappedYaw = wrapAngle(theta);
            }
            scratch_ = si_->allocState();
            for (auto *&m : motionScratch_)
                m = si_->allocState();
            {
                ob::State *other = si_->allocState();
                setState(scratch_, 0.5 * (b.low[0] + b.high[0]), 0.5 * (b.low[1] + b.high[1]), 0.);
                setState(other, 0.5 * (b.low[0] + b.high[0]), 0.5 * (b.low[1] + b.high[1]), 2. * PI / K);
                turnCost_ = si_->distance(scratch_, other);
                si_->freeState(other);
            }
            // how far the footprint reaches from the robot's origin; without FCL's bodies, any change resets
            // everything
            reach_ = fclReach();
            if (!(reach_ > 0.))
                reach_ = std::hypot(b.high[0] - b.low[0], b.high[1] - b.low[1]);
            // the straight-line heuristic is a lower bound as long as a turn edge (which shifts the position by
            // up to a cell between the headings' lattice points) costs at least the shift
            // (the same for the same cell size, headings and window: kept across clear(), which OMPL's Benchmark
            // calls before every run; on arena these 2 x 9,216 node positions were a fifth of a query)
            const std::array<double, 6> shiftKey{cellSize_,
                                                 static_cast<double>(K),
                                                 static_cast<double>(std::min(columns_, 24u)),
                                                 static_cast<double>(std::min(rows_, 24u)),
                                                 x0_,
                                                 y0_};
            if (shiftKey != shiftKey_)
            {
                double shift2 = 0.;
                for (unsigned int i = 0; i < std::min(columns_, 24u); ++i)
                    for (unsigned int j = 0; j < std::min(rows_, 24u); ++j)
                        for (unsigned int k = 0; k < K; ++k)
                        {
                            const Vertex probe = (i * rows_ + j) * K + k;
                            double ax, ay, bx, by;
                            nodePosition(probe, ax, ay);
                            nodePosition((i * rows_ + j) * K + (k + 1) % K, bx, by);
                            shift2 = std::max(shift2, (ax - bx) * (ax - bx) + (ay - by) * (ay - by));
                        }
                shift_ = std::sqrt(shift2);
                shiftKey_ = shiftKey;
            }
            const double shift = shift_;
            euclidWeight_ = shift > turnCost_ ? turnCost_ / shift : 1.;

            gridChecker_ = dynamic_cast<const validity::GridValidityChecker *>(si_->getStateValidityChecker().get());
            xyBounds_ = {b.low[0], b.high[0], b.low[1], b.high[1]};
            nodeState_.assign(nodeCount_, UNCHECKED);
            edgeState_.assign(nodeCount_, 0);
            groupFree_.assign(groupCount_, 0);
            hGroups_.resize(groupCount_, GroupEntry{std::numeric_limits<float>::infinity(), 0u});
            newHeuristicStamp();
            hReady_ = false;
            boxes_ = sceneBoxes();
            sceneChanges_ = checkerChanges();
            built_ = true;
            nodeListDirty_ = true;
            ++buildCount_;
            lastBuildTime_ = ompl::time::seconds(ompl::time::now() - started);
            OMPL_DEBUG("%s: lattice of %u x %u cells of %g m, %u headings (%u nodes, checked on demand; %.4f s)",
                       getName().c_str(), columns_, rows_, c, K, nodeCount_, lastBuildTime_);
        }

        void HeadingLattice::update()
        {
            std::vector<ObstacleBox> now = sceneBoxes();
            std::vector<std::array<double, 4>> changed;
            {
                std::map<std::string, const ObstacleBox *> before;
                for (const auto &o : boxes_)
                    before[o.name] = &o;
                for (const auto &o : now)
                {
                    auto it = before.find(o.name);
                    if (it == before.end() || !std::equal(o.box, o.box + 4, it->second->box))
                    {
                        changed.push_back({o.box[0], o.box[1], o.box[2], o.box[3]});
                        if (it != before.end())
                            changed.push_back(
                                {it->second->box[0], it->second->box[1], it->second->box[2], it->second->box[3]});
                    }
                    if (it != before.end())
                        before.erase(it);
                }
                for (const auto &kv : before)
                    changed.push_back({kv.second->box[0], kv.second->box[1], kv.second->box[2], kv.second->box[3]});
            }
            UpdateReport report;
            report.changedObstacles = changed.size();
            auto known = [](std::uint8_t status)
            {
                return status == VALID || status == INVALID;
            };
            auto knownEdges = [&](std::uint8_t e)
            {
                return static_cast<std::size_t>(known(e & 3)) + static_cast<std::size_t>(known(e >> 2));
            };
            // entries never written hold UNCHECKED / 0: only the pages made so far count
            nodeState_.forEachPage(
                [&](std::size_t first, const std::uint8_t *page)
                {
                    for (std::size_t v = 0; v < nodeState_.PAGE && first + v < nodeCount_; ++v)
                        report.nodesKnown += known(page[v]);
                });
            edgeState_.forEachPage(
                [&](std::size_t first, const std::uint8_t *page)
                {
                    for (std::size_t v = 0; v < edgeState_.PAGE && first + v < nodeCount_; ++v)
                        report.edgesKnown += knownEdges(page[v]);
                });
            // a node sees an obstacle within reach_ of its position (within half a cell of its group's point); its
            // drive reaches the next group, its turn stays at its position: 2.5 cells cover both
            const double margin = reach_ + 2.5 * cellSize_;
            const unsigned int K = headings_;
            for (const auto &box : changed)
            {
                const long i0 = std::max(0L, static_cast<long>(std::floor((box[0] - margin - x0_) / cellSize_)));
                const long j0 = std::max(0L, static_cast<long>(std::floor((box[1] - margin - y0_) / cellSize_)));
                const long i1 =
                    std::min<long>(columns_ - 1, static_cast<long>(std::ceil((box[2] + margin - x0_) / cellSize_)));
                const long j1 =
                    std::min<long>(rows_ - 1, static_cast<long>(std::ceil((box[3] + margin - y0_) / cellSize_)));
                for (long i = i0; i <= i1; ++i)
                    for (long j = j0; j <= j1; ++j)
                    {
                        const std::size_t g = static_cast<std::size_t>(i) * rows_ + j;
                        groupFree_[g] = 0;
                        for (unsigned int k = 0; k < K; ++k)
                        {
                            const std::size_t id = g * K + k;
                            if (!nodeState_.touched(id) && !edgeState_.touched(id))
                                continue;  // nothing known there
                            std::uint8_t &n = nodeState_[id], &e = edgeState_[id];
                            report.nodesReset += known(n);
                            report.edgesReset += knownEdges(e);
                            if (known(n))
                                n = STALE;
                            if (known(e & 3))
                                e = static_cast<std::uint8_t>((e & ~3) | STALE);
                            if (known(e >> 2))
                                e = static_cast<std::uint8_t>((e & 3) | (STALE << 2));
                        }
                    }
            }
            // joins of the query states are few: check them again
            for (auto &q : queries_)
                std::fill(q.status.begin(), q.status.end(), UNCHECKED);
            for (auto &d : direct_)
                d.status = UNCHECKED;
            resetHeuristic();
            hGoals_.clear();
            boxes_ = std::move(now);
            nodeListDirty_ = true;
            lastUpdate_ = report;
            ++updateCount_;
            OMPL_INFORM(
                "%s: the scene changed (%zu obstacle boxes): %zu of %zu checked nodes and %zu of %zu checked "
                "edges forgotten",
                getName().c_str(), report.changedObstacles, report.nodesReset, report.nodesKnown, report.edgesReset,
                report.edgesKnown);
        }
    }  // namespace planners
}  // namespace michi
