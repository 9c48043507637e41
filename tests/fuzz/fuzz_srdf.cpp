// Fuzz target: an SRDF file (michi::tools::readSrdf) checked against the Panda URDF of problems/robots/panda/.
#include "FuzzSupport.h"

#include <michi/tools/problem/MoveItImport.h>
#include <michi/validity/robot/RobotModel.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    static const auto model =
        michi::validity::RobotModel::fromUrdfFile(michi_fuzz::problemsCopy() + "/robots/panda/panda.urdf");
    const std::string path = michi_fuzz::writeInput("robots/panda/fuzz.srdf", data, size);
    michi_fuzz::expectCleanResult(
        [&]
        {
            michi::tools::readSrdf(path, *model);
        });
    return 0;
}
