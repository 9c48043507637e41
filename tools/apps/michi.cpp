// The `michi` command: benchmark and plan on michi problem files, list the planners.
#include <michi/tools/BenchmarkRunner.h>
#include <michi/tools/HeadingLatticeReport.h>
#include <michi/tools/DualArmCommand.h>
#include <michi/tools/CircleCommand.h>
#include <michi/tools/ExperienceQueries.h>
#include <michi/tools/JMapReport.h>
#include <michi/tools/PathFile.h>
#include <michi/tools/PathSeedFigure.h>
#include <michi/tools/PlannerRegistry.h>
#include <michi/tools/PlanningContext.h>
#include <michi/tools/ReplanCommand.h>
#include <michi/tools/RandomPlanarScene.h>
#include <michi/tools/Problem.h>
#include <michi/tools/SvgPlot.h>
#include <michi/validity/RobotModel.h>

#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <boost/filesystem.hpp>

#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = boost::filesystem;
using namespace michi::tools;

namespace
{
    const char *USAGE =
        "usage:\n"
        "  michi bench PROBLEM.yaml --out DIR [--planners A,B,...] [--runs N] [--time SECONDS] [--query I]\n"
        "      run OMPL's Benchmark; writes DIR/<problem>.log, DIR/<problem>.db (Planner Arena), DIR/summary.md\n"
        "      and DIR/<problem>.svg\n"
        "  michi plan PROBLEM.yaml --planner NAME [--out DIR] [--time SECONDS] [--query I] [--seed S]\n"
        "      solve once, print the path, write DIR/<problem>-<planner>.path and .svg\n"
        "  michi circles PROBLEM.yaml --out DIR [--checker fcl|jmap] [--time S] [--set NAME=VALUE]...\n"
        "      solve with michi::ConcentricCircle and draw its circles, candidates, links and paths (paper 000)\n"
        "  michi jmap PROBLEM.yaml --out DIR [--verify N] [--seed S]\n"
        "      build the J-map of the problem's arm (paper 000); writes DIR/jmap.svg and DIR/jmap.json; with\n"
        "      --verify, N uniform states are checked against FCL (unsafe and false-invalid counts, query times)\n"
        "  michi random-scenes --count N --seed S --out DIR [--arm PROBLEM.yaml] [--polygons K]\n"
        "      random planar scenes (seeds S, S+1, ...) for the arm of PROBLEM.yaml (default\n"
        "      problems/planar_2link.yaml): writes DIR/scene_<seed>.yaml with K polygons (default 6)\n"
        "  michi lattice PROBLEM.yaml --out DIR [--cell-sizes A,B,...] [--angle-steps A,B,...] [--time SECONDS]\n"
        "      build the heading-constrained lattice (paper 003) per setting: nodes, build and query times\n"
        "      (DIR/lattice.md) and pictures of the lattice, groups, path correction and path (DIR/*.svg)\n"
        "  michi dualarm PROBLEM.yaml --out DIR [--time SECONDS] [--seed S]\n"
        "      dual-arm work positions by manipulability (paper 004); writes DIR/dualarm.json and pictures\n"
        "  michi replan PROBLEM.yaml --out DIR [--episodes N] [--seed S] [--methods dual,rrtconnect,...]\n"
        "      non-stop replanning among moving obstacles (paper 002): N randomized episodes per method; writes\n"
        "      DIR/replan.json and DIR/episode/frame_*.svg\n"
        "  michi experience-queries PROBLEM.yaml --out FILE [--count N] [--training N] [--start-spread RAD]\n"
        "      [--goal-spread RAD] [--seed S]   training and held-out start/goal pairs (docs/path-seed.md)\n"
        "  michi path-seed-figure PROBLEM.yaml --out FILE.svg [--training I] [--held-out J]\n"
        "      [--variant blocks|rotation] [--seed S]   a training path and its seed decoded for a held-out query\n"
        "  michi path-seed-library PROBLEM.yaml --out FILE [--variant blocks|rotation] [--seed S]\n"
        "      learn path seeds from the problem's training queries and save them (experience.library)\n"
        "  michi list-planners\n"
        "bench and plan take --checker fcl|jmap (default: the problem's collision.checker); bench --checker fcl,jmap "
        "runs\n"
        "  every planner with both (J-map runs named <planner>_jmap)\n"
        "options: --verbose shows OMPL's log messages\n";

    struct UsageError : std::runtime_error
    {
        using std::runtime_error::runtime_error;
    };

    /** --key value options after the positional arguments. */
    struct Args
    {
        std::vector<std::string> positional;
        std::map<std::string, std::string> options;
        bool verbose{false};

