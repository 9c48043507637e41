// Tests of michi::validity::JMapMotionValidator and JMap::firstContact: motions checked as segments on the J-map
// never let a collision through (dense FCL re-check), lose no motion the FCL validator accepts in exact_fallback
// mode, give a valid last state, follow continuous joints the short way round, and pre-filter an arm with a hand.
#include "support/TestScenes.h"

#include <michi/tools/problem/ProblemJMap.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/validity/fcl/ConservativeMotionValidator.h>
#include <michi/validity/jmap/JMapMotionValidator.h>
#include <michi/validity/jmap/PlanarArm.h>

#include <ompl/base/ScopedState.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace michi;
namespace ob = ompl::base;

namespace
{
    /** A bundled problem planned with the J-map checker (the J-map motion validator comes with it). */
    struct JMapPlanning
    {
        tools::Problem problem;
        tools::PlanningContext ctx;

        explicit JMapPlanning(const std::string &name, const std::string &mode = "conservative")
            : problem(load(name, mode)), ctx(tools::makePlanningContext(problem))
        {
        }

        static tools::Problem load(const std::string &name, const std::string &mode)
        {
            auto p = tools::loadProblem(test::sourcePath("problems/" + name + ".yaml"));
            p.checker = "jmap";
            p.jmap.mode = mode == "conservative" ? validity::JMapCheckerSettings::Mode::CONSERVATIVE
                                                 : validity::JMapCheckerSettings::Mode::EXACT_FALLBACK;
            return p;
        }

        ob::SpaceInformationPtr si() const
        {
            return ctx.setup->getSpaceInformation();
        }

        std::shared_ptr<validity::JMapMotionValidator> validator() const
        {
            return std::dynamic_pointer_cast<validity::JMapMotionValidator>(si()->getMotionValidator());
        }
    };

    /** Whether the exact FCL checker finds a colliding state on the motion at \e samples + 1 points. */
    bool denseMotionCollides(const ob::SpaceInformation &si, const validity::FclValidityChecker &fcl,
                             const ob::State *a, const ob::State *b, int samples = 2000)
    {
        ob::State *s = si.allocState();
        bool hit = false;
        for (int i = 0; i <= samples && !hit; ++i)
        {
            si.getStateSpace()->interpolate(a, b, static_cast<double>(i) / samples, s);
            hit = !fcl.isValid(s);
        }
        si.freeState(s);
        return hit;
    }

    /** A state the checker \e valid accepts, drawn uniformly. */
    void sampleValid(const ob::SpaceInformation &si, const ob::StateValidityChecker &valid, ob::State *s)
    {
        auto sampler = si.allocStateSampler();
        do
            sampler->sampleUniform(s);
        while (!valid.isValid(s));
    }
}  // namespace

TEST(JMapFirstContact, IsTheFirstSampleInsideThePolygons)
{
    ompl::RNG::setSeed(11);
    const JMapPlanning p("planar_2link");
    validity::JMapCheckerSettings one = p.problem.jmap;
    one.tiles = 1;
    const auto checker = tools::makeJMapChecker(p.problem, p.ctx, one);
    const validity::JMap &map = checker->tile(0.);
    ompl::RNG rng;
    int hits = 0, misses = 0;
    for (int n = 0; n < 1500; ++n)
    {
        const double x0 = rng.uniformReal(map.lo1(), map.hi1()), y0 = rng.uniformReal(map.lo2(), map.hi2());
        // short and long segments, some vertical and horizontal
        const double len = n % 3 == 0 ? 3. : 0.4;
        double x1 = x0 + rng.uniformReal(-len, len), y1 = y0 + rng.uniformReal(-len, len);
        if (n % 10 == 1)
            x1 = x0;
        if (n % 10 == 2)
            y1 = y0;
        const double t = map.firstContact(x0, y0, x1, y1);
        const int samples = 4000;
        int first = -1;
        for (int i = 0; i <= samples && first < 0; ++i)
        {
            const double s = static_cast<double>(i) / samples;
            if (map.collides(x0 + s * (x1 - x0), y0 + s * (y1 - y0)))
                first = i;
        }
        if (first < 0)
        {
            // a segment may graze a corner between two samples; then the contact is on the boundary
            if (t <= 1.)
                EXPECT_LT(map.distanceToBoundary(x0 + t * (x1 - x0), y0 + t * (y1 - y0), 1.), 1e-6)
                    << "segment " << n << " free at every sample, contact " << t << " off the boundary";
            ++misses;
            continue;
        }
        ++hits;
        ASSERT_LE(t, static_cast<double>(first) / samples + 1e-12)
            << "segment " << n << " enters later than a sample inside";
        const double xc = x0 + t * (x1 - x0), yc = y0 + t * (y1 - y0);
        EXPECT_TRUE(map.collides(xc, yc) || map.distanceToBoundary(xc, yc, 1.) < 1e-9)
            << "segment " << n << ": contact " << t << " is not on a polygon";
        if (first > 0)
            EXPECT_GT(t, static_cast<double>(first - 1) / samples - 1e-12)
                << "segment " << n << ": contact before a sample that is outside";
    }
    EXPECT_GT(hits, 200);
    EXPECT_GT(misses, 200);
}

