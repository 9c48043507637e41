// Fuzz target: a MoveIt MotionPlanRequest YAML file (michi::tools::readMoveItRequest).
#include "FuzzSupport.h"

#include <michi/tools/problem/MoveItImport.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const std::string path = michi_fuzz::writeInput("moveit/table_pick/fuzz_request.yaml", data, size);
    michi_fuzz::expectCleanResult(
        [&]
        {
            michi::tools::readMoveItRequest(path);
        });
    return 0;
}
