// Tests of michi::validity::RobotModel: URDF loading (joint types, limits, shapes, meshes, errors), forward
// kinematics against hand-computed poses, the Jacobian against finite differences, self-collision pairs and
// displacement bounds.

#include "support/TestScenes.h"

#include <michi/validity/robot/RobotModel.h>

#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <set>
#include <sstream>

using namespace michi;
using validity::RobotJoint;
using validity::RobotModel;
using validity::Shape;

namespace
{
    /** A robot with every supported joint type and shape: base_link (box) -shoulder(revolute about y)- upper
        (cylinder) -weld(fixed)- bracket (sphere) -elbow(continuous about z, tilted origin)- wrist (STL mesh by a
        relative path) -extend(prismatic along x)- slider (box) -tool_joint(fixed)- tool (sphere). */
    const char *MIXED_URDF = R"(<?xml version="1.0"?>
<robot name="mixed">
  <link name="base_link">
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  <link name="upper">
    <collision><origin xyz="0 0 0.25"/><geometry><cylinder radius="0.05" length="0.5"/></geometry></collision>
  </link>
  <link name="bracket">
    <collision><geometry><sphere radius="0.06"/></geometry></collision>
  </link>
  <link name="wrist">
    <collision><origin xyz="0.1 0 0"/><geometry><mesh filename="meshes/cube.stl" scale="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <link name="slider">
    <collision><geometry><box size="0.05 0.05 0.2"/></geometry></collision>
  </link>
  <link name="tool">
    <collision><geometry><sphere radius="0.02"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="upper"/>
    <origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="2.0" effort="1" velocity="1"/>
  </joint>
  <joint name="weld" type="fixed">
    <parent link="upper"/><child link="bracket"/><origin xyz="0 0 0.5"/>
  </joint>
  <joint name="elbow" type="continuous">
    <parent link="bracket"/><child link="wrist"/>
    <origin xyz="0 0 0.06" rpy="0.3 0 0"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="extend" type="prismatic">
    <parent link="wrist"/><child link="slider"/>
    <origin xyz="0.2 0 0"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.3" effort="1" velocity="1"/>
  </joint>
  <joint name="tool_joint" type="fixed">
    <parent link="slider"/><child link="tool"/><origin xyz="0 0 0.1"/>
  </joint>
</robot>
)";

    /** The mixed robot written to a fresh temporary directory with its mesh (a unit cube, ASCII STL). */
    struct MixedRobotFiles
    {
        test::TempDir dir{"michi_robot_model"};
        std::string urdf;
        MixedRobotFiles()
        {
            dir.write("meshes/cube.stl", test::asciiStlBox(Eigen::Vector3d::Ones()));
            urdf = dir.write("robot.urdf", MIXED_URDF);
        }
    };

    Eigen::Isometry3d translation(double x, double y, double z)
    {
        return Eigen::Isometry3d(Eigen::Translation3d(x, y, z));
    }

    Eigen::Isometry3d rotation(double angle, const Eigen::Vector3d &axis)
    {
        return Eigen::Isometry3d(Eigen::AngleAxisd(angle, axis));
    }

    void expectPoseNear(const Eigen::Isometry3d &expected, const Eigen::Isometry3d &actual, double tol,
                        const std::string &what)
    {
        EXPECT_TRUE(expected.matrix().isApprox(actual.matrix(), tol) ||
                    (expected.matrix() - actual.matrix()).cwiseAbs().maxCoeff() < tol)
            << what << "\nexpected\n"
            << expected.matrix() << "\nactual\n"
            << actual.matrix();
    }

    /** The geometric Jacobian of a point on a link equals the central finite difference of forward kinematics:
        linear part d(p)/dq, angular part the rotation vector of R(q + h) R(q - h)^T / 2h. */
    void expectJacobianMatchesFiniteDifferences(const RobotModel &model, const std::vector<double> &q, int link,
                                                const Eigen::Vector3d &point, double tol = 1e-6)
    {
        const Eigen::MatrixXd jac = model.jacobian(q, link, point);
        ASSERT_EQ(jac.rows(), 6);
        ASSERT_EQ(jac.cols(), static_cast<long>(model.variableCount()));
        const double h = 1e-6;
        for (std::size_t v = 0; v < model.variableCount(); ++v)
        {
            std::vector<double> plus = q, minus = q;
            plus[v] += h;
            minus[v] -= h;
            const Eigen::Isometry3d tp = model.forwardKinematics(plus)[link];
            const Eigen::Isometry3d tm = model.forwardKinematics(minus)[link];
            const Eigen::Vector3d linear = (tp * point - tm * point) / (2. * h);
            const Eigen::AngleAxisd delta(Eigen::Matrix3d(tp.linear() * tm.linear().transpose()));
            const Eigen::Vector3d angular = delta.axis() * delta.angle() / (2. * h);
            for (int r = 0; r < 3; ++r)
            {
                EXPECT_NEAR(jac(r, static_cast<long>(v)), linear[r], tol)
                    << "linear row " << r << " variable " << v << " link " << model.links()[link].name;
                EXPECT_NEAR(jac(3 + r, static_cast<long>(v)), angular[r], tol)
                    << "angular row " << r << " variable " << v << " link " << model.links()[link].name;
            }
        }
    }

    std::set<std::pair<std::string, std::string>> pairNames(const RobotModel &model)
    {
        std::set<std::pair<std::string, std::string>> names;
        for (const auto &p : model.selfCollisionPairs())
        {
            std::string a = model.links()[p.first].name, b = model.links()[p.second].name;
            if (b < a)
                std::swap(a, b);
            names.insert({a, b});
        }
        return names;
    }

    // ---- xArm6 ----

    /** The xArm6 kinematic facts: joint origins in the parent frame (metres, roll in radians), all about z. */
    struct Xarm6Joint
    {
        double x, y, z, roll;
    };
    const Xarm6Joint XARM6_JOINTS[6] = {{0., 0., 0.267, 0.},       {0., 0., 0., -M_PI / 2},
                                        {0.0535, -0.2845, 0., 0.}, {0.0775, 0.3425, 0., -M_PI / 2},
                                        {0., 0., 0., M_PI / 2},    {0.076, 0.097, 0., -M_PI / 2}};

    /** The same arm as a URDF, with a thin cylinder on every link so the Jacobian of link points means something. */
    std::string xarm6Urdf()
    {
        std::ostringstream out;
        out << std::setprecision(17) << "<?xml version=\"1.0\"?>\n<robot name=\"xarm6\">\n";
        out << "  <link name=\"link_base\"><collision><origin xyz=\"0 0 0.1\"/><geometry><cylinder radius=\"0.06\" "
               "length=\"0.2\"/></geometry></collision></link>\n";
        const double lower[6] = {-2 * M_PI, -2.059, -3.927, -2 * M_PI, -1.69297, -2 * M_PI};
        const double upper[6] = {2 * M_PI, 2.0944, 0.19198, 2 * M_PI, M_PI, 2 * M_PI};
        for (int i = 0; i < 6; ++i)
        {
            const auto &j = XARM6_JOINTS[i];
            out << "  <link name=\"link" << i + 1 << "\"><collision><geometry><cylinder radius=\"0.04\" "
                << "length=\"0.1\"/></geometry></collision></link>\n";
            out << "  <joint name=\"joint" << i + 1 << "\" type=\"revolute\">\n"
                << "    <parent link=\"" << (i == 0 ? std::string("link_base") : "link" + std::to_string(i))
                << "\"/><child link=\"link" << i + 1 << "\"/>\n"
                << "    <origin xyz=\"" << j.x << " " << j.y << " " << j.z << "\" rpy=\"" << j.roll << " 0 0\"/>\n"
                << "    <axis xyz=\"0 0 1\"/>\n"
                << "    <limit lower=\"" << lower[i] << "\" upper=\"" << upper[i]
                << "\" effort=\"50\" velocity=\"3\"/>\n"
                << "  </joint>\n";
        }
        out << "</robot>\n";
        return out.str();
    }

    /** Poses of link1..link6 by a direct product of Eigen transforms built from XARM6_JOINTS. */
    std::vector<Eigen::Isometry3d> xarm6HandFk(const std::vector<double> &q)
    {
        std::vector<Eigen::Isometry3d> poses;
        Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
        for (int i = 0; i < 6; ++i)
        {
            const auto &j = XARM6_JOINTS[i];
            t = t * translation(j.x, j.y, j.z) * rotation(j.roll, Eigen::Vector3d::UnitX()) *
                rotation(q[i], Eigen::Vector3d::UnitZ());
            poses.push_back(t);
        }
        return poses;
    }

    const std::vector<std::vector<double>> XARM6_CONFIGURATIONS = {{0., 0., 0., 0., 0., 0.},
                                                                   {0.3, -0.5, -1.2, 0.7, 0.4, -2.1},
                                                                   {-1.9, 1.1, -0.2, -2.5, 1.6, 0.9},
                                                                   {2.8, -1.7, -3.0, 3.1, -1.2, 5.5}};
}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// Loading

