#include "PathClearance.h"

#include <michi/validity/robot/CollisionBodies.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ob = ompl::base;

namespace michi
{
    namespace planners
    {
        namespace
        {
            double distanceAt(const validity::JMapValidityChecker &checker, double x, double y, double cap)
            {
                // A point inside a polygon has no clearance, whatever its distance to the boundary.
                const validity::JMap &tile = checker.tile(x);
                if (tile.collides(x, y))
                    return 0.;
                return tile.distanceToBoundary(x, y, cap);
            }

            double cross(const Eigen::Vector2d &u, const Eigen::Vector2d &v)
            {
                return u.x() * v.y() - u.y() * v.x();
            }

            double pointSegmentSquared(const Eigen::Vector2d &p, const Eigen::Vector2d &a, const Eigen::Vector2d &b)
            {
                const Eigen::Vector2d ab = b - a;
                const double len2 = ab.squaredNorm();
                const double t = len2 > 0. ? std::clamp((p - a).dot(ab) / len2, 0., 1.) : 0.;
                return (a + t * ab - p).squaredNorm();
            }

            /** squared distance between segments [a, b] and [c, d]: 0 when they cross, else the nearest of the four
                end-point-to-segment distances (in the plane the closest pair of two disjoint segments always has an
                end point in it) */
            double segmentSegmentSquared(const Eigen::Vector2d &a, const Eigen::Vector2d &b, const Eigen::Vector2d &c,
                                         const Eigen::Vector2d &d)
            {
                const double d1 = cross(d - c, a - c), d2 = cross(d - c, b - c);
                const double d3 = cross(b - a, c - a), d4 = cross(b - a, d - a);
                if (((d1 > 0. && d2 < 0.) || (d1 < 0. && d2 > 0.)) && ((d3 > 0. && d4 < 0.) || (d3 < 0. && d4 > 0.)))
                    return 0.;
                return std::min({pointSegmentSquared(a, c, d), pointSegmentSquared(b, c, d),
                                 pointSegmentSquared(c, a, b), pointSegmentSquared(d, a, b)});
            }

        }  // namespace

        const validity::FclValidityChecker *fclOf(const ob::SpaceInformation &si)
        {
            const auto *checker = si.getStateValidityChecker().get();
            if (const auto *f = dynamic_cast<const validity::FclValidityChecker *>(checker))
                return f;
            if (const auto *j = dynamic_cast<const validity::JMapValidityChecker *>(checker))
                // A J-map checker keeps an FCL checker of the same robot and scene (its source of intervals): its
                // geometry.
                return j->fcl().get();
            return nullptr;
        }

        std::shared_ptr<const CapsuleClearance> CapsuleClearance::make(const ob::SpaceInformation &si)
        {
            const auto *fcl = fclOf(si);
            const auto *group = fcl ? dynamic_cast<const validity::RobotGroupBodies *>(fcl->bodies().get()) : nullptr;
            if (group == nullptr)
                return nullptr;
            std::shared_ptr<CapsuleClearance> out(new CapsuleClearance());
            try
            {
                out->arm_ = validity::PlanarArm::fromModel(*group->model());
            }
            catch (const std::invalid_argument &)
            {
                return nullptr;  // a joint that does not turn about z: no planar model, FCL measures instead
            }
            out->variables_ = group->variables();
            const std::vector<double> unset(out->variables_.size(), 0.);
            out->configuration_ = group->fullConfiguration(unset.data());
            for (const auto &poly : fcl->scene()->polygons2d())
            {
                auto addRing = [&out](const validity::Polygon2::ring_type &ring)
                {
                    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
                        out->edges_.push_back({{ring[i].x(), ring[i].y()}, {ring[i + 1].x(), ring[i + 1].y()}});
                };
                addRing(poly.outer());
                for (const auto &inner : poly.inners())
                    addRing(inner);
            }
            if (out->edges_.empty())
                return nullptr;
            for (const Edge2 &e : out->edges_)
            {
                out->boxLo_.push_back(e.a.cwiseMin(e.b));
                out->boxHi_.push_back(e.a.cwiseMax(e.b));
            }
            return out;
        }

        double CapsuleClearance::at(const double *values) const
        {
            // Per-thread buffers: the push calls this six times per point and step, and allocating the model's
            // configuration, frames and capsules each time cost as much as the distances.
            thread_local std::vector<double> q;
            thread_local std::vector<validity::Capsule2> capsules;
            thread_local std::vector<Eigen::Isometry2d> frames;
            q = configuration_;
            // The group's values into the model's configuration (the other joints keep the values the checker uses).
            for (std::size_t i = 0; i < variables_.size(); ++i)
                q[variables_[i]] = values[i];
            arm_->worldCapsules(q.data(), capsules, frames);
            double best = std::numeric_limits<double>::infinity();
            for (const auto &capsule : capsules)
            {
                const Eigen::Vector2d lo = capsule.a.cwiseMin(capsule.b), hi = capsule.a.cwiseMax(capsule.b);
                double nearest = std::numeric_limits<double>::infinity();
                for (std::size_t k = 0; k < edges_.size(); ++k)
                {
                    // The boxes' gap is a lower bound of the segments' distance: an edge whose box is already
                    // farther than the nearest edge found cannot be nearer.
                    const Eigen::Vector2d gap =
                        (lo - boxHi_[k]).cwiseMax(boxLo_[k] - hi).cwiseMax(Eigen::Vector2d::Zero());
                    if (gap.squaredNorm() >= nearest)
                        continue;
                    nearest = std::min(nearest, segmentSegmentSquared(capsule.a, capsule.b, edges_[k].a, edges_[k].b));
                }
                best = std::min(best, std::sqrt(nearest) - capsule.radius);
            }
            return std::max(best, 0.);
        }

