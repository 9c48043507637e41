#ifndef MICHI_VALIDITY_SPHERES_SELF_PAIR_TABLE_
#define MICHI_VALIDITY_SPHERES_SELF_PAIR_TABLE_

// Internal to the sphere checker: certified self-collision tables for link pairs whose relative pose depends on
// one or two of the group's joint values (a wrist: panda_link5 against panda_link7 and the hand depend on joints 6
// and 7 only). Such links sit close by construction, so their enclosing spheres overlap in most states; a table
// over those joint values, built once with FCL on the real geometry, answers instead of the spheres.

#include <michi/validity/fcl/FclValidityChecker.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief One self-check pair's table over one or two group values. Cell c covers the closed box
            [lo + c h, lo + (c + 1) h] of the values; its bit is set only when FCL showed the pair apart over the
            whole box: the distance at the box's centre exceeds how far the two bodies can close in while the
            values move to the box's corners (the displacement bounds per unit of value). Values outside the
            range (or not finite) read as blocked. Immutable once built. */
        class SelfPairTable
        {
        public:
            /** \param variables group indices (1 or 2) the pair's relative pose depends on
                \param lo, hi, wrap the range of each variable; wrap: continuous joint (values taken modulo 2 pi)
                \param closing how fast the two bodies can close in per unit of each variable (metres per unit)
                \param distance FCL's distance between the pair's bodies for given values of the variables */
            SelfPairTable(std::vector<int> variables, std::vector<double> lo, std::vector<double> hi,
                          std::vector<char> wrap, std::vector<double> closing, int cellsPerVariable,
                          const std::function<double(const double *)> &distance);

            /** \brief A table whose cells were certified before (the bits of bits() of a table built with the same
                arguments, read back from the cache); throws std::invalid_argument when the size does not fit. */
            SelfPairTable(std::vector<int> variables, std::vector<double> lo, std::vector<double> hi,
                          std::vector<char> wrap, std::vector<double> closing, int cellsPerVariable,
                          std::vector<std::uint64_t> bits);
            const std::vector<std::uint64_t> &bits() const
            {
                return bits_;
            }

            /** \brief Is the pair certainly apart at group values \e values? */
            bool free(const double *values) const;
            /** \brief free() in two steps, for a caller that starts the load early (a table is 128 KiB, and on
                fresh states its word is a cache miss the rest of a state check can hide): the flat index of the
                cell of \e values (false when outside the table: not certified), ... */
            bool cellOf(const double *values, std::size_t &k) const;
            /** \brief ... the address of its word, to prefetch, and its bit. */
            const std::uint64_t *wordOf(std::size_t k) const
            {
                return &bits_[k >> 6];
            }
            bool cellFree(std::size_t k) const
            {
                return (bits_[k >> 6] >> (k & 63)) & 1u;
            }
            /** \brief Is it apart for every value within \e span[v] of values[v] (group indices)? */
            bool freeOver(const double *values, const float *span) const;
            /** \brief FCL distance queries the build made. */
            std::size_t evaluations() const
            {
                return evaluations_;
            }
            const std::vector<int> &variables() const
            {
                return variables_;
            }
            /** \brief Fraction of cells certified free. */
            double freeFraction() const;

        private:
            /** Index range [first, last] of the cells meeting [v - s, v + s] of variable d; false when outside. */
            bool range(int d, double v, double s, int &first, int &last) const;
            bool freeWithin(const double *values, double span0, double span1) const;
            /** Are the \e count cells from flat index \e first on (one row) all set? Inline: a motion's piece reads a
                dozen rows or more per table, and each was a call through the library's PLT. */
            bool allSet(std::size_t first, std::size_t count) const
            {
                while (count > 0)
                {
                    const std::size_t word = first >> 6, bit = first & 63,
                                      take = std::min<std::size_t>(64 - bit, count);
                    const std::uint64_t mask = (take == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << take) - 1))
                                               << bit;
                    if ((bits_[word] & mask) != mask)
                        return false;
                    first += take;
                    count -= take;
                }
                return true;
            }
            /** The ranges and cell sizes; bits_ sized, empty. */
            void shape(const std::vector<double> &lo, const std::vector<double> &hi, const std::vector<char> &wrap,
                       const std::vector<double> &closing, int cellsPerVariable);
            void fill(int i0, int i1, int j0, int j1, const std::function<double(const double *)> &distance);

            std::vector<int> variables_;
            double lo_[2]{0., 0.}, h_[2]{1., 1.};
            int n_[2]{1, 1};
            bool wrap_[2]{false, false};
            double closing_[2]{0., 0.};
            std::vector<std::uint64_t> bits_;
            std::size_t evaluations_{0};
        };
    }  // namespace validity
}  // namespace michi

#endif
