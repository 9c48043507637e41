#include <michi/planners/HandIk.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>

namespace michi
{
    namespace planners
    {
        void HandTarget::errors(const Eigen::Isometry3d &tool, double &positionError, double &angleError) const
        {
            positionError = (tool.translation() - position).norm();
            const Eigen::Vector3d a = (tool.linear() * toolAxis).normalized();
            // AXIS_ALONG: atan2 of |sin| and cos is accurate at every angle, where acos of the dot product loses
            // precision near 0 and pi. AXIS_PERPENDICULAR: the angle by which the axis leaves the plane normal to
            // direction (the dot product clamped against rounding).
            if (mode == Mode::AXIS_ALONG)
                angleError = std::atan2(a.cross(direction).norm(), a.dot(direction));
            else
                angleError = std::abs(std::asin(std::max(-1., std::min(1., a.dot(direction)))));
        }

        bool solveHandIk(const ArmChain &arm, const HandTarget &target, std::vector<double> &q,
                         const HandIkSettings &settings)
        {
            const long n = static_cast<long>(arm.size());
            // Position (3 rows) plus either a full 3-row orientation error (axis along a direction) or one scalar row
            // (axis perpendicular to a direction: any rotation about the direction is allowed).
            const long rows = target.mode == HandTarget::Mode::AXIS_ALONG ? 6 : 4;
            Eigen::MatrixXd a(rows, n);
            Eigen::VectorXd e(rows);
            arm.clampToLimits(q);
            std::vector<double> history;
            for (unsigned int it = 0; it <= settings.maxIterations; ++it)
            {
                const Eigen::Isometry3d tool = arm.toolPose(q);
                double pe = 0., ae = 0.;
                target.errors(tool, pe, ae);
                if (pe <= settings.positionTolerance && ae <= settings.angleTolerance)
                    return true;
                if (it == settings.maxIterations)
                    break;
                // Stall test: give up when the weighted error has not halved over the last stallIterations steps (a
                // joint limit or a target out of reach) instead of spending every iteration on it.
                history.push_back(pe + settings.angleWeight * ae);
                if (settings.stallIterations > 0 && history.size() > settings.stallIterations &&
                    history.back() > 0.5 * history[history.size() - 1 - settings.stallIterations])
                    break;
                const Eigen::MatrixXd jac = arm.jacobian(q);
                const Eigen::Vector3d axis = (tool.linear() * target.toolAxis).normalized();
                a.topRows(3) = jac.topRows(3);
                e.head<3>() = target.position - tool.translation();
                const double w = settings.angleWeight;
                if (target.mode == HandTarget::Mode::AXIS_ALONG)
                {
                    // rotate the axis towards the direction: angular velocity along axis x direction
                    Eigen::Vector3d c = axis.cross(target.direction);
                    const double s = c.norm();
                    const double angle = std::atan2(s, axis.dot(target.direction));
                    // axis and direction parallel: done when aligned (angle 0), but when opposite (angle pi) any
                    // perpendicular rotation axis works; a zero one would leave the solver stuck.
                    if (s < 1e-12)
                        c = angle > 1. ? axis.unitOrthogonal() : Eigen::Vector3d::Zero();
                    else
                        c /= s;
                    a.bottomRows(3) = w * jac.bottomRows(3);
                    e.tail<3>() = w * angle * c;
                }
                else
                {
                    // d(axis . n)/dt = omega . (axis x n)
                    const Eigen::Vector3d g = axis.cross(target.direction);
                    a.row(3) = w * (g.transpose() * jac.bottomRows(3));
                    e(3) = -w * axis.dot(target.direction);
                }
                // Damped least squares (Levenberg-Marquardt): dq = A^T (A A^T + lambda^2 I)^-1 e stays bounded near
                // singularities, where the plain pseudo-inverse step blows up.
                const Eigen::MatrixXd aat =
                    a * a.transpose() + settings.damping * settings.damping * Eigen::MatrixXd::Identity(rows, rows);
                Eigen::VectorXd dq = a.transpose() * aat.ldlt().solve(e);
                // The linearisation only holds for small steps: the largest joint change is bounded, keeping the step's
                // direction.
                const double largest = dq.cwiseAbs().maxCoeff();
                if (largest > settings.maxStep)
                    dq *= settings.maxStep / largest;
                for (long i = 0; i < n; ++i)
                    q[arm.variables()[i]] += dq(i);
                arm.clampToLimits(q);
            }
            return false;
        }
    }  // namespace planners
}  // namespace michi
