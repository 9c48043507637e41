#include <michi/validity/grid/GridMotionValidator.h>
#include <michi/validity/MotionCount.h>
#include <michi/state_spaces/TurnMoveTurnStateSpace.h>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/SE2StateSpace.h>

#include <boost/math/constants/constants.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ob = ompl::base;

namespace michi
{
    namespace validity
    {
        namespace
        {
            const double PI = boost::math::constants::pi<double>();

            /** The signed turn SO2StateSpace::interpolate makes from \e a to \e b. */
            double so2Turn(double a, double b)
            {
                double d = b - a;
                if (std::fabs(d) <= PI)
                    return d;
                return d > 0. ? d - 2. * PI : d + 2. * PI;
            }
        }  // namespace

        GridMotionValidator::GridMotionValidator(const ob::SpaceInformationPtr &si, GridValidityCheckerPtr checker)
            : ob::MotionValidator(si), checker_(std::move(checker))
        {
            if (!checker_)
                throw std::invalid_argument("GridMotionValidator: no grid checker");
            if (!dynamic_cast<const ob::SE2StateSpace *>(si->getStateSpace().get()))
                throw std::invalid_argument("GridMotionValidator: needs an SE2StateSpace (or TurnMoveTurnStateSpace)");
            turnMoveTurn_ = dynamic_cast<const state_spaces::TurnMoveTurnStateSpace *>(si->getStateSpace().get());
        }

        std::vector<GridMotionValidator::Piece> GridMotionValidator::pieces(const double *a, const double *b) const
        {
            std::vector<Piece> out;
            if (!turnMoveTurn_)
            {
                // The end yaw is left unwrapped (start plus the short turn), so the walk crosses ±pi without a jump;
                // bins are taken modulo the heading count below.
                out.push_back(Piece{a[0], a[1], a[2], b[0], b[1], a[2] + so2Turn(a[2], b[2]), 0., 1.});
                return out;
            }
            const auto m = turnMoveTurn_->motion(a[0], a[1], a[2], b[0], b[1], b[2]);
            const double w = turnMoveTurn_->getTurnWeight();
            const double c1 = w * std::abs(m.turn1), c2 = w * std::abs(m.turn2);
            const double total = c1 + m.move + c2;
            if (!(total > 0.) || m.move == 0.)
            {
                // one turn in place (or no motion): interpolate() keeps the first position throughout
                out.push_back(Piece{a[0], a[1], a[2], a[0], a[1], a[2] + m.turn1, 0., 1.});
                return out;
            }
            // Each piece's share of the motion is its share of the cost, as TurnMoveTurnStateSpace::interpolate()
            // spends it, so a contact's t is the motion's own.
            const double f1 = c1 / total, f2 = (c1 + m.move) / total;
            out.push_back(Piece{a[0], a[1], a[2], a[0], a[1], a[2] + m.turn1, 0., f1});
            out.push_back(Piece{a[0], a[1], m.heading, b[0], b[1], m.heading, f1, f2});
            out.push_back(Piece{b[0], b[1], m.heading, b[0], b[1], m.heading + m.turn2, f2, 1.});
            return out;
        }

