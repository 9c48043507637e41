// Fuzz target: a URDF document (michi::validity::RobotModel::fromUrdfString), meshes resolved from problems/robots/.
#include "FuzzSupport.h"

#include <michi/validity/robot/RobotModel.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const std::string xml(reinterpret_cast<const char *>(data), size);
    const std::string baseDir = michi_fuzz::problemsCopy() + "/robots";
    michi_fuzz::expectCleanResult([&] { michi::validity::RobotModel::fromUrdfString(xml, "fuzz.urdf", baseDir); });
    return 0;
}
