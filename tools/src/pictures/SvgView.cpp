#include "SvgView.h"

#include <algorithm>
#include <cmath>

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
            Extent framed(Extent e)
            {
                if (e.empty())
                    e.add(0., 0.);
                // 5 % of room around the content (at least 0.05), so nothing touches the frame.
                const double pad = std::max(0.05 * std::max(e.width(), e.height()), 0.05);
                e.xMin -= pad;
                e.xMax += pad;
                e.yMin -= pad;
                e.yMax += pad;
                // Neither side below a quarter of the other: a long thin scene (a corridor) still gets a panel one can
                // read.
                const double minimum = 0.25 * std::max(e.width(), e.height());
                for (auto range : {std::make_pair(&e.xMin, &e.xMax), std::make_pair(&e.yMin, &e.yMax)})
                {
                    const double grow = 0.5 * (minimum - (*range.second - *range.first));
                    if (grow > 0.)
                    {
                        *range.first -= grow;
                        *range.second += grow;
                    }
                }
                return e;
            }

            double niceStep(double range, double count)
            {
                const double raw = range / count;
                const double magnitude = std::pow(10., std::floor(std::log10(raw)));
                const double n = raw / magnitude;
                // Steps of 1, 2 or 5 times a power of ten: tick labels a reader adds up at a glance.
                return (n < 1.5 ? 1. : n < 3. ? 2. : n < 7. ? 5. : 10.) * magnitude;
            }
        }  // namespace svg_plot
    }      // namespace tools
}  // namespace michi
