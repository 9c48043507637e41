#include <michi/planners/concentric_circle/ConcentricCircle.h>

#include <michi/planners/concentric_circle/CircleLifts.h>
#include "PathClearance.h"

#include <michi/validity/jmap/JMapValidityChecker.h>

#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/Exception.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace planners
    {
        ConcentricCircle::ConcentricCircle(const ob::SpaceInformationPtr &si) : ob::Planner(si, "ConcentricCircle")
        {
            specs_.approximateSolutions = false;
            specs_.optimizingPaths = false;
            specs_.multithreaded = false;
            specs_.directed = false;
            // The search needs one goal point on the map: a GoalState's state, else one state sampled from the region
            // (solve()).
            specs_.recognizedGoal = ob::GOAL_SAMPLEABLE_REGION;

            declareParam<double>("ring_spacing", this, &ConcentricCircle::setRingSpacing,
                                 &ConcentricCircle::getRingSpacing, "0.005:0.005:1.");
            declareParam<int>("divisions", this, &ConcentricCircle::setDivisions, &ConcentricCircle::getDivisions,
                              "8:4:720");
            declareParam<double>("point_spacing", this, &ConcentricCircle::setPointSpacing,
                                 &ConcentricCircle::getPointSpacing, "0.:0.01:1.");
            declareParam<double>("k_goal", this, &ConcentricCircle::setKGoal, &ConcentricCircle::getKGoal,
                                 "0.:0.1:100.");
            declareParam<double>("k_obstacle", this, &ConcentricCircle::setKObstacle, &ConcentricCircle::getKObstacle,
                                 "0.:0.0001:1.");
            declareParam<double>("potential_range", this, &ConcentricCircle::setPotentialRange,
                                 &ConcentricCircle::getPotentialRange, "0.:0.01:10.");
            declareParam<int>("max_arc_points", this, &ConcentricCircle::setMaxArcPoints,
                              &ConcentricCircle::getMaxArcPoints, "0:1:720");
            declareParam<bool>("arc_ends", this, &ConcentricCircle::setArcEnds, &ConcentricCircle::getArcEnds, "0,1");
            declareParam<int>("max_recursions", this, &ConcentricCircle::setMaxRecursions,
                              &ConcentricCircle::getMaxRecursions, "0:1:1000");
            declareParam<bool>("outer_rings", this, &ConcentricCircle::setOuterRings, &ConcentricCircle::getOuterRings,
                               "0,1");
            declareParam<int>("max_paths", this, &ConcentricCircle::setMaxPaths, &ConcentricCircle::getMaxPaths,
                              "1:1:1000");
            declareParam<std::string>("objective", this, &ConcentricCircle::setObjective,
                                      &ConcentricCircle::getObjective, "length,clearance");
            declareParam<std::string>("candidates", this, &ConcentricCircle::setCandidates,
                                      &ConcentricCircle::getCandidates, "michi,paper");
            // "select" names the same setting as "objective": which of the found paths is returned
            declareParam<std::string>("select", this, &ConcentricCircle::setObjective, &ConcentricCircle::getObjective,
                                      "length,clearance");
            declareParam<std::string>("mode", this, &ConcentricCircle::setMode, &ConcentricCircle::getMode,
                                      "auto,jmap,projection,hierarchy,surface");
            // the axes are values of this space's states: the declared range is what the setters accept
            const std::string lastValue =
                std::to_string(std::max<int>(1, static_cast<int>(si->getStateDimension())) - 1);
            declareParam<int>("axis1", this, &ConcentricCircle::setAxis1, &ConcentricCircle::getAxis1,
                              "0:1:" + lastValue);
            declareParam<int>("axis2", this, &ConcentricCircle::setAxis2, &ConcentricCircle::getAxis2,
                              "0:1:" + lastValue);
            declareParam<double>("surface_angle", this, &ConcentricCircle::setSurfaceAngle,
                                 &ConcentricCircle::getSurfaceAngle, "-3.15:0.05:3.15");
            declareParam<int>("hand_axis", this, &ConcentricCircle::setHandAxis, &ConcentricCircle::getHandAxis,
                              "-1:1:" + lastValue);
            declareParam<int>("arm_slices", this, &ConcentricCircle::setArmSlices, &ConcentricCircle::getArmSlices,
                              "0:1:100000");
            declareParam<double>("arm_tolerance", this, &ConcentricCircle::setArmTolerance,
                                 &ConcentricCircle::getArmTolerance, "0.001:0.001:0.5");
            declareParam<bool>("hand_in_bottleneck", this, &ConcentricCircle::setHandInBottleneck,
                               &ConcentricCircle::getHandInBottleneck, "0,1");
        }

        ConcentricCircle::~ConcentricCircle()
        {
            freePaths();
        }

        void ConcentricCircle::setObjective(const std::string &v)
        {
            if (v != "length" && v != "clearance")
                throw ompl::Exception(getName(), "objective must be 'length' or 'clearance', got '" + v + "'");
            objective_ = v;
        }

        void ConcentricCircle::setCandidates(const std::string &v)
        {
            if (v != "michi" && v != "paper")
                throw ompl::Exception(getName(), "candidates must be michi or paper, got '" + v + "'");
            settings_.candidates = v;
        }

        void ConcentricCircle::setMode(const std::string &v)
        {
            if (v != "auto" && v != "jmap" && v != "projection" && v != "hierarchy" && v != "surface")
                throw ompl::Exception(getName(),
                                      "mode must be auto, jmap, projection, hierarchy or surface, got '" + v + "'");
            mode_ = v;
        }

        void ConcentricCircle::setup()
        {
            ob::Planner::setup();
            // The J-map mode's map depends on the checker alone: its polygons are united and indexed here, once,
            // as OMPL's planners set up their structures in setup(); the other modes' maps depend on the query
            // (start, goal, plane) and are made in solve().
            jmapMap_.reset();
            jmapChecker_ = nullptr;
            if (mode_ == "auto" || mode_ == "jmap")
                refreshJMapMap();
        }

        void ConcentricCircle::freePaths()
        {
            for (auto &p : fullPaths_)
                for (auto *s : p)
                    si_->freeState(s);
            fullPaths_.clear();
            for (auto &p : stageStates_)
                for (auto *s : p)
                    si_->freeState(s);
            stageStates_.clear();
            bestPath_ = -1;
        }

        void ConcentricCircle::clear()
        {
            ob::Planner::clear();
            freePaths();
            stages_.clear();
            usedMode_.clear();
        }

        std::vector<ob::State *> ConcentricCircle::liftPath(const Stage &stage, std::size_t i, bool check)
        {
            const auto points = stage.search->pathPoints(i);
            std::vector<ob::State *> states;
            for (const auto &p : points)
            {
                states.push_back(si_->allocState());
                stage.lift(p, states.back());
            }
            bool ok = true;
            // check is only needed where the map's own links were not checked with the motion validator (the J-map's
            // segment-against-polygon test); the other maps' link tests already are the validator on these lifted
            // states.
            for (std::size_t j = 1; check && ok && j < states.size(); ++j)
                ok = si_->checkMotion(states[j - 1], states[j]);
            if (!ok)
            {
                for (auto *s : states)
                    si_->freeState(s);
                states.clear();
            }
            return states;
        }

        void ConcentricCircle::refreshJMapMap()
        {
            // Made again when the space has another checker, or the same J-map checker sees a changed scene (its
            // tiles are rebuilt then, so the united polygons would be stale).
            const auto *checker = si_->getStateValidityChecker().get();
            const auto *jmap = dynamic_cast<const validity::JMapValidityChecker *>(checker);
            const std::uint64_t generation = jmap ? jmap->fcl()->scene()->changeCount() : 0;
            if (checker == jmapChecker_ && generation == jmapGeneration_)
                return;
            jmapMap_ = makeJMapCircleMap(si_);
            jmapChecker_ = checker;
            jmapGeneration_ = generation;
        }

        void ConcentricCircle::refreshCapsules()
        {
            // As refreshJMapMap: another checker, or the same checker's scene changed, means other obstacles.
            const auto *checker = si_->getStateValidityChecker().get();
            const validity::FclValidityChecker *fcl = fclOf(*si_);
            const std::uint64_t generation = fcl ? fcl->scene()->changeCount() : 0;
            if (checker == capsuleChecker_ && generation == capsuleGeneration_)
                return;
            capsules_ = CapsuleClearance::make(*si_);
            capsuleChecker_ = checker;
            capsuleGeneration_ = generation;
        }

        bool ConcentricCircle::selectsClearance() const
        {
            // The problem's objective counts as well: a MaximizeMinClearanceObjective on the problem definition asks
            // every planner, this one included, for clearance (michi bench --objective clearance). A path-length
            // objective does not override the setting: OMPL's optimizing planners put one there by default.
            const auto &objective = pdef_ ? pdef_->getOptimizationObjective() : nullptr;
            return objective_ == "clearance" ||
                   dynamic_cast<const ob::MaximizeMinClearanceObjective *>(objective.get()) != nullptr;
        }

        double ConcentricCircle::pathCost(const std::vector<ob::State *> &states, double bound) const
        {
            if (!selectsClearance())
            {
                double len = 0.;
                for (std::size_t j = 1; j < states.size(); ++j)
                    len += si_->distance(states[j - 1], states[j]);
                return len;
            }
            // Negated clearances: as for length, a smaller cost is better and one ascending sort ranks both objectives.
            // The J-map mode measures clearance where its potential does, in the map plane (a slab walk per state);
            // the checker's clearance() is a workspace distance from FCL, about a hundred times dearer, and over
            // sixteen interpolated paths it cost more than the search.
            if (usedMode_ == "jmap")
                if (const auto *jmap =
                        dynamic_cast<const validity::JMapValidityChecker *>(si_->getStateValidityChecker().get()))
                    return -jmapPathClearance(*si_, *jmap, states, 1., -bound);
            // else the smallest clearance along the path (interpolated at the validity resolution)
            og::PathGeometric path(si_);
            for (auto *s : states)
                path.append(s);
            path.interpolate();
            double worst = std::numeric_limits<double>::infinity();
            const auto &checker = si_->getStateValidityChecker();
            for (auto *s : path.getStates())
            {
                worst = std::min(worst, checker->clearance(s));
                if (-worst >= bound)
                    break;  // it cannot beat the path that set the bound
            }
            return -worst;
        }

        bool ConcentricCircle::solveJMap(const std::vector<double> &start, const std::vector<double> &goal,
                                         const ob::PlannerTerminationCondition &ptc)
        {
            refreshJMapMap();
            const auto map = jmapMap_;
            if (!map)
                return false;
            Stage stage;
            stage.name = "jmap";
            stage.map = map;
            stage.lift = [this](const Eigen::Vector2d &p, ob::State *s)
            {
                setStateValues(*si_->getStateSpace(), {p.x(), p.y()}, s);
            };
            const Eigen::Vector2d s2(start[0], start[1]), g2(goal[0], goal[1]);
            // The J-map polygons are conservative (they contain the true collision region, paper 000): a valid start or
            // goal can lie inside them, and no circle search can leave such a point.
            if (!map->isFree(s2) || !map->isFree(g2))
            {
                OMPL_INFORM("%s: start or goal inside the J-map polygons; using the projection of the checker",
                            getName().c_str());
                return false;
            }
            stage.search = std::make_shared<ConcentricCircleSearch>(*map, settings_);
            bool found = stage.search->run(s2, g2, ptc);
            stages_.push_back(stage);
            // every path must pass the space's motion validator: drop links it rejects and look again
            // The polygons' segment test and the space's validator can disagree (the validator interpolates, the
            // polygons over-approximate). Each round drops every link a path uses that the validator rejects, then
            // collects the paths again (one collection per round, not per link: collecting re-runs the searches);
            // 200 rounds bound the work when the two disagree a lot.
            // A round that rejects nothing has checked every motion of every path: its lifted paths are the full
            // paths as they are (lifting and checking them once more cost the same again).
            std::vector<std::vector<ob::State *>> accepted;
            const auto freeAll = [this](std::vector<std::vector<ob::State *>> &paths)
            {
                for (auto &states : paths)
                    for (auto *s : states)
                        si_->freeState(s);
                paths.clear();
            };
            for (int round = 0; found && round < 200 && !ptc; ++round)
            {
                std::vector<std::pair<int, int>> rejected;
                std::vector<std::vector<ob::State *>> lifted;
                for (std::size_t i = 0; i < stage.search->paths().size(); ++i)
                {
                    const auto &nodes = stage.search->paths()[i];
                    lifted.push_back(liftPath(stage, i, false));
                    const auto &states = lifted.back();
                    for (std::size_t j = 1; j < states.size(); ++j)
                        if (!si_->checkMotion(states[j - 1], states[j]))
                            rejected.emplace_back(nodes[j - 1], nodes[j]);
                }
                if (rejected.empty())
                {
                    accepted = std::move(lifted);
                    break;
                }
                freeAll(lifted);
                for (const auto &link : rejected)
                    stage.search->removeLink(link.first, link.second);
                found = stage.search->collectPaths();
            }
            if (!found || ptc)
            {
                freeAll(accepted);
                return false;
            }
            if (!accepted.empty())
            {
                for (auto &states : accepted)
                    fullPaths_.push_back(std::move(states));
                return true;
            }
            // the rounds ran out with paths still rejected: only the paths whose every motion passes
            for (std::size_t i = 0; i < stage.search->paths().size(); ++i)
            {
                auto states = liftPath(stage, i, true);
                if (!states.empty())
                    fullPaths_.push_back(states);
            }
            return !fullPaths_.empty();
        }

        bool ConcentricCircle::solveProjection(const std::vector<double> &start, const std::vector<double> &goal,
                                               const ob::PlannerTerminationCondition &ptc)
        {
            auto projection = std::make_shared<ProjectionLift>(si_, start, goal, axis1_, axis2_);
            Stage stage;
            stage.name = "projection";
            stage.map = projection->makeMap();
            stage.lift = [projection](const Eigen::Vector2d &p, ob::State *s)
            {
                projection->lift(p, s);
            };
            stage.search = std::make_shared<ConcentricCircleSearch>(*stage.map, settings_);
            const bool found = stage.search->run(projection->start2(), projection->goal2(), ptc);
            stages_.push_back(stage);
            if (!found || ptc)
                return false;
            // every link of these paths was checked with the space's motion validator on the same states
            for (std::size_t i = 0; i < stage.search->paths().size(); ++i)
                fullPaths_.push_back(liftPath(stage, i, false));
            return !fullPaths_.empty();
        }

        bool ConcentricCircle::solveHierarchy(const std::vector<double> &start, const std::vector<double> &goal,
                                              const ob::PlannerTerminationCondition &ptc)
        {
            const int n = static_cast<int>(start.size());
            int hand = handAxis_;
            // hand_axis -1: the first value that is neither arm axis is the hand (paper 000's planar example: 2 arm
            // joints, 1 hand).
            for (int v = 0; hand < 0 && v < n; ++v)
                if (v != axis1_ && v != axis2_)
                    hand = v;
            if (hand < 0 || hand >= n || hand == axis1_ || hand == axis2_)
            {
                OMPL_ERROR("%s: hierarchy mode needs a hand value that is neither axis1 nor axis2", getName().c_str());
                return false;
            }
            // 1. the arm: its own map (without the hand's links when the robot is a planar arm)
            auto arm = std::make_shared<ProjectionLift>(si_, start, goal, axis1_, axis2_);
            Stage armStage;
            armStage.name = "arm";
            std::vector<int> others;
            for (int v = 0; v < n; ++v)
                if (v != axis1_ && v != axis2_)
                    others.push_back(v);
            const ArmMaps armMaps = makeArmMaps(si_, *arm, others, armSlices_, armTolerance_, &ptc);
            if (ptc)
                return false;  // out of time while the arm's J-map was built
            armStage.map = armMaps.map;
            armMapKind_ = armMaps.kind;
            if (armSlices_ > 0 && armMaps.kind == "capsules")
                OMPL_INFORM(
                    "%s: the arm's start or goal lies inside its J-map polygons (%d slices); the arm is planned "
                    "on the exact capsule geometry instead",
                    getName().c_str(), armSlices_);
            armStage.lift = [arm](const Eigen::Vector2d &p, ob::State *s)
            {
                arm->lift(p, s);
            };
            armStage.search = std::make_shared<ConcentricCircleSearch>(*armStage.map, settings_);
            const bool armFound = armStage.search->run(arm->start2(), arm->goal2(), ptc);
            stages_.push_back(armStage);
            if (!armFound || ptc)
                return false;
            // 2. along each arm path (shortest first): the hand map, arm-path arc length x hand value
            for (std::size_t i = 0; i < armStage.search->paths().size() && !ptc; ++i)
            {
                const auto armPath = armStage.search->pathPoints(i);
                // Paper 000, section 3.3: the hand needs a map only where the arm path crosses the bottleneck;
                // elsewhere the arm is farther from every obstacle than the hand reaches, so the hand keeps its start
                // value before that stretch and its goal value after it. The window is the stretch from the first to
                // the last point of the path in the grown map (sampled every 0.005 rad, widened by two samples).
                double from = 0., to = -1.;
                if (handInBottleneck_ && armMaps.inGrown)
                {
                    const double step = 0.005;
                    double s = 0., first = -1., last = -1.;
                    for (std::size_t k = 1; k < armPath.size(); ++k)
                    {
                        const double len = (armPath[k] - armPath[k - 1]).norm();
                        const int m = std::max(1, static_cast<int>(std::ceil(len / step)));
                        for (int j = k == 1 ? 0 : 1; j <= m; ++j)
                        {
                            const double f = static_cast<double>(j) / m;
                            if (armMaps.inGrown(armPath[k - 1] + f * (armPath[k] - armPath[k - 1])))
                            {
                                if (first < 0.)
                                    first = s + f * len;
                                last = s + f * len;
                            }
                        }
                        s += len;
                    }
                    if (first >= 0.)
                    {
                        from = std::max(0., first - 2. * step);
                        to = std::min(s, last + 2. * step);
                    }
                }
                if (solveHand(start, goal, hand, i, armPath, from, to, ptc))
                    return true;
                // The hand's turn outside the window can fail where the grown map says nothing (a self-collision of
                // the hand with the arm): the whole arm path then, as without the bottleneck.
                if ((from > 0. || to >= 0.) && !ptc && solveHand(start, goal, hand, i, armPath, 0., -1., ptc))
                    return true;
            }
            return false;
        }

        bool ConcentricCircle::solveHand(const std::vector<double> &start, const std::vector<double> &goal, int hand,
                                         std::size_t armPathIndex, const std::vector<Eigen::Vector2d> &armPath,
                                         double from, double to, const ob::PlannerTerminationCondition &ptc)
        {
            const std::size_t i = armPathIndex;
            auto handLift = std::make_shared<HandLift>(si_, start, goal, axis1_, axis2_, hand, armPath, from, to);
            Stage handStage;
            handStage.name = "hand";
            handStage.map = handLift->makeMap();
            handStage.lift = [handLift](const Eigen::Vector2d &p, ob::State *s)
            {
                handLift->lift(p, s);
            };
            handStage.search = std::make_shared<ConcentricCircleSearch>(*handStage.map, settings_);
            const bool handFound = handStage.search->run(handLift->start2(), handLift->goal2(), ptc);
            if (!handFound)
            {
                // keep the first failed hand map for pictures and diagnostics
                if (stages_.size() == 1)
                    stages_.push_back(handStage);
                return false;
            }
            // Only the arm stage and the solved hand stage are kept, so stages_.back() is the search that produced
            // the solution.
            stages_.resize(1);
            stages_[0].chosenPath = static_cast<int>(i);
            stages_.push_back(handStage);
            // Before the window the hand turns to its goal value, after it it holds still, while the arm moves:
            // those motions were not part of the hand map, so they are checked here (a path whose outside part
            // fails is left out).
            const auto before = handLift->outsideBefore(), after = handLift->outsideAfter();
            for (std::size_t j = 0; j < handStage.search->paths().size(); ++j)
            {
                std::vector<Eigen::Vector2d> points = before;
                const auto inside = handStage.search->pathPoints(j);
                points.insert(points.end(), inside.begin(), inside.end());
                points.insert(points.end(), after.begin(), after.end());
                std::vector<ob::State *> states;
                for (const auto &q : points)
                {
                    states.push_back(si_->allocState());
                    handLift->lift(q, states.back());
                }
                bool ok = true;
                for (std::size_t k = 1; ok && k <= before.size() && k < states.size(); ++k)
                    ok = si_->checkMotion(states[k - 1], states[k]);
                for (std::size_t k = states.size() - after.size(); ok && k < states.size(); ++k)
                    ok = k == 0 || si_->checkMotion(states[k - 1], states[k]);
                if (ok)
                    fullPaths_.push_back(std::move(states));
                else
                    for (auto *st : states)
                        si_->freeState(st);
            }
            if (!fullPaths_.empty())
                return true;
            stages_.pop_back();
            return false;
        }

        bool ConcentricCircle::solveSurface(const std::vector<double> &start, const std::vector<double> &goal,
                                            const ob::PlannerTerminationCondition &ptc)
        {
            // the plane at surface_angle, then turned by 45, 90 and 135 degrees (angle and angle + pi give the same
            // plane); the paper leaves switching surfaces open
            for (int k = 0; k < 4 && !ptc; ++k)
            {
                auto surface = std::make_shared<SurfaceLift>(si_, start, goal, surfaceAngle_ + k * M_PI / 4.);
                Stage stage;
                stage.name = "surface";
                stage.map = surface->makeMap();
                stage.lift = [surface](const Eigen::Vector2d &p, ob::State *s)
                {
                    surface->lift(p, s);
                };
                stage.search = std::make_shared<ConcentricCircleSearch>(*stage.map, settings_);
                const bool found = stage.search->run(surface->start2(), surface->goal2(), ptc);
                // Only the last plane tried is kept: pictures and PlannerData show the plane that gave the answer (or
                // the last that failed).
                stages_.clear();
                stages_.push_back(stage);
                if (!found)
                    continue;
                for (std::size_t i = 0; i < stage.search->paths().size(); ++i)
                    fullPaths_.push_back(liftPath(stage, i, false));
                return true;
            }
            return false;
        }

        ob::PlannerStatus ConcentricCircle::solve(const ob::PlannerTerminationCondition &ptc)
        {
            checkValidity();
            // Every solve plans from the problem's start afresh (no tree is kept between solves), so the input
            // states are read again: OMPL's PlannerInputStates hands each state out once, and a second solve()
            // without clear() (SimpleSetup::solve twice, a retry with more time) found no start at all.
            pis_.restart();
            const ob::State *startState = pis_.nextStart();
            if (startState == nullptr)
            {
                OMPL_ERROR("%s: no valid start state", getName().c_str());
                return ob::PlannerStatus::INVALID_START;
            }
            const ob::State *goalState = nullptr;
            const auto goal = pdef_->getGoal();
            // A goal region gives one sampled state: the circles need one point for the goal, and the method's
            // result does not improve with more of them.
            if (auto *gs = dynamic_cast<ob::GoalState *>(goal.get()))
                goalState = gs->getState();
            else
                goalState = pis_.nextGoal(ptc);
            if (goalState == nullptr || !si_->isValid(goalState))
            {
                OMPL_ERROR("%s: no valid goal state", getName().c_str());
                return ob::PlannerStatus::INVALID_GOAL;
            }
            if (ptc)
                return ob::PlannerStatus::TIMEOUT;

            freePaths();
            stages_.clear();
            std::vector<double> start, goalValues;
            si_->getStateSpace()->copyToReals(start, startState);
            si_->getStateSpace()->copyToReals(goalValues, goalState);
            const int n = static_cast<int>(start.size());
            if (axis1_ < 0 || axis2_ < 0 || axis1_ >= n || axis2_ >= n || axis1_ == axis2_)
            {
                OMPL_ERROR("%s: axis1 = %d and axis2 = %d must be two different values of the %d-value state",
                           getName().c_str(), axis1_, axis2_, n);
                return ob::PlannerStatus::ABORT;
            }

            bool found = false;
            usedMode_ = mode_;
            if (mode_ == "jmap" || mode_ == "auto")
            {
                // Mode order in auto: the J-map polygons when the checker has them (the paper's own map, with exact
                // visibility), else for 3 or more values the arm -> hand hierarchy (planar arms) or the restriction
                // surface, else the 2-D projection.
                // the map made in setup() (made again only for another checker or a changed scene): uniting the
                // polygons here in every solve cost about a sixth of a planar_2link solve
                bool possible = false;
                if (n == 2 && axis1_ == 0 && axis2_ == 1)
                {
                    refreshJMapMap();
                    possible = jmapMap_ != nullptr;
                }
                if (possible)
                {
                    usedMode_ = "jmap";
                    found = solveJMap(start, goalValues, ptc);
                }
                else if (mode_ == "jmap")
                    OMPL_WARN("%s: mode jmap needs a 2-value space checked by a JMapValidityChecker; using projection",
                              getName().c_str());
                if (!found && !ptc)
                {
                    freePaths();
                    stages_.clear();
                    usedMode_ =
                        (mode_ == "auto" && n >= 3) ? (isPlanarArm(si_) ? "hierarchy" : "surface") : "projection";
                }
            }
            else
                usedMode_ = mode_;
            if (!found && !ptc)
            {
                if (usedMode_ == "hierarchy" && n >= 3)
                {
                    found = solveHierarchy(start, goalValues, ptc);
                    if (!found && !ptc && mode_ == "auto")
                    {
                        // the arm -> hand split found nothing: the restriction surface through start and goal
                        freePaths();
                        usedMode_ = "surface";
                        found = solveSurface(start, goalValues, ptc);
                    }
                }
                else if (usedMode_ == "surface" && n >= 3)
                    found = solveSurface(start, goalValues, ptc);
                else
                {
                    usedMode_ = "projection";
                    found = solveProjection(start, goalValues, ptc);
                }
                if (!found && !ptc && mode_ == "auto" && usedMode_ == "surface")
                {
                    // Nor did the restriction planes: the 2-D projection is the last map auto tries. On a plain
                    // SE(2) space with start and goal at one heading the planes found nothing where the projection
                    // of x and y solves at once (found 2026-12-07).
                    freePaths();
                    usedMode_ = "projection";
                    found = solveProjection(start, goalValues, ptc);
                }
            }
            if (!found)
            {
                if (ptc)
                    return ob::PlannerStatus::TIMEOUT;
                OMPL_WARN("%s: no path (mode %s, %d recursions)", getName().c_str(), usedMode_.c_str(),
                          stages_.empty() ? 0 : stages_.back().search->recursions());
                return ob::PlannerStatus::ABORT;
            }
            // the first and last states are the exact start and goal
            for (auto &p : fullPaths_)
            {
                // The lift of the start and goal points can differ from the given states in the last bits
                // (enforceBounds, wrapping): OMPL checks that a solution starts at the start and reaches the goal.
                si_->copyState(p.front(), startState);
                si_->copyState(p.back(), goalState);
            }
            // the best path whose every motion the space's motion validator accepts (checked again here, with
            // the exact start and goal states)
            // First the best alone: each path is measured only until it cannot beat the best so far (measuring all
            // sixteen in full was a tenth of a J-map solve with the clearance objective). Equal costs keep the
            // search's order, as the full ranking below does.
            double bestCost = std::numeric_limits<double>::infinity();
            for (std::size_t i = 0; i < fullPaths_.size(); ++i)
            {
                const double cost = pathCost(fullPaths_[i], bestCost);
                if (cost < bestCost)
                {
                    bestCost = cost;
                    bestPath_ = static_cast<int>(i);
                }
            }
            for (std::size_t j = 1; bestPath_ >= 0 && j < fullPaths_[bestPath_].size(); ++j)
                if (!si_->checkMotion(fullPaths_[bestPath_][j - 1], fullPaths_[bestPath_][j]))
                    bestPath_ = -1;
            // the best failed the motion validator: every path measured in full and ranked
            std::vector<std::pair<double, int>> ranked;
            for (std::size_t i = 0; bestPath_ < 0 && i < fullPaths_.size(); ++i)
                ranked.emplace_back(pathCost(fullPaths_[i]), static_cast<int>(i));
            // stable: equal costs keep the search's order, so the same problem always gives the same path.
            std::stable_sort(ranked.begin(), ranked.end(),
                             [](const std::pair<double, int> &a, const std::pair<double, int> &b)
                             {
                                 return a.first < b.first;
                             });
            for (const auto &r : ranked)
            {
                const auto &states = fullPaths_[r.second];
                bool ok = true;
                for (std::size_t j = 1; ok && j < states.size(); ++j)
                    ok = si_->checkMotion(states[j - 1], states[j]);
                if (ok)
                {
                    bestPath_ = r.second;
                    break;
                }
                OMPL_WARN("%s: path %d failed the motion validator", getName().c_str(), r.second);
            }
            if (bestPath_ < 0)
                return ob::PlannerStatus::ABORT;
            if (!stages_.empty())
                stages_.back().chosenPath = bestPath_;
            // Safe paths (paper 000's aim): asked for clearance, the chosen path's points move away from the
            // obstacles, each move kept only if its state and motions stay valid.
            if (selectsClearance())
            {
                refreshCapsules();
                ClearanceFunction measure;
                if (capsules_)
                    measure = [this, values = std::vector<double>()](const ob::State *s) mutable
                    {
                        si_->getStateSpace()->copyToReals(values, s);
                        return capsules_->at(values.data());
                    };
                splitDirectLink(si_, fullPaths_[bestPath_]);
                pushAwayFromObstacles(si_, fullPaths_[bestPath_], ptc, measure);
            }
            auto path = std::make_shared<og::PathGeometric>(si_);
            for (auto *s : fullPaths_[bestPath_])
                path->append(s);
            pdef_->addSolutionPath(path, false, 0., getName());
            OMPL_INFORM("%s: %zu paths (mode %s), solution has %zu states", getName().c_str(), fullPaths_.size(),
                        usedMode_.c_str(), path->getStateCount());
            return ob::PlannerStatus::EXACT_SOLUTION;
        }

        void ConcentricCircle::getPlannerData(ob::PlannerData &data) const
        {
            ob::Planner::getPlannerData(data);
            // the states stay with the planner (PlannerData keeps pointers) until the next solve or clear()
            // getPlannerData() is const but must hand out states: they are lifted once, on the first call after a
            // solve, and kept in the mutable stageStates_ so repeated calls do not leak or duplicate them.
            const bool build = stageStates_.empty();
            for (std::size_t k = 0; k < stages_.size(); ++k)
            {
                const auto &stage = stages_[k];
                const auto &nodes = stage.search->nodes();
                if (build)
                {
                    std::vector<ob::State *> lifted;
                    for (const auto &node : nodes)
                    {
                        lifted.push_back(si_->allocState());
                        stage.lift(node.p, lifted.back());
                    }
                    stageStates_.push_back(std::move(lifted));
                }
                const std::vector<ob::State *> &states = stageStates_[k];
                const unsigned int tag = static_cast<unsigned int>(k);
                for (std::size_t v = 0; v < states.size(); ++v)
                {
                    // Node 0 and node 1 of every search are its start and goal (ConcentricCircleSearch's convention).
                    if (v == 0)
                        data.addStartVertex(ob::PlannerDataVertex(states[v], tag));
                    else if (v == 1)
                        data.addGoalVertex(ob::PlannerDataVertex(states[v], tag));
                    else
                        data.addVertex(ob::PlannerDataVertex(states[v], tag));
                }
                for (const auto &link : stage.search->links())
                {
                    const ob::PlannerDataVertex a(states[link.first], tag), b(states[link.second], tag);
                    const ob::Cost c(si_->distance(states[link.first], states[link.second]));
                    data.addEdge(a, b, ob::PlannerDataEdge(), c);
                    data.addEdge(b, a, ob::PlannerDataEdge(), c);
                }
            }
        }
    }  // namespace planners
}  // namespace michi
