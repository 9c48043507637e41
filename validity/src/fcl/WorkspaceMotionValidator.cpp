#include <michi/validity/fcl/WorkspaceMotionValidator.h>
#include <michi/validity/MotionCount.h>

#include <ompl/base/SpaceInformation.h>

#include <algorithm>
#include <cmath>
#include <queue>
#include <stdexcept>

namespace michi
{
    namespace validity
    {
        WorkspaceMotionValidator::WorkspaceMotionValidator(const ompl::base::SpaceInformationPtr &si,
                                                           FclValidityCheckerPtr checker, double maxStep)
            : ompl::base::MotionValidator(si), checker_(std::move(checker)), maxStep_(0.01)
        {
            setMaxStep(maxStep);
        }

        void WorkspaceMotionValidator::setMaxStep(double metres)
        {
            if (!(metres > 0.))
                throw std::invalid_argument("motion validator max_step must be positive");
            maxStep_ = metres;
        }

        unsigned int WorkspaceMotionValidator::stepCount(const ompl::base::State *s1, const ompl::base::State *s2) const
        {
            std::vector<double> from, to, bounds;
            si_->getStateSpace()->copyToReals(from, s1);
            si_->getStateSpace()->copyToReals(to, s2);
            checker_->bodies()->bodyDisplacementBounds(from.data(), to.data(), bounds);
            const double largest = bounds.empty() ? 0. : *std::max_element(bounds.begin(), bounds.end());
            // n equal steps of the motion: no point of any body moves more than maxStep_ between two consecutive
            // checks.
            // (clamped to what an unsigned int holds: beyond that the cast is undefined; michi's problem files refuse
            // settings that come anywhere near it)
            return std::max(1u, static_cast<unsigned int>(std::min(std::ceil(largest / maxStep_), 4e9)));
        }

        bool WorkspaceMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const
        {
            // s1 is taken as valid (OMPL's convention for motion validators); the end state is the cheapest rejection.
            if (!si_->isValid(s2))
            {
                countMotion(invalid_);
                return false;
            }
            const unsigned int n = stepCount(s1, s2);
            // intermediate states in bisection order, so a collision in the middle is found early
            ompl::base::State *state = si_->allocState();
            std::queue<std::pair<unsigned int, unsigned int>> intervals;
            // Steps 0 and n are s1 and s2, already settled above.
            intervals.emplace(1, n - 1);
            bool ok = true;
            while (ok && !intervals.empty())
            {
                const auto [lo, hi] = intervals.front();
                intervals.pop();
                if (lo > hi)
                    continue;
                const unsigned int mid = (lo + hi) / 2;
                si_->getStateSpace()->interpolate(s1, s2, static_cast<double>(mid) / n, state);
                ok = si_->isValid(state);
                if (mid > lo)
                    intervals.emplace(lo, mid - 1);
                intervals.emplace(mid + 1, hi);
            }
            si_->freeState(state);
            countMotion(ok ? valid_ : invalid_);
            return ok;
        }

        bool WorkspaceMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                                                   std::pair<ompl::base::State *, double> &lastValid) const
        {
            const unsigned int n = stepCount(s1, s2);
            ompl::base::State *state = si_->allocState();
            bool ok = true;
            // In order from s1, and up to s2 (not checked beforehand here), so the first invalid step gives the last
            // valid time.
            for (unsigned int i = 1; i <= n && ok; ++i)
            {
                si_->getStateSpace()->interpolate(s1, s2, static_cast<double>(i) / n, state);
                if (!si_->isValid(state))
                {
                    ok = false;
                    lastValid.second = static_cast<double>(i - 1) / n;
                    if (lastValid.first != nullptr)
                        si_->getStateSpace()->interpolate(s1, s2, lastValid.second, lastValid.first);
                }
            }
            si_->freeState(state);
            countMotion(ok ? valid_ : invalid_);
            return ok;
        }
    }  // namespace validity
}  // namespace michi
