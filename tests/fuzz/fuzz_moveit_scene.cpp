// Fuzz target: a MoveIt PlanningScene YAML file (michi::tools::readMoveItScene), with the Panda as the robot (its
// links are the allowed-collision entries of the seeds) and without a robot.
#include "FuzzSupport.h"

#include <michi/tools/problem/MoveItImport.h>
#include <michi/validity/robot/RobotModel.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    static const auto model =
        michi::validity::RobotModel::fromUrdfFile(michi_fuzz::problemsCopy() + "/robots/panda/panda.urdf");
    const std::string path = michi_fuzz::writeInput("moveit/table_pick/fuzz_scene.yaml", data, size);
    michi_fuzz::expectCleanResult(
        [&]
        {
            michi::tools::readMoveItScene(path, model.get());
        });
    michi_fuzz::expectCleanResult(
        [&]
        {
            michi::tools::readMoveItScene(path, nullptr);
        });
    return 0;
}
