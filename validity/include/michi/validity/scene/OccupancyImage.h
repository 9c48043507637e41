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
            int maxValue{255};                ///< the white value
            std::vector<int> grey;            ///< per pixel, 0..maxValue (a colour pixel: the mean of its channels)
            std::vector<std::uint8_t> alpha;  ///< per pixel 0..255; empty when the image has no alpha channel
        };

        /** \brief Read a PGM (P2, P5; 8 or 16 bits) or PNG (any colour type, 8 bits a channel) image, told apart
            by content. Throws std::runtime_error naming the file when it cannot be read. */
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
