#ifndef MICHI_VALIDITY_SPHERES_SPHERE_MOTION_VALIDATOR_
#define MICHI_VALIDITY_SPHERES_SPHERE_MOTION_VALIDATOR_

#include <michi/validity/spheres/SphereValidityChecker.h>

#include <ompl/base/MotionValidator.h>

#include <atomic>

namespace michi
{
    namespace validity
    {
        /** \brief Certified motion checks with the sphere model: no sampling gap. A piece of the motion is
            checked at its middle with every sphere grown by how far the sphere's centre can move over half the
            piece (the sum over joints of the sphere's displacement coefficient times the joint's change, which
            holds for any configuration); if the grown spheres are free, no configuration of the piece can touch
            anything. Otherwise the piece is halved, until a middle is in collision (the motion is rejected) or the
            pieces get shorter than \e minFraction of the motion (rejected too: the motion grazes an obstacle).
            A motion it accepts is free for the enclosing spheres, hence for the real geometry. Where the spheres
            touch something the real geometry does not (a hand at its grasp, a link a few millimetres from
            another), halving cannot help: when the checker has an FCL checker, such a piece is decided by
            WorkspaceMotionValidator on the real geometry (checks at most 1 cm of robot motion apart, as the FCL
            checker's default motions): only those pieces are not certified. Interpolation is the state space's;
            continuous joints are measured the short way round, as the space interpolates. */
        class SphereMotionValidator : public ompl::base::MotionValidator
        {
        public:
            SphereMotionValidator(const ompl::base::SpaceInformationPtr &si, SphereValidityCheckerPtr checker,
                                  double minFraction = 1. / 65536.);

            bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const override;
            bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                             std::pair<ompl::base::State *, double> &lastValid) const override;

            /** \brief Grown-sphere checks made so far (all threads). */
            std::uint64_t checkCount() const
            {
                return checks_.load();
            }

        private:
            bool check(const ompl::base::State *s1, const ompl::base::State *s2, double &certified) const;
            SphereValidityCheckerPtr checker_;
            std::shared_ptr<ompl::base::MotionValidator> exactMotions_;  ///< on the real geometry, or null
            double minFraction_;
            std::vector<char> continuous_;  ///< per group value: a continuous joint (wraps)
            mutable std::atomic<std::uint64_t> checks_{0};
        };
    }  // namespace validity
}  // namespace michi

#endif
