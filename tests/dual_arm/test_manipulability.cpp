// Tests of the manipulability measure (michi::planners::manipulability, ArmChain), the hand IK and
// ManipulabilityObjective: w against the closed form of a planar 2-link arm and against the singular values,
// the Jacobian-based w against a finite-difference Jacobian on both arms of the dual-arm robot, IK meeting
// the hand-orientation constraints, the objective's state and motion costs, and the reach sphere containing every
// tool position of arms with prismatic joints.

#include "support/TestScenes.h"

#include <michi/planners/HandIk.h>
#include <michi/planners/dual_arm/Manipulability.h>
#include <michi/planners/dual_arm/ManipulabilityObjective.h>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/util/RandomNumbers.h>

#include <Eigen/SVD>

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

using namespace michi;
using planners::ArmChain;
using planners::HandTarget;
using planners::ManipulabilityRows;

namespace
{
    validity::RobotModelPtr dualArm()
    {
        return validity::RobotModel::fromUrdfFile(test::sourcePath("problems/robots/dual_arm.urdf"));
    }

    std::vector<double> randomConfiguration(const validity::RobotModel &model, ompl::RNG &rng)
    {
        std::vector<double> q(model.variableCount());
        for (std::size_t v = 0; v < q.size(); ++v)
            q[v] = rng.uniformReal(model.variableJoint(v).lower, model.variableJoint(v).upper);
        return q;
    }

    /** Jacobian of the tool point by central differences of ArmChain::toolPose (linear rows from positions,
        angular rows from the rotation log). */
    Eigen::MatrixXd finiteDifferenceJacobian(const ArmChain &arm, const std::vector<double> &q)
    {
        const double h = 1e-6;
        Eigen::MatrixXd jac(6, static_cast<long>(arm.size()));
        for (std::size_t i = 0; i < arm.size(); ++i)
        {
            std::vector<double> plus = q, minus = q;
            plus[arm.variables()[i]] += h;
            minus[arm.variables()[i]] -= h;
            const Eigen::Isometry3d a = arm.toolPose(plus), b = arm.toolPose(minus);
            jac.block<3, 1>(0, static_cast<long>(i)) = (a.translation() - b.translation()) / (2 * h);
            const Eigen::AngleAxisd d(a.linear() * b.linear().transpose());
            jac.block<3, 1>(3, static_cast<long>(i)) = d.axis() * d.angle() / (2 * h);
        }
        return jac;
    }
}  // namespace

TEST(Manipulability, PlanarTwoLinkClosedForm)
{
    const auto model = validity::RobotModel::fromUrdfFile(test::sourcePath("problems/robots/planar_2link.urdf"));
    const ArmChain arm(model, "link2", Eigen::Vector3d(0.4, 0., 0.));
    for (double t2 : {-2.5, -1.0, 0.0, 0.3, 1.57, 3.0})
    {
        const std::vector<double> q{0.7, t2};
        const Eigen::MatrixXd jac = arm.jacobian(q);
        // w of the planar arm (x, y rows) is l1 l2 |sin t2|
        EXPECT_NEAR(planners::manipulability(jac.topRows(2)), 0.5 * 0.4 * std::abs(std::sin(t2)), 1e-12) << t2;
    }
    // more rows than columns: singular everywhere, an error rather than a silent 0
    EXPECT_THROW(planners::manipulability(Eigen::MatrixXd::Zero(3, 2)), std::invalid_argument);
}

TEST(Manipulability, EqualsProductOfSingularValues)
{
    ompl::RNG rng(3);
    for (int trial = 0; trial < 20; ++trial)
    {
        Eigen::MatrixXd j(3, 6);
        for (long r = 0; r < 3; ++r)
            for (long c = 0; c < 6; ++c)
                j(r, c) = rng.uniformReal(-1., 1.);
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(j);
        EXPECT_NEAR(planners::manipulability(j), svd.singularValues().prod(), 1e-10);
    }
}

