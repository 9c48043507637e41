#ifndef MICHI_VALIDITY_FAST_ROUND_
#define MICHI_VALIDITY_FAST_ROUND_

// Internal to the fast checkers (the grid checker's footprint tables, the sphere checker's self-pair tables): floor
// and ceil to an int without a call. x86-64's baseline has no rounding instruction, so std::floor is a libm call, and
// both callers ask for several in their hot loops.

namespace michi
{
    namespace validity
    {
        /** \brief floor(x) as an int, for \e x finite and well within int's range. */
        inline int floorToInt(double x)
        {
            const int t = static_cast<int>(x);
            return t - static_cast<int>(x < t);
        }
        /** \brief ceil(x) as an int, for \e x finite and well within int's range. */
        inline int ceilToInt(double x)
        {
            const int t = static_cast<int>(x);
            return t + static_cast<int>(x > t);
        }
    }  // namespace validity
}  // namespace michi

#endif
