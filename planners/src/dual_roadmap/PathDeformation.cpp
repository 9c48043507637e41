#include <michi/planners/dual_roadmap/PathDeformation.h>

#include <algorithm>
#include <cmath>

namespace michi
{
    namespace planners
    {
        Eigen::MatrixXd pointJacobian(const validity::CollisionBodies &bodies, const double *values, int body,
                                      const Eigen::Vector3d &point)
        {
            const std::size_t n = bodies.dimension();
            if (const auto *group = dynamic_cast<const validity::RobotGroupBodies *>(&bodies))
            {
                const std::vector<double> full = group->fullConfiguration(values);
                const int link = group->bodyLink(static_cast<std::size_t>(body));
                const auto poses = group->model()->forwardKinematics(full);
                const Eigen::Vector3d local = poses[link].inverse() * point;
                // The model's Jacobian has a column per model variable; the state holds only the group's, in the
                // group's order.
                const Eigen::MatrixXd j = group->model()->jacobian(full, link, local);
                Eigen::MatrixXd out(3, n);
                for (std::size_t c = 0; c < n; ++c)
                    out.col(c) = j.block(0, group->variables()[c], 3, 1);
                return out;
            }
            if (dynamic_cast<const validity::PlanarRigidBody *>(&bodies) != nullptr)
            {
                // SE(2) (x, y, yaw): a point r = p - (x, y) from the body's origin moves by (1, 0), (0, 1) and the
                // rotation's (-r_y, r_x) per unit of x, y and yaw; z never moves.
                Eigen::MatrixXd out = Eigen::MatrixXd::Zero(3, 3);
                out(0, 0) = 1.;
                out(1, 1) = 1.;
                out(0, 2) = -(point.y() - values[1]);
                out(1, 2) = point.x() - values[0];
                return out;
            }
            // any other bodies: central differences of the body pose
            std::vector<Eigen::Isometry3d> poses;
            bodies.bodyPoses(values, poses);
            const Eigen::Vector3d local = poses[body].inverse() * point;
            Eigen::MatrixXd out(3, n);
            std::vector<double> q(values, values + n);
            // Central differences have an O(h^2) error; h = 1e-6 balances it against rounding in the poses (about 1e-16
            // / h).
            const double h = 1e-6;
            for (std::size_t c = 0; c < n; ++c)
            {
                const double keep = q[c];
                q[c] = keep + h;
                bodies.bodyPoses(q.data(), poses);
                const Eigen::Vector3d plus = poses[body] * local;
                q[c] = keep - h;
                bodies.bodyPoses(q.data(), poses);
                const Eigen::Vector3d minus = poses[body] * local;
                q[c] = keep;
                out.col(c) = (plus - minus) / (2. * h);
            }
            return out;
        }

        bool deformPath(ConfigurationPath &path, const validity::FclValidityChecker &checker,
                        const std::function<double(const Configuration &, const Configuration &)> &distance,
                        const std::function<void(const Configuration &, const Configuration &, double, Configuration &)>
                            &interpolate,
                        const std::function<bool(const ConfigurationPath &)> &accept,
                        const DeformationSettings &settings)
        {
            if (path.size() < 2)
                return false;
            // the window: waypoints every `spacing` along the first `window` of the path; the rest is kept
            // Paper 002, Fig. 3 (temporal adaptation): only the near part of the path is deformed, the rest is kept as
            // planned. Resampling at settings.spacing gives the deformation waypoints to push, however long the
            // original segments are.
            ConfigurationPath wp{path.front()};
            std::size_t rest = path.size();  // index of the first original waypoint after the window
            double arc = 0.;
            for (std::size_t i = 1; i < path.size(); ++i)
            {
                const double len = distance(path[i - 1], path[i]);
                const int pieces = std::max(1, static_cast<int>(std::ceil(len / settings.spacing)));
                for (int k = 1; k <= pieces; ++k)
                {
                    Configuration q;
                    interpolate(path[i - 1], path[i], static_cast<double>(k) / pieces, q);
                    wp.push_back(q);
                }
                arc += len;
                if (arc >= settings.window)
                {
                    // the last window waypoint is path[i] itself, so the kept part resumes after it
                    rest = i + 1;
                    break;
                }
            }
            const std::size_t m = wp.size();
            // Below three waypoints there is no interior one: the ends stay fixed (the robot's own state and the join
            // to the rest).
            if (m < 3)
                return false;
            const auto &bodies = *checker.bodies();
            const std::size_t dof = bodies.dimension();
            bool moved = false;
            for (unsigned int it = 0; it < settings.iterations; ++it)
            {
                std::vector<Eigen::VectorXd> change(m, Eigen::VectorXd::Zero(dof));
                bool any = false;
                for (std::size_t i = 1; i + 1 < m; ++i)
                {
                    const validity::Proximity p = checker.proximity(wp[i].data());
                    // Only waypoints closer than the deformation start distance d_i are pushed (paper 002).
                    if (p.distance >= settings.startDistance)
                        continue;
                    if (p.distance <= 1e-9 || p.body < 0)
                        return false;  // in collision: no direction to push; replanning must do it
                    const Eigen::Vector3d n = (p.robotPoint - p.otherPoint).normalized();
                    const Eigen::MatrixXd j = pointJacobian(bodies, wp[i].data(), p.body, p.robotPoint);
                    // Paper 002 maps the small displacement of P to joints without inverting the Jacobian: dq = J^T n
                    // (d_i - d) / |J^T n|^2 moves P by d_i - d along n to first order (the minimum-norm step for this
                    // single row).
                    const Eigen::VectorXd g = j.transpose() * n;
                    const double gg = g.squaredNorm();
                    // No joint moves the closest point along n (a singular configuration): nothing to push with here.
                    if (gg < 1e-12)
                        continue;
                    Eigen::VectorXd dq = g * ((settings.startDistance - p.distance) / gg);
                    // The first-order step is only trusted locally; maxStep bounds it, and the iterations make up the
                    // rest.
                    if (dq.norm() > settings.maxStep)
                        dq *= settings.maxStep / dq.norm();
                    for (int k = -settings.spread; k <= settings.spread; ++k)
                    {
                        const long idx = static_cast<long>(i) + k;
                        if (idx <= 0 || idx >= static_cast<long>(m) - 1)
                            continue;
                        // Gaussian fall-off over the neighbours, so one pushed waypoint does not leave a kink; the
                        // window's ends (indices 0 and m - 1) are never moved.
                        const double w = std::exp(-2. * k * k / (settings.spread * settings.spread + 1.));
                        change[idx] += w * dq;
                    }
                    any = true;
                }
                if (!any)
                    break;
                for (std::size_t i = 1; i + 1 < m; ++i)
                {
                    // Several pushed neighbours can add up on one waypoint: bound the sum too.
                    if (change[i].norm() > settings.maxStep)
                        change[i] *= settings.maxStep / change[i].norm();
                    for (std::size_t c = 0; c < dof; ++c)
                        wp[i][c] += change[i][c];
                }
                moved = true;
            }
            if (!moved)
                return false;
            ConfigurationPath out = wp;
            for (std::size_t i = rest; i < path.size(); ++i)
                out.push_back(path[i]);
            // The deformed path is only first-order and was not collision-checked along its motions: the caller decides
            // (michi replan checks it against the predicted world); a rejected path is left as it was and the executor
            // replans.
            if (!accept(out))
                return false;
            path = std::move(out);
            return true;
        }
    }  // namespace planners
}  // namespace michi
