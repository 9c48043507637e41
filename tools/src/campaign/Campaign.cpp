// The campaign file reader and the work-unit plan. Read with the problem loader's Reader (problem/ProblemYaml.h), so
// a mistake is reported exactly like one in a problem file: "<file>: <key>: <what was expected>".
#include <michi/tools/campaign/Campaign.h>
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/tools/bench/PlanningContext.h>

#include "problem/ProblemYaml.h"

#include <boost/filesystem.hpp>

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace
        {
            using problem_file::Reader;

            std::string normalised(const std::string &file)
            {
                return fs::absolute(fs::path(file)).lexically_normal().string();
            }

            /** a problem file as the plan names it: relative to the campaign file, unless the campaign file gave it
                (or its dataset folder) by an absolute path */
            std::string planPath(const Campaign &campaign, const std::string &file)
            {
                const std::string problem = normalised(file);
                if (campaign.absoluteFiles.count(problem))
                    return problem;
                const fs::path folder = fs::absolute(fs::path(campaign.file)).parent_path().lexically_normal();
                return fs::path(problem).lexically_relative(folder).string();
            }

            /** the fewest digits (up to 17) that read back as the same double: 0.05, not 0.050000000000000003 */
            std::string shortestText(double v)
            {
                for (int digits = 15;; ++digits)
                {
                    std::ostringstream out;
                    out << std::setprecision(digits) << v;
                    if (digits == 17 || std::stod(out.str()) == v)
                        return out.str();
                }
            }

            /** FNV-1a over the file's bytes, in hex: enough to see that a problem file was edited between shards */
            std::string contentHash(const std::string &file)
            {
                std::ifstream in(file, std::ios::binary);
                std::uint64_t h = 14695981039346656037ULL;
                char c;
                while (in.get(c))
                {
                    h ^= static_cast<unsigned char>(c);
                    h *= 1099511628211ULL;
                }
                std::ostringstream out;
                out << std::hex << std::setw(16) << std::setfill('0') << h;
                return out.str();
            }

            /** "all", "A-B" or "A" under \e key, as a selection */
            QuerySelection selection(const Reader &r, const YAML::Node &n, const std::string &key)
            {
                try
                {
                    return parseQuerySelection(r.text(n, key));
                }
                catch (const std::invalid_argument &e)
                {
                    r.fail(key, e.what());
                }
            }

            /** problems: a list of files, or {file, queries}: each a dataset of its own queries (default: the
                problem's benchmark.queries, else its query 0, as `michi bench` plans) */
            void readProblems(const Reader &r, const YAML::Node &list, Campaign &c)
            {
                if (!list)
                    return;
                if (!list.IsSequence())
                    r.fail("problems", "expected a list of problem files or {file, queries}");
                for (std::size_t i = 0; i < list.size(); ++i)
                {
                    const std::string key = "problems[" + std::to_string(i) + "]";
                    const YAML::Node n = list[i];
                    std::string queries;
                    if (n.IsMap())
                    {
                        r.keys(n, key, {"file", "queries"});
                        r.require(n, "file", key);
                        if (n["queries"])
                            queries = key + ".queries";
                    }
                    // built once, never assigned: yaml-cpp's Node::operator= would overwrite the node it refers to
                    const YAML::Node fileNode = n.IsMap() ? n["file"] : n;
                    const std::string fileKey = n.IsMap() ? key + ".file" : key;
                    const std::string file = r.path(fileNode, fileKey);
                    if (fs::path(r.text(fileNode, fileKey)).is_absolute())
                        c.absoluteFiles.insert(normalised(file));
                    // Loaded (and so checked) now: a bad problem stops the campaign before its first unit, not in the
                    // middle.
                    const Problem problem = loadProblem(file);
                    QuerySelection s;
                    if (!queries.empty())
                        s = selection(r, n["queries"], queries);
                    else if (!problem.benchmark.queries.empty())
                        s = parseQuerySelection(problem.benchmark.queries);
                    else
                        s = QuerySelection{false, 0, 0};
                    try
                    {
                        c.datasets.push_back(datasetOf(problem, s));
                        if (queries.empty())
                            c.datasets.back().name = problem.name;  // not "name[0-0]" for its one query
                    }
                    catch (const ProblemError &e)
                    {
                        r.fail(queries.empty() ? fileKey : queries, e.what());
                    }
                }
            }

            /** datasets: a list of folders, or {folder, queries} (default: every query of every file) */
            void readDatasets(const Reader &r, const std::string &file, const YAML::Node &list, Campaign &c)
            {
                if (!list)
                    return;
                if (!list.IsSequence())
                    r.fail("datasets", "expected a list of folders of problem files or {folder, queries}");
                for (std::size_t i = 0; i < list.size(); ++i)
                {
                    const std::string key = "datasets[" + std::to_string(i) + "]";
                    const YAML::Node n = list[i];
                    QuerySelection s;
                    if (n.IsMap())
                    {
                        r.keys(n, key, {"folder", "queries"});
                        r.require(n, "folder", key);
                        if (n["queries"])
                            s = selection(r, n["queries"], key + ".queries");
                    }
                    const YAML::Node folderNode = n.IsMap() ? n["folder"] : n;
                    const std::string folderKey = n.IsMap() ? key + ".folder" : key;
                    // relative to the campaign file, as Reader::path() resolves files
                    const fs::path given(r.text(folderNode, folderKey));
                    const fs::path full = given.is_absolute() ? given : fs::path(file).parent_path() / given;
                    if (!fs::is_directory(full))
                        r.fail(folderKey, "'" + full.string() + "' is not a folder of problem files");
                    const std::string folder = full.lexically_normal().string();
                    try
                    {
                        c.datasets.push_back(loadDatasetFolder(folder, s));
                        if (given.is_absolute())
                            for (const auto &entry : c.datasets.back().entries)
                                c.absoluteFiles.insert(normalised(entry.problemFile));
                    }
                    catch (const ProblemError &)
                    {
                        throw;  // names the problem file and key
                    }
                    catch (const std::runtime_error &e)
                    {
                        r.fail(folderKey, e.what());
                    }
                }
            }

            void readPlanners(const Reader &r, const YAML::Node &list, Campaign &c)
            {
                if (!list || !list.IsSequence() || list.size() == 0)
                    r.fail("planners", "expected a non-empty list of planner names or {label, name, params}");
                std::set<std::string> labels;
                for (std::size_t i = 0; i < list.size(); ++i)
                {
                    const std::string key = "planners[" + std::to_string(i) + "]";
                    CampaignPlanner p;
                    if (list[i].IsScalar())
                        p.name = list[i].Scalar();
                    else if (list[i].IsMap())
                    {
                        r.keys(list[i], key, {"label", "name", "params"});
                        p.name = r.text(r.require(list[i], "name", key), key + ".name");
                        if (list[i]["label"])
                            p.label = r.text(list[i]["label"], key + ".label");
                        if (const YAML::Node params = list[i]["params"])
                        {
                            if (!params.IsMap())
                                r.fail(key + ".params", "expected a mapping of parameter name to value");
                            for (const auto &kv : params)
                                p.params[kv.first.as<std::string>()] =
                                    r.text(kv.second, key + ".params." + kv.first.as<std::string>());
                        }
                    }
                    else
                        r.fail(key, "expected a planner name or {label, name, params}");
                    try
                    {
                        requirePlannerName(p.name);
                    }
                    catch (const std::invalid_argument &)
                    {
                        r.fail(key, "unknown planner '" + p.name + "' (see michi list-planners)");
                    }
                    if (p.label.empty())
                        p.label = p.name;
                    // the label is a planner name in the log, whose runs are ';'-separated lines, and a field of the
                    // plan file, whose fields are tab-separated (a tab passed `run` and then failed `merge`)
                    if (std::any_of(p.label.begin(), p.label.end(),
                                    [](char c)
                                    {
                                        return c == ';' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
                                    }))
                        r.fail(key + ".label", "must not hold ';', a tab, a line break or another control character");
                    if (!labels.insert(p.label).second)
                        r.fail(key + ".label",
                               "label '" + p.label + "' is used twice (give each configuration its own)");
                    c.planners.push_back(p);
                }
            }

            void readCheckers(const Reader &r, const YAML::Node &list, Campaign &c)
            {
                if (!list)
                {
                    // "problem": each problem's own collision.checker.
                    c.checkers = {"problem"};
                    return;
                }
                if (!list.IsSequence() || list.size() == 0)
                    r.fail("checkers", "expected a non-empty list of checker names");
                const auto &known = checkerNames();
                for (std::size_t i = 0; i < list.size(); ++i)
                {
                    const std::string key = "checkers[" + std::to_string(i) + "]";
                    const std::string name = r.text(list[i], key);
                    if (name != "problem" && std::find(known.begin(), known.end(), name) == known.end())
                    {
                        std::string all = "problem";
                        for (const auto &k : known)
                            all += ", " + k;
                        r.fail(key, "expected one of " + all + ", got '" + name + "'");
                    }
                    if (std::find(c.checkers.begin(), c.checkers.end(), name) != c.checkers.end())
                        r.fail(key, "checker '" + name + "' is listed twice");
                    c.checkers.push_back(name);
                }
            }

            /** A query listed twice (a problem under problems and in a dataset folder, a folder listed twice) would be
                run and counted twice in one experiment; two problem files of one name would be pooled by Planner
                Arena, which groups runs by experiment name. Both are refused, naming the entry that repeats. */
            void refuseRepeatedQueries(const Reader &r, const Campaign &c, std::size_t fromProblems)
            {
                std::map<std::string, std::string> seenQuery, fileOfName;
                for (std::size_t i = 0; i < c.datasets.size(); ++i)
                {
                    const std::string key = i < fromProblems ? "problems[" + std::to_string(i) + "]"
                                                             : "datasets[" + std::to_string(i - fromProblems) + "]";
                    for (const auto &e : c.datasets[i].entries)
                    {
                        const std::string file = normalised(e.problemFile);
                        const std::string query = file + "#" + std::to_string(e.query);
                        const auto first = seenQuery.emplace(query, c.datasets[i].name);
                        if (!first.second)
                            r.fail(key, "query " + std::to_string(e.query) + " of " + e.problemFile +
                                            " is also in dataset '" + first.first->second +
                                            "': it would be run and counted twice");
                        const auto named = fileOfName.emplace(e.problemName, file);
                        if (!named.second && named.first->second != file)
                            r.fail(key, e.problemFile + " and " + named.first->second + " are both named '" +
                                            e.problemName +
                                            "': Planner Arena would pool their runs as one experiment (give each "
                                            "problem its own name)");
                    }
                }
            }

            std::uint64_t splitMix64(std::uint64_t x)
            {
                // SplitMix64's finalizer: consecutive ids come out as unrelated 64-bit values, so seeds and shard order
                // show no pattern of the plan's loops.
                x += 0x9e3779b97f4a7c15ULL;
                x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
                x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
                return x ^ (x >> 31);
            }
        }  // namespace

        Campaign loadCampaign(const std::string &file)
        {
            const Reader r(file);
            const YAML::Node root = problem_file::loadYaml(file);
            if (!root.IsMap())
                r.fail("", "expected a mapping (name, seed, time_limit, runs, problems, datasets, planners, ...)");
            r.keys(root, "",
                   {"name", "description", "seed", "time_limit", "runs", "hang_margin", "problems", "datasets",
                    "planners", "checkers"});
            Campaign c;
            c.file = file;
            c.name = root["name"] ? r.text(root["name"], "name") : fs::path(file).stem().string();
            if (c.name.empty() || c.name.find_first_of(" \t\n\r;/") != std::string::npos)
                r.fail("name", "expected a name without spaces, ';' or '/'");
            if (root["seed"])
                c.seed = r.count(root["seed"], "seed");
            c.timeLimit = r.number(root, "time_limit", "", c.timeLimit);
            if (!(c.timeLimit > 0.) || c.timeLimit > 1e6)
                r.fail("time_limit", "expected seconds in (0, 1e6]");
            if (root["runs"])
                c.runs = r.count(root["runs"], "runs");
            if (c.runs < 1 || c.runs > 100000)  // as michi bench --runs
                r.fail("runs", "expected an integer in 1..100000");
            c.hangMargin = r.number(root, "hang_margin", "", c.hangMargin);
            if (!(c.hangMargin > 0.) || c.hangMargin > 1e6)
                r.fail("hang_margin", "expected seconds in (0, 1e6]");
            if (!root["problems"] && !root["datasets"])
                r.fail("problems", "missing: give problems (files), datasets (folders) or both");
            readProblems(r, root["problems"], c);
            const std::size_t fromProblems = c.datasets.size();  // one dataset per problems entry
            readDatasets(r, file, root["datasets"], c);
            refuseRepeatedQueries(r, c, fromProblems);
            readPlanners(r, root["planners"], c);
            readCheckers(r, root["checkers"], c);
            // A checker that cannot serve a dataset's robot (the grid checker on an arm, the J-map or spheres on an
            // SE(2) robot) would fail each of its units at run time while the campaign reports success: said now,
            // from each dataset's first problem (a folder's problems share their robot).
            for (std::size_t i = 0; i < c.checkers.size(); ++i)
            {
                const std::string &checker = c.checkers[i];
                if (checker != "grid" && checker != "jmap" && checker != "spheres")
                    continue;
                for (const auto &dataset : c.datasets)
                {
                    if (dataset.entries.empty())
                        continue;
                    const Problem problem = loadProblem(dataset.entries.front().problemFile);
                    const bool se2 = problem.kind == Problem::Kind::SE2;
                    if ((checker == "grid") != se2)
                        r.fail("checkers[" + std::to_string(i) + "]",
                               "checker '" + checker + "' cannot check " + problem.file + "'s robot (" +
                                   (checker == "grid" ? "the grid checker is for SE(2) robots"
                                                      : "the " + checker + " checker is for arms") +
                                   ")");
                }
            }
            // the work units are listed in memory (planUnits): a billion of them would exhaust it before any ran
            double entries = 0.;
            for (const auto &dataset : c.datasets)
                entries += static_cast<double>(dataset.entries.size());
            const double units = entries * static_cast<double>(c.planners.size()) *
                                 static_cast<double>(c.checkers.size()) * static_cast<double>(c.runs);
            if (units > 1e7)
                r.fail("runs", "the campaign would have more than 10 million work units");
            return c;
        }

        std::uint32_t unitSeed(unsigned int campaignSeed, std::size_t id)
        {
            // From the campaign seed and the unit's id alone: a unit makes the same run whichever shard or machine runs
            // it, so 4 merged shards hold the very same paths as one unsharded run (campaigns.md).
            const std::uint64_t mixed = splitMix64((static_cast<std::uint64_t>(campaignSeed) << 32) ^ id);
            const auto seed = static_cast<std::uint32_t>(mixed ^ (mixed >> 32));
            // ompl::RNG::setSeed() ignores 0.
            return seed == 0 ? 1 : seed;
        }

        std::vector<WorkUnit> planUnits(const Campaign &campaign)
        {
            std::vector<WorkUnit> units;
            // Fixed nesting (entry, planner, checker, run): a unit's id is its place in this order, and resume and
            // merge match units by id across processes.
            for (const auto &dataset : campaign.datasets)
                for (const auto &entry : dataset.entries)
                    for (std::size_t p = 0; p < campaign.planners.size(); ++p)
                        for (const auto &checker : campaign.checkers)
                            for (unsigned int run = 0; run < campaign.runs; ++run)
                            {
                                WorkUnit u;
                                u.id = units.size();
                                u.dataset = dataset.name;
                                u.entry = entry;
                                u.planner = p;
                                u.checker = checker;
                                u.run = run;
                                u.seed = unitSeed(campaign.seed, u.id);
                                units.push_back(u);
                            }
            return units;
        }

        std::pair<unsigned int, unsigned int> parseShard(const std::string &text)
        {
            const auto slash = text.find('/');
            auto number = [&](const std::string &s)
            {
                // Digits only (stoul would also take a sign or spaces) and at most 6 of them, so the value fits
                // unsigned int.
                if (s.empty() || s.size() > 6 || !std::all_of(s.begin(), s.end(), ::isdigit))
                    throw std::invalid_argument("expected K/N with 1 <= K <= N (e.g. 2/4), got '" + text + "'");
                return static_cast<unsigned int>(std::stoul(s));
            };
            if (slash == std::string::npos)
                number("");
            const unsigned int k = number(text.substr(0, slash)), n = number(text.substr(slash + 1));
            if (k < 1 || k > n)
                throw std::invalid_argument("expected K/N with 1 <= K <= N (e.g. 2/4), got '" + text + "'");
            return {k, n};
        }

        std::vector<WorkUnit> shardUnits(const std::vector<WorkUnit> &units, unsigned int k, unsigned int n)
        {
            std::vector<WorkUnit> share;
            // the units dealt round-robin in an order shuffled by a hash of their id: shards differ in size by at
            // most one, and unlike id mod N no shard gets every unit of one planner when N is a multiple of the plan's
            // period (runs x checkers x planners)
            std::vector<std::pair<std::uint64_t, std::size_t>> order;
            for (std::size_t i = 0; i < units.size(); ++i)
                order.emplace_back(splitMix64(units[i].id ^ 0x6d696368ULL), i);
            std::sort(order.begin(), order.end());
            std::vector<std::size_t> mine;
            for (std::size_t p = k - 1; p < order.size(); p += n)
                mine.push_back(order[p].second);
            std::sort(mine.begin(), mine.end());  // run in plan order
            for (const std::size_t i : mine)
                share.push_back(units[i]);
            return share;
        }

        std::string unitPlannerName(const Campaign &campaign, const WorkUnit &unit)
        {
            const std::string &label = campaign.planners.at(unit.planner).label;
            // The checker goes into the name only when a campaign compares checkers: one-checker results keep the
            // planners' plain names.
            return campaign.checkers.size() > 1 ? label + "_" + unit.checker : label;
        }

        std::string planLine(const Campaign &campaign, const WorkUnit &unit)
        {
            // the problem relative to the campaign file, so that shards started from different folders (or with an
            // absolute campaign path) write the same plan, which resume and merge compare
            return std::to_string(unit.id) + "\t" + unit.dataset + "\t" + planPath(campaign, unit.entry.problemFile) +
                   "#" + std::to_string(unit.entry.query) + "\t" + campaign.planners.at(unit.planner).label + "\t" +
                   unit.checker + "\trun " + std::to_string(unit.run) + "\tseed " + std::to_string(unit.seed);
        }

        std::string planText(const Campaign &campaign, const std::vector<WorkUnit> &units)
        {
            std::ostringstream plan;
            plan << "# campaign " << campaign.name << " seed " << campaign.seed << "\n";
            // The settings a unit's record does not carry in its plan line: without them, shards run before and after
            // an edit of the campaign file merged into one database under the later file's settings.
            plan << "# time_limit " << shortestText(campaign.timeLimit) << "\n";
            for (const auto &p : campaign.planners)
            {
                plan << "# planner " << p.label << " = " << p.name;
                for (const auto &kv : p.params)
                    plan << " " << kv.first << "=" << kv.second;
                plan << "\n";
            }
            std::set<std::string> files;
            for (const auto &u : units)
                if (files.insert(u.entry.problemFile).second)
                    plan << "# problem " << planPath(campaign, u.entry.problemFile) << " content "
                         << contentHash(u.entry.problemFile) << "\n";
            for (const auto &u : units)
                plan << planLine(campaign, u) << "\n";
            return plan.str();
        }

        std::string planDifference(const std::string &here, const std::string &there)
        {
            std::istringstream a(here), b(there);
            std::string la, lb;
            for (std::size_t line = 1;; ++line)
            {
                const bool moreA = static_cast<bool>(std::getline(a, la)),
                           moreB = static_cast<bool>(std::getline(b, lb));
                if (!moreA && !moreB)
                    return "";
                if (moreA != moreB || la != lb)
                    return "line " + std::to_string(line) + ": '" + (moreA ? la : "(none)") + "' against '" +
                           (moreB ? lb : "(none)") + "'";
            }
        }
    }  // namespace tools
}  // namespace michi
