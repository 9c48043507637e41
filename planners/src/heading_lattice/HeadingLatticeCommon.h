#ifndef MICHI_PLANNERS_SRC_HEADING_LATTICE_COMMON_
#define MICHI_PLANNERS_SRC_HEADING_LATTICE_COMMON_

// Private to HeadingLattice.cpp and HeadingLatticeSearch.cpp (not installed): constants both halves share.

#include <michi/state_spaces/Angles.h>

#include <boost/math/constants/constants.hpp>

#include <cmath>
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

            inline bool heapLess(float fa, float ga, float fb, float gb)
            {
                // std heaps are max-heaps: "less" = lower priority; smaller f first, then larger g (deeper)
                return fa > fb || (fa == fb && ga < gb);
            }
        }  // namespace
    }      // namespace planners
}  // namespace michi

#endif
