#include "support/CountedSolve.h"

#include <ompl/base/ProblemDefinition.h>

#include <memory>

namespace michi
{
    namespace test
    {
        CountedSolve solveCounted(ompl::base::Planner &planner, const ompl::base::ScopedState<> &start,
                                  const ompl::base::ScopedState<> &goal, unsigned long evaluations)
        {
            const auto &si = planner.getSpaceInformation();
            auto pdef = std::make_shared<ompl::base::ProblemDefinition>(si);
            pdef->setStartAndGoalStates(start, goal);
            planner.setProblemDefinition(pdef);
            if (!planner.isSetup())
                planner.setup();
            unsigned long count = 0;
            CountedSolve result{planner.solve(ompl::base::PlannerTerminationCondition(
                                    [&]
                                    {
                                        return ++count > evaluations;
                                    })),
                                ompl::geometric::PathGeometric(si)};
            if (result.status == ompl::base::PlannerStatus::EXACT_SOLUTION)
            {
                result.path = *pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>();
                result.valid = result.path.check();
            }
            return result;
        }
    }  // namespace test
}  // namespace michi
