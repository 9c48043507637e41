/* J-map (paper 000): exact intervals, FCL-sweep intervals, polygons (containment, tightness), point queries,
   stacks, grown maps and bottlenecks. Deterministic: fixed seeds through local ompl::RNG instances. */

#include <michi/validity/jmap/JMap.h>
#include <michi/validity/jmap/PlanarArm.h>
#include <michi/tools/problem/Problem.h>
#include <michi/tools/bench/PlanningContext.h>

#include "support/TestScenes.h"

#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>

namespace bg = boost::geometry;
using namespace michi;
using namespace michi::validity;

namespace
{
    struct PlanarCase
    {
        tools::Problem problem;
        PlanarArmPtr arm;
        MultiPolygon2 obstacles;
    };

    PlanarCase loadPlanar(const std::string &name)
    {
        PlanarCase c{tools::loadProblem(test::sourcePath("problems/" + name + ".yaml")), nullptr, {}};
        c.arm = PlanarArm::fromModel(*c.problem.model);
        c.obstacles = c.problem.scene->polygons2d();
        return c;
    }

    MultiPolygon2 toPolygons(const std::vector<test::Outline> &outlines)
    {
        MultiPolygon2 out;
        for (const auto &o : outlines)
        {
            std::vector<Point2> pts;
            for (const auto &p : o)
                pts.emplace_back(p.x(), p.y());
            MultiPolygon2 merged;
            bg::union_(out, makePolygon2(pts), merged);
            out = std::move(merged);
        }
        return out;
    }

    bool inIntervals(const std::vector<JointInterval> &intervals, double t, double slack = 0.)
    {
        for (const auto &i : intervals)
            if (t >= i.lo - slack && t <= i.hi + slack)
                return true;
        return false;
    }

    /** Containment and tightness of a map against the exact test on uniform samples. */
    struct Sampled
    {
        int samples{0};
        int colliding{0};
        int missed{0};        ///< exact collision outside the polygons: must be 0
        int falseInvalid{0};  ///< inside the polygons but free
        int inside{0};
    };

    Sampled sampleMap(const JMap &map, const JMapIntervalSource &exact, int n, std::uint_fast32_t seed)
    {
        ompl::RNG rng(seed);
        Sampled s;
        for (int k = 0; k < n; ++k)
        {
            const double t1 = rng.uniformReal(map.lo1(), map.hi1());
            const double t2 = rng.uniformReal(map.lo2(), map.hi2());
            const bool truth = exact.collides(t1, t2);
            const bool mapped = map.collides(t1, t2);
            ++s.samples;
            s.colliding += truth;
            s.inside += mapped;
            if (truth && !mapped)
            {
                if (s.missed < 5)
                    std::cout << "  missed (" << t1 << ", " << t2 << ")\n";
                ++s.missed;
            }
            s.falseInvalid += mapped && !truth;
        }
        return s;
    }
}  // namespace

TEST(PlanarArm, FromPlanar2LinkUrdf)
{
    const auto c = loadPlanar("planar_2link");
    ASSERT_EQ(c.arm->variableCount(), 2u);
    const auto lengths = c.arm->linkLengths();
    EXPECT_NEAR(lengths[0], 0.5, 1e-7);
    EXPECT_NEAR(lengths[1], 0.4, 1e-7);
    std::vector<double> q{0.3, -0.7};
    std::vector<int> owner;
    const auto caps = c.arm->worldCapsules(q.data(), &owner);
    ASSERT_EQ(caps.size(), 3u);  // base disk, link1, link2
    const auto pts = test::planarArmPoints({0.5, 0.4}, q);
    for (std::size_t i = 0; i < caps.size(); ++i)
    {
        const std::string &name = c.arm->links()[owner[i]].name;
        EXPECT_NEAR(caps[i].radius, name == "base_link" ? 0.04 : 0.01, 1e-12) << name;
        if (name == "link2")
        {
            EXPECT_NEAR((caps[i].a - pts[1]).norm() + (caps[i].b - pts[2]).norm(), 0., 1e-7);
            EXPECT_NEAR(c.arm->reachFrom(0, owner[i]), 0.9, 1e-7);
            EXPECT_NEAR(c.arm->reachFrom(1, owner[i]), 0.4, 1e-7);
            EXPECT_TRUE(c.arm->moves(1, owner[i]));
        }
        if (name == "base_link")
        {
            EXPECT_NEAR(caps[i].a.norm() + caps[i].b.norm(), 0., 1e-12);
            EXPECT_FALSE(c.arm->moves(0, owner[i]));
        }
    }
}

