#include <michi/tools/JMapSetup.h>

#include <michi/validity/PlanarArm.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <algorithm>

namespace michi
{
    namespace tools
    {
        JMapProblem makeJMapProblem(const Problem &problem, const PlanningContext &ctx)
        {
            if (problem.kind != Problem::Kind::ARM || problem.groupVariables.size() < 2)
                throw ProblemError(problem.file, "robot", "a J-map needs an arm with at least two planned joints");
            JMapProblem jp;
            const auto &model = *problem.model;
            const int axis1 = problem.groupVariables[0], axis2 = problem.groupVariables[1];
            std::vector<double> configuration = problem.fixedValues;
            configuration[axis1] = 0.;
            configuration[axis2] = 0.;
            jp.coversRobot = problem.groupVariables.size() == 2;
            try
            {
                jp.arm = validity::PlanarArm::fromModel(model);
                jp.planar = true;
            }
            catch (const std::invalid_argument &)
            {
                jp.planar = false;  // not every joint about z: the FCL sweep works for any arm
            }
            if (jp.planar)
            {
                jp.axes = validity::planarAxes(*jp.arm, axis1, axis2, configuration);
                // the arm map leaves out the links that other planned joints move (the hand)
                for (std::size_t l = 0; l < jp.arm->links().size(); ++l)
                {
                    bool hand = false;
                    for (std::size_t g = 2; g < problem.groupVariables.size(); ++g)
                        hand = hand || jp.arm->moves(problem.groupVariables[g], static_cast<int>(l));
                    if (!hand)
                        jp.armLinks.push_back(static_cast<int>(l));
                    else
                        jp.handLength =
                            std::max(jp.handLength, jp.arm->reachFrom(problem.groupVariables[2], static_cast<int>(l)));
                }
                const auto arm = jp.arm;
                const auto links = jp.armLinks;
                const auto scene = problem.scene;
                jp.makeSource = [arm, links, scene](const validity::JMapAxes &axes)
                {
                    return std::make_shared<validity::PlanarIntervalSource>(arm, scene->polygons2d(), axes, links);
                };
            }
            else
            {
                jp.axes.axis1 = axis1;
                jp.axes.axis2 = axis2;
                jp.axes.configuration = configuration;
                jp.axes.lo1 = model.variableJoint(axis1).lower;
                jp.axes.hi1 = model.variableJoint(axis1).upper;
                jp.axes.lo2 = model.variableJoint(axis2).lower;
                jp.axes.hi2 = model.variableJoint(axis2).upper;
                // the sweep needs the other planned joints fixed: a checker over exactly the two axes
                auto bodies = std::make_shared<validity::RobotGroupBodies>(
                    problem.model, std::vector<int>{axis1, axis2}, configuration);
                auto checker = ctx.checker;
                auto si = ctx.setup->getSpaceInformation();
                jp.makeSource = [bodies, checker](const validity::JMapAxes &axes)
                {
                    auto space = std::make_shared<ompl::base::RealVectorStateSpace>(2);
                    ompl::base::RealVectorBounds b(2);
                    b.setLow(0, axes.lo1 - 1.);
                    b.setHigh(0, axes.hi1 + 1.);
                    b.setLow(1, axes.lo2 - 1.);
                    b.setHigh(1, axes.hi2 + 1.);
                    space->setBounds(b);
                    auto two = std::make_shared<ompl::base::SpaceInformation>(space);
                    auto fcl = std::make_shared<validity::FclValidityChecker>(two, bodies, checker->scene());
                    return std::make_shared<validity::FclIntervalSource>(fcl, axes);
                };
            }
            return jp;
        }

        validity::JMapValidityCheckerPtr makeJMapChecker(const Problem &problem, const PlanningContext &ctx,
                                                         const validity::JMapCheckerSettings &settings)
        {
            const JMapProblem jp = makeJMapProblem(problem, ctx);
            return std::make_shared<validity::JMapValidityChecker>(ctx.setup->getSpaceInformation(), ctx.checker,
                                                                   jp.makeSource, jp.axes, jp.coversRobot, settings);
        }
    }  // namespace tools
}  // namespace michi
