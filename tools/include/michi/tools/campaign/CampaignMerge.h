#ifndef MICHI_TOOLS_CAMPAIGN_CAMPAIGN_MERGE_
#define MICHI_TOOLS_CAMPAIGN_CAMPAIGN_MERGE_

#include <michi/tools/campaign/UnitRecord.h>

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        struct MergeResult
        {
            std::size_t planned{0};  ///< units in the campaign's plan
            std::size_t merged{0};   ///< unit records merged (one database row each)
            std::size_t missing{0};  ///< planned units with no record in any folder
            std::size_t failed{0};   ///< merged units whose outcome is crash, timeout or error
            std::string database;
            std::string summary;
            std::string summaryText;
            std::vector<std::string> logs;
            /** \brief Folders given that hold no `campaign.plan` (a Slurm task cancelled before it began, a shard that
                never started): left out, their units counted as missing. */
            std::vector<std::string> skipped;
        };

        /** \brief Merge shard folders of one campaign (each holds the same `campaign.plan`) into \e outDir:
            `logs/<problem>.log` (OMPL's benchmark log format, one per problem: every planner configuration's
            runs on it, failed units included as unsolved runs with their outcome and signal), `campaign.db`
            (Debian's ompl_benchmark_statistics over all the logs: Planner Arena's database, one `runs` row per
            unit) and `summary.md` (summaryMarkdown()). A unit found in two folders counts once. All-or-nothing:
            written to a staging folder and moved in at the end. A folder without a `campaign.plan` is skipped
            (MergeResult::skipped) so that one shard that never ran does not hold back the others; throws
            std::runtime_error naming the folder or file at fault otherwise, and when no folder holds a plan. */
        MergeResult mergeCampaign(const std::vector<std::string> &dirs, const std::string &outDir,
                                  std::ostream *progress = nullptr);

        /** \brief The OMPL benchmark log of one problem's unit records (all of the same problem). */
        std::string campaignLog(const std::vector<UnitRecord> &records, unsigned int campaignSeed);

        /** \brief Per planner (runs, solved, failed, median and 95th-percentile time, median length and
            clearance), then per dataset and planner; times over all runs, length and clearance over solved
            runs. */
        std::string campaignSummary(const std::vector<UnitRecord> &records, std::size_t planned);
    }  // namespace tools
}  // namespace michi

#endif
