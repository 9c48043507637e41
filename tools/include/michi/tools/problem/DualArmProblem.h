#ifndef MICHI_TOOLS_DUAL_ARM_PROBLEM_
#define MICHI_TOOLS_DUAL_ARM_PROBLEM_

#include <michi/planners/dual_arm/DualArmWorkspace.h>
#include <michi/tools/problem/Problem.h>

#include <string>

namespace michi
{
    namespace tools
    {
        /** \brief One arm in a problem's dual_arm section. */
        struct DualArmArmSpec
        {
            std::string tip;                                     ///< tip link
            Eigen::Vector3d toolPoint{Eigen::Vector3d::Zero()};  ///< in the tip link
            planners::HandTarget hand;                           ///< orientation (position unused)
        };

        /** \brief The dual_arm section of a problem file (paper 004, docs/dual-arm.md). */
        struct DualArmSpec
        {
            DualArmArmSpec large, small;
            planners::DualArmSettings settings;
            std::string planner{"geometric::RRTstar"};  ///< plans the approach motions
            double planningTime{2.};                    ///< seconds per approach plan
            double weight{1.};                          ///< ManipulabilityObjective::setWeight for the approach plans
            std::array<double, 3> paperHandover{{-0.168, 0.365, 0.720}};  ///< reported for comparison
        };

        /** \brief Read the dual_arm section of \e problem's file (strict keys). Throws ProblemError naming the
            file and key; checks the links exist in the problem's robot, that the planned group is the small
            arm's joints and that the small arm has enough joints for manipulability_rows. */
        DualArmSpec loadDualArmSpec(const Problem &problem);

        /** \brief The two ArmTasks of a spec on the problem's robot model. */
        planners::ArmTask makeArmTask(const Problem &problem, const DualArmArmSpec &arm, const std::string &name);
    }  // namespace tools
}  // namespace michi

#endif
