#include <michi/tools/pictures/SvgPlot.h>

#include <michi/validity/robot/RobotModel.h>
#include <michi/validity/scene/Scene.h>
#include <michi/validity/scene/Shape.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;
using michi::tools::PlotPath;
using michi::tools::Problem;
using michi::tools::writeProblemSvg;
using michi::validity::Obstacle;
using michi::validity::Shape;

namespace
{
    // two links turning about z (1 m and 0.8 m), a tool frame at the end of the second
    const char *PLANAR_2LINK_URDF = R"(<?xml version="1.0"?>
<robot name="planar_2link">
  <link name="base_link">
    <collision><geometry><cylinder radius="0.08" length="0.05"/></geometry></collision>
  </link>
  <link name="link1">
    <collision><origin xyz="0.5 0 0"/><geometry><box size="1.0 0.1 0.05"/></geometry></collision>
  </link>
  <link name="link2">
    <collision><origin xyz="0.4 0 0"/><geometry><box size="0.8 0.08 0.05"/></geometry></collision>
  </link>
  <link name="tool"/>
  <joint name="joint1" type="revolute">
    <parent link="base_link"/><child link="link1"/><axis xyz="0 0 1"/>
    <limit lower="-3.14159" upper="3.14159" effort="1" velocity="1"/>
  </joint>
  <joint name="joint2" type="revolute">
    <parent link="link1"/><child link="link2"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-2.5" upper="2.5" effort="1" velocity="1"/>
  </joint>
  <joint name="tool_joint" type="fixed">
    <parent link="link2"/><child link="tool"/><origin xyz="0.8 0 0"/>
  </joint>
</robot>
)";

    // a column turning about z with two links pitching about y: leaves the x-y plane
    const char *SPATIAL_3LINK_URDF = R"(<?xml version="1.0"?>
<robot name="spatial_3link">
  <link name="base_link">
    <collision><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.06" length="0.3"/></geometry></collision>
  </link>
  <link name="shoulder"/>
  <link name="upper_arm">
    <collision><origin xyz="0.25 0 0" rpy="0 1.5708 0"/><geometry><cylinder radius="0.04" length="0.5"/></geometry></collision>
  </link>
  <link name="forearm">
    <collision><origin xyz="0.2 0 0"/><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="yaw" type="continuous">
    <parent link="base_link"/><child link="shoulder"/><origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="pitch1" type="revolute">
    <parent link="shoulder"/><child link="upper_arm"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
  <joint name="pitch2" type="revolute">
    <parent link="upper_arm"/><child link="forearm"/><origin xyz="0.5 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-2.5" upper="2.5" effort="1" velocity="1"/>
  </joint>
</robot>
)";

    Eigen::Isometry3d translation(double x, double y, double z)
    {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translation() = Eigen::Vector3d(x, y, z);
        return pose;
    }

    Problem armProblem(const std::string &name, const char *urdf)
    {
        Problem problem;
        problem.name = name;
        problem.kind = Problem::Kind::ARM;
        problem.model = michi::validity::RobotModel::fromUrdfString(urdf, name + ".urdf", ".");
        problem.group = "arm";
        for (std::size_t i = 0; i < problem.model->variableCount(); ++i)
            problem.groupVariables.push_back(static_cast<int>(i));
        problem.fixedValues.assign(problem.model->variableCount(), 0.);
        problem.scene = std::make_shared<michi::validity::Scene>();
        return problem;
    }

    Problem planarArmProblem()
    {
        Problem problem = armProblem("planar 2-link test", PLANAR_2LINK_URDF);
        problem.scene->add(Obstacle{"wall", Shape::box(Eigen::Vector3d(0.2, 0.8, 0.3)), translation(1.2, 0.9, 0.)});
        problem.scene->add(Obstacle{"ball", Shape::sphere(0.15), translation(-0.6, -1.0, 0.)});
        Obstacle mover{"mover", Shape::box(Eigen::Vector3d(0.2, 0.2, 0.2)), translation(-1.2, 0.5, 0.)};
        mover.trajectory = {
            {0., translation(-1.2, 0.5, 0.)}, {1., translation(-1.2, 1.2, 0.)}, {2., translation(-0.6, 1.4, 0.)}};
        problem.scene->add(mover);
        problem.queries.push_back({{-0.3, 0.6}, {1.6, -0.8}});
        return problem;
    }

    std::vector<PlotPath> planarArmPaths()
    {
        return {{"RRTConnect", {{-0.3, 0.6}, {0.4, 1.2}, {1.6, -0.8}}},
                {"ConcentricCircle", {{-0.3, 0.6}, {0.5, -1.5}, {1.6, -0.8}}}};
    }

    Problem se2Problem()
    {
        Problem problem;
        problem.name = "se2 corridor test";
        problem.kind = Problem::Kind::SE2;
        problem.footprint = {{-0.4, -0.2}, {0.4, -0.2}, {0.4, 0.2}, {-0.4, 0.2}};
        problem.se2Bounds = {{0., 6., 0., 4.}};
        problem.scene = std::make_shared<michi::validity::Scene>();
        problem.scene->add(Obstacle{"block", Shape::box(Eigen::Vector3d(1., 2., 1.)), translation(3., 2.5, 0.5)});
        problem.queries.push_back({{1., 1., 0.}, {5., 3., M_PI / 2.}});
        return problem;
    }

    std::string readFile(const std::string &path)
    {
        std::ifstream in(path);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    }

    std::size_t count(const std::string &text, const std::string &what)
    {
        std::size_t n = 0;
        for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size()))
            ++n;
        return n;
    }

    /** A fresh directory for one test; removed with its contents at the end. */
    class SvgPlotTest : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
            dir_ = fs::temp_directory_path() /
                   ("michi_svg_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
            fs::remove_all(dir_);
            fs::create_directories(dir_);
        }
        void TearDown() override
        {
            fs::remove_all(dir_);
        }
        std::string file(const std::string &name) const
        {
            return (dir_ / name).string();
        }
        fs::path dir_;
    };
}  // namespace

