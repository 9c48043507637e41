#include "bench/TestPlanners.h"

#include <chrono>
#include <csignal>
#include <stdexcept>
#include <thread>

namespace ob = ompl::base;

namespace michi
{
    namespace tools
    {
        namespace
        {
            /** Dies of SIGSEGV when asked to solve: a planner crash as the process sees it. */
            class SegfaultPlanner : public ob::Planner
            {
            public:
                explicit SegfaultPlanner(const ob::SpaceInformationPtr &si) : ob::Planner(si, "test::Segfault")
                {
                }

                ob::PlannerStatus solve(const ob::PlannerTerminationCondition &) override
                {
                    // raise(), not a bad pointer: the crash is certain and the same under every compiler and sanitizer.
                    std::raise(SIGSEGV);
                    return ob::PlannerStatus::CRASH;  // not reached: the default action ends the process
                }
            };

            /** Never returns from solve(), whatever its termination condition says: a hung planner. */
            class HangPlanner : public ob::Planner
            {
            public:
                explicit HangPlanner(const ob::SpaceInformationPtr &si) : ob::Planner(si, "test::Hang")
                {
                }

                ob::PlannerStatus solve(const ob::PlannerTerminationCondition &) override
                {
                    for (;;)
                        // Sleeping, not spinning: a test that waits for the hang margin does not burn a core of the
                        // shared machine.
                        std::this_thread::sleep_for(std::chrono::seconds(1));
                }
            };
        }  // namespace

        ob::PlannerPtr allocateTestPlanner(const std::string &name, const ob::SpaceInformationPtr &si)
        {
            if (name == "test::Segfault")
                return std::make_shared<SegfaultPlanner>(si);
            if (name == "test::Hang")
                return std::make_shared<HangPlanner>(si);
            throw std::invalid_argument("unknown test planner '" + name + "'");
        }
    }  // namespace tools
}  // namespace michi
