// DualRoadmap's task level (paper 002's hierarchical roadmap for arms): the hand's route through the task space, over
// the joint-space working roadmap, realised as joint states by Jacobian micro-motions. The upper level's grid is in
// TaskLevel; the search and the roadmaps are in DualRoadmap.cpp.
#include <michi/planners/dual_roadmap/DualRoadmap.h>

#include "TaskLevel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ob = ompl::base;

namespace michi
{
    namespace planners
    {
        void DualRoadmap::setTaskMap(TaskMap map)
        {
            taskMap_ = std::move(map);
            vertexHand_.clear();
        }

        const Eigen::Vector3d &DualRoadmap::handOf(Vertex v)
        {
            if (vertexHand_.size() <= v)
                vertexHand_.resize(graph_.vertexCount(),
                                   Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
            Eigen::Vector3d &hand = vertexHand_[v];
            if (std::isnan(hand.x()))
                taskMap_(graph_[v].state, hand, nullptr);
            return hand;
        }

        void DualRoadmap::moveHandTowards(std::vector<double> &q, const Eigen::Vector3d &target)
        {
            // Paper 002 links the task level to the joint level by the Jacobian of micro-motions, without inverting
            // it: dq = a J^T e for the hand's error e, with the step a that minimises |e - J dq| (the linear model's
            // best along J^T e). A few steps: a waypoint only guides the samples, the roadmap's checks decide.
            const auto &space = si_->getStateSpace();
            ob::State *state = probe_;
            Eigen::Vector3d hand;
            Eigen::MatrixXd jacobian;
            for (int iteration = 0; iteration < 3; ++iteration)
            {
                space->copyFromReals(state, q);
                taskMap_(state, hand, &jacobian);
                const Eigen::Vector3d error = target - hand;
                if (error.norm() < 0.25 * taskCell_ || jacobian.cols() != static_cast<Eigen::Index>(q.size()))
                    break;
                const Eigen::VectorXd direction = jacobian.transpose() * error;
                const Eigen::Vector3d moved = jacobian * direction;
                const double squared = moved.squaredNorm();
                if (!(squared > 1e-12))
                    break;
                double a = error.dot(moved) / squared;
                // no step longer than half a radian (or metre) in any joint: the linear model holds only nearby
                const double largest = a * direction.cwiseAbs().maxCoeff();
                if (largest > 0.5)
                    a *= 0.5 / largest;
                for (std::size_t j = 0; j < q.size(); ++j)
                    q[j] += a * direction(static_cast<Eigen::Index>(j));
            }
            space->copyFromReals(state, q);
            si_->enforceBounds(state);
            space->copyToReals(q, state);
        }

        void DualRoadmap::expandAlongTaskRoute(const ob::State *start, const ob::State *goal,
                                               const ob::PlannerTerminationCondition &ptc)
        {
            if (!task_)
                task_ = std::make_unique<TaskLevel>();
            if (!rng_)
                rng_ = std::make_unique<ompl::RNG>();
            // The upper level learns where the hand cannot go in this scene from the lower level's records: this
            // query's invalid samples (marked as they are drawn, kept for the query) and the working roadmap's
            // states proved valid or invalid in this scene (read afresh every round: validatePath() changes them).
            if (!taskBegun_)
            {
                // the query's ends' hands, once per query (its start and first goal do not change)
                Eigen::Vector3d from, to;
                taskMap_(start, from, nullptr);
                taskMap_(goal, to, nullptr);
                task_->begin(from, to, taskCell_, 0.3);
                taskBegun_ = true;
            }
            task_->beginRound();
            for (Vertex v = 0; v < graph_.vertexCount(); ++v)
            {
                const auto &p = graph_[v];
                if (p.validIn == epoch_)
                    task_->markRound(handOf(v), true);
                else if (p.invalidIn == epoch_)
                    task_->markRound(handOf(v), false);
            }
            std::vector<Eigen::Vector3d> route;
            // crossing a cell where the arm was found blocked costs as much as going 50 cells round it: nearly
            // impassable, yet a route exists while any cell is open
            if (!task_->route(50., route) || route.size() < 3)
                return;
            // Each end realises up to a quarter of the batch: waypoints evenly spaced along the route's interior,
            // jittered by half a cell so that repeated rounds realise different joint states.
            const std::size_t inner = route.size() - 2;
            const std::size_t count = std::min<std::size_t>(inner, std::max(1u, batchSize_ / 4));
            std::vector<Eigen::Vector3d> waypoints;
            for (std::size_t m = 1; m <= count; ++m)
            {
                const std::size_t at = 1 + (m * inner) / (count + 1);
                Eigen::Vector3d w = route[std::min(at, inner)];
                for (int a = 0; a < 3; ++a)
                    w[a] += 0.5 * taskCell_ * rng_->gaussian01();
                waypoints.push_back(w);
            }
            const auto &space = si_->getStateSpace();
            std::vector<double> q;
            for (int end = 0; end < 2 && !ptc; ++end)
            {
                // the start's chain goes forwards, the goal's backwards: they meet along the route
                space->copyToReals(q, end == 0 ? start : goal);
                for (std::size_t m = 0; m < waypoints.size() && !ptc; ++m)
                {
                    moveHandTowards(q, waypoints[end == 0 ? m : waypoints.size() - 1 - m]);
                    ob::State *state = si_->allocState();
                    space->copyFromReals(state, q);
                    ++work_.samples;
                    ++work_.stateChecks;
                    if (!si_->isValid(state))
                    {
                        Eigen::Vector3d hand;
                        taskMap_(state, hand, nullptr);
                        task_->mark(hand, false);
                        si_->freeState(state);
                        continue;
                    }
                    const Vertex v = addWorkingVertex(state, -1);
                    graph_[v].validIn = epoch_;
                    connectLazily(v);
                }
            }
        }
    }  // namespace planners
}  // namespace michi
