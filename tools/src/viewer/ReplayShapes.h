#ifndef MICHI_TOOLS_SRC_VIEWER_REPLAY_SHAPES_
#define MICHI_TOOLS_SRC_VIEWER_REPLAY_SHAPES_

// Private to michi_tools: the shapes of a replay page, each written once however many bodies use it (ReplayShapes.cpp).

#include <michi/validity/scene/Shape.h>

#include <map>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace replay
        {
            /** Meshes with more triangles than this are decimated (vertex clustering) before they are written: a
                scanned object can have hundreds of thousands, more than the page's whole size bound. */
            constexpr std::size_t MAX_MESH_TRIANGLES = 20000;

            /** Shapes by identity: a URDF mesh used by two links, or the cells of a map, are written once and
                referred to by index. */
            class ShapeTable
            {
            public:
                /** The index of \e shape in the table, adding it the first time. */
                int index(const validity::ShapePtr &shape);

                /** "[...]": every shape as {"type":"box","size":[x,y,z]}, {"type":"sphere","radius":r},
                    {"type":"cylinder"|"capsule","radius":r,"length":l} (axis z, centred) or
                    {"type":"mesh","vertices":[x,y,z,...],"triangles":[i,j,k,...]} (prisms are written as meshes). */
                std::string json() const;

            private:
                std::map<const validity::Shape *, int> indices_;
                std::vector<validity::ShapePtr> kept_;  ///< keeps every indexed shape alive, so no address is reused
                std::string json_;
                int count_{0};
            };
        }  // namespace replay
    }      // namespace tools
}  // namespace michi

#endif
