#include <michi/validity/scene/Scene.h>
#include <michi/validity/Limits.h>

#include <cstdint>
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

        std::vector<Obstacle> occupancyObstacles(const std::string &pgmPath, double resolution,
                                                 const Eigen::Vector2d &origin, double height, double threshold)
        {
            if (!(resolution > 0.))
                throw std::invalid_argument(pgmPath + ": resolution must be positive");
            // a directory or a device (/dev/zero) would read forever or fail with a raw library message
            std::error_code ec;
            if (!std::filesystem::is_regular_file(pgmPath, ec))
                throw std::runtime_error(pgmPath + ": not a regular file");
            const auto fileSize = std::filesystem::file_size(pgmPath, ec);
            if (ec)
                throw std::runtime_error(pgmPath + ": cannot read the file size: " + ec.message());
            std::ifstream in(pgmPath, std::ios::binary);
            if (!in)
                throw std::runtime_error(pgmPath + ": cannot open map image");
            const std::string magic = headerToken(in);
            if (magic != "P5" && magic != "P2")
                throw std::runtime_error(pgmPath + ": not a PGM image (magic '" + magic + "', expected P2 or P5)");
            const int width = headerInt(in, pgmPath, "width");
            const int rows = headerInt(in, pgmPath, "height");
            const int maxValue = headerInt(in, pgmPath, "maximum grey value");
            if (maxValue > 65535)
                throw std::runtime_error(pgmPath + ": maximum grey value above 65535");
            const std::uint64_t cells = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(rows);
            if (cells > MAX_MAP_CELLS)
                throw std::runtime_error(pgmPath + ": PGM of " + std::to_string(width) + " x " + std::to_string(rows) +
                                         " cells is above the limit of " + std::to_string(MAX_MAP_CELLS) + " cells");
            // the header must agree with the data before anything is allocated: a 21-byte file claiming
            // 50000 x 50000 cells must not allocate 10 GB
            const int bytes = maxValue < 256 ? 1 : 2;
            const auto dataStart = static_cast<std::uint64_t>(in.tellg());
            const std::uint64_t available = fileSize > dataStart ? fileSize - dataStart : 0;
            const std::uint64_t needed = magic == "P5" ? cells * bytes : 2 * cells - 1;  // P2: digit + separator
            if (available < needed)
                throw std::runtime_error(pgmPath + ": image data is truncated (header says " + std::to_string(width) +
                                         " x " + std::to_string(rows) + " cells, the file holds " +
                                         std::to_string(available) + " bytes of data)");
            std::vector<int> pixels(cells);
            if (magic == "P5")
            {
                std::vector<unsigned char> raw(pixels.size() * bytes);
                in.read(reinterpret_cast<char *>(raw.data()), static_cast<std::streamsize>(raw.size()));
                if (in.gcount() != static_cast<std::streamsize>(raw.size()))
                    throw std::runtime_error(pgmPath + ": image data is truncated");
                for (std::size_t i = 0; i < pixels.size(); ++i)
                    pixels[i] = bytes == 1 ? raw[i] : (raw[2 * i] << 8) | raw[2 * i + 1];
                if (in.peek() != std::char_traits<char>::eof())
                    throw std::runtime_error(pgmPath + ": holds more data than its header's " + std::to_string(width) +
                                             " x " + std::to_string(rows) + " cells");
            }
            else
            {
                for (auto &p : pixels)
                    if (!(in >> p) || p < 0 || p > maxValue)
                        throw std::runtime_error(pgmPath + ": image data is truncated or has a value outside 0.." +
                                                 std::to_string(maxValue));
                std::string extra;
                if (in >> extra)
                    throw std::runtime_error(pgmPath + ": holds more data than its header's " + std::to_string(width) +
                                             " x " + std::to_string(rows) + " cells");
            }
            if (!isGeometryValue(width * resolution) || !isGeometryValue(rows * resolution) ||
                !isGeometryValue(origin.x()) || !isGeometryValue(origin.y()) || !isGeometryValue(height))
                throw std::invalid_argument(pgmPath + ": the map's extent, origin or height is out of range");

            std::vector<Obstacle> obstacles;
            for (int r = 0; r < rows; ++r)
            {
                const double y = origin.y() + (rows - 1 - r + 0.5) * resolution;  // image row 0 is the top
                int c = 0;
                while (c < width)
                {
                    if (pixels[static_cast<std::size_t>(r) * width + c] >= threshold * maxValue)
                    {
                        ++c;
                        continue;
                    }
                    const int start = c;
                    while (c < width && pixels[static_cast<std::size_t>(r) * width + c] < threshold * maxValue)
                        ++c;
                    Obstacle o;
                    o.name = "cells_r" + std::to_string(r) + "_c" + std::to_string(start);
                    o.shape = Shape::box(Eigen::Vector3d((c - start) * resolution, resolution, height));
                    o.pose.translation() =
                        Eigen::Vector3d(origin.x() + 0.5 * (start + c) * resolution, y, 0.5 * height);
                    obstacles.push_back(std::move(o));
                }
            }
            return obstacles;
        }
    }  // namespace validity
}  // namespace michi
