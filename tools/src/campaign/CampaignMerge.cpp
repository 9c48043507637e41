// `campaign merge`: shard folders -> one OMPL log per problem, one Planner Arena database, one summary.
#include <michi/tools/campaign/CampaignMerge.h>
#include <michi/tools/FileOutput.h>
#include <michi/tools/campaign/Campaign.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace
        {
            std::string readText(const fs::path &file)
            {
                std::ifstream in(file.string());
                if (!in)
                    throw std::runtime_error(file.string() + ": cannot read it (not a campaign run folder?)");
                std::stringstream s;
                s << in.rdbuf();
                return s.str();
            }

            /** the campaign seed, from the plan's header line "# campaign NAME seed S" */
            unsigned int planSeed(const std::string &plan)
            {
                const auto at = plan.find(" seed ");
                if (plan.rfind("# campaign ", 0) != 0 || at == std::string::npos || at > plan.find('\n'))
                    return 0;
                return static_cast<unsigned int>(std::stoul(plan.substr(at + 6)));
            }

            std::string fileSafe(std::string s)
            {
                for (char &c : s)
                    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
                        c = '_';
                return s;
            }

        }  // namespace

        MergeResult mergeCampaign(const std::vector<std::string> &dirs, const std::string &outDir,
                                  std::ostream *progress)
        {
            if (dirs.empty())
                throw std::runtime_error("no campaign run folder given");
            std::string plan, planDir;
            std::map<std::size_t, UnitRecord> records;
            MergeResult result;
            for (const auto &dir : dirs)
            {
                if (!fs::exists(fs::path(dir) / "campaign.plan"))
                {
                    // A shard that never began (a Slurm task cancelled while pending) must not hold back the others:
                    // its units are reported missing, as those of a shard still running are.
                    result.skipped.push_back(dir);
                    if (progress)
                        *progress << "michi campaign merge: " << dir
                                  << ": no campaign.plan (a shard that never started?): skipped" << std::endl;
                    continue;
                }
                // Shards are merged only when their plans match line for line: unit ids mean the same unit only within
                // one plan, and the plan's header holds the settings the units ran with.
                const std::string p = readText(fs::path(dir) / "campaign.plan");
                if (planDir.empty())
                {
                    plan = p;
                    planDir = dir;
                }
                else if (p != plan)
                    throw std::runtime_error(dir + ": its campaign.plan differs from " + planDir + "'s at " +
                                             planDifference(p, plan) +
                                             " (shards of different campaigns, or run with other settings)");
                const fs::path units = fs::path(dir) / "units";
                if (!fs::is_directory(units))
                    continue;  // a shard that has not finished a unit yet
                std::vector<fs::path> files;
                for (const auto &e : fs::directory_iterator(units))
                    if (e.path().extension() == ".run")
                        files.push_back(e.path());
                // Directory order differs between file systems; sorted, a merge reads the same records in the same
                // order everywhere.
                std::sort(files.begin(), files.end());
                for (const auto &f : files)
                {
                    UnitRecord r = readUnitRecord(f.string());
                    if (r.outcome == "pending")
                        throw std::runtime_error(f.string() + ": a unit spec, not a result");
                    records.emplace(r.id, std::move(r));  // a unit in two folders (a rerun shard) counts once
                }
            }
            // Every unit line is "id, problem, file#query, planner, checker, run k, seed s" between tabs, ids counting
            // from 0, and the file ends with a newline (run writes it whole): anything else is a plan cut short or
            // edited, whose unit count would otherwise be misread (a truncated plan gave "unit 2 is not in the
            // campaign's plan").
            if (planDir.empty())
                throw std::runtime_error("no campaign.plan in " + dirs.front() +
                                         (dirs.size() > 1 ? " nor in the other folders" : "") +
                                         " (not campaign run folders?)");
            const std::string planFile = (fs::path(planDir) / "campaign.plan").string();
            std::size_t planned = 0;
            {
                if (!plan.empty() && plan.back() != '\n')
                    throw std::runtime_error(planFile + ": ends in the middle of a line (a truncated plan)");
                std::istringstream in(plan);
                std::string line;
                for (std::size_t number = 1; std::getline(in, line); ++number)
                {
                    if (line.empty() || line[0] == '#')
                        continue;
                    std::vector<std::string> fields;
                    std::istringstream cells(line);
                    for (std::string cell; std::getline(cells, cell, '\t');)
                        fields.push_back(cell);
                    if (fields.size() != 7 || fields[0] != std::to_string(planned) || fields[5].rfind("run ", 0) != 0 ||
                        fields[6].rfind("seed ", 0) != 0)
                        throw std::runtime_error(planFile + ": line " + std::to_string(number) + " is not unit " +
                                                 std::to_string(planned) + " of a plan (a truncated or edited plan)");
                    ++planned;
                }
            }
            const unsigned int seed = planSeed(plan);

            result.planned = planned;
            std::vector<UnitRecord> all;
            for (auto &kv : records)
            {
                // Ids are places in the plan: an id past its end is no unit of this campaign.
                if (kv.first >= planned)
                    throw std::runtime_error("unit " + std::to_string(kv.first) + " is not in " + planFile + " (" +
                                             std::to_string(planned) +
                                             " units: a truncated plan, or a record of another campaign)");
                result.failed += kv.second.outcome != "done";
                all.push_back(kv.second);
            }
            result.merged = all.size();
            result.missing = planned - all.size();
            if (all.empty())
                throw std::runtime_error("no finished unit in " + planDir + (dirs.size() > 1 ? " and the rest" : ""));

            // one log per problem file, in plan order (records are sorted by unit id)
            std::vector<std::string> problems;
            std::map<std::string, std::vector<UnitRecord>> byProblem;
            for (const auto &r : all)
            {
                if (!byProblem.count(r.problemFile))
                    problems.push_back(r.problemFile);
                byProblem[r.problemFile].push_back(r);
            }
            StagedDirectory staging(outDir);
            fs::create_directories(staging.path("logs"));
            std::set<std::string> names;
            std::vector<std::string> logFiles;
            for (const auto &file : problems)
            {
                const auto &rs = byProblem[file];
                std::string name =
                    fileSafe(rs.front().problem.empty() ? fs::path(file).stem().string() : rs.front().problem);
                for (int i = 2; names.count(name); ++i)  // two problem files of one name
                    name = fileSafe(rs.front().problem) + "-" + std::to_string(i);
                names.insert(name);
                const fs::path log = staging.path("logs") / (name + ".log");
                writeAtomically(campaignLog(rs, seed), log.string());
                logFiles.push_back(log.string());
                result.logs.push_back((staging.out() / "logs" / (name + ".log")).string());
            }
            if (progress)
                *progress << "michi campaign merge: " << all.size() << " units of " << planned << " (" << result.failed
                          << " failed) in " << logFiles.size() << " logs" << std::endl;

            const fs::path db = staging.path("campaign.db");
            const fs::path statsLog = staging.path("ompl_benchmark_statistics.out");
            std::string command = "ompl_benchmark_statistics";
            for (const auto &l : logFiles)
                command += " " + shellQuote(l);
            command += " -d " + shellQuote(db.string()) + " > " + shellQuote(statsLog.string()) + " 2>&1";
            const int rc = std::system(command.c_str());
            if (rc != 0 || !fs::exists(db))
                throw std::runtime_error("ompl_benchmark_statistics failed (exit " + std::to_string(rc) + "): " +
                                         lastLine(statsLog.string()) + " (is the ompl-demos package installed?)");
            fs::remove(statsLog);

            result.summaryText = campaignSummary(all, planned);
            writeAtomically(result.summaryText, staging.path("summary.md").string());
            staging.commit();
            result.database = (staging.out() / "campaign.db").string();
            result.summary = (staging.out() / "summary.md").string();
            return result;
        }
    }  // namespace tools
}  // namespace michi
