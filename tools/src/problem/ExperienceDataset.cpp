#include <michi/tools/problem/ExperienceDataset.h>
#include <michi/tools/problem/ExperienceQueries.h>

#include <michi/planners/experience/ExperiencePlanner.h>

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <stdexcept>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace tools
    {
        namespace
        {
            Dataset select(const Problem &problem, const Dataset &all, const std::string &key, const std::string &range)
            {
                const QuerySelection s = parseQuerySelection(range);  // checked by readExperienceQueries
                if (s.last >= all.entries.size())
                    throw ProblemError(problem.file, key,
                                       "problems " + range + " requested, " + problem.experience.dataset + " has " +
                                           std::to_string(all.entries.size()) + " (0-" +
                                           std::to_string(all.entries.size() - 1) + ")");
                Dataset d;
                d.name = all.name + "[" + range + "]";
                d.entries.assign(all.entries.begin() + static_cast<long>(s.first),
                                 all.entries.begin() + static_cast<long>(s.last) + 1);
                return d;
            }
        }  // namespace

        ExperienceDataset loadExperienceDataset(const Problem &problem)
        {
            const Dataset all = loadDatasetFolder(problem.experience.dataset);
            ExperienceDataset d;
            d.training = select(problem, all, "experience.training", problem.experience.trainingProblems);
            d.heldOut = select(problem, all, "experience.held_out", problem.experience.heldOutProblems);
            return d;
        }

        validity::ScenePtr copyScene(const validity::Scene &scene)
        {
            auto copy = std::make_shared<validity::Scene>();
            // A copy the dataset's scenes can be swapped into: the problem's own scene stays as loaded.
            copy->add(scene.obstacles());
            return copy;
        }

        namespace
        {
            bool samePose(const Eigen::Isometry3d &a, const Eigen::Isometry3d &b)
            {
                return a.matrix() == b.matrix();
            }

            /** Why the two robots differ ("" when they are one robot): the dataset's scenes are installed into
                the problem's planning context, whose checkers hold the problem's robot, so an entry may change the
                scene and the query but not the robot. Compared as loaded (kinematics, limits, collision shapes,
                allowed pairs, base), not by file name: copies of one URDF are one robot. */
            std::string robotDifference(const validity::RobotModel &a, const validity::RobotModel &b)
            {
                if (!samePose(a.basePose(), b.basePose()))
                    return "its base pose";
                if (a.links().size() != b.links().size() || a.joints().size() != b.joints().size())
                    return "its links or joints";
                for (std::size_t j = 0; j < a.joints().size(); ++j)
                {
                    const auto &x = a.joints()[j], &y = b.joints()[j];
                    if (x.name != y.name || x.type != y.type || x.parentLink != y.parentLink ||
                        x.childLink != y.childLink || !samePose(x.origin, y.origin) || x.axis != y.axis ||
                        x.lower != y.lower || x.upper != y.upper || x.mimic != y.mimic ||
                        x.mimicMultiplier != y.mimicMultiplier || x.mimicOffset != y.mimicOffset)
                        return "joint '" + x.name + "' (its type, origin, axis or limits)";
                }
                for (std::size_t l = 0; l < a.links().size(); ++l)
                {
                    const auto &x = a.links()[l], &y = b.links()[l];
                    bool same = x.name == y.name && x.collisions.size() == y.collisions.size();
                    for (std::size_t c = 0; same && c < x.collisions.size(); ++c)
                    {
                        const auto &sx = *x.collisions[c].shape, &sy = *y.collisions[c].shape;
                        same = samePose(x.collisions[c].origin, y.collisions[c].origin) && sx.type() == sy.type() &&
                               sx.size() == sy.size() && sx.vertices() == sy.vertices() &&
                               sx.triangles() == sy.triangles() && sx.outline() == sy.outline();
                    }
                    if (!same)
                        return "the collision geometry of link '" + x.name + "'";
                }
                if (a.selfCollisionPairs() != b.selfCollisionPairs())
                    return "its self-collision pairs (allowed collisions)";
                return "";
            }
        }  // namespace

        void installScene(const Problem &problem, const PlanningContext &ctx, const Problem &source)
        {
            if (source.kind != Problem::Kind::ARM || source.valueNames() != problem.valueNames())
                throw ProblemError(source.file, "robot",
                                   "plans other joints than " + problem.file + " (a dataset's problems share a robot)");
            // A held-out problem with a robot of its own (a grasped tool) was planned with the dataset problem's
            // robot and its paths reported solved and certified, through the tool.
            if (source.model && problem.model && source.model != problem.model)
            {
                const std::string why = robotDifference(*problem.model, *source.model);
                if (!why.empty())
                    throw ProblemError(source.file, "robot",
                                       "differs from " + problem.file + "'s robot in " + why +
                                           " (a dataset's problems share one robot)");
            }
            // only the joints not planned: the planned ones' values there are the request's start
            bool same = source.fixedValues.size() == ctx.fixedValues.size();
            for (std::size_t i = 0; i < source.fixedValues.size() && same; ++i)
                same = std::find(problem.groupVariables.begin(), problem.groupVariables.end(), static_cast<int>(i)) !=
                           problem.groupVariables.end() ||
                       source.fixedValues[i] == ctx.fixedValues[i];
            if (!same)
                throw ProblemError(
                    source.file, "request.start_state",
                    "the robot's other joints differ from " + problem.file + "'s (a dataset's problems share them)");
            // The context's scene object is kept (its checkers hold it): its obstacles are replaced, not the scene.
            for (const auto &obstacle : ctx.scene->obstacles())
                ctx.scene->remove(obstacle.name);
            ctx.scene->add(source.scene->obstacles());
        }

        void installDatasetQuery(const Problem &problem, const PlanningContext &ctx, const Problem &source,
                                 std::size_t query)
        {
            installScene(problem, ctx, source);
            const Query &q = source.queries.at(query);
            for (const auto *values : {&q.start, &q.goal})
            {
                const std::string why = invalidStateReason(ctx, *values);
                if (!why.empty())
                    throw ProblemError(source.file, queryEndKey(source, query, values == &q.start ? "start" : "goal"),
                                       why);
            }
            setQuery(ctx, q);
        }

        std::size_t trainOnDataset(const Problem &problem, const PlanningContext &ctx, const Dataset &training,
                                   double time, const std::vector<ob::PlannerPtr> &planners, std::ostream *progress)
        {
            std::vector<planners::ExperiencePlanner *> learners;
            for (const auto &planner : planners)
                if (auto *learner = dynamic_cast<planners::ExperiencePlanner *>(planner.get()))
                    learners.push_back(learner);
            if (learners.empty())
                return 0;
            const auto began = std::chrono::steady_clock::now();
            std::size_t learned = 0;
            for (const auto &entry : training.entries)
            {
                const Problem source = loadProblem(entry.problemFile);
                installDatasetQuery(problem, ctx, source, entry.query);
                og::PathGeometric path(ctx.setup->getSpaceInformation());
                if (!solveTrainingQuery(ctx, source.queries[entry.query], time, path))
                    continue;
                // each learner sees the path in the scene it was solved in, and all of them the same path
                for (auto *learner : learners)
                {
                    learner->sceneChanged();
                    learner->addExperience(path);
                }
                ++learned;
            }
            if (progress)
                *progress << "michi: training: " << learned << " of " << training.entries.size()
                          << " training problems of " << training.name << " solved by RRT-Connect (" << time
                          << " s each, each in its own scene) in " << std::setprecision(3)
                          << std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count()
                          << " s (not in run times)" << std::endl;
            return learned;
        }

        std::size_t learnBeforePlanning(const Problem &problem, const PlanningContext &ctx,
                                        const ob::PlannerPtr &planner, std::size_t query, std::ostream *progress)
        {
            auto *learner = dynamic_cast<planners::ExperiencePlanner *>(planner.get());
            if (learner == nullptr)
                return 0;
            std::size_t learned = trainExperiencePlanners(problem, ctx, {planner}, progress);
            if (problem.experience.dataset.empty())
                return learned;
            if (ctx.scene == problem.scene)
                // installScene() would clear the very obstacles it is about to copy back
                throw std::logic_error("learnBeforePlanning: the context shares the problem's scene");
            const ExperienceDataset sets = loadExperienceDataset(problem);
            learned +=
                trainOnDataset(problem, ctx, sets.training, problem.experience.trainingTime, {planner}, progress);
            // the training left its last problem's scene and query installed
            installDatasetQuery(problem, ctx, problem, query);
            learner->sceneChanged();
            return learned;
        }
    }  // namespace tools
}  // namespace michi
