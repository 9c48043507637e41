#ifndef MICHI_TOOLS_CAMPAIGN_CAMPAIGN_
#define MICHI_TOOLS_CAMPAIGN_CAMPAIGN_

#include <michi/tools/problem/Dataset.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief One planner configuration of a campaign: a registry name and parameters under a label, so that
            two configurations of one planner are two entries ("rrtc_short" and "rrtc_long" of
            geometric::RRTConnect). The label is the planner's name in the log and the database. */
        struct CampaignPlanner
        {
            std::string label;
            std::string name;
            std::map<std::string, std::string> params;
        };

        /** \brief A campaign file (docs/campaigns.md): datasets (Dataset.h: a lone problem file is a dataset of
            its own queries, a folder of problem files is another) times planner configurations times checkers
            times runs. */
        struct Campaign
        {
            std::string file;  ///< the campaign file, as given
            std::string name;
            unsigned int seed{1};
            double timeLimit{1.};
            unsigned int runs{1};
            /** \brief Seconds a unit's process may run past its time limit (loading the problem, simplifying,
                writing) before it is killed and recorded as a timeout. */
            double hangMargin{30.};
            std::vector<Dataset> datasets;
            std::vector<CampaignPlanner> planners;
            /** \brief Checker names (PlanningContext.h checkerNames()); "problem" keeps each problem's own. */
            std::vector<std::string> checkers;
            /** \brief Problem files (absolute, normalised) that the campaign file names by an absolute path, directly
                or through a dataset folder: the plan keeps these absolute and the others relative to the campaign
                file, so that one campaign file copied to two places writes the same plan. */
            std::set<std::string> absoluteFiles;
        };

        /** \brief One work unit: a query of a problem, one planner configuration, one checker, one run. */
        struct WorkUnit
        {
            std::size_t id{0};  ///< its index in planUnits() order: stable while the campaign file is unchanged
            std::string dataset;
            DatasetEntry entry;
            std::size_t planner{0};  ///< index in Campaign::planners
            std::string checker;
            unsigned int run{0};
            std::uint32_t seed{1};  ///< unitSeed(campaign.seed, id)
        };

        /** \brief Read a campaign file; paths in it are relative to it. Every problem it names is loaded (so a bad
            problem fails here, before any run). Throws ProblemError naming the file (the campaign file or a
            problem file) and the key. */
        Campaign loadCampaign(const std::string &file);

        /** \brief Every work unit, in a fixed order: dataset entry, then planner, then checker, then run. */
        std::vector<WorkUnit> planUnits(const Campaign &campaign);

        /** \brief The ompl::RNG seed of unit \e id: a mix of both (SplitMix64), never 0, so that shards draw
            independent streams and a rerun of one unit is exact. */
        std::uint32_t unitSeed(unsigned int campaignSeed, std::size_t id);

        /** \brief "K/N" with 1 <= K <= N; std::invalid_argument (what was expected) otherwise. */
        std::pair<unsigned int, unsigned int> parseShard(const std::string &text);

        /** \brief Shard K of N: the units shuffled by a hash (SplitMix64) of their id, then dealt round-robin, so
            every unit is in exactly one shard, shards differ in size by at most one, and each gets a similar mix of
            problems and planners whatever N is. Returned in plan order. */
        std::vector<WorkUnit> shardUnits(const std::vector<WorkUnit> &units, unsigned int k, unsigned int n);

        /** \brief The planner's name in logs and the database: its label, suffixed "_<checker>" when the
            campaign has more than one checker. */
        std::string unitPlannerName(const Campaign &campaign, const WorkUnit &unit);

        /** \brief One line: id, dataset, problem file (relative to the campaign file's folder)#query, planner label,
            checker, run, seed (tab-separated). The same whatever the working folder. */
        std::string planLine(const Campaign &campaign, const WorkUnit &unit);

        /** \brief The text of a shard's `campaign.plan`: a header of what decides a unit's result beside its plan
            line (the campaign's name and seed, the time limit, every planner configuration with its parameters, and
            every problem file with a hash of its bytes), then one planLine() per unit. Resume and merge compare it
            line for line, so records run with other settings or an edited problem file are never mixed under one
            unit id. */
        std::string planText(const Campaign &campaign, const std::vector<WorkUnit> &units);

        /** \brief Where two plan texts first differ: "line N: 'here' against 'there'" (a missing line is
            "(none)"); empty when they are equal. */
        std::string planDifference(const std::string &here, const std::string &there);
    }  // namespace tools
}  // namespace michi

#endif
