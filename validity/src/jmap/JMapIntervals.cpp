/* Exact collision intervals of a planar arm (capsules) among polygons: critical angles + midpoint tests. */

#include <michi/validity/jmap/JMap.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bg = boost::geometry;

namespace michi
{
    namespace validity
    {
        namespace
        {
            /** \brief Interval ends are widened by this much (radians) against rounding of critical angles. */
            const double PAD = 1e-9;
            /** \brief Critical angles closer than this are merged. */
            const double SAME = 1e-13;

            double chord(double angle)
            {
                // How far a point at unit distance from the axis moves when turned by angle: the chord, not the arc.
                // Capped at pi so the value bounds every turn up to angle (the chord shrinks again past half a turn).
                return 2. * std::sin(0.5 * std::min(std::abs(angle), M_PI));
            }

            /** \brief Push \e alpha +- acos(c) (when |c| <= 1, up to rounding) into \e out. */
            void pushAcos(double alpha, double c, std::vector<double> &out)
            {
                // A tangency computed with rounding can land just past +-1; it is still a critical angle, so clamp
                // rather than drop.
                if (c > 1. + 1e-12 || c < -1. - 1e-12)
                    return;
                const double a = std::acos(std::max(-1., std::min(1., c)));
                out.push_back(alpha + a);
                out.push_back(alpha - a);
            }

            double angleOf(const Eigen::Vector2d &v)
            {
                return std::atan2(v.y(), v.x());
            }

            /** \brief A capsule turning about the pivot: end points relative to the pivot at theta2 = 0. */
            struct Turning
            {
                Eigen::Vector2d a, b;
                double radius;
            };

            /** \brief Critical world rotation angles of capsule \e c about the origin against the rings of
                \e near (coordinates relative to the pivot). */
            void criticalAngles(const Turning &c, const std::vector<std::vector<Eigen::Vector2d>> &rings,
                                std::vector<double> &out)
            {
                const double rho = c.radius;
                const Eigen::Vector2d ab = c.b - c.a;
                const bool segment = ab.norm() > 1e-12;
                Eigen::Vector2d u = Eigen::Vector2d::UnitX(), n = Eigen::Vector2d::UnitY();
                double offset = 0.;
                if (segment)
                {
                    u = ab.normalized();
                    n = Eigen::Vector2d(-u.y(), u.x());
                    offset = n.dot(c.a);
                }
                const double nu = angleOf(n), delta = angleOf(u);
                const Eigen::Vector2d ends[2] = {c.a, c.b};
                for (const auto &ring : rings)
                {
                    const std::size_t m = ring.size();
                    for (std::size_t i = 0; i < m; ++i)
                    {
                        const Eigen::Vector2d &v = ring[i];
                        const Eigen::Vector2d &w = ring[(i + 1) % m];
                        const double d = v.norm(), alpha = angleOf(v);
                        // the segment's line passes at rho from vertex v
                        if (segment && d > 0.)
                            for (double side : {-1., 1.})
                                pushAcos(alpha - nu, (offset + side * rho) / d, out);
                        for (int e = 0; e < (segment ? 2 : 1); ++e)
                        {
                            const double re = ends[e].norm();
                            if (re <= 0.)
                                continue;  // an end on the pivot does not move
                            const double beta = angleOf(ends[e]);
                            // the end point meets the disk of radius rho about v
                            if (d > 0.)
                                // Law of cosines: |R(phi) e - v| = rho when cos(phi + beta - alpha) = (re^2 + d^2 -
                                // rho^2) / (2 re d).
                                pushAcos(alpha - beta, (re * re + d * d - rho * rho) / (2. * re * d), out);
                            // the end point meets the edge's line offset by +-rho
                            const Eigen::Vector2d edge = w - v;
                            if (edge.norm() <= 0.)
                                continue;
                            const Eigen::Vector2d mm = Eigen::Vector2d(-edge.y(), edge.x()).normalized();
                            const double cm = mm.dot(v), mu = angleOf(mm);
                            for (double side : {-1., 1.})
                                // The turned end's height along the edge normal, re cos(phi + beta - mu), equals the
                                // edge line's cm +- rho.
                                pushAcos(mu - beta, (cm + side * rho) / re, out);
                        }
                        // the segment is parallel to the edge
                        if (segment && (w - v).norm() > 0.)
                        {
                            const double gamma = angleOf(w - v);
                            // When the segment turns parallel to an edge, which feature is nearest can switch without
                            // any contact event above.
                            out.push_back(gamma - delta);
                            out.push_back(gamma - delta + M_PI);
                        }
                    }
                }
            }
        }  // namespace