TEST(JMapMotionValidator, NeverLetsACollisionThroughOnPlanar2Link)
{
    ompl::RNG::setSeed(5);
    const JMapPlanning p("planar_2link");
    const auto mv = p.validator();
    ASSERT_NE(mv, nullptr) << "--checker jmap installs the J-map motion validator";
    ASSERT_TRUE(p.ctx.jmap->answersAlone());
    const auto si = p.si();
    ob::ScopedState<> a(si), b(si), last(si);
    int valid = 0, invalid = 0;
    for (int n = 0; n < 300; ++n)
    {
        sampleValid(*si, *p.ctx.jmap, a.get());
        sampleValid(*si, *p.ctx.jmap, b.get());
        const bool mine = mv->checkMotion(a.get(), b.get());
        const bool fcl = mv->fallback()->checkMotion(a.get(), b.get());
        if (mine)
        {
            ++valid;
            EXPECT_FALSE(denseMotionCollides(*si, *p.ctx.checker, a.get(), b.get())) << "motion " << n;
            EXPECT_TRUE(fcl) << "motion " << n << ": free on the map, so free for the exact validator";
            continue;
        }
        ++invalid;
        std::pair<ob::State *, double> lastValid{last.get(), -1.};
        EXPECT_FALSE(mv->checkMotion(a.get(), b.get(), lastValid));
        ASSERT_GE(lastValid.second, 0.);
        ASSERT_LT(lastValid.second, 1.);
        EXPECT_TRUE(p.ctx.jmap->isValid(last.get())) << "motion " << n << ": last valid state is inside a polygon";
        EXPECT_TRUE(mv->checkMotion(a.get(), last.get())) << "motion " << n << ": the part up to it is not free";
    }
    EXPECT_GT(valid, 30);
    EXPECT_GT(invalid, 30);
}

TEST(JMapMotionValidator, ExactFallbackLosesNoMotionTheExactValidatorAccepts)
{
    ompl::RNG::setSeed(6);
    const JMapPlanning p("planar_2link", "exact_fallback");
    const auto mv = p.validator();
    ASSERT_NE(mv, nullptr);
    const auto si = p.si();
    ob::ScopedState<> a(si), b(si);
    int valid = 0;
    for (int n = 0; n < 200; ++n)
    {
        sampleValid(*si, *p.ctx.checker, a.get());
        sampleValid(*si, *p.ctx.checker, b.get());
        const bool mine = mv->checkMotion(a.get(), b.get()), fcl = mv->fallback()->checkMotion(a.get(), b.get());
        EXPECT_EQ(mine, fcl) << "motion " << n;
        valid += mine;
    }
    EXPECT_GT(valid, 20);
}

TEST(JMapMotionValidator, PreFiltersAnArmWithAHand)
{
    ompl::RNG::setSeed(7);
    const JMapPlanning p("planar_3dof_hand");
    const auto mv = p.validator();
    ASSERT_NE(mv, nullptr);
    ASSERT_FALSE(p.ctx.jmap->answersAlone());
    const auto si = p.si();
    ob::ScopedState<> a(si), b(si);
    int valid = 0;
    for (int n = 0; n < 150; ++n)
    {
        sampleValid(*si, *p.ctx.jmap, a.get());
        sampleValid(*si, *p.ctx.jmap, b.get());
        if (!mv->checkMotion(a.get(), b.get()))
            continue;
        ++valid;
        EXPECT_FALSE(denseMotionCollides(*si, *p.ctx.checker, a.get(), b.get())) << "motion " << n;
    }
    EXPECT_GT(valid, 5);
}

TEST(JMapMotionValidator, FollowsContinuousJointsTheShortWayRound)
{
    // a continuous-joint arm; obstacle 1 is hit only with the arm pointing along -x (theta1 = pi), obstacle 2
    // only along +x (theta1 = 0). From theta1 = 3 to -2.9 OMPL's SO(2) goes through pi, not through 0.
    test::PlanarArmOptions options;
    options.continuous = true;
    for (const bool blockPi : {true, false})
    {
        const auto obstacle =
            blockPi ? test::boxOutline({-0.85, -0.05}, {-0.7, 0.05}) : test::boxOutline({0.7, -0.05}, {0.85, 0.05});
        auto setup = test::planarArmSetup({0.5, 0.4}, {obstacle}, options);
        auto arm = validity::PlanarArm::fromModel(*setup.model);
        auto polygons = setup.scene->polygons2d();
        auto jmap = std::make_shared<validity::JMapValidityChecker>(
            setup.si, setup.checker,
            [arm, polygons](const validity::JMapAxes &axes)
            {
                return std::make_shared<validity::PlanarIntervalSource>(arm, polygons, axes);
            },
            validity::planarAxes(*arm, 0, 1), true);
        validity::JMapMotionValidator mv(
            setup.si, jmap, std::make_shared<validity::ConservativeMotionValidator>(setup.si, setup.checker));
        ob::ScopedState<> a(setup.si), b(setup.si);
        a = std::vector<double>{3.0, 0.};
        b = std::vector<double>{-2.9, 0.};  // not symmetric: OMPL's SO(2) rejects a sample landing on pi itself
        ASSERT_TRUE(jmap->isValid(a.get()) && jmap->isValid(b.get()));
        const bool exactHit = denseMotionCollides(*setup.si, *setup.checker, a.get(), b.get());
        EXPECT_EQ(exactHit, blockPi) << "the scene is not what the test means";
        EXPECT_EQ(mv.checkMotion(a.get(), b.get()), !blockPi)
            << (blockPi ? "the motion through pi collides" : "the motion through pi is free");
    }
}
