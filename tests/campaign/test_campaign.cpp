// `michi campaign` as a user runs it: the plan lists every work unit; shards merged give the same runs as one
// unsharded run (each unit seeded from the campaign seed and its id, so even the paths agree); a shard killed midway
// resumes without losing or rerunning a finished unit; a planner that segfaults or hangs costs failed runs that
// record the signal or the timeout, and the campaign finishes. Bad campaign files name the file and key.
#include "support/MichiCommand.h"

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = boost::filesystem;

namespace
{
    using michi::test::CommandRun;
    using michi::test::problemFile;
    using michi::test::runMichi;
    using michi::test::slurp;

    /** what a shell command prints (stdout and stderr) */
    std::string shell(const std::string &command)
    {
        std::string out;
        FILE *pipe = popen(command.c_str(), "r");
        if (pipe == nullptr)
            return "popen failed";
        std::array<char, 4096> buffer{};
        std::size_t n;
        while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
            out.append(buffer.data(), n);
        pclose(pipe);
        return out;
    }

    /** the rows of an SQLite query, "a|b" per row (Debian's sqlite3 command) */
    std::string sql(const fs::path &db, const std::string &query)
    {
        return shell("sqlite3 '" + db.string() + "' \"" + query + "\" 2>&1");
    }

    std::size_t lines(const std::string &text)
    {
        std::size_t n = 0;
        std::istringstream in(text);
        std::string l;
        while (std::getline(in, l))
            n += !l.empty();
        return n;
    }

    /** every unit record of a shard folder, by file name */
    std::map<std::string, std::string> records(const fs::path &dir)
    {
        std::map<std::string, std::string> r;
        if (fs::is_directory(dir / "units"))
            for (const auto &e : fs::directory_iterator(dir / "units"))
                if (e.path().extension() == ".run")
                    r[e.path().filename().string()] = slurp(e.path());
        return r;
    }

    class Campaign : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            // the planners that crash and hang on purpose exist only with this (PlannerRegistry.h)
            setenv("MICHI_TEST_PLANNERS", "1", 1);
            dir_ = fs::temp_directory_path() / fs::unique_path("michi-campaign-%%%%%%%%");
            fs::create_directories(dir_);
        }
        void TearDown() override
        {
            fs::remove_all(dir_);
        }

        fs::path write(const std::string &name, const std::string &text)
        {
            const fs::path p = dir_ / name;
            std::ofstream(p.string()) << text;
            return p;
        }

        /** planar_2link and se2_corridor x RRTConnect and \e second x 2 runs: 8 units */
        fs::path smallCampaign(const std::string &second, const std::string &extra = "")
        {
            return write("small.yaml", "name: small\nseed: 11\ntime_limit: 1\nruns: 2\n" + extra + "problems:\n  - " +
                                           problemFile("planar_2link") + "\n  - " + problemFile("se2_corridor") +
                                           "\nplanners:\n  - geometric::RRTConnect\n  - " + second +
                                           "\ncheckers: [fcl]\n");
        }

        fs::path dir_;
    };
}  // namespace

