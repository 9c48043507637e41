#ifndef MICHI_VALIDITY_JMAP_MOTION_VALIDATOR_
#define MICHI_VALIDITY_JMAP_MOTION_VALIDATOR_

#include <michi/validity/jmap/JMapValidityChecker.h>

#include <ompl/base/MotionValidator.h>

#include <mutex>

namespace michi
{
    namespace validity
    {
        /** \brief Continuous motion validation on the J-map (paper 000): the straight motion between two states
            is a segment in the (theta1, theta2) plane, and it is free when the segment meets no polygon. The
            polygons contain every colliding state of their cells, so this is exact for the J-map and never lets
            a collision through, with no step size: a slab walk per tile the segment crosses (microseconds)
            replaces a walk of FCL queries. Continuous joints are followed the way OMPL's SO(2) interpolates them
            (the short way round, split at +-pi).
            - The checker answers alone (two joints, no self-collision possible): a segment that meets no polygon is
              valid, one that meets a polygon is invalid in conservative mode (last valid state just before the
              contact) and goes to \e fallback in exact_fallback mode.
            - The map is a pre-filter (more joints, or self-collisions possible): a contact is invalid in
              conservative mode; everything else goes to \e fallback (which checks the rest of the robot).
            The checker's tiles are built on demand, as for state queries. Thread-safe. */
        class JMapMotionValidator : public ompl::base::MotionValidator
        {
        public:
            /** \param checker the J-map checker installed as the space's state validity checker
                \param fallback the motion validator for what the map cannot decide (an FCL-based one) */
            JMapMotionValidator(const ompl::base::SpaceInformationPtr &si, JMapValidityCheckerPtr checker,
                                ompl::base::MotionValidatorPtr fallback);

            bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const override;
            bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                             std::pair<ompl::base::State *, double> &lastValid) const override;

            /** \brief First contact of the motion between two configurations (group values, as copyToReals
                gives them) with the map's polygons, as a fraction of the motion in [0, 1]; +infinity when the
                motion's (theta1, theta2) segment is free. */
            double firstContact(const double *from, const double *to) const;

            const ompl::base::MotionValidatorPtr &fallback() const
            {
                return fallback_;
            }

        private:
            /** \brief 0: free (decided), 1: contact (decided, at *contact), 2: ask the fallback. */
            int decide(const ompl::base::State *s1, const ompl::base::State *s2, double *contact) const;
            /** \brief decide(), then the fallback if needed; counts the motion; lastValid may be null. */
            bool check(const ompl::base::State *s1, const ompl::base::State *s2,
                       std::pair<ompl::base::State *, double> *lastValid) const;
            /** \brief Asks the space (once) whether it interpolates the axes round a circle. */
            void learnInterpolation() const;
            JMapValidityCheckerPtr checker_;
            ompl::base::MotionValidatorPtr fallback_;
            mutable std::once_flag learned_;
            mutable bool wraps1_{false}, wraps2_{false};  ///< the axes are continuous joints (SO(2) interpolation)
        };
    }  // namespace validity
}  // namespace michi

#endif