TEST(RobotModel, LoadsEveryJointTypeAndShapeFromFile)
{
    MixedRobotFiles files;
    const auto model = RobotModel::fromUrdfFile(files.urdf);
    EXPECT_EQ(model->name(), "mixed");
    EXPECT_EQ(model->source(), files.urdf);
    ASSERT_EQ(model->links().size(), 6u);
    ASSERT_EQ(model->joints().size(), 5u);
    ASSERT_EQ(model->variableCount(), 3u);
    EXPECT_EQ(model->variableNames(), (std::vector<std::string>{"shoulder", "elbow", "extend"}));

    const auto &shoulder = model->joints()[model->jointIndex("shoulder")];
    EXPECT_EQ(shoulder.type, RobotJoint::Type::REVOLUTE);
    EXPECT_DOUBLE_EQ(shoulder.lower, -1.5);
    EXPECT_DOUBLE_EQ(shoulder.upper, 2.0);
    EXPECT_TRUE(shoulder.axis.isApprox(Eigen::Vector3d::UnitY()));
    EXPECT_EQ(model->links()[shoulder.parentLink].name, "base_link");
    EXPECT_EQ(model->links()[shoulder.childLink].name, "upper");

    const auto &weld = model->joints()[model->jointIndex("weld")];
    EXPECT_EQ(weld.type, RobotJoint::Type::FIXED);
    EXPECT_FALSE(weld.movable());
    EXPECT_EQ(weld.variable, -1);

    const auto &elbow = model->joints()[model->jointIndex("elbow")];
    EXPECT_EQ(elbow.type, RobotJoint::Type::CONTINUOUS);
    EXPECT_DOUBLE_EQ(elbow.lower, -M_PI);
    EXPECT_DOUBLE_EQ(elbow.upper, M_PI);

    const auto &extend = model->joints()[model->jointIndex("extend")];
    EXPECT_EQ(extend.type, RobotJoint::Type::PRISMATIC);
    EXPECT_DOUBLE_EQ(extend.lower, 0.);
    EXPECT_DOUBLE_EQ(extend.upper, 0.3);
    EXPECT_TRUE(extend.axis.isApprox(Eigen::Vector3d::UnitX()));

    EXPECT_EQ(model->variableIndex("shoulder"), 0);
    EXPECT_EQ(model->variableIndex("elbow"), 1);
    EXPECT_EQ(model->variableIndex("extend"), 2);
    EXPECT_EQ(model->variableJoint(2).name, "extend");

    // shapes
    const auto &base = model->links()[model->linkIndex("base_link")];
    ASSERT_EQ(base.collisions.size(), 1u);
    EXPECT_EQ(base.collisions[0].shape->type(), Shape::Type::BOX);
    EXPECT_TRUE(base.collisions[0].shape->size().isApprox(Eigen::Vector3d(0.4, 0.3, 0.1)));

    const auto &upper = model->links()[model->linkIndex("upper")];
    ASSERT_EQ(upper.collisions.size(), 1u);
    EXPECT_EQ(upper.collisions[0].shape->type(), Shape::Type::CYLINDER);
    EXPECT_DOUBLE_EQ(upper.collisions[0].shape->size().x(), 0.05);
    EXPECT_DOUBLE_EQ(upper.collisions[0].shape->size().z(), 0.5);
    EXPECT_TRUE(upper.collisions[0].origin.translation().isApprox(Eigen::Vector3d(0, 0, 0.25)));

    const auto &bracket = model->links()[model->linkIndex("bracket")];
    ASSERT_EQ(bracket.collisions.size(), 1u);
    EXPECT_EQ(bracket.collisions[0].shape->type(), Shape::Type::SPHERE);
    EXPECT_DOUBLE_EQ(bracket.collisions[0].shape->size().x(), 0.06);

    const auto &wrist = model->links()[model->linkIndex("wrist")];
    ASSERT_EQ(wrist.collisions.size(), 1u);
    const auto &mesh = *wrist.collisions[0].shape;
    EXPECT_EQ(mesh.type(), Shape::Type::MESH);
    EXPECT_EQ(mesh.triangles().size(), 12u);
    EXPECT_GE(mesh.vertices().size(), 8u);
    for (const auto &v : mesh.vertices())
        EXPECT_NEAR(v.cwiseAbs().maxCoeff(), 0.05, 1e-12) << "the unit cube is scaled by 0.1";
    EXPECT_EQ(std::filesystem::path(mesh.source()).filename(), "cube.stl");

    EXPECT_TRUE(model->links()[model->linkIndex("tool")].collisions.size() == 1u);
}

