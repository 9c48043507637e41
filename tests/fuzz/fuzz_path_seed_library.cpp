// Fuzz target: a path-seed library file (michi::planners::PathSeedLibrary::load).
#include "FuzzSupport.h"

#include <michi/planners/path_seed/PathSeedLibrary.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const std::string path = michi_fuzz::writeInput("experience/fuzz.seeds", data, size);
    michi_fuzz::expectCleanResult(
        [&]
        {
            michi::planners::PathSeedLibrary::load(path);
        });
    return 0;
}
