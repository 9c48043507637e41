// Tests of michi::planners::DualArmWorkspace (paper 004) on the bundled dual-arm robot at a coarse grid:
// the common work space is inside both arms' work spaces, a position in the manipulability area gives w above
// the threshold at IK, both work positions are reached by both arms with the stated hand orientations and
// without collisions, and the stirring motion at B keeps w above the threshold at every state. Also the
// dual_arm section of the problem file: strict keys with errors naming the file and key (also for a small arm too
// short for the manipulability rows).

#include "support/TestScenes.h"

#include <michi/planners/dual_arm/DualArmWorkspace.h>
#include <michi/tools/problem/DualArmProblem.h>

#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <fstream>

using namespace michi;
using planners::DualArmWorkspace;
using planners::HandTarget;

namespace
{
    /** One coarse analysis shared by the tests (it takes a few seconds). */
    class DualArmFixture : public ::testing::Test
    {
    protected:
        static void SetUpTestSuite()
        {
            problem_ = new tools::Problem(tools::loadProblem(test::sourcePath("problems/dual_arm.yaml")));
            tools::DualArmSpec spec = tools::loadDualArmSpec(*problem_);
            spec.settings.resolution = 0.04;
            spec.settings.seedSamples = 1500;
            std::vector<double> home = problem_->fixedValues;
            for (std::size_t i = 0; i < problem_->groupVariables.size(); ++i)
                home[problem_->groupVariables[i]] = problem_->queries[0].start[i];
            ws_ = new DualArmWorkspace(problem_->model, tools::makeArmTask(*problem_, spec.large, "large"),
                                       tools::makeArmTask(*problem_, spec.small, "small"), home, spec.settings);
            ws_->compute();
        }
        static void TearDownTestSuite()
        {
            delete ws_;
            delete problem_;
        }

        /** Both hands at \e p with their orientations, in limits and collision free. */
        static void expectBothReach(const Eigen::Vector3d &p, const std::vector<double> &q)
        {
            const Eigen::Isometry3d large = ws_->large().arm.toolPose(q), small = ws_->small().arm.toolPose(q);
            EXPECT_LT((large.translation() - p).norm(), 1e-3);
            EXPECT_LT((small.translation() - p).norm(), 1e-3);
            EXPECT_LT(std::abs((large.linear() * Eigen::Vector3d::UnitZ()).z()), 2e-3);  // horizontal
            EXPECT_LT((small.linear() * Eigen::Vector3d::UnitZ() + Eigen::Vector3d::UnitZ()).norm(), 2e-3);  // down
            for (std::size_t v = 0; v < q.size(); ++v)
            {
                EXPECT_GE(q[v], problem_->model->variableJoint(v).lower - 1e-12);
                EXPECT_LE(q[v], problem_->model->variableJoint(v).upper + 1e-12);
            }
            EXPECT_TRUE(ws_->armFree(ws_->large(), q));
            EXPECT_TRUE(ws_->armFree(ws_->small(), q));
            EXPECT_TRUE(ws_->armsApart(q));
        }

        static tools::Problem *problem_;
        static DualArmWorkspace *ws_;
    };
    tools::Problem *DualArmFixture::problem_ = nullptr;
    DualArmWorkspace *DualArmFixture::ws_ = nullptr;
}  // namespace

TEST_F(DualArmFixture, CommonSpaceIsInsideBothWorkSpaces)
{
    EXPECT_GT(ws_->count(DualArmWorkspace::COMMON), 10u);
    EXPECT_GT(ws_->count(DualArmWorkspace::REACH_LARGE), ws_->count(DualArmWorkspace::COMMON));
    EXPECT_GT(ws_->count(DualArmWorkspace::REACH_SMALL), ws_->count(DualArmWorkspace::COMMON));
    std::size_t area = 0;
    for (auto f : ws_->flags())
    {
        if (f & DualArmWorkspace::COMMON)
        {
            EXPECT_TRUE(f & DualArmWorkspace::REACH_LARGE);
            EXPECT_TRUE(f & DualArmWorkspace::REACH_SMALL);
        }
        if (f & DualArmWorkspace::STIR)
            EXPECT_TRUE(f & DualArmWorkspace::AREA);
        if (f & DualArmWorkspace::AREA)
        {
            EXPECT_TRUE(f & DualArmWorkspace::COMMON);
            ++area;
        }
    }
    EXPECT_GT(area, 0u);
    EXPECT_LT(area, ws_->count(DualArmWorkspace::COMMON));  // the threshold cuts the common space
}

