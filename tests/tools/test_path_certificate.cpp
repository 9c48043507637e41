// certifyPath, michi bench's re-check of a returned path: it refuses what collides or leaves the bounds between the
// planner's checks, and accepts a path whose end sits exactly on a joint limit.
#include <michi/tools/bench/PathCertificate.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathGeometric.h>

#include <boost/filesystem.hpp>

#include <gtest/gtest.h>

#include <fstream>

namespace fs = boost::filesystem;
namespace ob = ompl::base;

namespace
{
    // one joint, limit 3.8223 (the Panda's sixth joint): from 1.5566949530440126, interpolate(a, b, 1.0) gives
    // b + 4.4e-16, an ulp past the limit
    const char *ARM_URDF = R"(<robot name="one">
  <link name="base"/>
  <link name="l1"><collision><origin xyz="0.25 0 0" rpy="0 1.5707963 0"/>
    <geometry><cylinder radius="0.01" length="0.5"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-0.0873" upper="3.8223" effort="1" velocity="1"/></joint>
</robot>)";

    class PathCertificateTest : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            dir_ = fs::temp_directory_path() / fs::unique_path("michi-certificate-%%%%%%%%");
            fs::create_directories(dir_);
            std::ofstream(dir_ / "arm.urdf") << ARM_URDF;
            // a wall the arm meets at about 1 rad (0.91-1.09)
            std::ofstream(dir_ / "p.yaml")
                << "name: p\nrobot: {urdf: arm.urdf}\n"
                   "scene:\n  obstacles:\n"
                   "    - {name: wall, box: [0.04, 0.04, 1], pose: {xyz: [0.1891, 0.2945, 0]}}\n"
                   "start: [0]\ngoal: [3.8223]\n";
            ctx_ = michi::tools::makePlanningContext(michi::tools::loadProblem((dir_ / "p.yaml").string()));
        }
        void TearDown() override
        {
            fs::remove_all(dir_);
        }
        ompl::geometric::PathGeometric path(std::initializer_list<double> values) const
        {
            const auto si = ctx_.setup->getSpaceInformation();
            ompl::geometric::PathGeometric p(si);
            for (double v : values)
            {
                ob::ScopedState<> s(si);
                s[0] = v;
                p.append(s.get());
            }
            return p;
        }
        fs::path dir_;
        michi::tools::PlanningContext ctx_;
    };
}  // namespace

TEST_F(PathCertificateTest, AcceptsAPathThatEndsOnAJointLimit)
{
    const double a = 1.5566949530440126, limit = 3.8223;
    // the premise: interpolating to the end overshoots the limit by rounding
    ASSERT_GT(a + (limit - a) * 1.0, limit);
    const auto si = ctx_.setup->getSpaceInformation();
    const auto p = path({a, limit});
    ASSERT_TRUE(si->isValid(p.getState(0)));
    ASSERT_TRUE(si->isValid(p.getState(1)));  // on the limit is within bounds
    const auto certificate = michi::tools::certifyPath(p, *ctx_.checker);
    EXPECT_TRUE(certificate.certified) << certificate.reason;
    EXPECT_GT(certificate.statesChecked, 10u);  // the states between the ends were checked too
}

TEST_F(PathCertificateTest, RefusesAPathThroughTheWallOrPastALimit)
{
    // both ends free, the wall in between
    const auto through = path({0., 2.});
    const auto certificate = michi::tools::certifyPath(through, *ctx_.checker);
    EXPECT_FALSE(certificate.certified);
    EXPECT_NE(certificate.reason.find("wall"), std::string::npos) << certificate.reason;
    const auto past = path({2.5, 3.9});
    const auto outside = michi::tools::certifyPath(past, *ctx_.checker);
    EXPECT_FALSE(outside.certified);
    EXPECT_NE(outside.reason.find("out of bounds"), std::string::npos) << outside.reason;
}
