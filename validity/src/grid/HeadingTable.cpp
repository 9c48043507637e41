#include <michi/validity/grid/HeadingTable.h>
#include <michi/validity/scene/Shape.h>

#include "../FastRound.h"
#include "../FastSinCos.h"

#include <boost/math/constants/constants.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

namespace michi
{
    namespace validity
    {
        namespace
        {
            const double TWO_PI = boost::math::constants::two_pi<double>();

            double cross(const Eigen::Vector2d &o, const Eigen::Vector2d &a, const Eigen::Vector2d &b)
            {
                return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
            }

            /** Convex hull (Andrew's monotone chain), counter-clockwise, no repeated last point. */
            std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> p)
            {
                std::sort(p.begin(), p.end(),
                          [](const Eigen::Vector2d &a, const Eigen::Vector2d &b)
                          {
                              return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
                          });
                std::vector<Eigen::Vector2d> h(2 * p.size());
                std::size_t k = 0;
                for (std::size_t i = 0; i < p.size(); ++i)
                {
                    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0.)
                        --k;
                    h[k++] = p[i];
                }
                for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i)
                {
                    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0.)
                        --k;
                    h[k++] = p[i - 1];
                }
                h.resize(k > 1 ? k - 1 : k);
                return h;
            }

            /** x range of a convex polygon on the line y = c; false when the line misses it. */
            bool rowInterval(const std::vector<Eigen::Vector2d> &hull, double c, double &xa, double &xb)
            {
                xa = std::numeric_limits<double>::infinity();
                xb = -xa;
                for (std::size_t e = 0; e < hull.size(); ++e)
                {
                    const Eigen::Vector2d &a = hull[e], &b = hull[(e + 1) % hull.size()];
                    if ((a.y() - c) * (b.y() - c) > 0.)
                        continue;
                    if (a.y() == b.y())
                    {
                        xa = std::min({xa, a.x(), b.x()});
                        xb = std::max({xb, a.x(), b.x()});
                        continue;
                    }
                    const double x = a.x() + (b.x() - a.x()) * (c - a.y()) / (b.y() - a.y());
                    xa = std::min(xa, x);
                    xb = std::max(xb, x);
                }
                return xa <= xb;
            }
        }  // namespace

        HeadingTable::HeadingTable(OccupancyGrid grid, std::vector<Eigen::Vector2d> footprint, unsigned int headings,
                                   double tolerance)
            : grid_(std::move(grid)), headings_(static_cast<int>(headings))
        {
            if (headings < 1 || headings > 4096)
                throw std::invalid_argument("HeadingTable: headings must be in 1..4096, got " +
                                            std::to_string(headings));
            if (grid_.width < 1 || grid_.height < 1 || !(grid_.resolution > 0.) ||
                grid_.cells.size() != static_cast<std::size_t>(grid_.width) * grid_.height)
                throw std::invalid_argument("HeadingTable: empty or inconsistent occupancy grid");
            if (footprint.size() < 3)
                throw std::invalid_argument("HeadingTable: the footprint needs at least 3 points");
            // Bin k holds the yaws within half a step of k * step_ (headingBin rounds to the nearest bin centre).
            step_ = TWO_PI / headings_;
            inverseStep_ = 1. / step_;
            inverseResolution_ = 1. / grid_.resolution;
            for (const auto &p : footprint)
                circumradius_ = std::max(circumradius_, p.norm());
            makeStamps(footprint, tolerance);
            tolerance_ = tolerance;
            // a convex footprint is one piece (its hull, with as many corners); any other is its triangles
            const auto hull = convexHull(footprint);
            // At most 16 corners: freePose() keeps a piece's rotated corners in fixed arrays of 16.
            if (hull.size() == footprint.size() && hull.size() <= 16)
                pieces_.push_back(hull);
            else
                for (const auto &t : triangulatePolygon(footprint))
                    pieces_.push_back({footprint[t[0]], footprint[t[1]], footprint[t[2]]});
            for (const auto &piece : pieces_)
            {
                // a convex piece holds the origin when the origin is on the inner side of (or on) every edge
                bool inside = true;
                for (std::size_t e = 0; e < piece.size() && inside; ++e)
                {
                    const Eigen::Vector2d &a = piece[e], &b = piece[(e + 1) % piece.size()];
                    inside = cross(a, b, Eigen::Vector2d::Zero()) >= 0.;
                }
                originInside_ = originInside_ || inside;
            }
            originMask_ = originInside_ ? ~std::uint64_t{0} : 0;
            // Bit rows padded to whole 64-bit words, so that every row starts on a word and a row range is a few word
            // masks.
            wordsPerRow_ = (static_cast<std::size_t>(grid_.width) + 63) / 64;
            cells_.assign(2 * wordsPerRow_ * grid_.height, 0);
            for (int j = 0; j < grid_.height; ++j)
                for (int i = 0; i < grid_.width; ++i)
                    if (grid_.cells[static_cast<std::size_t>(j) * grid_.width + i])
                        cells_[2 * (static_cast<std::size_t>(j) * wordsPerRow_ + (i >> 6)) + 1] |= std::uint64_t{1}
                                                                                                   << (i & 63);
            makeCoarse();
            chooseExactFirst();
            words_.assign(2 * wordsPerRow_ * grid_.height * headings_, 0);
            makeCoreStamps();
            blockShift_ = coarse_ == 4 ? 2 : MAX_BLOCK_SHIFT;
            blocksPerRow_ = (static_cast<std::size_t>(grid_.width) >> blockShift_) + 1;
            const std::size_t blocks = blocksPerRow_ * ((static_cast<std::size_t>(grid_.height) >> blockShift_) + 1);
            blocks_.assign(2 * (blocks / 64 + 1), 0);
            blockAllInvalid_.assign(blocks / 64 + 1, 0);
            superShift_ = blocks_.size() * sizeof(std::uint64_t) > SUPER_MIN_BYTES ? blockShift_ + SUPER_SHIFT : 0;
            if (superShift_ != 0)
            {
                supersPerRow_ = (static_cast<std::size_t>(grid_.width) >> superShift_) + 1;
                supers_.assign(
                    2 * (supersPerRow_ * ((static_cast<std::size_t>(grid_.height) >> superShift_) + 1) / 64 + 1), 0);
            }
            cellAllInvalid_.assign(wordsPerRow_ * grid_.height, 0);
            computeRegion(CellBox{0, grid_.width - 1, 0, grid_.height - 1});
        }

        void HeadingTable::summarise(const CellBox &box)
        {
            if (box.empty())
                return;
            const int s = blockShift_, size = 1 << blockShift_;
            for (int j = box.j0; j <= box.j1; ++j)
                for (int i = box.i0; i <= box.i1; ++i)
                {
                    bool allValid = true, allInvalid = true;
                    for (int k = 0; k < headings_ && (allValid || allInvalid); ++k)
                    {
                        const bool v = valid(i, j, k);
                        allValid = allValid && v;
                        allInvalid = allInvalid && !v;
                    }
                    // The cell summaries use the same padded row layout as occupiedBits_: bit c of the flat array is
                    // cell (i, j).
                    const std::size_t c = static_cast<std::size_t>(j) * wordsPerRow_ * 64 + static_cast<std::size_t>(i);
                    const std::uint64_t bit = std::uint64_t{1} << (c & 63);
                    std::uint64_t &all = cells_[2 * (c >> 6)];
                    all = allValid ? (all | bit) : (all & ~bit);
                    cellAllInvalid_[c >> 6] =
                        allInvalid ? (cellAllInvalid_[c >> 6] | bit) : (cellAllInvalid_[c >> 6] & ~bit);
                }
            for (int bj = box.j0 >> s; bj <= box.j1 >> s; ++bj)
                for (int bi = box.i0 >> s; bi <= box.i1 >> s; ++bi)
                {
                    bool allValid = true, allInvalid = true, allBlocked = true;
                    for (int k = 0; k < headings_ && (allValid || allInvalid || allBlocked); ++k)
                        for (int j = bj * size; j < (bj + 1) * size && (allValid || allInvalid || allBlocked); ++j)
                            for (int i = bi * size; i < (bi + 1) * size; ++i)
                            {
                                // cells outside the grid count as invalid (validPose never reaches them) and as
                                // blocked (freeOnGrid() refuses a pose outside the grid before its block)
                                const bool v = valid(i, j, k);
                                allValid = allValid && v && grid_.inside(i, j);
                                allInvalid = allInvalid && !v;
                                allBlocked = allBlocked && (!grid_.inside(i, j) || entryBlocked(i, j, k));
                            }
                    const std::size_t b = static_cast<std::size_t>(bj) * blocksPerRow_ + static_cast<std::size_t>(bi);
                    const std::uint64_t bit = std::uint64_t{1} << (b & 63);
                    std::uint64_t &valid = blocks_[2 * (b >> 6)], &blocked = blocks_[2 * (b >> 6) + 1];
                    valid = allValid ? (valid | bit) : (valid & ~bit);
                    blocked = allBlocked ? (blocked | bit) : (blocked & ~bit);
                    blockAllInvalid_[b >> 6] =
                        allInvalid ? (blockAllInvalid_[b >> 6] | bit) : (blockAllInvalid_[b >> 6] & ~bit);
                }
            if (superShift_ == 0)
                return;
            const std::size_t blockRows = (static_cast<std::size_t>(grid_.height) >> blockShift_) + 1;
            const int t = superShift_ - blockShift_;
            for (int sj = box.j0 >> superShift_; sj <= box.j1 >> superShift_; ++sj)
                for (int si = box.i0 >> superShift_; si <= box.i1 >> superShift_; ++si)
                {
                    // a super-block says only what each of its blocks says; one reaching past the blocks says nothing
                    bool allValid = true, allBlocked = true;
                    for (int bj = sj << t; bj < (sj + 1) << t; ++bj)
                        for (int bi = si << t; bi < (si + 1) << t; ++bi)
                        {
                            if (static_cast<std::size_t>(bi) >= blocksPerRow_ ||
                                static_cast<std::size_t>(bj) >= blockRows)
                            {
                                allValid = allBlocked = false;
                                continue;
                            }
                            const std::size_t b =
                                static_cast<std::size_t>(bj) * blocksPerRow_ + static_cast<std::size_t>(bi);
                            allValid = allValid && ((blocks_[2 * (b >> 6)] >> (b & 63)) & 1u);
                            allBlocked = allBlocked && ((blocks_[2 * (b >> 6) + 1] >> (b & 63)) & 1u);
                        }
                    const std::size_t u = static_cast<std::size_t>(sj) * supersPerRow_ + static_cast<std::size_t>(si);
                    const std::uint64_t bit = std::uint64_t{1} << (u & 63);
                    std::uint64_t &valid = supers_[2 * (u >> 6)], &blocked = supers_[2 * (u >> 6) + 1];
                    valid = allValid ? (valid | bit) : (valid & ~bit);
                    blocked = allBlocked ? (blocked | bit) : (blocked & ~bit);
                }
        }

        bool HeadingTable::freePose(double x, double y, double yaw, double margin) const
        {
            if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(yaw) || !(margin >= 0.))
                return false;
            // in cell units: cell (i, j) is the square [i, i + 1] x [j, j + 1]; growing the footprint by m is
            // growing each cell by m, so a piece meets the grown cell (i, j) when its x range over the rows
            // band [j - m, j + 1 + m] meets [i - m, i + 1 + m] (exact for a convex piece)
            const double inv = inverseResolution_;
            // most poses the table refuses lie inside an obstacle: their cell is occupied, and the footprint,
            // holding the origin, meets it (one bit, before any trigonometry)
            if (originInside_)
            {
                const double fx = (x - grid_.origin.x()) * inv, fy = (y - grid_.origin.y()) * inv;
                if (fx >= 0. && fy >= 0. && fx < grid_.width && fy < grid_.height &&
                    occupied(static_cast<int>(fx), static_cast<int>(fy)))
                    return false;
            }
            if (certainlyBlocked(x, y, yaw))
                return false;
            return footprintFree(x, y, yaw, margin);
        }

        bool HeadingTable::footprintFree(double x, double y, double yaw, double margin) const
        {
            // the polynomial subtracts k pi/2 without rounding while k stays below 2^20 (about 1.6e6 rad); a yaw of
            // 1e6 rad or more, from a caller that keeps no bounds, goes to the C library, which reduces any angle
            double s, c;
            if (std::abs(yaw) < 1e6)
                fastSinCos(yaw, s, c);
            else
            {
                s = std::sin(yaw);
                c = std::cos(yaw);
            }
            // cells beyond the grid may hold obstacles the grid does not know: a footprint reaching there is not free
            // (in table cells, whichever rows answer below; the 1e-9 turns a touch at round-off into a collision)
            const double inv = inverseResolution_;
            const double m = (margin + tolerance_) * inv + 1e-9;
            const double ox = (x - grid_.origin.x()) * inv, oy = (y - grid_.origin.y()) * inv;
            // most poses are further than the footprint's circle from the grid's edge: no corner to test
            const double r = circumradius_ * inv + m;
            if (!(ox - r >= 0. && oy - r >= 0. && ox + r < grid_.width && oy + r < grid_.height))
                for (const auto &piece : pieces_)
                    for (const auto &p : piece)
                    {
                        const double u = ox + (c * p.x() - s * p.y()) * inv, v = oy + (s * p.x() + c * p.y()) * inv;
                        if (u - m < 0. || v - m < 0. || u + m >= grid_.width || v + m >= grid_.height)
                            return false;
                    }
            // On a map whose cells are whole blocks of table cells the coarse rows hold the same obstacles in a
            // fraction of the memory, so the test reads a few lines that stay in the cache (checking.md).
            if (coarse_ > 1)
                return rowsFree(coarseCells_.data(), coarseWordsPerRow_, 1, coarseWidth_, coarseHeight_, inv / coarse_,
                                x, y, c, s, margin);
            return rowsFree(cells_.data() + 1, wordsPerRow_, 2, grid_.width, grid_.height, inv, x, y, c, s, margin);
        }

        bool HeadingTable::rowsFree(const std::uint64_t *occupied, std::size_t wordsPerRow, std::size_t stride,
                                    int width, int height, double inv, double x, double y, double c, double s,
                                    double margin) const
        {
            // The footprint grown by the caller's margin (a motion's spacing) and the table's tolerance, in cells of
            // these rows.
            const double m = (margin + tolerance_) * inv + 1e-9;
            const double ox = (x - grid_.origin.x()) * inv, oy = (y - grid_.origin.y()) * inv;
            double u[16], v[16];
            for (const auto &piece : pieces_)
            {
                const std::size_t n = std::min<std::size_t>(piece.size(), 16);
                double vmin = std::numeric_limits<double>::infinity(), vmax = -vmin;
                for (std::size_t p = 0; p < n; ++p)
                {
                    u[p] = ox + (c * piece[p].x() - s * piece[p].y()) * inv;
                    v[p] = oy + (s * piece[p].x() + c * piece[p].y()) * inv;
                    vmin = std::min(vmin, v[p]);
                    vmax = std::max(vmax, v[p]);
                }
                // Row j's grown band [j - m, j + 1 + m] meets [vmin, vmax] exactly for these j.
                const int j0 = ceilToInt(vmin - m - 1.), j1 = floorToInt(vmax + m);
                // each edge's x per unit of y and its y range, once (not a division per row)
                double slope[16], elo[16], ehi[16];
                for (std::size_t p = 0; p < n; ++p)
                {
                    const std::size_t q = p + 1 == n ? 0 : p + 1;
                    slope[p] = v[q] != v[p] ? (u[q] - u[p]) / (v[q] - v[p]) : 0.;
                    elo[p] = std::min(v[p], v[q]);
                    ehi[p] = std::max(v[p], v[q]);
                }
                for (int j = std::max(0, j0); j <= std::min(height - 1, j1); ++j)
                {
                    const double lo = j - m, hi = j + 1. + m;
                    // The piece's x range within the band: each edge clipped to the band (a vertex in the band is
                    // the end of an edge, a crossing of the band's line the end of a clipped one), without a branch
                    // per edge: which edges meet the band changes from pose to pose.
                    const double inf = std::numeric_limits<double>::infinity();
                    double xa = inf, xb = -inf;
                    for (std::size_t p = 0; p < n; ++p)
                    {
                        const double ya = std::max(elo[p], lo), yb = std::min(ehi[p], hi);
                        const double x0 = u[p] + slope[p] * (ya - v[p]), x1 = u[p] + slope[p] * (yb - v[p]);
                        const bool meets = ya <= yb;
                        xa = std::min(xa, meets ? std::min(x0, x1) : inf);
                        xb = std::max(xb, meets ? std::max(x0, x1) : -inf);
                    }
                    if (!(xa <= xb))
                        continue;
                    // The same for columns: cell i's grown span [i - m, i + 1 + m] meets the piece's x range [xa, xb].
                    const int i0 = std::max(0, ceilToInt(xa - m - 1.));
                    const int i1 = std::min(width - 1, floorToInt(xb + m));
                    const std::uint64_t *row = occupied + stride * static_cast<std::size_t>(j) * wordsPerRow;
                    for (int w = i0 >> 6; w <= i1 >> 6; ++w)
                    {
                        std::uint64_t mask = ~std::uint64_t{0};
                        if (w == i0 >> 6)
                            // Masks trim the first and last words to columns i0..i1; (i1 & 63) == 63 is special because
                            // a shift by 64 is undefined.
                            mask &= ~std::uint64_t{0} << (i0 & 63);
                        if (w == i1 >> 6 && (i1 & 63) != 63)
                            mask &= (std::uint64_t{1} << ((i1 & 63) + 1)) - 1;
                        if (row[stride * static_cast<std::size_t>(w)] & mask)
                            return false;
                    }
                }
            }
            return true;
        }

        void HeadingTable::makeCoarse()
        {
            // The largest block of f x f table cells (from cell 0, 0) in which every cell is occupied or every cell is
            // free, all over the grid: the map's own cells when the table splits them (GridValidityChecker aligns the
            // table to them). A block cut by the grid's edge counts by its cells inside.
            coarse_ = 1;
            coarseCells_.clear();
            const auto cell = [&](int i, int j)
            {
                return grid_.cells[static_cast<std::size_t>(j) * grid_.width + i] != 0;
            };
            for (int f : {8, 4, 2})
            {
                const int bw = (grid_.width + f - 1) / f, bh = (grid_.height + f - 1) / f;
                const std::size_t wpr = (static_cast<std::size_t>(bw) + 63) / 64;
                std::vector<std::uint64_t> bits(wpr * static_cast<std::size_t>(bh), 0);
                bool uniform = true;
                for (int bj = 0; bj < bh && uniform; ++bj)
                    for (int bi = 0; bi < bw && uniform; ++bi)
                    {
                        const bool first = cell(bi * f, bj * f);
                        for (int j = bj * f; j < std::min(grid_.height, bj * f + f) && uniform; ++j)
                            for (int i = bi * f; i < std::min(grid_.width, bi * f + f) && uniform; ++i)
                                uniform = cell(i, j) == first;
                        if (first)
                            bits[static_cast<std::size_t>(bj) * wpr + (bi >> 6)] |= std::uint64_t{1} << (bi & 63);
                    }
                if (!uniform)
                    continue;
                coarse_ = f;
                coarseWidth_ = bw;
                coarseHeight_ = bh;
                coarseWordsPerRow_ = wpr;
                coarseCells_ = std::move(bits);
                return;
            }
        }

        void HeadingTable::chooseExactFirst()
        {
            // rows of the exact test's bits (coarse_ table cells each) that the footprint's circle spans
            const double rows = 2. * circumradius_ * inverseResolution_ / coarse_;
            exactFirst_ = rows <= 2.;
            // On a large map the cell summary (two bits a table cell: 1 MiB on 64room) is a cache miss for most
            // fresh poses, while an exact test of at most two rows reads the coarse rows (a bit a map cell: 32 KiB
            // on 64room), which stay cached: there the exact test answers first. `michi verify-checker
            // problems/movingai_64room.yaml --checker grid --states 300000`, seeds 3-5, alternated: 32.5-35.3 ns a
            // query with the summary first, 27.5-30.2 ns without it; the same answers. A small map keeps the order
            // (arena's summary is 10 KiB).
            exactBeforeCells_ =
                exactFirst_ && coarse_ > 1 && cells_.size() * sizeof(std::uint64_t) > CELLS_CACHED_BYTES;
        }

        void HeadingTable::updateCoarse(const CellBox &changed)
        {
            // a change that splits a block ends the coarse rows (the table's own rows answer from then on)
            if (coarse_ <= 1 || changed.empty())
                return;
            const int f = coarse_;
            for (int bj = changed.j0 / f; bj <= changed.j1 / f; ++bj)
                for (int bi = changed.i0 / f; bi <= changed.i1 / f; ++bi)
                {
                    const bool first = grid_.cells[static_cast<std::size_t>(bj * f) * grid_.width + bi * f] != 0;
                    for (int j = bj * f; j < std::min(grid_.height, bj * f + f); ++j)
                        for (int i = bi * f; i < std::min(grid_.width, bi * f + f); ++i)
                            if ((grid_.cells[static_cast<std::size_t>(j) * grid_.width + i] != 0) != first)
                            {
                                coarse_ = 1;
                                coarseCells_.clear();
                                chooseExactFirst();
                                return;
                            }
                    std::uint64_t &word = coarseCells_[static_cast<std::size_t>(bj) * coarseWordsPerRow_ + (bi >> 6)];
                    const std::uint64_t bit = std::uint64_t{1} << (bi & 63);
                    word = first ? (word | bit) : (word & ~bit);
                }
        }

        void HeadingTable::buildBand()
        {
            band_ = BandTable(pieces_, grid_.resolution, headings_, tolerance_);
            computeBand(nullptr);
        }

        void HeadingTable::computeBand(const CellBox *box)
        {
            if (band_.empty())
                return;
            const std::size_t words = words_.size() / 2;
            // the occupancy as rows of words (BandTable::compute reads it so)
            std::vector<std::uint64_t> occupied(wordsPerRow_ * grid_.height);
            for (std::size_t w = 0; w < occupied.size(); ++w)
                occupied[w] = cells_[2 * w + 1];
            const int h = grid_.height;
            const std::uint64_t lastMask =
                (grid_.width & 63) ? (std::uint64_t{1} << (grid_.width & 63)) - 1 : ~std::uint64_t{0};
            std::vector<std::uint32_t> prefix(words + 1, 0);
            std::vector<BandTable::Entry> entries;
            entries.reserve(box ? band_.size() + band_.size() / 8 : 0);
            for (int k = 0; k < headings_; ++k)
                for (int j = 0; j < h; ++j)
                    for (std::size_t wc = 0; wc < wordsPerRow_; ++wc)
                    {
                        const std::size_t w = (static_cast<std::size_t>(k) * h + j) * wordsPerRow_ + wc;
                        if (entries.size() > std::numeric_limits<std::uint32_t>::max())
                            throw std::length_error("HeadingTable: too many band entries");
                        prefix[w] = static_cast<std::uint32_t>(entries.size());
                        const std::uint64_t mask = ~words_[2 * w] & ~words_[2 * w + 1] &
                                                   (wc + 1 == wordsPerRow_ ? lastMask : ~std::uint64_t{0});
                        // the entries of this word to compute (the others keep their sub-entries)
                        std::uint64_t fresh = ~std::uint64_t{0};
                        if (box)
                        {
                            fresh = 0;
                            const int c0 = static_cast<int>(wc) * 64;
                            if (j >= box->j0 && j <= box->j1 && box->i0 <= c0 + 63 && box->i1 >= c0)
                            {
                                const int a = std::max(box->i0, c0) - c0, b = std::min(box->i1, c0 + 63) - c0;
                                fresh = (b == 63 ? ~std::uint64_t{0} : (std::uint64_t{1} << (b + 1)) - 1) &
                                        ~((std::uint64_t{1} << a) - 1);
                            }
                        }
                        // old entries of this word: those outside the box are the same (before the box's columns,
                        // then after them)
                        const std::size_t oldStart = box ? band_.rank(w) : 0;
                        const std::size_t oldInBox =
                            box ? band_.rank(w + 1) - band_.rank(w) -
                                      static_cast<std::size_t>(__builtin_popcountll(mask & ~fresh))
                                : 0;
                        for (std::uint64_t bits = mask; bits; bits &= bits - 1)
                        {
                            const int t = __builtin_ctzll(bits);
                            if ((fresh >> t) & 1u)
                            {
                                entries.push_back(band_.compute(static_cast<int>(wc) * 64 + t, j, k, occupied.data(),
                                                                wordsPerRow_, grid_.width, h));
                                continue;
                            }
                            const std::uint64_t below = (std::uint64_t{1} << t) - 1;
                            std::size_t n =
                                oldStart + static_cast<std::size_t>(__builtin_popcountll(mask & ~fresh & below));
                            if (fresh & below)
                                n += oldInBox;  // past the box's columns
                            entries.push_back(band_.entry(n));
                        }
                    }
            prefix[words] = static_cast<std::uint32_t>(entries.size());
            band_.assign(std::move(prefix), entries);
        }

        bool HeadingTable::certainlyBlocked(double x, double y, double yaw) const
        {
            if (coreStamps_.empty())
                return false;
            const double fx = (x - grid_.origin.x()) * inverseResolution_;
            const double fy = (y - grid_.origin.y()) * inverseResolution_;
            if (!(fx >= 0. && fy >= 0. && fx < grid_.width && fy < grid_.height))
                return false;
            const int i = static_cast<int>(fx), j = static_cast<int>(fy);
            const int k = headingBin(yaw);
            const std::size_t word = (static_cast<std::size_t>(k) * grid_.height + j) * wordsPerRow_ + (i >> 6);
            return (words_[2 * word + 1] >> (i & 63)) & 1u;
        }

        void HeadingTable::makeCoreStamps()
        {
            coreStamps_.clear();
            if (pieces_.size() != 1)
                return;  // not convex: no core (freePose decides)
            const std::vector<Eigen::Vector2d> &hull = pieces_[0];
            const double r = grid_.resolution;
            // the same yaw samples as makeStamps; every yaw of the bin is within half a spacing of one, where a
            // point of the footprint moves at most sweep
            const int samples = std::max(1, static_cast<int>(std::ceil(step_ * circumradius_ / (0.1 * r))));
            const double sweep = circumradius_ * (step_ / samples) / 2. + tolerance_ + 1e-9 * (1. + circumradius_);
            // entry (i, j) holds positions u in [0, r)^2 of its cell; cell (i + dx, j + dy) minus u spans the
            // square [(dx - 1) r, (dx + 1) r] x [(dy - 1) r, (dy + 1) r]: inside the footprint (grown by sweep) at
            // every sample yaw, the footprint covers that cell whole from every pose of the entry
            const int n = static_cast<int>(std::ceil(circumradius_ / r)) + 1;
            coreStamps_.resize(headings_);
            for (int k = 0; k < headings_; ++k)
            {
                auto &stamp = coreStamps_[k];
                for (int dy = -n; dy <= n; ++dy)
                    for (int dx = -n; dx <= n; ++dx)
                    {
                        bool inside = true;
                        for (int s = 0; s < samples && inside; ++s)
                        {
                            const double yaw = k * step_ - step_ / 2. + (s + 0.5) * step_ / samples;
                            const Eigen::Rotation2Dd back(-yaw);  // the square in the footprint's frame
                            for (int c = 0; c < 4 && inside; ++c)
                            {
                                const Eigen::Vector2d corner(
                                    (dx + ((c & 1) ? 1. : -1.)) * r + ((c & 1) ? sweep : -sweep),
                                    (dy + ((c & 2) ? 1. : -1.)) * r + ((c & 2) ? sweep : -sweep));
                                const Eigen::Vector2d q = back * corner;
                                // strictly inside every edge of the counter-clockwise hull
                                for (std::size_t e = 0; e < hull.size() && inside; ++e)
                                    inside = cross(hull[e], hull[(e + 1) % hull.size()], q) > 0.;
                            }
                        }
                        if (!inside)
                            continue;
                        if (!stamp.empty() && stamp.back().dy == dy && stamp.back().x1 == dx - 1)
                            stamp.back().x1 = dx;
                        else
                            stamp.push_back(GridSpan{dy, dx, dx});
                    }
            }
        }

        int HeadingTable::headingBin(double yaw) const
        {
            // Nearest bin centre; fmod then maps any number of turns (and negative yaws) into 0..headings_-1.
            const double b = std::floor(yaw / step_ + 0.5);
            if (!std::isfinite(b))
                return 0;
            long long k = static_cast<long long>(std::fmod(b, static_cast<double>(headings_)));
            if (k < 0)
                k += headings_;
            return static_cast<int>(k);
        }

        void HeadingTable::makeStamps(const std::vector<Eigen::Vector2d> &footprint, double tolerance)
        {
            const double r = grid_.resolution;
            // convex pieces of the footprint: triangles (any simple polygon)
            std::vector<std::array<Eigen::Vector2d, 3>> triangles;
            for (const auto &t : triangulatePolygon(footprint))
                triangles.push_back({footprint[t[0]], footprint[t[1]], footprint[t[2]]});
            // samples of the bin so that a footprint point moves at most 0.05 cells between one and the next
            const int samples = std::max(1, static_cast<int>(std::ceil(step_ * circumradius_ / (0.1 * r))));
            const double sweep = circumradius_ * (step_ / samples) / 2.;  // >= 2 R sin(step / (4 samples))
            // Grown by a whole cell: half for the robot's pose anywhere in its entry's cell, half for the obstacle
            // anywhere in its cell (checking.md). sweep covers the yaws between samples, so every pose of the entry and
            // bin is inside.
            const double grow = r + sweep + tolerance + 1e-9 * (1. + circumradius_);
            reach_[0] = reach_[2] = std::numeric_limits<int>::max();
            reach_[1] = reach_[3] = std::numeric_limits<int>::min();
            stamps_.resize(headings_);
            for (int k = 0; k < headings_; ++k)
            {
                std::map<int, std::vector<std::pair<int, int>>> rows;
                for (int s = 0; s < samples; ++s)
                {
                    const double yaw = k * step_ - step_ / 2. + (s + 0.5) * step_ / samples;
                    const Eigen::Rotation2Dd rot(yaw);
                    for (const auto &t : triangles)
                    {
                        std::vector<Eigen::Vector2d> points;
                        for (const auto &v : t)
                        {
                            const Eigen::Vector2d w = rot * v;
                            for (double sx : {-grow, grow})
                                for (double sy : {-grow, grow})
                                    points.emplace_back(w.x() + sx, w.y() + sy);
                        }
                        const auto hull = convexHull(points);
                        double ymin = hull[0].y(), ymax = ymin;
                        for (const auto &h : hull)
                        {
                            ymin = std::min(ymin, h.y());
                            ymax = std::max(ymax, h.y());
                        }
                        for (int dy = static_cast<int>(std::ceil(ymin / r - 1e-9));
                             dy <= static_cast<int>(std::floor(ymax / r + 1e-9)); ++dy)
                        {
                            double xa = 0., xb = 0.;
                            // the line through the row's cell centres, clamped into the hull's y range
                            const double c = std::min(ymax, std::max(ymin, dy * r));
                            if (!rowInterval(hull, c, xa, xb))
                                continue;
                            // Lattice offsets inside the grown piece, with 1e-9 of slack so a point on its border
                            // blocks (conservative).
                            const int x0 = static_cast<int>(std::ceil(xa / r - 1e-9));
                            const int x1 = static_cast<int>(std::floor(xb / r + 1e-9));
                            if (x0 <= x1)
                                rows[dy].emplace_back(x0, x1);
                        }
                    }
                }
                auto &stamp = stamps_[k];
                for (auto &row : rows)
                {
                    auto &iv = row.second;
                    // Offsets from every sample and triangle, merged into disjoint spans per row: computeRegion() then
                    // tests each span once.
                    std::sort(iv.begin(), iv.end());
                    for (const auto &v : iv)
                        if (!stamp.empty() && stamp.back().dy == row.first && v.first <= stamp.back().x1 + 1)
                            stamp.back().x1 = std::max(stamp.back().x1, v.second);
                        else
                            stamp.push_back(GridSpan{row.first, v.first, v.second});
                }
                for (const auto &span : stamp)
                {
                    reach_[0] = std::min(reach_[0], span.x0);
                    reach_[1] = std::max(reach_[1], span.x1);
                    reach_[2] = std::min(reach_[2], span.dy);
                    reach_[3] = std::max(reach_[3], span.dy);
                }
            }
        }

        void HeadingTable::computeRegion(const CellBox &box)
        {
            if (box.empty())
                return;
            const int w = grid_.width, h = grid_.height;
            const int n = box.i1 - box.i0 + 1;
            std::vector<std::uint8_t> blocked(static_cast<std::size_t>(n));
            // running counts of occupied cells of the rows the box's stamps read (only while computing)
            const int r0 = std::max(0, box.j0 + reach_[2]), r1 = std::min(h - 1, box.j1 + reach_[3]);
            std::vector<std::int32_t> prefix(static_cast<std::size_t>(std::max(0, r1 - r0 + 1)) * (w + 1), 0);
            for (int j = r0; j <= r1; ++j)
            {
                std::int32_t *p = prefix.data() + static_cast<std::size_t>(j - r0) * (w + 1);
                const std::uint8_t *c = grid_.cells.data() + static_cast<std::size_t>(j) * w;
                // Prefix sums per row: "is any cell of [a, b) occupied" becomes p[b] > p[a], one comparison per stamp
                // span.
                for (int i = 0; i < w; ++i)
                    p[i + 1] = p[i] + (c[i] ? 1 : 0);
            }
            for (int k = 0; k < headings_; ++k)
                for (int j = box.j0; j <= box.j1; ++j)
                {
                    std::fill(blocked.begin(), blocked.end(), 0);
                    for (const auto &span : stamps_[k])
                    {
                        const int jj = j + span.dy;
                        if (jj < 0 || jj >= h)
                            continue;
                        const std::int32_t *p = prefix.data() + static_cast<std::size_t>(jj - r0) * (w + 1);
                        if (p[w] == 0)
                            continue;  // an empty row blocks nothing
                        for (int t = 0; t < n; ++t)
                        {
                            const int i = box.i0 + t;
                            const int a = std::min(w, std::max(0, i + span.x0));
                            const int b = std::min(w, std::max(0, i + span.x1 + 1));
                            blocked[t] |= static_cast<std::uint8_t>(p[b] > p[a]);
                        }
                    }
                    std::uint64_t *row = words_.data() + 2 * (static_cast<std::size_t>(k) * h + j) * wordsPerRow_;
                    for (int t = 0; t < n; ++t)
                    {
                        const int i = box.i0 + t;
                        const std::uint64_t bit = std::uint64_t{1} << (i & 63);
                        if (blocked[t])
                            row[2 * (i >> 6)] &= ~bit;
                        else
                            row[2 * (i >> 6)] |= bit;
                    }
                    if (coreStamps_.empty())
                        continue;
                    // the same with the core stamp: an occupied cell in it blocks every pose of the entry
                    std::fill(blocked.begin(), blocked.end(), 0);
                    for (const auto &span : coreStamps_[k])
                    {
                        const int jj = j + span.dy;
                        if (jj < r0 || jj > r1)
                            continue;
                        const std::int32_t *p = prefix.data() + static_cast<std::size_t>(jj - r0) * (w + 1);
                        if (p[w] == 0)
                            continue;
                        for (int t = 0; t < n; ++t)
                        {
                            const int i = box.i0 + t;
                            const int a = std::min(w, std::max(0, i + span.x0));
                            const int b = std::min(w, std::max(0, i + span.x1 + 1));
                            blocked[t] |= static_cast<std::uint8_t>(p[b] > p[a]);
                        }
                    }
                    std::uint64_t *core = row + 1;
                    for (int t = 0; t < n; ++t)
                    {
                        const int i = box.i0 + t;
                        const std::uint64_t bit = std::uint64_t{1} << (i & 63);
                        if (blocked[t])
                            core[2 * (i >> 6)] |= bit;
                        else
                            core[2 * (i >> 6)] &= ~bit;
                    }
                }
            summarise(box);
        }

        CellBox HeadingTable::affected(const CellBox &changed) const
        {
            // entry (i, j) reads cell (i + dx, j + dy): a changed cell c affects entries c - (dx, dy)
            CellBox box;
            if (changed.empty())
                return box;
            // reach_ is the bounding box of every heading's stamp (x0, x1, dy min, dy max), so this box holds every
            // entry whose stamp can touch a changed cell.
            box.i0 = std::max(0, changed.i0 - reach_[1]);
            box.i1 = std::min(grid_.width - 1, changed.i1 - reach_[0]);
            box.j0 = std::max(0, changed.j0 - reach_[3]);
            box.j1 = std::min(grid_.height - 1, changed.j1 - reach_[2]);
            return box;
        }

        CellBox HeadingTable::setOccupied(const std::vector<std::pair<int, int>> &cells, bool occupied)
        {
            CellBox changed{std::numeric_limits<int>::max(), std::numeric_limits<int>::min(),
                            std::numeric_limits<int>::max(), std::numeric_limits<int>::min()};
            for (const auto &c : cells)
            {
                if (!grid_.inside(c.first, c.second))
                    continue;
                auto &cell = grid_.cells[static_cast<std::size_t>(c.second) * grid_.width + c.first];
                if ((cell != 0) == occupied)
                    continue;
                cell = occupied ? 1 : 0;
                std::uint64_t &bits =
                    cells_[2 * (static_cast<std::size_t>(c.second) * wordsPerRow_ + (c.first >> 6)) + 1];
                const std::uint64_t bit = std::uint64_t{1} << (c.first & 63);
                bits = occupied ? (bits | bit) : (bits & ~bit);
                changed.i0 = std::min(changed.i0, c.first);
                changed.i1 = std::max(changed.i1, c.first);
                changed.j0 = std::min(changed.j0, c.second);
                changed.j1 = std::max(changed.j1, c.second);
            }
            if (changed.empty())
                return CellBox{};
            updateCoarse(changed);
            const CellBox box = affected(changed);
            computeRegion(box);
            if (!band_.empty())
            {
                // the band's entries read cells within its own reach (and change where the table's do)
                const int *reach = band_.reach();
                CellBox b{std::max(0, changed.i0 - reach[1]), std::min(grid_.width - 1, changed.i1 - reach[0]),
                          std::max(0, changed.j0 - reach[3]), std::min(grid_.height - 1, changed.j1 - reach[2])};
                b = CellBox{std::min(b.i0, box.i0), std::max(b.i1, box.i1), std::min(b.j0, box.j0),
                            std::max(b.j1, box.j1)};
                computeBand(&b);
            }
            return box;
        }

        CellBox HeadingTable::update(const OccupancyGrid &grid)
        {
            if (grid.width != grid_.width || grid.height != grid_.height || grid.resolution != grid_.resolution ||
                grid.origin != grid_.origin || grid.cells.size() != grid_.cells.size())
                throw std::invalid_argument("HeadingTable::update: the grid's size, resolution or origin differs");
            std::vector<std::pair<int, int>> on, off;
            for (int j = 0; j < grid.height; ++j)
                for (int i = 0; i < grid.width; ++i)
                {
                    const std::size_t c = static_cast<std::size_t>(j) * grid.width + i;
                    if ((grid.cells[c] != 0) != (grid_.cells[c] != 0))
                        (grid.cells[c] ? on : off).emplace_back(i, j);
                }
            // The union of both boxes holds every entry that may have changed; refresh() hands it to its caller.
            CellBox a = setOccupied(on, true), b = setOccupied(off, false);
            if (a.empty())
                return b;
            if (b.empty())
                return a;
            return CellBox{std::min(a.i0, b.i0), std::max(a.i1, b.i1), std::min(a.j0, b.j0), std::max(a.j1, b.j1)};
        }

        std::size_t HeadingTable::validCount() const
        {
            std::size_t n = 0;
            for (std::size_t w = 0; w < words_.size(); w += 2)
                n += static_cast<std::size_t>(__builtin_popcountll(words_[w]));
            return n;
        }

        std::size_t HeadingTable::bytes() const
        {
            return (words_.size() + blocks_.size() + blockAllInvalid_.size() + supers_.size() + cells_.size() +
                    cellAllInvalid_.size() + coarseCells_.size()) *
                       sizeof(std::uint64_t) +
                   grid_.cells.size() + band_.bytes();
        }
    }  // namespace validity
}  // namespace michi
