#ifndef MICHI_TOOLS_MOVING_AI_MAP_
#define MICHI_TOOLS_MOVING_AI_MAP_

#include <michi/validity/scene/Scene.h>

#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief A grid map of the MovingAI pathfinding benchmark (Sturtevant, "Benchmarks for Grid-Based
            Pathfinding", IEEE TCIAIG 2012; https://movingai.com/benchmarks/formats.html): a header
            ("type octile", "height H", "width W", "map") then H rows of W characters. '.', 'G' and 'S' (swamp) are
            passable; '@', 'O' (out of bounds), 'T' (trees) and 'W' (water) are blocked. Row 0 is the top of the map;
            cell (x, y) of the format is column x of row y. */
        struct MovingAiMap
        {
            std::string file;
            int width{0};
            int height{0};
            std::vector<std::string> rows;  ///< height rows of width characters, row 0 at the top

            /** \brief True when the cell at column \e x of row \e y (row 0 at the top) is blocked. */
            bool blocked(int x, int y) const;
            /** \brief True for the characters that block a cell ('@', 'O', 'T', 'W'). */
            static bool blockedCharacter(char c);
        };

        /** \brief Read a .map file. Throws ProblemError naming the file and the line ("header", "row 12") when the
            header is not the MovingAI one or a row has the wrong length or an unknown character. CRLF line ends are
            accepted. */
        MovingAiMap readMovingAiMap(const std::string &path);

        /** \brief The blocked cells as boxes of height \e height standing on z = 0, one box per run of blocked cells
            in a row (as validity::occupancyObstacles does for a PGM image). A cell is \e resolution metres wide;
            the map's lower-left corner is at \e origin, so cell (x, y) has its centre at
            (origin.x + (x + 0.5) r, origin.y + (H - 1 - y + 0.5) r). Boxes are named "cells_r<row>_c<column>". */
        std::vector<validity::Obstacle> movingAiObstacles(const MovingAiMap &map, double resolution,
                                                          const Eigen::Vector2d &origin = Eigen::Vector2d::Zero(),
                                                          double height = 1.);

        /** \brief One line of a MovingAI .scen file (version 1): a start and goal cell and the optimal octile
            length of an 8-connected path between them. */
        struct MovingAiScenario
        {
            int bucket{0};
            std::string map;  ///< map file named by the line (as written, usually a path on the author's disk)
            int mapWidth{0};
            int mapHeight{0};
            int startX{0};
            int startY{0};
            int goalX{0};
            int goalY{0};
            double optimalLength{0.};
            int line{0};  ///< line number in the file (1-based)
        };

        /** \brief Read a .scen file ("version 1" or "version 1.0", then one tab- or space-separated line per
            scenario). Throws ProblemError naming the file and the line when a line cannot be read. */
        std::vector<MovingAiScenario> readMovingAiScenarios(const std::string &path);

        /** \brief World position of the centre of cell (\e x, \e y) (row \e y counted from the top). */
        Eigen::Vector2d movingAiCellCentre(const MovingAiMap &map, int x, int y, double resolution,
                                           const Eigen::Vector2d &origin = Eigen::Vector2d::Zero());
    }  // namespace tools
}  // namespace michi

#endif
