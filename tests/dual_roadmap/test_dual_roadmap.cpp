// Tests of michi::planners::DualRoadmap (paper 002): the learning roadmap persists across queries, clear() and scene
// changes; a scene change reseeds the working roadmap only with learning edges that are valid in the new scene; the
// change counter decides when the working roadmap is rebuilt; the learning roadmap survives a save/load round trip
// and bad files are rejected with their name; the ablation (use_learning = 0) learns nothing; the learning roadmap
// reduces the planning work (counted, not timed) on a repeated scene change and after clear(); a change confined to a
// region keeps what was proved elsewhere; edge probes refute a blocked motion without its motion check; a search weight
// above 1 expands fewer vertices; a full working roadmap kept from earlier queries starts afresh once per query, and
// one that a failed query filled is dropped before the next query.
#include "support/TestScenes.h"

#include <michi/planners/dual_roadmap/DualRoadmap.h>
#include <michi/validity/fcl/WorkspaceMotionValidator.h>

#include <michi/state_spaces/JointStateSpace.h>

#include <ompl/base/PlannerData.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <fstream>

using namespace michi;
namespace ob = ompl::base;

namespace
{
    /** A 0.4 m square robot in a 10 m x 10 m room split by a wall at x = 5 with two gaps (y 2..3 and 7..8). */
    struct Fixture
    {
        test::CheckerSetup setup;
        ob::ProblemDefinitionPtr pdef;
        std::shared_ptr<planners::DualRoadmap> planner;

        Fixture()
        {
            const test::Outline robot = test::boxOutline({-0.2, -0.2}, {0.2, 0.2});
            setup = test::planarRigidBodySetup(
                robot,
                {test::boxOutline({4.8, 0.}, {5.2, 2.}), test::boxOutline({4.8, 3.}, {5.2, 7.}),
                 test::boxOutline({4.8, 8.}, {5.2, 10.})},
                {0., 0.}, {10., 10.});
            setup.si->setMotionValidator(
                std::make_shared<validity::WorkspaceMotionValidator>(setup.si, setup.checker, 0.02));
            setup.si->setup();
            planner = std::make_shared<planners::DualRoadmap>(setup.si);
            auto scene = setup.scene;
            planner->setSceneChangeCounter(
                [scene]
                {
                    return scene->changeCount();
                });
            query({1., 5., 0.}, {9., 5., 0.});
        }

        void query(const std::vector<double> &from, const std::vector<double> &to)
        {
            pdef = std::make_shared<ob::ProblemDefinition>(setup.si);
            ob::ScopedState<> s(setup.si), g(setup.si);
            setup.si->getStateSpace()->copyFromReals(s.get(), from);
            setup.si->getStateSpace()->copyFromReals(g.get(), to);
            pdef->setStartAndGoalStates(s, g);
            planner->setProblemDefinition(pdef);
        }

        ob::PlannerStatus solve()
        {
            return planner->ob::Planner::solve(5.);
        }

        /** Learning edges (both ends tag 1 in the planner data) whose states and motion are valid now. */
        std::size_t validLearningEdges() const
        {
            ob::PlannerData data(setup.si);
            planner->getPlannerData(data);
            std::size_t valid = 0;
            for (unsigned int i = 0; i < data.numVertices(); ++i)
            {
                if (data.getVertex(i).getTag() != 1)
                    continue;
                std::vector<unsigned int> out;
                data.getEdges(i, out);
                for (unsigned int j : out)
                    if (j > i && data.getVertex(j).getTag() == 1 && setup.si->isValid(data.getVertex(i).getState()) &&
                        setup.si->isValid(data.getVertex(j).getState()) &&
                        setup.si->checkMotion(data.getVertex(i).getState(), data.getVertex(j).getState()))
                        ++valid;
            }
            return valid;
        }
    };
}  // namespace

