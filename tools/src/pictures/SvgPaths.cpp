#include "SvgPanels.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
            namespace
            {
                // ---------------------------------------------------------------- paths in the value space

                double wrapDifference(double from, double to)
                {
                    // The short way round, in [-pi, pi], as OMPL's SO(2) interpolates: the picture follows the motion
                    // the planner checked, not the long way across the axis.
                    return std::remainder(to - from, 2. * M_PI);
                }

                /** Positions along a path of states, linear in the values except for angles that wrap, which take
                    the short way round. Length is the Euclidean length in the values. */
                class PathSampler
                {
                public:
                    PathSampler(std::vector<Values> states, std::vector<bool> wraps)
                        : states_(std::move(states)), wraps_(std::move(wraps))
                    {
                        cumulative_.push_back(0.);
                        for (std::size_t k = 1; k < states_.size(); ++k)
                            cumulative_.push_back(cumulative_.back() + segmentLength(k - 1));
                    }

                    double length() const
                    {
                        return cumulative_.back();
                    }

                    /** \e count states evenly spaced by length, the first and last state included. */
                    std::vector<Values> evenlySpaced(std::size_t count) const
                    {
                        if (states_.empty())
                            return {};
                        if (states_.size() == 1 || length() <= 0.)
                            return {states_.front()};
                        std::vector<Values> result;
                        for (std::size_t i = 0; i < count; ++i)
                            result.push_back(at(length() * static_cast<double>(i) / static_cast<double>(count - 1)));
                        return result;
                    }

                    /** Every state and about \e count states in between, spread by length. */
                    std::vector<Values> dense(std::size_t count) const
                    {
                        std::vector<Values> result;
                        for (std::size_t k = 0; k + 1 < states_.size(); ++k)
                        {
                            const double share = length() > 0. ? segmentLength(k) / length() : 0.;
                            // Steps in proportion to each segment's share of the length, and every waypoint kept: the
                            // trace bends exactly at the path's states.
                            const std::size_t steps = std::max<std::size_t>(1, std::ceil(share * count));
                            for (std::size_t j = 0; j < steps; ++j)
                                result.push_back(interpolate(k, static_cast<double>(j) / steps));
                        }
                        if (!states_.empty())
                            result.push_back(states_.back());
                        return result;
                    }

                private:
                    double difference(std::size_t i, double from, double to) const
                    {
                        return wraps_[i] ? wrapDifference(from, to) : to - from;
                    }

                    double segmentLength(std::size_t k) const
                    {
                        double squared = 0.;
                        for (std::size_t i = 0; i < wraps_.size(); ++i)
                            squared += std::pow(difference(i, states_[k][i], states_[k + 1][i]), 2);
                        return std::sqrt(squared);
                    }

                    Values interpolate(std::size_t k, double t) const
                    {
                        Values v(wraps_.size());
                        for (std::size_t i = 0; i < v.size(); ++i)
                            v[i] = states_[k][i] + t * difference(i, states_[k][i], states_[k + 1][i]);
                        return v;
                    }

                    Values at(double s) const
                    {
                        const auto next = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
                        if (next == cumulative_.end())
                            return states_.back();
                        const std::size_t k = std::max<std::ptrdiff_t>(next - cumulative_.begin() - 1, 0);
                        const double segment = cumulative_[k + 1] - cumulative_[k];
                        return interpolate(k, segment > 0. ? (s - cumulative_[k]) / segment : 0.);
                    }

                    std::vector<Values> states_;
                    std::vector<bool> wraps_;
                    std::vector<double> cumulative_;  ///< length from the first state to each state
                };
            }  // namespace

            void checkValues(const Values &values, std::size_t dimension, const std::string &what)
            {
                if (values.size() != dimension)
                    throw std::invalid_argument(what + " has " + std::to_string(values.size()) +
                                                " values, the problem's state has " + std::to_string(dimension));
                for (double v : values)
                    if (!std::isfinite(v))
                        throw std::invalid_argument(what + " has a value that is not finite");
            }

            std::vector<SampledPath> samplePaths(const std::vector<PlotPath> &paths, const RobotGeometry &robot,
                                                 std::size_t dimension)
            {
                std::vector<SampledPath> sampled;
                for (std::size_t p = 0; p < paths.size(); ++p)
                {
                    const auto &path = paths[p];
                    for (std::size_t k = 0; k < path.states.size(); ++k)
                        checkValues(path.states[k], dimension, "path '" + path.label + "': state " + std::to_string(k));
                    // Poses evenly spaced by length: the drawn robots show how far the path goes, not how many
                    // waypoints it has.
                    const PathSampler sampler(path.states, robot.wraps());
                    sampled.push_back({path.label, PALETTE[p % PALETTE_SIZE], sampler.evenlySpaced(POSES_PER_PATH),
                                       sampler.dense(TRACE_SAMPLES), path.states});
                }
                return sampled;
            }

        }  // namespace svg_plot
    }      // namespace tools
}  // namespace michi
