// Tests of michi::validity::ConservativeMotionValidator: motions through obstacles thinner than the state space's
// resolution are rejected (where OMPL's DiscreteMotionValidator accepts them), free motions are accepted, the last
// valid state is before the obstacle, on joint spaces and on SE(2).

#include "support/TestScenes.h"

#include <michi/validity/fcl/ConservativeMotionValidator.h>
#include <michi/validity/fcl/WorkspaceMotionValidator.h>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

using namespace michi;
using validity::ConservativeMotionValidator;

namespace ob = ompl::base;

namespace
{
    ob::ScopedState<> state(const ob::SpaceInformationPtr &si, const std::vector<double> &values)
    {
        ob::ScopedState<> s(si);
        si->getStateSpace()->copyFromReals(s.get(), values);
        return s;
    }

    /** The first fraction of the motion s1 -> s2 (the space's interpolation) at which a state is invalid, found by
        \e steps equal steps; 2 when the whole motion is valid at that resolution. */
    double firstInvalidFraction(const ob::SpaceInformationPtr &si, const ob::State *s1, const ob::State *s2,
                                int steps = 20000)
    {
        ob::ScopedState<> s(si);
        for (int i = 0; i <= steps; ++i)
        {
            const double t = static_cast<double>(i) / steps;
            si->getStateSpace()->interpolate(s1, s2, t, s.get());
            if (!si->isValid(s.get()))
                return t;
        }
        return 2.;
    }

    /** Checks the motion s1 -> s2 through a thin obstacle: OMPL's discrete check at the space's (coarse) resolution
        misses it, the conservative validator does not, and the last valid state it reports is valid and before
        the obstacle. */
    void expectThinObstacleCaught(const test::CheckerSetup &setup, const std::vector<double> &from,
                                  const std::vector<double> &to)
    {
        const auto &si = setup.si;
        const auto s1 = state(si, from), s2 = state(si, to);
        ASSERT_TRUE(si->isValid(s1.get()));
        ASSERT_TRUE(si->isValid(s2.get()));
        const double hit = firstInvalidFraction(si, s1.get(), s2.get());
        ASSERT_LT(hit, 1.) << "the motion must cross the obstacle";

        // the premise: the obstacle is thinner than the resolution, and OMPL's validator steps over it
        ob::DiscreteMotionValidator discrete(si);
        EXPECT_TRUE(discrete.checkMotion(s1.get(), s2.get()))
            << "the test needs a resolution at which DiscreteMotionValidator misses the obstacle";

        ConservativeMotionValidator conservative(si, setup.checker);
        EXPECT_FALSE(conservative.checkMotion(s1.get(), s2.get()));
        EXPECT_EQ(conservative.getCheckedMotionCount(), 1u);
        EXPECT_EQ(conservative.getValidMotionCount(), 0u);

        ob::ScopedState<> last(si);
        std::pair<ob::State *, double> lastValid{last.get(), -1.};
        EXPECT_FALSE(conservative.checkMotion(s1.get(), s2.get(), lastValid));
        EXPECT_GE(lastValid.second, 0.);
        EXPECT_LT(lastValid.second, hit) << "the last valid state is before the obstacle";
        EXPECT_GT(lastValid.second, 0.5 * hit) << "the walk gets close to the obstacle";
        EXPECT_TRUE(si->isValid(last.get()));
        ob::ScopedState<> expected(si);
        si->getStateSpace()->interpolate(s1.get(), s2.get(), lastValid.second, expected.get());
        EXPECT_LT(si->distance(expected.get(), last.get()), 1e-12);

        // the reverse motion is rejected too, with its last valid state on the other side
        std::pair<ob::State *, double> back{last.get(), -1.};
        EXPECT_FALSE(conservative.checkMotion(s2.get(), s1.get(), back));
        EXPECT_LT(back.second, 1. - hit);
        EXPECT_TRUE(si->isValid(last.get()));
    }

    /** A ball of radius 0.1 on a slide along x (limits [-2, 2]) and a wall 0.01 thick at x = 1. */
    test::CheckerSetup ballThroughThinWall(double resolution)
    {
        const char *urdf = R"(<robot name="ball_on_slide">
  <link name="base_link"/>
  <link name="ball"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <joint name="slide" type="prismatic">
    <parent link="base_link"/><child link="ball"/><axis xyz="1 0 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
</robot>)";
        auto scene = std::make_shared<validity::Scene>();
        validity::Obstacle wall;
        wall.name = "thin_wall";
        wall.shape = validity::Shape::box({0.01, 1., 1.});
        wall.pose = Eigen::Translation3d(1., 0., 0.) * Eigen::Isometry3d::Identity();
        scene->add(wall);
        return test::robotSetup(validity::RobotModel::fromUrdfString(urdf, "<ball urdf>", "."), scene, resolution);
    }
}  // namespace

