// Tests of the path deformation of paper 002 (michi::planners::deformPath, pointJacobian): the Jacobians agree with
// finite differences of the forward kinematics; a path passing closer than d_i to an obstacle is pushed away by
// Jacobian-transpose steps until its clearance is restored, its ends stay where they were; a path through an
// obstacle is not deformed (replanning must handle it); a rejected deformation leaves the path alone.
#include "support/TestScenes.h"

#include <michi/planners/dual_roadmap/PathDeformation.h>

#include <ompl/base/ScopedState.h>

#include <gtest/gtest.h>

#include <algorithm>

using namespace michi;
namespace ob = ompl::base;

namespace
{
    /** Finite-difference Jacobian of a world point fixed to a body. */
    Eigen::MatrixXd numericJacobian(const validity::CollisionBodies &bodies, std::vector<double> q, int body,
                                    const Eigen::Vector3d &point)
    {
        std::vector<Eigen::Isometry3d> poses;
        bodies.bodyPoses(q.data(), poses);
        const Eigen::Vector3d local = poses[body].inverse() * point;
        Eigen::MatrixXd j(3, q.size());
        for (std::size_t c = 0; c < q.size(); ++c)
        {
            const double keep = q[c];
            q[c] = keep + 1e-6;
            bodies.bodyPoses(q.data(), poses);
            const Eigen::Vector3d plus = poses[body] * local;
            q[c] = keep - 1e-6;
            bodies.bodyPoses(q.data(), poses);
            const Eigen::Vector3d minus = poses[body] * local;
            q[c] = keep;
            j.col(c) = (plus - minus) / 2e-6;
        }
        return j;
    }

    struct Se2Case
    {
        test::CheckerSetup setup;
        std::function<double(const planners::Configuration &, const planners::Configuration &)> distance;
        std::function<void(const planners::Configuration &, const planners::Configuration &, double,
                           planners::Configuration &)>
            interpolate;

        Se2Case()
        {
            // a 0.2 m square robot; a box whose lower edge is 0.35 m above the straight path y = 0
            setup = test::planarRigidBodySetup(test::boxOutline({-0.1, -0.1}, {0.1, 0.1}),
                                               {test::boxOutline({1.8, 0.35}, {2.2, 0.8})}, {-1., -2.}, {5., 2.});
            auto si = setup.si;
            distance = [si](const planners::Configuration &a, const planners::Configuration &b)
            {
                ob::ScopedState<> sa(si), sb(si);
                si->getStateSpace()->copyFromReals(sa.get(), a);
                si->getStateSpace()->copyFromReals(sb.get(), b);
                return si->distance(sa.get(), sb.get());
            };
            interpolate = [si](const planners::Configuration &a, const planners::Configuration &b, double t,
                               planners::Configuration &out)
            {
                ob::ScopedState<> sa(si), sb(si), so(si);
                si->getStateSpace()->copyFromReals(sa.get(), a);
                si->getStateSpace()->copyFromReals(sb.get(), b);
                si->getStateSpace()->interpolate(sa.get(), sb.get(), t, so.get());
                si->getStateSpace()->copyToReals(out, so.get());
            };
        }

        double minClearance(const planners::ConfigurationPath &path) const
        {
            double d = 1e9;
            for (std::size_t i = 0; i + 1 < path.size(); ++i)
                for (int k = 0; k <= 20; ++k)
                {
                    planners::Configuration q;
                    interpolate(path[i], path[i + 1], k / 20., q);
                    d = std::min(d, setup.checker->clearanceConfiguration(q.data()));
                }
            return d;
        }
    };
}  // namespace

TEST(PathDeformation, JacobiansMatchFiniteDifferences)
{
    const auto model = test::planarArmModel({0.5, 0.4, 0.3});
    validity::RobotGroupBodies arm(model, {0, 1, 2}, {0., 0., 0.});
    const std::vector<double> q{0.3, -0.7, 1.1};
    std::vector<Eigen::Isometry3d> poses;
    arm.bodyPoses(q.data(), poses);
    const Eigen::Vector3d p = poses[2] * Eigen::Vector3d(0.2, 0.01, 0.);
    EXPECT_TRUE(planners::pointJacobian(arm, q.data(), 2, p).isApprox(numericJacobian(arm, q, 2, p), 1e-5));

    validity::PlanarRigidBody body(test::boxOutline({-0.3, -0.2}, {0.3, 0.2}));
    const std::vector<double> s{1., 2., 0.7};
    body.bodyPoses(s.data(), poses);
    const Eigen::Vector3d c = poses[0] * Eigen::Vector3d(0.3, -0.2, 0.5);
    EXPECT_TRUE(planners::pointJacobian(body, s.data(), 0, c).isApprox(numericJacobian(body, s, 0, c), 1e-5));
}

TEST(PathDeformation, PathCloserThanDiIsPushedAwayEndsKept)
{
    Se2Case f;
    planners::ConfigurationPath path{{0., 0., 0.}, {4., 0., 0.}};
    const double before = f.minClearance(path);
    ASSERT_NEAR(before, 0.25, 1e-6);
    planners::DeformationSettings settings;
    settings.startDistance = 0.4;
    settings.window = 5.;
    settings.iterations = 30;
    bool checked = false;
    auto accept = [&](const planners::ConfigurationPath &p)
    {
        checked = true;
        for (const auto &q : p)
            if (!f.setup.checker->isValidConfiguration(q.data()))
                return false;
        return true;
    };
    ASSERT_TRUE(planners::deformPath(path, *f.setup.checker, f.distance, f.interpolate, accept, settings));
    EXPECT_TRUE(checked);
    EXPECT_GT(path.size(), 2u);
    EXPECT_EQ(path.front(), (planners::Configuration{0., 0., 0.}));
    EXPECT_NEAR(path.back()[0], 4., 1e-9);
    EXPECT_NEAR(path.back()[1], 0., 1e-9);
    const double after = f.minClearance(path);
    EXPECT_GT(after, 0.35) << "clearance restored towards d_i (was " << before << ")";
    // the path bent away from the box (downwards), not through it
    double lowest = 0.;
    for (const auto &q : path)
        lowest = std::min(lowest, q[1]);
    EXPECT_LT(lowest, -0.05);
}

TEST(PathDeformation, CollidingOrRejectedPathIsLeftAlone)
{
    Se2Case f;
    planners::DeformationSettings settings;
    settings.startDistance = 0.4;
    settings.window = 5.;
    auto acceptAll = [](const planners::ConfigurationPath &)
    {
        return true;
    };
    planners::ConfigurationPath through{{0., 0.5, 0.}, {4., 0.5, 0.}};  // straight through the box
    const auto keep = through;
    EXPECT_FALSE(planners::deformPath(through, *f.setup.checker, f.distance, f.interpolate, acceptAll, settings));
    EXPECT_EQ(through, keep);

    planners::ConfigurationPath close{{0., 0., 0.}, {4., 0., 0.}};
    const auto keep2 = close;
    auto reject = [](const planners::ConfigurationPath &)
    {
        return false;
    };
    EXPECT_FALSE(planners::deformPath(close, *f.setup.checker, f.distance, f.interpolate, reject, settings));
    EXPECT_EQ(close, keep2);

    planners::ConfigurationPath far{{0., -1.5, 0.}, {4., -1.5, 0.}};  // nowhere near: nothing to do
    EXPECT_FALSE(planners::deformPath(far, *f.setup.checker, f.distance, f.interpolate, acceptAll, settings));
}
