#include <michi/validity/ConservativeMotionValidator.h>

#include <ompl/base/SpaceInformation.h>

#include <algorithm>

namespace michi
{
    namespace validity
    {
        ConservativeMotionValidator::ConservativeMotionValidator(const ompl::base::SpaceInformationPtr &si,
                                                                 FclValidityCheckerPtr checker)
          : ompl::base::MotionValidator(si), checker_(std::move(checker))
        {
        }

        bool ConservativeMotionValidator::walk(const ompl::base::State *s1, const ompl::base::State *s2,
                                               double *lastValidTime) const
        {
            const auto &space = si_->getStateSpace();
            std::vector<double> from, to, values;
            space->copyToReals(from, s1);
            space->copyToReals(to, s2);
            const double bound = checker_->bodies()->displacementBound(from.data(), to.data());
            // with no displacement bound (a motion that moves nothing), OMPL's discrete resolution is the fallback
            const double length = space->distance(s1, s2);
            const double discreteStep =
                length > 0. ? std::min(1., space->getLongestValidSegmentLength() / length) : 1.;

            ompl::base::State *state = si_->allocState();
            double t = 0., lastGood = 0.;
            bool valid = true;
            while (true)
            {
                space->interpolate(s1, s2, t, state);
                space->copyToReals(values, state);
                if (!si_->satisfiesBounds(state) || !checker_->isValidConfiguration(values.data()))
                {
                    valid = false;
                    break;
                }
                lastGood = t;
                if (t >= 1.)
                    break;
                // Half the nearest distance (robot-obstacle or robot-robot): two bodies approach each other
                // at most twice as fast as one body moves.
                // (FCL's answer with rel_err r is at most 1 + r times the true distance)
                const double clearance =
                    0.5 * checker_->proximity(values.data(), true, relativeError_).distance / (1. + relativeError_);
                // Near contact the clearance is tiny: keep moving by at most minClearanceStep_ of workspace
                // displacement per check, so states stay dense in metres (never a coarse joint-space jump).
                const double step = bound > 0. ? std::max(clearance, minClearanceStep_) / bound : discreteStep;
                t = std::min(1., t + step);
            }
            si_->freeState(state);
            if (lastValidTime != nullptr)
                *lastValidTime = lastGood;
            return valid;
        }

        bool ConservativeMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const
        {
            // cheap rejection first, like OMPL's DiscreteMotionValidator
            if (!si_->isValid(s2))
            {
                ++invalid_;
                return false;
            }
            const bool ok = walk(s1, s2, nullptr);
            ok ? ++valid_ : ++invalid_;
            return ok;
        }

        bool ConservativeMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                                                      std::pair<ompl::base::State *, double> &lastValid) const
        {
            double t = 0.;
            const bool ok = walk(s1, s2, &t);
            if (!ok)
            {
                lastValid.second = t;
                if (lastValid.first != nullptr)
                    si_->getStateSpace()->interpolate(s1, s2, t, lastValid.first);
            }
            ok ? ++valid_ : ++invalid_;
            return ok;
        }
    }
}
