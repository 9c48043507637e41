#ifndef MICHI_TESTS_SUPPORT_COUNTED_SOLVE_
#define MICHI_TESTS_SUPPORT_COUNTED_SOLVE_

#include <ompl/base/Planner.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathGeometric.h>

namespace michi
{
    namespace test
    {
        /** \brief What solveCounted() found. */
        struct CountedSolve
        {
            ompl::base::PlannerStatus status;
            /** the solution path (exact solutions only; otherwise empty) */
            ompl::geometric::PathGeometric path;
            /** the path passes PathGeometric::check() */
            bool valid{false};
        };

        /** \brief \e planner (set up if it is not) solves \e start to \e goal, stopped after \e evaluations of the
            termination condition: a budget of work, not of time, so that a test counts and never times. */
        CountedSolve solveCounted(ompl::base::Planner &planner, const ompl::base::ScopedState<> &start,
                                  const ompl::base::ScopedState<> &goal, unsigned long evaluations);
    }  // namespace test
}  // namespace michi

#endif
