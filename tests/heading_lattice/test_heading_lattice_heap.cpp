// The 2-D heuristic's open list of HeadingLattice (planners/src/heading_lattice/HeadingLatticeCommon.h): keys that
// order as (priority, group) pairs, and a heap that makes the same moves as std::push_heap / std::pop_heap with
// std::greater, so the search closes the same groups in the same order as it did with them.
#include "../../planners/src/heading_lattice/HeadingLatticeCommon.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

using namespace michi::planners;

TEST(HeadingLatticeHeap, KeysOrderAsPriorityThenGroup)
{
    const std::vector<float> priorities{
        0.f, std::numeric_limits<float>::denorm_min(), 1e-30f, 0.05f, 0.0500001f, 1.f, 1.0000001f, 17.25f, 3.4e38f};
    const std::vector<std::uint32_t> groups{0u, 1u, 7u, 1048575u, 0xffffffffu};
    for (float pa : priorities)
        for (float pb : priorities)
            for (std::uint32_t ga : groups)
                for (std::uint32_t gb : groups)
                {
                    const bool pairLess = std::make_tuple(pa, ga) < std::make_tuple(pb, gb);
                    EXPECT_EQ(groupKey(pa, ga) < groupKey(pb, gb), pairLess)
                        << pa << " " << ga << " " << pb << " " << gb;
                }
    for (float p : priorities)
        for (std::uint32_t g : groups)
        {
            EXPECT_EQ(keyPriority(groupKey(p, g)), p);
            EXPECT_EQ(keyGroup(groupKey(p, g)), g);
        }
}

TEST(HeadingLatticeHeap, MovesAsTheStandardHeap)
{
    // pushes and pops interleaved, with repeated keys (a group pushed again after aimHeuristic() re-keys the heap):
    // after every operation the vector is the one std::push_heap / std::pop_heap leave, so ties come out alike too
    std::mt19937 random(7);
    std::uniform_int_distribution<int> priority(0, 40), group(0, 30), action(0, 2);
    std::vector<std::uint64_t> ours, theirs;
    std::size_t pops = 0;
    for (int step = 0; step < 20000; ++step)
    {
        if (action(random) != 0 || ours.empty())
        {
            const std::uint64_t key =
                groupKey(0.25f * static_cast<float>(priority(random)), static_cast<std::uint32_t>(group(random)));
            keyHeapPush(ours, key);
            theirs.push_back(key);
            std::push_heap(theirs.begin(), theirs.end(), std::greater<std::uint64_t>());
        }
        else
        {
            const std::uint64_t top = keyHeapPop(ours);
            std::pop_heap(theirs.begin(), theirs.end(), std::greater<std::uint64_t>());
            ASSERT_EQ(top, theirs.back()) << "step " << step;
            theirs.pop_back();
            ++pops;
        }
        ASSERT_EQ(ours, theirs) << "step " << step;
    }
    EXPECT_GT(pops, 5000u);
    // what is left comes out smallest first
    std::uint64_t last = 0;
    while (!ours.empty())
    {
        const std::uint64_t top = keyHeapPop(ours);
        EXPECT_LE(last, top);
        last = top;
    }
}

TEST(HeadingLatticeHeap, RebuiltHeapPopsInOrder)
{
    // aimHeuristic() re-keys every open entry and rebuilds the heap with keyHeapMake()
    std::mt19937 random(11);
    std::uniform_real_distribution<float> priority(0.f, 50.f);
    std::vector<std::uint64_t> heap;
    for (std::uint32_t g = 0; g < 500; ++g)
        heap.push_back(groupKey(priority(random), g));
    std::vector<std::uint64_t> sorted = heap;
    std::sort(sorted.begin(), sorted.end());
    keyHeapMake(heap);
    for (std::uint64_t expected : sorted)
        ASSERT_EQ(keyHeapPop(heap), expected);
    EXPECT_TRUE(heap.empty());
}
