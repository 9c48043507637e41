#ifndef MICHI_VALIDITY_SCENE_OCCUPANCY_IMAGE_
#define MICHI_VALIDITY_SCENE_OCCUPANCY_IMAGE_

#include <michi/validity/scene/Scene.h>

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief A grey image, row 0 the top. */
        struct GreyImage
        {
            int width{0}, rows{0};
            /** the white value: a PGM's maximum grey value; for a PNG 3 x the sample maximum (255 or 65535),
                since grey holds the sum of the three colour channels (exact: their mean is grey / maxValue) */
            int maxValue{255};
            std::vector<int> grey;             ///< per pixel, 0..maxValue
            std::vector<std::uint16_t> alpha;  ///< per pixel 0..alphaMax; empty when the image has no alpha channel
            int alphaMax{255};                 ///< fully opaque (the PNG's sample maximum)
        };

        /** \brief Read a PGM (P2, P5; 8 or 16 bits) or PNG (any colour type, 8 or 16 bits a channel) image, told
            apart by content. Samples are read as stored (value / maximum, as ROS map_server reads them), not
            converted between linear and sRGB. Throws std::runtime_error naming the file when it cannot be read. */
        GreyImage readGreyImage(const std::string &path);

        /** \brief One box per run of occupied cells in each row (\e occupied: width x rows, row 0 the top; boxes
            named cells_r<row>_c<first column>), in the map's frame: its lower-left corner at \e origin, turned by
            \e yaw about it. \e what names the source in errors (std::invalid_argument). */
        std::vector<Obstacle> cellObstacles(const std::vector<std::uint8_t> &occupied, int width, int rows,
                                            double resolution, const Eigen::Vector2d &origin, double height, double yaw,
                                            const std::string &what);
    }  // namespace validity
}  // namespace michi

#endif
