#include <michi/validity/spheres/SphereMotionValidator.h>
#include <michi/validity/MotionCount.h>
#include <michi/validity/fcl/WorkspaceMotionValidator.h>

#include <ompl/base/SpaceInformation.h>

#include <cmath>

namespace michi
{
    namespace validity
    {
        SphereMotionValidator::SphereMotionValidator(const ompl::base::SpaceInformationPtr &si,
                                                     SphereValidityCheckerPtr checker, double minFraction)
            : ompl::base::MotionValidator(si), checker_(std::move(checker)), minFraction_(minFraction)
        {
            if (checker_->exact())
                exactMotions_ = std::make_shared<WorkspaceMotionValidator>(si, checker_->exact(), 0.001);
            const auto &bodies = *checker_->bodies();
            for (int v : bodies.variables())
                continuous_.push_back(bodies.model()->variableJoint(v).type == RobotJoint::Type::CONTINUOUS);
        }

        namespace
        {
            /** How far (metres) a sphere may move from a first piece's middle. Measured in bench_validity's
                motion/spheres_* (200 motions a tenth of the space long): whole motion first 16.8 / 17.0 us (Panda /
                xArm6), 0.16 m 15.2 / 14.9, 0.1 m 15.2 / 13.5, 0.04 m 17.2 / 10.8, 0.01 m 27.5 / 17.0; RRTConnect's
                solve() the same from 0.1 m up. */
            constexpr double INITIAL_GROWTH = 0.1;
            /** At most this many first pieces (a motion across the whole space). */
            constexpr double MAX_PIECES = 1024.;
        }  // namespace

        bool SphereMotionValidator::check(const ompl::base::State *s1, const ompl::base::State *s2,
                                          double &certified) const
        {
            certified = 0.;
            const auto &space = si_->getStateSpace();
            thread_local std::vector<double> a, b, mid;
            thread_local Eigen::VectorXf delta, whole, grow, span, wholeBody, growBody;
            space->copyToReals(a, s1);
            space->copyToReals(b, s2);
            const std::size_t dim = a.size();
            delta.resize(static_cast<long>(dim));
            for (std::size_t i = 0; i < dim; ++i)
            {
                double d = std::abs(b[i] - a[i]);
                if (continuous_[i])
                {
                    // A continuous joint moves the short way round (as OMPL's SO(2) interpolates): its travel is at
                    // most pi.
                    d = std::fmod(d, 2. * M_PI);
                    d = std::min(d, 2. * M_PI - d);
                }
                delta[static_cast<long>(i)] = static_cast<float>(d);
            }
            const Eigen::MatrixXf &coefficients = checker_->displacementCoefficients();
            // the sphere displacement over the whole motion; a piece of fraction f moves f of it
            whole.noalias() = coefficients * delta;
            // each body's largest sphere displacement, once per motion: a piece scales it as it scales the spheres'
            wholeBody.resize(static_cast<long>(checker_->bodyCount()));
            checker_->bodyInflations(whole.data(), wholeBody.data());
            ompl::base::State *m = si_->allocState();
            // pieces in order, left first, so the certified prefix is known when one fails
            struct Piece
            {
                double t0, t1;
            };
            thread_local std::vector<Piece> stack;
            stack.clear();
            // Start from pieces over which no sphere moves more than INITIAL_GROWTH from the piece's middle rather
            // than from the whole motion: a long motion's coarse pieces are grown by tens of centimetres and never
            // come free, so halving down from them cost a failed check and a middle-state check per level.
            // Right to left on the stack, so the left piece is checked first.
            const double growth = whole.size() > 0 ? static_cast<double>(whole.maxCoeff()) : 0.;
            const int pieces =
                static_cast<int>(std::min(std::ceil(0.5 * growth / INITIAL_GROWTH), static_cast<double>(MAX_PIECES)));
            const int count = std::max(pieces, 1);
            for (int i = count - 1; i >= 0; --i)
                stack.push_back({static_cast<double>(i) / count, static_cast<double>(i + 1) / count});
            bool ok = true;
            while (!stack.empty())
            {
                const Piece p = stack.back();
                stack.pop_back();
                const double tm = 0.5 * (p.t0 + p.t1);
                space->interpolate(s1, s2, tm, m);
                space->copyToReals(mid, m);
                // From the piece's middle, no point moves more than half the piece's share of the whole displacement:
                // spheres grown by that hold every pose of the piece, so one check certifies it all. 1e-6 covers float
                // rounding.
                const float scale = static_cast<float>(0.5 * (p.t1 - p.t0) * (1. + 1e-6));
                grow = whole * scale;
                growBody = wholeBody * scale;
                span = delta * scale;
                ++checks_;
                if (checker_->isFreeInflated(mid.data(), grow.data(), span.data(), growBody.data()))
                {
                    certified = p.t1;
                    continue;
                }
                // The middle state itself collides: the motion is invalid, no need to split further.
                if (!checker_->isValidConfiguration(mid.data()))
                {
                    ok = false;
                    break;
                }
                // a state free for the real geometry that the spheres cannot show free (a hand at its grasp):
                // halving cannot help. FCL decides this piece with the workspace validator at 1 mm (no point of
                // the robot moves more than 1 mm between checks; at 1 cm verify-checker found unsafe motions):
                // FCL's exact walk took 8 ms a motion here. This piece is checked, not certified
                // (without exact states the check above was the spheres alone: they showed the state free)
                if (exactMotions_ && checker_->exactStates() && !checker_->spheresFree(mid.data()))
                {
                    ompl::base::State *from = si_->allocState(), *to = si_->allocState();
                    space->interpolate(s1, s2, p.t0, from);
                    space->interpolate(s1, s2, p.t1, to);
                    // the workspace validator takes its first state as valid (OMPL's convention); this piece may
                    // begin the motion, whose first state nobody has checked
                    const bool free = si_->isValid(from) && exactMotions_->checkMotion(from, to);
                    si_->freeState(from);
                    si_->freeState(to);
                    if (!free)
                    {
                        ok = false;
                        break;
                    }
                    certified = p.t1;
                    continue;
                }
                // Halving has a floor: near a contact the grown spheres never come free, and the piece is refused
                // (conservative) instead of split without end.
                if (p.t1 - p.t0 < minFraction_)
                {
                    ok = false;
                    break;
                }
                // Right half pushed first so the left half is checked first: certified grows from s1 without gaps.
                stack.push_back({tm, p.t1});
                stack.push_back({p.t0, tm});
            }
            si_->freeState(m);
            return ok;
        }

        bool SphereMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const
        {
            if (!si_->isValid(s2))
            {
                countMotion(invalid_);
                return false;
            }
            double certified = 0.;
            const bool ok = check(s1, s2, certified);
            if (ok)
                countMotion(valid_);
            else
                countMotion(invalid_);
            return ok;
        }

        bool SphereMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                                                std::pair<ompl::base::State *, double> &lastValid) const
        {
            double certified = 0.;
            bool ok = si_->isValid(s2);
            if (ok)
                ok = check(s1, s2, certified);
            else
            {
                check(s1, s2, certified);
                // The end state is invalid: the last valid time must stay short of 1 even when every piece but the end
                // came free.
                certified = std::min(certified, 1. - minFraction_);
            }
            if (ok)
            {
                countMotion(valid_);
                return true;
            }
            // the certified prefix ends at a state whose piece was shown free
            if (lastValid.first != nullptr)
                si_->getStateSpace()->interpolate(s1, s2, certified, lastValid.first);
            lastValid.second = certified;
            countMotion(invalid_);
            return false;
        }
    }  // namespace validity
}  // namespace michi
