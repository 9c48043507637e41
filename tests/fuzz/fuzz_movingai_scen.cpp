// Fuzz target: a MovingAI scenario file (michi::tools::readMovingAiScenarios).
#include "FuzzSupport.h"

#include <michi/tools/problem/MovingAiMap.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const std::string path = michi_fuzz::writeInput("maps/movingai/fuzz.map.scen", data, size);
    michi_fuzz::expectCleanResult(
        [&]
        {
            michi::tools::readMovingAiScenarios(path);
        });
    return 0;
}
