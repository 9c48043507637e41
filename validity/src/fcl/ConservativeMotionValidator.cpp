#include <michi/validity/fcl/ConservativeMotionValidator.h>
#include <michi/validity/MotionCount.h>

#include <ompl/base/SpaceInformation.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <limits>

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
            const auto &bodies = *checker_->bodies();
            std::vector<double> from, to, values, bounds;
            space->copyToReals(from, s1);
            space->copyToReals(to, s2);
            // how far each body can move over the whole motion; bodies and pairs that do not move are skipped
            bodies.bodyDisplacementBounds(from.data(), to.data(), bounds);
            const auto &pairs = bodies.selfCheckPairs();
            std::vector<char> wantBodies(bounds.size()), wantPairs(pairs.size());
            for (std::size_t b = 0; b < bounds.size(); ++b)
                wantBodies[b] = bounds[b] > 0.;
            for (std::size_t k = 0; k < pairs.size(); ++k)
                wantPairs[k] = bounds[pairs[k].first] + bounds[pairs[k].second] > 0.;

            const double maxBound = bounds.empty() ? 0. : *std::max_element(bounds.begin(), bounds.end());
            // Each step costs a distance query per moving body and per moving self pair: the step budget shrinks
            // with that count, so the work of one motion stays bounded whatever the robot (a 1,000-link chain has
            // half a million self pairs, and its motions took minutes each).
            const double perStep = std::max<double>(1., std::count(wantBodies.begin(), wantBodies.end(), 1) +
                                                            std::count(wantPairs.begin(), wantPairs.end(), 1));
            const int maxSteps = static_cast<int>(std::min<double>(MAX_WALK_STEPS, MAX_WALK_QUERIES / perStep));
            ompl::base::State *state = si_->allocState();
            std::vector<double> obstacle, self;
            double t = 0., lastGood = 0.;
            int steps = 0;
            bool valid = true, lastStepSafe = false;
            while (true)
            {
                space->interpolate(s1, s2, t, state);
                space->copyToReals(values, state);
                if (!si_->satisfiesBounds(state) || !checker_->isValidConfiguration(values.data()))
                {
                    // after a step within the clearance every state short of t is free: report one just before t
                    if (lastStepSafe && t > lastGood && maxBound > 0.)
                        lastGood = std::max(lastGood, t - minClearanceStep_ / maxBound);
                    valid = false;
                    break;
                }
                lastGood = t;
                if (t >= 1.)
                    break;
                checker_->bodyDistances(values.data(), wantBodies, wantPairs, obstacle, self);
                // a body moving at most bounds[b] * dt cannot reach an obstacle at distance d in less than
                // d / bounds[b]; two bodies close in at most as fast as the sum of their bounds. Near contact,
                // advance by at most minClearanceStep_ of displacement so states stay dense in metres.
                double step = std::numeric_limits<double>::infinity();
                double safeStep = step;  // the same without the near-contact minimum
                for (std::size_t b = 0; b < bounds.size(); ++b)
                    if (wantBodies[b])
                    {
                        step = std::min(step, std::max(obstacle[b], minClearanceStep_) / bounds[b]);
                        safeStep = std::min(safeStep, obstacle[b] / bounds[b]);
                    }
                for (std::size_t k = 0; k < pairs.size(); ++k)
                    if (wantPairs[k])
                    {
                        const double closing = bounds[pairs[k].first] + bounds[pairs[k].second];
                        step = std::min(step, std::max(self[k], minClearanceStep_) / closing);
                        safeStep = std::min(safeStep, self[k] / closing);
                    }
                lastStepSafe = step <= safeStep;
                // bounded work: a step that no longer moves t (geometry far from its joint makes the bounds huge)
                // or a motion that needs more than its step budget (maxSteps) is reported invalid. That is conservative
                // (a planner then avoids the motion), never a hang and never a motion passed unchecked.
                if (!(t + step > t) || ++steps > maxSteps)
                {
                    if (!warnedLongWalk_.exchange(true))
                        OMPL_WARN(
                            "ConservativeMotionValidator: a motion needs more than %d clearance steps (a body "
                            "moves %g m per unit of motion; %g distance queries per step); such motions are reported "
                            "invalid",
                            maxSteps, maxBound, perStep);
                    valid = false;
                    break;
                }
                t = std::min(1., t + step);  // step is +inf when nothing moves: one more check at the end
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
                countMotion(invalid_);
                return false;
            }
            const bool ok = walk(s1, s2, nullptr);
            countMotion(ok ? valid_ : invalid_);
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
            countMotion(ok ? valid_ : invalid_);
            return ok;
        }
    }  // namespace validity
}  // namespace michi
