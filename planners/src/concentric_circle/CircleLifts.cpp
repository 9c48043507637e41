#include <michi/planners/concentric_circle/CircleLifts.h>
#include "PathClearance.h"

#include <michi/validity/robot/CollisionBodies.h>
#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/jmap/JMap.h>
#include <michi/validity/jmap/JMapValidityChecker.h>
#include <michi/validity/jmap/PlanarArm.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/util/Exception.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace ob = ompl::base;
namespace bg = boost::geometry;

namespace michi
{
    namespace planners
    {
        namespace
        {
            void collectAxes(const ob::StateSpace &space, std::vector<ValueAxis> &out)
            {
                if (space.isCompound())
                {
                    const auto &compound = *space.as<ob::CompoundStateSpace>();
                    for (unsigned int i = 0; i < compound.getSubspaceCount(); ++i)
                        collectAxes(*compound.getSubspace(i), out);
                    return;
                }
                if (space.getType() == ob::STATE_SPACE_SO2)
                {
                    // OMPL's SO(2) range; values wrap, so the maps work in unwrapped coordinates
                    // (docs/concentric-circle.md).
                    out.push_back({-M_PI, M_PI, true});
                    return;
                }
                if (const auto *rv = dynamic_cast<const ob::RealVectorStateSpace *>(&space))
                {
                    const auto &b = rv->getBounds();
                    for (unsigned int i = 0; i < rv->getDimension(); ++i)
                        out.push_back({b.low[i], b.high[i], false});
                    return;
                }
                throw ompl::Exception("ConcentricCircle",
                                      "state space '" + space.getName() +
                                          "' is neither a real vector nor an SO(2) space (nor a compound of them)");
            }

            /** b - a, the short way round on a wrapping axis */
            double difference(const ValueAxis &axis, double a, double b)
            {
                double d = b - a;
                if (axis.wraps)
                {
                    const double period = axis.hi - axis.lo;
                    // Subtracting the nearest whole number of periods leaves d in [-period/2, period/2]: the same
                    // convention as OMPL's SO(2) interpolation, so a map segment and the motion the space checks go the
                    // same way round.
                    d -= period * std::round(d / period);
                }
                return d;
            }

            std::vector<double> interpolate(const std::vector<ValueAxis> &axes, const std::vector<double> &from,
                                            const std::vector<double> &to, double t)
            {
                std::vector<double> v(from.size());
                for (std::size_t i = 0; i < from.size(); ++i)
                    v[i] = from[i] + t * difference(axes[i], from[i], to[i]);
                return v;
            }

        }  // namespace

        std::vector<ValueAxis> valueAxes(const ob::StateSpace &space)
        {
            std::vector<ValueAxis> out;
            collectAxes(space, out);
            return out;
        }

        void setStateValues(const ob::StateSpace &space, const std::vector<double> &values, ob::State *state)
        {
            space.copyFromReals(state, values);
            // Unwrapped map coordinates become OMPL values: SO(2) values are wrapped into [-pi, pi), bounded values
            // clamped.
            space.enforceBounds(state);
        }

        // ---------------------------------------------------------------- projection

        ProjectionLift::ProjectionLift(ob::SpaceInformationPtr si, std::vector<double> start, std::vector<double> goal,
                                       int axis1, int axis2)
            : si_(std::move(si))
            , start_(std::move(start))
            , goal_(std::move(goal))
            , axis1_(axis1)
            , axis2_(axis2)
            , axes_(valueAxes(*si_->getStateSpace()))
        {
            if (axes_.size() != start_.size())
                throw ompl::Exception("ConcentricCircle", "the space's values do not match its components");
            start2_ = Eigen::Vector2d(start_[axis1_], start_[axis2_]);
            // The goal's image nearest to the start: on a wrapping axis the map never goes the long way round unless it
            // must.
            goal2_ = start2_ + Eigen::Vector2d(difference(axes_[axis1_], start_[axis1_], goal_[axis1_]),
                                               difference(axes_[axis2_], start_[axis2_], goal_[axis2_]));
            a_ = si_->allocState();
            b_ = si_->allocState();
        }

