/* J-map intervals of any URDF arm from FCL: a theta2 sweep certified by distances and displacement bounds. */

#include <michi/validity/jmap/JMap.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace michi
{
    namespace validity
    {
        FclIntervalSource::FclIntervalSource(FclValidityCheckerPtr checker, JMapAxes axes, double step, double margin)
            : checker_(std::move(checker)), axes_(std::move(axes)), step_(step), margin_(margin)
        {
            const auto bodies = std::dynamic_pointer_cast<const RobotGroupBodies>(checker_->bodies());
            if (!bodies)
                throw std::invalid_argument("FclIntervalSource: the checker's bodies are not a RobotGroupBodies");
            if (!(step_ > 0.))
                throw std::invalid_argument("FclIntervalSource: step must be > 0");
            const RobotModel &model = *bodies->model();
            const int n = static_cast<int>(model.variableCount());
            groupIndex_.assign(n, -1);
            for (std::size_t i = 0; i < bodies->variables().size(); ++i)
                groupIndex_[bodies->variables()[i]] = static_cast<int>(i);
            if (axes_.axis1 < 0 || axes_.axis1 >= n || axes_.axis2 < 0 || axes_.axis2 >= n ||
                axes_.axis1 == axes_.axis2 || groupIndex_[axes_.axis1] < 0 || groupIndex_[axes_.axis2] < 0)
                throw std::invalid_argument("FclIntervalSource: axes " + std::to_string(axes_.axis1) + ", " +
                                            std::to_string(axes_.axis2) + " must be two joints of the checker's group");
            // The joints other than the two axes stay at this configuration; by default the group's zero pose.
            if (axes_.configuration.empty())
                axes_.configuration = bodies->fullConfiguration(std::vector<double>(bodies->dimension(), 0.).data());
            if (axes_.configuration.size() != static_cast<std::size_t>(n))
                throw std::invalid_argument("FclIntervalSource: configuration has " +
                                            std::to_string(axes_.configuration.size()) + " values, robot has " +
                                            std::to_string(n));
            axes_.halfWidths.resize(n, 0.);
            for (int v = 0; v < n; ++v)
                if (axes_.halfWidths[v] > 0. && groupIndex_[v] < 0)
                    throw std::invalid_argument("FclIntervalSource: joint " + std::to_string(v) +
                                                " has a half width but is not in the checker's group");
            auto limits = [&](int v, double &lo, double &hi)
            {
                const RobotJoint &joint = model.variableJoint(v);
                lo = joint.type == RobotJoint::Type::CONTINUOUS ? -M_PI : joint.lower;
                hi = joint.type == RobotJoint::Type::CONTINUOUS ? M_PI : joint.upper;
            };
            if (axes_.lo1 >= axes_.hi1)
                limits(axes_.axis1, axes_.lo1, axes_.hi1);
            if (axes_.lo2 >= axes_.hi2)
                limits(axes_.axis2, axes_.lo2, axes_.hi2);

            const std::size_t nb = bodies->bodies().size();
            bound1_.resize(nb);
            bound2_.resize(nb);
            boundOther_.assign(nb, 0.);
            moves2_.resize(nb);
            for (std::size_t b = 0; b < nb; ++b)
            {
                const int link = bodies->bodyLink(b);
                // Per body, a Lipschitz bound: how far any point of it moves per radian of each joint. With distances
                // these turn one FCL query into a whole certified-free interval of theta2.
                bound1_[b] = model.displacementBound(axes_.axis1, link);
                bound2_[b] = model.displacementBound(axes_.axis2, link);
                // Joints with a half width may be anywhere within it (a stack's outer joint cell): their
                // worst-case motion is charged to every body up front.
                for (int v = 0; v < n; ++v)
                    if (v != axes_.axis1 && v != axes_.axis2 && axes_.halfWidths[v] > 0.)
                        boundOther_[b] += model.displacementBound(v, link) * axes_.halfWidths[v];
                moves2_[b] = bound2_[b] > 0.;
            }
        }

        std::uint64_t FclIntervalSource::queries() const
        {
            return queries_.load();
        }

        std::vector<JointInterval> FclIntervalSource::intervals(double theta1) const
        {
            return sweep(theta1, -1.);
        }

        std::vector<JointInterval> FclIntervalSource::cellIntervals(double lo, double hi) const
        {
            return sweep(0.5 * (lo + hi), 0.5 * (hi - lo));
        }

        bool FclIntervalSource::collides(double theta1, double theta2) const
        {
            const auto &vars = std::static_pointer_cast<const RobotGroupBodies>(checker_->bodies())->variables();
            std::vector<double> values(vars.size());
            for (std::size_t i = 0; i < vars.size(); ++i)
                values[i] = axes_.configuration[vars[i]];
            values[groupIndex_[axes_.axis1]] = theta1;
            values[groupIndex_[axes_.axis2]] = theta2;
            return !checker_->isValidConfiguration(values.data());
        }

        std::vector<JointInterval> FclIntervalSource::sweep(double theta1, double half) const
        {
            // half < 0: the true intervals at theta1 (no cell, other joints exactly at their values)
            const bool cell = half >= 0.;
            half = std::max(half, 0.);
            const double lo2 = axes_.lo2, hi2 = axes_.hi2;
            const auto &bodies = *checker_->bodies();
            const auto &vars = std::static_pointer_cast<const RobotGroupBodies>(checker_->bodies())->variables();
            std::vector<double> values(vars.size());
            for (std::size_t i = 0; i < vars.size(); ++i)
                values[i] = axes_.configuration[vars[i]];
            values[groupIndex_[axes_.axis1]] = theta1;
            const int i2 = groupIndex_[axes_.axis2];
            const std::vector<char> wantBodies(bodies.bodies().size(), 1);
            const std::vector<char> wantPairs(bodies.selfCheckPairs().size(), 1);
            std::vector<double> obstacle, self;
            const double inf = std::numeric_limits<double>::infinity();
            bool always = false;  // a collision no theta2 can avoid

            // half width of the certified free interval about theta2 = s (negative: not certified at s)
            auto certify = [&](double s)
            {
                values[i2] = s;
                checker_->bodyDistances(values.data(), wantBodies, wantPairs, obstacle, self);
                ++queries_;
                double w = inf;
                auto limit = [&](double distance, double fixedMotion, double rate)
                {
                    // A body at distance d stays clear while theta2 changes by less than (d - margin - motion from the
                    // other joints) / rate. A body theta2 does not move (rate 0) with no slack collides for every
                    // theta2.
                    const double slack = distance - margin_ - fixedMotion;
                    if (rate > 0.)
                        w = std::min(w, slack / rate);
                    else if (slack <= 0.)
                        always = true;
                };
                for (std::size_t b = 0; b < obstacle.size(); ++b)
                    limit(obstacle[b], bound1_[b] * half + (cell ? boundOther_[b] : 0.), bound2_[b]);
                const auto &pairs = bodies.selfCheckPairs();
                for (std::size_t k = 0; k < pairs.size(); ++k)
                {
                    const int a = pairs[k].first, b = pairs[k].second;
                    limit(self[k], (bound1_[a] + bound1_[b]) * half + (cell ? boundOther_[a] + boundOther_[b] : 0.),
                          bound2_[a] + bound2_[b]);
                }
                return w;
            };

            std::vector<JointInterval> out;
            double x = lo2, guess = 0.;
            while (x < hi2 && !always)
            {
                // Stepping: certify at s = x + guess (90 % of the last free half width), so that the interval about s
                // usually starts before x and the free stretch continues without a gap; if it does not reach back to x,
                // certify at x itself.
                double s = std::min(x + guess, hi2);
                double w = certify(s);
                if (guess > 0. && (w < step_ || s - w > x))
                {
                    s = x;
                    w = certify(s);
                }
                if (always)
                    break;
                if (w >= step_)
                {
                    x = s + w;
                    guess = 0.9 * w;
                }
                else
                {
                    // Not certifiable within one step: the whole step counts as colliding (conservative), at the cost
                    // of step_ resolution.
                    out.push_back({x, std::min(x + step_, hi2)});
                    x += step_;
                    guess = 0.;
                }
            }
            if (always)
                return {{lo2, hi2}};
            return mergeIntervals(std::move(out));
        }
    }  // namespace validity
}  // namespace michi
