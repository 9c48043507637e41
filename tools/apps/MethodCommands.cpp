// The sub-commands of the methods' own studies: `michi circles` and `michi jmap` (paper 000), `michi random-scenes`,
// `michi lattice` (paper 003), `michi dualarm` (paper 004) and `michi replan` (paper 002).
#include "CommandLine.h"

#include <michi/tools/commands/CircleCommand.h>
#include <michi/tools/commands/DualArmCommand.h>
#include <michi/tools/commands/HeadingLatticeReport.h>
#include <michi/tools/commands/JMapReport.h>
#include <michi/tools/commands/ReplanCommand.h>
#include <michi/tools/problem/Problem.h>
#include <michi/tools/problem/RandomPlanarScene.h>

#include <ompl/util/RandomNumbers.h>

#include <boost/filesystem.hpp>

#include <iostream>
#include <memory>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace cli
        {
            namespace
            {
                struct CirclesArgs
                {
                    std::string problem;
                    std::string out;
                    std::optional<std::string> checker;
                    std::optional<double> time;
                    std::optional<std::string> view;
                    std::vector<std::string> set;
                    bool html{false};
                    bool verbose{false};
                };

                int runCirclesCommand(const CirclesArgs &args)
                {
                    CircleOptions options;
                    for (const auto &kv : args.set)
                    {
                        const auto eq = kv.find('=');
                        if (eq == std::string::npos || eq == 0)
                            throw UsageError("--set: expected NAME=VALUE, got '" + kv + "'");
                        options.params[kv.substr(0, eq)] = kv.substr(eq + 1);
                    }
                    if (args.view)
                    {
                        options.view = parseRealList("--view", *args.view, -1e9, 1e9, true, 4);
                        if (!(options.view[0] < options.view[2]) || !(options.view[1] < options.view[3]))
                            throw UsageError(
                                "--view: expected XMIN,YMIN,XMAX,YMAX with XMIN < XMAX and YMIN < YMAX, "
                                "got '" +
                                *args.view + "'");
                    }
                    // Before the problem is loaded or anything runs: a bad --out fails at once, not after a long solve.
                    checkOutputPath("--out", args.out, OutputKind::FOLDER);
                    if (args.verbose)  // without --verbose, OMPL's log level is left as it is (as before)
                        setOmplLogLevel(true);
                    options.outDir = args.out;
                    options.checker = args.checker.value_or("");
                    options.timeLimit = args.time.value_or(options.timeLimit);
                    options.progress = &std::cerr;
                    options.html = args.html;
                    const Problem problem = loadProblem(args.problem);
                    try
                    {
                        std::cout << runCircles(problem, options);
                    }
                    catch (const ProblemError &e)
                    {
                        // circles takes ConcentricCircle's parameters from --set only, so a bad one is a usage error
                        // of --set, not a key of the problem file
                        const std::string prefix = "planners.michi::ConcentricCircle.params.";
                        if (e.key().compare(0, prefix.size(), prefix) != 0)
                            throw;
                        const std::string what = e.what();
                        const std::string head = e.file() + ": " + e.key() + ": ";
                        throw UsageError("--set " + e.key().substr(prefix.size()) + ": " +
                                         (what.compare(0, head.size(), head) == 0 ? what.substr(head.size()) : what));
                    }
                    return 0;
                }

                struct JMapArgs
                {
                    std::string problem;
                    std::string out;
                    std::optional<std::uint64_t> verify;
                    std::optional<unsigned int> seed;
                    bool verbose{false};
                };

                int runJMapCommand(const JMapArgs &args)
                {
                    checkOutputPath("--out", args.out, OutputKind::FOLDER);
                    setOmplLogLevel(args.verbose);
                    const Problem problem = loadProblem(args.problem);
                    JMapReportOptions options;
                    options.outDir = args.out;
                    options.verify = args.verify.value_or(0);
                    options.seed = args.seed.value_or(problem.benchmark.seed);
                    options.progress = &std::cerr;
                    std::cout << runJMapReport(problem, options);
                    std::cerr << "michi jmap: wrote " << (fs::path(options.outDir) / "jmap.json").string()
                              << " and jmap.svg (and .png)" << std::endl;
                    return 0;
                }

                struct RandomScenesArgs
                {
                    std::string out;
                    std::optional<std::string> arm;
                    std::optional<unsigned int> count;
                    std::optional<std::uint32_t> seed;
                    std::optional<int> polygons;
                    bool verbose{false};
                };

                /** The default --arm: planar_2link from the checkout michi runs in, else from the installed
                    problems (an installed michi run from any folder). */
                std::string defaultArm()
                {
                    const std::string local = RandomScenesOptions().arm;
                    if (boost::filesystem::exists(local))
                        return local;
                    // relative to the executable (bin/michi next to share/michi/problems), so that an install
                    // under any prefix finds its own copy
                    boost::system::error_code error;
                    const boost::filesystem::path exe = boost::filesystem::read_symlink("/proc/self/exe", error);
                    const std::string installed =
                        (exe.parent_path().parent_path() / MICHI_INSTALL_DATADIR / "michi/problems/planar_2link.yaml")
                            .string();
                    if (boost::filesystem::exists(installed))
                        return installed;
                    throw UsageError("--arm: not given, and the default arm (" + local +
                                     ") is neither in the current folder nor installed (" + installed +
                                     "): give --arm PROBLEM.yaml");
                }

                int runRandomScenesCommand(const RandomScenesArgs &args)
                {
                    RandomScenesOptions options;
                    options.count = args.count.value_or(options.count);
                    options.seed = args.seed.value_or(options.seed);
                    options.scene.polygons = args.polygons.value_or(options.scene.polygons);
                    // the scenes take seeds seed .. seed + count - 1, all 32-bit
                    if (options.seed > MAX_SEED - (options.count - 1))
                        throw UsageError("--seed: seed + count - 1 exceeds " + std::to_string(MAX_SEED) + ", got '" +
                                         std::to_string(options.seed) + "' with --count " +
                                         std::to_string(options.count));
                    checkOutputPath("--out", args.out, OutputKind::FOLDER);
                    // after the other arguments' checks, and only when --arm is not given
                    options.arm = args.arm ? *args.arm : defaultArm();
                    setOmplLogLevel(args.verbose);
                    options.outDir = args.out;
                    const auto files = writeRandomScenes(options);
                    for (const auto &f : files)
                        std::cout << f << "\n";
                    std::cerr << "michi random-scenes: wrote " << files.size() << " scene"
                              << (files.size() > 1 ? "s" : "") << " to " << options.outDir << std::endl;
                    return 0;
                }

                struct LatticeArgs
                {
                    std::string problem;
                    std::string out;
                    std::optional<std::string> cellSizes;
                    std::optional<std::string> angleSteps;
                    std::optional<double> time;
                    bool html{false};
                    bool verbose{false};
                };

                int runLatticeCommand(const LatticeArgs &args)
                {
                    HeadingLatticeReportOptions options;
                    if (args.cellSizes)
                        options.cellSizes = parseRealList("--cell-sizes", *args.cellSizes, 0., 1e6);
                    if (args.angleSteps)
                        // at most pi/2, as the planner takes it (a usage error here, exit 2, not a failed run)
                        options.angleSteps = parseRealList("--angle-steps", *args.angleSteps, 0., M_PI / 2. + 1e-9);
                    checkOutputPath("--out", args.out, OutputKind::FOLDER);
                    setOmplLogLevel(args.verbose);
                    options.outDir = args.out;
                    options.timeLimit = args.time.value_or(options.timeLimit);
                    options.progress = &std::cerr;
                    options.html = args.html;
                    std::cout << runHeadingLatticeReport(loadProblem(args.problem), options);
                    return 0;
                }

                struct DualArmArgs
                {
                    std::string problem;
                    std::string out;
                    std::optional<double> time;
                    std::optional<unsigned int> seed;
                    bool html{false};
                    bool verbose{false};
                };

                int runDualArmCommand(const DualArmArgs &args)
                {
                    checkOutputPath("--out", args.out, OutputKind::FOLDER);
                    setOmplLogLevel(args.verbose);
                    const Problem problem = loadProblem(args.problem);
                    // Before anything draws from OMPL's generator, so the same seed gives the same samples and plans.
                    ompl::RNG::setSeed(args.seed.value_or(problem.benchmark.seed));
                    DualArmOptions options;
                    options.outDir = args.out;
                    options.planningTime = args.time.value_or(0.);  // 0: the problem's dual_arm.planning.time
                    options.progress = &std::cerr;
                    options.html = args.html;
                    std::cout << runDualArm(problem, options);
                    std::cerr << "michi dualarm: wrote " << (fs::path(options.outDir) / "dualarm.json").string()
                              << " and dualarm-*.svg/.png";
                    if (args.html)
                        std::cerr << " and " << (fs::path(options.outDir) / (problem.name + ".html")).string();
                    std::cerr << std::endl;
                    return 0;
                }

                struct ReplanArgs
                {
                    std::string problem;
                    std::string out;
                    std::optional<unsigned int> episodes;
                    std::optional<unsigned int> seed;
                    std::optional<std::string> methods;  ///< unset: every method; given empty: a usage error
                    bool html{false};
                    bool verbose{false};
                };

                int runReplanCommand(const ReplanArgs &args)
                {
                    checkOutputPath("--out", args.out, OutputKind::FOLDER);
                    setOmplLogLevel(args.verbose, true);
                    ReplanOptions options;
                    options.problemFile = args.problem;
                    options.outDir = args.out;
                    options.episodes = args.episodes.value_or(20);
                    options.seed = args.seed.value_or(1);
                    if (args.methods)
                    {
                        if (args.methods->empty())
                            throw UsageError("--methods: expected method names, e.g. dual,rrtconnect, got ''");
                        options.methods = splitComma("--methods", *args.methods);
                    }
                    options.html = args.html;
                    options.progress = &std::cerr;
                    try
                    {
                        std::cout << runReplan(options);
                    }
                    catch (const std::invalid_argument &e)
                    {
                        // an unknown or repeated method name is a usage error of --methods (exit 2)
                        if (std::string(e.what()).rfind("--methods:", 0) == 0)
                            throw UsageError(e.what());
                        throw;
                    }
                    std::cerr << "michi replan: wrote " << (fs::path(options.outDir) / "replan.json").string();
                    if (args.html)  // the page is named by the problem's name, which may differ from the file's
                        std::cerr << " and "
                                  << (fs::path(options.outDir) / (loadProblem(args.problem).name + ".html")).string();
                    std::cerr << std::endl;
                    return 0;
                }
            }  // namespace

            Runner addCircles(CLI::App &michi)
            {
                // Shared with the runner: CLI11 fills args while parsing, and the runner reads them after this function
                // has returned.
                auto args = std::make_shared<CirclesArgs>();
                CLI::App *c = michi.add_subcommand("circles",
                                                   "solve with michi::planners::ConcentricCircle and draw its circles, "
                                                   "candidates, links and paths (paper 000)");
                addProblem(*c, args->problem);
                addOut(*c, args->out, "output folder (made if missing)");
                addChoice(*c, "--checker", args->checker, {"fcl", "jmap"},
                          "collision checker (default: the problem's collision.checker)");
                addTime(*c, args->time, "time limit (default 30)");
                c->add_option("--set", args->set, "a ConcentricCircle parameter by name (repeatable)")
                    ->type_name("NAME=VALUE")
                    ->allow_extra_args(false);
                c->add_option_function<std::string>(
                     "--view",
                     [args](const std::string &text)
                     {
                         args->view = text;
                     },
                     "picture box of every stage (default: all)")
                    ->type_name("XMIN,YMIN,XMAX,YMAX");
                c->add_flag("--html", args->html,
                            "also write DIR/<problem>.html: a self-contained 3-D replay of the path (docs/viewer.md)");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    return runCirclesCommand(*args);
                };
            }

            Runner addJMap(CLI::App &michi)
            {
                auto args = std::make_shared<JMapArgs>();
                CLI::App *c = michi.add_subcommand(
                    "jmap",
                    "build the J-map of the problem's arm (paper 000); writes DIR/jmap.svg and DIR/jmap.json; with "
                    "--verify, N uniform states are checked against FCL (unsafe and false-invalid counts, query "
                    "times)");
                addProblem(*c, args->problem);
                addOut(*c, args->out, "output folder (made if missing)");
                addInteger(*c, "--verify", args->verify, 0, 100000000,
                           "uniform states checked against FCL (default 0: none)");
                addSeed(*c, args->seed, "seed of the verification states (default: the problem's benchmark.seed)");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    return runJMapCommand(*args);
                };
            }

            Runner addRandomScenes(CLI::App &michi)
            {
                auto args = std::make_shared<RandomScenesArgs>();
                CLI::App *c = michi.add_subcommand(
                    "random-scenes",
                    "random planar scenes (seeds S, S+1, ...) for the arm of a problem: writes DIR/scene_<seed>.yaml");
                addOut(*c, args->out, "output folder (made if missing)");
                addInteger(*c, "--count", args->count, 1, 100000, "scenes to write (default 50)");
                // seeds of a local ompl::RNG per scene, not ompl::RNG::setSeed: 0 is accepted as before
                addInteger(*c, "--seed", args->seed, 0, MAX_SEED, "seed of the first scene (default 1)")
                    ->type_name("S");
                c->add_option_function<std::string>(
                     "--arm",
                     [args](const std::string &text)
                     {
                         args->arm = text;
                     },
                     "template problem whose arm and settings are used (default problems/planar_2link.yaml of the "
                     "current folder, else the installed one)")
                    ->type_name("PROBLEM.yaml");
                addInteger(*c, "--polygons", args->polygons, 0, 1000, "polygons per scene (default 6)")->type_name("K");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    return runRandomScenesCommand(*args);
                };
            }

            Runner addLattice(CLI::App &michi)
            {
                auto args = std::make_shared<LatticeArgs>();
                CLI::App *c = michi.add_subcommand(
                    "lattice",
                    "build the heading-constrained lattice (paper 003) per setting: nodes, build and query times "
                    "(DIR/lattice.md) and pictures of the lattice, groups, path correction and path (DIR/*.svg)");
                addProblem(*c, args->problem);
                addOut(*c, args->out, "output folder (made if missing)");
                c->add_option_function<std::string>(
                     "--cell-sizes",
                     [args](const std::string &text)
                     {
                         args->cellSizes = text;
                     },
                     "cell_size values in metres (default 0.25)")
                    ->type_name("A,B,...");
                c->add_option_function<std::string>(
                     "--angle-steps",
                     [args](const std::string &text)
                     {
                         args->angleSteps = text;
                     },
                     "angle_step values in radians, e.g. pi/8 (default 0.3927)")
                    ->type_name("A,B,...");
                addTime(*c, args->time, "time limit per solve (default 60)");
                c->add_flag("--html", args->html,
                            "also write DIR/<problem>.html: a self-contained 3-D replay of the first solved path "
                            "(docs/viewer.md)");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    return runLatticeCommand(*args);
                };
            }

            Runner addDualArm(CLI::App &michi)
            {
                auto args = std::make_shared<DualArmArgs>();
                CLI::App *c = michi.add_subcommand(
                    "dualarm",
                    "dual-arm work positions by manipulability (paper 004); writes DIR/dualarm.json and pictures");
                addProblem(*c, args->problem);
                addOut(*c, args->out, "output folder (made if missing)");
                addTime(*c, args->time, "time per approach plan (default: the problem's dual_arm.planning.time)");
                addSeed(*c, args->seed, "ompl::RNG seed (default: the problem's benchmark.seed)");
                c->add_flag("--html", args->html,
                            "also write DIR/<problem>.html: the stirring task (approach motions, stirring) replayed in "
                            "3-D (docs/viewer.md)");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    return runDualArmCommand(*args);
                };
            }

            Runner addReplan(CLI::App &michi)
            {
                auto args = std::make_shared<ReplanArgs>();
                CLI::App *c = michi.add_subcommand(
                    "replan",
                    "non-stop replanning among moving obstacles (paper 002): N randomized episodes per method; writes "
                    "DIR/replan.json and DIR/episode/frame_*.svg (and DIR/<problem>.html with --html)");
                addProblem(*c, args->problem);
                addOut(*c, args->out, "output folder (made if missing)");
                addInteger(*c, "--episodes", args->episodes, 1, 100000, "episodes per method (default 20)");
                addSeed(*c, args->seed, "seed of the episodes (default 1)");
                c->add_option("--methods", args->methods,
                              "methods to run, e.g. dual,rrtconnect (default: DualRoadmap and every baseline)")
                    ->type_name("A,B,...");
                c->add_flag("--html", args->html,
                            "also write DIR/<problem>.html: the first episode replayed in 3-D, the executed motion of "
                            "every method and the moving obstacles on the simulated clock (docs/viewer.md)");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    return runReplanCommand(*args);
                };
            }
        }  // namespace cli
    }      // namespace tools
}  // namespace michi
