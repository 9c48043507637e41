#ifndef MICHI_TOOLS_JMAP_REPORT_
#define MICHI_TOOLS_JMAP_REPORT_

#include <michi/tools/problem/Problem.h>

#include <cstdint>
#include <ostream>
#include <string>

namespace michi
{
    namespace tools
    {
        struct JMapReportOptions
        {
            std::string outDir;
            std::uint64_t verify{0};  ///< uniformly sampled states checked against FCL (0: none)
            unsigned int seed{1};
            std::ostream *progress{nullptr};
        };

        /** \brief Build the J-map of a problem's arm (every slice), its grown map and bottleneck when the planned
            group has a hand, write DIR/jmap.svg and DIR/jmap.json (slices, polygons, build_seconds,
            checked_states, unsafe_states, false_invalid_fraction, jmap_query_ns, fcl_query_ns, ...). With
            \e verify N, N uniform states are checked by the J-map checker (conservative mode, every tile built
            first) and by FCL, and both are timed over the same states in the same run. Files are staged and moved
            into DIR only when complete. Returns the JSON text. */
        std::string runJMapReport(const Problem &problem, const JMapReportOptions &options);
    }  // namespace tools
}  // namespace michi

#endif