        Args(int argc, char **argv, const std::vector<std::string> &known)
        {
            for (int i = 2; i < argc; ++i)
            {
                const std::string a = argv[i];
                if (a == "--verbose")
                    verbose = true;
                else if (a.rfind("--", 0) == 0)
                {
                    if (std::find(known.begin(), known.end(), a.substr(2)) == known.end())
                        throw UsageError("unknown option " + a);
                    if (i + 1 >= argc)
                        throw UsageError("option " + a + " needs a value");
                    options[a.substr(2)] = argv[++i];
                }
                else
                    positional.push_back(a);
            }
        }
        bool has(const std::string &k) const
        {
            return options.count(k) > 0;
        }
        std::string get(const std::string &k, const std::string &fallback = "") const
        {
            auto it = options.find(k);
            return it == options.end() ? fallback : it->second;
        }
        double number(const std::string &k, double fallback, bool integer = false) const
        {
            if (!has(k))
                return fallback;
            try
            {
                std::size_t used = 0;
                const double v = std::stod(get(k), &used);
                if (used != get(k).size() || !(v > 0.) || (integer && v != static_cast<long>(v)))
                    throw std::invalid_argument(k);
                return v;
            }
            catch (const std::exception &)
            {
                throw UsageError("--" + k + " expects a positive " + (integer ? "integer" : "number") + ", got '" +
                                 get(k) + "'");
            }
        }
        std::size_t index(const std::string &k) const
        {
            if (!has(k))
                return 0;
            try
            {
                std::size_t used = 0;
                const long v = std::stol(get(k), &used);
                if (used != get(k).size() || v < 0)
                    throw std::invalid_argument(k);
                return static_cast<std::size_t>(v);
            }
            catch (const std::exception &)
            {
                throw UsageError("--" + k + " expects a non-negative integer, got '" + get(k) + "'");
            }
        }
    };

    std::vector<std::string> splitComma(const std::string &s)
    {
        std::vector<std::string> parts;
        std::stringstream in(s);
        std::string item;
        while (std::getline(in, item, ','))
            if (!item.empty())
                parts.push_back(item);
        return parts;
    }

    /** The problem with --checker applied. */
    Problem withChecker(Problem problem, const Args &args)
    {
        if (args.has("checker"))
        {
            const std::string c = args.get("checker");
            if (c != "fcl" && c != "jmap")
                throw UsageError("--checker expects fcl or jmap, got '" + c + "'");
            problem.checker = c;
        }
        return problem;
    }

    std::string fileSafe(std::string s)
    {
        for (char &c : s)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_')
                c = '_';
        return s;
    }

