#ifndef MICHI_VALIDITY_JMAP_VALIDITY_CHECKER_
#define MICHI_VALIDITY_JMAP_VALIDITY_CHECKER_

#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/jmap/JMap.h>

#include <ompl/base/StateValidityChecker.h>

#include <atomic>
#include <functional>
#include <mutex>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief Settings of the J-map checker. */
        struct JMapCheckerSettings
        {
            enum class Mode
            {
                CONSERVATIVE,   ///< answer from the polygons: never valid where FCL says invalid
                EXACT_FALLBACK  ///< states the J-map calls invalid within fallbackBand of a polygon edge go to FCL
            };
            Mode mode{Mode::CONSERVATIVE};
            JMapSettings map;  ///< map.slices is the number of theta1 cells over the whole range
            int tiles{8};      ///< the theta1 range is built lazily in this many tiles (slices per tile rounded up)
            double fallbackBand{0.05};  ///< radians of the map, for EXACT_FALLBACK
        };

        /** \brief An OMPL StateValidityChecker that answers from a J-map (paper 000) of two joints of an arm.
            The map is cut along theta1 into tiles built lazily, each on the first query that falls into it, and
            cached (several threads may query at once; a tile is built once). When the scene's change counter
            moves, the cache is dropped. If the map covers the whole robot (the state is exactly the two axes and
            no self-collision pair can touch within their ranges), a state outside the polygons is valid without
            FCL; otherwise the map is a pre-filter (inside a polygon: invalid) and FCL decides the rest (the
            paper's arm map with the hand checked separately). Clearance comes from FCL. */
        class JMapValidityChecker : public ompl::base::StateValidityChecker
        {
        public:
            using SourceFactory = std::function<JMapIntervalSourcePtr(const JMapAxes &axes)>;

            /** \param fcl the exact checker of the same robot and scene (RobotGroupBodies)
                \param makeSource builds the interval source of a tile (axes with the tile's theta1 range)
                \param axes the map's axes (configuration indices) and the other joints' values
                \param coversRobot true when the source sees every link the state moves */
            JMapValidityChecker(const ompl::base::SpaceInformationPtr &si, FclValidityCheckerPtr fcl,
                                SourceFactory makeSource, JMapAxes axes, bool coversRobot,
                                JMapCheckerSettings settings = {});

            bool isValid(const ompl::base::State *state) const override;
            double clearance(const ompl::base::State *state) const override;

            /** \brief The same on raw group values (as copyToReals gives them). */
            bool isValidConfiguration(const double *values) const;
            /** \brief The tile holding theta1 (built if needed; valid as long as the checker lives). */
            const JMap &tile(double theta1) const;
            /** \brief Build every tile now (for pictures and measurements). */
            void buildAll() const;
            /** \brief Every tile's polygons, united into one set (a region split at a tile border is one polygon
                again); builds every tile first. For pictures and for planners that work on the polygons. */
            MultiPolygon2 unitedPolygons() const;
            std::size_t tileCount() const
            {
                return tileCount_;
            }
            std::size_t builtTiles() const;
            /** \brief Whether states outside the polygons are valid without asking FCL. */
            bool answersAlone() const
            {
                return answersAlone_;
            }
            /** \brief Queries answered by FCL so far (fallbacks and pre-filter passes). */
            std::uint64_t fclQueries() const
            {
                return fclQueries_.load();
            }
            /** \brief unitedPolygons() calls so far (each unites every tile's polygons: milliseconds; a planner
                should do it once per checker and scene, not per solve). */
            std::uint64_t unionsMade() const
            {
                return unionsMade_.load();
            }
            const JMapAxes &axes() const
            {
                return axes_;
            }
            /** \brief Where the two axes are in the state's values (copyToReals order). */
            int valueIndex1() const
            {
                return value1_;
            }
            int valueIndex2() const
            {
                return value2_;
            }
            const FclValidityCheckerPtr &fcl() const
            {
                return fcl_;
            }
            const JMapCheckerSettings &settings() const
            {
                return settings_;
            }

        private:
            std::size_t tileIndex(double theta1) const;
            void dropIfSceneChanged() const;
            FclValidityCheckerPtr fcl_;
            SourceFactory makeSource_;
            JMapAxes axes_;
            JMapCheckerSettings settings_;
            int value1_{0}, value2_{1};  ///< indices of the axes in the state's values
            bool answersAlone_{false};
            /** Current tile maps (null: not built), read without locks; every map ever built stays alive in owned_
                (a scene change only swaps the pointers), so a reader never sees a freed map. */
            mutable std::unique_ptr<std::atomic<const JMap *>[]> tiles_;
            std::size_t tileCount_{0};
            double tileScale_{1.};         ///< tiles per radian of axis 1
            const Scene *scene_{nullptr};  ///< fcl_'s scene (kept alive by fcl_)
            mutable std::vector<JMapPtr> owned_;
            mutable std::mutex buildMutex_;
            mutable std::atomic<std::uint64_t> generation_{0};
            mutable std::atomic<std::uint64_t> fclQueries_{0};
            mutable std::atomic<std::uint64_t> unionsMade_{0};
        };

        using JMapValidityCheckerPtr = std::shared_ptr<JMapValidityChecker>;

        /** \brief True when no self-collision pair of \e bodies can touch while axes 1 and 2 move over their
            ranges (other joints at the axes' configuration): a grid of FCL self distances, each certifying its
            cell with the pair's displacement bounds; false as soon as a cell cannot be certified. */
        bool selfCollisionImpossible(const FclValidityChecker &fcl, const JMapAxes &axes, double cell = 0.05);
    }  // namespace validity
}  // namespace michi

#endif