TEST(ConservativeMotionValidator, BallDoesNotPassThroughAThinWall)
{
    // extent 4, resolution 0.2: segments of 0.8, while the ball overlaps the wall only for 0.21 of its travel
    const auto setup = ballThroughThinWall(0.2);
    EXPECT_NEAR(setup.si->getStateSpace()->getLongestValidSegmentLength(), 0.8, 1e-12);
    expectThinObstacleCaught(setup, {-1.5}, {1.5});
}

TEST(ConservativeMotionValidator, PlanarArmDoesNotSweepThroughAThinWall)
{
    // a wall 0.02 thick along the x axis from x = 0.3 to 0.8; the arm swings from -1 rad to 1.4 rad through it.
    // Resolution 0.2 of the extent (2 pi sqrt 2) gives segments of 1.78 rad: the discrete check only looks at the
    // ends and at 0.2 rad, where the arm is already clear of the wall.
    const auto setup = test::planarArmSetup({0.5, 0.4}, {test::boxOutline({0.3, -0.01}, {0.8, 0.01})}, {}, 0.2);
    expectThinObstacleCaught(setup, {-1., 0.}, {1.4, 0.});
    // also with the elbow moving
    expectThinObstacleCaught(setup, {-1., 0.3}, {1.4, -0.3});
}

TEST(ConservativeMotionValidator, RigidBodyInSe2DoesNotPassThroughAThinWall)
{
    // a 0.2 x 0.2 square crossing a wall 0.02 thick at x = 0, turning on the way
    const auto setup =
        test::planarRigidBodySetup(test::boxOutline({-0.1, -0.1}, {0.1, 0.1}),
                                   {test::boxOutline({-0.01, -1.}, {0.01, 1.})}, {-2., -2.}, {2., 2.}, 0.5);
    expectThinObstacleCaught(setup, {-1., 0., 0.}, {1.4, 0.2, 1.});
    expectThinObstacleCaught(setup, {1.2, -0.3, 3.}, {-1.2, 0.3, -3.});  // yaw wraps the short way round
}

TEST(ConservativeMotionValidator, FreeMotionsAreAccepted)
{
    const auto arm = test::planarArmSetup({0.5, 0.4}, {test::boxOutline({0.3, -0.01}, {0.8, 0.01})}, {}, 0.2);
    ConservativeMotionValidator validator(arm.si, arm.checker);
    // swinging below and above the wall, folding above it, and staying put
    for (const auto &motion : std::vector<std::pair<std::vector<double>, std::vector<double>>>{
             {{-1., 0.}, {-2.5, 1.}}, {{0.5, 0.}, {2.5, -2.}}, {{0.3, 0.}, {0.3, 1.5}}, {{-0.2, -1.}, {-0.2, -1.}}})
    {
        const auto s1 = state(arm.si, motion.first), s2 = state(arm.si, motion.second);
        ASSERT_GT(firstInvalidFraction(arm.si, s1.get(), s2.get()), 1.);
        EXPECT_TRUE(validator.checkMotion(s1.get(), s2.get()));
        std::pair<ob::State *, double> lastValid{nullptr, -1.};
        EXPECT_TRUE(validator.checkMotion(s1.get(), s2.get(), lastValid));
    }
    EXPECT_EQ(validator.getValidMotionCount(), 8u);

    // a motion to an invalid or out-of-bounds state is not
    EXPECT_FALSE(validator.checkMotion(state(arm.si, {-1., 0.}).get(), state(arm.si, {0., 0.}).get()));
    EXPECT_FALSE(validator.checkMotion(state(arm.si, {-1., 0.}).get(), state(arm.si, {-1., 3.5}).get()));

    const auto body =
        test::planarRigidBodySetup(test::boxOutline({-0.1, -0.1}, {0.1, 0.1}),
                                   {test::boxOutline({-0.01, -1.}, {0.01, 1.})}, {-2., -2.}, {2., 2.}, 0.5);
    ConservativeMotionValidator se2(body.si, body.checker);
    EXPECT_TRUE(se2.checkMotion(state(body.si, {-1., -1.5, 0.}).get(), state(body.si, {1., -1.5, 2.}).get()));
    EXPECT_TRUE(se2.checkMotion(state(body.si, {-0.5, 0., 0.}).get(), state(body.si, {-0.5, 0.5, 3.}).get()));
}