        std::vector<JointInterval> mergeIntervals(std::vector<JointInterval> intervals, double gap)
        {
            std::sort(intervals.begin(), intervals.end(),
                      [](const JointInterval &x, const JointInterval &y)
                      {
                          return x.lo < y.lo;
                      });
            std::vector<JointInterval> out;
            for (const auto &i : intervals)
            {
                if (!out.empty() && i.lo <= out.back().hi + gap)
                    out.back().hi = std::max(out.back().hi, i.hi);
                else
                    out.push_back(i);
            }
            return out;
        }

        JMapAxes planarAxes(const PlanarArm &arm, int axis1, int axis2, std::vector<double> configuration)
        {
            JMapAxes axes;
            axes.axis1 = axis1;
            axes.axis2 = axis2;
            if (configuration.empty())
                configuration.assign(arm.variableCount(), 0.);
            axes.configuration = std::move(configuration);
            axes.lo1 = arm.lower(axis1);
            axes.hi1 = arm.upper(axis1);
            axes.lo2 = arm.lower(axis2);
            axes.hi2 = arm.upper(axis2);
            return axes;
        }

        PlanarIntervalSource::PlanarIntervalSource(PlanarArmPtr arm, MultiPolygon2 obstacles, JMapAxes axes,
                                                   std::vector<int> links)
            : arm_(std::move(arm)), obstacles_(std::move(obstacles)), axes_(std::move(axes))
        {
            const int n = static_cast<int>(arm_->variableCount());
            if (axes_.axis1 < 0 || axes_.axis1 >= n || axes_.axis2 < 0 || axes_.axis2 >= n ||
                axes_.axis1 == axes_.axis2)
                throw std::invalid_argument("J-map axes " + std::to_string(axes_.axis1) + ", " +
                                            std::to_string(axes_.axis2) + ": need two different joints of " +
                                            std::to_string(n));
            if (axes_.configuration.empty())
                axes_.configuration.assign(n, 0.);
            if (axes_.configuration.size() != static_cast<std::size_t>(n))
                throw std::invalid_argument("J-map configuration has " + std::to_string(axes_.configuration.size()) +
                                            " values, the arm has " + std::to_string(n) + " joints");
            axes_.halfWidths.resize(n, 0.);
            if (axes_.lo1 >= axes_.hi1)
            {
                axes_.lo1 = arm_->lower(axes_.axis1);
                axes_.hi1 = arm_->upper(axes_.axis1);
            }
            if (axes_.lo2 >= axes_.hi2)
            {
                axes_.lo2 = arm_->lower(axes_.axis2);
                axes_.hi2 = arm_->upper(axes_.axis2);
            }
            useLink_.assign(arm_->links().size(), links.empty() ? 1 : 0);
            for (int l : links)
                useLink_.at(l) = 1;
        }

        std::vector<double> PlanarIntervalSource::cellInflation(double half) const
        {
            std::vector<double> inflation(arm_->links().size(), 0.);
            for (std::size_t l = 0; l < inflation.size(); ++l)
            {
                const int link = static_cast<int>(l);
                inflation[l] = arm_->reachFrom(axes_.axis1, link) * chord(half);
                for (std::size_t v = 0; v < axes_.halfWidths.size(); ++v)
                    if (static_cast<int>(v) != axes_.axis1 && static_cast<int>(v) != axes_.axis2 &&
                        axes_.halfWidths[v] > 0.)
                        // Joints held at a cell centre (a stack's outer joint) add their own half width the same way.
                        inflation[l] += arm_->reachFrom(static_cast<int>(v), link) * chord(axes_.halfWidths[v]);
            }
            return inflation;
        }

        std::vector<JointInterval> PlanarIntervalSource::intervals(double theta1) const
        {
            return inflatedIntervals(theta1, std::vector<double>(arm_->links().size(), 0.));
        }

        std::vector<JointInterval> PlanarIntervalSource::cellIntervals(double lo, double hi) const
        {
            // Each subsample stands for a part of the column half as wide on each side: its intervals are inflated by
            // how far the links move over that half width, so together they hold every collision of the column.
            const double half = 0.5 * (hi - lo) / subsamples_;
            const auto inflation = cellInflation(half);
            std::vector<JointInterval> all;
            for (int k = 0; k < subsamples_; ++k)
            {
                const auto part = inflatedIntervals(lo + (2 * k + 1) * half, inflation);
                all.insert(all.end(), part.begin(), part.end());
            }
            return mergeIntervals(std::move(all));
        }

        bool PlanarIntervalSource::collides(double theta1, double theta2) const
        {
            std::vector<double> q = axes_.configuration;
            q[axes_.axis1] = theta1;
            q[axes_.axis2] = theta2;
            std::vector<int> owner;
            const auto caps = arm_->worldCapsules(q.data(), &owner);
            for (std::size_t i = 0; i < caps.size(); ++i)
                if (useLink_[owner[i]] && segmentDistance(caps[i].a, caps[i].b, obstacles_) <= caps[i].radius)
                    return true;
            return false;
        }