        double jmapClearance(const ob::SpaceInformation &si, const validity::JMapValidityChecker &checker,
                             const ob::State *state, double cap)
        {
            std::vector<double> v;
            si.getStateSpace()->copyToReals(v, state);
            return distanceAt(checker, v[0], v[1], cap);
        }

        double jmapPathClearance(const ob::SpaceInformation &si, const validity::JMapValidityChecker &checker,
                                 const std::vector<ob::State *> &states, double cap, double floor)
        {
            // Clearance is capped: the slab walk looks only within cap of the point, which bounds its cost.
            double worst = cap;
            ob::State *between = si.allocState();
            for (std::size_t i = 0; i < states.size() && worst > floor; ++i)
            {
                worst = std::min(worst, jmapClearance(si, checker, states[i], cap));
                if (i + 1 == states.size() || worst <= floor)
                    break;
                // the segment's interior at the resolution the motion validator samples a discrete check at
                const unsigned int n = si.getStateSpace()->validSegmentCount(states[i], states[i + 1]);
                for (unsigned int k = 1; k < n; ++k)
                {
                    si.getStateSpace()->interpolate(states[i], states[i + 1], static_cast<double>(k) / n, between);
                    worst = std::min(worst, jmapClearance(si, checker, between, cap));
                    if (worst <= floor)
                        break;
                }
            }
            si.freeState(between);
            return worst;
        }

        std::size_t splitDirectLink(const ob::SpaceInformationPtr &si, std::vector<ob::State *> &states, double piece)
        {
            if (states.size() != 2)
                return 0;
            // 0.05 of the extent: on 30 held-out random scenes (michi random-scenes --seed 201) the direct links'
            // clearance averaged along them rose by 1-96 % (docs/concentric-circle.md); 0.25 left most links
            // whole, 0.025 gained no more than 0.05
            const double step = piece * si->getMaximumExtent();
            const double length = si->distance(states[0], states[1]);
            const auto n = static_cast<std::size_t>(std::ceil(length / step));
            if (!(step > 0.) || n < 2)
                return 0;
            std::vector<ob::State *> split{states[0]};
            for (std::size_t k = 1; k < n; ++k)
            {
                split.push_back(si->allocState());
                si->getStateSpace()->interpolate(states[0], states[1], static_cast<double>(k) / n, split.back());
            }
            split.push_back(states[1]);
            // The pieces of a valid motion are valid for an exact or conservative motion validator, but not
            // necessarily for a sampling one (other samples): checked, so the path stays valid motion by motion.
            bool valid = true;
            for (std::size_t j = 1; valid && j < split.size(); ++j)
                valid = si->isValid(split[j]) && si->checkMotion(split[j - 1], split[j]);
            if (!valid)
            {
                for (std::size_t j = 1; j + 1 < split.size(); ++j)
                    si->freeState(split[j]);
                return 0;
            }
            states = std::move(split);
            return n - 1;
        }

        int pushAwayFromObstacles(const ob::SpaceInformationPtr &si, std::vector<ob::State *> &states,
                                  const ob::PlannerTerminationCondition &ptc, const ClearanceFunction &clearance,
                                  int sweeps, double step)
        {
            if (states.size() < 3)
                return 0;
            const auto &space = si->getStateSpace();
            const auto &checker = si->getStateValidityChecker();
            ob::State *moved = si->allocState();
            ob::State *probe = si->allocState();
            std::vector<double> v, w;
            auto measure = [&](const ob::State *s)
            {
                return clearance ? clearance(s) : checker->clearance(s);
            };
            auto clearanceAt = [&](const std::vector<double> &values)
            {
                space->copyFromReals(probe, values);
                return si->satisfiesBounds(probe) && checker->isValid(probe) ? measure(probe) : 0.;
            };
            int kept = 0;
            for (int sweep = 0; sweep < sweeps && !ptc && step > 1e-3; ++sweep)
            {
                int keptThisSweep = 0;
                const double h = 0.25 * step;  // central differences, narrower than a step
                for (std::size_t i = 1; i + 1 < states.size() && !ptc; ++i)
                {
                    space->copyToReals(v, states[i]);
                    const double c0 = clearanceAt(v);
                    double g[2];
                    for (int a = 0; a < 2; ++a)
                    {
                        w = v;
                        w[a] = v[a] + h;
                        const double up = clearanceAt(w);
                        w[a] = v[a] - h;
                        g[a] = up - clearanceAt(w);
                    }
                    const double norm = std::hypot(g[0], g[1]);
                    if (!(norm > 1e-12))
                        continue;  // on a ridge of the clearance: nowhere better close by
                    w = v;
                    w[0] += step * g[0] / norm;
                    w[1] += step * g[1] / norm;
                    space->copyFromReals(moved, w);
                    // kept only if clearer, valid, and both motions pass: the path stays a valid path at every move
                    if (!si->satisfiesBounds(moved) || !checker->isValid(moved) || measure(moved) <= c0 ||
                        !si->checkMotion(states[i - 1], moved) || !si->checkMotion(moved, states[i + 1]))
                        continue;
                    si->copyState(states[i], moved);
                    ++keptThisSweep;
                }
                kept += keptThisSweep;
                // A sweep that moved nothing: the step is too long for what is left to gain, so halve it (down to
                // 1e-3).
                if (keptThisSweep == 0)
                    step *= 0.5;
            }
            si->freeState(probe);
            si->freeState(moved);
            return kept;
        }
    }  // namespace planners
}  // namespace michi