TEST(ConservativeMotionValidator, AgreesWithAFineCheckOnRandomMotions)
{
    // a 3-link arm among random polygons: every motion the validator accepts is free at a resolution 100 times
    // finer than the space's, and almost every motion that is free there is accepted
    test::RandomPolygonOptions options;
    options.count = 8;
    options.lo = {-1.2, -1.2};
    options.hi = {1.2, 1.2};
    options.keepClearRadius = 0.15;
    const auto obstacles = test::randomPolygons(31, options);
    const auto setup = test::planarArmSetup({0.4, 0.35, 0.3}, obstacles, {}, 0.05);
    const auto fine = test::planarArmSetup({0.4, 0.35, 0.3}, obstacles, {}, 0.0005);
    ConservativeMotionValidator validator(setup.si, setup.checker);
    ob::DiscreteMotionValidator discrete(setup.si);
    ob::DiscreteMotionValidator fineDiscrete(fine.si);

    ompl::RNG rng(5);
    auto randomValidState = [&]
    {
        std::vector<double> q(3);
        while (true)
        {
            for (auto &v : q)
                v = rng.uniformReal(-M_PI, M_PI);
            if (setup.checker->isValidConfiguration(q.data()))
                return q;
        }
    };
    int checked = 0, accepted = 0, free = 0, agree = 0, discreteMissed = 0;
    const int motions = 300;
    for (int i = 0; i < motions; ++i)
    {
        auto from = randomValidState();
        auto to = randomValidState();
        // half of the motions short, so that many are free
        if (i % 2 == 0)
            for (int j = 0; j < 3; ++j)
                to[j] = from[j] + 0.25 * (to[j] - from[j]);
        const auto s1 = state(setup.si, from), s2 = state(setup.si, to);
        if (!setup.si->isValid(s2.get()))
            continue;
        ++checked;
        const bool ok = validator.checkMotion(s1.get(), s2.get());
        const bool fineOk = fineDiscrete.checkMotion(state(fine.si, from).get(), state(fine.si, to).get());
        accepted += ok;
        free += fineOk;
        agree += ok == fineOk;
        discreteMissed += discrete.checkMotion(s1.get(), s2.get()) && !fineOk;
        if (ok)
            EXPECT_TRUE(fineOk) << "accepted a motion that collides: from " << from[0] << " " << from[1] << " "
                                << from[2] << " to " << to[0] << " " << to[1] << " " << to[2];
    }
    // both kinds are common; the validator misses at most a few grazing free motions (never a colliding one)
    EXPECT_GT(free, 30);
    EXPECT_LT(free, checked - 30);
    EXPECT_GE(agree, checked - 3) << "accepted " << accepted << " of " << free << " free motions";
    EXPECT_GT(discreteMissed, 0) << "at this resolution OMPL's discrete check accepts some colliding motions";
}

TEST(ConservativeMotionValidator, SettingsKeepThinObstaclesCaught)
{
    // a coarser minimum step (5 mm, still below the wall's 10 mm) keeps the walk safe
    const auto setup = ballThroughThinWall(0.2);
    ConservativeMotionValidator validator(setup.si, setup.checker);
    EXPECT_DOUBLE_EQ(validator.getMinClearanceStep(), 1e-3);
    validator.setMinClearanceStep(5e-3);
    EXPECT_DOUBLE_EQ(validator.getMinClearanceStep(), 5e-3);
    EXPECT_FALSE(validator.checkMotion(state(setup.si, {-1.5}).get(), state(setup.si, {1.5}).get()));
    EXPECT_FALSE(validator.checkMotion(state(setup.si, {1.9}).get(), state(setup.si, {-1.9}).get()));
    EXPECT_TRUE(validator.checkMotion(state(setup.si, {-1.5}).get(), state(setup.si, {0.85}).get()));
    EXPECT_TRUE(validator.checkMotion(state(setup.si, {1.95}).get(), state(setup.si, {1.15}).get()));
}

