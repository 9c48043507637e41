// The problem the conformance suite plans on, and the independent checker that re-validates solutions.
#ifndef MICHI_TESTS_SUPPORT_CONFORMANCE_PROBLEM_
#define MICHI_TESTS_SUPPORT_CONFORMANCE_PROBLEM_

#include <michi/validity/fcl/FclValidityChecker.h>

#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>

#include <map>
#include <ostream>
#include <string>

namespace michi
{
    namespace test
    {
        struct ConformanceCase
        {
            std::string planner;                        ///< registry name
            std::map<std::string, std::string> params;  ///< set by name before solving
            double timeLimit{10.};                      ///< generous cap; the problem is easy
            std::string checker{"fcl"};                 ///< "fcl" or "jmap": the state validity checker used
            /** \brief "arm": the planar 2-link arm; "se2": a rectangle in TurnMoveTurnStateSpace
                (makeSe2ConformanceProblem). */
            std::string problem{"arm"};
        };

        inline std::ostream &operator<<(std::ostream &out, const ConformanceCase &c)
        {
            return out << c.planner << (c.checker == "fcl" ? "" : " with " + c.checker)
                       << (c.problem == "arm" ? "" : " on " + c.problem);
        }

        /** \brief The conformance problem: a planar 2-link arm (thin capsule links of 0.5 m and 0.4 m) among
            polygon obstacles, start and goal on both sides of an obstacle so the straight joint motion collides. */
        struct ConformanceProblem
        {
            ompl::geometric::SimpleSetupPtr setup;
            std::shared_ptr<validity::FclValidityChecker> checker;   ///< FCL (inside the J-map checker too)
            std::shared_ptr<ompl::base::StateValidityChecker> used;  ///< the space's checker
        };
        /** \e enclosedGoal: obstacles are added that wall the goal in (a free pocket it cannot leave), so the
            problem has no solution and a planner runs until its termination condition stops it. */
        ConformanceProblem makeConformanceProblem(const std::string &checker = "fcl", const std::string &kind = "arm",
                                                  bool enclosedGoal = false);

        /** \brief The SE(2) conformance problem: a 0.6 m x 0.2 m rectangle in state_spaces::TurnMoveTurnStateSpace
            on [0, 4] x [0, 4], a wall across the middle with a 0.8 m gap, start and goal on both sides (FCL checker,
            conservative motion validator with turn-move-turn displacement bounds). Checker "fcl" only. */
        ConformanceProblem makeSe2ConformanceProblem(bool enclosedGoal = false);
        /** \brief independentPathCheck() for the SE(2) problem: footprints along the path (Boost.Geometry). */
        std::string independentSe2PathCheck(const ompl::geometric::PathGeometric &path);

        /** \brief Independent re-check of a path: interpolated at 1/10 of the space's resolution, each state's
            link rectangles (Boost.Geometry: the links are cylinders lying in the plane) must keep off every obstacle
           polygon. Returns an empty string when valid, else what failed. */
        std::string independentPathCheck(const ompl::geometric::PathGeometric &path);
    }  // namespace test
}  // namespace michi

#endif