    int bench(int argc, char **argv)
    {
        Args args(argc, argv, {"out", "planners", "runs", "time", "query", "checker"});
        if (args.positional.size() != 1)
            throw UsageError("bench takes one problem file");
        if (!args.has("out"))
            throw UsageError("bench needs --out DIR");
        ompl::msg::setLogLevel(args.verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
        // --checker fcl,jmap: both checkers side by side in one benchmark
        const bool compare =
            args.has("checker") && (args.get("checker") == "fcl,jmap" || args.get("checker") == "jmap,fcl");
        if (args.has("checker") && !compare && args.get("checker").find(',') != std::string::npos)
            throw UsageError("bench --checker expects fcl, jmap or fcl,jmap, got '" + args.get("checker") + "'");
        Problem problem = loadProblem(args.positional[0]);
        if (!compare)
            problem = withChecker(problem, args);
        BenchOptions options;
        options.compareCheckers = compare;
        options.outDir = args.get("out");
        options.planners = splitComma(args.get("planners"));
        options.runs = static_cast<unsigned int>(args.number("runs", 0, true));
        options.timeLimit = args.number("time", 0.);
        options.query = args.index("query");
        options.heldOut = !args.has("query");  // --query: that query in every run, not the held-out ones
        options.progress = &std::cerr;
        const BenchResult result = runBenchmark(problem, options);
        std::ifstream summary(result.summary);
        std::cout << summary.rdbuf();
        std::cout << "\nwrote " << result.log << "\n      " << result.database << "\n      " << result.summary
                  << "\n      " << result.picture << " (and .png)" << std::endl;
        return 0;
    }

    int plan(int argc, char **argv)
    {
        Args args(argc, argv, {"out", "planner", "time", "query", "seed", "checker"});
        if (args.positional.size() != 1)
            throw UsageError("plan takes one problem file");
        if (!args.has("planner"))
            throw UsageError("plan needs --planner NAME (see michi list-planners)");
        ompl::msg::setLogLevel(args.verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
        const Problem problem = withChecker(loadProblem(args.positional[0]), args);
        const double seed = args.number("seed", problem.benchmark.seed, true);
        ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(seed));
        const std::size_t query = args.index("query");
        PlanningContext ctx = makePlanningContext(problem, query);
        const std::string name = args.get("planner");
        PlannerSpec spec{name, {}};
        for (const auto &s : problem.planners)
            if (s.name == name)
                spec = s;
        ompl::base::PlannerPtr planner;
        try
        {
            planner = allocatePlanner(name, ctx.setup->getSpaceInformation());
        }
        catch (const std::invalid_argument &e)
        {
            throw UsageError(e.what());
        }
        applyPlannerParams(*planner, spec, problem.file);
        ctx.setup->setPlanner(planner);
        const double time = args.number("time", problem.benchmark.timeLimit);
        const auto status = ctx.setup->solve(time);
        if (status != ompl::base::PlannerStatus::EXACT_SOLUTION)
        {
            std::cerr << "michi plan: " << problem.file << ": " << name << " found no path within " << time << " s ("
                      << status.asString() << ")" << std::endl;
            return 1;
        }
        ctx.setup->simplifySolution(time);  // bounded like the solve: OMPL's unbounded default can take minutes
        auto &path = ctx.setup->getSolutionPath();
        std::vector<std::vector<double>> states;
        for (const auto *s : path.getStates())
        {
            std::vector<double> values;
            ctx.setup->getStateSpace()->copyToReals(values, s);
            states.push_back(values);
        }
        std::ostringstream comment;
        comment << problem.name << " query " << query << ", " << name << ", " << states.size() << " states, length "
                << path.length() << ", clearance " << path.clearance();
        std::cout << "# " << comment.str() << "\n";
        for (const auto &s : states)
        {
            for (std::size_t i = 0; i < s.size(); ++i)
                std::cout << (i ? " " : "") << s[i];
            std::cout << "\n";
        }
        const fs::path out = args.get("out", ".");
        if (!fs::exists(out))
            fs::create_directories(out);
        const std::string stem = (out / (problem.name + "-" + fileSafe(name))).string();
        writePathFile(stem + ".path", problem.valueNames(), states, comment.str());
        writeProblemSvg(problem, {PlotPath{name, states}}, stem + ".svg", query);
        std::cerr << "michi plan: wrote " << stem << ".path and " << stem << ".svg" << std::endl;
        return 0;
    }

    int jmap(int argc, char **argv)
    {
        Args args(argc, argv, {"out", "verify", "seed"});
        if (args.positional.size() != 1)
            throw UsageError("jmap takes one problem file");
        if (!args.has("out"))
            throw UsageError("jmap needs --out DIR");
        ompl::msg::setLogLevel(args.verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
        const Problem problem = loadProblem(args.positional[0]);
        JMapReportOptions options;
        options.outDir = args.get("out");
        options.verify = static_cast<std::uint64_t>(args.number("verify", 0, true));
        options.seed = static_cast<unsigned int>(args.number("seed", problem.benchmark.seed, true));
        options.progress = &std::cerr;
        std::cout << runJMapReport(problem, options);
        std::cerr << "michi jmap: wrote " << (fs::path(options.outDir) / "jmap.json").string()
                  << " and jmap.svg (and .png)" << std::endl;
        return 0;
    }

    int lattice(int argc, char **argv)
    {
        Args args(argc, argv, {"out", "cell-sizes", "angle-steps", "time"});
        if (args.positional.size() != 1)
            throw UsageError("lattice takes one problem file");
        if (!args.has("out"))
            throw UsageError("lattice needs --out DIR");
        ompl::msg::setLogLevel(args.verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
        HeadingLatticeReportOptions options;
        options.outDir = args.get("out");
        options.timeLimit = args.number("time", options.timeLimit);
        if (args.has("cell-sizes"))
            options.cellSizes = parseNumberList(args.get("cell-sizes"), "--cell-sizes");
        if (args.has("angle-steps"))
            options.angleSteps = parseNumberList(args.get("angle-steps"), "--angle-steps");
        options.progress = &std::cerr;
        std::cout << runHeadingLatticeReport(loadProblem(args.positional[0]), options);
        return 0;
    }

    int dualarm(int argc, char **argv)
    {
        Args args(argc, argv, {"out", "time", "seed"});
        if (args.positional.size() != 1)
            throw UsageError("dualarm takes one problem file");
        if (!args.has("out"))
            throw UsageError("dualarm needs --out DIR");
        ompl::msg::setLogLevel(args.verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
        const Problem problem = loadProblem(args.positional[0]);
        ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(args.number("seed", problem.benchmark.seed, true)));
        DualArmOptions options;
        options.outDir = args.get("out");
        options.planningTime = args.number("time", 0.);
        options.progress = &std::cerr;
        std::cout << runDualArm(problem, options);
        std::cerr << "michi dualarm: wrote " << (fs::path(options.outDir) / "dualarm.json").string()
                  << " and dualarm-*.svg/.png" << std::endl;
        return 0;
    }

    int replan(int argc, char **argv)
    {
        Args args(argc, argv, {"out", "episodes", "seed", "methods"});
        if (args.positional.size() != 1)
            throw UsageError("replan takes one problem file");
        if (!args.has("out"))
            throw UsageError("replan needs --out DIR");
        ompl::msg::setLogLevel(args.verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_ERROR);
        ReplanOptions options;
        options.problemFile = args.positional[0];
        options.outDir = args.get("out");
        options.episodes = static_cast<unsigned int>(args.number("episodes", 20, true));
        options.seed = static_cast<unsigned int>(args.number("seed", 1, true));
        options.methods = splitComma(args.get("methods"));
        options.progress = &std::cerr;
        std::cout << runReplan(options);
        std::cerr << "michi replan: wrote " << (fs::path(options.outDir) / "replan.json").string() << std::endl;
        return 0;
    }

    int experienceQueries(int argc, char **argv)
    {
        Args args(argc, argv, {"out", "count", "training", "start-spread", "goal-spread", "seed"});
        if (args.positional.size() != 1 || !args.has("out"))
            throw UsageError("experience-queries takes one problem file and --out FILE");
        ExperienceQueriesOptions options;
        options.out = args.get("out");
        options.count = static_cast<std::size_t>(args.number("count", options.count, true));
        options.training = args.has("training") ? args.index("training") : options.training;
        options.startSpread = args.number("start-spread", options.startSpread);
        options.goalSpread = args.number("goal-spread", options.goalSpread);
        options.seed = static_cast<unsigned int>(args.number("seed", options.seed, true));
        std::cerr << writeExperienceQueriesFile(loadProblem(args.positional[0]), options) << std::endl;
        return 0;
    }

    int pathSeedFigure(int argc, char **argv)
    {
        Args args(argc, argv, {"out", "training", "held-out", "variant", "seed"});
        if (args.positional.size() != 1 || !args.has("out"))
            throw UsageError("path-seed-figure takes one problem file and --out FILE.svg");
        ompl::msg::setLogLevel(args.verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
        std::cerr << writePathSeedFigure(loadProblem(args.positional[0]), args.index("training"),
                                         args.index("held-out"), args.get("variant", "blocks"),
                                         static_cast<unsigned int>(args.number("seed", 1, true)), args.get("out"))
                  << std::endl;
        return 0;
    }

    int pathSeedLibrary(int argc, char **argv)
    {
        Args args(argc, argv, {"out", "variant", "seed"});
        if (args.positional.size() != 1 || !args.has("out"))
            throw UsageError("path-seed-library takes one problem file and --out FILE");
        ompl::msg::setLogLevel(args.verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
        std::cerr << writePathSeedLibrary(loadProblem(args.positional[0]), args.get("variant", "blocks"),
                                          static_cast<unsigned int>(args.number("seed", 1, true)), args.get("out"))
                  << std::endl;
        return 0;
    }

    int listPlanners()
    {
        for (const auto &name : plannerNames())
            std::cout << name << "\n";
        return 0;
    }
}  // namespace

int main(int argc, char **argv)
{
    if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "help")
    {
        std::cout << USAGE;
        return argc < 2 ? 2 : 0;
    }
    const std::string command = argv[1];
    try
    {
        if (command == "bench")
            return bench(argc, argv);
        if (command == "plan")
            return plan(argc, argv);
        if (command == "jmap")
            return jmap(argc, argv);
        if (command == "random-scenes")
            return michi::tools::randomScenesCommand(argc, argv);
        if (command == "lattice")
            return lattice(argc, argv);
        if (command == "dualarm")
            return dualarm(argc, argv);
        if (command == "circles")
            return michi::tools::circlesCommand(argc, argv);
        if (command == "replan")
            return replan(argc, argv);
        if (command == "experience-queries")
            return experienceQueries(argc, argv);
        if (command == "path-seed-figure")
            return pathSeedFigure(argc, argv);
        if (command == "path-seed-library")
            return pathSeedLibrary(argc, argv);
        if (command == "list-planners")
            return listPlanners();
        throw UsageError("unknown command '" + command + "'");
    }
    catch (const UsageError &e)
    {
        std::cerr << "michi: " << e.what() << "\n" << USAGE;
        return 2;
    }
    catch (const std::exception &e)
    {
        std::cerr << "michi " << command << ": " << e.what() << std::endl;
        return 1;
    }
}