        ProjectionLift::~ProjectionLift()
        {
            si_->freeState(a_);
            si_->freeState(b_);
        }

        std::vector<double> ProjectionLift::values(const Eigen::Vector2d &p) const
        {
            const Eigen::Vector2d d = goal2_ - start2_;
            const double len2 = d.squaredNorm();
            // Projection mode: the values off the map follow the point's progress along S -> G (its projection on the
            // line, clamped), so the start and goal map to the exact start and goal states.
            const double t = len2 > 0. ? std::clamp((p - start2_).dot(d) / len2, 0., 1.) : 0.;
            std::vector<double> v = interpolate(axes_, start_, goal_, t);
            v[axis1_] = p.x();
            v[axis2_] = p.y();
            return v;
        }

        void ProjectionLift::lift(const Eigen::Vector2d &p, ob::State *state) const
        {
            setStateValues(*si_->getStateSpace(), values(p), state);
        }

        std::shared_ptr<CircleMap> ProjectionLift::makeMap() const
        {
            auto map = std::make_shared<CallbackCircleMap>(
                [this](const Eigen::Vector2d &p)
                {
                    lift(p, a_);
                    return si_->isValid(a_);
                },
                [this](const Eigen::Vector2d &a, const Eigen::Vector2d &b)
                {
                    lift(a, a_);
                    lift(b, b_);
                    return si_->checkMotion(a_, b_);
                });
            map->lo = Eigen::Vector2d(axes_[axis1_].lo, axes_[axis2_].lo);
            map->hi = Eigen::Vector2d(axes_[axis1_].hi, axes_[axis2_].hi);
            map->wraps = {{axes_[axis1_].wraps, axes_[axis2_].wraps}};
            return map;
        }

        // ---------------------------------------------------------------- hand map

        HandLift::HandLift(ob::SpaceInformationPtr si, std::vector<double> start, std::vector<double> goal, int axis1,
                           int axis2, int hand, std::vector<Eigen::Vector2d> armPath, double from, double to)
            : si_(std::move(si))
            , start_(std::move(start))
            , goal_(std::move(goal))
            , axis1_(axis1)
            , axis2_(axis2)
            , hand_(hand)
            , axes_(valueAxes(*si_->getStateSpace()))
            , arm_(std::move(armPath))
        {
            s_.push_back(0.);
            for (std::size_t i = 1; i < arm_.size(); ++i)
                s_.push_back(s_.back() + (arm_[i] - arm_[i - 1]).norm());
            // an arm that does not move still gets a short axis, so the hand can turn
            length_ = std::max(s_.back(), 1e-3);
            from_ = std::clamp(from, 0., length_);
            to_ = to < 0. ? length_ : std::clamp(to, from_, length_);
            if (to_ - from_ < 1e-3)
            {
                // a window too short to plan in: widened around its middle (within the path)
                const double mid = 0.5 * (from_ + to_);
                from_ = std::max(0., std::min(mid - 5e-4, length_ - 1e-3));
                to_ = from_ + 1e-3;
            }
            const double goalHand = start_[hand_] + difference(axes_[hand_], start_[hand_], goal_[hand_]);
            // Before a window that starts later than the path, the arm is outside the grown map, where the hand
            // reaches no obstacle at any value: the hand turns to its goal value there (outsideBefore()), and the
            // hand map inside the window starts from it, often leaving a straight way through the bottleneck.
            start2_ = Eigen::Vector2d(from_, from_ > 0. ? goalHand : start_[hand_]);
            goal2_ = Eigen::Vector2d(to_, goalHand);
            a_ = si_->allocState();
            b_ = si_->allocState();
        }

        HandLift::~HandLift()
        {
            si_->freeState(a_);
            si_->freeState(b_);
        }

