#include "support/ConformanceProblem.h"

#include <michi/state_spaces/JointStateSpace.h>
#include <michi/validity/fcl/ConservativeMotionValidator.h>
#include <michi/validity/jmap/JMapMotionValidator.h>
#include <michi/validity/jmap/JMapValidityChecker.h>
#include <michi/validity/jmap/PlanarArm.h>
#include <michi/validity/scene/Polygon2.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE2StateSpace.h>

#include <cmath>
#include <sstream>

namespace bg = boost::geometry;

namespace michi
{
    namespace test
    {
        namespace
        {
            const double L1 = 0.5, L2 = 0.4, RADIUS = 0.01;

            const char *ARM_URDF = R"(<robot name="conformance_arm">
  <link name="base"/>
  <link name="link1"><collision><origin xyz="0.25 0 0" rpy="0 1.5707963267948966 0"/>
    <geometry><cylinder radius="0.01" length="0.5"/></geometry></collision></link>
  <link name="link2"><collision><origin xyz="0.2 0 0" rpy="0 1.5707963267948966 0"/>
    <geometry><cylinder radius="0.01" length="0.4"/></geometry></collision></link>
  <joint name="joint1" type="revolute"><parent link="base"/><child link="link1"/>
    <axis xyz="0 0 1"/><limit lower="-3.14159" upper="3.14159" effort="1" velocity="1"/></joint>
  <joint name="joint2" type="revolute"><parent link="link1"/><child link="link2"/>
    <origin xyz="0.5 0 0"/><axis xyz="0 0 1"/><limit lower="-3.14159" upper="3.14159" effort="1" velocity="1"/>
  </joint>
</robot>)";

            /** Obstacles of the conformance scene, in the arm's plane. */
            std::vector<std::vector<Eigen::Vector2d>> obstacleOutlines()
            {
                return {
                    {{0.55, 0.35},
                     {0.7, 0.35},
                     {0.7, 0.5},
                     {0.55, 0.5}},  // upper right: beyond link 1, in link 2's way
                    {{-0.6, -0.3}, {-0.3, -0.3}, {-0.3, -0.1}, {-0.45, -0.1}, {-0.45, 0.1}, {-0.6, 0.1}},  // L
                    {{0.2, -0.75}, {0.5, -0.75}, {0.35, -0.55}},                                           // triangle
                };
            }
        }  // namespace

        ConformanceProblem makeConformanceProblem(const std::string &checker, const std::string &kind,
                                                  bool enclosedGoal)
        {
            if (kind == "se2" && checker == "fcl")
                return makeSe2ConformanceProblem(enclosedGoal);
            if (kind != "arm")
                throw std::invalid_argument("conformance problem must be arm, or se2 with the fcl checker");
            auto model = validity::RobotModel::fromUrdfString(ARM_URDF, "conformance_arm.urdf", ".");
            auto bodies = std::make_shared<validity::RobotGroupBodies>(model, std::vector<int>{0, 1},
                                                                       std::vector<double>{0., 0.});
            auto scene = std::make_shared<validity::Scene>();
            int i = 0;
            auto outlines = obstacleOutlines();
            if (enclosedGoal)
            {
                // two posts at 0.25 m from the base on both sides of the goal's link 1 (1.2 rad +- 0.15 rad): link 1
                // passes through that radius at every angle, so the goal's pocket of about +-0.05 rad is closed
                for (double angle : {1.05, 1.35})
                {
                    const Eigen::Vector2d c(0.25 * std::cos(angle), 0.25 * std::sin(angle));
                    const double h = 0.015;
                    outlines.push_back({c + Eigen::Vector2d(-h, -h), c + Eigen::Vector2d(h, -h),
                                        c + Eigen::Vector2d(h, h), c + Eigen::Vector2d(-h, h)});
                }
            }
            for (const auto &outline : outlines)
                scene->add(validity::Obstacle{"obstacle" + std::to_string(i++),
                                              validity::Shape::prism(outline, -0.5, 0.5),
                                              Eigen::Isometry3d::Identity(),
                                              {}});
            auto space = state_spaces::makeJointStateSpace(
                {{"joint1", -3.14159, 3.14159, false}, {"joint2", -3.14159, 3.14159, false}});
            ConformanceProblem problem;
            problem.setup = std::make_shared<ompl::geometric::SimpleSetup>(space);
            auto si = problem.setup->getSpaceInformation();
            problem.checker = std::make_shared<validity::FclValidityChecker>(si, bodies, scene);
            problem.used = problem.checker;
            if (checker == "jmap")
            {
                // the J-map of the arm's two joints (exact planar intervals), answering alone
                auto arm = validity::PlanarArm::fromModel(*model);
                auto polygons = scene->polygons2d();
                problem.used = std::make_shared<validity::JMapValidityChecker>(
                    problem.setup->getSpaceInformation(), problem.checker,
                    [arm, polygons](const validity::JMapAxes &axes)
                    {
                        return std::make_shared<validity::PlanarIntervalSource>(arm, polygons, axes);
                    },
                    validity::planarAxes(*arm, 0, 1), true);
            }
            else if (checker != "fcl")
                throw std::invalid_argument("conformance checker must be fcl or jmap");
            problem.setup->setStateValidityChecker(problem.used);
            auto motions = std::make_shared<validity::ConservativeMotionValidator>(si, problem.checker);
            if (auto jmap = std::dynamic_pointer_cast<validity::JMapValidityChecker>(problem.used))
                si->setMotionValidator(std::make_shared<validity::JMapMotionValidator>(si, jmap, motions));
            else
                si->setMotionValidator(motions);
            ompl::base::ScopedState<> start(space), goal(space);
            start = std::vector<double>{0.2, 0.3};  // arm pointing right, below the upper-right box
            goal = std::vector<double>{1.2, -0.4};  // arm pointing up-left, past the box
            problem.setup->setStartAndGoalStates(start, goal);
            return problem;
        }

