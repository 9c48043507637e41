#include <michi/validity/jmap/JMapMotionValidator.h>
#include <michi/validity/MotionCount.h>

#include <ompl/base/SpaceInformation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace michi
{
    namespace validity
    {
        namespace
        {
            const double twoPi = 2. * M_PI;

            /** Whether the space interpolates value \e index the short way round a circle (SO(2)): the midpoint
                of 3 and -3 is then near +-pi instead of 0. Asked of the space itself, so any space that keeps
                the values in copyToReals order works. */
            bool wrapsAround(const ompl::base::StateSpace &space, int index)
            {
                std::vector<double> a(space.getDimension(), 0.), b(a);
                a[index] = 3.;
                b[index] = -3.;
                ompl::base::State *sa = space.allocState(), *sb = space.allocState(), *mid = space.allocState();
                space.copyFromReals(sa, a);
                space.copyFromReals(sb, b);
                space.interpolate(sa, sb, 0.5, mid);
                std::vector<double> m;
                space.copyToReals(m, mid);
                space.freeState(sa);
                space.freeState(sb);
                space.freeState(mid);
                return std::abs(m[index]) > 1.5;
            }

            /** The shift by a multiple of 2 pi that brings \e value into [-pi, pi). */
            double wrapShift(double value)
            {
                return twoPi * std::floor((value + M_PI) / twoPi);
            }
        }  // namespace

        JMapMotionValidator::JMapMotionValidator(const ompl::base::SpaceInformationPtr &si,
                                                 JMapValidityCheckerPtr checker,
                                                 ompl::base::MotionValidatorPtr fallback)
            : ompl::base::MotionValidator(si), checker_(std::move(checker)), fallback_(std::move(fallback))
        {
            if (!checker_ || !fallback_)
                throw std::invalid_argument("JMapMotionValidator needs a J-map checker and a fallback validator");
        }

        void JMapMotionValidator::learnInterpolation() const
        {
            // the space's value locations exist only once the space is set up, so not in the constructor
            std::call_once(learned_,
                           [this]
                           {
                               const auto &space = *si_->getStateSpace();
                               wraps1_ = wrapsAround(space, checker_->valueIndex1());
                               wraps2_ = wrapsAround(space, checker_->valueIndex2());
                           });
        }

        double JMapMotionValidator::firstContact(const double *from, const double *to) const
        {
            learnInterpolation();
            const double a1 = from[checker_->valueIndex1()], a2 = from[checker_->valueIndex2()];
            double d1 = to[checker_->valueIndex1()] - a1, d2 = to[checker_->valueIndex2()] - a2;
            // the motion as OMPL interpolates it: continuous joints the short way round
            if (wraps1_)
                d1 = std::remainder(d1, twoPi);
            if (wraps2_)
                d2 = std::remainder(d2, twoPi);
            // cut the motion where it wraps and where theta1 crosses a tile border: each piece is one segment
            // on one tile's map
            std::vector<double> cuts{0., 1.};
            auto cutAt = [&cuts](double value, double start, double delta)
            {
                if (delta == 0.)
                    return;
                const double t = (value - start) / delta;
                if (t > 0. && t < 1.)
                    cuts.push_back(t);
            };
            for (double bound : {-M_PI, M_PI})
            {
                if (wraps1_)
                    cutAt(bound, a1, d1);
                if (wraps2_)
                    cutAt(bound, a2, d2);
            }
            const auto &axes = checker_->axes();
            const double width = (axes.hi1 - axes.lo1) / static_cast<double>(checker_->tileCount());
            // An unwrapped theta1 may run up to half a turn past +-pi: the tile borders' images one period away cut it
            // too.
            for (double shift : wraps1_ ? std::vector<double>{-twoPi, 0., twoPi} : std::vector<double>{0.})
                for (std::size_t k = 1; k < checker_->tileCount(); ++k)
                    cutAt(axes.lo1 + static_cast<double>(k) * width + shift, a1, d1);
            std::sort(cuts.begin(), cuts.end());
            for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
            {
                const double ta = cuts[i], tb = cuts[i + 1];
                if (tb <= ta)
                    continue;
                double xa = a1 + ta * d1, ya = a2 + ta * d2, xb = a1 + tb * d1, yb = a2 + tb * d2;
                if (wraps1_)
                {
                    // Each piece lies within one period after the cuts: shifting by its midpoint's period brings the
                    // whole piece into [-pi, pi), where the tiles are.
                    const double s = wrapShift(0.5 * (xa + xb));
                    xa -= s;
                    xb -= s;
                }
                if (wraps2_)
                {
                    const double s = wrapShift(0.5 * (ya + yb));
                    ya -= s;
                    yb -= s;
                }
                const double t = checker_->tile(0.5 * (xa + xb)).firstContact(xa, ya, xb, yb);
                if (t <= 1.)
                    return ta + t * (tb - ta);
            }
            return std::numeric_limits<double>::infinity();
        }

        int JMapMotionValidator::decide(const ompl::base::State *s1, const ompl::base::State *s2, double *contact) const
        {
            // Decisions: 0 valid by the map alone, 1 invalid by the map alone, 2 ask the fallback validator. The map
            // cannot judge a state outside the bounds, so the fallback does (and reports it invalid as OMPL's
            // validators do).
            if (!si_->satisfiesBounds(s2))
                return 2;
            std::vector<double> from, to;
            const auto &space = *si_->getStateSpace();
            space.copyToReals(from, s1);
            space.copyToReals(to, s2);
            *contact = firstContact(from.data(), to.data());
            const bool conservative = checker_->settings().mode == JMapCheckerSettings::Mode::CONSERVATIVE;
            // The polygons contain the collision region with a margin: only in conservative mode is a contact with
            // them final; otherwise the exact fallback decides near obstacles.
            if (*contact <= 1.)
                return conservative ? 1 : 2;
            // No contact with any polygon: free, provided the map covers the whole robot (see JMapValidityChecker).
            return checker_->answersAlone() ? 0 : 2;
        }

        bool JMapMotionValidator::check(const ompl::base::State *s1, const ompl::base::State *s2,
                                        std::pair<ompl::base::State *, double> *lastValid) const
        {
            double contact = 0.;
            bool valid = false;
            switch (decide(s1, s2, &contact))
            {
                case 0:
                    valid = true;
                    break;
                case 1:
                    if (lastValid != nullptr)
                    {
                        // the polygons are closed sets: just before the contact the motion is still outside
                        lastValid->second = std::max(0., contact - 1e-6);
                        if (lastValid->first != nullptr)
                            si_->getStateSpace()->interpolate(s1, s2, lastValid->second, lastValid->first);
                    }
                    break;
                default:
                    valid = lastValid != nullptr ? fallback_->checkMotion(s1, s2, *lastValid)
                                                 : fallback_->checkMotion(s1, s2);
            }
            if (valid)
                countMotion(valid_);
            else
                countMotion(invalid_);
            return valid;
        }

        bool JMapMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const
        {
            return check(s1, s2, nullptr);
        }

        bool JMapMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                                              std::pair<ompl::base::State *, double> &lastValid) const
        {
            return check(s1, s2, &lastValid);
        }
    }  // namespace validity
}  // namespace michi
