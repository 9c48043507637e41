#include <michi/validity/grid/GridValidityChecker.h>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/SE2StateSpace.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <deque>
#include <iomanip>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace ob = ompl::base;

namespace michi
{
    namespace validity
    {
        namespace
        {
            /** Tables built in this process (tablesBuilt()). */
            std::atomic<std::size_t> builtCount{0};

            /** What a HeadingTable is made of: two checkers whose inputs are equal have equal tables. */
            struct TableInputs
            {
                OccupancyGrid grid;
                std::vector<Eigen::Vector2d> footprint;
                unsigned int headings{0};
                double tolerance{0.};
                bool band{false};  ///< buildBand() wanted (where the table does not test exactly first)

                bool operator==(const TableInputs &o) const
                {
                    return grid.width == o.grid.width && grid.height == o.grid.height &&
                           grid.resolution == o.grid.resolution && grid.origin == o.grid.origin &&
                           headings == o.headings && tolerance == o.tolerance && band == o.band &&
                           footprint == o.footprint && grid.cells == o.grid.cells;
                }
            };

            /** The tables built last, kept for the next checker over the same map: code that makes a planning
                context, hence a checker, per query of a map (the tests, a user's loop) built the same table every
                time, 1.5 s on movingai_64room (the footprint swept over every cell and heading); a copy is a memory
                copy (100 contexts of 64room: 156 s -> 16 s in all). Each checker gets its own copy, because
                refresh() changes a checker's table in place. Two entries (each within the table's bound of 6
                million cells) serve two maps used in turn; more are not kept, so a process that walks through many
                maps does not hold all their tables. */
            class TableCache
            {
            public:
                std::unique_ptr<HeadingTable> get(TableInputs inputs)
                {
                    {
                        std::lock_guard<std::mutex> lock(mutex_);
                        for (const auto &e : entries_)
                            if (e.first == inputs)
                                return std::make_unique<HeadingTable>(*e.second);
                    }
                    // built outside the lock: checkers of other maps are not held up by this one
                    auto table = std::make_shared<HeadingTable>(inputs.grid, inputs.footprint, inputs.headings,
                                                                inputs.tolerance);
                    if (inputs.band && !table->exactFirst())
                        table->buildBand();
                    ++builtCount;
                    auto copy = std::make_unique<HeadingTable>(*table);
                    std::lock_guard<std::mutex> lock(mutex_);
                    entries_.emplace_front(std::move(inputs), std::move(table));
                    while (entries_.size() > 2)
                        entries_.pop_back();
                    return copy;
                }

            private:
                std::mutex mutex_;
                std::deque<std::pair<TableInputs, std::shared_ptr<const HeadingTable>>> entries_;
            };

            TableCache &tableCache()
            {
                static TableCache cache;
                return cache;
            }

            /** Smallest width of the footprint over all directions (its convex hull's, edge directions). */
            double minimumWidth(const std::vector<Eigen::Vector2d> &footprint)
            {
                double best = std::numeric_limits<double>::infinity();
                for (std::size_t e = 0; e < footprint.size(); ++e)
                {
                    const Eigen::Vector2d a = footprint[e], b = footprint[(e + 1) % footprint.size()];
                    const Eigen::Vector2d d = b - a;
                    if (d.norm() <= 0.)
                        continue;
                    const Eigen::Vector2d n(-d.y() / d.norm(), d.x() / d.norm());
                    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
                    for (const auto &p : footprint)
                    {
                        lo = std::min(lo, n.dot(p - a));
                        hi = std::max(hi, n.dot(p - a));
                    }
                    best = std::min(best, hi - lo);
                }
                return best;
            }

