// The SE(2) conformance problem (a rectangle driving through a gap in a wall, turn-move-turn motions) and its
// independent path check.
#include "support/ConformanceProblem.h"

#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/tools/problem/TurnMoveTurnBodies.h>
#include <michi/validity/fcl/ConservativeMotionValidator.h>
#include <michi/validity/scene/Polygon2.h>

#include <ompl/base/ScopedState.h>

#include <cmath>
#include <sstream>

namespace bg = boost::geometry;

namespace michi
{
    namespace test
    {
        namespace
        {
            const double HALF_LENGTH = 0.3, HALF_WIDTH = 0.1;

            std::vector<std::vector<Eigen::Vector2d>> se2Walls()
            {
                return {
                    {{1.9, 0.}, {2.1, 0.}, {2.1, 1.6}, {1.9, 1.6}},  // the wall below the gap
                    {{1.9, 2.4}, {2.1, 2.4}, {2.1, 4.}, {1.9, 4.}},  // and above it
                };
            }
        }  // namespace

        ConformanceProblem makeSe2ConformanceProblem(bool enclosedGoal)
        {
            auto body =
                std::make_shared<validity::PlanarRigidBody>(std::vector<Eigen::Vector2d>{{-HALF_LENGTH, -HALF_WIDTH},
                                                                                         {HALF_LENGTH, -HALF_WIDTH},
                                                                                         {HALF_LENGTH, HALF_WIDTH},
                                                                                         {-HALF_LENGTH, HALF_WIDTH}},
                                                            -0.5, 0.5);
            auto space = state_spaces::makeTurnMoveTurnStateSpace(0., 4., 0., 4., body->circumradius());
            auto bodies = std::make_shared<tools::TurnMoveTurnBodies>(body, space);
            auto scene = std::make_shared<validity::Scene>();
            int i = 0;
            auto walls = se2Walls();
            if (enclosedGoal)
            {
                // a closed square of walls 0.45 m around the goal (3, 3): the body turns inside but cannot leave
                const double in = 0.45, out = 0.5;
                walls.push_back({{3. - out, 3. - out}, {3. + out, 3. - out}, {3. + out, 3. - in}, {3. - out, 3. - in}});
                walls.push_back({{3. - out, 3. + in}, {3. + out, 3. + in}, {3. + out, 3. + out}, {3. - out, 3. + out}});
                walls.push_back({{3. - out, 3. - in}, {3. - in, 3. - in}, {3. - in, 3. + in}, {3. - out, 3. + in}});
                walls.push_back({{3. + in, 3. - in}, {3. + out, 3. - in}, {3. + out, 3. + in}, {3. + in, 3. + in}});
            }
            for (const auto &outline : walls)
                scene->add(validity::Obstacle{"wall" + std::to_string(i++),
                                              validity::Shape::prism(outline, -0.5, 0.5),
                                              Eigen::Isometry3d::Identity(),
                                              {}});
            ConformanceProblem problem;
            problem.setup = std::make_shared<ompl::geometric::SimpleSetup>(space);
            auto si = problem.setup->getSpaceInformation();
            problem.checker = std::make_shared<validity::FclValidityChecker>(si, bodies, scene);
            problem.used = problem.checker;
            problem.setup->setStateValidityChecker(problem.used);
            si->setMotionValidator(std::make_shared<validity::ConservativeMotionValidator>(si, problem.checker));
            ompl::base::ScopedState<ompl::base::SE2StateSpace> start(space), goal(space);
            start->setXY(1., 1.);
            start->setYaw(0.);
            goal->setXY(3., 3.);
            goal->setYaw(M_PI / 2.);
            problem.setup->setStartAndGoalStates(start, goal);
            return problem;
        }

        std::string independentSe2PathCheck(const ompl::geometric::PathGeometric &path)
        {
            const auto si = path.getSpaceInformation();
            validity::MultiPolygon2 walls;
            for (const auto &outline : se2Walls())
            {
                std::vector<validity::Point2> pts;
                for (const auto &p : outline)
                    pts.emplace_back(p.x(), p.y());
                walls.push_back(validity::makePolygon2(pts));
            }
            const double step = si->getStateValidityCheckingResolution() * si->getMaximumExtent() / 10.;
            ompl::base::State *state = si->allocState();
            std::string failure;
            for (std::size_t k = 0; k + 1 < path.getStateCount() && failure.empty(); ++k)
            {
                const double d = si->distance(path.getState(k), path.getState(k + 1));
                const int n = std::max(1, static_cast<int>(std::ceil(d / step)));
                for (int s = 0; s <= n && failure.empty(); ++s)
                {
                    si->getStateSpace()->interpolate(path.getState(k), path.getState(k + 1), static_cast<double>(s) / n,
                                                     state);
                    const auto *p = state->as<ompl::base::SE2StateSpace::StateType>();
                    const double c = std::cos(p->getYaw()), sn = std::sin(p->getYaw());
                    std::vector<validity::Point2> corners;
                    for (const auto &q :
                         {std::make_pair(-HALF_LENGTH, -HALF_WIDTH), std::make_pair(HALF_LENGTH, -HALF_WIDTH),
                          std::make_pair(HALF_LENGTH, HALF_WIDTH), std::make_pair(-HALF_LENGTH, HALF_WIDTH)})
                        corners.emplace_back(p->getX() + c * q.first - sn * q.second,
                                             p->getY() + sn * q.first + c * q.second);
                    const bool outside = p->getX() < 0. || p->getX() > 4. || p->getY() < 0. || p->getY() > 4.;
                    if (outside || bg::intersects(validity::makePolygon2(corners), walls))
                    {
                        std::ostringstream out;
                        out << "pose (" << p->getX() << ", " << p->getY() << ", " << p->getYaw()
                            << ") between path states " << k << " and " << k + 1
                            << (outside ? " is out of bounds" : " touches a wall");
                        failure = out.str();
                    }
                }
            }
            si->freeState(state);
            return failure;
        }
    }  // namespace test
}  // namespace michi
