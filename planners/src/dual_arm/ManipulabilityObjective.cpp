#include <michi/planners/dual_arm/ManipulabilityObjective.h>

#include <ompl/base/goals/GoalRegion.h>

#include <algorithm>
#include <stdexcept>

namespace michi
{
    namespace planners
    {
        ManipulabilityObjective::ManipulabilityObjective(const ompl::base::SpaceInformationPtr &si,
                                                         Evaluator manipulability, double reference, double floor,
                                                         bool interpolate)
            : ompl::base::StateCostIntegralObjective(si, interpolate)
            , evaluator_(std::move(manipulability))
            , reference_(reference)
            , floor_(floor)
        {
            if (!(reference > 0.) || !(floor > 0.))
                throw std::invalid_argument("ManipulabilityObjective: reference and floor must be positive");
            description_ = "Manipulability";
            // Every state costs at least 1 per unit of length (see stateCost), so the distance to the goal region never
            // overestimates the cost to go.
            setCostToGoHeuristic(&ompl::base::goalRegionCostToGo);
        }

        ManipulabilityObjective::ManipulabilityObjective(const ompl::base::SpaceInformationPtr &si, const ArmChain &arm,
                                                         std::vector<int> stateVariables,
                                                         std::vector<double> fixedValues, ManipulabilityRows rows,
                                                         double reference, double floor, bool interpolate)
            : ManipulabilityObjective(
                  si,
                  // The state holds only the planned arm's joints; the rest of the robot (the other arm) stays at
                  // fixedValues.
                  [arm, stateVariables, fixedValues, rows, si](const ompl::base::State *s)
                  {
                      std::vector<double> reals;
                      si->getStateSpace()->copyToReals(reals, s);
                      std::vector<double> q = fixedValues;
                      for (std::size_t i = 0; i < stateVariables.size() && i < reals.size(); ++i)
                          q[stateVariables[i]] = reals[i];
                      return arm.manipulability(q, rows);
                  },
                  reference, floor, interpolate)
        {
            arm.requireRows(rows);
            if (fixedValues.size() != arm.model()->variableCount())
                throw std::invalid_argument("ManipulabilityObjective: fixed configuration has the wrong size");
            if (stateVariables.size() != si->getStateSpace()->getDimension())
                throw std::invalid_argument("ManipulabilityObjective: state variables do not match the space");
        }

        double ManipulabilityObjective::manipulability(const ompl::base::State *s) const
        {
            return evaluator_(s);
        }

        ompl::base::Cost ManipulabilityObjective::stateCost(const ompl::base::State *s) const
        {
            // Cost per unit of path length: 1 where w >= reference (paper 004's threshold, 0.0040), growing as
            // reference / w below it. The 1 keeps the objective a path length where manipulability is good (no detours
            // for nothing); floor_ keeps the cost finite at singular configurations (w = 0).
            return ompl::base::Cost(1. + weight_ * std::max(0., reference_ / std::max(evaluator_(s), floor_) - 1.));
        }

        void ManipulabilityObjective::setWeight(double weight)
        {
            if (!(weight > 0.))
                throw std::invalid_argument("ManipulabilityObjective: the weight must be positive");
            weight_ = weight;
        }

        ompl::base::Cost ManipulabilityObjective::motionCostHeuristic(const ompl::base::State *s1,
                                                                      const ompl::base::State *s2) const
        {
            // The cheapest a motion can be: length times the minimum state cost 1 (admissible for informed planners).
            return ompl::base::Cost(si_->distance(s1, s2));
        }
    }  // namespace planners
}  // namespace michi
