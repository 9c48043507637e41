// Tests of michi::validity::JMapValidityChecker on the bundled planar problems: conservative (never valid where
// FCL says invalid), lazy and cached, exact fallback near polygon edges, cache dropped when the scene changes,
// concurrent queries during lazy builds, and the pre-filter for an arm with a hand.
#include <michi/tools/problem/ProblemJMap.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/validity/fcl/ConservativeMotionValidator.h>
#include <michi/validity/jmap/JMapMotionValidator.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>

using namespace michi;

namespace
{
    struct Fixture
    {
        tools::Problem problem;
        tools::PlanningContext ctx;
        std::vector<std::vector<double>> states;

        Fixture(const std::string &name, std::size_t count, unsigned int seed = 3)
            : problem(tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/" + name + ".yaml"))
            , ctx(tools::makePlanningContext(problem))
        {
            ompl::RNG rng(seed);
            for (std::size_t n = 0; n < count; ++n)
            {
                std::vector<double> q;
                for (int v : problem.groupVariables)
                    q.push_back(
                        rng.uniformReal(problem.model->variableJoint(v).lower, problem.model->variableJoint(v).upper));
                states.push_back(q);
            }
        }

        validity::JMapValidityCheckerPtr checker(validity::JMapCheckerSettings settings = {}) const
        {
            return tools::makeJMapChecker(problem, ctx, settings);
        }
    };

    struct Counts
    {
        int unsafe{0};        // J-map valid, FCL invalid
        int falseInvalid{0};  // J-map invalid, FCL valid
    };

