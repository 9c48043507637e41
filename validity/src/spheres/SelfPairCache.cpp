#include "SelfPairCache.h"

#include <michi/validity/robot/RobotModel.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace michi
{
    namespace validity
    {
        void Fnv64::bytes(const void *data, std::size_t n)
        {
            const auto *p = static_cast<const unsigned char *>(data);
            for (std::size_t i = 0; i < n; ++i)
            {
                h_ ^= p[i];
                h_ *= 1099511628211ull;
            }
        }

        namespace
        {
            void hashPose(const Eigen::Isometry3d &pose, Fnv64 &hash)
            {
                hash.bytes(pose.matrix().data(), 16 * sizeof(double));
            }

            constexpr char MAGIC[8] = {'M', 'S', 'P', 'T', 'B', 'L', '0', '1'};
        }  // namespace

        void hashRobotGeometry(const RobotModel &model, Fnv64 &hash)
        {
            for (const auto &link : model.links())
            {
                hash.text(link.name);
                hash.value(link.collisions.size());
                for (const auto &c : link.collisions)
                {
                    hash.value(static_cast<int>(c.shape->type()));
                    hash.bytes(c.shape->size().data(), 3 * sizeof(double));
                    hashPose(c.origin, hash);
                    for (const auto &v : c.shape->outline())
                        hash.bytes(v.data(), 2 * sizeof(double));
                    for (const auto &v : c.shape->vertices())
                        hash.bytes(v.data(), 3 * sizeof(double));
                    for (const auto &t : c.shape->triangles())
                        hash.bytes(t.data(), 3 * sizeof(int));
                }
            }
            for (const auto &joint : model.joints())
            {
                hash.text(joint.name);
                hash.value(static_cast<int>(joint.type));
                hash.value(joint.parentLink);
                hash.value(joint.childLink);
                hashPose(joint.origin, hash);
                hash.bytes(joint.axis.data(), 3 * sizeof(double));
                hash.value(joint.lower);
                hash.value(joint.upper);
                hash.value(joint.variable);
            }
        }

        std::string selfPairCacheDir()
        {
            if (const char *dir = std::getenv("MICHI_CACHE_DIR"); dir != nullptr && *dir != '\0')
                return dir;
            if (const char *xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg != '\0')
                return std::string(xdg) + "/michi";
            if (const char *home = std::getenv("HOME"); home != nullptr && *home != '\0')
                return std::string(home) + "/.cache/michi";
            return "";
        }

        namespace
        {
            std::string cacheFile(const std::string &dir, std::uint64_t key)
            {
                char name[64];
                std::snprintf(name, sizeof(name), "self-pairs-%016llx.bin", static_cast<unsigned long long>(key));
                return dir + "/" + name;
            }
        }  // namespace

        bool readSelfPairCache(const std::string &dir, std::uint64_t key, std::size_t tables,
                               std::vector<std::vector<std::uint64_t>> &bits)
        {
            if (dir.empty())
                return false;
            std::ifstream in(cacheFile(dir, key), std::ios::binary);
            if (!in)
                return false;
            std::stringstream buffer;
            buffer << in.rdbuf();
            const std::string data = buffer.str();
            // layout: magic, key, table count, per table (word count, words), checksum of everything before it
            std::size_t at = 0;
            auto take = [&](void *out, std::size_t n)
            {
                if (at + n > data.size())
                    return false;
                std::copy(data.data() + at, data.data() + at + n, static_cast<char *>(out));
                at += n;
                return true;
            };
            char magic[8];
            std::uint64_t storedKey = 0, count = 0;
            if (!take(magic, 8) || !std::equal(magic, magic + 8, MAGIC) || !take(&storedKey, 8) || storedKey != key ||
                !take(&count, 8) || count != tables)
                return false;
            std::vector<std::vector<std::uint64_t>> out(tables);
            for (auto &words : out)
            {
                std::uint64_t n = 0;
                if (!take(&n, 8) || n > (data.size() - at) / 8)
                    return false;
                words.resize(n);
                if (!take(words.data(), 8 * n))
                    return false;
            }
            Fnv64 sum;
            sum.bytes(data.data(), at);
            std::uint64_t stored = 0;
            if (!take(&stored, 8) || stored != sum.digest() || at != data.size())
                return false;
            bits = std::move(out);
            return true;
        }

        void writeSelfPairCache(const std::string &dir, std::uint64_t key,
                                const std::vector<std::vector<std::uint64_t>> &bits)
        {
            if (dir.empty())
                return;
            std::string data(MAGIC, 8);
            auto put = [&](const void *p, std::size_t n)
            {
                data.append(static_cast<const char *>(p), n);
            };
            const std::uint64_t count = bits.size();
            put(&key, 8);
            put(&count, 8);
            for (const auto &words : bits)
            {
                const std::uint64_t n = words.size();
                put(&n, 8);
                put(words.data(), 8 * words.size());
            }
            Fnv64 sum;
            sum.bytes(data.data(), data.size());
            const std::uint64_t checksum = sum.digest();
            put(&checksum, 8);
            std::error_code error;
            std::filesystem::create_directories(dir, error);
            const std::string file = cacheFile(dir, key);
            // per process: two processes writing the same tables do not write into one temporary file
            const std::string temporary = file + ".tmp" + std::to_string(::getpid());
            {
                std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
                if (!out)
                    return;
                out.write(data.data(), static_cast<std::streamsize>(data.size()));
                if (!out)
                {
                    out.close();
                    std::filesystem::remove(temporary, error);
                    return;
                }
            }
            std::filesystem::rename(temporary, file, error);
            if (error)
                std::filesystem::remove(temporary, error);
        }
    }  // namespace validity
}  // namespace michi