        std::string independentPathCheck(const ompl::geometric::PathGeometric &path)
        {
            const auto si = path.getSpaceInformation();
            if (dynamic_cast<const ompl::base::SE2StateSpace *>(si->getStateSpace().get()) != nullptr)
                return independentSe2PathCheck(path);
            validity::MultiPolygon2 obstacles;
            for (const auto &outline : obstacleOutlines())
            {
                std::vector<validity::Point2> pts;
                for (const auto &p : outline)
                    pts.emplace_back(p.x(), p.y());
                obstacles.push_back(validity::makePolygon2(pts));
            }
            const double step = si->getStateValidityCheckingResolution() * si->getMaximumExtent() / 10.;
            ompl::geometric::PathGeometric fine(path);
            fine.interpolate();  // at the space's resolution
            std::vector<double> q;
            ompl::base::State *state = si->allocState();
            std::string failure;
            for (std::size_t k = 0; k + 1 < fine.getStateCount() && failure.empty(); ++k)
            {
                const double d = si->distance(fine.getState(k), fine.getState(k + 1));
                const int n = std::max(1, static_cast<int>(std::ceil(d / step)));
                for (int s = 0; s <= n && failure.empty(); ++s)
                {
                    si->getStateSpace()->interpolate(fine.getState(k), fine.getState(k + 1), static_cast<double>(s) / n,
                                                     state);
                    si->getStateSpace()->copyToReals(q, state);
                    const validity::Point2 base(0., 0.);
                    const validity::Point2 elbow(L1 * std::cos(q[0]), L1 * std::sin(q[0]));
                    const validity::Point2 tip(elbow.x() + L2 * std::cos(q[0] + q[1]),
                                               elbow.y() + L2 * std::sin(q[0] + q[1]));
                    // each link is a cylinder of RADIUS lying in the plane: its shadow is a rectangle
                    for (const auto &ends : {std::make_pair(base, elbow), std::make_pair(elbow, tip)})
                    {
                        const double dx = ends.second.x() - ends.first.x(), dy = ends.second.y() - ends.first.y();
                        const double len = std::hypot(dx, dy);
                        const double nx = -dy / len * RADIUS, ny = dx / len * RADIUS;
                        const auto rect = validity::makePolygon2({{ends.first.x() + nx, ends.first.y() + ny},
                                                                  {ends.second.x() + nx, ends.second.y() + ny},
                                                                  {ends.second.x() - nx, ends.second.y() - ny},
                                                                  {ends.first.x() - nx, ends.first.y() - ny}});
                        if (bg::intersects(rect, obstacles))
                        {
                            std::ostringstream out;
                            out << "state (" << q[0] << ", " << q[1] << ") between path states " << k << " and "
                                << k + 1 << " touches an obstacle";
                            failure = out.str();
                        }
                    }
                }
            }
            si->freeState(state);
            return failure;
        }
    }  // namespace test
}  // namespace michi