TEST(JMapIntervals, OneSquareHandComputed)
{
    // L1 = L2 = 1, links are capsules of radius 0.05; one square [0.75, 1.25] x [0.5, 1.0]
    test::PlanarArmOptions options;
    options.linkRadius = 0.05;
    const auto arm = PlanarArm::fromModel(*test::planarArmModel({1., 1.}, options));
    const auto obstacles = toPolygons({test::boxOutline({0.75, 0.5}, {1.25, 1.0})});
    PlanarIntervalSource source(arm, obstacles, planarAxes(*arm, 0, 1));
    // theta1 = 0: link 2 turns about (1, 0); its centre line first passes at 0.05 from the corner (1.25, 0.5)
    // and, by symmetry, last leaves the corner (0.75, 0.5)
    const double d = std::hypot(0.25, 0.5), alpha = std::atan2(0.5, 0.25);
    const double first = alpha - std::asin(0.05 / d);
    auto iv = source.intervals(0.);
    ASSERT_EQ(iv.size(), 1u);
    EXPECT_NEAR(iv[0].lo, first, 1e-8);
    EXPECT_NEAR(iv[0].hi, M_PI - first, 1e-8);
    // theta1 = pi/2: the elbow is at (0, 1), level with the square's top; link 2's absolute angle phi =
    // pi/2 + theta2. Upper end: the line passes 0.05 above the corner (0.75, 1); lower end: 0.05 below the
    // corner (0.75, 0.5)
    iv = source.intervals(M_PI / 2);
    ASSERT_EQ(iv.size(), 1u);
    const double d2 = std::hypot(0.75, 0.5), alpha2 = std::atan2(-0.5, 0.75);
    EXPECT_NEAR(iv[0].hi, std::asin(0.05 / 0.75) - M_PI / 2, 1e-8);
    EXPECT_NEAR(iv[0].lo, alpha2 - std::asin(0.05 / d2) - M_PI / 2, 1e-8);
    // brute force: dense samples agree with the intervals
    for (int k = 0; k <= 20000; ++k)
    {
        const double t2 = -M_PI + 2. * M_PI * k / 20000;
        const bool hit = source.collides(M_PI / 2, t2);
        EXPECT_EQ(hit, inIntervals(iv, t2)) << t2;
    }
}

namespace
{
    test::RandomPolygonOptions randomSceneOptions()
    {
        test::RandomPolygonOptions o;
        o.count = 6;
        o.lo = {-1., -1.};
        o.hi = {1., 1.};
        o.minRadius = 0.05;
        o.maxRadius = 0.18;
        o.keepClearRadius = 0.08;  // keep the base free
        return o;
    }

    PlanarArmPtr randomArm(double radius = 0.02)
    {
        test::PlanarArmOptions options;
        options.linkRadius = radius;
        return PlanarArm::fromModel(*test::planarArmModel({0.5, 0.4}, options));
    }
}  // namespace

TEST(JMapIntervals, MatchBruteForceOnRandomScenes)
{
    const auto arm = randomArm();
    for (std::uint_fast32_t seed = 1; seed <= 6; ++seed)
    {
        const auto obstacles = toPolygons(test::randomPolygons(seed, randomSceneOptions()));
        PlanarIntervalSource source(arm, obstacles, planarAxes(*arm, 0, 1));
        for (int i = 0; i < 12; ++i)
        {
            const double t1 = -M_PI + (i + 0.37) * 2. * M_PI / 12;
            const auto iv = source.intervals(t1);
            for (std::size_t k = 1; k < iv.size(); ++k)
                EXPECT_LT(iv[k - 1].hi, iv[k].lo);
            for (int k = 0; k <= 8000; ++k)
            {
                const double t2 = -M_PI + 2. * M_PI * k / 8000;
                const bool hit = source.collides(t1, t2);
                // exact both ways, up to the 1e-9 padding of the ends
                if (hit)
                    EXPECT_TRUE(inIntervals(iv, t2)) << "seed " << seed << " at (" << t1 << ", " << t2 << ")";
                else
                    EXPECT_FALSE(inIntervals(iv, t2, -2e-9)) << "seed " << seed << " at (" << t1 << ", " << t2 << ")";
            }
        }
    }
}

TEST(JMapIntervals, CellIntervalsContainEveryTheta1OfTheCell)
{
    const auto arm = randomArm();
    for (std::uint_fast32_t seed = 11; seed <= 14; ++seed)
    {
        const auto obstacles = toPolygons(test::randomPolygons(seed, randomSceneOptions()));
        for (int sub : {1, 3})
        {
            PlanarIntervalSource source(arm, obstacles, planarAxes(*arm, 0, 1));
            source.setSubsamples(sub);
            const double h = 2. * M_PI / 36;
            for (int cell = 0; cell < 36; cell += 5)
            {
                const double lo = -M_PI + cell * h, hi = lo + h;
                const auto outer = source.cellIntervals(lo, hi);
                for (int j = 0; j <= 10; ++j)
                {
                    const double t1 = lo + j * h / 10;
                    for (const auto &i : source.intervals(t1))
                    {
                        EXPECT_TRUE(inIntervals(outer, i.lo) && inIntervals(outer, i.hi))
                            << "seed " << seed << " theta1 " << t1;
                        for (const auto &o : outer)
                            if (o.lo <= i.lo && i.lo <= o.hi)
                                EXPECT_LE(i.hi, o.hi);
                    }
                }
            }
        }
    }
}