            /** Felzenszwalb & Huttenlocher's 1-D squared distance transform of f (n values) into d. */
            void squaredDistance1d(const std::vector<double> &f, std::vector<double> &d, std::vector<int> &v,
                                   std::vector<double> &z)
            {
                const int n = static_cast<int>(f.size());
                const double inf = std::numeric_limits<double>::infinity();
                int k = -1;
                for (int q = 0; q < n; ++q)
                {
                    // A free cell adds no parabola to the lower envelope (v: the parabolas' vertices, z: where each
                    // takes over).
                    if (f[q] == inf)
                        continue;
                    while (k >= 0)
                    {
                        // Where the parabola from q crosses the last one kept; if that is left of where the last took
                        // over, the last one is never the lowest and is dropped.
                        const double s =
                            ((f[q] + q * double(q)) - (f[v[k]] + v[k] * double(v[k]))) / (2. * q - 2. * v[k]);
                        if (s <= z[k])
                            --k;
                        else
                            break;
                    }
                    ++k;
                    v[k] = q;
                    z[k] = k == 0 ? -inf
                                  : ((f[q] + q * double(q)) - (f[v[k - 1]] + v[k - 1] * double(v[k - 1]))) /
                                        (2. * q - 2. * v[k - 1]);
                    z[k + 1] = inf;
                }
                if (k < 0)
                {
                    std::fill(d.begin(), d.end(), inf);
                    return;
                }
                z[0] = -inf;
                int j = 0;
                for (int q = 0; q < n; ++q)
                {
                    while (z[j + 1] < q)
                        ++j;
                    d[q] = (q - v[j]) * double(q - v[j]) + f[v[j]];
                }
            }
        }  // namespace

        double automaticGridResolution(const GridCheckerSettings &settings,
                                       const std::vector<Eigen::Vector2d> &footprint,
                                       const std::array<double, 4> &bounds)
        {
            if (settings.resolution > 0.)
                return settings.resolution;
            const double extent = std::max(bounds[1] - bounds[0], bounds[3] - bounds[2]);
            // Table cells are the map's cells split a whole number of times, so a map cell is exactly a set of table
            // cells.
            const double base = settings.mapResolution > 0. ? settings.mapResolution : extent / 200.;
            const double width = minimumWidth(footprint);
            // At most a quarter of the robot's smaller width: the stamps grow the footprint by a whole cell, and
            // coarser cells close passages the robot fits through (checking.md, 64room).
            double divisions = std::max(1., std::ceil(base / (0.25 * width) - 1e-9));
            // at most 6 million table cells: with 16 headings 7 bytes a cell (bits, occupancy, distance), 42 MB
            const double cells = (bounds[1] - bounds[0]) * (bounds[3] - bounds[2]) / (base * base);
            while (divisions > 1. && cells * divisions * divisions > 6e6)
                divisions -= 1.;
            return base / divisions;
        }