        std::vector<JointInterval> PlanarIntervalSource::inflatedIntervals(double theta1,
                                                                           const std::vector<double> &inflation) const
        {
            const double lo2 = axes_.lo2, hi2 = axes_.hi2;
            std::vector<double> q = axes_.configuration;
            q[axes_.axis1] = theta1;
            q[axes_.axis2] = 0.;
            std::vector<int> owner;
            const auto caps = arm_->worldCapsules(q.data(), &owner);
            const auto &joint = arm_->joints()[arm_->variableJoint(axes_.axis2)];
            const Eigen::Vector2d pivot = arm_->linkFrames(q.data())[joint.childLink].translation();
            const double sign = joint.axisSign;

            std::vector<JointInterval> result;
            for (std::size_t i = 0; i < caps.size(); ++i)
            {
                const int link = owner[i];
                if (!useLink_[link])
                    continue;
                const double rho = caps[i].radius + inflation[link];
                if (!arm_->moves(axes_.axis2, link))
                {
                    // not turned by axis 2: touching now means touching for every theta2
                    if (segmentDistance(caps[i].a, caps[i].b, obstacles_) <= rho)
                        return {{lo2, hi2}};
                    continue;
                }
                const Turning turning{caps[i].a - pivot, caps[i].b - pivot, rho};
                // Obstacles beyond this distance from the pivot cannot be met at any theta2: they add no critical
                // angles.
                const double reach = std::max(turning.a.norm(), turning.b.norm()) + rho;

                // obstacles the capsule can reach at all, relative to the pivot
                MultiPolygon2 near;
                std::vector<std::vector<Eigen::Vector2d>> rings;
                for (const auto &polygon : obstacles_)
                {
                    Box2 box(Point2(0., 0.), Point2(0., 0.));
                    bg::envelope(polygon, box);
                    const double dx =
                        std::max({box.min_corner().x() - pivot.x(), pivot.x() - box.max_corner().x(), 0.});
                    const double dy =
                        std::max({box.min_corner().y() - pivot.y(), pivot.y() - box.max_corner().y(), 0.});
                    if (std::hypot(dx, dy) > reach)
                        continue;
                    near.push_back(polygon);
                    auto addRing = [&](const Polygon2::ring_type &ring)
                    {
                        std::vector<Eigen::Vector2d> pts;
                        for (std::size_t k = 0; k + 1 < ring.size(); ++k)  // closed rings repeat the first point
                            pts.emplace_back(ring[k].x() - pivot.x(), ring[k].y() - pivot.y());
                        rings.push_back(std::move(pts));
                    };
                    addRing(polygon.outer());
                    for (const auto &inner : polygon.inners())
                        addRing(inner);
                }
                if (near.empty())
                    continue;

                std::vector<double> phis;
                criticalAngles(turning, rings, phis);
                std::vector<double> cuts{lo2, hi2};
                for (double phi : phis)
                {
                    // Critical angles repeat every turn: each copy inside the joint's range is a cut.
                    double t = sign * phi;                         // world rotation sign * theta2
                    t = std::remainder(t - lo2, 2. * M_PI) + lo2;  // in [lo2 - pi, lo2 + pi]
                    for (double tk = t; tk < hi2; tk += 2. * M_PI)
                        if (tk > lo2)
                            cuts.push_back(tk);
                }
                std::sort(cuts.begin(), cuts.end());
                std::vector<double> unique;
                for (double t : cuts)
                    if (unique.empty() || t - unique.back() > SAME)
                        unique.push_back(t);

                auto hits = [&](double theta2)
                {
                    const Eigen::Rotation2Dd rot(sign * theta2);
                    return segmentDistance(pivot + rot * turning.a, pivot + rot * turning.b, near) <= rho;
                };
                const std::size_t m = unique.size();
                std::vector<char> piece(m - 1, 0);
                for (std::size_t k = 0; k + 1 < m; ++k)
                    // No contact begins or ends between two critical angles, so one test at the middle classifies the
                    // whole piece.
                    piece[k] = hits(0.5 * (unique[k] + unique[k + 1]));
                for (std::size_t k = 0; k < m; ++k)
                {
                    const bool before = k > 0 && piece[k - 1];
                    const bool after = k + 1 < m && piece[k];
                    if (after)
                        result.push_back({unique[k], unique[k + 1]});
                    else if (!before && hits(unique[k]))
                        result.push_back({unique[k], unique[k]});  // an isolated touching angle
                }
            }
            auto merged = mergeIntervals(std::move(result));
            for (auto &i : merged)
            {
                i.lo = std::max(lo2, i.lo - PAD);
                i.hi = std::min(hi2, i.hi + PAD);
            }
            return mergeIntervals(std::move(merged));
        }
    }  // namespace validity
}  // namespace michi