TEST(JMapPolygons, LineWalkKeepsPointsInside)
{
    // collinear points collapse to the two ends
    std::vector<Point2> line;
    for (int i = 0; i <= 10; ++i)
        line.emplace_back(0.1 * i, 0.5 + 0.02 * i);
    EXPECT_EQ(lineWalk(line, 0.01, true).size(), 2u);
    // a bump: the upper walk keeps points so that no point lies above the result; the lower one below
    std::vector<Point2> bump;
    for (int i = 0; i <= 20; ++i)
        bump.emplace_back(0.05 * i, 0.3 * std::exp(-std::pow((i - 10) / 3., 2)));
    for (bool upper : {true, false})
        for (double r : {0.001, 0.05, 0.5})
        {
            const auto kept = lineWalk(bump, r, upper);
            EXPECT_EQ(kept.front().x(), bump.front().x());
            EXPECT_EQ(kept.back().x(), bump.back().x());
            for (const auto &p : bump)
            {
                // height of the kept polyline at p.x
                for (std::size_t k = 0; k + 1 < kept.size(); ++k)
                    if (kept[k].x() <= p.x() && p.x() <= kept[k + 1].x())
                    {
                        const double t = (p.x() - kept[k].x()) / (kept[k + 1].x() - kept[k].x());
                        const double y = kept[k].y() + t * (kept[k + 1].y() - kept[k].y());
                        if (upper)
                            EXPECT_GE(y, p.y() - 1e-15);
                        else
                            EXPECT_LE(y, p.y() + 1e-15);
                        // and within r of it (the paper's circles), plus the slope's effect
                        if (upper)
                            EXPECT_LE(y - p.y(), r / std::cos(std::atan(6.)) + 1e-12);
                    }
            }
            if (r >= 0.5 && upper)
                EXPECT_LT(kept.size(), 6u);
        }
}

TEST(JMapPolygons, SplitsMergesAndBordersAreEnclosed)
{
    // hand-made slices: a region that splits into two and merges again, one touching the theta2 limits
    std::vector<JMapSlice> slices;
    const int n = 12;
    for (int i = 0; i < n; ++i)
    {
        JMapSlice s;
        s.lo = -M_PI + i * 2. * M_PI / n;
        s.hi = s.lo + 2. * M_PI / n;
        s.theta1 = 0.5 * (s.lo + s.hi);
        if (i >= 2 && i <= 9)
        {
            if (i >= 4 && i <= 7)
                s.intervals = {{-0.8, -0.2}, {0.3, 0.9}};
            else
                s.intervals = {{-0.8, 0.9}};
        }
        if (i >= 8)
            s.intervals.push_back({2.5, M_PI});  // touches the upper limit
        s.intervals = mergeIntervals(s.intervals);
        s.trueIntervals = s.intervals;
        slices.push_back(s);
    }
    JMapSettings settings;
    settings.slices = n;
    settings.tolerance = 0.05;
    const auto map = JMap::fromSlices(slices, -M_PI, M_PI, settings);
    EXPECT_EQ(map->polygons().size(), 2u);
    std::string reason;
    EXPECT_TRUE(bg::is_valid(map->polygons(), reason)) << reason;
    // the ring region keeps its hole (free between the two branches)
    bool hole = false;
    for (const auto &p : map->polygons())
        hole = hole || !p.inners().empty();
    EXPECT_TRUE(hole);
    for (const auto &s : slices)
        for (const auto &i : s.intervals)
            for (int a = 0; a <= 10; ++a)
                for (int b = 0; b <= 10; ++b)
                {
                    const double x = s.lo + a * (s.hi - s.lo) / 10, y = i.lo + b * (i.hi - i.lo) / 10;
                    EXPECT_TRUE(map->collides(x, y)) << x << ", " << y;
                }
    EXPECT_FALSE(map->collides(0., 0.05));   // in the hole
    EXPECT_TRUE(map->collides(M_PI, M_PI));  // a corner of the map, on the limits
    EXPECT_FALSE(map->collides(-3., 0.));
}

TEST(JMap, Planar2LinkContainmentAndTightness)
{
    const auto c = loadPlanar("planar_2link");
    PlanarIntervalSource source(c.arm, c.obstacles, planarAxes(*c.arm, 0, 1));
    const auto map = JMap::build(source);
    ASSERT_EQ(map->slices().size(), 72u);
    std::string reason;
    EXPECT_TRUE(bg::is_valid(map->polygons(), reason)) << reason;
    const auto s = sampleMap(*map, source, 100000, 42);
    EXPECT_EQ(s.missed, 0);
    const double falseInvalid = double(s.falseInvalid) / s.samples;
    std::cout << "planar_2link: " << map->polygons().size() << " polygons, build " << map->buildSeconds()
              << " s, colliding " << double(s.colliding) / s.samples << ", inside polygons "
              << double(s.inside) / s.samples << ", false-invalid " << falseInvalid << " of all samples, "
              << double(s.falseInvalid) / std::max(1, s.inside) << " of those inside" << std::endl;
    EXPECT_LT(falseInvalid, 0.06);  // measured 0.036 (72 slices x 2 columns, r = 0.03)
    // every true segment of every slice is inside the polygons
    for (const auto &slice : map->slices())
        for (const auto &i : slice.trueIntervals)
            for (int b = 0; b <= 20; ++b)
                EXPECT_TRUE(map->collides(slice.theta1, i.lo + b * (i.hi - i.lo) / 20));

    // and so is every state the FCL checker rejects (capsules contain the URDF's cylinders)
    const auto context = tools::makePlanningContext(c.problem);
    ompl::RNG rng(7);
    int fclMissed = 0;
    for (int k = 0; k < 100000; ++k)
    {
        const double q[2] = {rng.uniformReal(-M_PI, M_PI), rng.uniformReal(-M_PI, M_PI)};
        if (!context.checker->isValidConfiguration(q) && !map->collides(q[0], q[1]))
            ++fclMissed;
    }
    EXPECT_EQ(fclMissed, 0);
}