        std::vector<double> HandLift::values(const Eigen::Vector2d &p) const
        {
            // Hand map (paper 000, Fig. 6): x is the arc length along the arm path, the paper's arm-path point number
            // made continuous; y is the hand value. The other values are interpolated between start and goal by x.
            const double x = std::clamp(p.x(), 0., length_);
            std::vector<double> v = interpolate(axes_, start_, goal_, x / length_);
            Eigen::Vector2d arm = arm_.back();
            const auto it = std::upper_bound(s_.begin(), s_.end(), x);
            if (it != s_.end())
            {
                const std::size_t k = std::max<std::ptrdiff_t>(0, (it - s_.begin()) - 1);
                const double seg = s_[k + 1] - s_[k];
                const double f = seg > 0. ? (x - s_[k]) / seg : 0.;
                arm = arm_[k] + f * (arm_[k + 1] - arm_[k]);
            }
            v[axis1_] = arm.x();
            v[axis2_] = arm.y();
            v[hand_] = p.y();
            return v;
        }

        std::vector<Eigen::Vector2d> HandLift::outsideBefore() const
        {
            std::vector<Eigen::Vector2d> out;
            // the hand turns linearly with arc length from its start value to the window's entry value
            for (std::size_t k = 0; k < s_.size() && s_[k] < from_ - 1e-12; ++k)
                out.emplace_back(s_[k], start_[hand_] + (start2_.y() - start_[hand_]) * s_[k] / from_);
            return out;
        }

        std::vector<Eigen::Vector2d> HandLift::outsideAfter() const
        {
            std::vector<Eigen::Vector2d> out;
            for (std::size_t k = 0; k < s_.size(); ++k)
                if (s_[k] > to_ + 1e-12)
                    out.emplace_back(s_[k], goal2_.y());
            // a path whose last vertex is within the window's rounding still ends at the goal's arm values
            if (to_ < length_ - 1e-12 && (out.empty() || out.back().x() < length_))
                out.emplace_back(length_, goal2_.y());
            return out;
        }

        void HandLift::lift(const Eigen::Vector2d &p, ob::State *state) const
        {
            setStateValues(*si_->getStateSpace(), values(p), state);
        }

        std::vector<Eigen::Vector2d> HandLift::breakpoints(const Eigen::Vector2d &a, const Eigen::Vector2d &b) const
        {
            std::vector<Eigen::Vector2d> out;
            const double lo = std::min(a.x(), b.x()), hi = std::max(a.x(), b.x());
            // A straight hand-map segment lifts to a polyline through the arm path's vertices: the motion validator
            // must check each piece, or a segment spanning an arm-path corner would be checked along a chord the arm
            // never takes.
            for (std::size_t k = 1; k + 1 < s_.size(); ++k)
                if (s_[k] > lo + 1e-12 && s_[k] < hi - 1e-12)
                {
                    const double f = (s_[k] - a.x()) / (b.x() - a.x());
                    out.emplace_back(s_[k], a.y() + f * (b.y() - a.y()));
                }
            if (b.x() < a.x())
                std::reverse(out.begin(), out.end());
            return out;
        }

        std::shared_ptr<CircleMap> HandLift::makeMap() const
        {
            auto map = std::make_shared<CallbackCircleMap>(
                [this](const Eigen::Vector2d &p)
                {
                    lift(p, a_);
                    return si_->isValid(a_);
                },
                [this](const Eigen::Vector2d &a, const Eigen::Vector2d &b)
                {
                    std::vector<Eigen::Vector2d> pts{a};
                    for (const auto &q : breakpoints(a, b))
                        pts.push_back(q);
                    pts.push_back(b);
                    for (std::size_t i = 1; i < pts.size(); ++i)
                    {
                        lift(pts[i - 1], a_);
                        lift(pts[i], b_);
                        if (!si_->checkMotion(a_, b_))
                            return false;
                    }
                    return true;
                },
                [this](const Eigen::Vector2d &a, const Eigen::Vector2d &b)
                {
                    return breakpoints(a, b);
                });
            map->lo = Eigen::Vector2d(from_, axes_[hand_].lo);
            map->hi = Eigen::Vector2d(to_, axes_[hand_].hi);
            map->wraps = {{false, axes_[hand_].wraps}};
            return map;
        }

        // ---------------------------------------------------------------- trajectory-restriction surface