    Counts compare(const Fixture &f, const validity::JMapValidityChecker &jmap)
    {
        Counts c;
        for (const auto &q : f.states)
        {
            const bool mine = jmap.isValidConfiguration(q.data()),
                       exact = f.ctx.checker->isValidConfiguration(q.data());
            c.unsafe += mine && !exact;
            c.falseInvalid += !mine && exact;
        }
        return c;
    }
}  // namespace

TEST(JMapValidityChecker, ConservativeAndLazyOnPlanar2Link)
{
    const Fixture f("planar_2link", 20000);
    const auto jmap = f.checker();
    EXPECT_TRUE(jmap->answersAlone()) << "two joints, no self pair that can touch: no FCL needed";
    EXPECT_EQ(jmap->builtTiles(), 0u);
    jmap->isValidConfiguration(f.states[0].data());
    EXPECT_EQ(jmap->builtTiles(), 1u) << "only the tile of the first query is built";
    const Counts c = compare(f, *jmap);
    EXPECT_EQ(c.unsafe, 0);
    EXPECT_GT(c.falseInvalid, 0) << "the map is conservative, so some free states near obstacles are refused";
    EXPECT_LT(c.falseInvalid, 2000) << "but not absurdly many (10 % of all states)";
    EXPECT_EQ(jmap->builtTiles(), jmap->tileCount());
    EXPECT_EQ(jmap->fclQueries(), 0u);
}

TEST(JMapValidityChecker, ExactFallbackLosesNoFreeSpaceNearEdges)
{
    const Fixture f("planar_2link", 20000);
    validity::JMapCheckerSettings settings;
    const Counts conservative = compare(f, *f.checker(settings));
    settings.mode = validity::JMapCheckerSettings::Mode::EXACT_FALLBACK;
    settings.fallbackBand = 0.3;  // wider than the polygons' looseness
    const auto fallback = f.checker(settings);
    const Counts c = compare(f, *fallback);
    EXPECT_EQ(c.unsafe, 0);
    EXPECT_EQ(c.falseInvalid, 0) << "every refused free state lies near a polygon edge and is re-checked";
    EXPECT_GT(conservative.falseInvalid, 0);
    EXPECT_GT(fallback->fclQueries(), 0u);
    EXPECT_LT(fallback->fclQueries(), f.states.size()) << "deep inside the polygons the map answers alone";
}

TEST(JMapValidityChecker, SceneChangeDropsTheCache)
{
    Fixture f("planar_2link", 0);
    const auto jmap = f.checker();
    // the arm stretched along +x at joint1 = 0 is free; a post on that line makes it collide
    const std::vector<double> q{0., 0.};
    ASSERT_TRUE(f.ctx.checker->isValidConfiguration(q.data()));
    ASSERT_TRUE(jmap->isValidConfiguration(q.data()));
    EXPECT_EQ(jmap->builtTiles(), 1u);
    validity::Obstacle post;
    post.name = "post";
    post.shape = validity::Shape::box(Eigen::Vector3d(0.05, 0.05, 1.));
    post.pose.translation() = Eigen::Vector3d(0.7, 0., 0.);
    f.problem.scene->add(post);
    EXPECT_FALSE(jmap->isValidConfiguration(q.data()));
    EXPECT_EQ(jmap->builtTiles(), 1u) << "tiles are rebuilt lazily after a change";
    f.problem.scene->remove("post");
    EXPECT_TRUE(jmap->isValidConfiguration(q.data()));
}

TEST(JMapValidityChecker, ConcurrentQueriesDuringLazyBuildsAgree)
{
    const Fixture f("planar_2link", 8000, 11);
    std::vector<char> expected(f.states.size());
    {
        const auto single = f.checker();
        for (std::size_t n = 0; n < f.states.size(); ++n)
            expected[n] = single->isValidConfiguration(f.states[n].data());
    }
    const auto shared = f.checker();  // nothing built yet: the threads race to build the tiles
    std::vector<int> mismatches(4, 0);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back(
            [&, t]
            {
                for (std::size_t k = 0; k < f.states.size(); ++k)
                {
                    const std::size_t n = (k * 7 + static_cast<std::size_t>(t) * 1999) % f.states.size();
                    mismatches[t] += shared->isValidConfiguration(f.states[n].data()) != (expected[n] != 0);
                }
            });
    for (auto &th : threads)
        th.join();
    for (int t = 0; t < 4; ++t)
        EXPECT_EQ(mismatches[t], 0) << "thread " << t;
    EXPECT_EQ(shared->builtTiles(), shared->tileCount());
}

TEST(JMapValidityChecker, ArmMapPreFiltersAnArmWithAHand)
{
    const Fixture f("planar_3dof_hand", 20000);
    const auto jmap = f.checker();
    EXPECT_FALSE(jmap->answersAlone()) << "the hand is not in the arm's map: FCL decides what the map lets through";
    const Counts c = compare(f, *jmap);
    EXPECT_EQ(c.unsafe, 0);
    EXPECT_GT(jmap->fclQueries(), 0u);
    EXPECT_LT(jmap->fclQueries(), f.states.size()) << "states inside the arm's polygons never reach FCL";
}

TEST(JMapValidityChecker, FclSweepMapOfASpatialArmInstalls)
{
    // arch_3dof's arm is not planar, so its J-map is an FCL sweep whose cost is measured on a start configuration
    // while the checker is made: that used to read the context's start state before it was set (a segfault of
    // `michi bench problems/arch_3dof.yaml --checker jmap`)
    auto problem = tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/arch_3dof.yaml");
    problem.checker = "jmap";
    const auto ctx = tools::makePlanningContext(problem);
    ASSERT_NE(ctx.jmap, nullptr);
    EXPECT_EQ(ctx.setup->getSpaceInformation()->getStateValidityChecker().get(), ctx.jmap.get());
    EXPECT_TRUE(ctx.setup->getSpaceInformation()->isValid(ctx.setup->getProblemDefinition()->getStartState(0)));
}

TEST(JMapValidityChecker, WhatTheMapCannotDecideGoesToAnExactValidator)
{
    // arch_3dof keeps the default workspace validator, which samples every 1 cm of motion; behind the J-map that let
    // shallow contacts through (verify-checker: 63 unsafe motions in 200,000). Motions the workspace validator
    // accepts and the exact one refuses must be refused with the J-map installed.
    auto problem = tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/arch_3dof.yaml");
    ASSERT_EQ(problem.motionValidator, "workspace");
    problem.checker = "jmap";
    const auto ctx = tools::makePlanningContext(problem);
    const auto si = ctx.setup->getSpaceInformation();
    const auto jmapMotions = si->getMotionValidator();
    validity::ConservativeMotionValidator exact(si, ctx.checker);
    // short motions, as verify-checker draws them (within 2 % of the space's extent)
    ompl::RNG rng(1);
    const auto &bounds = ctx.setup->getStateSpace()->as<ompl::base::RealVectorStateSpace>()->getBounds();
    const double near = 0.02 * si->getMaximumExtent();
    ompl::base::State *a = si->allocState(), *b = si->allocState();
    auto *va = a->as<ompl::base::RealVectorStateSpace::StateType>(),
         *vb = b->as<ompl::base::RealVectorStateSpace::StateType>();
    int shallow = 0, stepped = 0;
    for (int i = 0; i < 20000 && shallow < 3; ++i)
    {
        for (std::size_t d = 0; d < bounds.low.size(); ++d)
        {
            va->values[d] = rng.uniformReal(bounds.low[d], bounds.high[d]);
            vb->values[d] =
                std::min(bounds.high[d], std::max(bounds.low[d], va->values[d] + rng.uniformReal(-near, near)));
        }
        if (!ctx.checker->isValid(a) || !ctx.checker->isValid(b) || !ctx.referenceMotions->checkMotion(a, b) ||
            exact.checkMotion(a, b))
            continue;
        ++shallow;
        EXPECT_FALSE(jmapMotions->checkMotion(a, b)) << "a contact the workspace validator stepped over";
        // the map alone does not refuse them: behind it, the workspace validator let them through
        stepped += validity::JMapMotionValidator(si, ctx.jmap, ctx.referenceMotions).checkMotion(a, b) ? 1 : 0;
    }
    si->freeState(a);
    si->freeState(b);
    EXPECT_GT(shallow, 0) << "no motion the workspace validator gets wrong: the test shows nothing";
    EXPECT_GT(stepped, 0) << "the J-map refuses these motions by itself: the test shows nothing";
}

TEST(JMapValidityChecker, ProblemSwitchInstallsIt)
{
    auto problem = tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/planar_2link.yaml");
    problem.checker = "jmap";
    const auto ctx = tools::makePlanningContext(problem);
    ASSERT_NE(ctx.jmap, nullptr);
    EXPECT_EQ(ctx.setup->getSpaceInformation()->getStateValidityChecker().get(), ctx.jmap.get());
    problem.kind = tools::Problem::Kind::ARM;
    problem.groupVariables.resize(1);
    EXPECT_THROW(tools::makeJMapProblem(problem, ctx), tools::ProblemError);
}