TEST(JMap, RandomScenesContainment)
{
    const auto arm = randomArm();
    int totalInside = 0, totalFalse = 0, totalSamples = 0;
    for (std::uint_fast32_t seed = 100; seed < 124; ++seed)
    {
        const auto obstacles = toPolygons(test::randomPolygons(seed, randomSceneOptions()));
        PlanarIntervalSource source(arm, obstacles, planarAxes(*arm, 0, 1));
        JMapSettings settings;
        settings.slices = seed % 3 == 0 ? 36 : 72;
        settings.tolerance = seed % 2 == 0 ? 0.03 : 0.1;
        settings.columns = 1 + seed % 3;
        source.setSubsamples(seed % 4 == 1 ? 2 : 1);
        const auto map = JMap::build(source, settings);
        std::string reason;
        EXPECT_TRUE(bg::is_valid(map->polygons(), reason)) << "seed " << seed << ": " << reason;
        const auto s = sampleMap(*map, source, 10000, seed);
        EXPECT_EQ(s.missed, 0) << "seed " << seed;
        totalInside += s.inside;
        totalFalse += s.falseInvalid;
        totalSamples += s.samples;
    }
    std::cout << "random scenes: false-invalid " << double(totalFalse) / totalSamples << " of all samples" << std::endl;
}

TEST(JMap, BuildReportsEverySliceAndTheMapForgetsTheCallback)
{
    // `michi jmap` on an arm swept by FCL runs for minutes: it prints how far the build got from this callback
    const auto c = loadPlanar("planar_2link");
    PlanarIntervalSource source(c.arm, c.obstacles, planarAxes(*c.arm, 0, 1));
    JMapSettings settings;
    settings.slices = 12;
    std::vector<std::pair<int, int>> calls;
    settings.progress = [&calls](int done, int total)
    {
        calls.emplace_back(done, total);
    };
    const auto map = JMap::build(source, settings);
    ASSERT_EQ(calls.size(), 12u);
    for (int i = 0; i < 12; ++i)
        EXPECT_EQ(calls[i], std::make_pair(i + 1, 12));
    EXPECT_FALSE(map->settings().progress);
}

TEST(JMap, QueriesMatchBoostGeometry)
{
    const auto c = loadPlanar("planar_2link");
    PlanarIntervalSource source(c.arm, c.obstacles, planarAxes(*c.arm, 0, 1));
    JMapSettings settings;
    settings.slices = 36;
    const auto map = JMap::build(source, settings);
    bg::model::multi_linestring<Linestring2> boundary;
    for (const auto &p : map->polygons())
    {
        boundary.push_back(Linestring2(p.outer().begin(), p.outer().end()));
        for (const auto &inner : p.inners())
            boundary.push_back(Linestring2(inner.begin(), inner.end()));
    }
    ompl::RNG rng(3);
    for (int k = 0; k < 20000; ++k)
    {
        const Point2 p(rng.uniformReal(-M_PI, M_PI), rng.uniformReal(-M_PI, M_PI));
        const double d = bg::distance(p, boundary);
        if (d > 1e-9)
            EXPECT_EQ(map->collides(p.x(), p.y()), bg::covered_by(p, map->polygons())) << p.x() << ", " << p.y();
        EXPECT_NEAR(map->distanceToBoundary(p.x(), p.y(), 0.2), std::min(d, 0.2), 1e-12);
    }
    // near the edges, where the index's raster cells are mixed or border mixed ones (a cell an edge touches but the
    // raster missed would answer by its centre, wrongly, on one side of the edge)
    std::vector<std::pair<Point2, Point2>> edges;
    for (const auto &line : boundary)
        for (std::size_t i = 0; i + 1 < line.size(); ++i)
            edges.emplace_back(line[i], line[i + 1]);
    ASSERT_FALSE(edges.empty());
    int checked = 0;
    for (int k = 0; k < 40000; ++k)
    {
        const auto &e = edges[static_cast<std::size_t>(rng.uniformInt(0, static_cast<int>(edges.size()) - 1))];
        const double t = rng.uniform01(), r = rng.uniformReal(0., 0.03), a = rng.uniformReal(-M_PI, M_PI);
        const Point2 p(e.first.x() + t * (e.second.x() - e.first.x()) + r * std::cos(a),
                       e.first.y() + t * (e.second.y() - e.first.y()) + r * std::sin(a));
        if (bg::distance(p, boundary) <= 1e-9)
            continue;
        ++checked;
        ASSERT_EQ(map->collides(p.x(), p.y()), bg::covered_by(p, map->polygons())) << p.x() << ", " << p.y();
    }
    EXPECT_GT(checked, 39000);
}

