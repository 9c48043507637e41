#ifndef MICHI_VALIDITY_FAST_SIN_COS_
#define MICHI_VALIDITY_FAST_SIN_COS_

// Internal to the fast checkers (the sphere checker's kinematics, the grid checker's exact footprint test): sin and cos
// of one angle inline, without the C library's call (test SphereKinematics.SinCosAgreeWithTheCLibrary).

#include <cstdint>
#include <cstring>

namespace michi
{
    namespace validity
    {
        /** \brief sin and cos of \e x (|x| up to a few thousand radians), accurate to a few units in the last
            place: one reduction by pi/2 and the two minimax polynomials on [-pi/4, pi/4]. Inline: called once per
            joint of every sphere-checker state check and once per exact footprint test of the grid checker, where a
            call returning through memory cost as much as the polynomials. */
        inline void fastSinCos(double x, double &s, double &c)
        {
            // x = k pi/2 + r with |r| <= pi/4; pi/2 in two parts so that k pi/2 is subtracted without rounding for
            // the joint ranges of real robots.
            constexpr double twoOverPi = 0.636619772367581343076, pio2Hi = 1.57079632673412561417e+00,
                             pio2Lo = 6.07710050650619224932e-11;
            // round to nearest by the 1.5 * 2^52 shifter: inline, where nearbyint() is a library call per joint
            // (exact for |x| below 2^51 pi/2; strict IEEE arithmetic, no -ffast-math, keeps the two additions)
            constexpr double shifter = 6755399441055744.0;
            const double k = (x * twoOverPi + shifter) - shifter;
            const double r = (x - k * pio2Hi) - k * pio2Lo;
            const double z = r * r;
            // minimax polynomials of sin and cos on [-pi/4, pi/4] (the coefficients of the classic fdlibm kernels)
            const double sr =
                r + r * z *
                        (-1.66666666666666324348e-01 +
                         z * (8.33333333332248946124e-03 +
                              z * (-1.98412698298579493134e-04 +
                                   z * (2.75573137070700676789e-06 +
                                        z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)))));
            const double cr =
                1. - 0.5 * z +
                z * z *
                    (4.16666666666666019037e-02 +
                     z * (-1.38888888888741095749e-03 +
                          z * (2.48015872894767294178e-05 +
                               z * (-2.75573143513906633035e-07 +
                                    z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
            // The quadrant by bit selects, not a branch: the yaws of a planner's states and the joint values of
            // uniform samples fall in a random quadrant, where a switch on it mispredicts three times in four
            // (measured on fresh Panda states, docs/checking.md).
            const std::uint64_t q = static_cast<std::uint64_t>(static_cast<long>(k));
            const std::uint64_t swap = 0 - (q & 1);  // all ones in quadrants 1 and 3: sin and cos trade places
            std::uint64_t sb, cb;
            std::memcpy(&sb, &sr, sizeof sb);
            std::memcpy(&cb, &cr, sizeof cb);
            const std::uint64_t sinBits = ((sb & ~swap) | (cb & swap)) ^ ((q & 2) << 62);
            const std::uint64_t cosBits = ((cb & ~swap) | (sb & swap)) ^ (((q + 1) & 2) << 62);
            std::memcpy(&s, &sinBits, sizeof s);
            std::memcpy(&c, &cosBits, sizeof c);
        }

        /** \brief sin and cos of \e n values in floats (the sphere checker's frames are floats): the reduction by pi/2
           in double as fastSinCos() does it, the polynomials in float (the classic single-precision kernels on
            [-pi/4, pi/4], errors of about one float rounding). Without a branch or a call, so that the compiler runs
            the loop over whole SIMD lanes: a state check asks for every joint of the group at once. */
        inline void fastSinCosFloat(const double *x, int n, float *s, float *c)
        {
            constexpr double twoOverPi = 0.636619772367581343076, pio2Hi = 1.57079632673412561417e+00,
                             pio2Lo = 6.07710050650619224932e-11, shifter = 6755399441055744.0;
            // the reduction in double, then the polynomials and the quadrant's signs over float lanes (two loops:
            // the compiler vectorises the second, not one that mixes doubles and floats)
            float rs[64];
            int qs[64];
            for (int first = 0; first < n; first += 64)
            {
                const int m = n - first < 64 ? n - first : 64;
                for (int i = 0; i < m; ++i)
                {
                    const double k = (x[first + i] * twoOverPi + shifter) - shifter;
                    rs[i] = static_cast<float>((x[first + i] - k * pio2Hi) - k * pio2Lo);
                    // the quadrant modulo 4 through 64 bits: a continuous joint's value past 2^31 quarter turns stays
                    // right
                    qs[i] = static_cast<int>(static_cast<long long>(k) & 3);
                }
                for (int i = 0; i < m; ++i)
                {
                    const float r = rs[i], z = r * r;
                    const float sr = r + r * z * (-1.6666654611e-1f + z * (8.3321608736e-3f + z * -1.9515295891e-4f));
                    const float cr =
                        1.f - 0.5f * z +
                        z * z * (4.166664568298827e-2f + z * (-1.388731625493765e-3f + z * 2.443315711809948e-5f));
                    const int q = qs[i];
                    const bool swap = (q & 1) != 0;
                    const float sv = swap ? cr : sr, cv = swap ? sr : cr;
                    s[first + i] = (q & 2) != 0 ? -sv : sv;
                    c[first + i] = ((q + 1) & 2) != 0 ? -cv : cv;
                }
            }
        }
    }  // namespace validity
}  // namespace michi

#endif
