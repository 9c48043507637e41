// Fuzz target: a URDF document (michi::validity::RobotModel::fromUrdfString), meshes resolved from problems/robots/.
// Besides a clean result it checks a property (issue 13): when michi accepts a URDF, every link urdfdom parsed from it
// is in the model, so every link with collision geometry takes part in collision checking (no link silently dropped).
#include "FuzzSupport.h"

#include <michi/validity/robot/RobotModel.h>

#include <urdf_parser/urdf_parser.h>
#include <urdf_world/types.h>

#include <cstdio>
#include <cstdlib>
#include <set>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const std::string xml(reinterpret_cast<const char *>(data), size);
    const std::string baseDir = michi_fuzz::problemsCopy() + "/robots";
    michi::validity::RobotModelPtr model;
    michi_fuzz::expectCleanResult(
        [&]
        {
            model = michi::validity::RobotModel::fromUrdfString(xml, "fuzz.urdf", baseDir);
        });
    if (!model)
        return 0;
    const urdf::ModelInterfaceSharedPtr parsed = urdf::parseURDF(xml);
    if (!parsed)
        return 0;
    std::set<std::string> names;
    for (const auto &link : model->links())
        names.insert(link.name);
    for (const auto &kv : parsed->links_)
        if (names.count(kv.first) == 0)
        {
            std::fprintf(stderr, "fuzz_urdf: URDF accepted but link '%s' is not in the model (silently dropped)\n",
                         kv.first.c_str());
            std::abort();
        }
    return 0;
}
