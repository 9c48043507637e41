#ifndef MICHI_PLANNERS_SRC_HEADING_LATTICE_COMMON_
#define MICHI_PLANNERS_SRC_HEADING_LATTICE_COMMON_

// Private to HeadingLattice.cpp and HeadingLatticeSearch.cpp (not installed): constants both halves share.

#include <michi/state_spaces/Angles.h>

#include <boost/math/constants/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <vector>
#include <cstdint>
#include <limits>

namespace michi
{
    namespace planners
    {
        namespace
        {
            const double PI = boost::math::constants::pi<double>();
            const double INF = std::numeric_limits<double>::infinity();
            /** Node and edge states: unchecked, valid, invalid, and stale (checked once, forgotten by a scene change).
             */
            constexpr std::uint8_t UNCHECKED = 0, VALID = 1, INVALID = 2, STALE = 3;
            /** The most an 8-connected grid path exceeds a straight lattice drive it follows, per metre: the
                2-D heuristic is divided by it, so it stays a lower bound (see docs/heading-lattice.md). */
            const double OCTILE_EXCESS = std::sqrt(4. - 2. * std::sqrt(2.));

            using state_spaces::wrapAngle;

            /** The 2-D heuristic's open entries: priority and group in one integer, ordered as the pair (priority
                first, then the group). A priority is never negative, and a non-negative float's bits order as its
                value, so the heap compares integers: its child choice compiles to a conditional move instead of a
                branch that mispredicts half the time (the sift-down was half of the 2-D search's time, perf). */
            inline std::uint64_t groupKey(float priority, std::uint32_t group)
            {
                std::uint32_t bits;
                std::memcpy(&bits, &priority, sizeof bits);
                return (static_cast<std::uint64_t>(bits) << 32) | group;
            }
            inline float keyPriority(std::uint64_t key)
            {
                const auto bits = static_cast<std::uint32_t>(key >> 32);
                float priority;
                std::memcpy(&priority, &bits, sizeof priority);
                return priority;
            }
            inline std::uint32_t keyGroup(std::uint64_t key)
            {
                return static_cast<std::uint32_t>(key);
            }
            // A min-heap of keys in a vector: the same layout and moves as std::push_heap / std::pop_heap with
            // std::greater, so the 2-D search closes the same groups in the same order as with them
            // (tests/heading_lattice/test_heading_lattice_heap.cpp).
            /** Put \e key in the heap's \e hole, moving larger parents down. */
            inline void keyHeapRise(std::vector<std::uint64_t> &heap, std::size_t hole, std::uint64_t key)
            {
                while (hole > 0)
                {
                    const std::size_t parent = (hole - 1) / 2;
                    if (heap[parent] <= key)
                        break;
                    heap[hole] = heap[parent];
                    hole = parent;
                }
                heap[hole] = key;
            }
            inline void keyHeapPush(std::vector<std::uint64_t> &heap, std::uint64_t key)
            {
                heap.push_back(key);
                keyHeapRise(heap, heap.size() - 1, key);
            }
            inline std::uint64_t keyHeapPop(std::vector<std::uint64_t> &heap)
            {
                // The hole at the top goes down along the smaller children to a leaf, then the last key rises from
                // there (Floyd): one comparison per level on the way down, and the child is chosen without a branch.
                const std::uint64_t top = heap.front(), last = heap.back();
                heap.pop_back();
                const std::size_t n = heap.size();
                if (n == 0)
                    return top;
                std::size_t hole = 0;
                for (std::size_t child = 1; child < n; child = 2 * hole + 1)
                {
                    if (child + 1 < n)
                        child += heap[child + 1] <= heap[child] ? 1 : 0;
                    heap[hole] = heap[child];
                    hole = child;
                }
                keyHeapRise(heap, hole, last);
                return top;
            }
            inline void keyHeapMake(std::vector<std::uint64_t> &heap)
            {
                std::make_heap(heap.begin(), heap.end(), std::greater<std::uint64_t>());
            }
            inline bool heapLess(float fa, float ga, float fb, float gb)
            {
                // std heaps are max-heaps: "less" = lower priority; smaller f first, then larger g (deeper)
                return fa > fb || (fa == fb && ga < gb);
            }
        }  // namespace
    }      // namespace planners
}  // namespace michi

#endif
