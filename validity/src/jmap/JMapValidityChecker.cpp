#include <michi/validity/jmap/JMapValidityChecker.h>

#include <ompl/base/SpaceInformation.h>

#include <boost/geometry.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace michi
{
    namespace validity
    {
        namespace
        {
            const RobotGroupBodies &groupBodies(const FclValidityChecker &fcl)
            {
                const auto *bodies = dynamic_cast<const RobotGroupBodies *>(fcl.bodies().get());
                if (bodies == nullptr)
                    throw std::invalid_argument("the J-map checker needs an arm (RobotGroupBodies)");
                return *bodies;
            }

            int valueIndex(const RobotGroupBodies &bodies, int variable)
            {
                const auto &v = bodies.variables();
                const auto it = std::find(v.begin(), v.end(), variable);
                if (it == v.end())
                    throw std::invalid_argument("J-map axis " + std::to_string(variable) +
                                                " is not a joint of the planned group");
                return static_cast<int>(it - v.begin());
            }
        }  // namespace

        bool selfCollisionImpossible(const FclValidityChecker &fcl, const JMapAxes &axes, double cell)
        {
            const auto &bodies = groupBodies(fcl);
            const auto &pairs = bodies.selfCheckPairs();
            if (pairs.empty())
                return true;
            // With more joints than the map's two, other joints change the self-distances: no 2-D grid can prove them
            // safe.
            if (bodies.dimension() != 2)
                return false;
            const int i1 = valueIndex(bodies, axes.axis1), i2 = valueIndex(bodies, axes.axis2);
            const int n1 = std::max(1, static_cast<int>(std::ceil((axes.hi1 - axes.lo1) / cell)));
            const int n2 = std::max(1, static_cast<int>(std::ceil((axes.hi2 - axes.lo2) / cell)));
            const double h1 = (axes.hi1 - axes.lo1) / n1, h2 = (axes.hi2 - axes.lo2) / n2;
            const std::vector<char> noBodies(bodies.bodies().size(), 0), allPairs(pairs.size(), 1);
            std::vector<double> obstacle, self, bounds;
            double centre[2], corner[2];
            for (int a = 0; a < n1; ++a)
                for (int b = 0; b < n2; ++b)
                {
                    centre[i1] = axes.lo1 + (a + 0.5) * h1;
                    centre[i2] = axes.lo2 + (b + 0.5) * h2;
                    corner[i1] = centre[i1] + 0.5 * h1;
                    corner[i2] = centre[i2] + 0.5 * h2;
                    // how far each body can move from the cell centre to anywhere in the cell
                    bodies.bodyDisplacementBounds(centre, corner, bounds);
                    fcl.bodyDistances(centre, noBodies, allPairs, obstacle, self);
                    // Certified per cell: two bodies at distance d apart at the centre, each moving at most b_i
                    // within the cell, cannot touch anywhere in it when d > b_1 + b_2. One cell that fails this
                    // ends the proof (conservative).
                    for (std::size_t k = 0; k < pairs.size(); ++k)
                        if (!(self[k] > bounds[pairs[k].first] + bounds[pairs[k].second]))
                            return false;
                }
            return true;
        }

        JMapValidityChecker::JMapValidityChecker(const ompl::base::SpaceInformationPtr &si, FclValidityCheckerPtr fcl,
                                                 SourceFactory makeSource, JMapAxes axes, bool coversRobot,
                                                 JMapCheckerSettings settings)
            : ompl::base::StateValidityChecker(si)
            , fcl_(std::move(fcl))
            , makeSource_(std::move(makeSource))
            , axes_(std::move(axes))
            , settings_(settings)
        {
            specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::EXACT;
            if (!(axes_.lo1 < axes_.hi1) || !(axes_.lo2 < axes_.hi2))
                throw std::invalid_argument("J-map checker: axis ranges must be resolved (lo < hi)");
            if (settings_.tiles < 1 || settings_.map.slices < settings_.tiles)
                throw std::invalid_argument("J-map checker: need 1 <= tiles <= slices");
            const auto &bodies = groupBodies(*fcl_);
            value1_ = valueIndex(bodies, axes_.axis1);
            value2_ = valueIndex(bodies, axes_.axis2);
            // The map alone decides a free point only when it covers the whole robot, all its joints, and
            // self-collision is impossible; otherwise FCL must confirm what the map calls free.
            answersAlone_ = coversRobot && bodies.dimension() == 2 && selfCollisionImpossible(*fcl_, axes_);
            tileCount_ = static_cast<std::size_t>(settings_.tiles);
            tileScale_ = static_cast<double>(tileCount_) / (axes_.hi1 - axes_.lo1);
            scene_ = fcl_->scene().get();
            // Tiles along axis 1, built on first use: a planner that stays in part of the range never pays for the
            // rest.
            tiles_ = std::make_unique<std::atomic<const JMap *>[]>(tileCount_);
            for (std::size_t k = 0; k < tileCount_; ++k)
                tiles_[k] = nullptr;
            generation_ = fcl_->scene()->changeCount();
        }

        std::size_t JMapValidityChecker::tileIndex(double theta1) const
        {
            // Clamped so that theta1 == hi1 (and rounding just outside) falls in the last tile rather than past the
            // array.
            const long k = static_cast<long>(std::floor((theta1 - axes_.lo1) * tileScale_));
            return static_cast<std::size_t>(std::clamp<long>(k, 0, static_cast<long>(tileCount_) - 1));
        }

        void JMapValidityChecker::dropIfSceneChanged() const
        {
            const std::uint64_t now = scene_->changeCount();
            // Double-checked: the common case (scene unchanged) costs one atomic load, and only one thread drops the
            // tiles.
            if (now == generation_.load(std::memory_order_acquire))
                return;
            std::lock_guard<std::mutex> lock(buildMutex_);
            if (now == generation_.load())
                return;
            // Only unpublished: the old maps stay alive in owned_, since another thread may still be reading one it
            // was given.
            for (std::size_t k = 0; k < tileCount_; ++k)
                tiles_[k].store(nullptr, std::memory_order_release);
            generation_ = now;
        }

        const JMap &JMapValidityChecker::tile(double theta1) const
        {
            dropIfSceneChanged();
            const std::size_t k = tileIndex(theta1);
            if (const JMap *map = tiles_[k].load(std::memory_order_acquire))
                return *map;
            // tiles are built one at a time, once: the source and JMap::build are the expensive part
            std::lock_guard<std::mutex> lock(buildMutex_);
            if (const JMap *map = tiles_[k].load(std::memory_order_acquire))
                return *map;
            JMapAxes axes = axes_;
            const double w = (axes_.hi1 - axes_.lo1) / static_cast<double>(tileCount_);
            axes.lo1 = axes_.lo1 + static_cast<double>(k) * w;
            axes.hi1 = axes.lo1 + w;
            JMapSettings settings = settings_.map;
            // at least the requested resolution: slices per tile rounded up
            const int tiles = static_cast<int>(tileCount_);
            settings.slices = (settings_.map.slices + tiles - 1) / tiles;
            owned_.push_back(JMap::build(*makeSource_(axes), settings));
            // release pairs with the acquire loads above: a thread that sees the pointer also sees the finished map.
            tiles_[k].store(owned_.back().get(), std::memory_order_release);
            return *owned_.back();
        }

        void JMapValidityChecker::buildAll() const
        {
            const double w = (axes_.hi1 - axes_.lo1) / static_cast<double>(tileCount_);
            for (std::size_t k = 0; k < tileCount_; ++k)
                tile(axes_.lo1 + (static_cast<double>(k) + 0.5) * w);
        }

        MultiPolygon2 JMapValidityChecker::unitedPolygons() const
        {
            ++unionsMade_;
            buildAll();
            MultiPolygon2 all;
            for (std::size_t k = 0; k < tileCount_; ++k)
                for (const auto &polygon : tiles_[k].load()->polygons())
                {
                    // United rather than collected: a region cut at a tile border would otherwise keep an edge inside
                    // the obstacle, which pictures draw and planners would take for an obstacle boundary.
                    MultiPolygon2 merged;
                    boost::geometry::union_(all, polygon, merged);
                    all = std::move(merged);
                }
            return all;
        }

        std::size_t JMapValidityChecker::builtTiles() const
        {
            std::size_t n = 0;
            for (std::size_t k = 0; k < tileCount_; ++k)
                n += tiles_[k].load() != nullptr ? 1 : 0;
            return n;
        }

        bool JMapValidityChecker::isValid(const ompl::base::State *state) const
        {
            if (!si_->satisfiesBounds(state))
                return false;
            // per thread and kept: a planner's every check would otherwise allocate (53 -> 40 ns a check on
            // planar_2link, a scratch harness of 200,000 uniform states)
            thread_local std::vector<double> values;
            si_->getStateSpace()->copyToReals(values, state);
            return isValidConfiguration(values.data());
        }

        bool JMapValidityChecker::isValidConfiguration(const double *values) const
        {
            const double t1 = values[value1_], t2 = values[value2_];
            // OMPL's satisfiesBounds() lets a NaN through; a map lookup would take it for a free point
            if (!std::isfinite(t1) || !std::isfinite(t2))
                return false;
            const JMap &map = tile(t1);
            if (map.collides(t1, t2))
            {
                // The polygons contain the true collision region with some margin (paper 000's conservative
                // approximation): near their boundary FCL gives the exact answer, deeper inside the map's
                // "collides" is trusted.
                if (settings_.mode == JMapCheckerSettings::Mode::EXACT_FALLBACK &&
                    map.nearBoundary(t1, t2, settings_.fallbackBand))
                {
                    ++fclQueries_;
                    return fcl_->isValidConfiguration(values);
                }
                return false;
            }
            if (answersAlone_)
                return true;
            ++fclQueries_;
            return fcl_->isValidConfiguration(values);
        }

        double JMapValidityChecker::clearance(const ompl::base::State *state) const
        {
            // Clearance comes from FCL: the map has collision regions in joint space, not distances in the workspace.
            return fcl_->clearance(state);
        }
    }  // namespace validity
}  // namespace michi