TEST(RobotModel, LoadsFromStringWithBaseDirectoryForMeshes)
{
    MixedRobotFiles files;
    const auto model = RobotModel::fromUrdfString(MIXED_URDF, "inline-mixed", files.dir.path());
    EXPECT_EQ(model->source(), "inline-mixed");
    EXPECT_EQ(model->links()[model->linkIndex("wrist")].collisions.at(0).shape->type(), Shape::Type::MESH);
}

TEST(RobotModel, UnknownNamesThrow)
{
    MixedRobotFiles files;
    auto model = RobotModel::fromUrdfFile(files.urdf);
    EXPECT_THROW(model->linkIndex("no_such_link"), std::out_of_range);
    EXPECT_THROW(model->jointIndex("no_such_joint"), std::out_of_range);
    EXPECT_THROW(model->variableIndex("no_such_joint"), std::out_of_range);
    EXPECT_THROW(model->variableIndex("weld"), std::out_of_range);  // fixed joints have no value
    EXPECT_THROW(model->allowCollision("no_such_link", "upper"), std::out_of_range);
    EXPECT_THROW(model->allowCollision("upper", "no_such_link"), std::out_of_range);
    try
    {
        model->linkIndex("no_such_link");
    }
    catch (const std::out_of_range &e)
    {
        EXPECT_NE(std::string(e.what()).find("no_such_link"), std::string::npos) << e.what();
    }
    EXPECT_THROW(model->forwardKinematics(std::vector<double>{0., 0.}), std::invalid_argument);
}

namespace
{
    /** Load \e xml as a file in a temporary directory and expect a UrdfError whose message names the file and
        contains \e fragment. */
    void expectUrdfError(const std::string &xml, const std::string &fragment)
    {
        test::TempDir dir("michi_bad_urdf");
        const std::string path = dir.write("broken_robot.urdf", xml);
        try
        {
            RobotModel::fromUrdfFile(path);
            ADD_FAILURE() << "no exception for a URDF that should fail with '" << fragment << "'";
        }
        catch (const validity::UrdfError &e)
        {
            const std::string what = e.what();
            EXPECT_NE(what.find(path), std::string::npos) << "message does not name the file: " << what;
            EXPECT_NE(what.find(fragment), std::string::npos) << "message: " << what;
        }
        catch (const std::exception &e)
        {
            ADD_FAILURE() << "expected validity::UrdfError, got: " << e.what();
        }
    }
}  // namespace

