#ifndef MICHI_VALIDITY_GRID_HEADING_TABLE_
#define MICHI_VALIDITY_GRID_HEADING_TABLE_

#include <michi/validity/grid/BandTable.h>
#include <michi/validity/grid/OccupancyGrid.h>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief Cells (dx, dy) relative to a pose's cell: row dy, columns x0..x1 (inclusive). */
        struct GridSpan
        {
            int dy{0};
            int x0{0};
            int x1{0};
        };

        /** \brief A rectangle of cells, columns i0..i1 and rows j0..j1 inclusive; empty when i0 > i1. */
        struct CellBox
        {
            int i0{0}, i1{-1}, j0{0}, j1{-1};
            bool empty() const
            {
                return i0 > i1 || j0 > j1;
            }
        };

        /** \brief The bit-packed (x, y, heading) validity table of a planar footprint on an occupancy grid.

            Heading bin k covers yaws [k d - d / 2, k d + d / 2] (d = 2 pi / headings; bin 0 is centred on yaw 0).
            Entry (i, j, k) is 1 (valid) only when the footprint is free at \e every pose whose position lies in
            the closed square of cell (i, j) and whose yaw lies in bin k: the footprint is swept over the bin
            (sampled every d / n, each sample grown by the most a footprint point moves between samples,
            R d / (2 n)) and grown by the cell (a pose anywhere in its cell, an obstacle anywhere in an occupied
            cell), and every cell that this grown, swept footprint meets (its "stamp") must be free. Valid entries
            are therefore free for FCL too, whatever the pose within them; invalid ones may still hold free poses
            (the table is conservative). The table is the occupancy grid dilated by each heading's stamp, computed
            with row prefix sums (cells x stamp rows per heading).

            Summaries of blocks (8 x 8 cells, or a map cell of 4 x 4) and of cells (valid at every heading, invalid
            at every heading) answer most queries from a few kilobytes and two bits a cell that stay in the cache;
            the rest read the table.

            Memory: two bits per entry (valid; blocked: every pose collides), interleaved per 64 entries so that a
            query finds both in one cache line, a byte of occupancy per cell (and, while computing, a 32-bit running
            count per cell of the rows computed), and the BandTable when buildBand() made one. A 2048 x 2048 table
            with 16 headings holds 16 MiB of bits.

            Queries are const and thread-safe; setOccupied() is not (no query may run meanwhile). */
        class HeadingTable
        {
        public:
            /** \param footprint the robot's outline in its own frame (any simple polygon)
                \param headings number of heading bins (>= 1)
                \param tolerance how far (metres) an obstacle may reach into a cell marked free (see
                rasterizeScene); the stamps are grown by it */
            HeadingTable(OccupancyGrid grid, std::vector<Eigen::Vector2d> footprint, unsigned int headings,
                         double tolerance = 0.);

            int width() const
            {
                return grid_.width;
            }
            int height() const
            {
                return grid_.height;
            }
            int headings() const
            {
                return headings_;
            }
            /** \brief Radians per heading bin. */
            double headingStep() const
            {
                return step_;
            }
            const OccupancyGrid &grid() const
            {
                return grid_;
            }
            /** \brief Heading bin of a yaw (any real). */
            int headingBin(double yaw) const;
            /** \brief Table entry; false outside the grid. \e k is taken modulo headings(). */
            bool valid(int i, int j, int k) const
            {
                if (!grid_.inside(i, j))
                    return false;
                k %= headings_;
                if (k < 0)
                    k += headings_;
                const std::size_t word = (static_cast<std::size_t>(k) * grid_.height + j) * wordsPerRow_ + (i >> 6);
                return (words_[2 * word] >> (i & 63)) & 1u;
            }
            /** \brief The entry holding pose (x, y, yaw); false outside the grid or for a non-finite value. The hot
                path of the grid checker: a few multiplications and one bit (no division, no library call). */
            bool validPose(double x, double y, double yaw) const
            {
                const double fx = (x - grid_.origin.x()) * inverseResolution_;
                const double fy = (y - grid_.origin.y()) * inverseResolution_;
                if (!(fx >= 0. && fy >= 0. && fx < grid_.width && fy < grid_.height && std::abs(yaw) < 1e6))
                    return false;
                const int i = static_cast<int>(fx), j = static_cast<int>(fy);  // >= 0: truncation is floor
                // most queries end here: blocks valid (or invalid) at every heading, a few kB
                const std::size_t b = static_cast<std::size_t>(j >> blockShift_) * blocksPerRow_ +
                                      static_cast<std::size_t>(i >> blockShift_);
                if ((blocks_[2 * (b >> 6)] >> (b & 63)) & 1u)
                    return true;
                if ((blockAllInvalid_[b >> 6] >> (b & 63)) & 1u)
                    return false;
                // then cells valid (or invalid) at every heading: two bits a cell
                const std::size_t c = static_cast<std::size_t>(j) * wordsPerRow_ * 64 + static_cast<std::size_t>(i);
                if ((cells_[2 * (c >> 6)] >> (c & 63)) & 1u)
                    return true;
                if ((cellAllInvalid_[c >> 6] >> (c & 63)) & 1u)
                    return false;
                const int k = fastHeadingBin(yaw);
                const std::size_t word = (static_cast<std::size_t>(k) * grid_.height + j) * wordsPerRow_ + (i >> 6);
                return (words_[2 * word] >> (i & 63)) & 1u;
            }
            /** \brief Is the footprint at pose (x, y, yaw) clear of every occupied cell? The same answer as
                freePose(x, y, yaw), for the grid checker on grid maps, mostly from bits: a valid entry (free), the
                pose's own cell occupied or a blocked entry (collides), then, for a band entry (invalid, not
                blocked), its sub-entry in the BandTable (when buildBand() made one: free or colliding at every pose
                of the sub-entry); only a pose none of them decides is tested exactly. With exactFirst() the table
                word and the band are skipped: a pose the block and cell summaries leave open is tested exactly (on
                a map whose cell summary outgrows the caches, one the block summaries leave open). False outside
                the grid. */
            bool freeOnGrid(double x, double y, double yaw) const
            {
                const double fx = (x - grid_.origin.x()) * inverseResolution_;
                const double fy = (y - grid_.origin.y()) * inverseResolution_;
                if (!(fx >= 0. && fy >= 0. && fx < grid_.width && fy < grid_.height && std::abs(yaw) < 1e6))
                    return false;
                const int i = static_cast<int>(fx), j = static_cast<int>(fy);
                if (superShift_ != 0)
                {
                    // where the block summary outgrows the first-level cache (64room: 64 KiB), blocks of 4 x 4
                    // blocks first (4 KiB), which FCL's work between a planner's queries does not evict
                    const std::size_t s = static_cast<std::size_t>(j >> superShift_) * supersPerRow_ +
                                          static_cast<std::size_t>(i >> superShift_);
                    const std::uint64_t superValid = supers_[2 * (s >> 6)];
                    const std::uint64_t superBlocked = supers_[2 * (s >> 6) + 1];
                    if (((superValid | superBlocked) >> (s & 63)) & 1u)
                        return (superValid >> (s & 63)) & 1u;
                }
                const std::size_t b = static_cast<std::size_t>(j >> blockShift_) * blocksPerRow_ +
                                      static_cast<std::size_t>(i >> blockShift_);
                // Most queries end at their block: free at every pose, or colliding at every pose (inside a wall:
                // with the table aligned to the map, an occupied map cell of 8 x 8 or 4 x 4 table cells is a whole
                // block). One branch for "the block decides" and the answer as data: a branch on the answer itself
                // mispredicts as often as free and colliding poses alternate.
                const std::uint64_t blockValid = blocks_[2 * (b >> 6)];
                const std::uint64_t blockBlocked = blocks_[2 * (b >> 6) + 1];  // the same cache line
                if (((blockValid | blockBlocked) >> (b & 63)) & 1u)
                    return (blockValid >> (b & 63)) & 1u;
                // the cell's "valid at every heading" and "occupied" bits share a cache line
                const std::size_t c = static_cast<std::size_t>(j) * wordsPerRow_ + static_cast<std::size_t>(i >> 6);
                double fb = 0.;
                std::size_t word = 0;
                if (!exactFirst_)  // with exactFirst() no table word is read: nothing to fetch
                {
                    const int k = fastHeadingBin(yaw, fb);
                    word = (static_cast<std::size_t>(k) * grid_.height + j) * wordsPerRow_ + (i >> 6);
                    // the three cache lines a query may need next are fetched at once, not one after the other (on
                    // a large map, after other work, each is a miss)
                    __builtin_prefetch(&words_[2 * word]);
                    if (!band_.empty())
                        __builtin_prefetch(band_.record(word));
                }
                if (exactBeforeCells_)  // a large map: the exact test's coarse rows stay cached, the cells do not
                    return footprintFree(x, y, yaw, 0.);
                // valid at every heading, or occupied while the footprint holds the origin: the cell decides
                const std::uint64_t cellValid = cells_[2 * c];
                const std::uint64_t cellBlocked = cells_[2 * c + 1] & originMask_;
                if (((cellValid | cellBlocked) >> (i & 63)) & 1u)
                    return (cellValid >> (i & 63)) & 1u;
                if (exactFirst_)
                    return footprintFree(x, y, yaw, 0.);
                const std::uint64_t valid = words_[2 * word];
                const std::uint64_t blocked = words_[2 * word + 1];  // the same cache line
                if (((valid | blocked) >> (i & 63)) & 1u)
                    return (valid >> (i & 63)) & 1u;
                if (!band_.empty())
                {
                    const std::uint64_t below = (std::uint64_t{1} << (i & 63)) - 1;
                    const BandTable::Entry &e =
                        band_.entry(word, static_cast<unsigned>(__builtin_popcountll(~valid & ~blocked & below)));
                    const int s = band_.subEntry(fx, fy, fb);
                    if ((e.valid >> s) & 1u)
                        return true;
                    if ((e.blocked >> s) & 1u)
                        return false;
                }
                return footprintFree(x, y, yaw, 0.);
            }
            /** \brief Split the band entries (invalid, not blocked) into sub-entries (BandTable) for freeOnGrid();
                kept up to date by setOccupied() and update() from then on. */
            void buildBand();
            const BandTable &band() const
            {
                return band_;
            }
            /** \brief The band's sub-entries of entry (i, j, k); null when it is no band entry (valid, blocked or
                outside the grid) or buildBand() was not called. */
            const BandTable::Entry *bandEntry(int i, int j, int k) const
            {
                if (band_.empty() || !grid_.inside(i, j) || k < 0 || k >= headings_)
                    return nullptr;
                const std::size_t word = (static_cast<std::size_t>(k) * grid_.height + j) * wordsPerRow_ + (i >> 6);
                const std::uint64_t valid = words_[2 * word];
                const std::uint64_t blocked = words_[2 * word + 1];  // the same cache line
                if (((valid | blocked) >> (i & 63)) & 1u)
                    return nullptr;
                const std::uint64_t below = (std::uint64_t{1} << (i & 63)) - 1;
                return &band_.entry(word, static_cast<unsigned>(__builtin_popcountll(~valid & ~blocked & below)));
            }
            /** \brief Is the footprint at pose (x, y, yaw), grown by \e margin metres (a square growth, so at least
                as far in every direction), clear of every occupied cell? Exact on the grid (each convex piece of the
                footprint is intersected with the rows of cells it spans), for the poses the table's entries cannot
                decide: an invalid entry only says that \e some pose of its cell and heading bin collides. The
                tolerance given at construction is added to the margin. False outside the grid. */
            bool freePose(double x, double y, double yaw, double margin = 0.) const;
            /** \brief Is every pose of entry (i, j, k) in collision (an occupied cell lies in its core stamp, or
                the cell is occupied and the footprint holds the origin)? False outside the grid. */
            bool entryBlocked(int i, int j, int k) const
            {
                if (!grid_.inside(i, j))
                    return false;
                const std::size_t word = (static_cast<std::size_t>(k) * grid_.height + j) * wordsPerRow_ + (i >> 6);
                const std::size_t c = static_cast<std::size_t>(j) * wordsPerRow_ + (i >> 6);
                return (((words_[2 * word + 1] | (cells_[2 * c + 1] & originMask_)) >> (i & 63)) & 1u) != 0;
            }
            /** \brief Does freeOnGrid() test a pose the summaries leave open exactly, without the table word
                and the band (a footprint over at most two rows of the exact test's bits)? */
            bool exactFirst() const
            {
                return exactFirst_;
            }
            /** \brief Cells per side of the summary blocks: a grid whose origin is a multiple of it from the map's
                origin has whole map cells in its blocks (when the map cell is a whole number of table cells). */
            static constexpr int blockCells()
            {
                return 1 << MAX_BLOCK_SHIFT;
            }
            /** \brief Is cell (i, j) occupied? False outside the grid. */
            bool occupied(int i, int j) const
            {
                if (!grid_.inside(i, j))
                    return false;
                return (cells_[2 * (static_cast<std::size_t>(j) * wordsPerRow_ + (i >> 6)) + 1] >> (i & 63)) & 1u;
            }
            /** \brief Cells that, when occupied, make heading \e k invalid, relative to the pose's cell. */
            const std::vector<GridSpan> &stamp(int k) const
            {
                return stamps_[static_cast<std::size_t>(k)];
            }
            /** \brief Table cells per side of the second summary level freeOnGrid() reads before the blocks (0:
                none; made where the block summary outgrows the first-level cache). */
            int superBlockCells() const
            {
                return superShift_ == 0 ? 0 : 1 << superShift_;
            }
            /** \brief Table cells per side of the coarse occupancy the exact test reads (1: it reads the table's own
                rows). */
            int coarseFactor() const
            {
                return coarse_;
            }
            /** \brief Radius of the smallest circle about the robot's origin holding the footprint. */
            double circumradius() const
            {
                return circumradius_;
            }
            /** \brief Number of valid entries. */
            std::size_t validCount() const;
            /** \brief Bytes held (bits, occupancy, summaries). */
            std::size_t bytes() const;

            /** \brief Mark cells occupied or free and recompute the entries they can change; returns the box of
                table cells whose entries were recomputed (all headings). Cells outside the grid are ignored. */
            CellBox setOccupied(const std::vector<std::pair<int, int>> &cells, bool occupied);
            /** \brief Take a new occupancy of the same grid (size, resolution, origin) and recompute only around
                the cells that changed; returns the recomputed box (empty when nothing changed). */
            CellBox update(const OccupancyGrid &grid);

        private:
            /** headingBin() for the inline queries: a floor without std::floor, one wrap for yaws within a turn
                of [-pi, pi), headingBin() beyond */
            int fastHeadingBin(double yaw) const
            {
                double fb;
                return fastHeadingBin(yaw, fb);
            }
            /** the same, and the yaw in bins (\e fb, shifted by half a bin) */
            int fastHeadingBin(double yaw, double &fb) const
            {
                fb = yaw * inverseStep_ + 0.5;
                int k = static_cast<int>(fb);
                k -= static_cast<int>(fb < k);  // floor
                // Wrapped without a branch: half of all yaws are negative, and a branch on the sign mispredicted on
                // every other query (measured, docs/checking.md).
                k += headings_ & -static_cast<int>(k < 0);
                k -= headings_ & -static_cast<int>(k >= headings_);
                if (k < 0 || k >= headings_)
                    k = headingBin(yaw);  // more than a turn away from [-pi, pi)
                return k;
            }
            void makeStamps(const std::vector<Eigen::Vector2d> &footprint, double tolerance);
            /** \brief coreStamps_ of a convex footprint: the cells the footprint covers whole at every pose of an
                entry (every position in the cell, every yaw in the bin). */
            void makeCoreStamps();
            /** \brief Is entry (cell of x, y; bin of yaw) known to collide at every pose (its blocked bit)? */
            bool certainlyBlocked(double x, double y, double yaw) const;
            /** \brief freePose() without its shortcuts: the footprint's pieces against the rows of cells (the coarse
                rows when the grid has them). */
            bool footprintFree(double x, double y, double yaw, double margin) const;
            /** \brief The pieces at pose (x, y; cos c, sin s of the yaw), grown by \e margin, against occupied bits in
                rows of \e wordsPerRow words (\e stride apart), \e width x \e height cells of 1 / \e inv metres from
                the grid's origin. */
            bool rowsFree(const std::uint64_t *occupied, std::size_t wordsPerRow, std::size_t stride, int width,
                          int height, double inv, double x, double y, double c, double s, double margin) const;
            /** \brief coarseCells_ from the grid (none when no block size fits every cell). */
            void makeCoarse();
            /** \brief Keep coarseCells_ after the cells in \e changed changed (or drop them). */
            void updateCoarse(const CellBox &changed);
            /** \brief Recompute the band's sub-entries of the entries in \e box (all when null), keep the others. */
            void computeBand(const CellBox *box);
            void computeRegion(const CellBox &box);
            /** \brief Recompute the block summaries of the blocks meeting \e box. */
            void summarise(const CellBox &box);
            static constexpr int MAX_BLOCK_SHIFT = 3;  ///< summary blocks of at most 8 x 8 cells (blockCells())
            /** summary blocks of 2^blockShift_ cells a side: a map cell when the map's cells are 4 x 4 table cells
                (coarse_), so that an occupied map cell is a blocked block; else 8 x 8 (measured, checking.md) */
            int blockShift_{MAX_BLOCK_SHIFT};
            CellBox affected(const CellBox &changed) const;
            OccupancyGrid grid_;
            int headings_{16};
            double step_{0.};
            double inverseStep_{0.};
            double inverseResolution_{0.};
            double circumradius_{0.};
            std::size_t wordsPerRow_{0};
            /** the table, two words per 64 entries (k, j, i / 64): the valid bits, then the blocked bits (1 where an
                occupied cell lies in the entry's core stamp, so every pose of the entry collides and freePose() need
                not look; all 0 when the footprint is not convex), so that a query finds both in one cache line */
            std::vector<std::uint64_t> words_;
            std::vector<std::vector<GridSpan>> coreStamps_;
            std::size_t blocksPerRow_{0};
            /** per block, two words per 64 blocks: every entry valid, then every entry blocked (all poses collide),
                so that freeOnGrid() finds both in one cache line (64room's blocks are single map cells: 32 KiB a
                summary, past the first-level cache, so a second array cost a second line) */
            std::vector<std::uint64_t> blocks_;
            std::vector<std::uint64_t> blockAllInvalid_;  ///< per block: every entry invalid
            /** super-blocks of 2^SUPER_SHIFT x 2^SUPER_SHIFT blocks, laid out as blocks_ (valid, blocked): a bit is
                set only where it is set for every block inside; made when blocks_ exceeds SUPER_MIN_BYTES
                (superShift_ 0: none) */
            static constexpr int SUPER_SHIFT = 2;
            static constexpr std::size_t SUPER_MIN_BYTES = 16 * 1024;
            /** \brief With exactFirst() on the coarse rows, the exact test comes before the cell summary where the
                summary is larger than this (chooseExactFirst()). */
            static constexpr std::size_t CELLS_CACHED_BYTES = 256 * 1024;
            bool exactBeforeCells_{false};
            int superShift_{0};
            std::size_t supersPerRow_{0};
            std::vector<std::uint64_t> supers_;
            std::uint64_t originMask_{0};  ///< all ones when originInside_: an occupied cell then blocks its poses
            /** per cell, two words per 64 cells (j, i / 64): valid at every heading, then occupied */
            std::vector<std::uint64_t> cells_;
            std::vector<std::uint64_t>
                cellAllInvalid_;  ///< per cell (rows of wordsPerRow_ words): every heading invalid
            /** convex pieces of the footprint (its hull when it is convex, else triangles), for freePose() */
            std::vector<std::vector<Eigen::Vector2d>> pieces_;
            double tolerance_{0.};
            /** the robot's origin lies in its footprint: a pose in an occupied cell collides (freePose's shortcut) */
            bool originInside_{false};
            std::vector<std::vector<GridSpan>> stamps_;
            /** Occupancy at f x f table cells a bit (f = coarse_, 2, 4 or 8; 1: none), for the exact test: every block
                of the grid is wholly occupied or wholly free (a map cell split by the table), so the rows hold the same
                obstacles; on arena 51 x 51 bits instead of 406 x 406 */
            int coarse_{1};
            /** freeOnGrid() goes to the exact test right after the cell summary, without the table word and the
                band: the footprint spans at most two rows of the exact test's bits, so the test is a sincos and a
                row or two of a few kilobytes that stay cached, while the table word and the band (megabytes) are a
                miss to L3 once other work (a planner's, FCL's in verify-checker) has run (measured, checking.md) */
            bool exactFirst_{false};
            /** \brief Set exactFirst_ from the footprint and the exact test's rows (after coarse_ changes). */
            void chooseExactFirst();
            int coarseWidth_{0}, coarseHeight_{0};
            std::size_t coarseWordsPerRow_{0};
            std::vector<std::uint64_t> coarseCells_;
            BandTable band_;            ///< empty until buildBand()
            int reach_[4]{0, 0, 0, 0};  ///< min dx, max dx, min dy, max dy over all stamps
        };
    }  // namespace validity
}  // namespace michi

#endif