TEST(ConservativeMotionValidator, WorkPerMotionIsBoundedForRobotsWithManyBodies)
{
    // A 200-link chain of 0.3 mm spheres 1 mm apart: about 20,000 self pairs, each a distance query at every step of
    // the walk, and a curling motion whose walk needs about a thousand steps. Before the budget a 1,000-link chain
    // took minutes per motion (the bad-input sweep of docs/reliability.md); now the walk stops after its share of
    // the query budget and reports the motion invalid (conservative, never a motion passed unchecked).
    const int links = 200;
    std::string urdf = "<robot name=\"chain\"><link name=\"l0\"/>";
    for (int i = 1; i <= links; ++i)
        urdf += "<link name=\"l" + std::to_string(i) +
                "\"><collision><geometry><sphere radius=\"0.0003\"/></geometry></collision></link>"
                "<joint name=\"j" +
                std::to_string(i) + "\" type=\"revolute\"><parent link=\"l" + std::to_string(i - 1) +
                "\"/><child link=\"l" + std::to_string(i) +
                "\"/><origin xyz=\"0.001 0 0\"/><axis xyz=\"0 0 1\"/>"
                "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>";
    urdf += "</robot>";
    const auto setup = test::robotSetup(validity::RobotModel::fromUrdfString(urdf, "<chain urdf>", "."),
                                        std::make_shared<validity::Scene>());
    const std::vector<double> straight(links, 0.), curled(links, 0.03);  // 6 rad of curl: the ends stay apart
    const auto s1 = state(setup.si, straight), s2 = state(setup.si, curled);
    ASSERT_TRUE(setup.si->isValid(s1.get()));
    ASSERT_TRUE(setup.si->isValid(s2.get()));
    ConservativeMotionValidator validator(setup.si, setup.checker);
    const std::uint64_t before = setup.checker->queryCount();
    EXPECT_FALSE(validator.checkMotion(s1.get(), s2.get()));
    // one collision query per step; every step also queries each moving body and self pair
    const double perStep = static_cast<double>(setup.bodies->selfCheckPairs().size() + setup.bodies->bodies().size());
    EXPECT_LE(static_cast<double>(setup.checker->queryCount() - before), 5e6 / perStep + 2.);
    // a short motion of the same chain still walks to its end and passes
    const std::vector<double> bent(links, 0.0002);
    EXPECT_TRUE(validator.checkMotion(s1.get(), state(setup.si, bent).get()));
}

TEST(WorkspaceMotionValidator, ChecksEveryMaxStepOfDisplacement)
{
    // on random motions of a 3-link arm, no point of a link's cylinder axis moves more than max_step between two
    // consecutive checked states
    const auto setup = test::planarArmSetup({0.4, 0.35, 0.3}, {}, {}, 0.05);
    validity::WorkspaceMotionValidator validator(setup.si, setup.checker, 0.02);
    ompl::RNG rng(9);
    const auto &bodies = *setup.checker->bodies();
    for (int i = 0; i < 50; ++i)
    {
        std::vector<double> from(3), to(3);
        for (int j = 0; j < 3; ++j)
        {
            from[j] = rng.uniformReal(-M_PI, M_PI);
            to[j] = rng.uniformReal(-M_PI, M_PI);
        }
        const auto s1 = state(setup.si, from), s2 = state(setup.si, to);
        const unsigned int n = validator.stepCount(s1.get(), s2.get());
        ASSERT_GE(n, 1u);
        std::vector<Eigen::Isometry3d> before, after;
        std::vector<double> a, b;
        ob::ScopedState<> sa(setup.si), sb(setup.si);
        for (unsigned int k = 0; k < n; ++k)
        {
            setup.si->getStateSpace()->interpolate(s1.get(), s2.get(), static_cast<double>(k) / n, sa.get());
            setup.si->getStateSpace()->interpolate(s1.get(), s2.get(), static_cast<double>(k + 1) / n, sb.get());
            setup.si->getStateSpace()->copyToReals(a, sa.get());
            setup.si->getStateSpace()->copyToReals(b, sb.get());
            bodies.bodyPoses(a.data(), before);
            bodies.bodyPoses(b.data(), after);
            for (std::size_t body = 0; body < before.size(); ++body)
                for (const auto &s : bodies.bodies()[body].shapes)
                    for (double z : {-0.5, 0., 0.5})
                    {
                        const Eigen::Vector3d p(0., 0., z * s.shape->size().z());
                        const double moved = ((after[body] * s.origin * p) - (before[body] * s.origin * p)).norm();
                        EXPECT_LE(moved, 0.02 + 1e-12) << "motion " << i << " step " << k;
                    }
        }
    }
    EXPECT_THROW(validator.setMaxStep(0.), std::invalid_argument);
}

TEST(WorkspaceMotionValidator, CatchesAWallThickerThanItsStep)
{
    // the 10 mm wall with 5 mm steps: rejected both ways, where OMPL's discrete validator steps over it
    const auto setup = ballThroughThinWall(0.2);
    validity::WorkspaceMotionValidator validator(setup.si, setup.checker, 0.005);
    const auto s1 = state(setup.si, {-1.5}), s2 = state(setup.si, {1.5});
    EXPECT_FALSE(validator.checkMotion(s1.get(), s2.get()));
    EXPECT_FALSE(validator.checkMotion(s2.get(), s1.get()));
    ob::ScopedState<> last(setup.si);
    std::pair<ob::State *, double> lastValid{last.get(), -1.};
    EXPECT_FALSE(validator.checkMotion(s1.get(), s2.get(), lastValid));
    EXPECT_TRUE(setup.si->isValid(last.get()));
    EXPECT_LT(lastValid.second, firstInvalidFraction(setup.si, s1.get(), s2.get()));
    EXPECT_TRUE(validator.checkMotion(s1.get(), state(setup.si, {0.85}).get()));
}