        SurfaceLift::SurfaceLift(ob::SpaceInformationPtr si, std::vector<double> start, std::vector<double> goal,
                                 double angle, double margin)
            : si_(std::move(si)), start_(std::move(start)), margin_(margin)
        {
            const auto axes = valueAxes(*si_->getStateSpace());
            const std::size_t n = start_.size();
            std::vector<double> d(n);
            for (std::size_t i = 0; i < n; ++i)
                d[i] = difference(axes[i], start_[i], goal[i]);
            double len = 0.;
            for (double x : d)
                len += x * x;
            len = std::sqrt(len);
            // e1 along the start-goal line; when start == goal any direction will do, and the search ends at once
            e1_.assign(n, 0.);
            if (len > 0.)
                for (std::size_t i = 0; i < n; ++i)
                    e1_[i] = d[i] / len;
            else
                e1_[0] = 1.;
            // the two coordinate axes least aligned with e1, orthonormalised against e1 (and each other)
            std::vector<std::size_t> order(n);
            for (std::size_t i = 0; i < n; ++i)
                order[i] = i;
            // stable: ties keep the axes' order, so the plane (and the planner's result) is the same in every run.
            std::stable_sort(order.begin(), order.end(),
                             [this](std::size_t a, std::size_t b)
                             {
                                 return std::abs(e1_[a]) < std::abs(e1_[b]);
                             });
            std::vector<std::vector<double>> basis{e1_};
            for (std::size_t k = 0; k < n && basis.size() < 3; ++k)
            {
                std::vector<double> v(n, 0.);
                v[order[k]] = 1.;
                for (const auto &b : basis)
                {
                    double dot = 0.;
                    for (std::size_t i = 0; i < n; ++i)
                        dot += v[i] * b[i];
                    for (std::size_t i = 0; i < n; ++i)
                        v[i] -= dot * b[i];
                }
                double norm = 0.;
                for (double x : v)
                    norm += x * x;
                norm = std::sqrt(norm);
                // The axis is (nearly) in the span already: take the next one, so the basis stays orthonormal.
                if (norm < 1e-9)
                    continue;
                for (double &x : v)
                    x /= norm;
                basis.push_back(v);
            }
            e2_.assign(n, 0.);
            // Turning e2 about e1 by surface_angle picks the plane through the start-goal line; ConcentricCircle
            // tries the planes at +45, +90 and +135 degrees too. With only two values the plane is the whole space.
            for (std::size_t i = 0; i < n; ++i)
                e2_[i] = std::cos(angle) * basis[1][i] + (basis.size() > 2 ? std::sin(angle) * basis[2][i] : 0.);
            start2_ = Eigen::Vector2d::Zero();
            goal2_ = Eigen::Vector2d(len, 0.);
            a_ = si_->allocState();
            b_ = si_->allocState();
        }

        SurfaceLift::~SurfaceLift()
        {
            si_->freeState(a_);
            si_->freeState(b_);
        }

        std::vector<double> SurfaceLift::values(const Eigen::Vector2d &p) const
        {
            std::vector<double> v(start_);
            for (std::size_t i = 0; i < v.size(); ++i)
                v[i] += p.x() * e1_[i] + p.y() * e2_[i];
            return v;
        }

        void SurfaceLift::lift(const Eigen::Vector2d &p, ob::State *state) const
        {
            setStateValues(*si_->getStateSpace(), values(p), state);
        }

        std::shared_ptr<CircleMap> SurfaceLift::makeMap() const
        {
            auto map = std::make_shared<CallbackCircleMap>(
                [this](const Eigen::Vector2d &p)
                {
                    // values beyond a bounded joint's limits are outside the map (not clamped)
                    si_->getStateSpace()->copyFromReals(a_, values(p));
                    if (!si_->satisfiesBounds(a_))
                    {
                        si_->getStateSpace()->enforceBounds(a_);
                        std::vector<double> wrapped;
                        si_->getStateSpace()->copyToReals(wrapped, a_);
                        const auto v = values(p);
                        const auto axes = valueAxes(*si_->getStateSpace());
                        for (std::size_t i = 0; i < v.size(); ++i)
                            if (!axes[i].wraps && std::abs(wrapped[i] - v[i]) > 1e-12)
                                return false;
                    }
                    return si_->isValid(a_);
                },
                [this](const Eigen::Vector2d &a, const Eigen::Vector2d &b)
                {
                    lift(a, a_);
                    lift(b, b_);
                    return si_->checkMotion(a_, b_);
                });
            // The plane is unbounded: the map covers the start-goal segment plus margin on every side (pi in the
            // planner, so a detour may turn a joint half a revolution away from the straight line).
            map->lo = Eigen::Vector2d(-margin_, -margin_);
            map->hi = Eigen::Vector2d(goal2_.x() + margin_, margin_);
            return map;
        }

