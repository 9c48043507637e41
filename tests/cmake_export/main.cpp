// Uses every michi component through the installed package, as a user's own OMPL code would: planar arms from a
// URDF (validity), their joint space (state_spaces), a stock planner from the registry (tools), and a michi
// planner, michi::planners::ConcentricCircle, built from `si` alone and set on OMPL's SimpleSetup (planners).
#include <michi/planners/concentric_circle/ConcentricCircle.h>
#include <michi/state_spaces/JointStateSpace.h>
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/validity/fcl/ConservativeMotionValidator.h>
#include <michi/validity/fcl/FclValidityChecker.h>

#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace
{
    // A link of length `length` along x, as a thin cylinder, hanging from `parent` on a z revolute joint placed
    // `offset` metres along the parent's x axis.
    std::string link(const std::string &name, const std::string &parent, double offset, double length, double limit)
    {
        const auto half = std::to_string(length / 2.), len = std::to_string(length), lim = std::to_string(limit);
        return "<link name=\"" + name + "\"><collision><origin xyz=\"" + half +
               " 0 0\" rpy=\"0 1.5708 0\"/><geometry><cylinder radius=\"0.02\" length=\"" + len +
               "\"/></geometry></collision></link><joint name=\"j_" + name + "\" type=\"revolute\"><parent link=\"" +
               parent + "\"/><child link=\"" + name + "\"/><origin xyz=\"" + std::to_string(offset) +
               " 0 0\"/><axis xyz=\"0 0 1\"/><limit lower=\"-" + lim + "\" upper=\"" + lim +
               "\" effort=\"1\" velocity=\"1\"/></joint>";
    }

    // A planar arm of the given link lengths among box posts, with FCL checking and a conservative motion
    // validator on its joint space.
    struct ArmSetup
    {
        std::shared_ptr<ompl::geometric::SimpleSetup> ss;
        std::shared_ptr<michi::validity::FclValidityChecker> checker;
    };

    ArmSetup armSetup(const std::vector<double> &lengths, const std::vector<Eigen::Vector3d> &posts, double limit)
    {
        std::string urdf = "<robot name=\"arm\"><link name=\"base\"/>";
        std::string parent = "base";
        double offset = 0.;
        std::vector<michi::state_spaces::JointSpec> joints;
        std::vector<int> variables;
        for (std::size_t i = 0; i < lengths.size(); ++i)
        {
            const std::string name = "l" + std::to_string(i + 1);
            urdf += link(name, parent, offset, lengths[i], limit);
            joints.push_back({"j_" + name, -limit, limit, false});
            variables.push_back(static_cast<int>(i));
            parent = name;
            offset = lengths[i];
        }
        urdf += "</robot>";
        auto model = michi::validity::RobotModel::fromUrdfString(urdf, "consumer.urdf", ".");
        auto bodies = std::make_shared<michi::validity::RobotGroupBodies>(model, variables,
                                                                          std::vector<double>(lengths.size(), 0.));
        auto scene = std::make_shared<michi::validity::Scene>();
        for (std::size_t i = 0; i < posts.size(); ++i)
            scene->add({"post" + std::to_string(i),
                        michi::validity::Shape::box(Eigen::Vector3d(0.1, 0.1, 1.)),
                        Eigen::Isometry3d(Eigen::Translation3d(posts[i])),
                        {}});
        ArmSetup setup;
        setup.ss = std::make_shared<ompl::geometric::SimpleSetup>(michi::state_spaces::makeJointStateSpace(joints));
        auto si = setup.ss->getSpaceInformation();
        setup.checker = std::make_shared<michi::validity::FclValidityChecker>(si, bodies, scene);
        setup.ss->setStateValidityChecker(setup.checker);
        si->setMotionValidator(std::make_shared<michi::validity::ConservativeMotionValidator>(si, setup.checker));
        return setup;
    }

    // Solves from `start` to `goal`, then re-checks the path at 200 states; true if it is exact and valid.
    bool solveAndCheck(const std::string &what, ArmSetup &setup, const std::vector<double> &start,
                       const std::vector<double> &goal)
    {
        auto &ss = *setup.ss;
        ompl::base::ScopedState<> s(ss.getStateSpace()), g(ss.getStateSpace());
        s = start;
        g = goal;
        ss.setStartAndGoalStates(s, g);
        if (!ss.solve(10.0) || !ss.haveExactSolutionPath())
        {
            std::cerr << "consumer: " << what << ": no solution" << std::endl;
            return false;
        }
        auto path = ss.getSolutionPath();
        const auto states = path.getStateCount();
        path.interpolate(200);
        for (const auto *state : path.getStates())
            if (!setup.checker->isValid(state))
            {
                std::cerr << "consumer: " << what << ": the path passes through a post" << std::endl;
                return false;
            }
        std::cout << "consumer: " << what << " solved, " << states << " states" << std::endl;
        return true;
    }
}  // namespace

int main()
{
    ompl::RNG::setSeed(1);

    // One link, a post at -pi/2, away from the way from 0 to 3: OMPL's RRTConnect from michi's registry.
    auto one = armSetup({0.5}, {Eigen::Vector3d(0., -0.4, 0.)}, 3.1);
    one.ss->setPlanner(michi::tools::allocatePlanner("geometric::RRTConnect", one.ss->getSpaceInformation()));
    if (!solveAndCheck("geometric::RRTConnect", one, {0.}, {3.}))
        return 1;

    // Two links, a post that only the outstretched second link reaches at -pi/2: the arm must fold its second
    // joint to pass it. michi's concentric-circle planner, constructed from si as any OMPL planner.
    auto two = armSetup({0.5, 0.5}, {Eigen::Vector3d(0., -0.85, 0.)}, 2.8);
    auto planner = std::make_shared<michi::planners::ConcentricCircle>(two.ss->getSpaceInformation());
    planner->params().setParam("mode", "projection");  // set by name, as MoveIt and OMPL's Benchmark do
    two.ss->setPlanner(planner);
    if (!solveAndCheck("michi::planners::ConcentricCircle", two, {-2.5, 0.}, {0.5, 0.}))
        return 1;
    return 0;
}
