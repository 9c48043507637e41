#ifndef MICHI_VALIDITY_CONSERVATIVE_MOTION_VALIDATOR_
#define MICHI_VALIDITY_CONSERVATIVE_MOTION_VALIDATOR_

#include <michi/validity/FclValidityChecker.h>

#include <ompl/base/MotionValidator.h>

namespace michi
{
    namespace validity
    {
        /** \brief Motion validation by conservative advancement: at a state with clearance c, no point of the
            robot can reach an obstacle before it has moved c, and CollisionBodies::displacementBound() says how
            far a joint-space step moves it. So the motion is walked in steps that are safe by construction, and
            the check is exact with respect to the scene: no obstacle is missed however thin, except within
            \e minClearanceStep of contact, where the walk advances by at most minClearanceStep of workspace motion
            per check (1 mm by default; OMPL's DiscreteMotionValidator instead steps by a fraction of the joint
            space, which can be centimetres at the end of an arm). Self-collision counts too: the step uses half the
            smallest robot-obstacle or robot-robot distance, since two bodies close in at most twice as fast as one
            moves. The interpolation is the space's own. Thread-safe. */
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
            /** \brief Relative error allowed in the distance queries (FCL's rel_err); the walk uses the lower
                bound d / (1 + r). Larger values make each query cheaper on meshes and each step shorter. */
            void setRelativeError(double r)
            {
                relativeError_ = r;
            }
            double getRelativeError() const
            {
                return relativeError_;
            }

        private:
            bool walk(const ompl::base::State *s1, const ompl::base::State *s2, double *lastValidTime) const;
            FclValidityCheckerPtr checker_;
            double minClearanceStep_{1e-3};
            double relativeError_{0.};
        };
    }
}

#endif