        bool GridMotionValidator::walk(const std::vector<Piece> &pieces, double *contact, double *lastFree) const
        {
            const HeadingTable &table = checker_->table();
            const OccupancyGrid &g = table.grid();
            const double inf = std::numeric_limits<double>::infinity();
            double lastEnter = 0.;  // motion fraction at which the current (valid) entry was entered
            bool first = true;
            std::uint64_t visited = 0;
            for (const auto &piece : pieces)
            {
                // coordinates in cells and bins: floor gives the entry (bin k covers [k - 1/2, k + 1/2] steps)
                const double p[3] = {(piece.x0 - g.origin.x()) / g.resolution, (piece.y0 - g.origin.y()) / g.resolution,
                                     piece.yaw0 / table.headingStep() + 0.5};
                const double q[3] = {(piece.x1 - g.origin.x()) / g.resolution, (piece.y1 - g.origin.y()) / g.resolution,
                                     piece.yaw1 / table.headingStep() + 0.5};
                long long idx[3], end[3];
                int step[3];
                double tMax[3], tDelta[3];
                long long remaining = 0;
                for (int k = 0; k < 3; ++k)
                {
                    // Too far to convert to an integer cell: refused (conservative), never walked with overflowed
                    // indices.
                    if (!std::isfinite(p[k]) || !std::isfinite(q[k]) || std::abs(p[k]) > 1e12 || std::abs(q[k]) > 1e12)
                    {
                        visited_.fetch_add(visited, std::memory_order_relaxed);
                        if (contact)
                            *contact = piece.t0;
                        if (lastFree)
                            *lastFree = first ? 0. : lastEnter;
                        return false;
                    }
                    idx[k] = static_cast<long long>(std::floor(p[k]));
                    end[k] = static_cast<long long>(std::floor(q[k]));
                    const double d = q[k] - p[k];
                    step[k] = end[k] > idx[k] ? 1 : (end[k] < idx[k] ? -1 : 0);
                    if (step[k] == 0 || d == 0.)
                    {
                        step[k] = 0;
                        end[k] = idx[k];
                        tMax[k] = tDelta[k] = inf;
                        continue;
                    }
                    // Amanatides-Woo voxel walk: tDelta is the piece fraction per cell along axis k, tMax the fraction
                    // at which the next cell border of that axis is crossed.
                    tDelta[k] = 1. / std::abs(d);
                    tMax[k] = step[k] > 0 ? (static_cast<double>(idx[k] + 1) - p[k]) / d
                                          : (p[k] - static_cast<double>(idx[k])) / -d;
                    // Every border crossing enters one new entry: remaining counts the entries still to visit.
                    remaining += std::llabs(end[k] - idx[k]);
                }
                double u = 0.;
                for (;;)
                {
                    ++visited;
                    const double t = piece.t0 + std::min(1., u) * (piece.t1 - piece.t0);
                    // % of a negative number is negative in C++: shifted into 0..headings-1.
                    const int k = static_cast<int>(((idx[2] % table.headings()) + table.headings()) % table.headings());
                    bool free = idx[0] >= 0 && idx[1] >= 0 && idx[0] < g.width && idx[1] < g.height;
                    if (free && !table.valid(static_cast<int>(idx[0]), static_cast<int>(idx[1]), k))
                    {
                        // the entry holds a colliding pose, maybe not this piece's: check the piece's poses in it
                        double uNext = 1.;
                        for (int a = 0; a < 3; ++a)
                            if (idx[a] != end[a])
                                uNext = std::min(uNext, tMax[a]);
                        free = checker_->exact() && exactSpan(piece, std::min(1., u), uNext);
                    }
                    if (!free)
                    {
                        visited_.fetch_add(visited, std::memory_order_relaxed);
                        if (contact)
                            *contact = t;
                        if (lastFree)
                            *lastFree = first ? 0. : 0.5 * (lastEnter + t);
                        return false;
                    }
                    if (first || u > 0.)
                        lastEnter = t;
                    first = false;
                    if (remaining == 0)
                        break;
                    int axis = -1;
                    // The axis whose next border comes first: the segment leaves the entry there.
                    for (int a = 0; a < 3; ++a)
                        if (idx[a] != end[a] && (axis < 0 || tMax[a] < tMax[axis]))
                            axis = a;
                    u = tMax[axis];
                    idx[axis] += step[axis];
                    tMax[axis] += tDelta[axis];
                    --remaining;
                }
            }
            visited_.fetch_add(visited, std::memory_order_relaxed);
            return true;
        }

        bool GridMotionValidator::exactSpan(const Piece &piece, double ua, double ub) const
        {
            // no footprint point moves farther than L over the span (position change plus circumradius times the
            // turn); poses n + 1 equally spaced hold every pose between within L / (2 n) of one of them, so each
            // is tested with the footprint grown by that
            const HeadingTable &table = checker_->table();
            const double span = std::max(0., ub - ua);
            const double length = span * (std::hypot(piece.x1 - piece.x0, piece.y1 - piece.y0) +
                                          table.circumradius() * std::abs(piece.yaw1 - piece.yaw0));
            const double spacing = EXACT_SPACING * table.grid().resolution;
            const int n = std::max(1, static_cast<int>(std::ceil(length / spacing)));
            // A span too long for the exact test within bounded work is refused, not passed unchecked.
            if (n > 100000)
                return false;
            const double margin = length / (2. * n);
            for (int i = 0; i <= n; ++i)
            {
                const double u = ua + span * i / n;
                if (!table.freePose(piece.x0 + u * (piece.x1 - piece.x0), piece.y0 + u * (piece.y1 - piece.y0),
                                    piece.yaw0 + u * (piece.yaw1 - piece.yaw0), margin))
                    return false;
            }
            return true;
        }

        bool GridMotionValidator::check(const ob::State *s1, const ob::State *s2,
                                        std::pair<ob::State *, double> *lastValid) const
        {
            const auto *a = s1->as<ob::SE2StateSpace::StateType>();
            const auto *b = s2->as<ob::SE2StateSpace::StateType>();
            const double from[3] = {a->getX(), a->getY(), a->getYaw()};
            const double to[3] = {b->getX(), b->getY(), b->getYaw()};
            double contact = 0., lastFree = 0.;
            if (walk(pieces(from, to), &contact, &lastFree))
            {
                countMotion(valid_);
                return true;
            }
            if (lastValid)
            {
                if (lastValid->first)
                    si_->getStateSpace()->interpolate(s1, s2, lastFree, lastValid->first);
                lastValid->second = lastFree;
            }
            countMotion(invalid_);
            return false;
        }

        bool GridMotionValidator::checkMotion(const ob::State *s1, const ob::State *s2) const
        {
            return check(s1, s2, nullptr);
        }

        bool GridMotionValidator::checkMotion(const ob::State *s1, const ob::State *s2,
                                              std::pair<ob::State *, double> &lastValid) const
        {
            return check(s1, s2, &lastValid);
        }
    }  // namespace validity
}  // namespace michi