TEST(JMap, AnEdgeAnUlpOffVerticalStopsTheSegmentsThatCrossIt)
{
    // Found by the safety sweep of 2026-12-07: a union of J-map tiles left an edge from x = -0.043633231299858251 to
    // -0.043633231299858244 (one ulp apart, on a slice border). Stored as a sloped edge of slope 1e15 in a slab 7e-18
    // wide, its heights rounded so far off that firstContact() called 42 segments that cross it free, and the
    // J-map motion validator accepted motions into the polygon.
    const double xa = -0.043633231299858251, xb = std::nextafter(xa, 1.);
    ASSERT_NE(xa, xb);
    Polygon2 square;
    // clockwise, closed (Boost.Geometry's default); the left side is the near-vertical edge
    bg::append(square.outer(), Point2(xa, -0.3));
    bg::append(square.outer(), Point2(xb, 0.2));
    bg::append(square.outer(), Point2(0.4, 0.2));
    bg::append(square.outer(), Point2(0.4, -0.3));
    bg::append(square.outer(), Point2(xa, -0.3));
    ASSERT_TRUE(bg::is_valid(square));
    MultiPolygon2 polygons;
    polygons.push_back(square);
    const auto map = JMap::fromPolygons(polygons, -M_PI, M_PI, -M_PI, M_PI);
    ompl::RNG rng(11);
    int crossing = 0;
    for (int k = 0; k < 20000; ++k)
    {
        // from left of the edge to inside the square, at every height and slant
        const double y0 = rng.uniformReal(-0.29, 0.19), y1 = rng.uniformReal(-0.29, 0.19);
        const double x0 = xa - rng.uniformReal(1e-6, 0.05), x1 = xa + rng.uniformReal(1e-6, 0.3);
        ASSERT_FALSE(map->collides(x0, y0));
        ASSERT_TRUE(map->collides(x1, y1)) << x1 << ", " << y1;
        const double t = map->firstContact(x0, y0, x1, y1);
        ASSERT_TRUE(std::isfinite(t)) << "(" << x0 << ", " << y0 << ") -> (" << x1 << ", " << y1 << ")";
        // it meets the square where it crosses the edge, not later
        EXPECT_LE(x0 + t * (x1 - x0), xb + 1e-9);
        ++crossing;
    }
    EXPECT_EQ(crossing, 20000);
}

namespace
{
    /** A 2-link arm made of spheres: its x-y view (disks) is exactly what FCL checks. */
    RobotModelPtr ballArm()
    {
        const std::string limit =
            "<limit lower=\"-3.14159265359\" upper=\"3.14159265359\" effort=\"1\" velocity=\"1\"/>";
        auto ball = [](double x, double r)
        {
            return "<collision><origin xyz=\"" + std::to_string(x) + " 0 0\"/><geometry><sphere radius=\"" +
                   std::to_string(r) + "\"/></geometry></collision>";
        };
        const std::string xml =
            "<robot name=\"balls\"><link name=\"base_link\"/>"
            "<joint name=\"joint1\" type=\"revolute\"><parent link=\"base_link\"/>"
            "<child link=\"link1\"/><origin xyz=\"0 0 0\"/><axis xyz=\"0 0 1\"/>" +
            limit + "</joint><link name=\"link1\">" + ball(0.3, 0.06) + ball(0.5, 0.05) +
            "</link><joint name=\"joint2\" type=\"revolute\"><parent link=\"link1\"/>"
            "<child link=\"link2\"/><origin xyz=\"0.5 0 0\"/><axis xyz=\"0 0 1\"/>" +
            limit + "</joint><link name=\"link2\">" + ball(0.2, 0.05) + ball(0.4, 0.04) + "</link></robot>";
        return RobotModel::fromUrdfString(xml, "balls.urdf", "/tmp");
    }
}  // namespace

