#include <michi/tools/problem/ExperienceQueries.h>
#include <michi/tools/problem/Dataset.h>
#include <michi/tools/problem/ExperienceDataset.h>
#include <michi/tools/problem/TaskRegionQueries.h>
#include <michi/planners/path_seed/PathSeed.h>
#include "ProblemYaml.h"
#include <michi/validity/InputFile.h>

#include <michi/planners/experience/ExperiencePlanner.h>
#include <michi/planners/path_seed/PathSeedLibrary.h>
#include <michi/tools/FileOutput.h>

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include <yaml-cpp/yaml.h>

#include <boost/filesystem.hpp>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace fs = boost::filesystem;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace tools
    {
        namespace
        {
            std::vector<double> readState(const YAML::Node &n, const std::string &file, const std::string &key,
                                          const Problem &problem)
            {
                if (!n || !n.IsSequence())
                    throw ProblemError(file, key,
                                       "expected a list of " + std::to_string(problem.dimension()) + " numbers");
                if (n.size() != problem.dimension())
                    throw ProblemError(file, key,
                                       "expected " + std::to_string(problem.dimension()) + " numbers, got " +
                                           std::to_string(n.size()));
                std::vector<double> v;
                for (std::size_t i = 0; i < n.size(); ++i)
                {
                    double x;
                    try
                    {
                        x = n[i].as<double>();
                    }
                    catch (const YAML::Exception &)
                    {
                        throw ProblemError(file, key + "[" + std::to_string(i) + "]", "expected a number");
                    }
                    if (!std::isfinite(x))
                        throw ProblemError(file, key + "[" + std::to_string(i) + "]", "expected a finite number");
                    if (problem.kind == Problem::Kind::ARM)
                    {
                        const auto &j = problem.model->variableJoint(problem.groupVariables[i]);
                        // A continuous joint has no limits: any value names an angle.
                        if (j.type != validity::RobotJoint::Type::CONTINUOUS && (x < j.lower || x > j.upper))
                        {
                            std::ostringstream msg;
                            msg << "value " << x << " outside the limits of " << j.name << " [" << j.lower << ", "
                                << j.upper << "]";
                            throw ProblemError(file, key + "[" + std::to_string(i) + "]", msg.str());
                        }
                    }
                    v.push_back(x);
                }
                return v;
            }

            std::vector<Query> readList(const YAML::Node &root, const std::string &name, const std::string &file,
                                        const Problem &problem)
            {
                std::vector<Query> out;
                const YAML::Node list = root[name];
                if (!list || list.IsNull())
                    return out;
                if (!list.IsSequence())
                    throw ProblemError(file, name, "expected a list of {start, goal}");
                for (std::size_t i = 0; i < list.size(); ++i)
                {
                    const std::string key = name + "[" + std::to_string(i) + "]";
                    if (!list[i].IsMap())
                        throw ProblemError(file, key, "expected {start: [...], goal: [...]}");
                    out.push_back(Query{readState(list[i]["start"], file, key + ".start", problem),
                                        readState(list[i]["goal"], file, key + ".goal", problem),
                                        {}});
                }
                return out;
            }

            void setState(ob::ScopedState<> &state, const std::vector<double> &values)
            {
                state.getSpace()->copyFromReals(state.get(), values);
                state.getSpace()->enforceBounds(state.get());
            }

            std::string invalidReason(const PlanningContext &ctx, const std::vector<double> &values)
            {
                ob::ScopedState<> s(ctx.setup->getStateSpace());
                setState(s, values);
                if (!ctx.setup->getSpaceInformation()->satisfiesBounds(s.get()))
                    return "outside the state space bounds";
                // Bounds first: describeCollision() looks at geometry only and would call an out-of-bounds state fine.
                const std::string collision = ctx.checker->describeCollision(values.data());
                return collision.empty() ? "" : "in collision: " + collision;
            }

            // experience: {dataset: FOLDER, training: A-B, held_out: C-D}: the sets are problems of the folder
            // (Dataset.h), resolved by loadExperienceDataset() when a benchmark needs them
            void readExperienceDataset(const std::string &problemFile, const Problem &problem, const YAML::Node &e,
                                       ExperienceQueries &out)
            {
                // Two ways to give the sets (a queries file, or ranges of a folder of problems): both at once would
                // leave it unclear which the benchmark uses.
                if (e["queries"])
                    throw ProblemError(problemFile, "experience.queries",
                                       "give either queries (a queries file) or dataset (a folder of problems)");
                if (problem.kind != Problem::Kind::ARM)
                    throw ProblemError(problemFile, "experience", "experience queries need an arm problem");
                const YAML::Node d = e["dataset"];
                const fs::path p(d.IsScalar() ? d.Scalar() : std::string());
                const fs::path full = p.is_absolute() ? p : fs::path(problemFile).parent_path() / p;
                if (!d.IsScalar() || p.empty() || !fs::is_directory(full))
                    throw ProblemError(problemFile, "experience.dataset",
                                       "expected a folder of problem files, got '" + full.string() + "'");
                out.dataset = full.lexically_normal().string();
                QuerySelection sets[2];
                const char *keys[2] = {"training", "held_out"};
                for (int i = 0; i < 2; ++i)
                {
                    const std::string key = std::string("experience.") + keys[i];
                    const YAML::Node n = e[keys[i]];
                    if (!n || !n.IsScalar())
                        throw ProblemError(problemFile, key, "expected a range A-B of the dataset's problems (from 0)");
                    try
                    {
                        sets[i] = parseQuerySelection(n.Scalar());
                    }
                    catch (const std::invalid_argument &error)
                    {
                        throw ProblemError(problemFile, key, error.what());
                    }
                    if (sets[i].all)
                        throw ProblemError(problemFile, key,
                                           "expected a range A-B, not all (the sets must be disjoint)");
                    (i == 0 ? out.trainingProblems : out.heldOutProblems) = n.Scalar();
                }
                if (sets[0].first <= sets[1].last && sets[1].first <= sets[0].last)
                    throw ProblemError(problemFile, "experience.held_out",
                                       "overlaps experience.training: held-out problems must not be trained on");
            }

            double seconds(std::chrono::steady_clock::time_point since)
            {
                return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
            }
        }  // namespace

        ExperienceQueries readExperienceQueries(const std::string &problemFile, const Problem &problem)
        {
            ExperienceQueries out;
            // parsed once, by loadProblem(); only this section is copied
            const YAML::Node e = problem_file::loadYamlSection(problemFile, "experience");
            if (!e)
                return out;
            if (!e.IsMap())
                throw ProblemError(problemFile, "experience", "expected a mapping (queries, training_time)");
            for (const auto &kv : e)
            {
                const std::string k = kv.first.as<std::string>();
                if (k != "queries" && k != "training_time" && k != "library" && k != "dataset" && k != "training" &&
                    k != "held_out" && k != "learned_on")
                    throw ProblemError(problemFile, "experience." + k,
                                       "unknown key (expected queries, training_time, library, learned_on, dataset, "
                                       "training, held_out)");
            }
            if (const YAML::Node t = e["training_time"])
            {
                try
                {
                    out.trainingTime = t.as<double>();
                }
                catch (const YAML::Exception &)
                {
                    // Not a number: -1 lets the one check below give the one message for both mistakes.
                    out.trainingTime = -1.;
                }
                if (!(out.trainingTime > 0.))
                    throw ProblemError(problemFile, "experience.training_time",
                                       "expected a positive number of seconds");
            }
            // a file the experience key names: relative to the problem file, as for every other file a problem
            // names, so a problem folder can be moved as a whole
            auto existingFile = [&](const char *name, const std::string &what)
            {
                const YAML::Node l = e[name];
                const fs::path lp(l.IsScalar() ? l.Scalar() : std::string());
                const fs::path lfull = lp.is_absolute() ? lp : fs::path(problemFile).parent_path() / lp;
                if (!l.IsScalar() || !fs::is_regular_file(lfull))
                    throw ProblemError(problemFile, std::string("experience.") + name,
                                       "expected an existing " + what + ", got '" + lfull.string() + "'");
                return lfull.lexically_normal().string();
            };
            if (e["library"])
                out.library = existingFile("library", "experience file");
            if (e["learned_on"])
            {
                out.learnedOn = existingFile("learned_on", "problem file");
                if (fs::equivalent(fs::path(out.learnedOn), fs::path(problemFile)))
                    throw ProblemError(problemFile, "experience.learned_on", "names this problem itself");
            }
            if (e["dataset"])
            {
                if (!out.learnedOn.empty())
                    throw ProblemError(problemFile, "experience.learned_on",
                                       "not with experience.dataset (a dataset trains on its own problems)");
                readExperienceDataset(problemFile, problem, e, out);
                return out;
            }
            for (const char *k : {"training", "held_out"})
                if (e[k])
                    throw ProblemError(problemFile, std::string("experience.") + k,
                                       "only with experience.dataset (a queries file holds its own sets)");
            if (!e["queries"] || !e["queries"].IsScalar())
                throw ProblemError(problemFile, "experience.queries", "expected the name of a queries file");
            const fs::path p(e["queries"].Scalar());
            const fs::path full = p.is_absolute() ? p : fs::path(problemFile).parent_path() / p;
            out.file = full.lexically_normal().string();
            if (!fs::is_regular_file(full))
                throw ProblemError(problemFile, "experience.queries", "file '" + out.file + "' does not exist");
            if (problem.kind != Problem::Kind::ARM)
                throw ProblemError(problemFile, "experience", "experience queries need an arm problem");
            const YAML::Node q = problem_file::loadYaml(out.file);
            if (!q.IsMap())
                throw ProblemError(out.file, "", "expected a mapping with training and held_out");
            for (const auto &kv : q)
            {
                const std::string k = kv.first.as<std::string>();
                if (k != "training" && k != "held_out")
                    throw ProblemError(out.file, k, "unknown key (expected training, held_out)");
            }
            out.training = readList(q, "training", out.file, problem);
            out.heldOut = readList(q, "held_out", out.file, problem);
            if (!out.learnedOn.empty() && !out.training.empty())
                throw ProblemError(problemFile, "experience.learned_on",
                                   "the queries file " + out.file +
                                       " has training queries too: train on one or the other (learned_on: its "
                                       "problem's training queries)");
            return out;
        }

        ExperienceQueries generateExperienceQueries(const Problem &problem, std::size_t count, std::size_t training,
                                                    double startSpread, double goalSpread, unsigned int seed)
        {
            if (training > count)
                throw std::invalid_argument("more training queries than queries");
            const PlanningContext ctx = makePlanningContext(problem, 0);
            // A seeded generator of its own: the same options always write the same queries file.
            ompl::RNG rng(seed);
            ExperienceQueries out;
            out.trainingTime = problem.experience.trainingTime;
            for (std::size_t i = 0; i < count; ++i)
            {
                // Queries cycle over the problem's own queries, so training and held-out pairs cover each of them
                // alike.
                const Query &base = problem.queries[i % problem.queries.size()];
                Query q;
                bool found = false;
                // Rejection sampling: near obstacles most perturbations may collide; 10000 tries bound the work before
                // the spread is declared too large for this query.
                for (int attempt = 0; attempt < 10000 && !found; ++attempt)
                {
                    q = base;
                    // rounded to the 6 decimals the file keeps, so the values checked are the values written
                    for (auto &x : q.start)
                        x = std::round((x + rng.uniformReal(-startSpread, startSpread)) * 1e6) / 1e6;
                    for (auto &x : q.goal)
                        x = std::round((x + rng.uniformReal(-goalSpread, goalSpread)) * 1e6) / 1e6;
                    found = invalidReason(ctx, q.start).empty() && invalidReason(ctx, q.goal).empty();
                    // the stored values are the ones checked: within joint limits (enforceBounds would clamp); a
                    // problem without a URDF arm (an SE(2) robot) has no joints, its bounds were checked above
                    for (std::size_t k = 0; problem.kind == Problem::Kind::ARM && k < q.start.size() && found; ++k)
                    {
                        const auto &j = problem.model->variableJoint(problem.groupVariables[k]);
                        if (j.type != validity::RobotJoint::Type::CONTINUOUS)
                            found = q.start[k] >= j.lower && q.start[k] <= j.upper && q.goal[k] >= j.lower &&
                                    q.goal[k] <= j.upper;
                    }
                }
                if (!found)
                    throw std::runtime_error(problem.file + ": no valid start/goal pair near query " +
                                             std::to_string(i % problem.queries.size()) + " in 10000 attempts");
                (i < training ? out.training : out.heldOut).push_back(q);
            }
            return out;
        }

        std::string experienceQueriesYaml(const ExperienceQueries &queries, const std::string &header)
        {
            std::ostringstream out;
            out << header;
            // Six decimals, the precision generateExperienceQueries() rounds to: the values written are the values it
            // checked.
            out << std::setprecision(6) << std::fixed;
            auto list = [&](const char *name, const std::vector<Query> &qs)
            {
                out << name << ":" << (qs.empty() ? " []" : "") << "\n";
                auto values = [&](const std::vector<double> &v)
                {
                    out << "[";
                    for (std::size_t i = 0; i < v.size(); ++i)
                        out << (i ? ", " : "") << v[i];
                    out << "]";
                };
                for (const auto &q : qs)
                {
                    out << "  - {start: ";
                    values(q.start);
                    out << ", goal: ";
                    values(q.goal);
                    out << "}\n";
                }
            };
            list("training", queries.training);
            list("held_out", queries.heldOut);
            return out.str();
        }

        std::string writeExperienceQueriesFile(const Problem &problem, const ExperienceQueriesOptions &options)
        {
            const bool fromRegions = !options.regions.empty();
            const TaskRegions regions = fromRegions ? readTaskRegions(options.regions, problem) : TaskRegions();
            const auto queries =
                fromRegions ? generateTaskRegionQueries(problem, regions, options.count, options.training, options.seed)
                            : generateExperienceQueries(problem, options.count, options.training, options.startSpread,
                                                        options.goalSpread, options.seed);
            std::ostringstream header;
            header << "# Experience queries of " << fs::path(problem.file).filename().string()
                   << " (docs/path-seed.md): training and held-out start/goal pairs, disjoint.\n"
                   << "# Made by: michi experience-queries " << fs::path(problem.file).filename().string()
                   << " --count " << options.count << " --training " << options.training;
            if (fromRegions)
            {
                header << " --regions " << fs::path(options.regions).filename().string() << " --seed " << options.seed
                       << " --out " << fs::path(options.out).filename().string() << "\n"
                       << "# Start and goal of each pair are drawn independently: a (start region, goal region) pair "
                          "of the regions file,\n# then in each region a hand pose ("
                       << regions.tipLink
                       << "'s tool point in the region's box, its axis within the region's cone), solved by IK;\n"
                       << "# training and held-out pairs come from that one distribution. Regions:";
                for (const auto &region : regions.regions)
                    header << " " << region.name;
                header << ".\n";
            }
            else
                header << " --start-spread " << options.startSpread << " --goal-spread " << options.goalSpread
                       << " --seed " << options.seed << " --out " << fs::path(options.out).filename().string() << "\n"
                       << "# Pair i perturbs the problem's query i mod " << problem.queries.size()
                       << " uniformly per joint (start by +-" << options.startSpread << " rad, goal by +-"
                       << options.goalSpread << " rad);\n";
            header << "# every start and goal is within the joint limits and collision-free (FCL).\n";
            writeAtomically(experienceQueriesYaml(queries, header.str()), options.out);
            std::ostringstream report;
            report << "michi experience-queries: wrote " << options.out << " (" << queries.training.size()
                   << " training, " << queries.heldOut.size() << " held-out queries)";
            return report.str();
        }

        namespace
        {
            /** why path-seed-library writes nothing when RRT-Connect solved none of \e what */
            std::string noSeedsLearned(const std::string &what, double time)
            {
                std::ostringstream message;
                message << "none of the " << what << " was solved by RRT-Connect in " << time
                        << " s each (experience.training_time): no seeds to learn, and an empty library written as "
                           "if it were one would mislead every later run; nothing written";
                return message.str();
            }
        }  // namespace

        std::string writePathSeedLibrary(const Problem &problem, const std::string &variant, unsigned int seed,
                                         const std::string &file)
        {
            // Before anything draws from OMPL's generator: RRT-Connect's training paths, and so the library, follow
            // from --seed.
            ompl::RNG::setSeed(seed);
            if (!problem.experience.dataset.empty())
            {
                // a dataset problem: trained as michi bench trains, each training problem in its own scene
                ContextOptions options;
                options.scene = copyScene(*problem.scene);
                const PlanningContext dctx = makePlanningContext(problem, options);
                auto planner = std::make_shared<planners::PathSeed>(dctx.setup->getSpaceInformation());
                planner->setVariant(variant);
                const auto sets = loadExperienceDataset(problem);
                trainOnDataset(problem, dctx, sets.training, problem.experience.trainingTime, {planner}, nullptr);
                // nothing learned: an empty library would mislead every later run as much as one with no training
                if (planner->experienceCount() == 0)
                    throw ProblemError(problem.file, "experience",
                                       noSeedsLearned(std::to_string(sets.training.entries.size()) +
                                                          " training problems of " + sets.training.name,
                                                      problem.experience.trainingTime));
                planner->saveLibrary(file);
                std::ostringstream report;
                report << "michi path-seed-library: wrote " << file << " (" << planner->experienceCount() << " "
                       << variant << " seeds from " << sets.training.entries.size() << " training problems of "
                       << sets.training.name << ")";
                return report.str();
            }
            // nothing to learn from: an empty library written as if it were one would mislead every later run
            if (problem.experience.training.empty())
                throw ProblemError(
                    problem.file, "experience",
                    "no training queries to learn seeds from (experience.queries or experience.dataset)");
            const PlanningContext ctx = makePlanningContext(problem, 0);
            planners::PathSeedLibrary library(planners::seedVariantFromName(variant));
            const auto paths = solveTrainingQueries(problem, ctx, nullptr);
            std::vector<double> reals;
            for (const auto &path : paths)
            {
                std::vector<Eigen::VectorXd> states;
                for (const auto *s : const_cast<og::PathGeometric &>(path).getStates())
                {
                    ctx.setup->getStateSpace()->copyToReals(reals, s);
                    states.push_back(Eigen::Map<const Eigen::VectorXd>(reals.data(), reals.size()));
                }
                library.add(states);
            }
            if (library.size() == 0)
                throw ProblemError(
                    problem.file, "experience",
                    noSeedsLearned(std::to_string(problem.experience.training.size()) + " training queries",
                                   problem.experience.trainingTime));
            library.save(file);
            std::ostringstream report;
            report << "michi path-seed-library: wrote " << file << " (" << library.size() << " " << variant
                   << " seeds from " << problem.experience.training.size() << " training queries)";
            return report.str();
        }

        bool solveTrainingQuery(const PlanningContext &ctx, const Query &query, double time, og::PathGeometric &path)
        {
            const auto si = ctx.setup->getSpaceInformation();
            auto pdef = std::make_shared<ob::ProblemDefinition>(si);
            ob::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
            setState(start, query.start);
            setState(goal, query.goal);
            pdef->setStartAndGoalStates(start, goal);
            og::RRTConnect rrt(si);
            rrt.setProblemDefinition(pdef);
            rrt.setup();
            // Paper 001's seeds come from RRT-Connect with a time limit (5 s there); a query it does not solve
            // gives no seed.
            if (rrt.solve(ob::timedPlannerTerminationCondition(time)) != ob::PlannerStatus::EXACT_SOLUTION)
                return false;
            path = *pdef->getSolutionPath()->as<og::PathGeometric>();
            og::PathSimplifier simplifier(si);
            // Simplified before it is stored: RRT-Connect's raw paths zigzag, and the zigzag would be decoded into
            // every new query.
            simplifier.simplify(path, 1.);
            // The simplifier's shortcuts are checked motions, but the whole path is checked once more before it
            // becomes experience.
            return path.check();
        }

        std::vector<og::PathGeometric> solveTrainingQueries(const Problem &problem, const PlanningContext &ctx,
                                                            std::ostream *progress, std::optional<std::size_t> only)
        {
            const auto si = ctx.setup->getSpaceInformation();
            const auto &training = problem.experience.training;
            std::vector<og::PathGeometric> paths;
            const auto began = std::chrono::steady_clock::now();
            for (std::size_t i = only ? *only : 0; i < (only ? std::min(*only + 1, training.size()) : training.size());
                 ++i)
            {
                const std::string key = "experience.training[" + std::to_string(i) + "]";
                for (const auto *which : {"start", "goal"})
                {
                    const std::string why =
                        invalidReason(ctx, std::string(which) == "start" ? training[i].start : training[i].goal);
                    if (!why.empty())
                        throw ProblemError(problem.experience.file, key + "." + which, why);
                }
                og::PathGeometric path(si);
                if (solveTrainingQuery(ctx, training[i], problem.experience.trainingTime, path))
                    paths.push_back(path);
            }
            if (progress)
                *progress << "michi: training: " << paths.size() << " of " << (only ? 1 : training.size())
                          << " training queries solved by RRT-Connect (" << problem.experience.trainingTime
                          << " s each) in " << std::setprecision(3) << seconds(began) << " s (not in run times)"
                          << std::endl;
            return paths;
        }

        namespace
        {
            /** experience.learned_on: the other problem's training queries solved on its robot, in its scene; the
                paths' joint values handed, as paths of this problem's space, to every learner, which checks them on
                this robot as it checks any experience (PathSeed and Lightning when they use a path, Thunder's
                roadmap when it inserts one). */
            std::size_t trainOnOtherProblem(const Problem &problem, const PlanningContext &ctx,
                                            const std::vector<planners::ExperiencePlanner *> &learners,
                                            std::ostream *progress)
            {
                const Problem other = loadProblem(problem.experience.learnedOn);
                const auto names = [](const Problem &p)
                {
                    std::vector<std::string> out;
                    for (int v : p.groupVariables)
                        out.push_back(p.model->variableJoint(static_cast<std::size_t>(v)).name);
                    return out;
                };
                if (other.kind != Problem::Kind::ARM || problem.kind != Problem::Kind::ARM ||
                    names(other) != names(problem))
                    throw ProblemError(problem.file, "experience.learned_on",
                                       other.file +
                                           " plans other joints than this problem (a kinematic change keeps "
                                           "the joints and changes the robot's geometry)");
                if (other.experience.training.empty())
                    throw ProblemError(problem.file, "experience.learned_on",
                                       other.file + " has no training queries (experience.queries)");
                const PlanningContext otherCtx = makePlanningContext(other, 0);
                const auto paths = solveTrainingQueries(other, otherCtx, progress);
                const auto otherSpace = otherCtx.setup->getStateSpace(), space = ctx.setup->getStateSpace();
                std::vector<double> values;
                for (const auto &path : paths)
                {
                    og::PathGeometric here(ctx.setup->getSpaceInformation());
                    ob::ScopedState<> state(space);
                    for (std::size_t i = 0; i < path.getStateCount(); ++i)
                    {
                        otherSpace->copyToReals(values, path.getState(i));
                        space->copyFromReals(state.get(), values);
                        here.append(state.get());
                    }
                    for (auto *learner : learners)
                        learner->addExperience(here);
                }
                if (progress)
                    *progress << "michi: experience learned on " << other.file << " (" << paths.size()
                              << " paths of its robot); this problem's robot checks them when it uses them"
                              << std::endl;
                return paths.size();
            }
        }  // namespace

        std::size_t trainExperiencePlanners(const Problem &problem, const PlanningContext &ctx,
                                            const std::vector<ob::PlannerPtr> &planners, std::ostream *progress)
        {
            std::vector<planners::ExperiencePlanner *> learners;
            for (const auto &planner : planners)
                if (auto *learner = dynamic_cast<planners::ExperiencePlanner *>(planner.get()))
                    learners.push_back(learner);
            if (!problem.experience.library.empty())
                for (auto *learner : learners)
                    if (!learner->loadExperience(problem.experience.library) && progress)
                        *progress << "michi: experience.library: " << dynamic_cast<ob::Planner *>(learner)->getName()
                                  << " cannot read " << problem.experience.library
                                  << " (not its format); it starts empty" << std::endl;
            if (learners.empty())
                return 0;
            if (!problem.experience.learnedOn.empty())
                return trainOnOtherProblem(problem, ctx, learners, progress);
            if (problem.experience.training.empty())
                return 0;
            // Solved once and handed to every learner: experience planners compared in one benchmark learn from the
            // same paths.
            const auto paths = solveTrainingQueries(problem, ctx, progress);
            for (auto *learner : learners)
                for (const auto &path : paths)
                    learner->addExperience(path);
            return paths.size();
        }

        void checkHeldOutQueries(const Problem &problem, const PlanningContext &ctx)
        {
            const auto &heldOut = problem.experience.heldOut;
            // Checked before the first run (as michi bench checks everything it can): a bad held-out query is an error
            // in the queries file, not a run that fails.
            for (std::size_t i = 0; i < heldOut.size(); ++i)
            {
                const std::string key = "experience.held_out[" + std::to_string(i) + "]";
                std::string why = invalidReason(ctx, heldOut[i].start);
                if (!why.empty())
                    throw ProblemError(problem.experience.file, key + ".start", why);
                why = invalidReason(ctx, heldOut[i].goal);
                if (!why.empty())
                    throw ProblemError(problem.experience.file, key + ".goal", why);
            }
        }

        std::string invalidStateReason(const PlanningContext &ctx, const std::vector<double> &values)
        {
            return invalidReason(ctx, values);
        }

        void setQuery(const PlanningContext &ctx, const Query &query)
        {
            const auto space = ctx.setup->getStateSpace();
            ob::ScopedState<> start(space), goal(space);
            setState(start, query.start);
            setState(goal, query.goal);
            const auto pdef = ctx.setup->getProblemDefinition();
            // addStartState() appends: without this, the previous run's start would stay as a second start state.
            pdef->clearStartStates();
            pdef->addStartState(start);
            pdef->setGoalState(goal);
            // a grasp among a dataset's queries needs the sphere checker's exact states, the others not
            chooseExactStates(ctx, query.start, query.goal);
        }
    }  // namespace tools
}  // namespace michi
