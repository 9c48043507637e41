#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/state_spaces/Angles.h>
#include <michi/state_spaces/JointStateSpace.h>

#include <boost/math/constants/constants.hpp>

#include <cmath>
#include <stdexcept>

namespace ob = ompl::base;

namespace michi
{
    namespace state_spaces
    {
        namespace
        {
            const double PI = boost::math::constants::pi<double>();
        }  // namespace

        TurnMoveTurnStateSpace::TurnMoveTurnStateSpace(double turnWeight, bool allowBackward)
            : turnWeight_(1.), allowBackward_(allowBackward)
        {
            setName("TurnMoveTurn" + getName());
            setTurnWeight(turnWeight);
        }

        void TurnMoveTurnStateSpace::setTurnWeight(double weight)
        {
            if (!(weight > 0.) || !std::isfinite(weight))
                throw std::invalid_argument("TurnMoveTurnStateSpace: turn weight must be positive and finite");
            turnWeight_ = weight;
        }

        void TurnMoveTurnStateSpace::setAllowBackward(bool allow)
        {
            allowBackward_ = allow;
        }

        TurnMoveTurn TurnMoveTurnStateSpace::motion(double x1, double y1, double yaw1, double x2, double y2,
                                                    double yaw2) const
        {
            TurnMoveTurn m;
            const double dx = x2 - x1, dy = y2 - y1;
            m.move = std::hypot(dx, dy);
            // No drive, so no heading of travel to face (atan2 of a zero vector means nothing): the motion is one turn
            // in place.
            if (m.move <= SAME_POSITION)
            {
                m.move = 0.;
                m.turn1 = turnBetween(yaw1, yaw2);
                m.heading = yaw2;
                return m;
            }
            // Paper 003's robot only turns in place and moves straight: turn to face the target, move, turn to the goal
            // heading.
            // atan2 gives pi for a drive towards -x, which OMPL's SO2 bounds [-pi, pi) refuse: wrap it to -pi
            const double ahead = wrapAngle(std::atan2(dy, dx));
            m.heading = ahead;
            m.turn1 = turnBetween(yaw1, ahead);
            m.turn2 = turnBetween(ahead, yaw2);
            if (allowBackward_)
            {
                const double behind = wrapAngle(ahead + PI);
                TurnMoveTurn b;
                b.move = m.move;
                b.backward = true;
                b.heading = behind;
                b.turn1 = turnBetween(yaw1, behind);
                b.turn2 = turnBetween(behind, yaw2);
                // Backwards wins only when strictly cheaper: a tie keeps the forward motion, so distance() and
                // interpolate() choose the same motion for the same pair of states.
                if (cost(b) < cost(m))
                    return b;
            }
            return m;
        }

        TurnMoveTurn TurnMoveTurnStateSpace::motion(const ob::State *from, const ob::State *to) const
        {
            const auto *a = from->as<StateType>();
            const auto *b = to->as<StateType>();
            return motion(a->getX(), a->getY(), a->getYaw(), b->getX(), b->getY(), b->getYaw());
        }

        double TurnMoveTurnStateSpace::realsDistance(const double *from, const double *to) const
        {
            return cost(motion(from[0], from[1], from[2], to[0], to[1], to[2]));
        }

        double TurnMoveTurnStateSpace::distance(const ob::State *state1, const ob::State *state2) const
        {
            return cost(motion(state1, state2));
        }

        void TurnMoveTurnStateSpace::interpolate(const ob::State *from, const ob::State *to, double t,
                                                 ob::State *state) const
        {
            const auto *a = from->as<StateType>();
            const auto *b = to->as<StateType>();
            const TurnMoveTurn m = motion(from, to);
            const double total = cost(m);
            // read everything from \e from and \e to before writing: \e state may be one of them
            const double x1 = a->getX(), y1 = a->getY(), yaw1 = a->getYaw();
            const double x2 = b->getX(), y2 = b->getY(), yaw2 = b->getYaw();
            auto *s = state->as<StateType>();
            if (total <= 0. || t <= 0.)
            {
                s->setXY(x1, y1);
                s->setYaw(yaw1);
                return;
            }
            if (t >= 1.)
            {
                s->setXY(x2, y2);
                s->setYaw(yaw2);
                return;
            }
            // t is a fraction of the cost (the distance): the state at t lies t of the distance along, as OMPL's
            // planners assume (distance(from, interpolate(t)) = t distance(from, to)).
            double along = t * total;
            const double c1 = turnWeight_ * std::abs(m.turn1);
            if (along < c1 || m.move == 0.)
            {
                // first turn (or the only one), in place
                s->setXY(x1, y1);
                s->setYaw(wrapAngle(yaw1 + m.turn1 * (along / c1)));
                return;
            }
            along -= c1;
            if (along < m.move)
            {
                const double f = along / m.move;
                // The straight move: position linear in the arc, heading fixed (the heading of travel, or its opposite
                // when reversing).
                s->setXY(x1 + (x2 - x1) * f, y1 + (y2 - y1) * f);
                s->setYaw(m.heading);
                return;
            }
            along -= m.move;
            const double c2 = turnWeight_ * std::abs(m.turn2);
            // second turn, at the target position (copied exactly, so the rest of the motion is one turn)
            s->setXY(x2, y2);
            s->setYaw(c2 > 0. ? wrapAngle(m.heading + m.turn2 * std::min(1., along / c2)) : yaw2);
        }

        double TurnMoveTurnStateSpace::getMaximumExtent() const
        {
            // the position part's diagonal plus the largest turns: 2 pi forwards only; with reversing the cheaper of
            // forwards and backwards turns by pi at most in all (their turns add up to 2 pi)
            const double diagonal = getSubspace(0)->getMaximumExtent();
            return diagonal + turnWeight_ * PI * (allowBackward_ ? 1. : 2.);
        }

        TurnMoveTurnStateSpacePtr makeTurnMoveTurnStateSpace(double xMin, double xMax, double yMin, double yMax,
                                                             double turnWeight, bool allowBackward)
        {
            auto space = std::make_shared<TurnMoveTurnStateSpace>(turnWeight, allowBackward);
            setSe2Bounds(*space, xMin, xMax, yMin, yMax);
            return space;
        }
    }  // namespace state_spaces
}  // namespace michi