TEST(RobotModel, MalformedUrdfThrowsUrdfErrorNamingTheFile)
{
    expectUrdfError(R"(<robot name="r"><link name="a"/><link name="b"/>
        <joint name="j" type="fixed"><parent link="a"/></joint></robot>)",
                    "");
    expectUrdfError(R"(<robot name="r"><link name="a"/><link name="b"/>
        <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint></robot>)",
                    "");
    expectUrdfError(R"(<robot name="r"><link name="a"><collision><geometry>
        <mesh filename="meshes/missing.stl"/></geometry></collision></link></robot>)",
                    "missing.stl");
    expectUrdfError("this is not XML at all { ]", "");
    expectUrdfError("", "");

    // a file that does not exist
    const std::string missing = (std::filesystem::temp_directory_path() / "michi_no_such_dir/robot.urdf").string();
    try
    {
        RobotModel::fromUrdfFile(missing);
        ADD_FAILURE() << "no exception for a missing file";
    }
    catch (const validity::UrdfError &e)
    {
        EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
    }
}

TEST(RobotModel, UnreadableMeshThrowsUrdfErrorNamingTheUrdf)
{
    test::TempDir dir("michi_bad_mesh");
    dir.write("meshes/garbage.stl", "solid nothing\nthis is not an STL\n");
    const std::string path = dir.write("robot.urdf", R"(<robot name="r"><link name="a"><collision><geometry>
        <mesh filename="meshes/garbage.stl"/></geometry></collision></link></robot>)");
    try
    {
        RobotModel::fromUrdfFile(path);
        ADD_FAILURE() << "no exception for an unreadable mesh";
    }
    catch (const validity::UrdfError &e)
    {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("garbage.stl"), std::string::npos) << e.what();
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Forward kinematics

TEST(RobotModel, PlanarArmForwardKinematicsMatchesCosSinSums)
{
    for (const std::vector<double> &lengths : {std::vector<double>{0.5, 0.3}, std::vector<double>{0.4, 0.3, 0.2}})
    {
        const auto model = test::planarArmModel(lengths);
        ASSERT_EQ(model->variableCount(), lengths.size());
        const std::vector<std::vector<double>> configurations = {
            {0., 0., 0.}, {M_PI / 2, -M_PI / 2, M_PI / 4}, {0.3, 1.2, -2.5}, {-2.9, 3.0, 0.1}, {1., 1., 1.}};
        for (auto q : configurations)
        {
            q.resize(lengths.size());
            const auto poses = model->forwardKinematics(q);
            const auto points = test::planarArmPoints(lengths, q);
            double angle = 0.;
            for (std::size_t i = 0; i < lengths.size(); ++i)
            {
                angle += q[i];
                const auto &pose = poses[model->linkIndex("link" + std::to_string(i + 1))];
                EXPECT_NEAR(pose.translation().x(), points[i].x(), 1e-12);
                EXPECT_NEAR(pose.translation().y(), points[i].y(), 1e-12);
                EXPECT_NEAR(pose.translation().z(), 0., 1e-12);
                const Eigen::Matrix3d expected = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
                EXPECT_TRUE(pose.linear().isApprox(expected, 1e-12)) << pose.linear();
                // the far end of the link is the next point
                const Eigen::Vector3d end = pose * Eigen::Vector3d(lengths[i], 0., 0.);
                EXPECT_NEAR(end.x(), points[i + 1].x(), 1e-12);
                EXPECT_NEAR(end.y(), points[i + 1].y(), 1e-12);
            }
        }
    }
}

TEST(RobotModel, BasePoseMovesEveryLink)
{
    const std::vector<double> lengths{0.5, 0.3};
    auto model = test::planarArmModel(lengths);
    const std::vector<double> q{0.4, -0.9};
    const auto before = model->forwardKinematics(q);
    const Eigen::Isometry3d base = translation(1., -2., 0.5) * rotation(0.7, Eigen::Vector3d(1, 2, 3).normalized());
    model->setBasePose(base);
    const auto after = model->forwardKinematics(q);
    for (std::size_t l = 0; l < before.size(); ++l)
        expectPoseNear(base * before[l], after[l], 1e-12, model->links()[l].name);
}

TEST(RobotModel, MixedRobotForwardKinematicsMatchesProductOfTransforms)
{
    MixedRobotFiles files;
    const auto model = RobotModel::fromUrdfFile(files.urdf);
    for (const std::vector<double> &q :
         {std::vector<double>{0., 0., 0.}, std::vector<double>{0.7, -2.2, 0.25}, std::vector<double>{-1.4, 3., 0.1}})
    {
        const Eigen::Isometry3d upper = translation(0, 0, 0.05) * rotation(q[0], Eigen::Vector3d::UnitY());
        const Eigen::Isometry3d bracket = upper * translation(0, 0, 0.5);
        const Eigen::Isometry3d wrist = bracket * translation(0, 0, 0.06) * rotation(0.3, Eigen::Vector3d::UnitX()) *
                                        rotation(q[1], Eigen::Vector3d::UnitZ());
        const Eigen::Isometry3d slider = wrist * translation(0.2 + q[2], 0, 0);
        const Eigen::Isometry3d tool = slider * translation(0, 0, 0.1);
        const auto poses = model->forwardKinematics(q);
        expectPoseNear(Eigen::Isometry3d::Identity(), poses[model->linkIndex("base_link")], 1e-12, "base_link");
        expectPoseNear(upper, poses[model->linkIndex("upper")], 1e-12, "upper");
        expectPoseNear(bracket, poses[model->linkIndex("bracket")], 1e-12, "bracket");
        expectPoseNear(wrist, poses[model->linkIndex("wrist")], 1e-12, "wrist");
        expectPoseNear(slider, poses[model->linkIndex("slider")], 1e-12, "slider");
        expectPoseNear(tool, poses[model->linkIndex("tool")], 1e-12, "tool");
    }
}

TEST(RobotModel, RevoluteAxesOfEverySignAndAGeneralAxisMatchTheRotationAboutThem)
{
    // forwardKinematics turns about a coordinate axis by mixing two columns, and about any other axis by the general
    // rotation: both must give the product of transforms
    const std::vector<Eigen::Vector3d> axes{-Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitY(),
                                            -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                                            Eigen::Vector3d(0.6, 0., 0.8)};
    std::ostringstream urdf;
    urdf << "<robot name=\"axes\"><link name=\"l0\"/>";
    for (std::size_t j = 0; j < axes.size(); ++j)
        urdf << "<link name=\"l" << j + 1 << "\"/><joint name=\"j" << j << "\" type=\"revolute\"><parent link=\"l" << j
             << "\"/><child link=\"l" << j + 1 << "\"/><origin xyz=\"0.1 0.02 0.3\" rpy=\"0.2 -0.1 0.4\"/><axis xyz=\""
             << axes[j].x() << " " << axes[j].y() << " " << axes[j].z()
             << "\"/><limit lower=\"-3\" upper=\"3\" effort=\"1\" velocity=\"1\"/></joint>";
    urdf << "</robot>";
    const auto model = RobotModel::fromUrdfString(urdf.str(), "axes", ".");
    const Eigen::Isometry3d origin = translation(0.1, 0.02, 0.3) * rotation(0.4, Eigen::Vector3d::UnitZ()) *
                                     rotation(-0.1, Eigen::Vector3d::UnitY()) * rotation(0.2, Eigen::Vector3d::UnitX());
    for (const std::vector<double> &q :
         {std::vector<double>{0.3, -1.2, 2.5, -2.9, 0.7}, std::vector<double>{-0.4, 0.9, -1.7, 1.1, -2.2}})
    {
        const auto poses = model->forwardKinematics(q);
        Eigen::Isometry3d expected = Eigen::Isometry3d::Identity();
        for (std::size_t j = 0; j < axes.size(); ++j)
        {
            expected = expected * origin * rotation(q[j], axes[j]);
            expectPoseNear(expected, poses[model->linkIndex("l" + std::to_string(j + 1))], 1e-12,
                           "link " + std::to_string(j + 1));
        }
    }
}

TEST(RobotModel, Xarm6ForwardKinematicsMatchesProductOfTransforms)
{
    const auto model = RobotModel::fromUrdfString(xarm6Urdf(), "<xarm6 test urdf>", ".");
    ASSERT_EQ(model->variableCount(), 6u);
    for (const auto &q : XARM6_CONFIGURATIONS)
    {
        const auto poses = model->forwardKinematics(q);
        const auto expected = xarm6HandFk(q);
        for (int i = 0; i < 6; ++i)
            expectPoseNear(expected[i], poses[model->linkIndex("link" + std::to_string(i + 1))], 1e-12,
                           "link" + std::to_string(i + 1));
    }
    // the zero configuration by hand: the flange sits at x = 0.0535 + 0.0775 + 0.076 = 0.207 and
    // z = 0.267 + 0.2845 - 0.3425 - 0.097 = 0.112, pointing down
    const auto zero = model->forwardKinematics(XARM6_CONFIGURATIONS[0]);
    const auto &flange = zero[model->linkIndex("link6")];
    EXPECT_NEAR(flange.translation().x(), 0.207, 1e-12);
    EXPECT_NEAR(flange.translation().y(), 0., 1e-12);
    EXPECT_NEAR(flange.translation().z(), 0.112, 1e-12);
    EXPECT_NEAR(flange.linear().col(2).z(), -1., 1e-12);
}

TEST(RobotModel, Xarm6UrdfFileGivesTheSameForwardKinematics)
{
    const std::string path = test::sourcePath("problems/robots/xarm6.urdf");
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << path << " does not exist yet";
    const auto model = RobotModel::fromUrdfFile(path);
    ASSERT_GE(model->variableCount(), 6u);
    const int first = model->variableJoint(0).parentLink;  // the frame joint 1 is placed in
    for (const auto &arm : XARM6_CONFIGURATIONS)
    {
        std::vector<double> q(model->variableCount(), 0.);
        std::copy(arm.begin(), arm.end(), q.begin());
        const auto poses = model->forwardKinematics(q);
        const auto expected = xarm6HandFk(arm);
        for (int i = 0; i < 6; ++i)
        {
            const auto &joint = model->variableJoint(i);
            // URDF files write pi/2 with 7 or 8 decimals (an error of about 3e-8 rad): compare to 1e-6
            expectPoseNear(expected[i], poses[first].inverse() * poses[joint.childLink], 1e-6,
                           path + ": child of " + joint.name);
        }
        // and its Jacobian is consistent with its own forward kinematics
        expectJacobianMatchesFiniteDifferences(*model, q, model->variableJoint(5).childLink,
                                               Eigen::Vector3d(0.01, 0.02, 0.07));
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Jacobian

TEST(RobotModel, PlanarArmJacobianMatchesFiniteDifferences)
{
    for (const std::vector<double> &lengths : {std::vector<double>{0.5, 0.3}, std::vector<double>{0.4, 0.3, 0.2}})
    {
        const auto model = test::planarArmModel(lengths);
        const std::vector<std::vector<double>> configurations = {{0., 0., 0.}, {0.3, 1.2, -2.5}, {-2.9, 3.0, 0.1}};
        for (auto q : configurations)
        {
            q.resize(lengths.size());
            for (std::size_t i = 0; i < lengths.size(); ++i)
            {
                const int link = model->linkIndex("link" + std::to_string(i + 1));
                expectJacobianMatchesFiniteDifferences(*model, q, link, Eigen::Vector3d::Zero());
                expectJacobianMatchesFiniteDifferences(*model, q, link, Eigen::Vector3d(lengths[i], 0., 0.));
            }
            // the tip of a planar arm by hand: d tip / d q_j = z x (tip - joint_j)
            const auto points = test::planarArmPoints(lengths, q);
            const int last = model->linkIndex("link" + std::to_string(lengths.size()));
            const Eigen::MatrixXd jac = model->jacobian(q, last, Eigen::Vector3d(lengths.back(), 0., 0.));
            for (std::size_t j = 0; j < lengths.size(); ++j)
            {
                const Eigen::Vector2d r = points.back() - points[j];
                EXPECT_NEAR(jac(0, static_cast<long>(j)), -r.y(), 1e-12);
                EXPECT_NEAR(jac(1, static_cast<long>(j)), r.x(), 1e-12);
                EXPECT_NEAR(jac(2, static_cast<long>(j)), 0., 1e-12);
                EXPECT_NEAR(jac(5, static_cast<long>(j)), 1., 1e-12);
            }
        }
    }
}

TEST(RobotModel, Xarm6JacobianMatchesFiniteDifferences)
{
    const auto model = RobotModel::fromUrdfString(xarm6Urdf(), "<xarm6 test urdf>", ".");
    for (const auto &q : XARM6_CONFIGURATIONS)
        for (int i = 1; i <= 6; ++i)
        {
            const int link = model->linkIndex("link" + std::to_string(i));
            expectJacobianMatchesFiniteDifferences(*model, q, link, Eigen::Vector3d::Zero());
            expectJacobianMatchesFiniteDifferences(*model, q, link, Eigen::Vector3d(0.05, -0.08, 0.12));
        }
}

TEST(RobotModel, PrismaticAndOffsetPointJacobianMatchesFiniteDifferences)
{
    MixedRobotFiles files;
    auto model = RobotModel::fromUrdfFile(files.urdf);
    model->setBasePose(translation(0.3, -0.2, 0.1) * rotation(0.5, Eigen::Vector3d(1, -1, 2).normalized()));
    for (const std::vector<double> &q :
         {std::vector<double>{0., 0., 0.}, std::vector<double>{0.7, -2.2, 0.25}, std::vector<double>{-1.4, 3., 0.1}})
        for (const char *link : {"upper", "bracket", "wrist", "slider", "tool"})
            for (const Eigen::Vector3d &point :
                 {Eigen::Vector3d(0., 0., 0.), Eigen::Vector3d(0.03, -0.02, 0.05), Eigen::Vector3d(-0.3, 0.2, 0.4)})
                expectJacobianMatchesFiniteDifferences(*model, q, model->linkIndex(link), point);

    // the prismatic column of any point below the joint is the joint axis in the world, without rotation
    const std::vector<double> q{0.7, -2.2, 0.25};
    const auto poses = model->forwardKinematics(q);
    const Eigen::MatrixXd jac = model->jacobian(q, model->linkIndex("tool"), Eigen::Vector3d(0.1, 0.2, 0.3));
    const Eigen::Vector3d axis = poses[model->linkIndex("wrist")].linear() * Eigen::Vector3d::UnitX();
    EXPECT_TRUE(jac.col(2).head(3).isApprox(axis, 1e-12));
    EXPECT_TRUE(jac.col(2).tail(3).isZero(1e-12));
    // joints that are not between the root and the link give zero columns
    const Eigen::MatrixXd upperJac = model->jacobian(q, model->linkIndex("upper"));
    EXPECT_TRUE(upperJac.rightCols(2).isZero(0.));
}

// ---------------------------------------------------------------------------------------------------------------
// Self-collision pairs

TEST(RobotModel, SelfCollisionPairsExcludeAdjacentAndWeldedLinks)
{
    MixedRobotFiles files;
    auto model = RobotModel::fromUrdfFile(files.urdf);
    // welded groups: {upper, bracket} and {slider, tool}; adjacent groups: base-{upper, bracket}-wrist-{slider,
    // tool}. What is left: links two or more movable joints apart.
    const std::set<std::pair<std::string, std::string>> expected = {
        {"base_link", "wrist"}, {"base_link", "slider"}, {"slider", "upper"}, {"bracket", "slider"},
        {"base_link", "tool"},  {"tool", "upper"},       {"bracket", "tool"}};
    EXPECT_EQ(pairNames(*model), expected);
    for (const auto &p : model->selfCollisionPairs())
        EXPECT_LT(p.first, p.second);

    EXPECT_FALSE(model->isCollisionAllowed(model->linkIndex("upper"), model->linkIndex("slider")));
    model->allowCollision("slider", "upper");
    EXPECT_TRUE(model->isCollisionAllowed(model->linkIndex("upper"), model->linkIndex("slider")));
    EXPECT_TRUE(model->isCollisionAllowed(model->linkIndex("slider"), model->linkIndex("upper")));
    auto reduced = expected;
    reduced.erase({"slider", "upper"});
    EXPECT_EQ(pairNames(*model), reduced);
}

TEST(RobotModel, PlanarArmSelfCollisionPairsSkipNeighbours)
{
    auto model = test::planarArmModel({0.3, 0.3, 0.3, 0.3});
    // base_link has no geometry; link i and link i+1 are adjacent
    const std::set<std::pair<std::string, std::string>> expected = {
        {"link1", "link3"}, {"link1", "link4"}, {"link2", "link4"}};
    EXPECT_EQ(pairNames(*model), expected);
    model->allowCollision("link1", "link4");
    EXPECT_EQ(pairNames(*model),
              (std::set<std::pair<std::string, std::string>>{{"link1", "link3"}, {"link2", "link4"}}));
}

// ---------------------------------------------------------------------------------------------------------------
// Displacement bounds

namespace
{
    /** Points that bound every collision shape of every link: the six extreme points of each shape's bounding
        sphere, in link frames. */
    std::vector<std::pair<int, Eigen::Vector3d>> boundingPoints(const RobotModel &model)
    {
        std::vector<std::pair<int, Eigen::Vector3d>> points;
        for (std::size_t l = 0; l < model.links().size(); ++l)
            for (const auto &c : model.links()[l].collisions)
                for (int axis = 0; axis < 3; ++axis)
                    for (double sign : {-1., 1.})
                        points.emplace_back(static_cast<int>(l), c.origin * (sign * c.shape->boundingRadius() *
                                                                             Eigen::Vector3d::Unit(axis)));
        return points;
    }

    /** No point of the robot moves further between the end configurations than the sum of per-joint bounds. */
    void expectDisplacementBounded(const RobotModel &model, const std::vector<double> &from,
                                   const std::vector<double> &to)
    {
        double bound = 0.;
        for (std::size_t v = 0; v < model.variableCount(); ++v)
        {
            double dq = std::abs(to[v] - from[v]);
            if (model.variableJoint(v).type == RobotJoint::Type::CONTINUOUS)
                dq = std::min(dq, 2. * M_PI - dq);
            bound += model.displacementBound(v) * dq;
        }
        // walk the straight joint-space line finely: the path length of every point is bounded too
        const int steps = 200;
        std::vector<double> q(from.size());
        std::vector<Eigen::Isometry3d> previous = model.forwardKinematics(from), current;
        const auto points = boundingPoints(model);
        std::vector<double> travelled(points.size(), 0.);
        for (int s = 1; s <= steps; ++s)
        {
            for (std::size_t v = 0; v < q.size(); ++v)
                q[v] = from[v] + (to[v] - from[v]) * s / steps;
            current = model.forwardKinematics(q);
            for (std::size_t i = 0; i < points.size(); ++i)
            {
                const auto &[link, p] = points[i];
                travelled[i] += (current[link] * p - previous[link] * p).norm();
            }
            previous = current;
        }
        for (std::size_t i = 0; i < points.size(); ++i)
            EXPECT_LE(travelled[i], bound + 1e-12) << "a point of link " << model.links()[points[i].first].name
                                                   << " travels " << travelled[i] << " > bound " << bound;
    }
}  // namespace

TEST(RobotModel, DisplacementBoundsContainTheMotionOfEveryPoint)
{
    MixedRobotFiles files;
    const auto mixed = RobotModel::fromUrdfFile(files.urdf);
    const auto arm = test::planarArmModel({0.4, 0.3, 0.2});
    const auto xarm = RobotModel::fromUrdfString(xarm6Urdf(), "<xarm6 test urdf>", ".");

    // planar arm by hand: joint i moves the links after it, whose far end is at most sum(lengths[i..]) away
    // (plus the link radius)
    EXPECT_GE(arm->displacementBound(0), 0.9);
    EXPECT_GE(arm->displacementBound(1), 0.5);
    EXPECT_GE(arm->displacementBound(2), 0.2);
    EXPECT_DOUBLE_EQ(mixed->displacementBound(2), 1.);  // prismatic: metres per metre

    // a revolute joint above an extended prismatic joint
    expectDisplacementBounded(*mixed, {0., 0., 0.3}, {0.1, 0., 0.3});
    expectDisplacementBounded(*mixed, {-1.5, 0., 0.3}, {2.0, 0., 0.3});

    ompl::RNG rng(42);
    for (int trial = 0; trial < 50; ++trial)
    {
        for (const RobotModel *model : {mixed.get(), arm.get(), xarm.get()})
        {
            std::vector<double> from, to;
            for (std::size_t v = 0; v < model->variableCount(); ++v)
            {
                const auto &joint = model->variableJoint(v);
                from.push_back(rng.uniformReal(joint.lower, joint.upper));
                if (joint.type == RobotJoint::Type::CONTINUOUS)
                {
                    // less than half a turn, so the straight line is also the short way round
                    to.push_back(from.back() + rng.uniformReal(-3., 3.));
                    continue;
                }
                // short motions, where the bound is tight enough to matter, and long ones
                const double span = trial % 2 == 0 ? 0.05 * (joint.upper - joint.lower) : joint.upper - joint.lower;
                to.push_back(std::clamp(from.back() + rng.uniformReal(-span, span), joint.lower, joint.upper));
            }
            expectDisplacementBounded(*model, from, to);
        }
    }
}

namespace
{
    /** A gripper: a palm and two fingers on prismatic joints, the right one following the left (URDF <mimic>) with
        \e mimic's attribute text. */
    std::string gripperUrdf(const std::string &mimic)
    {
        return R"(<robot name="gripper"><link name="palm"/>
  <link name="left"><collision><geometry><box size="0.01 0.02 0.05"/></geometry></collision></link>
  <link name="right"><collision><geometry><box size="0.01 0.02 0.05"/></geometry></collision></link>
  <joint name="left_joint" type="prismatic"><parent link="palm"/><child link="left"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
  <joint name="right_joint" type="prismatic"><parent link="palm"/><child link="right"/><axis xyz="0 -1 0"/>
    <limit lower="-0.01" upper="0.04" effort="1" velocity="1"/>)" +
               mimic + R"(</joint></robot>)";
    }
}  // namespace

TEST(RobotModel, MimicJointFollowsTheJointItNames)
{
    const auto model = RobotModel::fromUrdfString(
        gripperUrdf(R"(<mimic joint="left_joint" multiplier="0.5" offset="-0.01"/>)"), "gripper", ".");
    const RobotJoint &right = model->joints()[model->jointIndex("right_joint")];
    ASSERT_EQ(right.mimic, model->jointIndex("left_joint"));
    EXPECT_DOUBLE_EQ(right.mimicMultiplier, 0.5);
    EXPECT_DOUBLE_EQ(right.mimicOffset, -0.01);
    // whatever the configuration held for the mimic joint, it becomes 0.5 * left - 0.01
    std::vector<double> q{0.04, 0.03};
    model->applyMimic(q);
    EXPECT_DOUBLE_EQ(q[0], 0.04);
    EXPECT_DOUBLE_EQ(q[1], 0.01);
    EXPECT_NEAR(model->forwardKinematics(q)[model->linkIndex("right")].translation().y(), -0.01, 1e-15);
    // a joint without <mimic> follows nothing
    EXPECT_EQ(model->joints()[model->jointIndex("left_joint")].mimic, -1);
}

TEST(RobotModel, MimicOfAnUnknownFixedOrMimicJointIsAUrdfErrorNamingIt)
{
    auto expectError = [](const std::string &urdf, const std::string &part)
    {
        try
        {
            RobotModel::fromUrdfString(urdf, "gripper.urdf", ".");
            ADD_FAILURE() << "accepted: " << part;
        }
        catch (const validity::UrdfError &e)
        {
            EXPECT_NE(std::string(e.what()).find("gripper.urdf"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    // before, the right finger stayed wherever its own value put it, not where the real gripper holds it
    expectError(gripperUrdf(R"(<mimic joint="nosuch"/>)"), "names no joint");
    expectError(gripperUrdf(R"(<mimic joint="right_joint"/>)"), "another movable joint");
    expectError(gripperUrdf(R"(<mimic joint="left_joint" multiplier="1e300"/>)"), "multiplier or offset");
    std::string chain = gripperUrdf(R"(<mimic joint="left_joint"/>)");
    chain.insert(chain.find("</robot>"), R"(<link name="tip"/><joint name="tip_joint" type="prismatic">
      <parent link="right"/><child link="tip"/><axis xyz="0 0 1"/><limit lower="0" upper="0.01" effort="1" velocity="1"/>
      <mimic joint="right_joint"/></joint>)");
    expectError(chain, "itself a mimic joint");
    // on a fixed joint (the bundled Panda's fingers) <mimic> means nothing and is left alone
    std::string fixed = gripperUrdf(R"(<mimic joint="nosuch"/>)");
    fixed.replace(fixed.find(R"(name="right_joint" type="prismatic")"), 35, R"(name="right_joint" type="fixed")");
    EXPECT_NO_THROW(RobotModel::fromUrdfString(fixed, "gripper.urdf", "."));
}
