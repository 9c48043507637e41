// `michi campaign plan|run|merge|slurm`: benchmark campaigns over datasets, in shards, surviving crashes
// (docs/campaigns.md). `michi campaign unit` is internal: the process that runs one work unit for `run`.
#include "CommandLine.h"

#include <michi/tools/FileOutput.h>
#include <michi/tools/campaign/Campaign.h>
#include <michi/tools/campaign/CampaignMerge.h>
#include <michi/tools/campaign/CampaignRunner.h>
#include <michi/tools/campaign/CampaignSlurm.h>
#include <michi/tools/campaign/UnitRunner.h>

#include <boost/filesystem.hpp>

#include <filesystem>
#include <iostream>
#include <memory>

#include <unistd.h>

#include "michi_git_hash.h"  // MICHI_GIT_HASH, generated at build time (cmake/michiGitHash.cmake)

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace cli
        {
            namespace
            {
                struct CampaignArgs
                {
                    std::string file;
                    std::string shard{"1/1"};
                    std::string out;
                    std::vector<std::string> dirs;
                    std::optional<unsigned int> shards;
                    std::optional<unsigned int> seed;
                    std::string partition;
                    std::string spec, result;
                    bool verbose{false};
                };

                std::string version()
                {
                    // Recorded in every unit's record, so a merged database says which build produced each run.
                    return std::string(MICHI_VERSION) + " (git " + MICHI_GIT_HASH + ")";
                }

                /** this executable, for the units' processes and the Slurm scripts */
                std::string selfPath()
                {
                    std::error_code ec;
                    // The very binary that is running, not whatever "michi" comes first on PATH: units and Slurm tasks
                    // must run the same version as the shard that plans them.
                    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
                    if (ec)
                        throw std::runtime_error("cannot find the michi executable (/proc/self/exe): " + ec.message());
                    return self.string();
                }

                Campaign load(const CampaignArgs &args)
                {
                    Campaign c = loadCampaign(args.file);
                    if (args.seed)
                        c.seed = *args.seed;
                    return c;
                }

                int runPlan(const CampaignArgs &args)
                {
                    setOmplLogLevel(args.verbose, true);
                    const Campaign c = load(args);
                    for (const auto &u : planUnits(c))
                        std::cout << planLine(c, u) << "\n";
                    return 0;
                }

                int runRun(const CampaignArgs &args)
                {
                    checkOutputPath("--out", args.out, OutputKind::FOLDER);
                    std::pair<unsigned int, unsigned int> shard;
                    try
                    {
                        shard = parseShard(args.shard);
                    }
                    catch (const std::invalid_argument &e)
                    {
                        throw UsageError(std::string("--shard: ") + e.what());
                    }
                    setOmplLogLevel(args.verbose, true);
                    const Campaign c = load(args);
                    checkCampaignPlanners(c);
                    ShardOptions options;
                    options.shard = shard.first;
                    options.shards = shard.second;
                    options.outDir = args.out;
                    options.michiBinary = selfPath();
                    options.michiVersion = version();
                    options.progress = &std::cerr;
                    const ShardResult r = runShard(c, options);
                    std::cout << "shard " << args.shard << ": " << r.units << " units, " << r.ran << " run now, "
                              << r.skipped << " already done, " << r.failed << " failed; results in " << args.out
                              << std::endl;
                    return 0;
                }

                int runMerge(const CampaignArgs &args)
                {
                    checkOutputPath("--out", args.out, OutputKind::FOLDER);
                    const MergeResult r = mergeCampaign(args.dirs, args.out, &std::cerr);  // names skipped folders
                    std::cout << r.summaryText << "\nwrote " << r.database << "\n      " << r.summary << "\n      "
                              << r.logs.size() << " logs in " << (fs::path(r.database).parent_path() / "logs").string()
                              << std::endl;
                    if (r.missing > 0)
                        std::cerr << "michi campaign merge: " << r.missing << " of " << r.planned
                                  << " units have no result yet (run or resume their shards, then merge again)"
                                  << std::endl;
                    return 0;
                }

                int runSlurm(const CampaignArgs &args)
                {
                    checkOutputPath("--out", args.out, OutputKind::FOLDER);
                    const Campaign c = load(args);
                    SlurmScripts s;
                    try
                    {
                        s = writeSlurmScripts(c, args.file, *args.shards, args.out, selfPath(), args.partition);
                    }
                    catch (const std::invalid_argument &e)
                    {
                        throw UsageError(e.what());  // a flag's value: exit 2, as other bad flags
                    }
                    std::cout << "wrote " << s.run << "\n      " << s.merge << "\n      " << s.submit
                              << "\nsubmit with: sh " << shellQuote(s.submit) << std::endl;
                    return 0;
                }

                int runUnitCommand(const CampaignArgs &args)
                {
                    // warnings stay out of the unit's error file, whose last line is the cause of a failure
                    setOmplLogLevel(false, true);
                    const UnitRecord spec = readUnitRecord(args.spec);
                    writeUnitRecord(runUnit(spec), args.result);
                    return 0;
                }
            }  // namespace

            Runner addCampaign(CLI::App &michi)
            {
                auto args = std::make_shared<CampaignArgs>();
                CLI::App *c = michi.add_subcommand(
                    "campaign",
                    "benchmark campaigns: datasets x planner configurations x checkers x runs, in shards that "
                    "survive crashes, merged into one Planner Arena database (docs/campaigns.md)");
                c->require_subcommand(1);
                auto seed = [&](CLI::App *s)
                {
                    addSeed(*s, args->seed,
                            "campaign seed (default: the file's seed); each unit's seed mixes it "
                            "with the unit's id");
                };

                CLI::App *plan = c->add_subcommand("plan", "print the work units, one per line");
                plan->add_option("file", args->file, "the campaign file (YAML)")->required()->type_name("FILE");
                seed(plan);
                addVerbose(*plan, args->verbose);

                CLI::App *run = c->add_subcommand(
                    "run", "run shard K/N into DIR, each unit in its own process; resumes a stopped shard");
                run->add_option("file", args->file, "the campaign file (YAML)")->required()->type_name("FILE");
                run->add_option("--shard", args->shard, "this shard, K of N (default 1/1: every unit)")
                    ->type_name("K/N");
                addOut(*run, args->out, "the shard's folder (made if missing; resumed if it holds this shard)");
                seed(run);
                addVerbose(*run, args->verbose);

                CLI::App *merge = c->add_subcommand(
                    "merge", "merge shard folders into OUT/campaign.db, OUT/summary.md and OUT/logs/");
                merge->add_option("DIR", args->dirs, "the shards' folders")->required()->type_name("");
                addOut(*merge, args->out, "output folder (made if missing)");

                CLI::App *slurm = c->add_subcommand(
                    "slurm", "write an sbatch job array (one shard per task) and a dependent merge job into DIR");
                slurm->add_option("file", args->file, "the campaign file (YAML)")->required()->type_name("FILE");
                addInteger(*slurm, "--shards", args->shards, 1, 100000, "number of shards (array tasks)")->required();
                addOut(*slurm, args->out, "folder of the scripts, the shards' results and the merged results");
                slurm->add_option("--partition", args->partition, "Slurm partition (default: the cluster's)")
                    ->type_name("NAME");
                // no --seed: every array task reads the campaign file, so the seed has to be in it

                // internal: one work unit, run by `campaign run` in a child process
                CLI::App *unit = c->add_subcommand("unit", "run one work unit (internal, used by campaign run)");
                unit->group("");
                unit->add_option("spec", args->spec)->required();
                unit->add_option("result", args->result)->required();

                return [args, plan, run, merge, slurm, unit]
                {
                    if (plan->parsed())
                        return runPlan(*args);
                    if (run->parsed())
                        return runRun(*args);
                    if (merge->parsed())
                        return runMerge(*args);
                    if (slurm->parsed())
                        return runSlurm(*args);
                    if (unit->parsed())
                        return runUnitCommand(*args);
                    throw UsageError("expected plan, run, merge or slurm");
                };
            }
        }  // namespace cli
    }      // namespace tools
}  // namespace michi
