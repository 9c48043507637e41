// Fuzz target: an occupancy image, binary or ASCII PGM (michi::validity::occupancyObstacles).
#include "FuzzSupport.h"

#include <michi/validity/scene/Scene.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const std::string path = michi_fuzz::writeInput("maps/fuzz.pgm", data, size);
    michi_fuzz::expectCleanResult(
        [&]
        {
            michi::validity::occupancyObstacles(path, 0.05, Eigen::Vector2d(-1., 2.), 1., 0.5);
        });
    return 0;
}
