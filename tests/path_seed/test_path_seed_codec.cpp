// Path seed encoding and decoding (paper 001, Tables 1 and 2): exact reproduction, invariants of decoding,
// degenerate cases.
#include <michi/planners/path_seed/PathSeedCodec.h>

#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

using michi::planners::decodePath;
using michi::planners::encodePath;
using michi::planners::PathSeedCode;
using michi::planners::SeedVariant;

namespace
{
    Eigen::VectorXd randomVector(ompl::RNG &rng, int n, double range = 3.)
    {
        Eigen::VectorXd v(n);
        for (int i = 0; i < n; ++i)
            v[i] = rng.uniformReal(-range, range);
        return v;
    }

    std::vector<Eigen::VectorXd> randomPath(ompl::RNG &rng, int n, int waypoints)
    {
        std::vector<Eigen::VectorXd> path;
        for (int i = 0; i < waypoints + 2; ++i)
            path.push_back(randomVector(rng, n));
        return path;
    }

    double maxError(const std::vector<Eigen::VectorXd> &a, const std::vector<Eigen::VectorXd> &b)
    {
        EXPECT_EQ(a.size(), b.size());
        double err = 0.;
        for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
            err = std::max(err, (a[i] - b[i]).cwiseAbs().maxCoeff());
        return err;
    }

    bool allFinite(const std::vector<Eigen::VectorXd> &path)
    {
        for (const auto &p : path)
            if (!p.allFinite())
                return false;
        return true;
    }

    Eigen::VectorXd blockOf(const Eigen::VectorXd &x, int b)
    {
        Eigen::VectorXd out = Eigen::VectorXd::Zero(3);
        for (int k = 0; k < 3; ++k)
            if (3 * b + k < x.size())
                out[k] = x[3 * b + k];
        return out;
    }

    /** Ratio and deviation of w from the line s-g (signed ratio, as the encoder defines it). */
    void ratioDeviation(const Eigen::VectorXd &s, const Eigen::VectorXd &g, const Eigen::VectorXd &w, double &r,
                        double &tau)
    {
        const Eigen::VectorXd v = g - s;
        r = (w - s).dot(v) / v.squaredNorm();
        tau = (w - s - r * v).norm();
    }

    const SeedVariant VARIANTS[] = {SeedVariant::BLOCKS, SeedVariant::ROTATION};
}  // namespace

TEST(PathSeedCodec, ReproducesThePathForItsOwnStartAndGoal)
{
    ompl::RNG rng(11);
    std::vector<int> dims{3, 6, 7};
    for (int i = 0; i < 5; ++i)
        dims.push_back(rng.uniformInt(1, 12));  // random N
    for (SeedVariant variant : VARIANTS)
        for (int n : dims)
            for (int trial = 0; trial < 20; ++trial)
            {
                const auto path = randomPath(rng, n, rng.uniformInt(0, 25));
                const PathSeedCode seed = encodePath(path, variant);
                EXPECT_EQ(seed.dimension, static_cast<unsigned int>(n));
                EXPECT_EQ(seed.waypoints(), path.size() - 2);
                const auto decoded = decodePath(seed, path.front(), path.back());
                EXPECT_LT(maxError(path, decoded), 1e-12)
                    << "N = " << n << " " << michi::planners::seedVariantName(variant);
            }
}

TEST(PathSeedCodec, ThreeJointsFollowTheTablesLiterally)
{
    // N = 3: one block; r, tau and delta are Table 1's quantities (delta = normalize(e x (w - l))).
    Eigen::VectorXd s(3), g(3), w(3);
    s << 0, 0, 0;
    g << 2, 0, 0;
    w << 0.5, 0, 1.5;
    const auto seed = encodePath({s, w, g}, SeedVariant::BLOCKS);
    ASSERT_EQ(seed.waypoints(), 1u);
    EXPECT_DOUBLE_EQ(seed.ratio[0], 0.25);
    EXPECT_DOUBLE_EQ(seed.deviation[0], 1.5);
    // e = x, w - l = 1.5 z, e x z = -y
    EXPECT_NEAR(seed.direction[0], 0., 1e-15);
    EXPECT_NEAR(seed.direction[1], -1., 1e-15);
    EXPECT_NEAR(seed.direction[2], 0., 1e-15);
    // decoding on a new line along y: l~ = s~ + r v~, w~ = l~ + tau (delta x e~) = l~ + 1.5 * (-y x y) = l~
    // ... (-y) x y = 0: delta parallel to e~, so the seed's offset is turned from e to e~ (z stays z)
    Eigen::VectorXd s2(3), g2(3);
    s2 << 1, 1, 1;
    g2 << 1, 5, 1;
    const auto d = decodePath(seed, s2, g2);
    EXPECT_TRUE(allFinite(d));
    EXPECT_NEAR((d[1] - Eigen::Vector3d(1, 2, 2.5)).norm(), 0., 1e-12);
    // a new line along x scaled and shifted: the same shape scaled
    g2 << 5, 1, 1;
    const auto d2 = decodePath(seed, s2, g2);
    EXPECT_NEAR((d2[1] - Eigen::Vector3d(2, 1, 2.5)).norm(), 0., 1e-12);
}

