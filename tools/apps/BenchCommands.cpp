// `michi bench`, `michi plan` and `michi list-planners`: OMPL's Benchmark and one solve on a problem file.
#include "CommandLine.h"

#include <michi/tools/FileOutput.h>
#include <michi/tools/bench/BenchmarkRunner.h>
#include <michi/tools/bench/PathCertificate.h>
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/commands/VerifyChecker.h>
#include <michi/tools/pictures/SvgPlot.h>
#include <michi/tools/problem/PathFile.h>
#include <michi/tools/problem/Problem.h>
#include <michi/tools/problem/Dataset.h>
#include <michi/tools/problem/ExperienceDataset.h>
#include <michi/tools/viewer/ReplayPage.h>

#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/RandomNumbers.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace cli
        {
            namespace
            {
                const char *CHECKER_HELP = "collision checker (default: the problem's collision.checker)";
                const std::vector<std::string> OBJECTIVES{"length", "clearance"};
                const char *OBJECTIVE_HELP =
                    "optimisation objective of every planner: path length, or the path's minimum clearance (OMPL's "
                    "MaximizeMinClearanceObjective) (default: the problem's benchmark.objective)";

                /** a planner name as a file name part: geometric::RRTConnect -> geometric__RRTConnect */
                std::string fileSafe(std::string s)
                {
                    for (char &c : s)
                        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_')
                            c = '_';
                    return s;
                }

                struct BenchArgs
                {
                    std::string problem;
                    std::string out;
                    std::string planners;
                    std::optional<unsigned int> runs;
                    std::optional<double> time;
                    std::optional<std::size_t> query;
                    std::optional<std::string> checker;
                    std::optional<std::string> objective;
                    std::string queries;
                    bool html{false};
                    std::optional<unsigned int> seed;
                    bool verbose{false};
                };

                /** --checker for bench: one checker, or fcl,X to compare X with FCL in one run. */
                std::string benchChecker(const std::string &text)
                {
                    const auto &names = checkerNames();
                    auto known = [&](const std::string &n)
                    {
                        return std::find(names.begin(), names.end(), n) != names.end();
                    };
                    // split here rather than by splitComma(): any malformed list gets the message below
                    std::vector<std::string> parts;
                    std::stringstream in(text);
                    for (std::string item; std::getline(in, item, ',');)
                        parts.push_back(item);
                    const bool single = parts.size() == 1 && known(parts[0]) && text == parts[0];
                    const bool pair = parts.size() == 2 && known(parts[0]) && known(parts[1]) &&
                                      // A pair is FCL and one other: a benchmark context holds FCL and at most one
                                      // other checker, and every comparison is against FCL.
                                      (parts[0] == "fcl") != (parts[1] == "fcl") && text == parts[0] + "," + parts[1];
                    if (!single && !pair)
                    {
                        std::string list;
                        for (const auto &n : names)
                            list += (list.empty() ? "" : ", ") + n;
                        throw UsageError("--checker: expected one of " + list +
                                         " or fcl,X (X one of them but fcl), got '" + text + "'");
                    }
                    return text;
                }

                int runBench(const BenchArgs &args)
                {
                    checkOutputPath("--out", args.out, OutputKind::FOLDER);
                    setOmplLogLevel(args.verbose);
                    // --checker fcl,X: both checkers side by side in one benchmark
                    const bool compare = args.checker && args.checker->find(',') != std::string::npos;
                    Problem problem = loadProblem(args.problem);
                    if (args.checker && !compare)
                        problem.checker = *args.checker;
                    if (args.objective)
                        problem.benchmark.objective = *args.objective;
                    if (args.seed)
                        problem.benchmark.seed = *args.seed;  // runBenchmark seeds ompl::RNG with it
                    BenchOptions options;
                    if (compare)
                        for (const auto &name : splitComma("--checker", *args.checker))
                            if (name != "fcl")
                                options.compareChecker = name;
                    options.queries = args.queries;
                    options.outDir = args.out;
                    options.planners = splitComma("--planners", args.planners);
                    // A name on the command line is the user's flag, not the problem file's: a usage error (exit 2)
                    // before anything is loaded into a benchmark.
                    for (const auto &name : options.planners)
                        try
                        {
                            requirePlannerName(name);
                        }
                        catch (const std::invalid_argument &e)
                        {
                            throw UsageError(std::string("--planners: ") + e.what());
                        }
                    options.runs = args.runs.value_or(0);        // 0: the problem's benchmark.runs
                    options.timeLimit = args.time.value_or(0.);  // 0: the problem's benchmark.time_limit
                    options.query = args.query.value_or(0);
                    options.heldOut = !args.query;  // --query: that query in every run, not the held-out ones
                    options.progress = &std::cerr;
                    options.html = args.html;
                    const BenchResult result = runBenchmark(problem, options);
                    std::cout << result.summaryText;
                    std::cout << "\nwrote " << result.log << "\n      " << result.database << "\n      "
                              << result.summary << "\n      " << result.picture << " (and .png)";
                    if (!result.page.empty())
                        std::cout << "\n      " << result.page;
                    std::cout << std::endl;
                    return 0;
                }

                struct PlanArgs
                {
                    std::string problem;
                    std::string out{"."};
                    std::string planner;
                    std::optional<double> time;
                    std::optional<std::size_t> query;
                    std::optional<unsigned int> seed;
                    std::optional<std::string> checker;
                    std::optional<std::string> objective;
                    bool html{false};
                    bool verbose{false};
                };

                int runPlan(const PlanArgs &args)
                {
                    checkOutputPath("--out", args.out, OutputKind::FOLDER);
                    setOmplLogLevel(args.verbose);
                    Problem problem = loadProblem(args.problem);
                    if (args.checker)
                        problem.checker = *args.checker;
                    if (args.objective)
                        problem.benchmark.objective = *args.objective;
                    // Before the context is made: everything drawn from here on (planner samples) follows from the
                    // seed.
                    ompl::RNG::setSeed(args.seed.value_or(problem.benchmark.seed));
                    const std::size_t query = args.query.value_or(0);
                    ContextOptions contextOptions;
                    contextOptions.query = query;
                    if (!problem.experience.dataset.empty())
                        // an experience planner learns the dataset's training problems in their own scenes first
                        contextOptions.scene = copyScene(*problem.scene);
                    PlanningContext ctx = makePlanningContext(problem, contextOptions);
                    const std::string &name = args.planner;
                    ompl::base::PlannerPtr planner;
                    try
                    {
                        planner = makePlanner(problem, name, ctx.setup->getSpaceInformation());
                    }
                    catch (const ProblemError &)
                    {
                        throw;  // a bad parameter in the problem file
                    }
                    catch (const std::invalid_argument &e)
                    {
                        throw UsageError(std::string("--planner: ") + e.what());  // an unknown planner name
                    }
                    // as in michi bench: an experience planner plans with what the problem's experience section
                    // teaches (library, training queries or problems), learned before the timed solve
                    const auto learnStart = std::chrono::steady_clock::now();
                    const std::size_t learned = learnBeforePlanning(problem, ctx, planner, query, &std::cerr);
                    if (learned > 0)
                        std::cerr
                            << "michi plan: " << name << " learned " << learned << " paths in " << std::setprecision(3)
                            << std::chrono::duration<double>(std::chrono::steady_clock::now() - learnStart).count()
                            << " s (not part of the planning time)" << std::endl;
                    ctx.setup->setPlanner(planner);
                    const double time = args.time.value_or(problem.benchmark.timeLimit);
                    const auto status = ctx.setup->solve(time);
                    if (status != ompl::base::PlannerStatus::EXACT_SOLUTION)
                    {
                        std::cerr << "michi plan: " << problem.file << ": " << name << " found no path within " << time
                                  << " s (" << statusText(status) << ")" << std::endl;
                        return 1;
                    }
                    // bounded like the solve: OMPL's unbounded default can take minutes
                    ctx.setup->simplifySolution(time);
                    auto &path = ctx.setup->getSolutionPath();
                    // As in michi bench: the path is re-checked with FCL on the real geometry, ten times finer than
                    // the planners' checks, before anything is printed or written. A motion validator that samples
                    // (the default workspace one, 1 cm) can step over a corner's contact, and a fast checker can be
                    // wrong; such a path is not a solution, and plan must not hand it out with exit code 0.
                    const PathCertificate certificate = certifyPath(path, *ctx.checker);
                    if (!certificate.certified)
                    {
                        std::cerr << "michi plan: " << problem.file << ": " << name
                                  << "'s path is NOT certified by FCL (" << certificate.reason << "); nothing written"
                                  << std::endl;
                        return 1;
                    }
                    std::vector<std::vector<double>> states;
                    for (const auto *s : path.getStates())
                    {
                        std::vector<double> values;
                        ctx.setup->getStateSpace()->copyToReals(values, s);
                        states.push_back(values);
                    }
                    std::ostringstream comment;
                    comment << problem.name << " query " << query << ", " << name << ", " << states.size()
                            << " states, length " << path.length() << ", clearance " << path.clearance()
                            << " (mean over the states), certified by FCL at " << certificate.statesChecked
                            << " states";
                    std::cout << "# " << comment.str() << "\n";
                    for (const auto &s : states)
                    {
                        for (std::size_t i = 0; i < s.size(); ++i)
                            std::cout << (i ? " " : "") << s[i];
                        std::cout << "\n";
                    }
                    // both files or neither: a failure in the picture used to leave the .path behind
                    StagedDirectory stage(args.out);
                    const std::string base = problem.name + "-" + fileSafe(name);
                    writePathFile(stage.path(base + ".path").string(), problem.valueNames(), states, comment.str());
                    writeProblemSvg(problem, {PlotPath{name, states}}, stage.path(base + ".svg").string(), query);
                    const std::string page = problem.name + ".html";
                    if (args.html)
                        writeReplayPage(problem, {PlotPath{name, states}}, stage.path(page).string());
                    stage.commit();
                    // the folder as the user wrote it (as before the outputs were staged): scripts match this line
                    const std::string stem = (fs::path(args.out) / base).string();
                    std::cerr << "michi plan: wrote " << stem << ".path" << (args.html ? ", " : " and ") << stem
                              << ".svg";
                    if (args.html)
                        std::cerr << " and " << (fs::path(args.out) / page).string();
                    std::cerr << std::endl;
                    return 0;
                }
            }  // namespace

            Runner addBench(CLI::App &michi)
            {
                auto args = std::make_shared<BenchArgs>();
                CLI::App *c = michi.add_subcommand(
                    "bench",
                    "run OMPL's Benchmark; writes DIR/<problem>.log, DIR/<problem>.db (Planner Arena), DIR/summary.md "
                    "and DIR/<problem>.svg");
                addProblem(*c, args->problem);
                addOut(*c, args->out, "output folder (made if missing)");
                c->add_option("--planners", args->planners,
                              "planners to run, A,B,... (default: the problem's planners; see michi list-planners)")
                    ->type_name("A,B,...");
                addInteger(*c, "--runs", args->runs, 1, 100000, "runs per planner (default: the problem's)");
                addTime(*c, args->time, "time limit per run (default: the problem's)");
                addInteger(*c, "--query", args->query, 0, 1000000,
                           "run this query of the problem every time (default: cycle the held-out experience "
                           "queries if any, else query 0)")
                    ->type_name("I");
                c->add_option_function<std::string>(
                     "--checker",
                     [args](const std::string &text)
                     {
                         args->checker = benchChecker(text);
                     },
                     std::string(CHECKER_HELP) +
                         "; fcl,X runs every planner with both (runs with X named <planner>_X), e.g. fcl,jmap or "
                         "fcl,grid")
                    ->type_name("fcl|jmap|grid|fcl,X");
                c->add_option_function<std::string>(
                     "--queries",
                     [args](const std::string &text)
                     {
                         try
                         {
                             parseQuerySelection(text);  // checked here; applied against the problem later
                         }
                         catch (const std::invalid_argument &e)
                         {
                             throw UsageError(std::string("--queries: ") + e.what());
                         }
                         args->queries = text;
                     },
                     "plan query i of the problem in run i, one run per query: all, or A-B (indices, inclusive); "
                     "overrides --runs and the problem's benchmark.queries")
                    ->type_name("all|A-B");
                addChoice(*c, "--objective", args->objective, OBJECTIVES, OBJECTIVE_HELP);
                c->add_flag("--html", args->html,
                            "also write DIR/<problem>.html: a self-contained 3-D replay of every planner's solution "
                            "(docs/viewer.md)");
                addSeed(*c, args->seed, "ompl::RNG seed (default: the problem's benchmark.seed)");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    return runBench(*args);
                };
            }

            Runner addPlan(CLI::App &michi)
            {
                auto args = std::make_shared<PlanArgs>();
                CLI::App *c = michi.add_subcommand(
                    "plan",
                    "solve once, print the path, write DIR/<problem>-<planner>.path and .svg (and DIR/<problem>.html "
                    "with --html)");
                addProblem(*c, args->problem);
                c->add_option("--planner", args->planner, "the planner (see michi list-planners)")
                    ->required()
                    ->type_name("NAME");
                addOut(*c, args->out, "output folder (default: the current folder)", false);
                addTime(*c, args->time, "time limit (default: the problem's)");
                addInteger(*c, "--query", args->query, 0, 1000000, "the problem's query to solve (default 0)")
                    ->type_name("I");
                addSeed(*c, args->seed, "ompl::RNG seed (default: the problem's benchmark.seed)");
                addChoice(*c, "--checker", args->checker, checkerNames(), CHECKER_HELP);
                addChoice(*c, "--objective", args->objective, OBJECTIVES, OBJECTIVE_HELP);
                c->add_flag("--html", args->html,
                            "also write DIR/<problem>.html: a self-contained 3-D replay of the path (docs/viewer.md)");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    return runPlan(*args);
                };
            }

            Runner addVerifyChecker(CLI::App &michi)
            {
                struct Args
                {
                    std::string problem;
                    std::optional<std::string> checker;
                    std::optional<std::size_t> states;
                    std::optional<unsigned int> seed;
                    bool verbose{false};
                };
                auto args = std::make_shared<Args>();
                CLI::App *c = michi.add_subcommand(
                    "verify-checker",
                    "check N uniform states and N random short motions with a fast checker and with FCL on the same "
                    "scene; prints one JSON line (unsafe_states, unsafe_motions, false_invalid_fraction, query_ns, "
                    "reference_query_ns)");
                addProblem(*c, args->problem);
                addChoice(*c, "--checker", args->checker, checkerNames(), "the checker to verify against FCL")
                    ->required();
                addInteger(*c, "--states", args->states, 1, 1000000000, "states, and as many motions (default 100000)");
                addSeed(*c, args->seed, "ompl::RNG seed (default 1)");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    setOmplLogLevel(args->verbose);
                    const Problem problem = loadProblem(args->problem);
                    VerifyCheckerOptions options;
                    options.checker = *args->checker;
                    options.states = args->states.value_or(100000);
                    options.seed = args->seed.value_or(1);
                    options.progress = &std::cerr;
                    const VerifyCheckerResult result = verifyChecker(problem, options);
                    std::cout << result.json() << std::endl;
                    // Exit 1 on anything unsafe, so a script or CI job can gate on a checker's safety.
                    return result.unsafeStates == 0 && result.unsafeMotions == 0 ? 0 : 1;
                };
            }

            Runner addListPlanners(CLI::App &michi)
            {
                auto verbose = std::make_shared<bool>(false);
                CLI::App *c = michi.add_subcommand("list-planners", "the planner names that bench and plan take");
                addVerbose(*c, *verbose);
                return []
                {
                    for (const auto &name : plannerNames())
                        std::cout << name << "\n";
                    return 0;
                };
            }
        }  // namespace cli
    }      // namespace tools
}  // namespace michi
