#ifndef MICHI_VALIDITY_GRID_GRID_VALIDITY_CHECKER_
#define MICHI_VALIDITY_GRID_GRID_VALIDITY_CHECKER_

#include <michi/validity/grid/HeadingTable.h>
#include <michi/validity/scene/Scene.h>

#include <ompl/base/StateValidityChecker.h>

#include <array>
#include <cstdint>
#include <limits>
#include <atomic>
#include <memory>
#include <string>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief Settings of the grid checker (collision.grid in a problem file, docs/checking.md). */
        struct GridCheckerSettings
        {
            /** \brief Table cell size (metres); 0: automatic: the map's cell (or 1/200 of the larger side of the
                bounds when the scene is no map) divided by the smallest whole number that makes a table cell at
                most a quarter of the footprint's smaller width, within a budget of 6 million cells. */
            double resolution{0.};
            /** \brief The map's cell size when the scene is a grid map (set by the problem loader), else 0. */
            double mapResolution{0.};
            /** \brief A corner of the map's cells: table cells are aligned with it. */
            Eigen::Vector2d origin{Eigen::Vector2d::Zero()};
            unsigned int headings{16};  ///< heading bins over 2 pi
            /** \brief The z range the robot occupies (an SE(2) robot: [0, its height]). Obstacles wholly above or
                below it are left out of the grid, as FCL never finds them in contact; the default keeps every
                obstacle. */
            double robotZMin{-std::numeric_limits<double>::infinity()};
            double robotZMax{std::numeric_limits<double>::infinity()};
        };

        /** \brief The table cell size GridCheckerSettings::resolution = 0 stands for. */
        double automaticGridResolution(const GridCheckerSettings &settings,
                                       const std::vector<Eigen::Vector2d> &footprint,
                                       const std::array<double, 4> &bounds);

        /** \brief Grid-native SE(2) state validity checking (issue 14): the scene rasterised into an occupancy
            grid (rasterizeScene), a HeadingTable of the footprint over it, and a distance transform of the grid.

            isValid() is one bit of the table: the cell of (x, y) and the heading bin of the yaw. The table is
            conservative: a state it calls valid is free for FCL at every pose of its cell and heading bin, so
            it never lets a collision through. Where the entry is invalid (near obstacles: the footprint is grown
            by the cell and swept over the heading bin) of a grid map, the footprint at the state's own pose is
            tested exactly against the occupied cells (HeadingTable::freeOnGrid: the pose's cell occupied or the
            entry blocked at every pose: invalid; then the finer bits of a BandTable, 64 sub-entries of the entry;
            only the poses none of these decide get HeadingTable::freePose), so the checker is exact on the map's
            grid: a narrow door the table closes stays open for the poses that fit (exact()). States outside the
            grid are invalid.

            clearance() is a lower bound of the distance from the footprint to the obstacles, from the distance
            transform at points of the footprint's outline (table cells apart), less the cells' sizes; 0 where
            the table entry is invalid.

            The grid covers \e bounds (x min, x max, y min, y max) grown by the footprint's circumradius, so every
            obstacle a valid state could touch is in it. States are SE(2) (read as x, y, yaw through
            StateSpace::copyToReals, or directly for SE2StateSpace and its descendants). Thread-safe for queries;
            refresh() must not run during queries. */
        class GridValidityChecker : public ompl::base::StateValidityChecker
        {
        public:
            GridValidityChecker(const ompl::base::SpaceInformationPtr &si, std::vector<Eigen::Vector2d> footprint,
                                ScenePtr scene, const std::array<double, 4> &bounds,
                                const GridCheckerSettings &settings = GridCheckerSettings());

            bool isValid(const ompl::base::State *state) const override;
            bool isValid(const ompl::base::State *state, double &dist) const override;
            double clearance(const ompl::base::State *state) const override;

            /** \brief The same on a pose: the table's entry when it is valid (most queries), else, on a grid map,
                the exact answer on the grid (HeadingTable::freeOnGrid: the band's finer bits, then the footprint at
                this pose against the occupied cells), so that poses near obstacles that the entry's other poses
                would hit are not refused. */
            bool isValidPose(double x, double y, double yaw) const
            {
                return exact_ ? table_->freeOnGrid(x, y, yaw) : table_->validPose(x, y, yaw);
            }
            /** \brief Does an invalid entry fall back to the exact test at the pose? Only on a grid map's cells
                (GridCheckerSettings::mapResolution > 0), which are the obstacles exactly; a polygon scene's cells
                are only rasterised (measured: 49 unsafe states of 1,000,000 on se2_corridor with the fallback). */
            bool exact() const
            {
                return exact_;
            }
            double clearancePose(double x, double y, double yaw) const;

            const HeadingTable &table() const
            {
                return *table_;
            }
            /** \brief Distance (metres) from the centre of cell (i, j) to the centre of the nearest occupied cell;
                +inf when no cell is occupied or outside the grid. */
            double cellDistance(int i, int j) const;
            const std::vector<Eigen::Vector2d> &footprint() const
            {
                return footprint_;
            }
            const ScenePtr &scene() const
            {
                return scene_;
            }
            /** \brief Seconds taken by the last build or refresh (rasterisation, table, distance transform). */
            double buildSeconds() const
            {
                return buildSeconds_;
            }
            /** \brief HeadingTables built in this process so far. A checker over the same grid, footprint and
                headings as one made recently copies that table instead of building it again (the last two are
                kept). */
            static std::size_t tablesBuilt();
            /** \brief Bytes of the table, occupancy, prefix sums and distance transform. */
            std::size_t bytes() const;
            /** \brief One line: grid size, resolution, headings, memory, build time. */
            std::string describe() const;

            /** \brief Rasterise the scene again (it changed: a door closed) and recompute the table only around
                the cells that changed; returns the box of table cells recomputed (empty: nothing changed). */
            CellBox refresh();
            /** \brief How many refresh() calls changed the table so far: a planner that keeps checks between queries
                (HeadingLattice) compares it to see that the scene it checked against is gone. */
            std::uint64_t refreshCount() const
            {
                return refreshes_;
            }

        private:
            void distanceTransform();
            std::vector<Eigen::Vector2d> footprint_;
            std::vector<Eigen::Vector2d> outline_;  ///< points of the footprint's outline, at most a cell apart
            ScenePtr scene_;
            double tolerance_{0.};
            double zMin_{-std::numeric_limits<double>::infinity()};  ///< the robot's z range (GridCheckerSettings)
            double zMax_{std::numeric_limits<double>::infinity()};
            std::unique_ptr<HeadingTable> table_;
            std::uint64_t refreshes_{0};   ///< refresh() calls that changed the table
            std::vector<float> distance_;  ///< cellDistance() per cell, metres
            double buildSeconds_{0.};
            bool se2_{false};    ///< the space is an SE2StateSpace (read directly)
            bool exact_{false};  ///< see exact()
        };

        using GridValidityCheckerPtr = std::shared_ptr<GridValidityChecker>;
    }  // namespace validity
}  // namespace michi

#endif
