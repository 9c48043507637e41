#ifndef MICHI_TOOLS_PROBLEM_EXPERIENCE_DATASET_
#define MICHI_TOOLS_PROBLEM_EXPERIENCE_DATASET_

#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Dataset.h>

#include <ompl/base/Planner.h>

#include <memory>
#include <ostream>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief An experience problem whose queries are problems of a dataset folder (docs/path-seed.md):
            \code
            experience:
              dataset: datasets/table_pick   # a folder of problem files (loadDatasetFolder), in file order
              training: 0-49                 # the problems the experience planners learn from (scene and query)
              held_out: 50-99                # one per benchmark run, each in its own scene
              training_time: 5
            \endcode
            Every problem must plan the same joints of the same robot as the problem naming the dataset. */
        struct ExperienceDataset
        {
            Dataset training;
            Dataset heldOut;
        };

        /** \brief The folder's entries split by experience.training / held_out. Throws ProblemError naming
            the problem file and key when a range goes past the folder's entries. */
        ExperienceDataset loadExperienceDataset(const Problem &problem);

        /** \brief A copy of \e scene's obstacles (a dataset run installs other scenes in it, never in the
            problem's own). */
        validity::ScenePtr copyScene(const validity::Scene &scene);

        /** \brief Put \e source's obstacles in place of \e ctx's (the scene object stays: the checkers hold it).
            Throws ProblemError naming source's file when it plans other joints than \e problem or holds the
            robot's other joints elsewhere than \e ctx. */
        void installScene(const Problem &problem, const PlanningContext &ctx, const Problem &source);

        /** \brief Install \e source's scene and query \e query in \e ctx, checking start and goal there first
            (ProblemError naming source's file and queries[i].start / goal). */
        void installDatasetQuery(const Problem &problem, const PlanningContext &ctx, const Problem &source,
                                 std::size_t query);

        /** \brief Train every experience planner of \e planners on \e training: for each entry, its scene is
            installed in \e ctx, RRT-Connect solves its query (\e time seconds, solveTrainingQuery) and every
            experience planner learns the path while that scene is installed (Thunder checks it in its roadmap).
            Returns the number of paths learned; leaves the last training scene installed. */
        std::size_t trainOnDataset(const Problem &problem, const PlanningContext &ctx, const Dataset &training,
                                   double time, const std::vector<ompl::base::PlannerPtr> &planners,
                                   std::ostream *progress);

        /** \brief What `michi bench` does before its runs, for one planner about to plan query \e query of \e
            problem (`michi plan`): when \e planner is an experience planner, it reads the problem's library and
            learns its training queries (trainExperiencePlanners) and, for an experience dataset, the training
            problems, each in its own scene (trainOnDataset), after which the problem's own scene and query are
            installed again. \e ctx must hold a scene of its own (ContextOptions::scene, copyScene) when the
            problem has a dataset. Returns the paths learned (0 for other planners). */
        std::size_t learnBeforePlanning(const Problem &problem, const PlanningContext &ctx,
                                        const ompl::base::PlannerPtr &planner, std::size_t query,
                                        std::ostream *progress);
    }  // namespace tools
}  // namespace michi

#endif
