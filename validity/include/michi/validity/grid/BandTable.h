#ifndef MICHI_VALIDITY_GRID_BAND_TABLE_
#define MICHI_VALIDITY_GRID_BAND_TABLE_

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief Finer bits for the "band" entries of a HeadingTable: entries that are invalid (some pose of the
            cell and heading bin collides) but not blocked (not every pose collides), where the grid checker would
            otherwise test the footprint at the pose itself (HeadingTable::freePose, 100-500 ns).

            A band entry is split into 64 sub-entries: P x P sub-squares of its cell times S sub-bins of its heading
            bin (P^2 S = 64, chosen by layout()). Each sub-entry has two bits: \e valid (no pose of it meets an
            occupied cell: free for FCL, as a table entry) and \e blocked (every pose of it meets an occupied cell,
            which on a grid map is an obstacle whole). Neither: the caller tests the pose exactly.

            The bits come from two masks per heading bin and cell offset o (relative to the entry's cell), made once
            from the footprint: may(o) (the sub-entries some pose of which meets cell o: the footprint at sample yaws
            of the sub-bin, grown by how far a point moves between samples, against cell o less the sub-square) and
            blocks(o) (the sub-entries every pose of which meets cell o: at each sample yaw and each corner of the
            sub-square the footprint meets cell o shrunk by that distance; a convex piece and the convex set of
            positions from which it meets a box make the corners enough). An entry's sub-entries are then
            valid = ~OR may(o), blocked = OR blocks(o) over its occupied cells o: a few OR operations per occupied
            cell near it. Cells outside the grid count as occupied (valid bits stay conservative).

            Storage: a 16-bit index per band entry into the distinct entries, in the order of the table's bits,
            found by rank (a running count of band entries per 64-bit table word and a popcount). Each table word's
            record (16 bytes) holds its rank and the indices of its first INLINE band entries, so that a query reads
            the record beside the table word, both at once, and then only the distinct entries (a few kilobytes,
            in the cache): not the index array after the rank, a second cache miss that waited for the first. */
        class BandTable
        {
        public:
            /** \brief The two 64-bit words of a band entry: bit s = sub-entry s (s = (h P + py) P + px). */
            struct Entry
            {
                std::uint64_t valid{0};
                std::uint64_t blocked{0};
            };

            BandTable() = default;
            /** \param pieces convex pieces of the footprint (any orientation)
                \param resolution table cell size (metres)
                \param headings heading bins over 2 pi (bin k centred on yaw k 2 pi / headings)
                \param tolerance how far an obstacle may reach into a free cell (metres) */
            BandTable(const std::vector<std::vector<Eigen::Vector2d>> &pieces, double resolution, int headings,
                      double tolerance);

            /** \brief Sub-squares per cell side P (1, 2, 4 or 8) and sub-bins S (P^2 S = 64) that make a sub-entry's
                reach (P: r / P of position, S: the footprint's sweep R 2 pi / (headings S)) smallest. */
            static void layout(double resolution, double circumradius, int headings, int &positions, int &subHeadings);

            int positions() const
            {
                return positions_;
            }
            int subHeadings() const
            {
                return subHeadings_;
            }
            bool empty() const
            {
                return offsets_.empty();
            }
            /** \brief Sub-entry of a pose: fx, fy its position in cells (fractional parts used), fb its yaw in bins
                plus one half (fractional part used). */
            int subEntry(double fx, double fy, double fb) const
            {
                const double sx = (fx - static_cast<double>(static_cast<long long>(fx))) * positions_;
                const double sy = (fy - static_cast<double>(static_cast<long long>(fy))) * positions_;
                double fl = static_cast<double>(static_cast<long long>(fb));
                fl -= (fb < fl) ? 1. : 0.;
                const double sh = (fb - fl) * subHeadings_;
                int px = static_cast<int>(sx), py = static_cast<int>(sy), h = static_cast<int>(sh);
                px = px < positions_ ? px : positions_ - 1;
                py = py < positions_ ? py : positions_ - 1;
                h = h < subHeadings_ ? (h < 0 ? 0 : h) : subHeadings_ - 1;
                return (h * positions_ + py) * positions_ + px;
            }

            /** \brief The sub-entry bits of entry (i, j, k) from the occupancy (rows of \e wordsPerRow 64-bit words,
                \e width x \e height cells; outside counts as occupied). */
            Entry compute(int i, int j, int k, const std::uint64_t *occupied, std::size_t wordsPerRow, int width,
                          int height) const;

            /** \brief Band entries before table word \e w (rank); w may be the number of words (then: all). */
            std::uint32_t rank(std::size_t w) const
            {
                return records_[w].rank;
            }
            /** \brief Band entries of a table word kept in its record. */
            static constexpr unsigned INLINE = 6;
            /** \brief The \e n-th band entry of table word \e w (n counts the word's band entries before it). */
            const Entry &entry(std::size_t w, unsigned n) const
            {
                const Record &r = records_[w];
                return patterns_[n < INLINE ? r.first[n] : index_[r.rank + n]];
            }
            /** \brief Where table word \e w's record lies (for a prefetch). */
            const void *record(std::size_t w) const
            {
                return &records_[w];
            }
            /** \brief Band entry number \e n (in the order of the table's bits). */
            const Entry &entry(std::size_t n) const
            {
                return patterns_[index_[n]];
            }
            /** \brief Number of band entries. */
            std::size_t size() const
            {
                return index_.size();
            }
            /** \brief Number of distinct entries (each band entry is an index into them). */
            std::size_t patterns() const
            {
                return patterns_.size();
            }
            std::size_t bytes() const
            {
                std::size_t b = records_.size() * sizeof(Record) + index_.size() * sizeof(std::uint16_t) +
                                patterns_.size() * sizeof(Entry);
                for (const auto &o : offsets_)
                    b += (o.may.size() + o.blocks.size()) * sizeof(std::uint64_t);
                return b;
            }
            /** \brief Take new ranks (one per table word and the total) and entries (HeadingTable fills them); the
                entries are stored as 16-bit indices into their distinct values (along a straight wall most entries
                repeat), so that the band stays in the cache: the first 65535 distinct values, any other entry as
                "undecided" (no bits). */
            void assign(const std::vector<std::uint32_t> &prefix, const std::vector<Entry> &entries);
            /** \brief Offsets an entry's bits read: min dx, max dx, min dy, max dy over all headings. */
            const int *reach() const
            {
                return reach_;
            }

        private:
            /** may / blocks masks of one heading bin over a box of offsets dx0..dx1, dy0..dy1 */
            struct Offsets
            {
                int dx0{0}, dx1{-1}, dy0{0}, dy1{-1};
                std::vector<std::uint64_t> may, blocks;  ///< index (dy - dy0) (dx1 - dx0 + 1) + dx - dx0
            };
            int positions_{1};
            int subHeadings_{64};
            /** per table word: its rank and the indices of its first INLINE band entries (0 past its last) */
            struct Record
            {
                std::uint32_t rank{0};
                std::uint16_t first[INLINE]{};
            };
            static_assert(sizeof(Record) == 16, "a record is 16 bytes: four to a cache line, never across two");
            std::vector<Offsets> offsets_;
            std::vector<Record> records_;
            std::vector<std::uint16_t> index_;  ///< per band entry: its value in patterns_
            std::vector<Entry> patterns_;       ///< distinct values; patterns_[0] has no bits
            int reach_[4]{0, 0, 0, 0};
        };
    }  // namespace validity
}  // namespace michi

#endif
