#include <michi/tools/campaign/CampaignSlurm.h>
#include <michi/tools/FileOutput.h>

#include <boost/filesystem.hpp>

#include <cmath>
#include <sstream>

#include <sys/stat.h>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        SlurmScripts writeSlurmScripts(const Campaign &campaign, const std::string &campaignFile, unsigned int shards,
                                       const std::string &outDir, const std::string &michiBinary,
                                       const std::string &partition)
        {
            if (shards == 0)
                throw std::invalid_argument("shards: expected at least 1");
            // The partition goes into an #SBATCH line unquoted: a newline or a shell character in it would become a
            // command of the script. Slurm's partition names (and lists of them) need none of those.
            if (partition.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.,-") !=
                std::string::npos)
                throw std::invalid_argument(
                    "--partition: expected a Slurm partition name (letters, digits, '_', '.', "
                    "'-', ',' between names), got '" +
                    partition + "'");
            // Absolute paths throughout: array tasks start on other nodes and in Slurm's own working directory.
            const fs::path out = fs::absolute(outDir);
            const std::string file = fs::absolute(campaignFile).string();
            const std::string michi = fs::absolute(michiBinary).string();
            const std::size_t units = planUnits(campaign).size();
            const std::size_t perShard = (units + shards - 1) / shards;
            // The largest shard's worst case (every unit killed at time limit + hang margin), plus 10 minutes for
            // loading problems and starting processes: Slurm kills a task at its time limit, and the rest of the shard
            // would wait for a resume.
            const auto minutes =
                static_cast<long>(std::ceil(perShard * (campaign.timeLimit + campaign.hangMargin) / 60.)) + 10;
            const std::string name = "michi-" + campaign.name;

            // One core per task: a shard runs its units one after another, one planner process at a time. exec: the
            // shard's exit status becomes the task's, so a failed shard shows as a failed task.
            std::ostringstream run;
            run << "#!/bin/bash\n"
                << "# michi campaign " << campaign.name << ": " << units << " work units in " << shards
                << " shards, one per array task (written by `michi campaign slurm`; docs/campaigns.md)\n"
                << "#SBATCH --job-name=" << name << "\n"
                << "#SBATCH --array=1-" << shards << "\n"
                << "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n"
                << "#SBATCH --time=" << minutes << "\n"
                << "#SBATCH --output=" << (out / "slurm" / "shard-%a.out").string() << "\n";
            if (!partition.empty())
                run << "#SBATCH --partition=" << partition << "\n";
            run << "set -eu\n"
                << "exec " << shellQuote(michi) << " campaign run " << shellQuote(file)
                << " --shard \"${SLURM_ARRAY_TASK_ID}/" << shards << "\" --out "
                << shellQuote((out / "shards").string()) << "/\"${SLURM_ARRAY_TASK_ID}\"\n";

            std::ostringstream merge;
            merge << "#!/bin/bash\n"
                  << "# michi campaign " << campaign.name << ": merge the " << shards
                  << " shards into merged/campaign.db, merged/summary.md and merged/logs/\n"
                  << "#SBATCH --job-name=" << name << "-merge\n"
                  << "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n#SBATCH --time=60\n"
                  << "#SBATCH --output=" << (out / "slurm" / "merge.out").string() << "\n";
            if (!partition.empty())
                merge << "#SBATCH --partition=" << partition << "\n";
            merge << "set -eu\nexec " << shellQuote(michi) << " campaign merge";
            for (unsigned int k = 1; k <= shards; ++k)
                merge << " " << shellQuote((out / "shards" / std::to_string(k)).string());
            merge << " --out " << shellQuote((out / "merged").string()) << "\n";

            // sbatch --parsable prints "jobid;cluster" on a multi-cluster setup: the job id is the part before ';'.
            std::ostringstream submit;
            submit << "#!/bin/sh\n"
                   << "# submit the shards' job array, then the merge once every task has ended (afterany: a failed "
                      "task's finished units are merged; submit again to resume)\n"
                   << "set -eu\n"
                   << "array=$(sbatch --parsable " << shellQuote((out / "run.sbatch").string()) << ")\n"
                   << "merge=$(sbatch --parsable --dependency=afterany:\"${array%%;*}\" "
                   << shellQuote((out / "merge.sbatch").string()) << ")\n"
                   << "echo \"${array%%;*} ${merge%%;*}\"\n";

            fs::create_directories(out / "slurm");
            SlurmScripts s{(out / "run.sbatch").string(), (out / "merge.sbatch").string(),
                           (out / "submit.sh").string()};
            writeAtomically(run.str(), s.run);
            writeAtomically(merge.str(), s.merge);
            writeAtomically(submit.str(), s.submit);
            // The scripts are meant to be run as they are (./submit.sh).
            for (const auto &f : {s.run, s.merge, s.submit})
                chmod(f.c_str(), 0755);
            return s;
        }
    }  // namespace tools
}  // namespace michi
