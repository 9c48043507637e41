#ifndef MICHI_STATE_SPACES_TURN_MOVE_TURN_STATE_SPACE_
#define MICHI_STATE_SPACES_TURN_MOVE_TURN_STATE_SPACE_

#include <ompl/base/spaces/SE2StateSpace.h>

#include <memory>

namespace michi
{
    namespace state_spaces
    {
        /** \brief The motion of a turn-in-place robot between two poses: turn in place by \e turn1 (radians,
            signed), drive straight \e move metres (forwards, or backwards when \e backward), turn in place by
            \e turn2. A pure turn (same position) has move = 0, turn2 = 0. */
        struct TurnMoveTurn
        {
            double turn1{0.};
            double move{0.};
            double turn2{0.};
            bool backward{false};
            double heading{0.};  ///< the robot's heading while it drives (after turn1)
        };

        /** \brief SE(2) for a robot that can only turn in place and drive straight (paper 003's robot: a long
            rectangle on a differential drive). The motion between two states is: turn in place to face the
            target position (or to face away from it and reverse, when driving backwards is allowed and cheaper),
            drive straight to it, turn in place to the final heading. When the positions coincide it is one turn.

            distance(a, b) = turn_weight * (|turn1| + |turn2|) + |move| of that motion, the cheaper of forwards
            and backwards; interpolate(a, b, t) is the state a fraction t of that distance along it, so
            interpolate(interpolate(a, b, s), b, u) = interpolate(a, b, s + u (1 - s)) and distance(a,
            interpolate(a, b, t)) = t distance(a, b). With turn_weight = the robot's circumradius the distance bounds
            how far any point of the robot moves.

            The distance is not a metric (a zig-zag of several turn-move-turn motions can be shorter than one), so
            isMetricSpace() is false: OMPL's planners then use nearest-neighbour structures that do not rely on the
            triangle inequality. With backwards driving allowed the distance is symmetric; without it, it is not,
            and bidirectional planners (RRTConnect, PRM) would check motions in the wrong direction: use
            forward-only spaces with unidirectional planners only.

            The default projection is SE2StateSpace's (x, y). */
        class TurnMoveTurnStateSpace : public ompl::base::SE2StateSpace
        {
        public:
            explicit TurnMoveTurnStateSpace(double turnWeight = 1., bool allowBackward = true);

            /** \brief Metres of distance per radian of turning in place (> 0). */
            void setTurnWeight(double weight);
            double getTurnWeight() const
            {
                return turnWeight_;
            }
            void setAllowBackward(bool allow);
            bool getAllowBackward() const
            {
                return allowBackward_;
            }

            /** \brief The motion from (x1, y1, yaw1) to (x2, y2, yaw2) that distance() measures. */
            TurnMoveTurn motion(double x1, double y1, double yaw1, double x2, double y2, double yaw2) const;
            TurnMoveTurn motion(const ompl::base::State *from, const ompl::base::State *to) const;
            /** \brief The distance between two configurations given as [x, y, yaw]. */
            double realsDistance(const double *from, const double *to) const;

            double distance(const ompl::base::State *state1, const ompl::base::State *state2) const override;
            void interpolate(const ompl::base::State *from, const ompl::base::State *to, double t,
                             ompl::base::State *state) const override;
            double getMaximumExtent() const override;
            bool isMetricSpace() const override
            {
                return false;
            }
            bool hasSymmetricDistance() const override
            {
                return allowBackward_;
            }
            bool hasSymmetricInterpolate() const override
            {
                return allowBackward_;
            }

            /** \brief Positions closer than this are the same position (the motion is one turn). */
            static constexpr double SAME_POSITION = 1e-9;

        private:
            double cost(const TurnMoveTurn &m) const
            {
                return turnWeight_ * (std::abs(m.turn1) + std::abs(m.turn2)) + m.move;
            }
            double turnWeight_;
            bool allowBackward_;
        };

        using TurnMoveTurnStateSpacePtr = std::shared_ptr<TurnMoveTurnStateSpace>;

        /** \brief A TurnMoveTurnStateSpace on the given position bounds. */
        TurnMoveTurnStateSpacePtr makeTurnMoveTurnStateSpace(double xMin, double xMax, double yMin, double yMax,
                                                             double turnWeight = 1., bool allowBackward = true);
    }  // namespace state_spaces
}  // namespace michi

#endif
