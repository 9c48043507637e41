// Fuzz target: a mesh file read as .stl (michi::validity::Shape::meshFromFile, through assimp), unscaled and scaled.
#include "FuzzSupport.h"

#include <michi/validity/scene/Shape.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const std::string path = michi_fuzz::writeInput("meshes/fuzz.stl", data, size);
    michi_fuzz::expectCleanResult(
        [&]
        {
            michi::validity::Shape::meshFromFile(path);
        });
    michi_fuzz::expectCleanResult(
        [&]
        {
            michi::validity::Shape::meshFromFile(path, Eigen::Vector3d(1e-3, 2., 1e3));
        });
    return 0;
}
