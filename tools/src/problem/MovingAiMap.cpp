#include <michi/tools/problem/MovingAiMap.h>
#include <michi/tools/problem/Problem.h>
#include <michi/validity/InputFile.h>

#include <fstream>
#include <sstream>

namespace michi
{
    namespace tools
    {
        namespace
        {
            /** A line read from the file, as a message quotes it: the first 80 bytes (a binary file's first "line"
                can be megabytes long; ProblemError escapes what is not printable). */
            std::string shortLine(const std::string &line)
            {
                return line.size() <= 80 ? line : line.substr(0, 80) + "...";
            }

            /** getline without the '\r' of CRLF files. */
            bool readLine(std::istream &in, std::string &line)
            {
                if (!std::getline(in, line))
                    return false;
                if (!line.empty() && line.back() == '\r')
                    line.pop_back();
                return true;
            }

            bool knownCharacter(char c)
            {
                return c == '.' || c == 'G' || c == 'S' || MovingAiMap::blockedCharacter(c);
            }

            bool parseInt(const std::string &text, int &value)
            {
                try
                {
                    std::size_t used = 0;
                    value = std::stoi(text, &used);
                    return used == text.size();
                }
                catch (const std::exception &)
                {
                    return false;
                }
            }
        }  // namespace

        bool MovingAiMap::blockedCharacter(char c)
        {
            // MovingAI's map characters: '@' and 'O' out of bounds, 'T' trees, 'W' water (not passable from ground):
            // blocked.
            // '.', 'G' (ground) and 'S' (swamp, passable from ground in MovingAI's description) are free.
            return c == '@' || c == 'O' || c == 'T' || c == 'W';
        }

        bool MovingAiMap::blocked(int x, int y) const
        {
            return blockedCharacter(rows[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)]);
        }

        MovingAiMap readMovingAiMap(const std::string &path)
        {
            try
            {
                validity::requireInputFile(path);
            }
            catch (const validity::InputFileError &e)
            {
                throw ProblemError(path, "", e.reason());
            }
            std::ifstream in(path);
            if (!in)
                throw ProblemError(path, "", "cannot open the map file");
            MovingAiMap map;
            map.file = path;
            std::string line;
            int lineNumber = 0;
            const std::string expected = "expected the MovingAI header 'type octile', 'height H', 'width W', 'map'";
            bool haveType = false;
            while (true)
            {
                if (!readLine(in, line))
                    throw ProblemError(path, "header", "ends before 'map'; " + expected);
                ++lineNumber;
                std::istringstream words(line);
                std::string word, value, extra;
                words >> word;
                if (word.empty())
                    continue;
                // The header's lines may come in any order; "map" ends it and the rows follow.
                if (word == "map")
                    break;
                if (!(words >> value) || (words >> extra))
                    throw ProblemError(path, "header (line " + std::to_string(lineNumber) + ")",
                                       "'" + shortLine(line) + "': " + expected);
                if (word == "type")
                {
                    // Octile is the only type the benchmark sets use; another type would mean other movement rules.
                    if (value != "octile")
                        throw ProblemError(path, "header.type", "map type '" + value + "', expected 'octile'");
                    haveType = true;
                }
                else if (word == "height" || word == "width")
                {
                    int v = 0;
                    if (!parseInt(value, v) || v <= 0)
                        throw ProblemError(path, "header." + word,
                                           "'" + value + "', expected a positive number of cells");
                    (word == "height" ? map.height : map.width) = v;
                }
                else
                    throw ProblemError(path, "header (line " + std::to_string(lineNumber) + ")",
                                       "unknown header line '" + shortLine(line) + "': " + expected);
            }
            if (!haveType)
                throw ProblemError(path, "header.type", "missing; " + expected);
            if (map.height == 0 || map.width == 0)
                throw ProblemError(path, map.height == 0 ? "header.height" : "header.width", "missing; " + expected);
            while (static_cast<int>(map.rows.size()) < map.height)
            {
                const std::string key = "row " + std::to_string(map.rows.size());
                if (!readLine(in, line))
                    throw ProblemError(path, key,
                                       "missing: the header says " + std::to_string(map.height) +
                                           " rows, the file has " + std::to_string(map.rows.size()));
                // A row of the wrong length would shift every cell after it: refuse it, naming the row, rather than
                // guess.
                if (static_cast<int>(line.size()) != map.width)
                    throw ProblemError(path, key,
                                       std::to_string(line.size()) + " characters, the header says width " +
                                           std::to_string(map.width));
                for (std::size_t c = 0; c < line.size(); ++c)
                    if (!knownCharacter(line[c]))
                        throw ProblemError(path, key,
                                           "unknown character '" + std::string(1, line[c]) + "' in column " +
                                               std::to_string(c) + " (expected . G S @ O T W)");
                map.rows.push_back(line);
            }
            while (readLine(in, line))
                if (line.find_first_not_of(" \t") != std::string::npos)
                    throw ProblemError(path, "row " + std::to_string(map.height),
                                       "more rows than the header's height " + std::to_string(map.height));
            return map;
        }

