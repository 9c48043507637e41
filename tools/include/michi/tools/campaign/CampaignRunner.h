#ifndef MICHI_TOOLS_CAMPAIGN_CAMPAIGN_RUNNER_
#define MICHI_TOOLS_CAMPAIGN_CAMPAIGN_RUNNER_

#include <michi/tools/campaign/Campaign.h>
#include <michi/tools/campaign/UnitRecord.h>

#include <cstddef>
#include <ostream>
#include <string>

namespace michi
{
    namespace tools
    {
        struct ShardOptions
        {
            unsigned int shard{1};  ///< K of K/N, from 1
            unsigned int shards{1};
            std::string outDir;
            /** \brief The executable that runs one unit: `<michiBinary> campaign unit SPEC RESULT` (the `michi`
                command itself, so a crash takes only that unit's process down). */
            std::string michiBinary;
            std::string michiVersion;         ///< recorded in every unit ("0.1.0 (git abc1234)")
            std::ostream *progress{nullptr};  ///< one line per unit: done/total, failures, time left
        };

        struct ShardResult
        {
            std::size_t units{0};    ///< the shard's share
            std::size_t skipped{0};  ///< already finished (a resumed shard)
            std::size_t ran{0};
            std::size_t failed{0};  ///< crash, timeout or error (among those run now)
        };

        /** \brief Check what the units' processes would otherwise find one by one: every planner configuration is
            made with its parameters on the first problem. Throws ProblemError naming the campaign file and
            planners[i]. */
        void checkCampaignPlanners(const Campaign &campaign);

        /** \brief The unit's record before it runs (what a failed unit's record holds besides its cause). */
        UnitRecord unitSpec(const Campaign &campaign, const WorkUnit &unit, const std::string &michiVersion);

        /** \brief Run shard K/N of the campaign into options.outDir: `campaign.plan` (every unit of the campaign,
            the same in every shard's folder: merge checks it), `units/<id>.run` per finished unit. Each unit runs in
            a child process; a unit that dies of a signal is recorded as outcome "crash" with the signal, one still
            running at time limit + hang margin is killed and recorded as "timeout", one that exits with an error as
            "error", and the shard goes on. Units whose record exists are skipped, so a stopped shard resumes where it
            stopped. Throws std::runtime_error when the folder holds another campaign's plan or shard. */
        ShardResult runShard(const Campaign &campaign, const ShardOptions &options);
    }  // namespace tools
}  // namespace michi

#endif
