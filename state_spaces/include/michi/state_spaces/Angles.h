#ifndef MICHI_STATE_SPACES_ANGLES_
#define MICHI_STATE_SPACES_ANGLES_

#include <boost/math/constants/constants.hpp>

#include <cmath>

namespace michi
{
    namespace state_spaces
    {
        /** \brief \e a wrapped into [-pi, pi), as OMPL's SO2StateSpace::enforceBounds does. */
        inline double wrapAngle(double a)
        {
            const double pi = boost::math::constants::pi<double>();
            double v = std::fmod(a, 2. * pi);
            if (v < -pi)
                v += 2. * pi;
            else if (v >= pi)
                v -= 2. * pi;
            return v;
        }

        /** \brief Signed shortest rotation from \e from to \e to, in [-pi, pi). */
        inline double turnBetween(double from, double to)
        {
            const double pi = boost::math::constants::pi<double>();
            double d = std::remainder(to - from, 2. * pi);
            if (d >= pi)
                d -= 2. * pi;
            return d;
        }
    }  // namespace state_spaces
}  // namespace michi

#endif
