// Statistical check of the conservative J-map (label `slow`): on 50 random planar scenes (fixed seeds) the J-map
// checker never calls a state valid that FCL calls invalid. MICHI_JMAP_VERIFY sets the states per scene (default
// 200000; the figure is 1000000: `MICHI_JMAP_VERIFY=1000000 ctest --test-dir build -L slow`).
#include "support/TestScenes.h"

#include <michi/validity/JMapValidityChecker.h>
#include <michi/validity/PlanarArm.h>

#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cstdlib>

using namespace michi;

TEST(JMapRandomScenes, NoUnsafeStateOnFiftyScenes)
{
    const char *env = std::getenv("MICHI_JMAP_VERIFY");
    const long perScene = env != nullptr ? std::atol(env) : 200000;
    ASSERT_GT(perScene, 0);
    long checked = 0, unsafe = 0, falseInvalid = 0, invalid = 0;
    for (unsigned int seed = 1; seed <= 50; ++seed)
    {
        test::RandomPolygonOptions options;
        options.count = 6;
        options.keepClearRadius = 0.1;
        const auto obstacles = test::randomPolygons(seed, options);
        const auto setup = test::planarArmSetup({0.5, 0.4}, obstacles);
        const auto arm = validity::PlanarArm::fromModel(*setup.model);
        const auto polygons = setup.scene->polygons2d();
        validity::JMapValidityChecker jmap(
            setup.si, setup.checker,
            [arm, polygons](const validity::JMapAxes &axes)
            {
                return std::make_shared<validity::PlanarIntervalSource>(arm, polygons, axes);
            },
            validity::planarAxes(*arm, 0, 1), true);
        ompl::RNG rng(1000 + seed);
        for (long n = 0; n < perScene; ++n)
        {
            const double q[2] = {rng.uniformReal(-M_PI, M_PI), rng.uniformReal(-M_PI, M_PI)};
            const bool mine = jmap.isValidConfiguration(q), exact = setup.checker->isValidConfiguration(q);
            unsafe += mine && !exact;
            falseInvalid += !mine && exact;
            invalid += !exact;
            ++checked;
            if (mine && !exact)
                ADD_FAILURE() << "scene " << seed << ": J-map calls (" << q[0] << ", " << q[1]
                              << ") valid, FCL says it collides";
        }
    }
    EXPECT_EQ(unsafe, 0);
    RecordProperty("checked_states", std::to_string(checked));
    RecordProperty("false_invalid_fraction", std::to_string(static_cast<double>(falseInvalid) / checked));
    std::cout << "checked " << checked << " states on 50 scenes: unsafe " << unsafe << ", false invalid "
              << static_cast<double>(falseInvalid) / checked << ", colliding " << static_cast<double>(invalid) / checked
              << std::endl;
}
