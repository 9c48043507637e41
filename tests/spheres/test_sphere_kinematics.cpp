// The sphere checker's own forward kinematics (fixed transforms folded into the frames the group's joints move) gives
// the same link poses as RobotModel::forwardKinematics, and its sin/cos agree with the C library's.
#include "../../validity/src/spheres/SphereKinematics.h"

#include <michi/tools/bench/PlanningContext.h>

#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>

using namespace michi;
using namespace michi::validity;

TEST(SphereKinematics, SinCosAgreeWithTheCLibrary)
{
    double worst = 0.;
    // joint values of real robots, past a few turns either way, and the quadrant boundaries themselves
    for (double x = -20.; x <= 20.; x += 0.000731)
    {
        double s, c;
        fastSinCos(x, s, c);
        worst = std::max({worst, std::abs(s - std::sin(x)), std::abs(c - std::cos(x))});
    }
    for (int k = -12; k <= 12; ++k)
    {
        double s, c;
        const double x = k * M_PI / 4.;
        fastSinCos(x, s, c);
        worst = std::max({worst, std::abs(s - std::sin(x)), std::abs(c - std::cos(x))});
    }
    EXPECT_LT(worst, 4e-16);
}

// The float kernels the sphere checker's frames use: a float's rounding from the C library's over the joint values of
// real robots and the quadrant boundaries, and the right quadrant far out (more than 2^31 quarter turns), where a
// 32-bit quadrant count would wrap.
TEST(SphereKinematics, FloatSinCosAgreeWithTheCLibrary)
{
    std::vector<double> x;
    for (double v = -20.; v <= 20.; v += 0.000731)
        x.push_back(v);
    for (int k = -12; k <= 12; ++k)
        x.push_back(k * M_PI / 4.);
    std::vector<float> s(x.size()), c(x.size());
    fastSinCosFloat(x.data(), static_cast<int>(x.size()), s.data(), c.data());
    double worst = 0.;
    for (std::size_t i = 0; i < x.size(); ++i)
        worst = std::max({worst, std::abs(s[i] - std::sin(x[i])), std::abs(c[i] - std::cos(x[i]))});
    EXPECT_LT(worst, 2e-7);
    const double far[4] = {4.1e9, -4.1e9, 1e12 + 0.3, -7.3e11};
    float fs[4], fc[4];
    fastSinCosFloat(far, 4, fs, fc);
    for (int i = 0; i < 4; ++i)
    {
        EXPECT_NEAR(fs[i], std::sin(far[i]), 1e-3) << far[i];
        EXPECT_NEAR(fc[i], std::cos(far[i]), 1e-3) << far[i];
    }
}

class SphereKinematicsOf : public ::testing::TestWithParam<std::string>
{
};

namespace
{
    /** The pose of link \e l from the kinematics' float frames (what the sphere checker places its spheres with),
        its largest difference to \e pose (rotation entries and metres). The centres are floats: a few 1e-7 m on a
        metre-long arm is expected, far inside the 1e-5 m every sphere radius is grown by for rounding. */
    double poseError(const SphereKinematics &kinematics, const std::vector<FloatFrame> &frames, std::size_t l,
                     const Eigen::Isometry3d &pose)
    {
        const FloatFrame &f = frames[static_cast<std::size_t>(kinematics.frameOf(l))];
        Eigen::Matrix3d r;
        r.col(0) = f.c0.head<3>().cast<double>().matrix();
        r.col(1) = f.c1.head<3>().cast<double>().matrix();
        r.col(2) = f.c2.head<3>().cast<double>().matrix();
        const RigidFrame &o = kinematics.offsetOf(l);
        const double rotation = (r * o.r - pose.linear()).cwiseAbs().maxCoeff();
        const double translation =
            (r * o.t + f.t.head<3>().cast<double>().matrix() - pose.translation()).cwiseAbs().maxCoeff();
        return std::max(
            {rotation, translation, static_cast<double>(std::abs(f.c0(3))), static_cast<double>(std::abs(f.t(3)))});
    }
}  // namespace