TEST(DualRoadmap, LearningRoadmapPersistsAcrossQueriesAndClear)
{
    ompl::RNG::setSeed(3);
    Fixture f;
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    const std::size_t learned = f.planner->learningEdgeCount();
    EXPECT_GT(learned, 0u);
    EXPECT_GT(f.planner->learningVertexCount(), 1u);
    f.planner->clear();
    EXPECT_EQ(f.planner->workingVertexCount(), 0u);
    EXPECT_EQ(f.planner->learningEdgeCount(), learned);
    f.query({1., 1., 0.}, {9., 9., 0.});
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_GT(f.planner->seededEdgeCount(), 0u) << "a new working roadmap is seeded from experience";
    EXPECT_GE(f.planner->learningEdgeCount(), learned);
    f.planner->clearLearningRoadmap();
    EXPECT_EQ(f.planner->learningEdgeCount(), 0u);
}

TEST(DualRoadmap, SceneChangeSeedsOnlyEdgesValidInTheNewScene)
{
    ompl::RNG::setSeed(5);
    Fixture f;
    f.planner->setSeedEdges(100000);   // try every learning edge
    f.planner->setLazySeeding(false);  // and check each at once
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    // close the lower gap and block the middle of the left half: some learned edges become invalid
    validity::Obstacle door;
    door.name = "door";
    door.shape = validity::Shape::box({0.4, 1.2, 1.});
    door.pose.translation() = Eigen::Vector3d(5., 2.5, 0.);
    f.setup.scene->add(door);
    validity::Obstacle block;
    block.name = "block";
    block.shape = validity::Shape::box({2., 2., 1.});
    block.pose.translation() = Eigen::Vector3d(3., 5., 0.);
    f.setup.scene->add(block);
    const std::size_t expected = f.validLearningEdges();
    f.query({1., 8.5, 0.}, {9., 1., 0.});
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_GT(expected, 0u);
    EXPECT_EQ(f.planner->seededEdgeCount(), expected);
    auto path = f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>();
    EXPECT_TRUE(path->check());
}

TEST(DualRoadmap, WorkingRoadmapKeptWhileTheSceneDoesNotChange)
{
    ompl::RNG::setSeed(7);
    Fixture f;
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    const std::size_t vertices = f.planner->workingVertexCount();
    f.query({1., 2., 0.}, {9., 8., 0.});
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_GE(f.planner->workingVertexCount(), vertices + 2) << "same scene: roadmap kept, the query added";
    f.setup.scene->setPose("polygon0", Eigen::Isometry3d::Identity());  // a change
    f.query({1., 2., 0.}, {9., 8., 0.});
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    f.planner->notifySceneChanged();
    f.query({1., 5., 0.}, {9., 5., 0.});
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_GT(f.planner->seededEdgeCount(), 0u);
}