TEST(Manipulability, JacobianMatchesFiniteDifferences)
{
    const auto model = dualArm();
    ompl::RNG rng(5);
    for (const char *tip : {"large_tip", "small_tip"})
    {
        const ArmChain arm(model, tip);
        EXPECT_EQ(arm.size(), std::string(tip) == "large_tip" ? 5u : 6u);
        for (int trial = 0; trial < 25; ++trial)
        {
            const auto q = randomConfiguration(*model, rng);
            const Eigen::MatrixXd analytic = arm.jacobian(q), numeric = finiteDifferenceJacobian(arm, q);
            EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-6) << tip;
            for (auto rows : {ManipulabilityRows::POSITION, ManipulabilityRows::FULL})
            {
                const Eigen::MatrixXd jn =
                    rows == ManipulabilityRows::POSITION ? Eigen::MatrixXd(numeric.topRows(3)) : numeric;
                if (jn.rows() > jn.cols())
                {
                    // the 5-joint large arm has no 6-row manipulability: an error, not a silent 0
                    EXPECT_THROW(arm.manipulability(q, rows), std::invalid_argument) << tip;
                    continue;
                }
                const double w = arm.manipulability(q, rows), wn = planners::manipulability(jn);
                EXPECT_NEAR(w, wn, 1e-6 * std::max(1e-3, wn)) << tip;
            }
        }
    }
}

TEST(Manipulability, HandIkMeetsPositionAndOrientation)
{
    const auto model = dualArm();
    const ArmChain small(model, "small_tip"), large(model, "large_tip");
    HandTarget down;                                    // small hand pointing down
    down.position = Eigen::Vector3d(0.41, 0.47, 0.59);  // the small arm is side-mounted (first joint along +y)
    std::vector<double> q(model->variableCount(), 0.);
    const std::vector<double> seed{-0.15, -0.25, 1.16, -1.09, -1.58, -2.2};  // near the hand-over posture
    for (int i = 0; i < 6; ++i)
        q[small.variables()[i]] = seed[i];
    ASSERT_TRUE(planners::solveHandIk(small, down, q));
    const Eigen::Isometry3d ts = small.toolPose(q);
    EXPECT_LT((ts.translation() - down.position).norm(), 1e-4);
    EXPECT_GT((ts.linear() * Eigen::Vector3d::UnitZ()).dot(-Eigen::Vector3d::UnitZ()), std::cos(1e-3));

    HandTarget horizontal;  // large hand horizontal
    horizontal.mode = HandTarget::Mode::AXIS_PERPENDICULAR;
    horizontal.direction = Eigen::Vector3d::UnitZ();
    horizontal.position = Eigen::Vector3d(0.65, 0.1, 0.7);
    q[large.variables()[1]] = 0.8;
    q[large.variables()[2]] = 0.8;
    ASSERT_TRUE(planners::solveHandIk(large, horizontal, q));
    const Eigen::Isometry3d tl = large.toolPose(q);
    EXPECT_LT((tl.translation() - horizontal.position).norm(), 1e-4);
    EXPECT_LT(std::abs((tl.linear() * Eigen::Vector3d::UnitZ()).z()), 1e-3);
    for (int v : large.variables())  // within limits
    {
        EXPECT_GE(q[v], model->variableJoint(v).lower);
        EXPECT_LE(q[v], model->variableJoint(v).upper);
    }

    HandTarget far = down;  // out of reach: no solution
    far.position = Eigen::Vector3d(2.0, 0.2, 0.75);
    EXPECT_FALSE(planners::solveHandIk(small, far, q));
}

