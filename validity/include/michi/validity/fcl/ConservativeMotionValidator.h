#ifndef MICHI_VALIDITY_CONSERVATIVE_MOTION_VALIDATOR_
#define MICHI_VALIDITY_CONSERVATIVE_MOTION_VALIDATOR_

#include <michi/validity/fcl/FclValidityChecker.h>

#include <ompl/base/MotionValidator.h>

#include <atomic>

namespace michi
{
    namespace validity
    {
        /** \brief Exact motion validation by conservative advancement. At a state where body b is d_b from the
            nearest obstacle, nothing on b can reach an obstacle before b has moved d_b, and
            CollisionBodies::bodyDisplacementBounds() says how far b moves over the motion; self-check pairs close
            in at most as fast as the sum of their bounds. So the motion is walked in steps that cannot miss an
            obstacle, however thin; bodies that do not move cost nothing. Within \e minClearanceStep of contact the
            walk advances by at most minClearanceStep (1 mm) of displacement per check. Each step costs an FCL
            distance query per moving body, which is expensive against meshes: WorkspaceMotionValidator is the
            cheaper default. The interpolation is the space's own. Thread-safe. */
        class ConservativeMotionValidator : public ompl::base::MotionValidator
        {
        public:
            ConservativeMotionValidator(const ompl::base::SpaceInformationPtr &si, FclValidityCheckerPtr checker);

            bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const override;
            bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                             std::pair<ompl::base::State *, double> &lastValid) const override;

            void setMinClearanceStep(double metres)
            {
                minClearanceStep_ = metres;
            }
            double getMinClearanceStep() const
            {
                return minClearanceStep_;
            }

        private:
            bool walk(const ompl::base::State *s1, const ompl::base::State *s2, double *lastValidTime) const;
            /** Most clearance steps one motion may take; a motion that needs more is reported invalid. */
            static constexpr int MAX_WALK_STEPS = 100000;
            /** Most distance queries (bodies and self pairs, summed over the steps) one motion may take: bounds the
                walk of robots with very many bodies, whose every step is expensive. */
            static constexpr double MAX_WALK_QUERIES = 5e6;
            FclValidityCheckerPtr checker_;
            double minClearanceStep_{1e-3};
            mutable std::atomic<bool> warnedLongWalk_{false};
        };
    }  // namespace validity
}  // namespace michi

#endif