        Eigen::Vector2d movingAiCellCentre(const MovingAiMap &map, int x, int y, double resolution,
                                           const Eigen::Vector2d &origin)
        {
            return Eigen::Vector2d(origin.x() + (x + 0.5) * resolution,
                                   // Row 0 is the map's top line: y is flipped so the map reads the right way up with y
                                   // pointing up in the world.
                                   origin.y() + (map.height - 1 - y + 0.5) * resolution);
        }

        std::vector<validity::Obstacle> movingAiObstacles(const MovingAiMap &map, double resolution,
                                                          const Eigen::Vector2d &origin, double height)
        {
            if (!(resolution > 0.))
                throw ProblemError(map.file, "resolution", "expected a positive number (metres per cell)");
            if (!(height > 0.))
                throw ProblemError(map.file, "height", "expected a positive number (metres)");
            std::vector<validity::Obstacle> obstacles;
            for (int r = 0; r < map.height; ++r)
            {
                // Through movingAiCellCentre(), as the scenarios' starts and goals: cells and queries share one row
                // convention.
                const double y = movingAiCellCentre(map, 0, r, resolution, origin).y();
                int c = 0;
                while (c < map.width)
                {
                    if (!map.blocked(c, r))
                    {
                        ++c;
                        continue;
                    }
                    // One box per horizontal run of blocked cells, not one per cell: far fewer FCL objects on large
                    // maps.
                    const int start = c;
                    while (c < map.width && map.blocked(c, r))
                        ++c;
                    validity::Obstacle o;
                    // The cells_r prefix is how the replay page recognises a map's cells and draws them as one textured
                    // plane (replay::isMapCell), as for PGM maps.
                    o.name = "cells_r" + std::to_string(r) + "_c" + std::to_string(start);
                    o.shape = validity::Shape::box(Eigen::Vector3d((c - start) * resolution, resolution, height));
                    o.pose.translation() =
                        Eigen::Vector3d(origin.x() + 0.5 * (start + c) * resolution, y, 0.5 * height);
                    obstacles.push_back(std::move(o));
                }
            }
            return obstacles;
        }

        std::vector<MovingAiScenario> readMovingAiScenarios(const std::string &path)
        {
            try
            {
                validity::requireInputFile(path);
            }
            catch (const validity::InputFileError &e)
            {
                throw ProblemError(path, "", e.reason());
            }
            std::ifstream in(path);
            if (!in)
                throw ProblemError(path, "", "cannot open the scenario file");
            std::string line;
            if (!readLine(in, line))
                throw ProblemError(path, "version", "empty file, expected 'version 1' then one scenario per line");
            {
                std::istringstream words(line);
                std::string word, version;
                words >> word >> version;
                // '1' and '1.0' name the same format version.
                if (word != "version" || (version != "1" && version != "1.0"))
                    throw ProblemError(path, "version", "first line '" + shortLine(line) + "', expected 'version 1'");
            }
            std::vector<MovingAiScenario> scenarios;
            int lineNumber = 1;
            while (readLine(in, line))
            {
                ++lineNumber;
                if (line.find_first_not_of(" \t") == std::string::npos)
                    continue;
                std::istringstream words(line);
                MovingAiScenario s;
                s.line = lineNumber;
                std::string extra;
                if (!(words >> s.bucket >> s.map >> s.mapWidth >> s.mapHeight >> s.startX >> s.startY >> s.goalX >>
                      s.goalY >> s.optimalLength) ||
                    (words >> extra))
                    throw ProblemError(path, "line " + std::to_string(lineNumber),
                                       "'" + line +
                                           "': expected bucket, map, width, height, start x, start y, goal x, "
                                           "goal y, optimal length");
                scenarios.push_back(s);
            }
            return scenarios;
        }
    }  // namespace tools
}  // namespace michi