TEST_F(Campaign, PlanPrintsOneLinePerUnitWithDistinctSeeds)
{
    const fs::path file = smallCampaign("geometric::PRM");
    const CommandRun run = runMichi("campaign plan " + file.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_EQ(lines(run.output), 8u) << run.output;
    std::map<std::string, int> seeds;
    std::istringstream in(run.output);
    std::string l;
    while (std::getline(in, l))
        ++seeds[l.substr(l.rfind("seed "))];
    EXPECT_EQ(seeds.size(), 8u) << run.output;
    // --seed changes every unit's seed, and the same seed gives the same plan
    EXPECT_NE(runMichi("campaign plan --seed 12 " + file.string()).output, run.output);
    EXPECT_EQ(runMichi("campaign plan --seed 11 " + file.string()).output, run.output);
}

TEST_F(Campaign, DatasetFoldersAndQuerySelectionsMakeTheirUnits)
{
    // a dataset folder (100 MotionBenchMaker problems) and 3 MovingAI scenario queries of one problem, 2 planners,
    // 2 checkers: (100 + 3) x 2 x 2 units
    const fs::path file = write(
        "datasets.yaml", "problems:\n  - {file: " + problemFile("movingai_arena") + ", queries: 0-2}\ndatasets:\n  - " +
                             (fs::path(MICHI_SOURCE_DIR) / "problems" / "datasets" / "table_pick").string() +
                             "\nplanners: [geometric::RRTConnect, geometric::PRM]\ncheckers: [problem, fcl]\n");
    const CommandRun run = runMichi("campaign plan " + file.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_EQ(lines(run.output), 412u);
    EXPECT_NE(run.output.find("\tmovingai_arena[0-2]\t"), std::string::npos) << run.output.substr(0, 400);
    EXPECT_NE(run.output.find("\ttable_pick\t"), std::string::npos);
    EXPECT_NE(run.output.find("table_pick_0100.yaml#0\tgeometric::PRM\tfcl\trun 0"), std::string::npos);
}

TEST_F(Campaign, BadCampaignFileNamesFileAndKeyAndWritesNothing)
{
    const fs::path bad = write("bad.yaml", "name: bad\nproblems: [" + problemFile("planar_2link") +
                                               "]\nplanners:\n  - {name: geometric::RRTConnect, rnage: 1}\n");
    const fs::path out = dir_ / "out";
    CommandRun run = runMichi("campaign run " + bad.string() + " --out " + out.string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find(bad.string() + ": planners[0].rnage: unknown key"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out));

    const fs::path unknown = write(
        "unknown.yaml", "problems: [" + problemFile("planar_2link") + "]\nplanners: [geometric::NoSuchPlanner]\n");
    run = runMichi("campaign plan " + unknown.string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find("planners[0]: unknown planner 'geometric::NoSuchPlanner'"), std::string::npos)
        << run.output;

    const fs::path param = write("param.yaml", "problems: [" + problemFile("planar_2link") +
                                                   "]\nplanners:\n  - {name: geometric::RRTConnect, params: "
                                                   "{no_such_param: 1}}\n");
    run = runMichi("campaign run " + param.string() + " --out " + out.string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find(param.string() + ": planners[0].params"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out / "units"));

    run = runMichi("campaign run " + param.string() + " --shard 5/4 --out " + out.string());
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(run.output.find("--shard: expected K/N"), std::string::npos) << run.output;

    // the J-map cannot check an SE(2) robot: said before any unit runs (each unit used to fail at run time while
    // the campaign exited 0)
    const fs::path jmap = write("jmap.yaml", "problems: [" + problemFile("se2_corridor") +
                                                 "]\nplanners: [geometric::RRTConnect]\ncheckers: [fcl, jmap]\n");
    run = runMichi("campaign run " + jmap.string() + " --out " + out.string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find(jmap.string() + ": checkers[1]: checker 'jmap' cannot check"), std::string::npos)
        << run.output;
    EXPECT_FALSE(fs::exists(out / "units"));

    // a tab in a label: `run` took it and `merge` then found the tab-separated plan file broken
    const fs::path tab = write("tab.yaml", "problems: [" + problemFile("planar_2link") +
                                               "]\nplanners:\n  - {label: \"a\\tb\", name: geometric::RRTConnect}\n");
    run = runMichi("campaign run " + tab.string() + " --out " + out.string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find(tab.string() + ": planners[0].label: must not hold"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(out / "units"));

    // found by the campaign sweep of 2026-12-07: a problem listed twice became two "run 0" units of one experiment,
    // and two problem files of one name two experiments of that name, which Planner Arena pools
    const fs::path twice =
        write("twice.yaml", "problems: [" + problemFile("planar_2link") + ", " + problemFile("planar_2link") +
                                "]\nplanners: [geometric::RRTConnect]\n");
    run = runMichi("campaign plan " + twice.string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find(twice.string() + ": problems[1]: query 0 of"), std::string::npos) << run.output;
    fs::copy_file(problemFile("planar_2link"), dir_ / "copy.yaml");
    std::string copy = slurp(dir_ / "copy.yaml");
    // the copy's paths (the URDF) are relative to the problem file: point them back at the bundled robots
    copy = std::regex_replace(copy, std::regex("robots/"), (fs::path(MICHI_SOURCE_DIR) / "problems/robots/").string());
    write("copy.yaml", copy);
    const fs::path named =
        write("named.yaml", "problems: [" + problemFile("planar_2link") + ", " + (dir_ / "copy.yaml").string() +
                                "]\nplanners: [geometric::RRTConnect]\n");
    run = runMichi("campaign plan " + named.string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find("are both named 'planar_2link'"), std::string::npos) << run.output;
}

TEST_F(Campaign, FourShardsMergeIntoTheUnshardedRunsAndSegfaultsAreFailedRuns)
{
    const fs::path file = smallCampaign("test::Segfault");
    std::string shards;
    for (int k = 1; k <= 4; ++k)
    {
        const fs::path out = dir_ / ("s" + std::to_string(k));
        const CommandRun run =
            runMichi("campaign run " + file.string() + " --shard " + std::to_string(k) + "/4 --out " + out.string());
        ASSERT_EQ(run.exitCode, 0) << run.output;
        EXPECT_EQ(records(out).size(), 2u) << run.output;
        shards += " " + out.string();
    }
    CommandRun merged = runMichi("campaign merge" + shards + " --out " + (dir_ / "merged").string());
    ASSERT_EQ(merged.exitCode, 0) << merged.output;
    const fs::path whole = dir_ / "whole";
    CommandRun run = runMichi("campaign run " + file.string() + " --out " + whole.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    run = runMichi("campaign merge " + whole.string() + " --out " + (dir_ / "whole-merged").string());
    ASSERT_EQ(run.exitCode, 0) << run.output;

    const fs::path a = dir_ / "merged" / "campaign.db", b = dir_ / "whole-merged" / "campaign.db";
    EXPECT_EQ(sql(a, "select count(*) from runs"), "8\n");
    const std::string perPlanner =
        "select p.name, count(*), sum(r.solved), group_concat(r.outcome) from runs r join "
        "plannerConfigs p on r.plannerid = p.id group by p.name order by p.name";
    EXPECT_EQ(sql(a, perPlanner), sql(b, perPlanner));
    EXPECT_EQ(sql(a, perPlanner),
              "geometric::RRTConnect|4|4|done,done,done,done\ntest::Segfault|4|0|crash,crash,crash,crash\n");
    // the crashed units carry their signal; every unit its own seed, the checker and its check counts
    EXPECT_EQ(sql(a, "select count(*) from runs where outcome = 'crash' and crash_signal = 11"), "4\n");
    EXPECT_EQ(sql(a, "select count(distinct seed) from runs"), "8\n");
    EXPECT_EQ(sql(a,
                  "select count(*) from runs where outcome = 'done' and checker = 'fcl' and validity_checks > 0 "
                  "and motion_checks > 0 and length(path) > 0"),
              "4\n");
    // a unit's seed fixes its run: the same paths whichever shard ran it
    const std::string paths = "select unit, path from runs where outcome = 'done' order by unit";
    EXPECT_EQ(sql(a, paths), sql(b, paths));
    EXPECT_EQ(sql(a, "select count(*) from experiments where michi_version like '0.%(git %)'"), "2\n");
    // one OMPL log per problem, and a summary with both planners and the crash
    EXPECT_TRUE(fs::exists(dir_ / "merged" / "logs" / "planar_2link.log"));
    EXPECT_TRUE(fs::exists(dir_ / "merged" / "logs" / "se2_corridor.log"));
    const std::string summary = slurp(dir_ / "merged" / "summary.md");
    EXPECT_NE(summary.find("| geometric::RRTConnect | 4 | 4 (100 %) | 0 |"), std::string::npos) << summary;
    EXPECT_NE(summary.find("| test::Segfault | 4 | 0 (0 %) | 4 |"), std::string::npos) << summary;
    EXPECT_NE(summary.find("crash SIGSEGV (signal 11)"), std::string::npos) << summary;

    // a plan cut short (a full disk, a copy stopped half way) is named as such; before, its records read as units of
    // another campaign ("unit 2 is not in the campaign's plan")
    const fs::path cut = dir_ / "cut";
    fs::create_directories(cut / "units");
    for (const auto &e : fs::directory_iterator(whole / "units"))
        fs::copy_file(e.path(), cut / "units" / e.path().filename());
    const std::string plan = slurp(whole / "campaign.plan");
    write("cut/campaign.plan", plan.substr(0, plan.find('\n', plan.size() / 2) + 3));  // inside a unit line
    run = runMichi("campaign merge " + cut.string() + " --out " + (dir_ / "cut-merged").string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find("campaign.plan"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("truncated"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir_ / "cut-merged"));
}

TEST_F(Campaign, KilledShardResumesWithoutLosingAFinishedUnit)
{
    // test::Hang never returns: each of its units is killed at time limit + hang margin and recorded as a timeout
    const fs::path file = smallCampaign("test::Hang", "hang_margin: 1\n");
    const fs::path out = dir_ / "shard";
    const std::string michi = std::string(MICHI_BINARY_DIR) + "/bin/michi";
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0)
    {
        setpgid(0, 0);  // the shard and its unit processes in one group, killed together as by Ctrl-C or scancel
        if (freopen("/dev/null", "w", stderr) == nullptr)
            _exit(126);
        execl(michi.c_str(), michi.c_str(), "campaign", "run", file.c_str(), "--out", out.c_str(), nullptr);
        _exit(127);
    }
    // kill the shard's process as soon as it has finished a unit (no timing: it waits for the file)
    while (records(out).empty())
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    kill(-pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status));
    const auto before = records(out);
    ASSERT_FALSE(before.empty());

    const CommandRun run = runMichi("campaign run " + file.string() + " --out " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const auto after = records(out);
    EXPECT_EQ(after.size(), 8u) << run.output;
    for (const auto &kv : before)
    {
        ASSERT_TRUE(after.count(kv.first)) << kv.first;
        EXPECT_EQ(after.at(kv.first), kv.second) << kv.first << " was run again";
    }
    EXPECT_NE(run.output.find(std::to_string(before.size()) + " already done"), std::string::npos) << run.output;

    const CommandRun merged = runMichi("campaign merge " + out.string() + " --out " + (dir_ / "merged").string());
    ASSERT_EQ(merged.exitCode, 0) << merged.output;
    const fs::path db = dir_ / "merged" / "campaign.db";
    EXPECT_EQ(sql(db, "select count(*) from runs"), "8\n");
    EXPECT_EQ(sql(db, "select count(*) from runs where outcome = 'timeout' and solved = 0"), "4\n");
}

TEST_F(Campaign, ShardsRunWithOtherSettingsAreNeverMixedAndProgressIsKept)
{
    // Found by the campaign sweep of 2026-12-07: the plan held neither the time limit nor the planners' parameters,
    // so shards run before and after an edit of the campaign file merged into one database under the later settings
    // (and a resume mixed them in one folder); and the database's progress table stayed empty.
    const std::string head = "name: edited\nseed: 3\nruns: 2\nproblems: [" + problemFile("planar_2link") +
                             "]\ncheckers: [fcl]\nplanners:\n  - {name: geometric::RRTstar, params: {range: ";
    const fs::path file = write("edited.yaml", "time_limit: 0.2\n" + head + "0.3}}\n");
    const fs::path s1 = dir_ / "s1", s2 = dir_ / "s2";
    CommandRun run = runMichi("campaign run " + file.string() + " --shard 1/2 --out " + s1.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    write("edited.yaml", "time_limit: 0.1\n" + head + "0.3}}\n");
    run = runMichi("campaign run " + file.string() + " --shard 2/2 --out " + s2.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    run = runMichi("campaign merge " + s1.string() + " " + s2.string() + " --out " + (dir_ / "m").string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find("'# time_limit 0.1' against '# time_limit 0.2'"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir_ / "m"));
    // resuming shard 1 with a planner parameter changed is refused, naming the line
    write("edited.yaml", "time_limit: 0.2\n" + head + "2}}\n");
    run = runMichi("campaign run " + file.string() + " --shard 1/2 --out " + s1.string());
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find("range=0.3"), std::string::npos) << run.output;

    // shard 1 alone, with a folder that never got a plan (a Slurm task cancelled while pending): merged, the
    // missing folder named and its units counted missing; RRT*'s progress reaches the database
    fs::create_directories(dir_ / "never");
    run = runMichi("campaign merge " + s1.string() + " " + (dir_ / "never").string() + " --out " +
                   (dir_ / "m1").string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("never: no campaign.plan"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("1 of 2 units have no result"), std::string::npos) << run.output;
    const fs::path db = dir_ / "m1" / "campaign.db";
    EXPECT_EQ(sql(db, "select count(*) from runs"), "1\n");
    EXPECT_NE(sql(db, "select count(*) > 0 from progress p join runs r on p.runid = r.id where p.best_cost > 0"),
              "0\n");
    EXPECT_EQ(sql(db, "select count(*) from enums where name = 'status' and description = 'Abort'"), "1\n");
}

TEST_F(Campaign, OneRunWorksInAShardFolderAndItsUnitsDieWithIt)
{
    const fs::path file = smallCampaign("test::Hang", "hang_margin: 100\n");
    const fs::path out = dir_ / "shard";
    fs::create_directories(out);
    {
        // another run holds the folder: refused at once, not run twice (the second run's scratch files were removed
        // under it)
        const int fd = open((out / ".lock").c_str(), O_RDWR | O_CREAT, 0644);
        ASSERT_GE(fd, 0);
        ASSERT_EQ(flock(fd, LOCK_EX), 0);
        const CommandRun run = runMichi("campaign run " + file.string() + " --out " + out.string());
        EXPECT_EQ(run.exitCode, 1) << run.output;
        EXPECT_NE(run.output.find("another `michi campaign run` is working in this folder"), std::string::npos)
            << run.output;
        EXPECT_FALSE(fs::exists(out / "units"));
        close(fd);
    }
    // A shard killed on its own (kill, the OOM killer) left its unit running: a hung planner spun for ever. Now the
    // unit gets SIGKILL when its shard dies.
    const std::string michi = std::string(MICHI_BINARY_DIR) + "/bin/michi";
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0)
    {
        if (freopen("/dev/null", "w", stderr) == nullptr)
            _exit(126);
        execl(michi.c_str(), michi.c_str(), "campaign", "run", file.c_str(), "--out", out.c_str(), nullptr);
        _exit(127);
    }
    // the units run in plan order: the first test::Hang unit is unit 2 (planner 1 of problem 0, run 0)
    auto unitAlive = [&]
    {
        // a process whose command line names the unit's spec (read from /proc: no procps needed; a zombie's command
        // line is empty, so a killed unit not yet reaped counts as gone)
        const std::string spec = (out / "work" / "2.spec").string();
        for (const auto &e : fs::directory_iterator("/proc"))
        {
            const std::string pid = e.path().filename().string();
            if (pid.find_first_not_of("0123456789") != std::string::npos)
                continue;
            std::ifstream in((e.path() / "cmdline").string(), std::ios::binary);
            const std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            if (cmdline.find(spec) != std::string::npos)
                return true;
        }
        return false;
    };
    for (int i = 0; i < 6000 && !unitAlive(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(unitAlive());
    kill(pid, SIGKILL);  // the shard only, not its group
    int status = 0;
    waitpid(pid, &status, 0);
    // an event to wait for, with a bound far above the kernel's few milliseconds, not a timing
    for (int i = 0; i < 3000 && unitAlive(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_FALSE(unitAlive());
}

TEST_F(Campaign, CopiesOfOneCampaignFileWriteTheSamePlan)
{
    // Found by the campaign sweep of 2026-12-07: problems named by absolute paths were written into the plan relative
    // to the campaign file, so two copies of one file in different folders made "different campaigns".
    const std::string text = "name: copies\nseed: 2\ntime_limit: 0.5\nruns: 2\nproblems: [" +
                             problemFile("planar_2link") + "]\nplanners: [geometric::RRTConnect]\ncheckers: [fcl]\n";
    fs::create_directories(dir_ / "a");
    fs::create_directories(dir_ / "b" / "deeper");
    const fs::path a = write("a/c.yaml", text), b = write("b/deeper/c.yaml", text);
    ASSERT_EQ(runMichi("campaign run " + a.string() + " --shard 1/2 --out " + (dir_ / "s1").string()).exitCode, 0);
    ASSERT_EQ(runMichi("campaign run " + b.string() + " --shard 2/2 --out " + (dir_ / "s2").string()).exitCode, 0);
    const CommandRun run = runMichi("campaign merge " + (dir_ / "s1").string() + " " + (dir_ / "s2").string() +
                                    " --out " + (dir_ / "m").string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_EQ(sql(dir_ / "m" / "campaign.db", "select count(*) from runs"), "2\n");
}
