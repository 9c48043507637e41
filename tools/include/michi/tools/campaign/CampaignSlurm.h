#ifndef MICHI_TOOLS_CAMPAIGN_CAMPAIGN_SLURM_
#define MICHI_TOOLS_CAMPAIGN_CAMPAIGN_SLURM_

#include <michi/tools/campaign/Campaign.h>

#include <string>

namespace michi
{
    namespace tools
    {
        struct SlurmScripts
        {
            std::string run;     ///< the job array: one `campaign run --shard K/N` per task
            std::string merge;   ///< `campaign merge` of every shard folder
            std::string submit;  ///< submits both, the merge depending on the array (afterany)
        };

        /** \brief Write into \e outDir: `run.sbatch` (an sbatch job array 1-N, task K runs shard K/N into
            OUT/shards/K), `merge.sbatch` (merges every OUT/shards/K into OUT/merged) and `submit.sh` (sbatch the array,
            then the merge with --dependency=afterany on it, so that a shard killed by Slurm still leaves the others
            merged; resubmitting resumes). Every path is absolute: the nodes are expected to share the file system.
            A task's --time is the worst case of its shard: units x (time limit + hang margin), plus 10 minutes. */
        SlurmScripts writeSlurmScripts(const Campaign &campaign, const std::string &campaignFile, unsigned int shards,
                                       const std::string &outDir, const std::string &michiBinary,
                                       const std::string &partition = "");
    }  // namespace tools
}  // namespace michi

#endif
