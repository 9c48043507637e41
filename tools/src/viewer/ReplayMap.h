#ifndef MICHI_TOOLS_SRC_VIEWER_REPLAY_MAP_
#define MICHI_TOOLS_SRC_VIEWER_REPLAY_MAP_

// Private to michi_tools: an occupancy map's cells as one image for the replay page (ReplayMap.cpp).

#include <michi/tools/problem/Problem.h>
#include <michi/validity/scene/Scene.h>

#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace replay
        {
            /** True for an obstacle made from one row run of an occupancy map's cells (scene.map, scene.movingai):
                a box named "cells_r<row>_c<column>" (validity::occupancyObstacles, movingAiObstacles). A map has
                thousands of them; the page shows them as one textured plane instead of as many boxes. */
            bool isMapCell(const Problem &problem, const validity::Obstacle &obstacle);

            /** {"origin":[x,y],"resolution":r,"width":w,"height":h,"wallHeight":z,"runs":[free,occupied,...]}:
                the cells of \e cells on a grid of the problem's map resolution covering them (and an SE2 robot's
                bounds), row by row from the lowest y, run-length encoded starting with a free run. */
            std::string mapJson(const Problem &problem, const std::vector<validity::Obstacle> &cells);
        }  // namespace replay
    }      // namespace tools
}  // namespace michi

#endif
