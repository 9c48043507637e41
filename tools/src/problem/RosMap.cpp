// ROS map_server maps as scene.map obstacles: the map's YAML file (image, resolution, origin, negate,
// occupied_thresh, free_thresh, mode) and its PGM or PNG image, read the way map_server reads them
// (http://wiki.ros.org/map_server, nav2_map_server), every mistake reported with the map file and its key.
#include "ProblemYaml.h"

#include <michi/validity/scene/OccupancyImage.h>

#include <cmath>

namespace michi
{
    namespace tools
    {
        namespace problem_file
        {
            RosMap readRosMap(const std::string &file, double height)
            {
                const YAML::Node doc = loadYaml(file);
                const Reader r(file);
                if (!doc.IsMap())
                    r.fail("",
                           "expected a ROS map_server map: a mapping with image, resolution, origin, negate, "
                           "occupied_thresh, free_thresh (and mode)");
                r.keys(doc, "", {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh", "mode"});
                RosMap map;
                map.image = r.path(r.require(doc, "image", ""), "image");
                map.resolution = r.number(r.require(doc, "resolution", ""), "resolution");
                if (!(map.resolution >= MIN_MAP_RESOLUTION && map.resolution <= MAX_MAP_RESOLUTION))
                    r.fail("resolution", MAP_RESOLUTION_RANGE);
                const auto origin = r.numbers(r.require(doc, "origin", ""), "origin", 3);
                for (double v : origin)
                    if (!std::isfinite(v) || std::abs(v) > 1e6)
                        r.fail("origin", "expected [x, y, yaw], finite, within 1e6");
                map.origin = Eigen::Vector2d(origin[0], origin[1]);
                map.yaw = origin[2];
                // ROS 1's map_server requires these three; nav2's defaults are taken when they are left out
                bool negate = false;
                if (const YAML::Node n = doc["negate"])
                {
                    const std::string v = n.IsScalar() ? n.Scalar() : "";
                    // 0/1 as map_server documents it, and true/false as YAML writes a boolean.
                    if (v == "0" || v == "false" || v == "False")
                        negate = false;
                    else if (v == "1" || v == "true" || v == "True")
                        negate = true;
                    else
                        r.fail("negate", "expected 0 or 1 (or false / true)");
                }
                const double occupied = r.number(doc, "occupied_thresh", "", 0.65);
                const double free = r.number(doc, "free_thresh", "", 0.25);
                if (!(occupied >= 0. && occupied <= 1.))
                    r.fail("occupied_thresh", "expected a number in [0, 1]");
                if (!(free >= 0. && free <= 1.))
                    r.fail("free_thresh", "expected a number in [0, 1]");
                if (free > occupied)
                    r.fail("free_thresh", "is above occupied_thresh (" + std::to_string(occupied) + ")");
                const std::string mode = doc["mode"] ? r.text(doc["mode"], "mode") : "trinary";
                if (mode != "trinary" && mode != "scale")
                    r.fail("mode", "'" + mode + "' is not supported (expected trinary or scale)");

                validity::GreyImage image;
                try
                {
                    image = validity::readGreyImage(map.image);
                }
                catch (const std::exception &e)
                {
                    r.fail("image", e.what());
                }
                map.width = image.width;
                map.rows = image.rows;
                // occupancy p = (white - grey) / white, or grey / white when negated; p > occupied_thresh is
                // occupied, p < free_thresh free, and in trinary mode anything between is unknown; in scale mode
                // the between values are scaled occupancies (below the occupied threshold: no obstacle) and a
                // pixel that is not fully opaque is unknown. michi plans only through space known to be free:
                // unknown cells are obstacles too.
                std::vector<std::uint8_t> blocked(image.grey.size(), 0);
                const bool alpha = !image.alpha.empty();
                for (std::size_t i = 0; i < blocked.size(); ++i)
                {
                    double v = static_cast<double>(image.grey[i]) / image.maxValue;
                    // Trinary mode averages alpha in with the three colour channels, as both map_servers do (ROS 1's
                    // image_loader and nav2's map_io, "to preserve existing behavior"): a transparent pixel is
                    // unknown there, not free.
                    if (alpha && mode == "trinary")
                        v = (3. * v + static_cast<double>(image.alpha[i]) / image.alphaMax) / 4.;
                    // map_server's convention: dark pixels are occupied, unless negate flips it.
                    const double p = negate ? v : 1. - v;
                    bool unknown;
                    if (mode == "scale")
                        unknown = alpha && image.alpha[i] < image.alphaMax;
                    else
                        unknown = !(p > occupied) && !(p < free);
                    blocked[i] = (p > occupied || unknown) ? 1 : 0;
                    map.occupiedCells += blocked[i];
                }
                try
                {
                    map.obstacles = validity::cellObstacles(blocked, image.width, image.rows, map.resolution,
                                                            map.origin, height, map.yaw, map.image);
                }
                catch (const std::exception &e)
                {
                    r.fail("", e.what());
                }
                return map;
            }
        }  // namespace problem_file
    }      // namespace tools
}  // namespace michi