TEST(FclIntervals, ContainExactIntervalsOfABallArm)
{
    const auto model = ballArm();
    const auto arm = PlanarArm::fromModel(*model);
    for (std::uint_fast32_t seed = 31; seed <= 33; ++seed)
    {
        const auto outlines = test::randomPolygons(seed, randomSceneOptions());
        const auto setup = test::robotSetup(model, test::polygonScene(outlines));
        const auto obstacles = setup.scene->polygons2d();
        PlanarIntervalSource exact(arm, obstacles, planarAxes(*arm, 0, 1));
        FclIntervalSource fcl(setup.checker, planarAxes(*arm, 0, 1));
        const double h = 2. * M_PI / 24;
        for (int cell = 0; cell < 24; cell += 3)
        {
            const double lo = -M_PI + cell * h, hi = lo + h;
            const auto outer = fcl.cellIntervals(lo, hi);
            for (int j = 0; j <= 4; ++j)
            {
                const double t1 = lo + j * h / 4;
                const auto atT1 = fcl.intervals(t1);
                for (const auto &i : exact.intervals(t1))
                    for (int b = 0; b <= 10; ++b)
                    {
                        const double t2 = i.lo + b * (i.hi - i.lo) / 10;
                        EXPECT_TRUE(inIntervals(outer, t2)) << "seed " << seed << " (" << t1 << ", " << t2 << ")";
                        if (j == 2)
                            EXPECT_TRUE(inIntervals(atT1, t2)) << "seed " << seed << " (" << t1 << ", " << t2 << ")";
                    }
            }
        }
        // the FCL sweep is not absurdly loose: at the centre of a cell, its intervals exceed the exact ones by
        // about one sweep step
        double exactLength = 0., fclLength = 0.;
        for (int i = 0; i < 24; ++i)
        {
            const double t1 = -M_PI + (i + 0.5) * h;
            for (const auto &iv : exact.intervals(t1))
                exactLength += iv.hi - iv.lo;
            for (const auto &iv : fcl.intervals(t1))
                fclLength += iv.hi - iv.lo;
        }
        EXPECT_LE(fclLength, exactLength + 24 * 6 * 0.004) << "seed " << seed;
        EXPECT_GT(fcl.queries(), 0u);
    }
}

TEST(FclIntervals, Planar2LinkMapContainsFclCollisions)
{
    const auto c = loadPlanar("planar_2link");
    const auto context = tools::makePlanningContext(c.problem);
    auto fcl = std::make_shared<FclIntervalSource>(context.checker, planarAxes(*c.arm, 0, 1));
    JMapSettings settings;
    settings.slices = 36;
    const auto map = JMap::build(*fcl, settings);
    std::cout << "planar_2link FCL-sweep map (36 slices): " << map->polygons().size() << " polygons, build "
              << map->buildSeconds() << " s, " << fcl->queries() << " FCL distance queries" << std::endl;
    ompl::RNG rng(9);
    int missed = 0, inside = 0;
    for (int k = 0; k < 50000; ++k)
    {
        const double q[2] = {rng.uniformReal(-M_PI, M_PI), rng.uniformReal(-M_PI, M_PI)};
        const bool hit = !context.checker->isValidConfiguration(q);
        missed += hit && !map->collides(q[0], q[1]);
        inside += map->collides(q[0], q[1]);
    }
    EXPECT_EQ(missed, 0);
    std::cout << "  inside polygons " << inside / 50000. << std::endl;
}

TEST(JMapStack, Planar3DofHandSlicesContainCollisions)
{
    const auto c = loadPlanar("planar_3dof_hand");
    ASSERT_EQ(c.arm->variableCount(), 3u);
    JMapAxes base = planarAxes(*c.arm, 1, 2);
    const auto arm = c.arm;
    const auto obstacles = c.obstacles;
    JMapSettings settings;
    settings.slices = 36;
    JMapStack stack(
        [arm, obstacles](const JMapAxes &axes)
        {
            return std::make_shared<PlanarIntervalSource>(arm, obstacles, axes);
        },
        base, 0, -M_PI, M_PI, 24, settings);
    EXPECT_EQ(stack.size(), 24u);
    EXPECT_EQ(stack.sliceIndex(-M_PI), 0u);
    EXPECT_EQ(stack.sliceIndex(M_PI), 23u);
    EXPECT_NEAR(stack.centre(0), -M_PI + M_PI / 24, 1e-12);
    const auto t0 = std::chrono::steady_clock::now();
    stack.buildAll();
    std::cout << "planar_3dof_hand stack (24 x 36 slices): "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s" << std::endl;
    // the built-on-demand slice equals the cached one
    EXPECT_EQ(stack.slice(5)->polygons().size(), stack.map(5)->polygons().size());
    ompl::RNG rng(5);
    int missed = 0, colliding = 0, inside = 0;
    for (int k = 0; k < 50000; ++k)
    {
        std::vector<double> q{rng.uniformReal(-M_PI, M_PI), rng.uniformReal(-M_PI, M_PI), rng.uniformReal(-M_PI, M_PI)};
        bool hit = false;
        for (const auto &cap : arm->worldCapsules(q.data()))
            hit = hit || segmentDistance(cap.a, cap.b, obstacles) <= cap.radius;
        const bool mapped = stack.collides(q[0], q[1], q[2]);
        colliding += hit;
        inside += mapped;
        missed += hit && !mapped;
    }
    EXPECT_EQ(missed, 0);
    std::cout << "  colliding " << colliding / 50000. << ", inside polygons " << inside / 50000. << std::endl;
}

