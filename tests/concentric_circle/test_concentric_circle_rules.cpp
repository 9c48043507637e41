// The rules of paper 000 inside michi::planners::ConcentricCircle, each on a case small enough to compute by hand:
// the potential of equations (1)-(3) (attraction, oval repulsion, the sum over edges whose both end points are
// visible), the paper's candidate rule (one minimum-potential point per free arc of a 72-point circle), and the
// several paths of different homotopy (left and right of one obstacle) that the planner hands out in its
// PlannerData. A constant potential, a rule that keeps the wrong point or a planner that keeps only its best path
// fails these.
#include <michi/planners/concentric_circle/CircleMap.h>
#include <michi/planners/concentric_circle/ConcentricCircle.h>
#include <michi/planners/concentric_circle/ConcentricCircleSearch.h>

#include <michi/state_spaces/JointStateSpace.h>

#include <ompl/base/PlannerData.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/Console.h>

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <functional>

using namespace michi;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace
{
    /** the square [x0, x1] x [y0, y1] as the only obstacle of a map over [-3, 3]^2 */
    std::shared_ptr<planners::PolygonCircleMap> squareMap(double x0, double y0, double x1, double y1)
    {
        validity::MultiPolygon2 obstacles{validity::makePolygon2({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}})};
        return std::make_shared<planners::PolygonCircleMap>(obstacles, Eigen::Vector2d(-3., -3.),
                                                            Eigen::Vector2d(3., 3.));
    }

    double oval(const Eigen::Vector2d &p, const Eigen::Vector2d &a, const Eigen::Vector2d &b)
    {
        return (p - a).norm() + (p - b).norm() - (a - b).norm();
    }
}  // namespace

TEST(ConcentricCircleRules, PotentialIsEquationsOneToThree)
{
    // The square [1, 2] x [-0.5, 0.5]; P at the origin sees both end points of the left edge only: the top and
    // bottom edges have their far end point behind the square (the sight line to (2, 0.5) crosses x = 1 at
    // y = 0.25), the right edge is hidden. So, equation (3): Phi = -Kg / |PG| + Kp / Dp(left)^2.
    auto map = squareMap(1., -0.5, 2., 0.5);
    planners::ConcentricCircleSettings settings;
    settings.kGoal = 2.;
    settings.kObstacle = 0.01;
    settings.potentialRange = 10.;  // every edge in range: only visibility leaves some out
    planners::ConcentricCircleSearch search(*map, settings);
    const Eigen::Vector2d p(0., 0.), goal(0., 3.);
    const double dp = 2. * std::sqrt(1.25) - 1.;  // |PA| + |PB| - |AB| for A = (1, -0.5), B = (1, 0.5)
    EXPECT_NEAR(search.potentialAt(p, goal), -2. / 3. + 0.01 / (dp * dp), 1e-12);
    EXPECT_NEAR(dp, oval(p, {1., -0.5}, {1., 0.5}), 1e-15);

    // Above the square P sees the top edge and both side edges' upper end points but not their lower ones: only
    // the top edge counts.
    const Eigen::Vector2d q(1.5, 1.5);
    const double dq = oval(q, {1., 0.5}, {2., 0.5});
    EXPECT_NEAR(search.potentialAt(q, goal), -2. / (goal - q).norm() + 0.01 / (dq * dq), 1e-12);

    // Equation (2) grows as P nears the edge (the oval distance shrinks), and equation (1) pulls towards the goal.
    EXPECT_GT(search.potentialAt({0.9, 0.}, goal), search.potentialAt({0.5, 0.}, goal));
    EXPECT_LT(search.potentialAt({-1., 2.}, goal), search.potentialAt({-1., -2.}, goal));

    // A range that leaves the edge out leaves the attraction alone.
    settings.potentialRange = 0.5;
    planners::ConcentricCircleSearch near(*map, settings);
    EXPECT_NEAR(near.potentialAt(p, goal), -2. / 3., 1e-12);
}

