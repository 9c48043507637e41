// One problem's unit records as an OMPL benchmark log, in the format ompl::tools::Benchmark::saveResultsToStream
// writes and ompl_benchmark_statistics reads (so the database is made by OMPL's own script, as `michi bench`'s is).
#include <michi/tools/campaign/CampaignMerge.h>

#include <ompl/base/PlannerStatus.h>
#include <ompl/config.h>

#include <algorithm>
#include <ctime>
#include <map>
#include <set>
#include <sstream>

#include <unistd.h>

namespace ob = ompl::base;

namespace michi
{
    namespace tools
    {
        namespace
        {
            /** a run value: ';' separates values in the log, a line break ends the run */
            std::string logValue(std::string v)
            {
                std::replace(v.begin(), v.end(), ';', ',');
                std::replace(v.begin(), v.end(), '\n', ' ');
                std::replace(v.begin(), v.end(), '\r', ' ');
                return v;
            }

            std::string hostName()
            {
                char name[256] = {0};
                if (gethostname(name, sizeof(name) - 1) != 0)
                    return "unknown";
                return name;
            }

            std::string now()
            {
                const std::time_t t = std::time(nullptr);
                char text[64];
                std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%S", std::gmtime(&t));
                return text;
            }
        }  // namespace

        std::string campaignLog(const std::vector<UnitRecord> &records, unsigned int campaignSeed)
        {
            if (records.empty())
                throw std::invalid_argument("campaignLog: no records");
            const UnitRecord &first = records.front();
            // the planners in the order their first unit comes in the plan
            std::vector<std::string> order;
            std::map<std::string, std::vector<const UnitRecord *>> byPlanner;
            double totalTime = 0.;
            std::string setupInfo;
            for (const auto &r : records)
            {
                if (!byPlanner.count(r.plannerName))
                    order.push_back(r.plannerName);
                byPlanner[r.plannerName].push_back(&r);
                totalTime += r.wallTime;
                if (setupInfo.empty() && r.outcome == "done")
                    setupInfo = r.setupInfo;
            }
            std::size_t runsPerPlanner = 0;
            for (const auto &kv : byPlanner)
                // The log has one "runs per planner" line: with units missing (not run yet) the largest count stands
                // for all.
                runsPerPlanner = std::max(runsPerPlanner, kv.second.size());
            double memoryLimit = 0.;
            for (const auto &r : records)
                memoryLimit = std::max(memoryLimit, r.memoryLimit);

            std::ostringstream log;
            log << "OMPL version " << OMPL_MAJOR_VERSION << "." << OMPL_MINOR_VERSION << "." << OMPL_PATCH_VERSION
                << "\n";
            log << "Experiment " << first.problem << "\n";
            log << "5 experiment properties\n";
            log << "campaign VARCHAR(128) = " << first.campaign << "\n";
            log << "dataset VARCHAR(128) = " << first.dataset << "\n";
            log << "problem_file VARCHAR(512) = " << first.problemFile << "\n";
            log << "michi_version VARCHAR(128) = " << first.michiVersion << "\n";
            log << "unit_seeds VARCHAR(64) = from campaign seed and unit id (run property seed)\n";
            log << "Running on " << hostName() << "\n";
            log << "Starting at " << now() << "\n";
            log << "<<<|\n" << (setupInfo.empty() ? "campaign " + first.campaign + "\n" : setupInfo);
            if (!setupInfo.empty() && setupInfo.back() != '\n')
                log << "\n";
            log << "|>>>\n";
            log << campaignSeed << " is the random seed\n";
            log << first.timeLimit << " seconds per run\n";
            log << memoryLimit << " MB per run\n";
            log << runsPerPlanner << " runs per planner\n";
            log << totalTime << " seconds spent to collect the data\n";
            log << "1 enum types\nstatus";
            // The status enum as OMPL writes it, so ompl_benchmark_statistics maps the status numbers (CRASH, TIMEOUT)
            // to names.
            // OMPL 1.5.2's asString() has no name for ABORT ("Unknown status"); the database gets "Abort".
            for (int i = 0; i < ob::PlannerStatus::TYPE_COUNT; ++i)
                log << "|"
                    << (i == ob::PlannerStatus::ABORT
                            ? std::string("Abort")
                            : ob::PlannerStatus(static_cast<ob::PlannerStatus::StatusType>(i)).asString());
            log << "\n";
            log << order.size() << " planners\n";
            for (const auto &name : order)
            {
                const auto &runs = byPlanner[name];
                log << name << "\n";
                // the settings of a unit that ran (a crashed unit's process could not report them); the same for
                // every unit of one configuration, so Planner Arena pools them under one plannerConfigs row
                std::vector<std::string> settings;
                for (const auto *r : runs)
                    if (r->outcome == "done")
                    {
                        settings = r->settings;
                        break;
                    }
                log << settings.size() << " common properties\n";
                for (const auto &s : settings)
                    log << logValue(s) << "\n";
                // The union of every run's property names: a crashed unit has fewer properties than a finished one, and
                // each run must still give a value (maybe empty) for every column.
                std::set<std::string> keys;
                for (const auto *r : runs)
                    for (const auto &kv : r->properties)
                        keys.insert(kv.first);
                log << keys.size() << " properties for each run\n";
                for (const auto &k : keys)
                    log << k << "\n";
                log << runs.size() << " runs\n";
                for (const auto *r : runs)
                {
                    for (const auto &k : keys)
                    {
                        const auto it = r->properties.find(k);
                        log << (it == r->properties.end() ? "" : logValue(it->second)) << "; ";
                    }
                    log << "\n";
                }
                // OMPL's progress section (saveResultsToStream): one line per run, in the runs' order, each sample's
                // values followed by ',' and each sample by ';'. A unit that crashed has none: an empty line keeps the
                // lines matched to their runs.
                const std::vector<std::string> *progressNames = nullptr;
                for (const auto *r : runs)
                    if (!r->progressNames.empty())
                    {
                        progressNames = &r->progressNames;
                        break;
                    }
                if (progressNames != nullptr)
                {
                    log << progressNames->size() << " progress properties for each run\n";
                    for (const auto &n : *progressNames)
                        log << n << "\n";
                    log << runs.size() << " runs\n";
                    for (const auto *r : runs)
                    {
                        if (r->progressNames == *progressNames)
                            for (const auto &sample : r->progress)
                            {
                                for (const auto &v : sample)
                                    log << logValue(v) << ",";
                                log << ";";
                            }
                        log << "\n";
                    }
                }
                log << ".\n";
            }
            return log.str();
        }
    }  // namespace tools
}  // namespace michi
