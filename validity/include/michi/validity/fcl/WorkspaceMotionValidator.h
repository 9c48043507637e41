#ifndef MICHI_VALIDITY_WORKSPACE_MOTION_VALIDATOR_
#define MICHI_VALIDITY_WORKSPACE_MOTION_VALIDATOR_

#include <michi/validity/fcl/FclValidityChecker.h>

#include <ompl/base/MotionValidator.h>

namespace michi
{
    namespace validity
    {
        /** \brief Discrete motion validation at a resolution in metres: states are checked so that no point of
            the robot moves more than \e maxStep between two checks (CollisionBodies::bodyDisplacementBounds()
            gives the bound). OMPL's DiscreteMotionValidator spaces its checks by a fraction of the joint space
            instead, which at the end of an arm can be centimetres to decimetres. Only boolean collision queries
            are made, so it is cheap with meshes; obstacles thinner than maxStep can be missed near their
            corners, which ConservativeMotionValidator rules out at a higher price. Thread-safe. */
        class WorkspaceMotionValidator : public ompl::base::MotionValidator
        {
        public:
            WorkspaceMotionValidator(const ompl::base::SpaceInformationPtr &si, FclValidityCheckerPtr checker,
                                     double maxStep = 0.01);

            bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const override;
            bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                             std::pair<ompl::base::State *, double> &lastValid) const override;

            /** \brief Largest displacement of any robot point between two checks, metres. */
            void setMaxStep(double metres);
            double getMaxStep() const
            {
                return maxStep_;
            }
            /** \brief Number of checks a motion needs (at least 1: the end state). */
            unsigned int stepCount(const ompl::base::State *s1, const ompl::base::State *s2) const;

        private:
            FclValidityCheckerPtr checker_;
            double maxStep_;
        };
    }  // namespace validity
}  // namespace michi

#endif