TEST(ConcentricCircleRules, PaperRuleKeepsTheMinimumOfEveryFreeArc)
{
    auto map = squareMap(-0.5, -0.6, 0.4, 0.6);
    planners::ConcentricCircleSettings settings;
    settings.candidates = "paper";
    settings.ringSpacing = 0.25;
    settings.potentialRange = 1.;
    planners::ConcentricCircleSearch search(*map, settings);
    ASSERT_TRUE(search.run({-2., 0.1}, {2., -0.1}, ob::plannerNonTerminatingCondition()));

    int linkedRings = 0;
    for (const auto &ring : search.rings())
    {
        if (ring.candidates.empty())
            continue;
        ++linkedRings;
        const int n = static_cast<int>(ring.points.size());
        EXPECT_EQ(n, 72) << "the paper cuts every circle into 72 points";
        // the free arcs: maximal cyclic runs of free points
        std::vector<int> arcOf(n, -1);
        int arcs = 0;
        int firstBlocked = -1;
        for (int i = 0; i < n && firstBlocked < 0; ++i)
            if (!ring.free[i])
                firstBlocked = i;
        if (firstBlocked < 0)
        {
            arcs = 1;
            std::fill(arcOf.begin(), arcOf.end(), 0);
        }
        else
            for (int step = 1; step <= n; ++step)
            {
                const int i = (firstBlocked + step) % n;
                if (!ring.free[i])
                    continue;
                if (!ring.free[(i + n - 1) % n])
                    ++arcs;
                arcOf[i] = arcs - 1;
            }
        ASSERT_EQ(static_cast<int>(ring.candidates.size()), arcs) << "one candidate per free arc";
        std::vector<int> seen(arcs, 0);
        for (const int node : ring.candidates)
        {
            const auto &c = search.nodes()[node];
            int index = -1;
            for (int i = 0; i < n; ++i)
                if ((ring.points[i] - c.p).norm() < 1e-12)
                    index = i;
            ASSERT_GE(index, 0) << "a candidate is one of its circle's points";
            const int arc = arcOf[index];
            ASSERT_GE(arc, 0) << "a candidate is a free point";
            ++seen[arc];
            for (int i = 0; i < n; ++i)
                if (arcOf[i] == arc)
                    EXPECT_LE(ring.potential[index], ring.potential[i]) << "the candidate is its arc's minimum";
        }
        for (const int count : seen)
            EXPECT_EQ(count, 1);
    }
    EXPECT_GT(linkedRings, 3);
}

TEST(ConcentricCircleRules, PathsLeftAndRightOfAnObstacleAreBothInThePlannerData)
{
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    auto space = std::make_shared<ob::RealVectorStateSpace>(2);
    space->setBounds(-3., 3.);
    og::SimpleSetup setup(space);
    // one square across the straight line from start to goal: a path passes above it or below it
    setup.setStateValidityChecker(
        [](const ob::State *s)
        {
            const auto *v = s->as<ob::RealVectorStateSpace::StateType>()->values;
            return !(std::abs(v[0]) <= 0.5 && std::abs(v[1]) <= 0.5);
        });
    setup.getSpaceInformation()->setStateValidityCheckingResolution(0.002);
    ob::ScopedState<> start(space), goal(space);
    start[0] = -2.;
    start[1] = 0.;
    goal[0] = 2.;
    goal[1] = 0.;
    setup.setStartAndGoalStates(start, goal);
    auto planner = std::make_shared<planners::ConcentricCircle>(setup.getSpaceInformation());
    setup.setPlanner(planner);
    ASSERT_EQ(setup.solve(10.), ob::PlannerStatus::EXACT_SOLUTION);

    ob::PlannerData data(setup.getSpaceInformation());
    planner->getPlannerData(data);
    ASSERT_GT(data.numStartVertices(), 0u);
    ASSERT_GT(data.numGoalVertices(), 0u);
    // a chain of PlannerData edges from the start to the goal through vertices on one side only (y >= 0: above
    // the square, y <= 0: below); the start and goal, at y = 0, are on both sides
    auto reachable = [&](const std::function<bool(double)> &side)
    {
        const unsigned int from = data.getStartIndex(0);
        std::vector<char> seen(data.numVertices(), 0);
        std::deque<unsigned int> open{from};
        seen[from] = 1;
        while (!open.empty())
        {
            const unsigned int v = open.front();
            open.pop_front();
            if (data.isGoalVertex(v))
                return true;
            std::vector<unsigned int> next;
            data.getEdges(v, next);
            for (const unsigned int w : next)
            {
                const auto *values = data.getVertex(w).getState()->as<ob::RealVectorStateSpace::StateType>()->values;
                if (!seen[w] && side(values[1]))
                {
                    seen[w] = 1;
                    open.push_back(w);
                }
            }
        }
        return false;
    };
    EXPECT_TRUE(reachable(
        [](double y)
        {
            return y >= -1e-9;
        }))
        << "no path above the obstacle in the planner data";
    EXPECT_TRUE(reachable(
        [](double y)
        {
            return y <= 1e-9;
        }))
        << "no path below the obstacle in the planner data";
    // and the planner kept both as full paths, of which the solution is one
    EXPECT_GE(planner->fullPaths().size(), 2u);
}