TEST_F(DualArmFixture, AreaPositionsHaveManipulabilityAboveThresholdAtIk)
{
    const double threshold = ws_->settings().threshold;
    const auto &flags = ws_->flags();
    std::size_t checked = 0;
    for (std::size_t c = 0; c < flags.size() && checked < 40; ++c)
        if ((flags[c] & DualArmWorkspace::AREA) && c % 3 == 0)
        {
            // solve again from the rest pose and the samples, independently of the stored solution
            std::vector<double> q = ws_->home();
            const Eigen::Vector3d p = ws_->grid().centre(c);
            ASSERT_TRUE(ws_->solveArm(ws_->small(), p, q, {}));
            const Eigen::Isometry3d tool = ws_->small().arm.toolPose(q);
            EXPECT_LT((tool.translation() - p).norm(), 1e-3);
            EXPECT_GT(ws_->small().arm.manipulability(q, ws_->settings().rows), threshold);
            EXPECT_GT(ws_->smallManipulability()[c], threshold);
            ++checked;
        }
    EXPECT_GT(checked, 0u);
}

TEST_F(DualArmFixture, WorkPositionsAreReachedByBothArms)
{
    SCOPED_TRACE("type A");
    expectBothReach(ws_->typeAPosition(), ws_->typeAConfiguration());
    SCOPED_TRACE("type B");
    expectBothReach(ws_->typeBPosition(), ws_->typeBConfiguration());
    // A is the common-space centroid when both reach it, else the nearest common cell
    EXPECT_LE((ws_->typeAPosition() - ws_->typeACentroid()).norm(),
              (ws_->typeACentroid() - ws_->grid().centre(0)).norm());
}

TEST_F(DualArmFixture, StirringAtBKeepsManipulabilityAboveThreshold)
{
    const auto m = ws_->stir(ws_->typeBPosition(), ws_->typeBConfiguration());
    ASSERT_TRUE(m.valid) << m.failure;
    ASSERT_GE(m.states.size(), 4u * 12u);
    const double threshold = ws_->settings().threshold;
    for (std::size_t i = 0; i < m.states.size(); ++i)
    {
        EXPECT_GT(ws_->small().arm.manipulability(m.states[i], ws_->settings().rows), threshold);
        const Eigen::Isometry3d tool = ws_->small().arm.toolPose(m.states[i]);
        EXPECT_LT((tool.translation() - m.hand[i]).norm(), 1e-3);
        EXPECT_NEAR(tool.translation().z(), ws_->typeBPosition().z(), 1e-3);  // horizontal square
        EXPECT_TRUE(ws_->armsApart(m.states[i]));
    }
    EXPECT_GT(m.minManipulability, threshold);
    // the square's corners are 3 cm apart
    EXPECT_NEAR((m.hand.front() - m.hand[m.hand.size() / 4]).norm(), 0.03, 1e-9);
}

TEST(DualArmProblem, StrictKeysNameFileAndKey)
{
    const std::string dir = ::testing::TempDir();
    std::ifstream in(test::sourcePath("problems/dual_arm.yaml"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("urdf: robots/dual_arm.urdf"), 26,
                 "urdf: " + test::sourcePath("problems/robots/dual_arm.urdf"));
    auto expectError = [&](const std::string &from, const std::string &to, const std::string &key)
    {
        std::string bad = text;
        const auto at = bad.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        bad.replace(at, from.size(), to);
        const std::string file = dir + "/dual_arm_bad.yaml";
        std::ofstream(file) << bad;
        try
        {
            tools::loadDualArmSpec(tools::loadProblem(file));
            ADD_FAILURE() << "no error for " << to;
        }
        catch (const tools::ProblemError &e)
        {
            EXPECT_EQ(e.file(), file);
            EXPECT_EQ(e.key(), key) << e.what();
        }
    };
    expectError("threshold: 0.004", "threshhold: 0.004", "dual_arm.threshhold");
    expectError("threshold: 0.004", "threshold: -1", "dual_arm.threshold");
    expectError("tip: large_tip", "tip: no_such_link", "dual_arm.large.tip");
    expectError("along: [0, 0, -1]", "alongside: [0, 0, -1]", "dual_arm.small.hand.alongside");
    expectError("manipulability_rows: full", "manipulability_rows: some", "dual_arm.manipulability_rows");
    expectError("stirring: {side: 0.03, step: 0.0025}", "stirring: {side: 0.03, step: 0.1}", "dual_arm.stirring.step");
    expectError("small: [small_joint1, small_joint2,", "small: [small_joint2, small_joint1,", "robot.group");
    // a small arm of 5 joints has no 6-row manipulability (manipulability_rows: full): named by file and key
    expectError("tip: small_tip", "tip: small_link5", "dual_arm.small.tip");
}
