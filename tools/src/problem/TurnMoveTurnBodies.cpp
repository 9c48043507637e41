#include <michi/tools/problem/TurnMoveTurnBodies.h>

#include <algorithm>
#include <stdexcept>

namespace michi
{
    namespace tools
    {
        TurnMoveTurnBodies::TurnMoveTurnBodies(std::shared_ptr<const validity::PlanarRigidBody> body,
                                               std::shared_ptr<const state_spaces::TurnMoveTurnStateSpace> space)
            : body_(std::move(body)), space_(std::move(space))
        {
            if (!body_ || !space_)
                throw std::invalid_argument("TurnMoveTurnBodies needs a body and a space");
        }

        double TurnMoveTurnBodies::displacementBound(const double *from, const double *to) const
        {
            // realsDistance() weighs a turn by turn_weight per radian, but a footprint point moves circumradius per
            // radian: the ratio (never below 1, moves count in full) turns the cost into a bound on how far any point
            // moves.
            const double scale = std::max(1., body_->circumradius() / space_->getTurnWeight());
            return scale * space_->realsDistance(from, to);
        }

        void TurnMoveTurnBodies::bodyDisplacementBounds(const double *from, const double *to,
                                                        std::vector<double> &bounds) const
        {
            bounds.assign(1, displacementBound(from, to));
        }
    }  // namespace tools
}  // namespace michi
