#include <michi/validity/scene/OccupancyImage.h>
#include <michi/validity/scene/Scene.h>
#include <michi/validity/Limits.h>

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace michi
{
    namespace validity
    {
        namespace
        {
            /** Next header token of a PGM file, skipping white space and # comments. */
            std::string headerToken(std::istream &in)
            {
                std::string token;
                while (in)
                {
                    const int c = in.get();
                    if (c == '#')
                    {
                        std::string rest;
                        std::getline(in, rest);
                    }
                    else if (std::isspace(c) || c == EOF)
                    {
                        if (!token.empty())
                            return token;
                    }
                    else
                        token.push_back(static_cast<char>(c));
                }
                return token;
            }

            int headerInt(std::istream &in, const std::string &path, const char *what)
            {
                const std::string token = headerToken(in);
                try
                {
                    std::size_t used = 0;
                    const int v = std::stoi(token, &used);
                    if (used == token.size() && v > 0)
                        return v;
                }
                catch (const std::exception &)
                {
                }
                throw std::runtime_error(path + ": PGM " + what + " is '" + token + "', expected a positive integer");
            }
        }  // namespace

        namespace
        {
            GreyImage readPgm(const std::string &pgmPath, std::uint64_t fileSize)
            {
                std::ifstream in(pgmPath, std::ios::binary);
                if (!in)
                    throw std::runtime_error(pgmPath + ": cannot open map image");
                const std::string magic = headerToken(in);
                if (magic != "P5" && magic != "P2")
                    throw std::runtime_error(pgmPath + ": not a PGM image (magic '" + magic +
                                             "', expected P2 or P5) nor a PNG image");
                const int width = headerInt(in, pgmPath, "width");
                const int rows = headerInt(in, pgmPath, "height");
                const int maxValue = headerInt(in, pgmPath, "maximum grey value");
                if (maxValue > 65535)
                    throw std::runtime_error(pgmPath + ": maximum grey value above 65535");
                const std::uint64_t cells = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(rows);
                if (cells > MAX_MAP_CELLS)
                    throw std::runtime_error(pgmPath + ": PGM of " + std::to_string(width) + " x " +
                                             std::to_string(rows) + " cells is above the limit of " +
                                             std::to_string(MAX_MAP_CELLS) + " cells");
                // the header must agree with the data before anything is allocated: a 21-byte file claiming
                // 50000 x 50000 cells must not allocate 10 GB
                const int bytes = maxValue < 256 ? 1 : 2;
                const auto dataStart = static_cast<std::uint64_t>(in.tellg());
                const std::uint64_t available = fileSize > dataStart ? fileSize - dataStart : 0;
                const std::uint64_t needed = magic == "P5" ? cells * bytes : 2 * cells - 1;  // P2: digit + separator
                if (available < needed)
                    throw std::runtime_error(pgmPath + ": image data is truncated (header says " +
                                             std::to_string(width) + " x " + std::to_string(rows) +
                                             " cells, the file holds " + std::to_string(available) + " bytes of data)");
                GreyImage image;
                image.width = width;
                image.rows = rows;
                image.maxValue = maxValue;
                std::vector<int> &pixels = image.grey;
                pixels.resize(cells);
                if (magic == "P5")
                {
                    std::vector<unsigned char> raw(pixels.size() * bytes);
                    in.read(reinterpret_cast<char *>(raw.data()), static_cast<std::streamsize>(raw.size()));
                    if (in.gcount() != static_cast<std::streamsize>(raw.size()))
                        throw std::runtime_error(pgmPath + ": image data is truncated");
                    for (std::size_t i = 0; i < pixels.size(); ++i)
                        // 16-bit PGM samples are stored most significant byte first.
                        pixels[i] = bytes == 1 ? raw[i] : (raw[2 * i] << 8) | raw[2 * i + 1];
                    // Data left over means the header's size is wrong; read with it, the map would come out sheared,
                    // not refused.
                    if (in.peek() != std::char_traits<char>::eof())
                        throw std::runtime_error(pgmPath + ": holds more data than its header's " +
                                                 std::to_string(width) + " x " + std::to_string(rows) + " cells");
                }
                else
                {
                    for (auto &p : pixels)
                        if (!(in >> p) || p < 0 || p > maxValue)
                            throw std::runtime_error(pgmPath + ": image data is truncated or has a value outside 0.." +
                                                     std::to_string(maxValue));
                    std::string extra;
                    if (in >> extra)
                        throw std::runtime_error(pgmPath + ": holds more data than its header's " +
                                                 std::to_string(width) + " x " + std::to_string(rows) + " cells");
                }
                return image;
            }

            GreyImage readPng(const std::string &path)
            {
                // libpng's simplified API, as RGBA: a grey image gives R = G = B, an image without alpha gives alpha
                // at its maximum. An 8-bit file is read as 8-bit sRGB (its samples as stored); a 16-bit file as
                // 16-bit "linear", which is how libpng takes 16-bit samples, so they too come as stored. Read as
                // 8-bit, a 16-bit file was converted from linear to sRGB: 0.3 of white became 0.58 and dark
                // cells came out free.
                png_image png;
                std::memset(&png, 0, sizeof(png));
                png.version = PNG_IMAGE_VERSION;
                if (!png_image_begin_read_from_file(&png, path.c_str()))
                    throw std::runtime_error(path + ": not a readable PNG image (" + png.message + ")");
                const std::uint64_t cells = static_cast<std::uint64_t>(png.width) * png.height;
                if (png.width == 0 || png.height == 0 || cells > MAX_MAP_CELLS || png.width > 1u << 30)
                {
                    png_image_free(&png);
                    throw std::runtime_error(path + ": PNG of " + std::to_string(png.width) + " x " +
                                             std::to_string(png.height) + " cells is empty or above the limit of " +
                                             std::to_string(MAX_MAP_CELLS) + " cells");
                }
                // Read before format is set below, which always has an alpha channel.
                const bool hasAlpha = (png.format & PNG_FORMAT_FLAG_ALPHA) != 0;
                const bool sixteen = (png.format & PNG_FORMAT_FLAG_LINEAR) != 0;
                png.format = sixteen ? PNG_FORMAT_LINEAR_RGB_ALPHA : PNG_FORMAT_RGBA;
                const int sampleMax = sixteen ? 65535 : 255;
                std::vector<std::uint8_t> bytes(PNG_IMAGE_SIZE(png));
                if (!png_image_finish_read(&png, nullptr, bytes.data(), 0, nullptr))
                {
                    const std::string message = png.message;
                    png_image_free(&png);
                    throw std::runtime_error(path + ": cannot decode the PNG image (" + message + ")");
                }
                GreyImage image;
                image.width = static_cast<int>(png.width);
                image.rows = static_cast<int>(png.height);
                // the sum of the three channels, so that their mean is exact (map_server averages in floating point)
                image.maxValue = 3 * sampleMax;
                image.alphaMax = sampleMax;
                image.grey.resize(cells);
                if (hasAlpha)
                    image.alpha.resize(cells);
                for (std::size_t i = 0; i < cells; ++i)
                {
                    int c[4];
                    if (sixteen)
                    {
                        std::uint16_t v[4];
                        std::memcpy(v, bytes.data() + 8 * i, sizeof v);
                        for (int k = 0; k < 4; ++k)
                            c[k] = v[k];
                        // libpng premultiplies linear colour by alpha: undone, rounded to nearest (a fully
                        // transparent pixel keeps no colour and reads as black)
                        if (c[3] > 0 && c[3] < 65535)
                            for (int k = 0; k < 3; ++k)
                                c[k] = static_cast<int>(std::min<std::int64_t>(
                                    65535, (static_cast<std::int64_t>(c[k]) * 65535 + c[3] / 2) / c[3]));
                    }
                    else
                        for (int k = 0; k < 4; ++k)
                            c[k] = bytes[4 * i + static_cast<std::size_t>(k)];
                    image.grey[i] = c[0] + c[1] + c[2];
                    if (hasAlpha)
                        image.alpha[i] = static_cast<std::uint16_t>(c[3]);
                }
                return image;
            }
        }  // namespace

        GreyImage readGreyImage(const std::string &path)
        {
            // a directory or a device (/dev/zero) would read forever or fail with a raw library message
            std::error_code ec;
            if (!std::filesystem::is_regular_file(path, ec))
                throw std::runtime_error(path + ": not a regular file");
            const auto fileSize = std::filesystem::file_size(path, ec);
            if (ec)
                throw std::runtime_error(path + ": cannot read the file size: " + ec.message());
            char signature[8] = {0};
            {
                std::ifstream in(path, std::ios::binary);
                if (!in)
                    throw std::runtime_error(path + ": cannot open map image");
                in.read(signature, 8);
            }
            static const unsigned char PNG_SIGNATURE[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
            if (fileSize >= 8 && std::memcmp(signature, PNG_SIGNATURE, 8) == 0)
                return readPng(path);
            return readPgm(path, fileSize);
        }

        std::vector<Obstacle> cellObstacles(const std::vector<std::uint8_t> &occupied, int width, int rows,
                                            double resolution, const Eigen::Vector2d &origin, double height, double yaw,
                                            const std::string &what)
        {
            if (!(resolution > 0.))
                throw std::invalid_argument(what + ": resolution must be positive");
            if (occupied.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(rows))
                throw std::invalid_argument(what + ": occupancy does not match the image size");
            if (!isGeometryValue(width * resolution) || !isGeometryValue(rows * resolution) ||
                !isGeometryValue(origin.x()) || !isGeometryValue(origin.y()) || !isGeometryValue(height) ||
                !std::isfinite(yaw))
                throw std::invalid_argument(what + ": the map's extent, origin or height is out of range");
            // the map's frame: origin at its lower-left corner, turned by yaw (ROS map_server's origin)
            Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
            frame.translation() = Eigen::Vector3d(origin.x(), origin.y(), 0.);
            frame.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
            std::vector<Obstacle> obstacles;
            for (int r = 0; r < rows; ++r)
            {
                const double y = (rows - 1 - r + 0.5) * resolution;  // image row 0 is the top
                // One box per run of occupied cells in a row, not one per cell: a 512 x 512 map then holds thousands of
                // obstacles, not hundreds of thousands, for the broad phase.
                int c = 0;
                while (c < width)
                {
                    if (!occupied[static_cast<std::size_t>(r) * width + c])
                    {
                        ++c;
                        continue;
                    }
                    const int start = c;
                    while (c < width && occupied[static_cast<std::size_t>(r) * width + c])
                        ++c;
                    Obstacle o;
                    o.name = "cells_r" + std::to_string(r) + "_c" + std::to_string(start);
                    o.shape = Shape::box(Eigen::Vector3d((c - start) * resolution, resolution, height));
                    Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
                    local.translation() = Eigen::Vector3d(0.5 * (start + c) * resolution, y, 0.5 * height);
                    o.pose = yaw == 0. ? local : frame * local;
                    if (yaw == 0.)
                        o.pose.translation() += Eigen::Vector3d(origin.x(), origin.y(), 0.);
                    obstacles.push_back(std::move(o));
                }
            }
            return obstacles;
        }

        std::vector<Obstacle> occupancyObstacles(const std::string &pgmPath, double resolution,
                                                 const Eigen::Vector2d &origin, double height, double threshold)
        {
            if (!(resolution > 0.))
                throw std::invalid_argument(pgmPath + ": resolution must be positive");
            if (!(threshold > 0. && threshold <= 1.))
                throw std::invalid_argument(pgmPath + ": threshold must be in (0, 1]");
            const GreyImage image = readGreyImage(pgmPath);
            std::vector<std::uint8_t> occupied(image.grey.size());
            for (std::size_t i = 0; i < occupied.size(); ++i)
                // Dark is occupied (a PGM map's convention): a cell darker than the threshold's share of the maximum
                // grey.
                occupied[i] = image.grey[i] < threshold * image.maxValue ? 1 : 0;
            return cellObstacles(occupied, image.width, image.rows, resolution, origin, height, 0., pgmPath);
        }
    }  // namespace validity
}  // namespace michi