TEST_F(SvgPlotTest, PlanarArmDrawsPathsLegendAndConfigurationSpace)
{
    const std::string out = file("planar.svg");
    writeProblemSvg(planarArmProblem(), planarArmPaths(), out);
    ASSERT_TRUE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out + ".tmp"));
    const std::string svg = readFile(out);
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    EXPECT_EQ(count(svg, "<svg"), count(svg, "</svg>"));
    EXPECT_EQ(count(svg, "<g"), count(svg, "</g>"));
    EXPECT_NE(svg.find("planar 2-link test"), std::string::npos);
    // legend
    EXPECT_NE(svg.find(">RRTConnect</text>"), std::string::npos);
    EXPECT_NE(svg.find(">ConcentricCircle</text>"), std::string::npos);
    EXPECT_NE(svg.find(">start</text>"), std::string::npos);
    EXPECT_NE(svg.find(">goal</text>"), std::string::npos);
    // one end-effector trace per path in the top view, one polyline per path in the configuration space
    EXPECT_EQ(count(svg, "class=\"trace\""), 2u);
    EXPECT_NE(svg.find("id=\"cspace\""), std::string::npos);
    EXPECT_EQ(count(svg, "class=\"cspace-trace\""), 2u);
    EXPECT_NE(svg.find("joint1 [rad]"), std::string::npos);
    // the arm is drawn with its links at the start, the goal and 12 poses along each path; obstacles drawn
    EXPECT_EQ(count(svg, "class=\"robot\""), 24u);
    EXPECT_NE(svg.find("class=\"robot start\""), std::string::npos);
    EXPECT_NE(svg.find("class=\"robot goal\""), std::string::npos);
    EXPECT_NE(svg.find("class=\"obstacles\""), std::string::npos);
    EXPECT_NE(svg.find("class=\"key-frames\""), std::string::npos);
    // a planar arm has no side view
    EXPECT_EQ(svg.find("id=\"side-view\""), std::string::npos);
}

TEST_F(SvgPlotTest, EmptyPathListDrawsSceneStartAndGoal)
{
    const std::string out = file("empty.svg");
    writeProblemSvg(planarArmProblem(), {}, out);
    const std::string svg = readFile(out);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    EXPECT_NE(svg.find("class=\"obstacles\""), std::string::npos);
    EXPECT_NE(svg.find("class=\"robot start\""), std::string::npos);
    EXPECT_NE(svg.find("class=\"robot goal\""), std::string::npos);
    EXPECT_EQ(svg.find("class=\"trace\""), std::string::npos);
}

TEST_F(SvgPlotTest, LabelsAreEscaped)
{
    const std::string out = file("escaped.svg");
    writeProblemSvg(planarArmProblem(), {{"A<B & \"C\"", {{0., 0.}, {1., 1.}}}}, out);
    const std::string svg = readFile(out);
    EXPECT_NE(svg.find("A&lt;B &amp; &quot;C&quot;"), std::string::npos);
    EXPECT_EQ(svg.find("A<B"), std::string::npos);
}

