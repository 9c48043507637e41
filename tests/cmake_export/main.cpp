// Uses every michi component through the installed package: a planar arm from a URDF (validity), its joint
// space (state_spaces), a stock planner from the registry (tools), solved with OMPL's SimpleSetup.
#include <michi/state_spaces/JointStateSpace.h>
#include <michi/tools/PlannerRegistry.h>
#include <michi/validity/ConservativeMotionValidator.h>
#include <michi/validity/FclValidityChecker.h>

#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>

#include <iostream>

int main()
{
    ompl::RNG::setSeed(1);
    const char *urdf = R"(<robot name="arm"><link name="base"/>
      <link name="l1"><collision><origin xyz="0.25 0 0" rpy="0 1.5708 0"/>
        <geometry><cylinder radius="0.02" length="0.5"/></geometry></collision></link>
      <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
        <limit lower="-3.1" upper="3.1" effort="1" velocity="1"/></joint></robot>)";
    auto model = michi::validity::RobotModel::fromUrdfString(urdf, "consumer.urdf", ".");
    auto bodies =
        std::make_shared<michi::validity::RobotGroupBodies>(model, std::vector<int>{0}, std::vector<double>{0.});
    auto scene = std::make_shared<michi::validity::Scene>();
    scene->add({"post",
                michi::validity::Shape::box(Eigen::Vector3d(0.1, 0.1, 1.)),
                Eigen::Isometry3d(Eigen::Translation3d(0., -0.4, 0.)),
                {}});
    auto space = michi::state_spaces::makeJointStateSpace({{"j1", -3.1, 3.1, false}});
    ompl::geometric::SimpleSetup ss(space);
    auto si = ss.getSpaceInformation();
    auto checker = std::make_shared<michi::validity::FclValidityChecker>(si, bodies, scene);
    ss.setStateValidityChecker(checker);
    si->setMotionValidator(std::make_shared<michi::validity::ConservativeMotionValidator>(si, checker));
    ompl::base::ScopedState<> start(space), goal(space);
    start = std::vector<double>{0.};
    goal = std::vector<double>{3.};  // the post stands at -pi/2, away from the way from 0 to 3
    ss.setStartAndGoalStates(start, goal);
    ss.setPlanner(michi::tools::allocatePlanner("geometric::RRTConnect", si));
    if (!ss.solve(5.0) || !ss.haveExactSolutionPath())
    {
        std::cerr << "consumer: no solution" << std::endl;
        return 1;
    }
    ss.getSolutionPath().interpolate(200);
    for (const auto *s : ss.getSolutionPath().getStates())
        if (!checker->isValid(s))
        {
            std::cerr << "consumer: path passes through the post" << std::endl;
            return 1;
        }
    std::cout << "consumer: solved, " << ss.getSolutionPath().getStateCount() << " states" << std::endl;
    return 0;
}
