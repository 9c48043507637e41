// A shard of a campaign: each unit in a child process (the `michi` command itself), so that a planner that
// segfaults or hangs costs one failed run, not the campaign. Results are one file per unit, written atomically,
// which is also what makes a stopped shard resumable.
#include <michi/tools/campaign/CampaignRunner.h>
#include <michi/tools/FileOutput.h>
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/tools/bench/PlanningContext.h>

#include <ompl/base/PlannerStatus.h>

#include <boost/filesystem.hpp>

#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = boost::filesystem;
namespace ob = ompl::base;

namespace michi
{
    namespace tools
    {
        namespace
        {
            using Clock = std::chrono::steady_clock;

            std::string readText(const fs::path &file)
            {
                std::ifstream in(file.string());
                std::stringstream s;
                s << in.rdbuf();
                return s.str();
            }

            /** "1m05s" */
            std::string duration(double seconds)
            {
                const long s = static_cast<long>(seconds + 0.5);
                std::ostringstream out;
                if (s >= 3600)
                    out << s / 3600 << "h" << std::setw(2) << std::setfill('0') << (s / 60) % 60 << "m";
                else if (s >= 60)
                    out << s / 60 << "m" << std::setw(2) << std::setfill('0') << s % 60 << "s";
                else
                    out << s << "s";
                return out.str();
            }

            /** The text file \e file must hold \e text: written when missing, compared otherwise. */
            void claim(const fs::path &file, const std::string &text, const std::string &what)
            {
                if (!fs::exists(file))
                {
                    writeAtomically(text, file.string());
                    return;
                }
                const std::string held = readText(file);
                if (held != text)
                    // A folder belongs to one campaign plan and one shard: resuming it with another would mix records
                    // of different units, or of other settings, under the same ids.
                    throw std::runtime_error(file.string() + ": the folder holds " + what +
                                             " (the folder's against this run's, " + planDifference(held, text) +
                                             "; resume with the same campaign file and --shard, or use another "
                                             "--out)");
            }

            struct Child
            {
                int status{0};
                bool killed{false};
                double seconds{0.};
            };

            /** fork + exec \e argv with stdout and stderr to \e errFile; wait, killing it past \e deadline s */
            Child runChild(const std::vector<std::string> &argv, const fs::path &errFile, double deadline)
            {
                std::vector<char *> args;
                for (const auto &a : argv)
                    args.push_back(const_cast<char *>(a.c_str()));
                args.push_back(nullptr);
                const auto start = Clock::now();
                const pid_t parent = getpid();
                const pid_t pid = fork();
                if (pid < 0)
                    throw std::runtime_error(std::string("cannot start a unit's process: ") + std::strerror(errno));
                if (pid == 0)
                {
                    // only async-signal-safe calls between fork and exec. The unit dies with its shard: a shard
                    // killed by a signal (kill, the OOM killer) can no longer kill a hung unit at its deadline, which
                    // would then spin on a core for ever. If the shard died before this line, exit at once.
                    prctl(PR_SET_PDEATHSIG, SIGKILL);
                    if (getppid() != parent)
                        _exit(126);
                    const int fd = open(errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
                    if (fd >= 0)
                    {
                        dup2(fd, 1);
                        dup2(fd, 2);
                        close(fd);
                    }
                    execv(args[0], args.data());
                    _exit(127);
                }
                Child child;
                for (;;)
                {
                    // Polled rather than blocking in waitpid(): the parent has to notice the deadline of a child that
                    // never returns.
                    const pid_t done = waitpid(pid, &child.status, WNOHANG);
                    child.seconds = std::chrono::duration<double>(Clock::now() - start).count();
                    if (done == pid)
                        break;
                    if (done < 0 && errno != EINTR)
                        throw std::runtime_error(std::string("waiting for a unit's process: ") + std::strerror(errno));
                    if (!child.killed && child.seconds > deadline)
                    {
                        // SIGKILL, not SIGTERM: a hung planner may ignore or never reach a polite request, and the
                        // shard must go on.
                        kill(pid, SIGKILL);
                        child.killed = true;
                    }
                    std::this_thread::sleep_for(std::chrono::milliseconds(5));
                }
                return child;
            }

            /** An exclusive lock on a shard folder for as long as a run works in it: two runs into one folder would
                run the same units and remove each other's scratch files. The kernel drops the lock when the process
                ends, however it ends, so a killed shard never leaves the folder locked. */
            class FolderLock
            {
            public:
                explicit FolderLock(const fs::path &folder)
                {
                    const std::string file = (folder / ".lock").string();
                    fd_ = open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
                    if (fd_ < 0)
                        throw std::runtime_error(file + ": cannot open the folder's lock: " + std::strerror(errno));
                    if (flock(fd_, LOCK_EX | LOCK_NB) != 0)
                    {
                        close(fd_);
                        throw std::runtime_error(folder.string() +
                                                 ": another `michi campaign run` is working in this folder (wait for "
                                                 "it, or use another --out)");
                    }
                }
                ~FolderLock()
                {
                    close(fd_);  // releases the lock
                }
                FolderLock(const FolderLock &) = delete;
                FolderLock &operator=(const FolderLock &) = delete;

            private:
                int fd_{-1};
            };

            /** the properties a run that never returned gets, so the log and database count it as a failed run */
            void failedRun(UnitRecord &r, const std::string &outcome, ob::PlannerStatus::StatusType status)
            {
                r.outcome = outcome;
                // A timeout is recorded at the time limit, not at the kill (limit + hang margin), so it compares
                // with runs that stopped on their own; a crash counts the time until it died.
                r.properties["time REAL"] = std::to_string(outcome == "timeout" ? r.timeLimit : r.wallTime);
                r.properties["solved BOOLEAN"] = "0";
                r.properties["status ENUM"] = std::to_string(static_cast<int>(status));
                r.properties["unit INTEGER"] = std::to_string(r.id);
                r.properties["seed INTEGER"] = std::to_string(r.seed);
                r.properties["query INTEGER"] = std::to_string(r.query);
                r.properties["checker VARCHAR(16)"] = r.checker;
                r.properties["outcome VARCHAR(16)"] = outcome;
                r.properties["crash_signal INTEGER"] = std::to_string(r.signal);
                r.properties["certified_paths INTEGER"] = "0";
            }
        }  // namespace

