// Fuzz target: a problem YAML file (michi::tools::loadProblem), written beside the problems it is seeded from so
// that its robot, mesh, map and experience references resolve.
#include "FuzzSupport.h"

#include <michi/tools/problem/Problem.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const std::string path = michi_fuzz::writeInput("fuzz_problem.yaml", data, size);
    michi_fuzz::expectCleanResult(
        [&]
        {
            michi::tools::loadProblem(path);
        });
    return 0;
}
