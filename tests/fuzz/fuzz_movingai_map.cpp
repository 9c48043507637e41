// Fuzz target: a MovingAI grid map (michi::tools::readMovingAiMap), then its obstacles (movingAiObstacles).
#include "FuzzSupport.h"

#include <michi/tools/problem/MovingAiMap.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const std::string path = michi_fuzz::writeInput("maps/movingai/fuzz.map", data, size);
    michi_fuzz::expectCleanResult(
        [&]
        {
            const auto map = michi::tools::readMovingAiMap(path);
            michi::tools::movingAiObstacles(map, 0.5);
            if (map.width > 0 && map.height > 0)
                michi::tools::movingAiCellCentre(map, map.width - 1, map.height - 1, 0.5);
        });
    return 0;
}