TEST(ConcentricCircleRules, FreeArcsFromCrossingsAgreeWithPointTestsAndSplitAtThinObstacles)
{
    // Two squares and a sliver 0.01 wide: on circles around the origin, every point's arc says what its own point
    // test says, and the sliver (thinner than the points' spacing) still cuts the arc it crosses in two.
    validity::MultiPolygon2 obstacles{
        validity::makePolygon2({{1., -0.5}, {2., -0.5}, {2., 0.5}, {1., 0.5}}),
        validity::makePolygon2({{-2., 1.}, {-1., 1.}, {-1., 2.}, {-2., 2.}}),
        validity::makePolygon2({{-0.005, -2.5}, {0.005, -2.5}, {0.005, -0.5}, {-0.005, -0.5}})};
    planners::PolygonCircleMap map(obstacles, Eigen::Vector2d(-3., -3.), Eigen::Vector2d(3., 3.));
    const int n = 72;
    for (double radius = 0.3; radius < 3.; radius += 0.17)
    {
        const double phase = 0.1 * radius;
        std::vector<int> arc;
        ASSERT_TRUE(map.freeArcs(Eigen::Vector2d::Zero(), radius, phase, n, arc));
        ASSERT_EQ(arc.size(), static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i)
        {
            const double a = phase + 2. * M_PI * i / n;
            const Eigen::Vector2d p = radius * Eigen::Vector2d(std::cos(a), std::sin(a));
            EXPECT_EQ(arc[i] >= 0, map.isFree(p)) << "radius " << radius << ", point " << i;
        }
    }
    // radius 1.2: the sliver crosses the circle at the bottom (angle -pi/2 +- 0.004 rad), between two points 5
    // degrees apart that are both free; they lie on different arcs
    std::vector<int> arc;
    const double radius = 1.2, phase = -M_PI / 2. + M_PI / 72.;  // points at -pi/2 -+ 2.5 degrees
    ASSERT_TRUE(map.freeArcs(Eigen::Vector2d::Zero(), radius, phase, n, arc));
    ASSERT_GE(arc[0], 0);
    ASSERT_GE(arc[n - 1], 0);
    EXPECT_NE(arc[0], arc[n - 1]) << "the sliver between the two points splits the arc";
    // a circle that meets no polygon: one free arc
    ASSERT_TRUE(map.freeArcs(Eigen::Vector2d(2.5, -2.5), 0.2, 0., n, arc));
    for (int i = 0; i < n; ++i)
        EXPECT_EQ(arc[i], arc[0]);
    EXPECT_GE(arc[0], 0);
}

TEST(ConcentricCircle, SettersRefuseValuesThatMakeTheSearchNonsense)
{
    // Found 2026-12-07 through the C++ API (the command line already refused values outside the declared ranges):
    // a ring spacing of 0 or below ran to the time limit, negative counts ended in ABORT.
    auto space = std::make_shared<ompl::base::RealVectorStateSpace>(2);
    space->setBounds(-1., 1.);
    auto si = std::make_shared<ompl::base::SpaceInformation>(space);
    michi::planners::ConcentricCircle planner(si);
    for (const auto &bad : std::vector<std::pair<std::string, std::string>>{{"ring_spacing", "0"},
                                                                            {"ring_spacing", "-1"},
                                                                            {"divisions", "-8"},
                                                                            {"divisions", "0"},
                                                                            {"point_spacing", "-0.1"},
                                                                            {"max_paths", "0"},
                                                                            {"max_arc_points", "-1"},
                                                                            {"max_recursions", "-1"},
                                                                            {"potential_range", "-1"},
                                                                            {"k_obstacle", "-1"}})
    {
        const std::string before = planner.params()[bad.first].getValue();
        EXPECT_THROW(planner.params().setParam(bad.first, bad.second), ompl::Exception)
            << bad.first << " " << bad.second;
        EXPECT_EQ(planner.params()[bad.first].getValue(), before) << bad.first;
    }
    EXPECT_TRUE(planner.params().setParam("ring_spacing", "0.05"));
    EXPECT_TRUE(planner.params().setParam("max_arc_points", "0"));
}

TEST(ConcentricCircle, AutoModeOnAPlainSe2SpaceFallsBackToTheProjection)
{
    // Found 2026-12-07 through the C++ API: on OMPL's SE2StateSpace (3 values, no arm) auto chose the restriction
    // surface, which found nothing for start and goal at one heading (ABORT), where mode projection solves at once.
    // A wall at x in [4.9, 5.1] up to y = 8 (the way round it above), a thin wall at y = 5 from x = 6.
    const auto space = michi::state_spaces::makeSe2StateSpace(0., 10., 0., 10.);
    ompl::geometric::SimpleSetup setup(space);
    auto free = [](double x, double y)
    {
        return !(x >= 4.9 && x <= 5.1 && y <= 8.) && !(y >= 4.99 && y <= 5.01 && x >= 6.);
    };
    setup.setStateValidityChecker(
        [&](const ompl::base::State *s)
        {
            const auto *se2 = s->as<ompl::base::SE2StateSpace::StateType>();
            return setup.getSpaceInformation()->satisfiesBounds(s) && free(se2->getX(), se2->getY());
        });
    setup.getSpaceInformation()->setStateValidityCheckingResolution(0.001);
    ompl::base::ScopedState<ompl::base::SE2StateSpace> start(space), goal(space);
    start->setXY(1., 1.);
    start->setYaw(0.);
    goal->setXY(9., 1.);
    goal->setYaw(0.);
    setup.setStartAndGoalStates(start, goal);
    auto planner = std::make_shared<michi::planners::ConcentricCircle>(setup.getSpaceInformation());
    setup.setPlanner(planner);
    ASSERT_EQ(setup.solve(5.), ompl::base::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(planner->usedMode(), "projection");
    auto &path = setup.getSolutionPath();
    EXPECT_TRUE(path.check());
    path.interpolate(2000);
    for (const auto *s : path.getStates())
    {
        const auto *se2 = s->as<ompl::base::SE2StateSpace::StateType>();
        ASSERT_TRUE(free(se2->getX(), se2->getY())) << se2->getX() << " " << se2->getY();
    }
}
