#include "SelfPairTable.h"

#include "../FastRound.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace michi
{
    namespace validity
    {
        SelfPairTable::SelfPairTable(std::vector<int> variables, std::vector<double> lo, std::vector<double> hi,
                                     std::vector<char> wrap, std::vector<double> closing, int cellsPerVariable,
                                     const std::function<double(const double *)> &distance)
            : variables_(std::move(variables))
        {
            shape(lo, hi, wrap, closing, cellsPerVariable);
            fill(0, n_[0], 0, n_[1], distance);
        }

        SelfPairTable::SelfPairTable(std::vector<int> variables, std::vector<double> lo, std::vector<double> hi,
                                     std::vector<char> wrap, std::vector<double> closing, int cellsPerVariable,
                                     std::vector<std::uint64_t> bits)
            : variables_(std::move(variables))
        {
            shape(lo, hi, wrap, closing, cellsPerVariable);
            if (bits.size() != bits_.size())
                throw std::invalid_argument("SelfPairTable: stored bits do not fit the table");
            bits_ = std::move(bits);
        }

        void SelfPairTable::shape(const std::vector<double> &lo, const std::vector<double> &hi,
                                  const std::vector<char> &wrap, const std::vector<double> &closing,
                                  int cellsPerVariable)
        {
            if (variables_.empty() || variables_.size() > 2 || lo.size() != variables_.size() ||
                hi.size() != variables_.size() || wrap.size() != variables_.size() ||
                closing.size() != variables_.size() || cellsPerVariable < 1)
                throw std::invalid_argument("SelfPairTable: one or two variables with a range each");
            for (std::size_t d = 0; d < variables_.size(); ++d)
            {
                if (!(hi[d] > lo[d]) || !std::isfinite(hi[d] - lo[d]))
                    throw std::invalid_argument("SelfPairTable: empty or unbounded range");
                n_[d] = cellsPerVariable;
                lo_[d] = lo[d];
                h_[d] = (hi[d] - lo[d]) / cellsPerVariable;
                wrap_[d] = wrap[d] != 0;
                closing_[d] = closing[d];
            }
            const std::size_t cells = static_cast<std::size_t>(n_[0]) * static_cast<std::size_t>(n_[1]);
            bits_.assign((cells + 63) / 64, 0);
        }

        void SelfPairTable::fill(int i0, int i1, int j0, int j1, const std::function<double(const double *)> &distance)
        {
            // the box's centre, and how far the bodies can close in from there to any point of the box
            const double centre[2] = {lo_[0] + 0.5 * (i0 + i1) * h_[0], lo_[1] + 0.5 * (j0 + j1) * h_[1]};
            const double reach =
                // Grown a little against rounding in the bound and in FCL's distance.
                (closing_[0] * 0.5 * (i1 - i0) * h_[0] + closing_[1] * 0.5 * (j1 - j0) * h_[1]) * (1. + 1e-6) + 1e-7;
            ++evaluations_;
            const double d = distance(centre);
            // Distance at the centre beats how far the two bodies can close in on the way to any point of the box: the
            // whole box is free, proved by this one FCL distance (the table's bits are proofs, never samples).
            if (d > reach)
            {
                for (int j = j0; j < j1; ++j)
                    for (int i = i0; i < i1; ++i)
                    {
                        const std::size_t k =
                            static_cast<std::size_t>(j) * static_cast<std::size_t>(n_[0]) + static_cast<std::size_t>(i);
                        bits_[k >> 6] |= std::uint64_t{1} << (k & 63);
                    }
                return;
            }
            if (i1 - i0 == 1 && j1 - j0 == 1)
                return;  // the finest cell: not shown free
            // a box in contact at its centre is split all the same: its corners may be free
            const int im = i1 - i0 > 1 ? (i0 + i1) / 2 : i1, jm = j1 - j0 > 1 ? (j0 + j1) / 2 : j1;
            fill(i0, im, j0, jm, distance);
            if (im < i1)
                fill(im, i1, j0, jm, distance);
            if (jm < j1)
            {
                fill(i0, im, jm, j1, distance);
                if (im < i1)
                    fill(im, i1, jm, j1, distance);
            }
        }

        bool SelfPairTable::range(int d, double v, double s, int &first, int &last) const
        {
            if (!std::isfinite(v) || !std::isfinite(s))
                return false;
            if (wrap_[d])
            {
                const double period = h_[d] * n_[d];
                // Into [lo, lo + period): fmod keeps the sign of its argument, so a second fmod after adding a period.
                v = lo_[d] + std::fmod(std::fmod(v - lo_[d], period) + period, period);
            }
            // cells are closed boxes, so the cell a value's floor names covers it even on a boundary
            const double a = (v - s - lo_[d]) / h_[d], b = (v + s - lo_[d]) / h_[d];
            if (!wrap_[d] && (a < -1e-9 || b > n_[d] + 1e-9))
                return false;  // outside the joint's range: not certified
            first = floorToInt(a);
            last = floorToInt(b);
            if (wrap_[d])
            {
                // A span of a whole turn or more touches every cell: read them all once.
                if (last - first + 1 >= n_[d])
                {
                    first = 0;
                    last = n_[d] - 1;
                }
                return true;
            }
            first = std::max(first, 0);
            last = std::min(last, n_[d] - 1);
            return true;
        }

        bool SelfPairTable::freeWithin(const double *values, double span0, double span1) const
        {
            int i0, i1, j0 = 0, j1 = 0;
            if (!range(0, values[variables_[0]], span0, i0, i1))
                return false;
            if (variables_.size() == 2 && !range(1, values[variables_[1]], span1, j0, j1))
                return false;
            // Indices may run past the ends of a continuous joint's range: they wrap. Each row's run of cells is
            // read as whole 64-bit words under a mask, so a motion's wide span costs a few words per row, not one
            // read per cell. Integer remainders only where a joint wraps: a motion's piece reads a dozen rows or more,
            // and two divisions per row were a tenth of RRTConnect's solve with spheres on the Panda (no wrapping
            // joint there).
            auto wrapped = [](int i, int n)
            {
                const int r = i % n;
                return r < 0 ? r + n : r;
            };
            for (int j = j0; j <= j1; ++j)
            {
                const int jw = wrap_[1] ? wrapped(j, n_[1]) : j;
                const std::size_t row = static_cast<std::size_t>(jw) * static_cast<std::size_t>(n_[0]);
                if (!wrap_[0])
                {
                    // range() clamped i0..i1 into the row
                    if (!allSet(row + static_cast<std::size_t>(i0), static_cast<std::size_t>(i1 - i0 + 1)))
                        return false;
                    continue;
                }
                for (int i = i0; i <= i1;)
                {
                    const int iw = wrapped(i, n_[0]);
                    // the run from this cell to the last wanted one or the end of the row, whichever comes first
                    const int run = std::min(i1 - i, n_[0] - 1 - iw) + 1;
                    if (!allSet(row + static_cast<std::size_t>(iw), static_cast<std::size_t>(run)))
                        return false;
                    i += run;
                }
            }
            return true;
        }

        bool SelfPairTable::cellOf(const double *values, std::size_t &k) const
        {
            // A state reads one cell: the index straight from the value (the span-0 case of range(), without its
            // fmod calls, which a state check on every wrist pair felt).
            k = 0;
            std::size_t stride = 1;
            for (std::size_t d = 0; d < variables_.size(); ++d)
            {
                double a = (values[variables_[d]] - lo_[d]) / h_[d];
                if (!std::isfinite(a))
                    return false;
                if (wrap_[d])
                    a -= n_[d] * std::floor(a / n_[d]);  // into [0, n): a whole turn is n cells
                else if (a < -1e-9 || a > n_[d] + 1e-9)
                    return false;  // outside the joint's range: not certified
                // a >= -1e-9 here: truncation is the floor, except for the tiny negatives the clamp takes to 0
                const int i = std::min(std::max(static_cast<int>(a), 0), n_[d] - 1);
                k += static_cast<std::size_t>(i) * stride;
                stride *= static_cast<std::size_t>(n_[d]);
            }
            return true;
        }

        bool SelfPairTable::free(const double *values) const
        {
            std::size_t k = 0;
            return cellOf(values, k) && cellFree(k);
        }

        bool SelfPairTable::freeOver(const double *values, const float *span) const
        {
            return freeWithin(values, span[variables_[0]], variables_.size() == 2 ? span[variables_[1]] : 0.);
        }

        double SelfPairTable::freeFraction() const
        {
            std::size_t set = 0;
            for (std::uint64_t w : bits_)
                set += static_cast<std::size_t>(__builtin_popcountll(w));
            return static_cast<double>(set) / (static_cast<double>(n_[0]) * n_[1]);
        }
    }  // namespace validity
}  // namespace michi