        void checkCampaignPlanners(const Campaign &campaign)
        {
            const DatasetEntry *first = nullptr;
            for (const auto &d : campaign.datasets)
                if (!d.entries.empty())
                {
                    first = &d.entries.front();
                    break;
                }
            if (first == nullptr)
                throw ProblemError(campaign.file, "problems", "the campaign selects no query");
            const Problem problem = loadProblem(first->problemFile);
            ContextOptions options;
            options.query = first->query;
            // One context is enough to check names and parameters: every planner is allocated here, in this process, so
            // a typo fails the shard before the first unit instead of failing every unit in its child.
            const PlanningContext ctx = makePlanningContext(problem, options);
            for (std::size_t i = 0; i < campaign.planners.size(); ++i)
            {
                const CampaignPlanner &p = campaign.planners[i];
                const std::string key = "planners[" + std::to_string(i) + "]";
                try
                {
                    auto planner = allocatePlanner(p.name, ctx.setup->getSpaceInformation());
                    applyPlannerParams(*planner, PlannerSpec{p.name, p.params, {}}, campaign.file);
                }
                catch (const ProblemError &e)
                {
                    // applyPlannerParams() names "planners.<name>.params.<param>" of a problem file; here the
                    // parameter is under this configuration's key of the campaign file
                    const std::string what = e.what();
                    const std::string prefix = e.file() + ": " + e.key() + ": ";
                    const auto param = e.key().find(".params.");
                    throw ProblemError(campaign.file,
                                       key + ".params" + (param == std::string::npos ? "" : e.key().substr(param + 7)),
                                       what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
                }
                catch (const std::invalid_argument &e)
                {
                    throw ProblemError(campaign.file, key, e.what());
                }
            }
        }

        UnitRecord unitSpec(const Campaign &campaign, const WorkUnit &unit, const std::string &michiVersion)
        {
            const CampaignPlanner &p = campaign.planners.at(unit.planner);
            UnitRecord r;
            r.id = unit.id;
            r.campaign = campaign.name;
            r.dataset = unit.dataset;
            r.problem = unit.entry.problemName;
            r.problemFile = unit.entry.problemFile;
            r.query = unit.entry.query;
            r.queryLabel = unit.entry.label;
            r.plannerName = unitPlannerName(campaign, unit);
            r.plannerLabel = p.label;
            r.planner = p.name;
            r.params = p.params;
            r.checker = unit.checker;
            r.run = unit.run;
            r.seed = unit.seed;
            r.timeLimit = campaign.timeLimit;
            r.michiVersion = michiVersion;
            r.outcome = "pending";
            return r;
        }

        ShardResult runShard(const Campaign &campaign, const ShardOptions &options)
        {
            const auto units = planUnits(campaign);
            const auto share = shardUnits(units, options.shard, options.shards);
            const fs::path out = fs::absolute(options.outDir);
            fs::create_directories(out);
            const FolderLock lock(out);
            claim(out / "campaign.plan", planText(campaign, units), "another campaign's units or settings");
            claim(out / "shard", std::to_string(options.shard) + "/" + std::to_string(options.shards) + "\n",
                  "another shard");
            // after the claims: a refused run leaves no work folders behind (the lock file stays, hidden)
            fs::create_directories(out / "units");
            fs::create_directories(out / "work");

            ShardResult result;
            result.units = share.size();
            std::vector<const WorkUnit *> todo;
            for (const auto &u : share)
            {
                const fs::path done = out / "units" / (std::to_string(u.id) + ".run");
                bool finished = false;
                if (fs::exists(done))
                {
                    try
                    {
                        // Records are written atomically, so a record that reads back is whole; one that does not is
                        // run again.
                        finished = readUnitRecord(done.string()).id == u.id;
                    }
                    catch (const std::runtime_error &)
                    {
                        finished = false;  // unreadable: run it again
                    }
                }
                if (finished)
                    ++result.skipped;
                else
                    todo.push_back(&u);
            }
            std::ostream *progress = options.progress;
            const std::string prefix =
                "michi campaign: shard " + std::to_string(options.shard) + "/" + std::to_string(options.shards) + ": ";
            if (progress)
                *progress << prefix << share.size() << " of " << units.size() << " units, " << result.skipped
                          << " already done, " << todo.size() << " to run" << std::endl;
            const auto start = Clock::now();
            for (const WorkUnit *u : todo)
            {
                const std::string id = std::to_string(u->id);
                const fs::path specFile = out / "work" / (id + ".spec");
                const fs::path errFile = out / "work" / (id + ".err");
                const fs::path runFile = out / "units" / (id + ".run");
                UnitRecord record = unitSpec(campaign, *u, options.michiVersion);
                // The child reads its unit from this file and writes its record itself: the parent writes one only for
                // a child that never did (crash, hang, error).
                writeUnitRecord(record, specFile.string());
                const Child child =
                    runChild({options.michiBinary, "campaign", "unit", specFile.string(), runFile.string()}, errFile,
                             campaign.timeLimit + campaign.hangMargin);
                record.wallTime = child.seconds;
                bool ok = false;
                if (!child.killed && WIFEXITED(child.status) && WEXITSTATUS(child.status) == 0 && fs::exists(runFile))
                    ok = true;
                else if (child.killed)
                {
                    record.cause = "killed after " + duration(child.seconds) + " (time limit " +
                                   std::to_string(campaign.timeLimit) + " s + hang margin " +
                                   std::to_string(campaign.hangMargin) + " s)";
                    failedRun(record, "timeout", ob::PlannerStatus::TIMEOUT);
                }
                else if (WIFSIGNALED(child.status))
                {
                    record.signal = WTERMSIG(child.status);
                    const char *abbrev = sigabbrev_np(record.signal);  // null for a number glibc does not name
                    record.cause = (abbrev ? std::string("SIG") + abbrev : std::string("a signal")) + " (signal " +
                                   std::to_string(record.signal) + ")";
                    failedRun(record, "crash", ob::PlannerStatus::CRASH);
                }
                else
                {
                    const std::string why = lastLine(errFile.string());
                    record.cause = why.empty() ? "exit status " + std::to_string(WEXITSTATUS(child.status)) : why;
                    failedRun(record, "error", ob::PlannerStatus::ABORT);
                }
                if (!ok)
                {
                    writeUnitRecord(record, runFile.string());
                    ++result.failed;
                }
                fs::remove(specFile);
                fs::remove(errFile);
                ++result.ran;
                if (progress)
                {
                    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
                    const std::size_t done = result.skipped + result.ran;
                    const double left = elapsed / result.ran * (todo.size() - result.ran);
                    *progress << prefix << "[" << done << "/" << share.size() << "] " << result.failed << " failed, "
                              << duration(left) << " left; unit " << id << " " << record.plannerName << " on "
                              << record.queryLabel << ": " << (ok ? "done" : record.outcome + ": " + record.cause)
                              << std::endl;
                }
            }
            // Only scratch files live here; the records in units/ are what resume and merge read.
            fs::remove_all(out / "work");
            return result;
        }
    }  // namespace tools
}  // namespace michi
