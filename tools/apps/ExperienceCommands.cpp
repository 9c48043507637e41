// The experience sub-commands (docs/path-seed.md): `michi experience-queries`, `michi path-seed-figure` and
// `michi path-seed-library`.
#include "CommandLine.h"

#include <michi/tools/pictures/PathSeedFigure.h>
#include <michi/tools/problem/ExperienceQueries.h>
#include <michi/tools/problem/Problem.h>

#include <iostream>
#include <memory>

namespace michi
{
    namespace tools
    {
        namespace cli
        {
            namespace
            {
                /** indices and counts of queries */
                constexpr std::uint64_t MAX_QUERIES = 1000000;
                /** spreads are joint angles: a few turns at most */
                constexpr double MAX_SPREAD = 100.;

                const std::vector<std::string> VARIANTS{"blocks", "rotation"};

                struct ExperienceQueriesArgs
                {
                    std::string problem;
                    std::string out;
                    std::optional<std::size_t> count;
                    std::optional<std::size_t> training;
                    std::optional<double> startSpread;
                    std::optional<double> goalSpread;
                    std::optional<unsigned int> seed;
                    std::string regions;
                    bool verbose{false};
                };

                int runExperienceQueries(const ExperienceQueriesArgs &args)
                {
                    checkOutputPath("--out", args.out, OutputKind::FILE);
                    if (args.verbose)  // without --verbose, OMPL's log level is left as it is (as before)
                        setOmplLogLevel(true);
                    ExperienceQueriesOptions options;
                    options.out = args.out;
                    options.count = args.count.value_or(options.count);
                    options.training = args.training.value_or(options.training);
                    // Checked here, against both options: a usage error (exit 2), not a failed run.
                    if (options.training > options.count)
                        throw UsageError("--training: expected at most --count (" + std::to_string(options.count) +
                                         ") queries, got '" + std::to_string(options.training) + "'");
                    options.startSpread = args.startSpread.value_or(options.startSpread);
                    options.goalSpread = args.goalSpread.value_or(options.goalSpread);
                    options.seed = args.seed.value_or(options.seed);
                    options.regions = args.regions;
                    std::cerr << writeExperienceQueriesFile(loadProblem(args.problem), options) << std::endl;
                    return 0;
                }

                struct PathSeedArgs
                {
                    std::string problem;
                    std::string out;
                    std::optional<std::size_t> training;
                    std::optional<std::size_t> heldOut;
                    std::optional<std::string> variant;
                    std::optional<unsigned int> seed;
                    bool verbose{false};
                };

                int runPathSeedFigure(const PathSeedArgs &args)
                {
                    checkOutputPath("--out", args.out, OutputKind::FILE);
                    setOmplLogLevel(args.verbose);
                    std::cerr << writePathSeedFigure(loadProblem(args.problem), args.training.value_or(0),
                                                     args.heldOut.value_or(0), args.variant.value_or("blocks"),
                                                     args.seed.value_or(1), args.out)
                              << std::endl;
                    return 0;
                }

                int runPathSeedLibrary(const PathSeedArgs &args)
                {
                    checkOutputPath("--out", args.out, OutputKind::FILE);
                    setOmplLogLevel(args.verbose);
                    std::cerr << writePathSeedLibrary(loadProblem(args.problem), args.variant.value_or("blocks"),
                                                      args.seed.value_or(1), args.out)
                              << std::endl;
                    return 0;
                }
            }  // namespace

            Runner addExperienceQueries(CLI::App &michi)
            {
                auto args = std::make_shared<ExperienceQueriesArgs>();
                CLI::App *c = michi.add_subcommand("experience-queries",
                                                   "training and held-out start/goal pairs (docs/path-seed.md)");
                addProblem(*c, args->problem);
                addOut(*c, args->out, "the queries file to write")->type_name("FILE");
                addInteger(*c, "--count", args->count, 1, MAX_QUERIES, "pairs in all (default 160)");
                addInteger(*c, "--training", args->training, 0, MAX_QUERIES,
                           "the first N are the training set, the rest held out (default 60)");
                CLI::Option *start = addReal(*c, "--start-spread", args->startSpread, 0., MAX_SPREAD,
                                             "uniform perturbation of the starts per joint (> 0; default 0.3)", "RAD");
                CLI::Option *goal = addReal(*c, "--goal-spread", args->goalSpread, 0., MAX_SPREAD,
                                            "uniform perturbation of the goals per joint (> 0; default 0.05)", "RAD");
                c->add_option("--regions", args->regions,
                              "task regions (YAML): start and goal drawn independently from hand poses in them, "
                              "solved by IK, instead of perturbing the problem's queries")
                    ->type_name("FILE")
                    ->excludes(start)
                    ->excludes(goal);
                addSeed(*c, args->seed, "seed (default 1)");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    return runExperienceQueries(*args);
                };
            }

            Runner addPathSeedFigure(CLI::App &michi)
            {
                auto args = std::make_shared<PathSeedArgs>();
                CLI::App *c = michi.add_subcommand(
                    "path-seed-figure", "a training path and its seed decoded for a held-out query (an SVG picture)");
                addProblem(*c, args->problem);
                addOut(*c, args->out, "the picture to write")->type_name("FILE.svg");
                addInteger(*c, "--training", args->training, 0, MAX_QUERIES, "training query (default 0)")
                    ->type_name("I");
                addInteger(*c, "--held-out", args->heldOut, 0, MAX_QUERIES, "held-out query (default 0)")
                    ->type_name("J");
                addChoice(*c, "--variant", args->variant, VARIANTS, "path seed encoding (default blocks)");
                addSeed(*c, args->seed, "seed (default 1)");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    return runPathSeedFigure(*args);
                };
            }

            Runner addPathSeedLibrary(CLI::App &michi)
            {
                auto args = std::make_shared<PathSeedArgs>();
                CLI::App *c = michi.add_subcommand(
                    "path-seed-library",
                    "learn path seeds from the problem's training queries and save them (experience.library)");
                addProblem(*c, args->problem);
                addOut(*c, args->out, "the library file to write")->type_name("FILE");
                addChoice(*c, "--variant", args->variant, VARIANTS, "path seed encoding (default blocks)");
                addSeed(*c, args->seed, "seed (default 1)");
                addVerbose(*c, args->verbose);
                return [args]
                {
                    return runPathSeedLibrary(*args);
                };
            }
        }  // namespace cli
    }      // namespace tools
}  // namespace michi
