// Task-region experience queries (issue 17 part 2): starts and goals drawn independently from hand poses in the
// regions of problems/experience/ring_task_regions.yaml and solved by IK. Each state's hand lies in a region (box
// and cone), the pairs follow the file's region pairs, every state is collision-free, the training and held-out
// sets share no state, a seed gives the same queries, and a bad regions file names its key.
#include <michi/planners/dual_arm/Manipulability.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/ExperienceQueries.h>
#include <michi/tools/problem/TaskRegionQueries.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

namespace tools = michi::tools;

namespace
{
    const std::string PROBLEMS = std::string(MICHI_SOURCE_DIR) + "/problems/";

    /** The regions (indices) whose box and cone hold the hand of group values \e values. */
    std::set<std::size_t> regionsHolding(const tools::Problem &problem, const tools::TaskRegions &regions,
                                         const michi::planners::ArmChain &arm, const std::vector<double> &values)
    {
        std::vector<double> q = problem.fixedValues;
        for (std::size_t k = 0; k < values.size(); ++k)
            q[static_cast<std::size_t>(problem.groupVariables[k])] = values[k];
        const Eigen::Isometry3d tool = arm.toolPose(q);
        const Eigen::Vector3d axis = tool.linear() * regions.toolAxis;
        std::set<std::size_t> in;
        for (std::size_t r = 0; r < regions.regions.size(); ++r)
        {
            const auto &region = regions.regions[r];
            const Eigen::Vector3d p = tool.translation();
            // tolerances: the IK's (1e-4 m, 1e-3 rad) and the 6 decimals the values are rounded to
            const bool inBox =
                ((p.array() >= region.lower.array() - 1e-3) && (p.array() <= region.upper.array() + 1e-3)).all();
            const double angle = std::acos(std::max(-1., std::min(1., axis.normalized().dot(region.direction))));
            if (inBox && angle <= region.cone + 5e-3)
                in.insert(r);
        }
        return in;
    }
}  // namespace

TEST(TaskRegionQueries, StartsAndGoalsAreFreeHandPosesInTheRegionsPairs)
{
    const auto problem = tools::loadProblem(PROBLEMS + "xarm6_ring.yaml");
    const auto regions = tools::readTaskRegions(PROBLEMS + "experience/ring_task_regions.yaml", problem);
    ASSERT_EQ(regions.regions.size(), 5u);
    ASSERT_EQ(regions.pairs.size(), 8u);
    const auto queries = tools::generateTaskRegionQueries(problem, regions, 40, 15, 3);
    ASSERT_EQ(queries.training.size(), 15u);
    ASSERT_EQ(queries.heldOut.size(), 25u);

    const michi::planners::ArmChain arm(problem.model, regions.tipLink, regions.toolPoint);
    const auto ctx = tools::makePlanningContext(problem, 0);
    std::set<std::pair<std::size_t, std::size_t>> allowed(regions.pairs.begin(), regions.pairs.end());
    std::set<std::vector<double>> training;
    for (const auto &q : queries.training)
    {
        training.insert(q.start);
        training.insert(q.goal);
    }
    std::set<std::pair<std::size_t, std::size_t>> pairsSeen;
    for (const auto *set : {&queries.training, &queries.heldOut})
        for (const auto &q : *set)
        {
            EXPECT_EQ(tools::invalidStateReason(ctx, q.start), "");
            EXPECT_EQ(tools::invalidStateReason(ctx, q.goal), "");
            // within the limits as written (six decimals), as the queries file's reader checks them
            for (const auto *values : {&q.start, &q.goal})
                for (std::size_t k = 0; k < values->size(); ++k)
                {
                    const auto &j = problem.model->variableJoint(static_cast<std::size_t>(problem.groupVariables[k]));
                    if (j.type != michi::validity::RobotJoint::Type::CONTINUOUS)
                    {
                        EXPECT_GE((*values)[k], j.lower) << j.name;
                        EXPECT_LE((*values)[k], j.upper) << j.name;
                    }
                }
            const auto starts = regionsHolding(problem, regions, arm, q.start);
            const auto goals = regionsHolding(problem, regions, arm, q.goal);
            bool pairFound = false;
            for (std::size_t a : starts)
                for (std::size_t b : goals)
                    if (allowed.count({a, b}))
                    {
                        pairFound = true;
                        pairsSeen.insert({a, b});
                    }
            EXPECT_TRUE(pairFound) << "a query whose start and goal are in no region pair of the file";
            if (set == &queries.heldOut)
            {
                EXPECT_EQ(training.count(q.start), 0u) << "a held-out start is a training state";
                EXPECT_EQ(training.count(q.goal), 0u) << "a held-out goal is a training state";
            }
        }
    // independent draws over 8 pairs: 40 queries see most of them, not one pair repeated
    EXPECT_GE(pairsSeen.size(), 6u);

    // deterministic for a seed, another seed draws other queries
    const auto again = tools::generateTaskRegionQueries(problem, regions, 40, 15, 3);
    EXPECT_EQ(again.heldOut.back().goal, queries.heldOut.back().goal);
    const auto other = tools::generateTaskRegionQueries(problem, regions, 40, 15, 4);
    EXPECT_NE(other.heldOut.back().goal, queries.heldOut.back().goal);
}

TEST(TaskRegionQueries, ABadRegionsFileNamesItsKey)
{
    const auto problem = tools::loadProblem(PROBLEMS + "xarm6_ring.yaml");
    const auto dir = std::filesystem::temp_directory_path() / "michi_task_regions_test";
    std::filesystem::create_directories(dir);
    auto expectError = [&](const std::string &text, const std::string &key)
    {
        const std::string file = (dir / "regions.yaml").string();
        std::ofstream(file) << text;
        try
        {
            tools::readTaskRegions(file, problem);
            ADD_FAILURE() << "no error for: " << text;
        }
        catch (const tools::ProblemError &e)
        {
            EXPECT_EQ(e.key(), key) << e.what();
            EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
        }
    };
    const std::string region =
        "{name: a, box: {min: [0.5, 0, 0.3], max: [0.6, 0.1, 0.4]}, direction: [1, 0, 0], "
        "cone: 0.2}";
    expectError("tip_link: hand\ntool_axis: [0, 0, 1]\nregions: [" + region + "]\n", "tip_link");
    expectError("tip_link: link6\ntool_axis: [0, 0, 0]\nregions: [" + region + "]\n", "tool_axis");
    expectError("tip_link: link6\ntool_axis: [0, 0, 1]\nregions: [" + region + "]\npairs: [[a, b]]\n", "pairs[0][1]");
    expectError(
        "tip_link: link6\ntool_axis: [0, 0, 1]\nregions: [{name: a, box: {min: [0.7, 0, 0.3], max: [0.6, "
        "0.1, 0.4]}, direction: [1, 0, 0], cone: 0.2}]\n",
        "regions[0].box");
    expectError("tip_link: link6\ntool_axis: [0, 0, 1]\nregions: [" + region + "]\n", "regions");
    expectError("tip_link: link6\ntool_axis: [0, 0, 1]\nregion: [" + region + "]\n", "region");
    std::filesystem::remove_all(dir);
}
