/* Stacks of 2-D J-maps for three joints (one map per cell of the outer joint). */

#include <michi/validity/jmap/JMap.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace michi
{
    namespace validity
    {
        JMapStack::JMapStack(SourceFactory makeSource, JMapAxes base, int outer, double outerLo, double outerHi,
                             int outerSlices, JMapSettings settings)
            : makeSource_(std::move(makeSource))
            , base_(std::move(base))
            , outer_(outer)
            , outerLo_(outerLo)
            , outerHi_(outerHi)
            , outerSlices_(outerSlices)
            , settings_(settings)
        {
            if (outerSlices_ < 1 || !(outerHi_ > outerLo_))
                throw std::invalid_argument("J-map stack: need outerSlices >= 1 and outerLo < outerHi");
            if (outer_ < 0 || outer_ == base_.axis1 || outer_ == base_.axis2)
                throw std::invalid_argument("J-map stack: the outer joint " + std::to_string(outer_) +
                                            " must differ from the map's axes");
            if (base_.configuration.size() <= static_cast<std::size_t>(outer_))
                throw std::invalid_argument("J-map stack: the base configuration has no value for joint " +
                                            std::to_string(outer_));
            maps_.resize(outerSlices_);
        }

        std::size_t JMapStack::sliceIndex(double value) const
        {
            const double k = std::floor((value - outerLo_) / (outerHi_ - outerLo_) * outerSlices_);
            // Clamped so the upper limit itself (and values rounding past either end) use the end slices.
            return static_cast<std::size_t>(std::max(0., std::min<double>(outerSlices_ - 1, k)));
        }

        std::pair<double, double> JMapStack::cell(std::size_t k) const
        {
            const double step = (outerHi_ - outerLo_) / outerSlices_;
            // The last cell ends exactly at outerHi_, not at a rounded sum, so the cells cover the whole range without
            // a gap.
            const double hi = k + 1 == static_cast<std::size_t>(outerSlices_) ? outerHi_ : outerLo_ + (k + 1) * step;
            return {outerLo_ + k * step, hi};
        }

        double JMapStack::centre(std::size_t k) const
        {
            const auto c = cell(k);
            return 0.5 * (c.first + c.second);
        }

        JMapPtr JMapStack::slice(std::size_t k) const
        {
            const auto c = cell(k);
            JMapAxes axes = base_;
            axes.configuration[outer_] = 0.5 * (c.first + c.second);
            axes.halfWidths.resize(axes.configuration.size(), 0.);
            // Paper 000's stack has one 2-D map per quantised theta1. Each map here is built for the outer joint
            // anywhere in its cell (centre +- half width), so a state between two slices is still covered
            // (conservative).
            axes.halfWidths[outer_] = 0.5 * (c.second - c.first);
            const JMapIntervalSourcePtr source = makeSource_(axes);
            return JMap::build(*source, settings_);
        }

        const JMapPtr &JMapStack::map(std::size_t k)
        {
            // Built on first use: a query touches few outer cells, and a whole stack of FCL-certified maps takes
            // minutes.
            if (!maps_.at(k))
                maps_[k] = slice(k);
            return maps_[k];
        }

        void JMapStack::buildAll()
        {
            for (std::size_t k = 0; k < maps_.size(); ++k)
                map(k);
        }

        bool JMapStack::collides(double outer, double theta1, double theta2)
        {
            return map(sliceIndex(outer))->collides(theta1, theta2);
        }
    }  // namespace validity
}  // namespace michi