TEST(JMapGrow, GrownObstaclesContainTheMinkowskiSum)
{
    const auto obstacles = toPolygons(test::randomPolygons(77, randomSceneOptions()));
    const auto grown = growObstacles(obstacles, 0.15);
    ompl::RNG rng(77);
    int near = 0;
    for (int k = 0; k < 20000; ++k)
    {
        const Point2 p(rng.uniformReal(-1.3, 1.3), rng.uniformReal(-1.3, 1.3));
        if (bg::distance(p, obstacles) <= 0.15)
        {
            ++near;
            EXPECT_TRUE(bg::covered_by(p, grown)) << p.x() << ", " << p.y();
        }
    }
    EXPECT_GT(near, 1000);
    EXPECT_LT(bg::area(grown), 1.1 * bg::area(growObstacles(obstacles, 0.15, 360)));
}

TEST(JMapGrow, BottleneckOfPlanar3DofHand)
{
    // the paper's arm / hand split: the arm (joints 1-2, without the hand link) on plain and grown obstacles
    const auto c = loadPlanar("planar_3dof_hand");
    std::vector<int> armLinks;
    for (std::size_t l = 0; l < c.arm->links().size(); ++l)
        if (c.arm->links()[l].name != "hand")
            armLinks.push_back(static_cast<int>(l));
    const double hand = c.arm->linkLengths()[2];
    EXPECT_NEAR(hand, 0.15, 1e-7);
    const auto axes = planarAxes(*c.arm, 0, 1);
    PlanarIntervalSource plain(c.arm, c.obstacles, axes, armLinks);
    PlanarIntervalSource grown(c.arm, growObstacles(c.obstacles, hand), axes, armLinks);
    const auto plainMap = JMap::build(plain), grownMap = JMap::build(grown);
    const auto neck = bottleneck(*grownMap, *plainMap);
    EXPECT_GT(bg::area(neck), 0.);
    // grown contains plain
    MultiPolygon2 outside;
    bg::difference(plainMap->polygons(), grownMap->polygons(), outside);
    EXPECT_LT(bg::area(outside), 1e-9);
    ompl::RNG rng(12);
    for (int k = 0; k < 20000; ++k)
    {
        const double t1 = rng.uniformReal(-M_PI, M_PI), t2 = rng.uniformReal(-M_PI, M_PI);
        if (plainMap->collides(t1, t2))
            EXPECT_TRUE(grownMap->collides(t1, t2)) << t1 << ", " << t2;
    }
    // the goal puts link 2 through the slot with the hand under the shelf: the arm is free there but the
    // hand could collide, so the goal's arm angles lie in the bottleneck
    const auto &goal = c.problem.queries[0].goal;
    EXPECT_FALSE(plainMap->collides(goal[0], goal[1]));
    EXPECT_TRUE(grownMap->collides(goal[0], goal[1]));
    EXPECT_TRUE(bg::covered_by(Point2(goal[0], goal[1]), neck));
    std::cout << "planar_3dof_hand: plain " << plainMap->polygons().size() << " polygons (area "
              << bg::area(plainMap->polygons()) << "), grown " << grownMap->polygons().size() << " (area "
              << bg::area(grownMap->polygons()) << "), bottleneck area " << bg::area(neck) << std::endl;
}

TEST(JMap, Planar2LinkQuerySpeedReport)
{
    // numbers for docs/jmap.md; printed, never asserted (a timing never decides a test)
    const auto c = loadPlanar("planar_2link");
    PlanarIntervalSource source(c.arm, c.obstacles, planarAxes(*c.arm, 0, 1));
    std::vector<double> builds;
    JMapPtr map;
    for (int k = 0; k < 7; ++k)
    {
        map = JMap::build(source);
        builds.push_back(map->buildSeconds());
    }
    std::sort(builds.begin(), builds.end());
    std::size_t vertices = 0;
    for (const auto &p : map->polygons())
        vertices += p.outer().size();
    std::cout << "planar_2link 72 slices x 2 columns: build median " << builds[3] << " s (min " << builds[0] << "), "
              << map->polygons().size() << " polygons, " << vertices << " outer-ring vertices" << std::endl;
    const auto context = tools::makePlanningContext(c.problem);
    ompl::RNG rng(1);
    std::vector<double> qs(2 * 200000);
    for (auto &v : qs)
        v = rng.uniformReal(-M_PI, M_PI);
    int hits = 0;
    auto t0 = std::chrono::steady_clock::now();
    for (int rep = 0; rep < 5; ++rep)
        for (std::size_t k = 0; k < qs.size(); k += 2)
            hits += map->collides(qs[k], qs[k + 1]);
    const double jmapNs =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / (5 * 200000.);
    t0 = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < 2 * 20000; k += 2)
        hits += context.checker->isValidConfiguration(&qs[k]);
    const double fclNs =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / 20000.;
    t0 = std::chrono::steady_clock::now();
    double sum = 0.;
    for (std::size_t k = 0; k < 2 * 20000; k += 2)
        sum += map->distanceToBoundary(qs[k], qs[k + 1], 0.05);
    const double distNs =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / 20000.;
    std::cout << "planar_2link: collides " << jmapNs << " ns, FCL " << fclNs << " ns (ratio " << fclNs / jmapNs
              << "), distanceToBoundary(0.05) " << distNs << " ns" << std::endl;
    EXPECT_GT(hits + sum, 0.);
}

