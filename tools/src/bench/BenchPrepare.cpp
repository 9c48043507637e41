#include "bench/BenchSession.h"

#include <michi/tools/bench/PathCertificate.h>
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/tools/problem/ExperienceQueries.h>
#include <michi/planners/experience/ExperiencePlanner.h>

#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <iomanip>

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;

namespace michi
{
    namespace tools
    {
        void BenchSession::prepare()
        {
            if (options.outDir.empty())
                throw std::invalid_argument("no output folder given");
            timeLimit = options.timeLimit > 0. ? options.timeLimit : problem.benchmark.timeLimit;
            runs = options.runs > 0 ? options.runs : problem.benchmark.runs;
            // a dataset run: run i of every planner plans query i of the selection
            const std::string queries = !options.queries.empty() ? options.queries : problem.benchmark.queries;
            if (!queries.empty())
            {
                try
                {
                    dataset = datasetOf(problem, parseQuerySelection(queries));
                }
                catch (const std::invalid_argument &e)
                {
                    throw ProblemError(problem.file, "benchmark.queries", e.what());
                }
                if (dataset.entries.empty())
                    throw ProblemError(problem.file, "benchmark.queries", "selects no query");
                // One run per query: every planner plans each selected query once, and run i means the same query for
                // all.
                runs = static_cast<unsigned int>(dataset.entries.size());
            }
            datasetRun = !dataset.entries.empty();
            experienceDataset = options.heldOut && !problem.experience.dataset.empty();
            if (experienceDataset)
            {
                if (datasetRun)
                    throw ProblemError(problem.file, "benchmark.queries",
                                       "an experience dataset's runs are its held-out problems (no --queries)");
                experienceSets = loadExperienceDataset(problem);
                for (const auto &entry : experienceSets.heldOut.entries)
                    heldOutProblems.push_back(loadProblem(entry.problemFile));
                heldOutFirst = parseQuerySelection(problem.experience.heldOutProblems).first;
                runs = options.runs > 0 ? options.runs : static_cast<unsigned int>(heldOutProblems.size());
                // scenes of the dataset's problems are installed in a copy, never in the problem's own
                contextOptions.scene = copyScene(*problem.scene);
            }
            if (options.planners.empty())
                specs = problem.planners;
            else
                for (const auto &name : options.planners)
                {
                    auto it = std::find_if(problem.planners.begin(), problem.planners.end(),
                                           [&](const PlannerSpec &s)
                                           {
                                               return s.name == name;
                                           });
                    specs.push_back(it != problem.planners.end() ? *it : PlannerSpec{name, {}, {}});
                }

            // Before any context or planner exists: everything they draw follows from benchmark.seed.
            ompl::RNG::setSeed(problem.benchmark.seed);
            contextOptions.query = datasetRun ? dataset.entries.front().query : options.query;
            compareCheckers = !compare.empty();
            if (compare == "fcl")
                throw std::invalid_argument("compareChecker: name a checker other than fcl");
            if (compareCheckers)
                contextOptions.checker = compare;  // the context then holds both checkers and both motion validators
            // planners[i].checker: planners on their own checker beside the others (compare mode runs every planner
            // on both checkers, so there it is not needed). A context holds FCL and at most one other checker.
            if (!compareCheckers)
                for (std::size_t i = 0; i < specs.size(); ++i)
                {
                    const std::string &c = specs[i].checker;
                    if (c.empty() || c == problem.checker || c == "fcl")
                        continue;
                    if (problem.checker != "fcl" || (!ownChecker.empty() && c != ownChecker))
                        throw ProblemError(problem.file, "planners[" + std::to_string(i) + "].checker",
                                           "a benchmark runs FCL and at most one other checker (here " +
                                               (problem.checker != "fcl" ? problem.checker : ownChecker) + ")");
                    ownChecker = c;
                }
            if (!ownChecker.empty())
                contextOptions.checker = ownChecker;
            // A dataset's scenes are swapped in the context's scene object: FCL and the sphere checker follow its
            // changes (Scene::changeCount()); the J-map and the grid checker precompute the scene.
            const std::string datasetChecker = ownChecker.empty() ? problem.checker : ownChecker;
            if (experienceDataset && ((datasetChecker != "fcl" && datasetChecker != "spheres") || compareCheckers))
                throw ProblemError(problem.file, "experience.dataset",
                                   "an experience dataset runs on the FCL or the sphere checker only "
                                   "(collision.checker: fcl or spheres; not --checker fcl,OTHER)");
            ctx = makePlanningContext(problem, contextOptions);  // checks start and goal
            si = ctx.setup->getSpaceInformation();
            if (experienceDataset)
                for (std::size_t k = 0; k < heldOutProblems.size(); ++k)  // every held-out query, before any run
                    installDatasetQuery(problem, ctx, heldOutProblems[k], experienceSets.heldOut.entries[k].query);
            if (datasetRun)
                checkDatasetQueries(problem, ctx, dataset);
            // checker and motion validator of each planner instance (compareCheckers: FCL ones, then the other's)
            const ob::StateValidityCheckerPtr fastChecker = si->getStateValidityChecker();
            const ob::MotionValidatorPtr fastMotions = si->getMotionValidator();
            const ob::MotionValidatorPtr fclMotions = ctx.referenceMotions;

            benchmark = std::make_unique<ot::Benchmark>(*ctx.setup, problem.name);
            const bool mixedCheckers = std::any_of(specs.begin(), specs.end(),
                                                   [this](const PlannerSpec &spec)
                                                   {
                                                       return !spec.checker.empty() && spec.checker != problem.checker;
                                                   });
            for (const auto &spec : specs)
            {
                auto make = [&]
                {
                    try
                    {
                        return makePlanner(problem, spec.name, si, spec.params);
                    }
                    catch (const std::invalid_argument &e)
                    {
                        throw ProblemError(problem.file, "planners", e.what());
                    }
                };
                ob::PlannerPtr planner = make();
                if (!compareCheckers)
                {
                    // the context's installed checker is the problem's, or ownChecker (then FCL is the default)
                    const std::string installed = ownChecker.empty() ? problem.checker : ownChecker;
                    const std::string wanted = spec.checker.empty() ? problem.checker : spec.checker;
                    if (wanted != problem.checker)
                        planner->setName(planner->getName() + "_" + wanted);
                    // With planners on different checkers every planner names its own: the pre-run event would
                    // otherwise leave the previous planner's checker installed for one that has no entry.
                    if (mixedCheckers)
                        checking[planner.get()] =
                            wanted == installed ? std::make_pair(fastChecker, fastMotions)
                                                : std::make_pair(ob::StateValidityCheckerPtr(ctx.checker), fclMotions);
                    benchmark->addPlanner(planner);
                    planners.push_back(planner);
                    continue;
                }
                benchmark->addPlanner(planner);
                planners.push_back(planner);
                checking[planner.get()] = {ctx.checker, fclMotions};
                // Both instances run in the same OMPL Benchmark, alternating, so the two checkers are compared under
                // the same load.
                auto withFast = make();
                withFast->setName(withFast->getName() + "_" + compare);
                benchmark->addPlanner(withFast);
                planners.push_back(withFast);
                checking[withFast.get()] = {fastChecker, fastMotions};
            }
            benchmark->addExperimentParameter("query", "INTEGER", std::to_string(options.query));
            // experience planners learn the training queries' solutions before the runs (not timed); run i of every
            // planner plans held-out query i mod n (docs/path-seed.md, ExperienceQueries.h)
            const auto &heldOut = problem.experience.heldOut;
            cycleHeldOut = options.heldOut && !heldOut.empty() && !datasetRun;
            if (datasetRun)
            {
                benchmark->addExperimentParameter("dataset", "VARCHAR(128)", dataset.name);
                benchmark->addExperimentParameter("dataset_queries", "INTEGER", std::to_string(dataset.entries.size()));
            }
            if (cycleHeldOut)
            {
                checkHeldOutQueries(problem, ctx);
                benchmark->addExperimentParameter("held_out_queries", "INTEGER", std::to_string(heldOut.size()));
            }
            if (experienceDataset)
            {
                benchmark->addExperimentParameter("experience_dataset", "VARCHAR(128)", experienceSets.heldOut.name);
                benchmark->addExperimentParameter("held_out_queries", "INTEGER",
                                                  std::to_string(heldOutProblems.size()));
            }
            if (cycleHeldOut || !checking.empty() || datasetRun || experienceDataset)
                benchmark->setPreRunEvent(
                    [this](const ob::PlannerPtr &planner)
                    {
                        if (experienceDataset)
                        {
                            // the run's own scene and query; installed before OMPL starts the run's clock
                            const std::size_t k = datasetNext[planner.get()]++ % heldOutProblems.size();
                            runQuery[planner.get()] = k;
                            installDatasetQuery(problem, ctx, heldOutProblems[k],
                                                experienceSets.heldOut.entries[k].query);
                            if (auto *learner = dynamic_cast<planners::ExperiencePlanner *>(planner.get()))
                                learner->sceneChanged();
                        }
                        if (datasetRun)
                        {
                            const auto &entry = dataset.entries[datasetNext[planner.get()]++ % dataset.entries.size()];
                            runQuery[planner.get()] = entry.query;
                            setQuery(ctx, problem.queries[entry.query]);
                        }
                        if (cycleHeldOut)
                        {
                            const auto &heldOut = problem.experience.heldOut;
                            setQuery(ctx, heldOut[heldOutRun[planner->getName()]++ % heldOut.size()]);
                        }
                        const auto it = checking.find(planner.get());
                        if (it != checking.end())
                        {
                            // SimpleSetup::setup() sets the space information up again before the run
                            si->setStateValidityChecker(it->second.first);
                            si->setMotionValidator(it->second.second);
                        }
                    });
            if (compareCheckers)
                benchmark->addExperimentParameter("checkers", "VARCHAR(32)", "fcl," + compare);
            trainExperiencePlanners(problem, ctx, planners, options.progress);
            if (experienceDataset)
                trainOnDataset(problem, ctx, experienceSets.training, problem.experience.trainingTime, planners,
                               options.progress);
            benchmark->addExperimentParameter("seed", "INTEGER", std::to_string(problem.benchmark.seed));
        }
    }  // namespace tools
}  // namespace michi