TEST(Manipulability, ObjectiveCostsFollowManipulability)
{
    const auto model = dualArm();
    const ArmChain small(model, "small_tip");
    auto space = std::make_shared<ompl::base::RealVectorStateSpace>(6);
    ompl::base::RealVectorBounds bounds(6);
    for (int i = 0; i < 6; ++i)
    {
        bounds.setLow(i, model->variableJoint(small.variables()[i]).lower);
        bounds.setHigh(i, model->variableJoint(small.variables()[i]).upper);
    }
    space->setBounds(bounds);
    auto si = std::make_shared<ompl::base::SpaceInformation>(space);
    si->setStateValidityChecker(
        [](const ompl::base::State *)
        {
            return true;
        });
    si->setup();
    const std::vector<double> fixed(model->variableCount(), 0.);
    planners::ManipulabilityObjective objective(si, small, small.variables(), fixed, ManipulabilityRows::POSITION,
                                                0.004);
    auto *a = si->allocState();
    auto *b = si->allocState();
    const std::vector<double> qa{0.2, 0.5, 0.9, 0.1, 1.0, 0.}, qb{0.25, 0.6, 0.8, 0.1, 1.1, 0.};
    space->copyFromReals(a, qa);
    space->copyFromReals(b, qb);
    std::vector<double> full = fixed;
    for (int i = 0; i < 6; ++i)
        full[small.variables()[i]] = qa[i];
    const double wa = small.manipulability(full, ManipulabilityRows::POSITION);
    EXPECT_GT(wa, 0.);
    EXPECT_NEAR(objective.stateCost(a).value(), std::max(1., 0.004 / wa), 1e-12);
    // the motion cost integrates the state cost over the motion: between the end costs times the length
    const double ca = objective.stateCost(a).value(), cb = objective.stateCost(b).value();
    const double m = objective.motionCost(a, b).value(), d = si->distance(a, b);
    EXPECT_GT(m, 0.9 * std::min(ca, cb) * d);
    EXPECT_LT(m, 1.1 * std::max(ca, cb) * d);
    EXPECT_LE(objective.motionCostHeuristic(a, b).value(), m + 1e-12);  // admissible
    EXPECT_NEAR(objective.motionCostHeuristic(a, b).value(), d, 1e-12);
    // a less dexterous state costs more than 1 per unit length
    const std::vector<double> qc{0.2, 0.1, 0.1, 0.1, 0.1, 0.};
    space->copyFromReals(b, qc);
    for (int i = 0; i < 6; ++i)
        full[small.variables()[i]] = qc[i];
    const double wc = small.manipulability(full, ManipulabilityRows::POSITION);
    ASSERT_LT(wc, 0.004);
    EXPECT_NEAR(objective.stateCost(b).value(), 0.004 / wc, 1e-9);
    objective.setWeight(3.);  // only the part below the reference is weighted
    EXPECT_NEAR(objective.stateCost(b).value(), 1. + 3. * (0.004 / wc - 1.), 1e-9);
    EXPECT_NEAR(objective.stateCost(a).value(), std::max(1., 1. + 3. * (0.004 / wa - 1.)), 1e-9);
    EXPECT_THROW(objective.setWeight(0.), std::invalid_argument);
    objective.setWeight(1.);
    // the straight-up pose is singular (w = 0): clamped to the floor, so it costs reference / floor
    space->copyFromReals(a, std::vector<double>(6, 0.));
    EXPECT_NEAR(objective.stateCost(a).value(), 0.004 / 1e-6, 1e-6);
    si->freeState(a);
    si->freeState(b);
}

TEST(Manipulability, ShortArmRowsAreRejectedNotZero)
{
    // the planar arm has 2 joints: neither the 3-row nor the 6-row manipulability can be anything but 0
    const auto model = validity::RobotModel::fromUrdfFile(test::sourcePath("problems/robots/planar_2link.urdf"));
    const ArmChain arm(model, "link2", Eigen::Vector3d(0.4, 0., 0.));
    EXPECT_THROW(arm.requireRows(ManipulabilityRows::POSITION), std::invalid_argument);
    EXPECT_THROW(arm.requireRows(ManipulabilityRows::FULL), std::invalid_argument);
    EXPECT_THROW(arm.manipulability({0.7, 0.3}, ManipulabilityRows::FULL), std::invalid_argument);
}