        GridValidityChecker::GridValidityChecker(const ob::SpaceInformationPtr &si,
                                                 std::vector<Eigen::Vector2d> footprint, ScenePtr scene,
                                                 const std::array<double, 4> &bounds,
                                                 const GridCheckerSettings &settings)
            : ob::StateValidityChecker(si), footprint_(std::move(footprint)), scene_(std::move(scene))
        {
            // APPROXIMATE: clearance() is a lower bound from the distance transform, not FCL's exact distance.
            specs_.clearanceComputationType = ob::StateValidityCheckerSpecs::APPROXIMATE;
            se2_ = dynamic_cast<const ob::SE2StateSpace *>(si->getStateSpace().get()) != nullptr;
            if (!se2_ && si->getStateSpace()->getDimension() != 3)
                throw std::invalid_argument("GridValidityChecker: needs an SE(2) state space (x, y, yaw)");
            if (!scene_)
                throw std::invalid_argument("GridValidityChecker: no scene");
            if (settings.headings < 1 || settings.headings > 4096)
                throw std::invalid_argument("GridValidityChecker: headings must be in 1..4096");
            for (double b : bounds)
                if (!std::isfinite(b))
                    throw std::invalid_argument("GridValidityChecker: bounds must be finite");
            const auto start = std::chrono::steady_clock::now();
            const double res = automaticGridResolution(settings, footprint_, bounds);
            if (!(res > 0.))
                throw std::invalid_argument("GridValidityChecker: resolution must be positive");
            double radius = 0.;
            for (const auto &p : footprint_)
                radius = std::max(radius, p.norm());
            // The grid reaches a footprint radius and two cells beyond the bounds: a robot anywhere in the bounds never
            // reads past the grid, where freePose() would call it blocked.
            const double pad = radius + 2. * res;
            const Eigen::Vector2d o = settings.origin;
            // Whole cells from the map's origin, so the table's cells line up with the map's, and the first cell a
            // multiple of the table's summary blocks from it: a map cell of 2, 4 or 8 table cells then lies in one
            // block, and the poses inside an occupied one are refused by their block alone.
            const double block = HeadingTable::blockCells();
            const double i0 = block * std::floor(std::floor((bounds[0] - pad - o.x()) / res) / block),
                         i1 = std::ceil((bounds[1] + pad - o.x()) / res);
            const double j0 = block * std::floor(std::floor((bounds[2] - pad - o.y()) / res) / block),
                         j1 = std::ceil((bounds[3] + pad - o.y()) / res);
            if ((i1 - i0) * (j1 - j0) > 2e8)
                throw std::invalid_argument("GridValidityChecker: a grid of " + std::to_string(i1 - i0) + " x " +
                                            std::to_string(j1 - j0) +
                                            " cells is too large; set collision.grid.resolution");
            // A cell is occupied when an obstacle overlaps it shrunk by this much, so a map's box on cell edges
            // occupies exactly its cells, not their neighbours too (checking.md).
            tolerance_ = 1e-6 * res;
            zMin_ = settings.robotZMin;  // refresh() rasterises the moved scene over the same heights
            zMax_ = settings.robotZMax;
            // On a grid map the occupied cells are the obstacles exactly, so the exact footprint test is exact; a
            // polygon scene is only rasterised, and the table alone answers.
            exact_ = settings.mapResolution > 0.;
            const Eigen::Vector2d origin(o.x() + i0 * res, o.y() + j0 * res);
            OccupancyGrid grid =
                rasterizeScene(*scene_, res, origin, static_cast<int>(i1 - i0), static_cast<int>(j1 - j0), tolerance_,
                               settings.robotZMin, settings.robotZMax);
            // the band table where the exact test is costly: a footprint over more than a few table cells (on
            // 64room, 1.4 cells of circumradius, the exact test took about 40 ns and a band table of 6 million
            // entries, 20 MiB, made the queries slower, not faster: measured, docs/checking.md); nor where the
            // exact test is cheaper than a miss on the band (HeadingTable::exactFirst(), decided in the cache);
            // should an update end exactFirst() there (a map cell split), freeOnGrid() reads the table word and then
            // tests exactly
            table_ = tableCache().get(
                TableInputs{std::move(grid), footprint_, settings.headings, tolerance_, exact_ && radius >= 2. * res});
            // points of the outline at most one cell apart, for clearance()
            for (std::size_t e = 0; e < footprint_.size(); ++e)
            {
                const Eigen::Vector2d a = footprint_[e], b = footprint_[(e + 1) % footprint_.size()];
                const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / res)));
                for (int s = 0; s < n; ++s)
                    outline_.push_back(a + (b - a) * (double(s) / n));
            }
            distanceTransform();
            buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }

        std::size_t GridValidityChecker::tablesBuilt()
        {
            return builtCount.load();
        }

        void GridValidityChecker::distanceTransform()
        {
            const OccupancyGrid &g = table_->grid();
            const int w = g.width, h = g.height;
            const double inf = std::numeric_limits<double>::infinity();
            // Separable: the squared distance is a 1-D transform down each column, then one along each row of the
            // results.
            std::vector<double> column(static_cast<std::size_t>(w) * h);
            {
                std::vector<double> f(h), d(h), z(h + 1);
                std::vector<int> v(h);
                for (int i = 0; i < w; ++i)
                {
                    for (int j = 0; j < h; ++j)
                        f[j] = g.cells[static_cast<std::size_t>(j) * w + i] ? 0. : inf;
                    squaredDistance1d(f, d, v, z);
                    for (int j = 0; j < h; ++j)
                        column[static_cast<std::size_t>(j) * w + i] = d[j];
                }
            }
            // float, not double: a 2064 x 2064 table already needs 17 MiB of distances (checking.md).
            distance_.assign(static_cast<std::size_t>(w) * h, std::numeric_limits<float>::infinity());
            std::vector<double> f(w), d(w), z(w + 1);
            std::vector<int> v(w);
            for (int j = 0; j < h; ++j)
            {
                std::copy(column.begin() + static_cast<std::ptrdiff_t>(j) * w,
                          column.begin() + static_cast<std::ptrdiff_t>(j + 1) * w, f.begin());
                squaredDistance1d(f, d, v, z);
                for (int i = 0; i < w; ++i)
                    distance_[static_cast<std::size_t>(j) * w + i] = static_cast<float>(std::sqrt(d[i]) * g.resolution);
            }
        }

        double GridValidityChecker::cellDistance(int i, int j) const
        {
            const OccupancyGrid &g = table_->grid();
            if (!g.inside(i, j))
                return std::numeric_limits<double>::infinity();
            return distance_[static_cast<std::size_t>(j) * g.width + i];
        }

        bool GridValidityChecker::isValid(const ob::State *state) const
        {
            if (se2_)
            {
                const auto *s = state->as<ob::SE2StateSpace::StateType>();
                return isValidPose(s->getX(), s->getY(), s->getYaw());
            }
            std::vector<double> v;
            si_->getStateSpace()->copyToReals(v, state);
            return isValidPose(v[0], v[1], v[2]);
        }

        bool GridValidityChecker::isValid(const ob::State *state, double &dist) const
        {
            dist = clearance(state);
            return isValid(state);
        }

        double GridValidityChecker::clearance(const ob::State *state) const
        {
            if (se2_)
            {
                const auto *s = state->as<ob::SE2StateSpace::StateType>();
                return clearancePose(s->getX(), s->getY(), s->getYaw());
            }
            std::vector<double> v;
            si_->getStateSpace()->copyToReals(v, state);
            return clearancePose(v[0], v[1], v[2]);
        }

        double GridValidityChecker::clearancePose(double x, double y, double yaw) const
        {
            if (!table_->validPose(x, y, yaw))
                return 0.;
            // the table says the footprint is free, so the nearest obstacle lies outside it: its distance is
            // that of the outline. A point q of the outline is at least (distance between cell centres)
            // - sqrt(2) r from the occupied cells (q to its cell centre, the occupied cell's centre to its
            // corner), and every outline point is within r / 2 of a sampled one.
            const OccupancyGrid &g = table_->grid();
            const Eigen::Rotation2Dd rot(yaw);
            double best = std::numeric_limits<double>::infinity();
            for (const auto &p : outline_)
            {
                const Eigen::Vector2d q = rot * p + Eigen::Vector2d(x, y);
                best = std::min(best, cellDistance(g.column(q.x()), g.row(q.y())));
            }
            if (!std::isfinite(best))
                return best;
            return std::max(0., best - (std::sqrt(2.) + 0.5) * g.resolution - tolerance_);
        }

        std::size_t GridValidityChecker::bytes() const
        {
            return table_->bytes() + distance_.size() * sizeof(float);
        }

        std::string GridValidityChecker::describe() const
        {
            std::ostringstream s;
            const auto &g = table_->grid();
            s << "grid checker: " << g.width << " x " << g.height << " cells of " << g.resolution << " m, "
              << table_->headings() << " headings, " << std::setprecision(3) << bytes() / (1024. * 1024.)
              << " MiB, built in " << buildSeconds_ << " s";
            return s.str();
        }

        CellBox GridValidityChecker::refresh()
        {
            const auto start = std::chrono::steady_clock::now();
            const OccupancyGrid &g = table_->grid();
            // The same grid as the constructor's (resolution, origin, size, tolerance), so update() can compare cell by
            // cell and recompute only the entries near changed cells.
            const OccupancyGrid now =
                rasterizeScene(*scene_, g.resolution, g.origin, g.width, g.height, tolerance_, zMin_, zMax_);
            const CellBox box = table_->update(now);
            if (!box.empty())
            {
                distanceTransform();
                ++refreshes_;
            }
            buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            return box;
        }
    }  // namespace validity
}  // namespace michi
