#ifndef MICHI_TOOLS_TURN_MOVE_TURN_BODIES_
#define MICHI_TOOLS_TURN_MOVE_TURN_BODIES_

#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/validity/robot/CollisionBodies.h>

namespace michi
{
    namespace tools
    {
        /** \brief A planar rigid body moving by turn-move-turn motions (state_spaces::TurnMoveTurnStateSpace).
            The bodies, poses and self pairs are the wrapped PlanarRigidBody's; the displacement bound follows the
            space's motion, not the straight line in (x, y, yaw) that PlanarRigidBody assumes: a point of the body
            at most circumradius r from its origin moves at most r per radian turned and 1 per metre driven, so
            over a motion of distance D (turn_weight w) it moves at most max(1, r / w) D, and a fraction t of the
            motion moves it at most t times that. The workspace and conservative motion validators, which step
            through interpolate() with this bound, then check turn-move-turn motions at their stated resolution. */
        class TurnMoveTurnBodies : public validity::CollisionBodies
        {
        public:
            TurnMoveTurnBodies(std::shared_ptr<const validity::PlanarRigidBody> body,
                               std::shared_ptr<const state_spaces::TurnMoveTurnStateSpace> space);

            std::size_t dimension() const override
            {
                return 3;
            }
            const std::vector<validity::Body> &bodies() const override
            {
                return body_->bodies();
            }
            void bodyPoses(const double *values, std::vector<Eigen::Isometry3d> &poses) const override
            {
                body_->bodyPoses(values, poses);
            }
            const std::vector<std::pair<int, int>> &selfCheckPairs() const override
            {
                return body_->selfCheckPairs();
            }
            double displacementBound(const double *from, const double *to) const override;
            void bodyDisplacementBounds(const double *from, const double *to,
                                        std::vector<double> &bounds) const override;
            const validity::PlanarRigidBody &body() const
            {
                return *body_;
            }

        private:
            std::shared_ptr<const validity::PlanarRigidBody> body_;
            std::shared_ptr<const state_spaces::TurnMoveTurnStateSpace> space_;
        };
    }  // namespace tools
}  // namespace michi

#endif