TEST_P(SphereKinematicsOf, SameLinkPosesAsTheRobotModel)
{
    const auto problem = tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/" + GetParam() + ".yaml");
    const auto ctx = tools::makePlanningContext(problem);
    auto group = std::dynamic_pointer_cast<const RobotGroupBodies>(ctx.bodies);
    ASSERT_TRUE(group);
    const RobotModel &model = *group->model();
    std::vector<int> links;
    for (std::size_t l = 0; l < model.links().size(); ++l)
        links.push_back(static_cast<int>(l));
    const auto &vars = group->variables();
    ompl::RNG rng(11);
    // a template whose joints outside the group are not at zero, so that folding them in is tested too
    std::vector<double> values(vars.size(), 0.);
    const std::vector<double> fullTemplate = group->fullConfiguration(values.data());
    SphereKinematics kinematics(model, vars, fullTemplate, links);
    std::vector<FloatFrame> frames(kinematics.frameCount());
    std::vector<Eigen::Isometry3d> poses;
    for (int trial = 0; trial < 200; ++trial)
    {
        for (std::size_t i = 0; i < vars.size(); ++i)
        {
            const RobotJoint &joint = model.variableJoint(vars[i]);
            values[i] = joint.type == RobotJoint::Type::CONTINUOUS ? rng.uniformReal(-7., 7.)
                                                                   : rng.uniformReal(joint.lower, joint.upper);
        }
        kinematics.framesFloat(values.data(), frames.data());
        model.forwardKinematics(group->fullConfiguration(values.data()).data(), poses);
        for (std::size_t l = 0; l < links.size(); ++l)
            EXPECT_LT(poseError(kinematics, frames, l, poses[l]), 1e-6) << model.links()[l].name;
    }
}

// an arm with continuous joints (xarm6_ring), the Panda (axes +z, fixed hand and fingers), a 3-joint planar arm and
// the two-arm robot, whose group leaves one arm's joints at the template's values
INSTANTIATE_TEST_SUITE_P(Problems, SphereKinematicsOf,
                         ::testing::Values("panda_table_pick", "xarm6_ring", "arch_3dof", "dual_arm"));

// Axes other than +z (the Rodrigues rotation, -z, a tilted axis), a prismatic joint, a fixed joint between moving
// ones and a joint held outside the group: none of the bundled robots has them all.
TEST(SphereKinematics, GeneralAxesPrismaticAndHeldJoints)
{
    const std::string urdf = R"(<robot name="axes">
      <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/><link name="e"/><link name="f"/>
      <joint name="j1" type="revolute"><parent link="base"/><child link="a"/><axis xyz="1 0 0"/>
        <origin xyz="0.1 0.2 0.3" rpy="0.3 -0.2 0.9"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
      <joint name="j2" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 -1"/>
        <origin xyz="0 0.4 0" rpy="0 0.5 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
      <joint name="fx" type="fixed"><parent link="b"/><child link="c"/><origin xyz="0.2 0 0.1" rpy="1 0 0"/></joint>
      <joint name="j3" type="prismatic"><parent link="c"/><child link="d"/><axis xyz="0 1 0"/>
        <origin xyz="0 0 0.3"/><limit lower="-0.5" upper="0.5" effort="1" velocity="1"/></joint>
      <joint name="held" type="revolute"><parent link="d"/><child link="e"/><axis xyz="0 1 0"/>
        <origin xyz="0.1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
      <joint name="j4" type="continuous"><parent link="e"/><child link="f"/><axis xyz="0.48 0.6 0.64"/>
        <origin xyz="0 0.1 0.2" rpy="0.1 0.2 0.3"/></joint>
    </robot>)";
    const auto model = RobotModel::fromUrdfString(urdf, "axes.urdf", ".");
    std::vector<int> vars;  // every variable but the one of joint "held"
    for (std::size_t v = 0; v < model->variableCount(); ++v)
        if (model->variableJoint(v).name != "held")
            vars.push_back(static_cast<int>(v));
    ASSERT_EQ(vars.size(), 4u);
    std::vector<double> full(model->variableCount(), 0.);
    for (std::size_t v = 0; v < model->variableCount(); ++v)
        if (model->variableJoint(v).name == "held")
            full[v] = 0.7;
    std::vector<int> links;
    for (std::size_t l = 0; l < model->links().size(); ++l)
        links.push_back(static_cast<int>(l));
    SphereKinematics kinematics(*model, vars, full, links);
    EXPECT_EQ(kinematics.frameCount(), 5u);  // the base and one frame per group joint
    std::vector<FloatFrame> frames(kinematics.frameCount());
    std::vector<Eigen::Isometry3d> poses;
    ompl::RNG rng(3);
    for (int trial = 0; trial < 100; ++trial)
    {
        std::vector<double> values;
        for (int v : vars)
        {
            const RobotJoint &joint = model->variableJoint(v);
            values.push_back(joint.movable() && joint.type != RobotJoint::Type::CONTINUOUS
                                 ? rng.uniformReal(joint.lower, joint.upper)
                                 : rng.uniformReal(-7., 7.));
            full[v] = values.back();
        }
        kinematics.framesFloat(values.data(), frames.data());
        model->forwardKinematics(full.data(), poses);
        for (std::size_t l = 0; l < links.size(); ++l)
            EXPECT_LT(poseError(kinematics, frames, l, poses[l]), 1e-6) << model->links()[l].name;
    }
}