TEST_F(SvgPlotTest, Se2DrawsFootprintsAndNoConfigurationSpace)
{
    const std::string out = file("se2.svg");
    // the second segment turns from 3 to -3 rad: the short way through pi
    writeProblemSvg(se2Problem(), {{"PRM", {{1., 1., 0.}, {1.5, 3., 3.}, {5., 3., -3.}, {5., 3., M_PI / 2.}}}}, out);
    const std::string svg = readFile(out);
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find(">PRM</text>"), std::string::npos);
    EXPECT_EQ(count(svg, "class=\"footprint\""), 2u + 12u);  // start, goal and the poses along the path
    EXPECT_EQ(count(svg, "class=\"trace\""), 1u);
    EXPECT_NE(svg.find("class=\"limits\""), std::string::npos);
    EXPECT_EQ(svg.find("id=\"cspace\""), std::string::npos);
    EXPECT_EQ(svg.find("id=\"side-view\""), std::string::npos);
}

TEST_F(SvgPlotTest, SpatialArmGetsSideView)
{
    Problem problem = armProblem("spatial 3-link test", SPATIAL_3LINK_URDF);
    problem.scene->add(Obstacle{"table", Shape::box(Eigen::Vector3d(0.6, 1.0, 0.05)), translation(0.6, 0., 0.2)});
    problem.queries.push_back({{0., -0.5, 0.8}, {2.5, 0.3, -0.6}});
    const std::string out = file("spatial.svg");
    writeProblemSvg(problem, {{"RRT", {{0., -0.5, 0.8}, {1.5, -1.0, 0.}, {2.5, 0.3, -0.6}}}}, out);
    const std::string svg = readFile(out);
    EXPECT_NE(svg.find("id=\"top-view\""), std::string::npos);
    EXPECT_NE(svg.find("id=\"side-view\""), std::string::npos);
    EXPECT_NE(svg.find("z [m]"), std::string::npos);
    EXPECT_EQ(count(svg, "class=\"trace\""), 2u);  // one per panel
    EXPECT_EQ(svg.find("id=\"cspace\""), std::string::npos);
}

TEST_F(SvgPlotTest, ContinuousJointTakesTheShortWayInConfigurationSpace)
{
    std::string urdf = PLANAR_2LINK_URDF;
    const std::string revolute = "name=\"joint1\" type=\"revolute\"";
    urdf.replace(urdf.find(revolute), revolute.size(), "name=\"joint1\" type=\"continuous\"");
    Problem problem = armProblem("continuous joint1", urdf.c_str());
    problem.queries.push_back({{3., 0.5}, {-3., -0.5}});
    const std::string out = file("wrap.svg");
    // from 3 to -3 rad the short way crosses +-pi: two pieces in the configuration space; through 0: one piece
    writeProblemSvg(problem, {{"short", {{3., 0.5}, {-3., -0.5}}}}, out);
    EXPECT_EQ(count(readFile(out), "class=\"cspace-trace\""), 2u);
    writeProblemSvg(problem, {{"long", {{3., 0.5}, {0., 0.}, {-3., -0.5}}}}, out);
    EXPECT_EQ(count(readFile(out), "class=\"cspace-trace\""), 1u);
}

TEST_F(SvgPlotTest, UnwritableFileThrowsNamingItAndLeavesNothing)
{
    const std::string out = file("no/such/dir/plot.svg");
    try
    {
        writeProblemSvg(planarArmProblem(), planarArmPaths(), out);
        FAIL() << "expected std::runtime_error";
    }
    catch (const std::runtime_error &e)
    {
        EXPECT_NE(std::string(e.what()).find(out), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out + ".tmp"));
    EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(SvgPlotTest, WrongDimensionThrowsNamingThePath)
{
    const std::string out = file("bad.svg");
    try
    {
        writeProblemSvg(planarArmProblem(), {{"good", {{0., 0.}}}, {"BadPlanner", {{0., 0.}, {1., 2., 3.}}}}, out);
        FAIL() << "expected std::invalid_argument";
    }
    catch (const std::invalid_argument &e)
    {
        EXPECT_NE(std::string(e.what()).find("BadPlanner"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(SvgPlotTest, UnknownQueryThrows)
{
    EXPECT_THROW(writeProblemSvg(planarArmProblem(), {}, file("query.svg"), 3), std::out_of_range);
    EXPECT_FALSE(fs::exists(file("query.svg")));
}
