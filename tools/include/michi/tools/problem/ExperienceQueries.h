#ifndef MICHI_TOOLS_EXPERIENCE_QUERIES_
#define MICHI_TOOLS_EXPERIENCE_QUERIES_

#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <ompl/base/Planner.h>
#include <ompl/geometric/PathGeometric.h>

#include <ostream>
#include <optional>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief The problem's `experience` key (docs/path-seed.md):
            \code
            experience:
              queries: ring_task_queries.yaml   # {training: [{start, goal}, ...], held_out: [...]}
              training_time: 5                    # seconds of RRT-Connect per training query
              library: xarm6_ring.seeds           # optional: experience file loaded before training
            \endcode
            Returns empty sets when the key is absent. Throws ProblemError naming the file and key for anything
            malformed: a missing file, a state of the wrong size, a value out of the joint bounds. Called by
            loadProblem() once the robot is known. */
        ExperienceQueries readExperienceQueries(const std::string &problemFile, const Problem &problem);

        /** \brief Generate \e count start/goal pairs around the problem's queries: pair i perturbs query
            i mod Q uniformly (start by +-startSpread, goal by +-goalSpread per joint, in joint units) until both
            are within bounds and collision-free (FCL). The first \e training pairs are the training set, the rest
            held out. Deterministic for a seed (its own ompl::RNG). Throws std::runtime_error when a pair cannot be
            found in 10000 attempts. */
        ExperienceQueries generateExperienceQueries(const Problem &problem, std::size_t count, std::size_t training,
                                                    double startSpread, double goalSpread, unsigned int seed);

        /** \brief Settings of `michi experience-queries`. */
        struct ExperienceQueriesOptions
        {
            std::size_t count{160};    ///< pairs in all
            std::size_t training{60};  ///< the first ones: training set; the rest: held out
            double startSpread{0.3};   ///< uniform perturbation of the starts per joint (rad)
            double goalSpread{0.05};   ///< of the goals (rad; they sit in the ring)
            unsigned int seed{1};
            std::string out;  ///< file to write
            /** \brief A task regions file (TaskRegionQueries.h): starts and goals drawn independently from hand
                poses in the regions, solved by IK, instead of perturbing the problem's queries (the spreads are
                then unused). */
            std::string regions;
        };

        /** \brief `michi experience-queries`: generate the queries and write them to options.out (atomically,
            with a header saying how they were made). Returns a one-line report. */
        std::string writeExperienceQueriesFile(const Problem &problem, const ExperienceQueriesOptions &options);

        /** \brief `michi path-seed-library`: solve the problem's training queries (solveTrainingQueries, RNG seed
            \e seed), encode the paths as path seeds (\e variant) and save the library to \e file. */
        std::string writePathSeedLibrary(const Problem &problem, const std::string &variant, unsigned int seed,
                                         const std::string &file);

        /** \brief The queries as the YAML file readExperienceQueries() reads (\e header: comment lines). */
        std::string experienceQueriesYaml(const ExperienceQueries &queries, const std::string &header);

        /** \brief Solve one training query with RRT-Connect (\e time seconds) in \e ctx's scene, simplify the
            solution (OMPL's PathSimplifier, 1 s) and check it; false when RRT-Connect found none or the simplified
            path is invalid. */
        bool solveTrainingQuery(const PlanningContext &ctx, const Query &query, double time,
                                ompl::geometric::PathGeometric &path);

        /** \brief Solve every training query with RRT-Connect (problem.experience.trainingTime each), simplify
            the solutions (OMPL's PathSimplifier) and return them. Checks each start and goal first (ProblemError
            naming experience.training[i]). \e only: that training query alone. */
        std::vector<ompl::geometric::PathGeometric> solveTrainingQueries(const Problem &problem,
                                                                         const PlanningContext &ctx,
                                                                         std::ostream *progress,
                                                                         std::optional<std::size_t> only = {});

        /** \brief When some of \e planners are michi::planners::ExperiencePlanner and the problem has training
            queries: solve them (solveTrainingQueries) and give every such planner the paths. Returns the number
            of paths each learned. */
        std::size_t trainExperiencePlanners(const Problem &problem, const PlanningContext &ctx,
                                            const std::vector<ompl::base::PlannerPtr> &planners,
                                            std::ostream *progress);

        /** \brief Check the held-out queries (bounds, collisions) before a benchmark; throws ProblemError naming
            experience.held_out[i].start/goal. */
        void checkHeldOutQueries(const Problem &problem, const PlanningContext &ctx);

        /** \brief Why \e values cannot be a start or goal in \e ctx (outside the bounds, or what collides), or ""
            when it can. */
        std::string invalidStateReason(const PlanningContext &ctx, const std::vector<double> &values);

        /** \brief Set start and goal of \e ctx's problem definition to \e query (a held-out query's run). */
        void setQuery(const PlanningContext &ctx, const Query &query);
    }  // namespace tools
}  // namespace michi

#endif