TEST(JMapExperiment, DISABLED_Tightness)
{
    const auto c = loadPlanar("planar_2link");
    for (int slices : {36, 72, 144})
        for (int sub : {1, 2, 4})
            for (double tol : {0.01, 0.03, 0.1})
            {
                PlanarIntervalSource source(c.arm, c.obstacles, planarAxes(*c.arm, 0, 1));
                JMapSettings settings;
                settings.slices = slices;
                settings.columns = sub;
                settings.tolerance = tol;
                const auto map = JMap::build(source, settings);
                ompl::RNG rng(42);
                int n = 50000, truth = 0, stair = 0, poly = 0, missed = 0;
                for (int k = 0; k < n; ++k)
                {
                    const double t1 = rng.uniformReal(-M_PI, M_PI), t2 = rng.uniformReal(-M_PI, M_PI);
                    const bool hit = source.collides(t1, t2);
                    truth += hit;
                    stair += inIntervals(map->slices()[map->sliceIndex(t1)].intervals, t2);
                    poly += map->collides(t1, t2);
                    missed += hit && !map->collides(t1, t2);
                }
                std::size_t vertices = 0;
                for (const auto &p : map->polygons())
                    vertices += p.outer().size();
                std::cout << "slices " << slices << " columns " << sub << " tol " << tol << ": true "
                          << double(truth) / n << " slice staircase " << double(stair) / n << " polygons "
                          << double(poly) / n << " false-invalid " << double(poly - truth) / n << " missed " << missed
                          << " polygons " << map->polygons().size() << " vertices " << vertices << " build "
                          << map->buildSeconds() << std::endl;
            }
}

#include <michi/tools/pictures/JMapPicture.h>

#include <fstream>
#include <sstream>

TEST(JMapPicture, WritesAnSvgAtomically)
{
    const auto c = loadPlanar("planar_2link");
    PlanarIntervalSource source(c.arm, c.obstacles, planarAxes(*c.arm, 0, 1));
    const auto map = JMap::build(source);
    test::TempDir dir("michi_jmap");
    const std::string file = dir.path() + "/jmap.svg";
    tools::JMapPictureOptions options;
    options.title = "planar_2link J-map";
    options.start = c.problem.queries[0].start;
    options.goal = c.problem.queries[0].goal;
    tools::writeJMapSvg(*map, file, options);
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_NE(text.str().find("<svg"), std::string::npos);
    EXPECT_NE(text.str().find("</svg>"), std::string::npos);
    EXPECT_NE(text.str().find("J-map polygons"), std::string::npos);
    EXPECT_FALSE(std::ifstream(file + ".tmp").good());
    EXPECT_THROW(tools::writeJMapSvg(*map, dir.path() + "/no/such/dir/x.svg", options), std::runtime_error);
}

TEST(JMapPicture, DISABLED_WritePicturesForViewing)
{
    // writes /tmp/michi_jmap_*.svg: run with --gtest_also_run_disabled_tests and look at them
    {
        const auto c = loadPlanar("planar_2link");
        PlanarIntervalSource source(c.arm, c.obstacles, planarAxes(*c.arm, 0, 1));
        const auto map = JMap::build(source);
        tools::JMapPictureOptions options;
        options.title = "planar_2link: J-map, 72 slices";
        options.axis1 = "joint1";
        options.axis2 = "joint2";
        options.start = c.problem.queries[0].start;
        options.goal = c.problem.queries[0].goal;
        tools::writeJMapSvg(*map, "/tmp/michi_jmap_planar_2link.svg", options);
        options.cellIntervals = true;
        tools::writeJMapSvg(*map, "/tmp/michi_jmap_planar_2link_cells.svg", options);
    }
    {
        const auto c = loadPlanar("planar_3dof_hand");
        std::vector<int> armLinks;
        for (std::size_t l = 0; l < c.arm->links().size(); ++l)
            if (c.arm->links()[l].name != "hand")
                armLinks.push_back(static_cast<int>(l));
        const auto axes = planarAxes(*c.arm, 0, 1);
        PlanarIntervalSource plain(c.arm, c.obstacles, axes, armLinks);
        PlanarIntervalSource grown(c.arm, growObstacles(c.obstacles, c.arm->linkLengths()[2]), axes, armLinks);
        const auto plainMap = JMap::build(plain);
        tools::JMapPictureOptions options;
        options.title = "planar_3dof_hand: arm J-map, grown J-map (hand 0.15 m) and bottleneck";
        options.axis1 = "joint1";
        options.axis2 = "joint2";
        options.grown = JMap::build(grown);
        options.bottleneck = bottleneck(*options.grown, *plainMap);
        options.start = c.problem.queries[0].start;
        options.goal = c.problem.queries[0].goal;
        tools::writeJMapSvg(*plainMap, "/tmp/michi_jmap_planar_3dof_hand.svg", options);
    }
}
