#ifndef MICHI_PLANNERS_HEADING_LATTICE_PAGED_ARRAY_
#define MICHI_PLANNERS_HEADING_LATTICE_PAGED_ARRAY_

// A helper of HeadingLattice. A lattice over a large map has tens of millions of node ids (64room at
// 0.05 m: 17 million) of which a query touches a few hundred thousand; flat arrays of them cost more to allocate,
// fill and page in than the search itself. A PagedArray is such an array made of pages of 4096 entries, each
// allocated and filled the first time it is written, so memory and reset time follow what the search touched.

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

namespace michi
{
    namespace planners
    {
        template <typename T, unsigned int PAGE_BITS = 12>
        class PagedArray
        {
        public:
            static constexpr std::size_t PAGE = std::size_t{1} << PAGE_BITS;

            /** \brief \e size entries, all \e fill; frees every page. */
            void assign(std::size_t size, T fill)
            {
                pages_.clear();
                pages_.resize((size + PAGE - 1) / PAGE);
                size_ = size;
                fill_ = fill;
            }
            /** \brief No entries, no pages. */
            void release()
            {
                std::vector<std::unique_ptr<T[]>>().swap(pages_);
                size_ = 0;
            }
            std::size_t size() const
            {
                return size_;
            }
            /** \brief Entry \e i for writing (its page made on first use). */
            T &operator[](std::size_t i)
            {
                std::unique_ptr<T[]> &page = pages_[i >> PAGE_BITS];
                if (!page)
                {
                    page.reset(new T[PAGE]);
                    std::fill_n(page.get(), PAGE, fill_);
                }
                return page[i & (PAGE - 1)];
            }
            /** \brief Entry \e i for reading (no page made). */
            T get(std::size_t i) const
            {
                const std::unique_ptr<T[]> &page = pages_[i >> PAGE_BITS];
                return page ? page[i & (PAGE - 1)] : fill_;
            }
            /** \brief Is entry \e i on a page made so far (else it holds the fill value)? */
            bool touched(std::size_t i) const
            {
                return static_cast<bool>(pages_[i >> PAGE_BITS]);
            }
            /** \brief Call f(first index, entries) for every page made, in order. */
            template <typename F>
            void forEachPage(F &&f)
            {
                for (std::size_t p = 0; p < pages_.size(); ++p)
                    if (pages_[p])
                        f(p * PAGE, pages_[p].get());
            }

            template <typename F>
            void forEachPage(F &&f) const
            {
                for (std::size_t p = 0; p < pages_.size(); ++p)
                    if (pages_[p])
                        f(p * PAGE, static_cast<const T *>(pages_[p].get()));
            }

        private:
            std::vector<std::unique_ptr<T[]>> pages_;
            std::size_t size_{0};
            T fill_{};
        };
    }  // namespace planners
}  // namespace michi

#endif