TEST(DualRoadmap, FullKeptRoadmapStartsAfreshOnceInsteadOfFailing)
{
    ompl::RNG::setSeed(11);
    Fixture f;
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    // the gap the path went through
    auto first = f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>();
    first->interpolate(200);
    double gapY = -1.;
    for (std::size_t i = 0; i < first->getStateCount(); ++i)
    {
        const auto *st = first->getState(i)->as<ob::SE2StateSpace::StateType>();
        if (std::abs(st->getX() - 5.) < 0.1)
            gapY = st->getY();
    }
    ASSERT_GT(gapY, 0.);
    // the kept roadmap is full: no room for a sample
    f.planner->setMaxWorkingVertices(static_cast<unsigned int>(f.planner->workingVertexCount()));
    validity::Obstacle door;
    door.name = "door";
    door.shape = validity::Shape::box({0.4, 1.2, 1.});
    door.pose.translation() = Eigen::Vector3d(5., gapY < 5. ? 2.5 : 7.5, 0.);
    f.setup.scene->add(door);
    f.query({1., 5., 0.}, {9., 5., 0.});
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION)
        << "the other gap needs samples the full roadmap has no room for";
    EXPECT_EQ(f.planner->workingRestarts(), 1u);
    auto second = f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>();
    EXPECT_TRUE(second->check());

    // both gaps closed: no path; the query starts afresh at most once and then fails, it does not loop
    validity::Obstacle other = door;
    other.name = "other door";
    other.pose.translation() = Eigen::Vector3d(5., gapY < 5. ? 7.5 : 2.5, 0.);
    f.setup.scene->add(other);
    f.query({1., 5., 0.}, {9., 5., 0.});
    EXPECT_NE(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_LE(f.planner->workingRestarts(), 2u);
    // the next query again at most once
    f.query({1., 5., 0.}, {9., 5., 0.});
    EXPECT_NE(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_LE(f.planner->workingRestarts(), 3u);
}

TEST(DualRoadmap, RoadmapFilledByAFailedQueryIsDroppedBeforeTheNextQuery)
{
    ompl::RNG::setSeed(13);
    Fixture f;
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    const unsigned int full = 300;
    f.planner->setMaxWorkingVertices(full);
    validity::Obstacle lower;
    lower.name = "lower door";
    lower.shape = validity::Shape::box({0.4, 1.2, 1.});
    lower.pose.translation() = Eigen::Vector3d(5., 2.5, 0.);
    validity::Obstacle upper = lower;
    upper.name = "upper door";
    upper.pose.translation() = Eigen::Vector3d(5., 7.5, 0.);
    f.setup.scene->add(lower);
    f.setup.scene->add(upper);
    f.query({1., 5., 0.}, {9., 5., 0.});
    // both gaps closed: the query fills its roadmap and gives up before the time is up, which is not a timeout
    ASSERT_EQ(f.solve(), ob::PlannerStatus::ABORT) << "both gaps closed";
    ASSERT_GE(f.planner->workingVertexCount(), full) << "the failed query filled the roadmap";
    // the doors open again: the next query starts from the learning roadmap near it, not from the thousands of
    // vertices the failed query left (each search would expand them)
    ASSERT_TRUE(f.setup.scene->remove("lower door"));
    ASSERT_TRUE(f.setup.scene->remove("upper door"));
    f.query({1., 5., 0.}, {9., 5., 0.});
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_LT(f.planner->workingVertexCount(), full / 2);
    EXPECT_TRUE(f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>()->check());
}

TEST(DualRoadmap, AblationLearnsNothing)
{
    ompl::RNG::setSeed(9);
    Fixture f;
    ASSERT_TRUE(f.planner->params().setParam("use_learning", "0"));
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    f.planner->notifySceneChanged();
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(f.planner->learningEdgeCount(), 0u);
    EXPECT_EQ(f.planner->seededEdgeCount(), 0u);
}

TEST(DualRoadmap, SaveAndLoadLearningRoadmap)
{
    ompl::RNG::setSeed(11);
    test::TempDir dir;
    Fixture f;
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    const std::string file = dir.path() + "/learning.txt";
    f.planner->saveLearningRoadmap(file);

    Fixture g;
    g.planner->loadLearningRoadmap(file);
    EXPECT_EQ(g.planner->learningEdgeCount(), f.planner->learningEdgeCount());
    EXPECT_EQ(g.planner->learningVertexCount(), f.planner->learningVertexCount());
    ASSERT_EQ(g.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_GT(g.planner->seededEdgeCount(), 0u) << "the loaded experience is used";
    const std::size_t learned = g.planner->learningEdgeCount();

    const std::string bad = dir.write("bad.txt", "michi-dual-roadmap 1\nspace 3 3 SE2\nvertices 2\n1 2\n");
    try
    {
        g.planner->loadLearningRoadmap(bad);
        FAIL() << "a truncated file must be rejected";
    }
    catch (const std::runtime_error &e)
    {
        EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
    EXPECT_EQ(g.planner->learningEdgeCount(), learned) << "a bad file changes nothing";
    const std::string other = dir.write("other.txt", "michi-dual-roadmap 1\nspace 7 7 Joints\nvertices 0\nedges 0\n");
    EXPECT_THROW(g.planner->loadLearningRoadmap(other), std::runtime_error);
    EXPECT_THROW(g.planner->loadLearningRoadmap(dir.path() + "/missing.txt"), std::runtime_error);
}

namespace
{
    /** Total planning work of a solve(): state and motion checks and samples (counts, never time). */
    std::uint64_t workOf(const planners::DualRoadmap &p)
    {
        const auto &w = p.lastWork();
        return w.stateChecks + w.motionChecks + w.samples;
    }

    /** Queries across the room while a door opens and closes the lower gap \e repeats times; the work of every
        query after the first opening and the first closing (the scenes seen before). */
    std::uint64_t repeatedChangeWork(bool learning, int repeats)
    {
        ompl::RNG::setSeed(21);
        Fixture f;
        f.planner->setUseLearning(learning);
        validity::Obstacle door;
        door.name = "door";
        door.shape = validity::Shape::box({0.4, 1.2, 1.});
        door.pose.translation() = Eigen::Vector3d(5., 2.5, 0.);
        std::uint64_t work = 0;
        for (int i = 0; i < repeats; ++i)
            for (const bool closed : {false, true})
            {
                if (closed)
                    f.setup.scene->add(door);
                else
                    f.setup.scene->remove("door");  // false (no change) before the first closing
                f.query({1., 1., 0.}, {9., 1., 0.});
                EXPECT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
                EXPECT_TRUE(f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>()->check());
                if (i > 0)
                    work += workOf(*f.planner);
            }
        return work;
    }
}  // namespace

TEST(DualRoadmap, LearningRoadmapReducesWorkOnARepeatedSceneChange)
{
    // Paper 002's point: experience pays when the world changes back and forth. The same scene changes with and
    // without the learning roadmap (the ablation rebuilds its roadmap at every change); work is counted in checks
    // and samples, so the test is deterministic (seeded) and independent of the machine's speed.
    const std::uint64_t with = repeatedChangeWork(true, 4);
    const std::uint64_t without = repeatedChangeWork(false, 4);
    RecordProperty("work_with_learning", std::to_string(with));  // in --gtest_output=xml, for docs/dual-roadmap.md
    RecordProperty("work_without_learning", std::to_string(without));
    EXPECT_GT(without, 0u);
    EXPECT_LT(2 * with, without) << "with learning " << with << ", without " << without;
}

TEST(DualRoadmap, SeedingFromTheLearningRoadmapReducesWorkAfterClear)
{
    ompl::RNG::setSeed(23);
    Fixture f;
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    const std::uint64_t first = workOf(*f.planner);
    // the working roadmap forgotten, the experience kept: the same query again is seeded from it
    f.planner->clear();
    f.query({1., 5., 0.}, {9., 5., 0.});
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_GT(f.planner->seededEdgeCount(), 0u);
    EXPECT_EQ(f.planner->lastWork().samples, 0u) << "the seeded local paths already join start and goal";
    EXPECT_LT(workOf(*f.planner), first);
}

TEST(DualRoadmap, ChangeConfinedToARegionKeepsWhatWasProvedElsewhere)
{
    ompl::RNG::setSeed(25);
    Fixture f;
    f.planner->setSmooth(false);  // shortcuts would try new motions; the point here is the roadmap's records
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    // an obstacle appears in the far corner, and the planner is told that nothing else changed
    validity::Obstacle box;
    box.name = "box";
    box.shape = validity::Shape::box({0.5, 0.5, 1.});
    box.pose.translation() = Eigen::Vector3d(9.5, 9.5, 0.);
    f.setup.scene->add(box);
    const auto space = f.setup.si->getStateSpace();
    f.planner->notifySceneChanged(
        [space](const ob::State *a, const ob::State *b)
        {
            std::vector<double> qa, qb;
            space->copyToReals(qa, a);
            space->copyToReals(qb, b);
            return std::max(qa[0], qb[0]) > 8.5 && std::max(qa[1], qb[1]) > 8.5;  // x, y near the box
        });
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(f.planner->lastWork().stateChecks + f.planner->lastWork().motionChecks, 0u)
        << "the same query's path lies away from the change: nothing to re-check";
    // a change without a region: everything on the path is checked again
    f.planner->notifySceneChanged();
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_GT(f.planner->lastWork().motionChecks, 0u);
    EXPECT_TRUE(f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>()->check());
}

namespace
{
    /** The fixture's query solved, then a small box put on the middle of the path's longest motion, away from its
        ends, and the same query solved again with \e probes edge probes; the box's centre in \e boxX, \e boxY. */
    planners::DualRoadmap::Work afterABoxOnThePath(unsigned int probes, double &boxX, double &boxY)
    {
        ompl::RNG::setSeed(31);
        Fixture f;
        f.planner->setSmooth(false);
        EXPECT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
        const auto *path = f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>();
        std::size_t longest = 0;
        for (std::size_t i = 0; i + 1 < path->getStateCount(); ++i)
            if (f.setup.si->distance(path->getState(i), path->getState(i + 1)) >
                f.setup.si->distance(path->getState(longest), path->getState(longest + 1)))
                longest = i;
        ob::ScopedState<> middle(f.setup.si);
        f.setup.si->getStateSpace()->interpolate(path->getState(longest), path->getState(longest + 1), 0.5,
                                                 middle.get());
        boxX = middle[0];
        boxY = middle[1];
        validity::Obstacle box;
        box.name = "box";
        box.shape = validity::Shape::box({0.3, 0.3, 1.});
        box.pose.translation() = Eigen::Vector3d(boxX, boxY, 0.);
        f.setup.scene->add(box);
        EXPECT_TRUE(f.setup.si->isValid(path->getState(longest)));  // the box leaves the motion's ends free
        EXPECT_TRUE(f.setup.si->isValid(path->getState(longest + 1)));
        f.planner->setEdgeProbes(probes);
        f.query({1., 5., 0.}, {9., 5., 0.});
        EXPECT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
        EXPECT_TRUE(f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>()->check());
        return f.planner->lastWork();
    }
}  // namespace

TEST(DualRoadmap, EdgeProbesRefuteABlockedMotionWithoutAMotionCheck)
{
    double x0 = 0., y0 = 0., x3 = 0., y3 = 0.;
    const auto without = afterABoxOnThePath(0, x0, y0);
    const auto with = afterABoxOnThePath(3, x3, y3);
    EXPECT_EQ(x0, x3);  // the same roadmap and box before the second query
    EXPECT_EQ(y0, y3);
    // the blocked motion costs a motion check without probes, a state check (its middle) with them
    EXPECT_LT(with.motionChecks, without.motionChecks)
        << "motion checks with probes " << with.motionChecks << ", without " << without.motionChecks;
    EXPECT_GT(with.stateChecks, without.stateChecks);
}

TEST(DualRoadmap, SearchWeightExpandsFewerVertices)
{
    // The same roadmap (a first query with a batch of 400 samples), then another query searched with weight 1 and
    // with weight 3 (the bound on the path's cost is RoadmapSearch's test).
    std::uint64_t expansions[2] = {0, 0};
    for (int i = 0; i < 2; ++i)
    {
        ompl::RNG::setSeed(33);
        Fixture f;
        f.planner->setSmooth(false);
        f.planner->setBatchSize(400);
        ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
        ASSERT_GE(f.planner->workingVertexCount(), 300u);  // the samples in the walls are dropped
        f.planner->setSearchWeight(i == 0 ? 1. : 3.);
        f.query({1., 9., 0.}, {9., 1., 0.});
        f.planner->notifySceneChanged();  // every record stale: the search meets unknown edges everywhere
        ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
        EXPECT_TRUE(f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>()->check());
        expansions[i] = f.planner->lastWork().expansions;
    }
    EXPECT_LT(2 * expansions[1], expansions[0])
        << "weight 3 expanded " << expansions[1] << " vertices, weight 1 " << expansions[0];
    Fixture f;
    EXPECT_THROW(f.planner->setSearchWeight(0.5), ompl::Exception);  // below 1 the heuristic would only mislead
    EXPECT_EQ(f.planner->params().getParam("search_weight")->getValue(), "1");
}

namespace
{
    /** The fixture's motion validator, summing the length of the motions it is asked about. */
    class LengthCountingValidator : public ob::MotionValidator
    {
    public:
        LengthCountingValidator(const ob::SpaceInformationPtr &si, ob::MotionValidatorPtr inner)
            : ob::MotionValidator(si), inner_(std::move(inner))
        {
        }
        bool checkMotion(const ob::State *a, const ob::State *b) const override
        {
            checked += si_->distance(a, b);
            return inner_->checkMotion(a, b);
        }
        bool checkMotion(const ob::State *a, const ob::State *b, std::pair<ob::State *, double> &last) const override
        {
            checked += si_->distance(a, b);
            return inner_->checkMotion(a, b, last);
        }
        mutable double checked{0.};

    private:
        ob::MotionValidatorPtr inner_;
    };

    /** The fixture's query solved (smoothed: long shortcut edges), a local change announced over the band
        x in [4.8, 5.2] (the wall, its gaps) with \e boxInBand a box put on the path there, and the query solved again
        with recheck depth \e depth. Returns the length of motion checked by the second solve; \e pathValid: its
        path holds in the new scene. */
    double recheckAfterABandChange(unsigned int depth, bool boxInBand, bool &pathValid)
    {
        ompl::RNG::setSeed(41);
        Fixture f;
        auto counter = std::make_shared<LengthCountingValidator>(f.setup.si, f.setup.si->getMotionValidator());
        f.setup.si->setMotionValidator(counter);
        f.planner->setRecheckDepth(depth);
        f.planner->setEdgeProbes(0);  // motions decided by their checks only
        EXPECT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
        if (boxInBand)
        {
            // on the path where it crosses x = 5 (through a gap)
            const auto *path = f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>();
            for (std::size_t i = 0; i + 1 < path->getStateCount(); ++i)
            {
                const auto *a = path->getState(i)->as<ob::SE2StateSpace::StateType>();
                const auto *b = path->getState(i + 1)->as<ob::SE2StateSpace::StateType>();
                if ((a->getX() - 5.) * (b->getX() - 5.) > 0.)
                    continue;
                const double t = (5. - a->getX()) / (b->getX() - a->getX());
                validity::Obstacle box;
                box.name = "box";
                box.shape = validity::Shape::box({0.3, 0.3, 1.});
                box.pose.translation() = Eigen::Vector3d(5., a->getY() + t * (b->getY() - a->getY()), 0.);
                f.setup.scene->add(box);
                break;
            }
        }
        const auto space = f.setup.si->getStateSpace();
        f.planner->notifySceneChanged(
            [space](const ob::State *a, const ob::State *b)
            {
                const double xa = a->as<ob::SE2StateSpace::StateType>()->getX();
                const double xb = b->as<ob::SE2StateSpace::StateType>()->getX();
                return std::max(xa, xb) >= 4.6 && std::min(xa, xb) <= 5.4;  // the band and the robot's half-size
            });
        if (!boxInBand)
        {
            // inside the wall, in the band: nothing really changes, but the scene's change counter moves
            validity::Obstacle inWall;
            inWall.name = "in_wall";
            inWall.shape = validity::Shape::box({0.2, 0.2, 1.});
            inWall.pose.translation() = Eigen::Vector3d(5., 5., 0.);
            f.setup.scene->add(inWall);
        }
        counter->checked = 0.;
        EXPECT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
        const double checked = counter->checked;
        pathValid = f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>()->check();
        return checked;
    }
}  // namespace

TEST(DualRoadmap, LocalChangeRechecksOnlyTheAffectedPartsOfALongEdge)
{
    bool valid = false;
    const double whole = recheckAfterABandChange(0, false, valid);
    EXPECT_TRUE(valid);
    const double parts = recheckAfterABandChange(4, false, valid);
    EXPECT_TRUE(valid);
    EXPECT_GT(whole, 0.) << "the path's edges across the band are stale and re-checked";
    // the path's edge across the band spans 2.7 m in x, the band with the robot 0.8 m: about 40 % in 1/16 parts
    EXPECT_GT(parts, 0.);
    EXPECT_LT(parts, 0.6 * whole) << "only the parts of them in the band";
}

TEST(DualRoadmap, PartialRecheckStillFindsAnObstacleInTheAffectedPart)
{
    bool valid = false;
    recheckAfterABandChange(4, true, valid);
    EXPECT_TRUE(valid) << "the box on the old path, inside the changed band, is seen";
}

TEST(DualRoadmap, PartialRecheckKeepsEveryPathValidUnderRandomLocalChanges)
{
    // Boxes appear one after another on the path just found, each announced with its region (the motions whose robot,
    // within its circumradius of the segment, can reach the box); every path returned after a change must hold in
    // the scene as it now is, though long edges are re-checked only in parts.
    ompl::RNG::setSeed(43);
    Fixture f;
    ASSERT_EQ(f.solve(), ob::PlannerStatus::EXACT_SOLUTION);
    ompl::RNG rng;
    const double robotRadius = 0.2 * std::sqrt(2.);
    int solved = 0;
    for (int i = 0; i < 25; ++i)
    {
        // on the last path found, at a random place along one of its motions (away from start and goal)
        const auto *last = f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>();
        ob::ScopedState<ob::SE2StateSpace> at(f.setup.si);
        const std::size_t k = rng.uniformInt(0, static_cast<int>(last->getStateCount()) - 2);
        f.setup.si->getStateSpace()->interpolate(last->getState(k), last->getState(k + 1), rng.uniform01(), at.get());
        const Eigen::Vector2d c(at->getX(), at->getY());
        // not at start or goal, and not in the wall's gaps (which a few boxes would close)
        if ((c - Eigen::Vector2d(1., 5.)).norm() < 1. || (c - Eigen::Vector2d(9., 5.)).norm() < 1. ||
            std::abs(c.x() - 5.) < 0.8)
            continue;
        const double h = rng.uniformReal(0.05, 0.2);
        validity::Obstacle box;
        box.name = "box" + std::to_string(i);
        box.shape = validity::Shape::box({2. * h, 2. * h, 1.});
        box.pose.translation() = Eigen::Vector3d(c.x(), c.y(), 0.);
        f.setup.scene->add(box);
        const double reach = h * std::sqrt(2.) + robotRadius + 1e-3;
        f.planner->notifySceneChanged(
            [c, reach](const ob::State *a, const ob::State *b)
            {
                const auto *sa = a->as<ob::SE2StateSpace::StateType>();
                const auto *sb = b->as<ob::SE2StateSpace::StateType>();
                const Eigen::Vector2d pa(sa->getX(), sa->getY()), d = Eigen::Vector2d(sb->getX(), sb->getY()) - pa;
                const double t = d.squaredNorm() > 0. ? std::clamp((c - pa).dot(d) / d.squaredNorm(), 0., 1.) : 0.;
                return (pa + t * d - c).norm() <= reach;
            });
        f.query({1., 5., 0.}, {9., 5., 0.});
        if (f.solve() != ob::PlannerStatus::EXACT_SOLUTION)
            break;  // no last path to put the next box on
        ++solved;
        EXPECT_TRUE(f.pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>()->check()) << "after box " << i;
    }
    EXPECT_GE(solved, 10);
}

TEST(DualRoadmap, EdgeProbesBeyondTheirRangeAreRefused)
{
    // Found 2026-12-07 through the C++ API: edge_probes 4294967295 made the probe loop endless (solve never
    // returned), 100,000,000 made a 0.5 s solve take 6 s.
    auto si = std::make_shared<ompl::base::SpaceInformation>(michi::state_spaces::makeSe2StateSpace(0., 1., 0., 1.));
    michi::planners::DualRoadmap planner(si);
    EXPECT_THROW(planner.setEdgeProbes(4294967295u), ompl::Exception);
    EXPECT_THROW(planner.params().setParam("edge_probes", "16"), ompl::Exception);
    EXPECT_TRUE(planner.params().setParam("edge_probes", "15"));
    EXPECT_EQ(planner.getEdgeProbes(), 15u);
}
