#include "viewer/ReplayMap.h"
#include "viewer/ReplayJson.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace michi
{
    namespace tools
    {
        namespace replay
        {
            bool isMapCell(const Problem &problem, const validity::Obstacle &obstacle)
            {
                return problem.grid.mapResolution > 0. && obstacle.trajectory.empty() && obstacle.shape &&
                       // The boxes cellObstacles() makes for a map's rows of occupied cells (named
                       // cells_r<row>_c<col>), and nothing else.
                       obstacle.shape->type() == validity::Shape::Type::BOX && obstacle.name.rfind("cells_r", 0) == 0;
            }

            std::string mapJson(const Problem &problem, const std::vector<validity::Obstacle> &cells)
            {
                const double res = problem.grid.mapResolution;
                double xMin = std::numeric_limits<double>::infinity(), yMin = xMin, xMax = -xMin, yMax = -xMin;
                double wall = 0.;
                struct Box
                {
                    double x0, x1, y0, y1;
                };
                std::vector<Box> boxes;
                for (const auto &cell : cells)
                {
                    // an axis-aligned box: its corners' extent is the cells it covers
                    const Eigen::Vector3d half = 0.5 * cell.shape->size();
                    const Eigen::Vector3d extent = cell.pose.linear().cwiseAbs() * half;
                    const Eigen::Vector3d centre = cell.pose.translation();
                    boxes.push_back({centre.x() - extent.x(), centre.x() + extent.x(), centre.y() - extent.y(),
                                     centre.y() + extent.y()});
                    wall = std::max(wall, centre.z() + extent.z());
                    xMin = std::min(xMin, boxes.back().x0);
                    xMax = std::max(xMax, boxes.back().x1);
                    yMin = std::min(yMin, boxes.back().y0);
                    yMax = std::max(yMax, boxes.back().y1);
                }
                if (problem.kind == Problem::Kind::SE2)
                {
                    // the free space the robot may drive over is part of the picture, occupied or not
                    const auto &b = problem.se2Bounds;
                    xMin = std::min(xMin, b[0]);
                    xMax = std::max(xMax, b[1]);
                    yMin = std::min(yMin, b[2]);
                    yMax = std::max(yMax, b[3]);
                }
                if (!(xMin < xMax && yMin < yMax))
                    return "null";
                const long width = std::max(1L, std::lround((xMax - xMin) / res));
                const long height = std::max(1L, std::lround((yMax - yMin) / res));
                std::vector<char> occupied(static_cast<std::size_t>(width * height), 0);
                auto cellIndex = [&](double v, double lo, long n)
                {
                    // Rounded to the nearest cell border: box edges lie on borders up to rounding, so floor or ceil
                    // could shift a run.
                    return std::clamp(std::lround((v - lo) / res), 0L, n);
                };
                for (const auto &box : boxes)
                {
                    const long i0 = cellIndex(box.x0, xMin, width), i1 = cellIndex(box.x1, xMin, width);
                    const long j0 = cellIndex(box.y0, yMin, height), j1 = cellIndex(box.y1, yMin, height);
                    for (long j = j0; j < j1; ++j)
                        std::fill(occupied.begin() + j * width + i0, occupied.begin() + j * width + i1, 1);
                }
                std::string out = "{\"origin\":[";
                appendFixed(out, xMin, POSITION_DECIMALS);
                out += ',';
                appendFixed(out, yMin, POSITION_DECIMALS);
                out += "],\"resolution\":";
                appendPrecise(out, res);
                out += ",\"width\":" + std::to_string(width) + ",\"height\":" + std::to_string(height) +
                       ",\"wallHeight\":";
                appendFixed(out, wall, POSITION_DECIMALS);
                out += ",\"runs\":[";
                char current = 0;
                long run = 0;
                bool first = true;
                // Run-length encoded, alternating free and occupied and starting with free: a 512 x 512 map is a few
                // thousand numbers, not a quarter of a million.
                for (char c : occupied)
                {
                    if (c != current)
                    {
                        out += (first ? "" : ",") + std::to_string(run);
                        first = false;
                        current = c;
                        run = 0;
                    }
                    ++run;
                }
                out += (first ? "" : ",") + std::to_string(run);
                return out + "]}";
            }
        }  // namespace replay
    }      // namespace tools
}  // namespace michi