        bool isPlanarArm(const ob::SpaceInformationPtr &si)
        {
            const auto *fcl = fclOf(*si);
            const auto *rgb = fcl ? dynamic_cast<const validity::RobotGroupBodies *>(fcl->bodies().get()) : nullptr;
            if (rgb == nullptr)
                return false;
            try
            {
                validity::PlanarArm::fromModel(*rgb->model());
                return true;
            }
            catch (const std::invalid_argument &)
            {
                return false;
            }
        }

        // ---------------------------------------------------------------- J-map polygons

        std::shared_ptr<CircleMap> makeJMapCircleMap(const ob::SpaceInformationPtr &si)
        {
            auto *checker = dynamic_cast<validity::JMapValidityChecker *>(si->getStateValidityChecker().get());
            if (checker == nullptr)
                return nullptr;
            const auto axes = valueAxes(*si->getStateSpace());
            if (axes.size() != 2 || axes[0].wraps || axes[1].wraps)
                return nullptr;
            const auto *rgb = dynamic_cast<const validity::RobotGroupBodies *>(checker->fcl()->bodies().get());
            if (rgb == nullptr || rgb->variables().size() != 2 || rgb->variables()[0] != checker->axes().axis1 ||
                rgb->variables()[1] != checker->axes().axis2)
                return nullptr;
            const validity::MultiPolygon2 all = checker->unitedPolygons();
            auto map = std::make_shared<PolygonCircleMap>(all, Eigen::Vector2d(axes[0].lo, axes[1].lo),
                                                          Eigen::Vector2d(axes[0].hi, axes[1].hi));
            // Point tests through the tiles' slab indexes (tens of nanoseconds, the checker's own test): the united
            // polygons cover the same set, and covered_by on them costs a walk over every edge.
            auto keep = si->getStateValidityChecker();
            map->setInsideTest(
                [keep, checker](const Eigen::Vector2d &p)
                {
                    return checker->tile(p.x()).collides(p.x(), p.y());
                });
            return map;
        }

        // ---------------------------------------------------------------- the arm without its hand