namespace
{
    /** Tool positions of \e arm at many configurations inside the joint limits (uniform samples and every joint at
        a limit, where a prismatic joint reaches furthest) must stay inside ArmChain::reachSphere. */
    void expectReachSphereHolds(const ArmChain &arm, const std::string &what)
    {
        const auto &model = *arm.model();
        Eigen::Vector3d centre;
        double radius = 0.;
        arm.reachSphere(centre, radius);
        ompl::RNG rng(11);
        double farthest = 0.;
        for (int s = 0; s < 20000; ++s)
        {
            std::vector<double> q(model.variableCount(), 0.);
            for (int v : arm.variables())
            {
                const auto &joint = model.variableJoint(static_cast<std::size_t>(v));
                // a quarter of the samples put each joint at one of its limits
                const int pick = rng.uniformInt(0, 7);
                q[v] = pick == 0 ? joint.lower : pick == 1 ? joint.upper : rng.uniformReal(joint.lower, joint.upper);
            }
            const double d = (arm.toolPose(q).translation() - centre).norm();
            farthest = std::max(farthest, d);
            ASSERT_LE(d, radius + 1e-9) << what << ": the tool is " << d
                                        << " m from the reach sphere's centre, its radius is " << radius << " m";
        }
        // the samples do stretch the arm (the triangle inequality's bound is loose where offsets are not in line)
        EXPECT_GT(farthest, 0.5 * radius) << what;
    }
}  // namespace

TEST(Manipulability, ReachSphereHoldsWithPrismaticJoints)
{
    // the dual-arm robot with the small arm's third joint made prismatic (0 to 0.4 m along its link): the sum of the
    // link offsets alone (0.435 m) is far short of the stretched arm (0.65 m from the shoulder)
    std::ifstream in(test::sourcePath("problems/robots/dual_arm.urdf"));
    std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string joint3 = "<joint name=\"small_joint3\" type=\"revolute\">";
    const auto at = urdf.find(joint3);
    ASSERT_NE(at, std::string::npos);
    urdf.replace(at, joint3.size(), "<joint name=\"small_joint3\" type=\"prismatic\">");
    const std::string limits = "<limit lower=\"-2.09440\" upper=\"2.09440\"";
    const auto limitAt = urdf.find(limits, at);
    ASSERT_NE(limitAt, std::string::npos);
    urdf.replace(limitAt, limits.size(), "<limit lower=\"0\" upper=\"0.4\"");
    const auto prismatic = validity::RobotModel::fromUrdfString(urdf, "dual_arm_prismatic.urdf", ".");
    ASSERT_EQ(prismatic->variableJoint(static_cast<std::size_t>(prismatic->variableIndex("small_joint3"))).type,
              validity::RobotJoint::Type::PRISMATIC);
    expectReachSphereHolds(ArmChain(prismatic, "small_tip"), "small arm, prismatic joint 3");
    expectReachSphereHolds(ArmChain(prismatic, "small_link6", Eigen::Vector3d(0.05, 0.02, 0.1)),
                           "small arm, prismatic joint 3, tool point");
    expectReachSphereHolds(ArmChain(prismatic, "large_tip"), "large arm");

    // a prismatic first joint (a rail) carries everything after it: the centre cannot be its moving child frame
    const std::string rail = R"(<?xml version="1.0"?>
<robot name="rail_arm">
  <link name="base"/>
  <joint name="rail" type="prismatic">
    <parent link="base"/><child link="carriage"/><origin xyz="0.1 0 0"/><axis xyz="1 0 0"/>
    <limit lower="-0.5" upper="0.5" effort="10" velocity="1"/>
  </joint>
  <link name="carriage"/>
  <joint name="shoulder" type="revolute">
    <parent link="carriage"/><child link="upper"/><origin xyz="0 0 0.2"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="1"/>
  </joint>
  <link name="upper"/>
  <joint name="slide" type="prismatic">
    <parent link="upper"/><child link="fore"/><origin xyz="0.3 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-0.25" upper="0.1" effort="10" velocity="1"/>
  </joint>
  <link name="fore"/>
  <joint name="tip_joint" type="fixed">
    <parent link="fore"/><child link="tip"/><origin xyz="0 0 0.05"/>
  </joint>
  <link name="tip"/>
</robot>)";
    const auto railArm = validity::RobotModel::fromUrdfString(rail, "rail_arm.urdf", ".");
    expectReachSphereHolds(ArmChain(railArm, "tip"), "arm on a rail");
}
