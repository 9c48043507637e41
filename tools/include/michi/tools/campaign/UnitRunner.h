#ifndef MICHI_TOOLS_CAMPAIGN_UNIT_RUNNER_
#define MICHI_TOOLS_CAMPAIGN_UNIT_RUNNER_

#include <michi/tools/campaign/UnitRecord.h>

namespace michi
{
    namespace tools
    {
        /** \brief Run one work unit in this process: seed ompl::RNG with spec.seed (before anything draws from
            it, so call this in a fresh process), load the problem, install the checker, and run OMPL's Benchmark
            once with the planner configuration. Returns \e spec completed: outcome "done", the planner's settings
            and the run's properties as OMPL records them, plus michi's: unit, seed, checker, validity_checks (state
            checks through the space information), motion_checks (motion validator calls), fcl_queries (FCL
            collision queries, including those of motion checks), certified_paths (a path FCL re-checks at a fine
            step; one that fails counts as not solved) and path (the solution's states, "a b c|d e f"). Throws
            ProblemError / std::runtime_error when the unit cannot run (e.g. its start collides under that
            checker). */
        UnitRecord runUnit(const UnitRecord &spec);
    }  // namespace tools
}  // namespace michi

#endif