TEST(PathSeedCodec, DecodingKeepsRatioAndDeviation)
{
    ompl::RNG rng(5);
    for (SeedVariant variant : VARIANTS)
        for (int n : {3, 6, 7, 2, 10})
            for (int trial = 0; trial < 20; ++trial)
            {
                const auto path = randomPath(rng, n, 15);
                const auto seed = encodePath(path, variant);
                const Eigen::VectorXd s = randomVector(rng, n), g = randomVector(rng, n);
                const auto decoded = decodePath(seed, s, g);
                ASSERT_EQ(decoded.size(), path.size());
                EXPECT_LT((decoded.front() - s).norm(), 1e-15);
                EXPECT_LT((decoded.back() - g).norm(), 1e-15);
                for (std::size_t m = 1; m + 1 < path.size(); ++m)
                {
                    if (variant == SeedVariant::ROTATION)
                    {
                        double r0, t0, r1, t1;
                        ratioDeviation(path.front(), path.back(), path[m], r0, t0);
                        ratioDeviation(s, g, decoded[m], r1, t1);
                        EXPECT_NEAR(r0, r1, 1e-9);
                        EXPECT_NEAR(t0, t1, 1e-9);
                    }
                    else
                        for (int b = 0; b < (n + 2) / 3; ++b)  // per block
                        {
                            double r0, t0, r1, t1;
                            ratioDeviation(blockOf(path.front(), b), blockOf(path.back(), b), blockOf(path[m], b), r0,
                                           t0);
                            ratioDeviation(blockOf(s, b), blockOf(g, b), blockOf(decoded[m], b), r1, t1);
                            EXPECT_NEAR(r0, r1, 1e-9) << "N " << n << " block " << b;
                            EXPECT_NEAR(t0, t1, 1e-9) << "N " << n << " block " << b;
                        }
                }
            }
}

TEST(PathSeedCodec, RotationVariantKeepsTheShapeUnderARotationOfTheLine)
{
    // the decoded path of a rotated start/goal is the original path rotated: distances between waypoints kept
    ompl::RNG rng(3);
    const auto path = randomPath(rng, 6, 8);
    const auto seed = encodePath(path, SeedVariant::ROTATION);
    const Eigen::VectorXd s = randomVector(rng, 6);
    const Eigen::VectorXd g = s + (path.back() - path.front()).norm() * randomVector(rng, 6).normalized();
    const auto d = decodePath(seed, s, g);
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
        EXPECT_NEAR((path[i + 1] - path[i]).norm(), (d[i + 1] - d[i]).norm(), 1e-9);
}

TEST(PathSeedCodec, BehindTheStartKeepsItsSide)
{
    Eigen::VectorXd s(3), g(3), w(3);
    s << 0, 0, 0;
    g << 1, 0, 0;
    w << -0.5, 1, 0;  // behind the start
    for (SeedVariant variant : VARIANTS)
    {
        const auto seed = encodePath({s, w, g}, variant);
        EXPECT_DOUBLE_EQ(seed.ratio[0], -0.5);
        const auto d = decodePath(seed, s, 2 * g);
        EXPECT_NEAR(d[1][0], -1., 1e-12);
    }
}

TEST(PathSeedCodec, DegenerateCasesGiveNoNaN)
{
    Eigen::VectorXd z = Eigen::VectorXd::Zero(6), a(6), b(6), c(6);
    a << 1, 2, 3, 0, 0, 0;      // joints 4-6 do not move from z to a
    b << 0.5, 1, 1.5, 0, 0, 0;  // on the line z-a
    c << 0.3, -1, 2, 0.2, 0.1, -0.4;
    for (SeedVariant variant : VARIANTS)
    {
        const std::string name = michi::planners::seedVariantName(variant);
        // waypoint on the line (w - l = 0), a block that does not move, an off-line waypoint
        const std::vector<Eigen::VectorXd> path{z, b, c, a};
        auto seed = encodePath(path, variant);
        for (double x : seed.direction)
            EXPECT_TRUE(std::isfinite(x)) << name;
        EXPECT_LT(maxError(path, decodePath(seed, z, a)), 1e-12) << name;
        // decoded where the seed's moving blocks stand still, and where the still block moves
        EXPECT_TRUE(allFinite(decodePath(seed, z, z))) << name;
        EXPECT_TRUE(allFinite(decodePath(seed, z, c))) << name;
        EXPECT_TRUE(allFinite(decodePath(seed, a, z))) << name;  // reversed: e~ = -e
        // s = g at encoding: offsets kept as they are
        const std::vector<Eigen::VectorXd> loop{z, c, b, z};
        seed = encodePath(loop, variant);
        for (double x : seed.direction)
            EXPECT_TRUE(std::isfinite(x)) << name;
        EXPECT_LT(maxError(loop, decodePath(seed, z, z)), 1e-12) << name;
        const auto moved = decodePath(seed, a, c);
        EXPECT_TRUE(allFinite(moved)) << name;
        // start and goal only (M = 0)
        seed = encodePath({z, a}, variant);
        EXPECT_EQ(seed.waypoints(), 0u);
        EXPECT_EQ(decodePath(seed, c, b).size(), 2u);
    }
}

TEST(PathSeedCodec, RejectsBadInput)
{
    Eigen::VectorXd a = Eigen::VectorXd::Zero(3), b = Eigen::VectorXd::Zero(4);
    EXPECT_THROW(encodePath({a}, SeedVariant::BLOCKS), std::invalid_argument);
    EXPECT_THROW(encodePath({a, b}, SeedVariant::BLOCKS), std::invalid_argument);
    const auto seed = encodePath({a, a}, SeedVariant::ROTATION);
    EXPECT_THROW(decodePath(seed, b, b), std::invalid_argument);
    EXPECT_THROW(michi::planners::seedVariantFromName("cross"), std::invalid_argument);
}
