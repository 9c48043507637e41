#ifndef MICHI_PLANNERS_MANIPULABILITY_OBJECTIVE_
#define MICHI_PLANNERS_MANIPULABILITY_OBJECTIVE_

#include <michi/planners/dual_arm/Manipulability.h>

#include <ompl/base/objectives/StateCostIntegralObjective.h>

#include <functional>
#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief An OMPL optimization objective that makes planners prefer dexterous configurations: the cost
            of a state is 1 + weight * max(0, reference / w(state) - 1) (weight 1 by default: max(1, reference / w)),
           where w is the manipulability sqrt(det(J J^T)) of an arm (Yoshikawa), and the cost of a motion is that state
           cost integrated over the motion's length in the state space (OMPL's StateCostIntegralObjective: by default
           the trapezoid rule over the motion's two end states, which costs two evaluations of w per motion; with \e
           interpolate, the motion is subdivided at the space's collision-checking resolution, which is more exact for
           long motions and much slower). Where w >= reference a path costs its length; through less dexterous states it
           costs more, near a singularity much more. Since every cost is at least the path length, the state-space
           distance is an admissible heuristic (motionCostHeuristic, and the goal-region cost-to-go), so informed
           planners (BITstar, informed RRTstar) can use it. Use it with RRTstar, PRMstar, BITstar, ... like
           PathLengthOptimizationObjective.

            @par Short description
            Paper 004 (Takahama, Nagatani & Tanaka) chooses the stirring work position so that the small arm's
            manipulability stays above a threshold along the motion; this objective carries the same criterion
            into OMPL's optimizing planners, so the planned motion itself keeps w high.

            @par External documentation
            T. Yoshikawa, "Manipulability of robotic mechanisms", IJRR 4(2), 1985, doi:10.1177/027836498500400201.
            T. Takahama, K. Nagatani, Y. Tanaka, "Motion planning for dual manipulator with consideration of size
            and payload" (Japanese), see docs/dual-arm.md. */
        class ManipulabilityObjective : public ompl::base::StateCostIntegralObjective
        {
        public:
            /** \brief w(state) of the arm; must be thread-safe. */
            using Evaluator = std::function<double(const ompl::base::State *)>;

            /** \param reference the manipulability at which a state costs 1 per unit length (the paper's
                threshold, e.g. 0.004)
                \param floor w is clamped to at least this value, so singular states cost reference / floor */
            ManipulabilityObjective(const ompl::base::SpaceInformationPtr &si, Evaluator manipulability,
                                    double reference, double floor = 1e-6, bool interpolate = false);

            /** \brief The objective for an ArmChain planned over configuration indices \e stateVariables (the
                state's reals, in order), the other joints at \e fixedValues (a full configuration). */
            ManipulabilityObjective(const ompl::base::SpaceInformationPtr &si, const ArmChain &arm,
                                    std::vector<int> stateVariables, std::vector<double> fixedValues,
                                    ManipulabilityRows rows, double reference, double floor = 1e-6,
                                    bool interpolate = false);

            ompl::base::Cost stateCost(const ompl::base::State *s) const override;
            /** \brief The state-space distance (a lower bound: every state costs at least 1 per unit length). */
            ompl::base::Cost motionCostHeuristic(const ompl::base::State *s1,
                                                 const ompl::base::State *s2) const override;
            /** \brief w of a state. */
            double manipulability(const ompl::base::State *s) const;
            double reference() const
            {
                return reference_;
            }
            /** \brief How much less dexterous states cost: a state costs 1 + weight * max(0, reference / w - 1)
                per unit length (default 1: max(1, reference / w)). Must be positive. */
            void setWeight(double weight);
            double getWeight() const
            {
                return weight_;
            }

        private:
            Evaluator evaluator_;
            double reference_;
            double floor_;
            double weight_{1.};
        };
    }  // namespace planners
}  // namespace michi

#endif
