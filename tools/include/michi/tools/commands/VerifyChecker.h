#ifndef MICHI_TOOLS_COMMANDS_VERIFY_CHECKER_
#define MICHI_TOOLS_COMMANDS_VERIFY_CHECKER_

#include <michi/tools/problem/Problem.h>

#include <cstddef>
#include <ostream>
#include <string>

namespace michi
{
    namespace tools
    {
        struct VerifyCheckerOptions
        {
            std::string checker;         ///< a name of checkerNames() (the fast checker to verify)
            std::size_t states{100000};  ///< uniform states, and as many random short motions
            unsigned int seed{1};        ///< ompl::RNG::setSeed
            /** \brief A motion goes from a uniform state to a state sampled near it, within this fraction of the
                space's maximum extent. */
            double motionFraction{0.02};
            std::ostream *progress{nullptr};
        };

        /** \brief What `michi verify-checker` measures (docs/checking.md). */
        struct VerifyCheckerResult
        {
            std::string problem;
            std::string checker;
            std::size_t states{0};
            std::size_t motions{0};
            unsigned int seed{1};
            std::size_t unsafeStates{0};    ///< the checker says valid, FCL says invalid: must be 0
            std::size_t unsafeMotions{0};   ///< the checker's motion validator says valid, FCL's reference invalid
            std::size_t referenceValid{0};  ///< states FCL calls valid
            std::size_t falseInvalid{0};    ///< of those, the ones the checker calls invalid
            std::size_t motionsValid{0};    ///< motions the checker calls valid (each then checked by FCL)
            double queryNs{0.};             ///< the checker's time per state check
            double referenceQueryNs{0.};    ///< FCL's (FclValidityChecker::isValid) in the same run
            double motionNs{0.};            ///< the checker's motion validator's time per motion
            double buildSeconds{0.};        ///< making the context with the checker (its tables)
            double falseInvalidFraction() const
            {
                return referenceValid ? double(falseInvalid) / referenceValid : 0.;
            }
            /** \brief One line of JSON (the keys above in snake_case). */
            std::string json() const;
        };

        /** \brief Check \e options.states uniform states and as many random short motions with the checker
            (and its motion validator) that makePlanningContext() installs for \e options.checker, and with FCL on
            the same scene: FclValidityChecker for states, and for the motions the checker calls valid
            ConservativeMotionValidator (exact), or for the sphere checker (arm meshes, where exact distances are
            too slow for a million motions) certifyPath's FCL checks ten times finer than the planners' resolution.
           Generic over every checker the planning context can install. Times are measured in the same run, in batches
           of 1,000 states (in the cache, as the states a planner checks are) alternating between the two. */
        VerifyCheckerResult verifyChecker(const Problem &problem, const VerifyCheckerOptions &options);
    }  // namespace tools
}  // namespace michi

#endif