        ArmMaps makeArmMaps(const ob::SpaceInformationPtr &si, const ProjectionLift &arm,
                            const std::vector<int> &handValues, int slices, double tolerance,
                            const ob::PlannerTerminationCondition *ptc)
        {
            ArmMaps out;
            const auto *fcl = fclOf(*si);
            const auto *rgb = fcl ? dynamic_cast<const validity::RobotGroupBodies *>(fcl->bodies().get()) : nullptr;
            validity::PlanarArmPtr planar;
            if (rgb != nullptr)
            {
                try
                {
                    planar = validity::PlanarArm::fromModel(*rgb->model());
                }
                catch (const std::invalid_argument &)
                {
                    planar.reset();
                }
            }
            if (!planar)
            {
                out.map = arm.makeMap();
                out.kind = "projection";
                return out;
            }
            const auto &variables = rgb->variables();
            std::vector<double> start = arm.values(arm.start2());
            std::vector<double> configuration = rgb->fullConfiguration(start.data());
            std::vector<int> links;
            // The hand's reach beyond its joint: how far the obstacles grow for the grown map. A hand link's points
            // lie within reachFrom() (its capsules' centre segments) plus the capsule's radius of the hand joint.
            double handReach = 0.;
            for (std::size_t l = 0; l < planar->links().size(); ++l)
            {
                bool hand = false;
                // Paper 000: the arm's map is built without the hand. A link moved by a hand value is left out, so
                // the arm map only blocks what the arm's own links hit; the hand map deals with the rest.
                for (const int h : handValues)
                    if (planar->moves(variables[h], static_cast<int>(l)))
                    {
                        hand = true;
                        double radius = 0.;
                        for (const auto &capsule : planar->links()[l].capsules)
                            radius = std::max(radius, capsule.radius);
                        handReach = std::max(handReach, planar->reachFrom(variables[h], static_cast<int>(l)) + radius);
                    }
                if (!hand)
                    links.push_back(static_cast<int>(l));
            }
            auto axes = validity::planarAxes(*planar, variables[arm.axis1()], variables[arm.axis2()], configuration);
            const validity::MultiPolygon2 obstacles = fcl->scene()->polygons2d();
            auto source = std::make_shared<validity::PlanarIntervalSource>(planar, obstacles, axes, links);
            const auto &valueAxis = arm.axes();
            const ValueAxis ax1 = valueAxis[arm.axis1()], ax2 = valueAxis[arm.axis2()];
            if (handReach > 0.)
            {
                // the grown map's question for one configuration: the exact capsules against the grown obstacles
                auto grown = std::make_shared<validity::PlanarIntervalSource>(
                    planar, validity::growObstacles(obstacles, handReach), axes, links);
                out.inGrown = [grown](const Eigen::Vector2d &p)
                {
                    return grown->collides(p.x(), p.y());
                };
            }
            // The paper's arm J-map: polygons that contain the arm's collision region, searched with the J-map's own
            // point and segment tests. The polygons are conservative and may close a channel the start or goal lies
            // in (docs/concentric-circle.md); then the exact capsules decide instead. Polygon maps do not wrap.
            if (slices > 0 && !ax1.wraps && !ax2.wraps)
            {
                validity::JMapSettings settings;
                settings.slices = slices;
                settings.tolerance = tolerance;
                settings.trueIntervals = false;
                // The build is the solve's work (arm_slices 100,000: 5 s past a 0.5 s limit): it stops between
                // slices when the time is up, through its progress callback (JMap::build has no other exit).
                struct Stopped
                {
                };
                if (ptc != nullptr)
                    settings.progress = [ptc](int, int)
                    {
                        if ((*ptc)())
                            throw Stopped{};
                    };
                validity::JMapPtr jmap;
                try
                {
                    jmap = validity::JMap::build(*source, settings);
                }
                catch (const Stopped &)
                {
                    jmap.reset();
                }
                const Eigen::Vector2d s2 = arm.start2(), g2 = arm.goal2();
                if (jmap && !jmap->collides(s2.x(), s2.y()) && !jmap->collides(g2.x(), g2.y()))
                {
                    auto map = std::make_shared<PolygonCircleMap>(jmap->polygons(), Eigen::Vector2d(ax1.lo, ax2.lo),
                                                                  Eigen::Vector2d(ax1.hi, ax2.hi));
                    map->setInsideTest(
                        [jmap](const Eigen::Vector2d &p)
                        {
                            return jmap->collides(p.x(), p.y());
                        });
                    out.map = map;
                    out.kind = "jmap";
                    return out;
                }
            }
            auto freeAt = [source](const Eigen::Vector2d &p)
            {
                return !source->collides(p.x(), p.y());
            };
            auto map = std::make_shared<CallbackCircleMap>(
                freeAt,
                [freeAt](const Eigen::Vector2d &a, const Eigen::Vector2d &b)
                {
                    // Sampled at 0.005 rad: the capsule model has no motion test of its own; every returned path is
                    // checked again with the space's motion validator (ConcentricCircle::solve), so this only has to be
                    // fine enough to rarely propose a link the validator rejects.
                    const double step = 0.005;
                    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
                    for (int i = 0; i <= n; ++i)
                        if (!freeAt(a + (b - a) * (static_cast<double>(i) / n)))
                            return false;
                    return true;
                });
            map->lo = Eigen::Vector2d(ax1.lo, ax2.lo);
            map->hi = Eigen::Vector2d(ax1.hi, ax2.hi);
            map->wraps = {{ax1.wraps, ax2.wraps}};
            out.map = map;
            out.kind = "capsules";
            return out;
        }
    }  // namespace planners
}  // namespace michi
