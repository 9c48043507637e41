#ifndef MICHI_VALIDITY_SPHERES_SELF_PAIR_CACHE_
#define MICHI_VALIDITY_SPHERES_SELF_PAIR_CACHE_

// Internal to the sphere checker: the self-pair tables on disk. Building them takes FCL distances over whole grids
// (seconds for the Panda), yet they depend on the robot alone, so a checker made again for the same robot (another
// problem of a dataset, another process of a campaign) reads them back. The file is named by a hash of everything the
// tables are built from (geometry, joints, the cells and bounds of each table), and carries a checksum: a file that
// does not match is ignored and rebuilt, never trusted.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace michi
{
    namespace validity
    {
        class RobotModel;

        /** \brief 64-bit FNV-1a over the bytes fed to it. */
        class Fnv64
        {
        public:
            void bytes(const void *data, std::size_t n);
            template <typename T>
            void value(const T &v)
            {
                bytes(&v, sizeof(T));
            }
            void text(const std::string &s)
            {
                value(s.size());
                bytes(s.data(), s.size());
            }
            std::uint64_t digest() const
            {
                return h_;
            }

        private:
            std::uint64_t h_{1469598103934665603ull};
        };

        /** \brief Hash of what FCL sees of a robot: every link's collision shapes (kind, size, pose, mesh vertices
            and triangles) and every joint (kind, pose, axis, limits, links). */
        void hashRobotGeometry(const RobotModel &model, Fnv64 &hash);

        /** \brief The cache folder: $MICHI_CACHE_DIR, else $XDG_CACHE_HOME/michi, else $HOME/.cache/michi; empty
            when none is set. */
        std::string selfPairCacheDir();

        /** \brief Read the tables' bits stored under \e key (one vector per table, in order); false when there is no
            such file or it does not check out (size, checksum, table count \e tables). */
        bool readSelfPairCache(const std::string &dir, std::uint64_t key, std::size_t tables,
                               std::vector<std::vector<std::uint64_t>> &bits);
        /** \brief Store them (written to a temporary file, then renamed: a reader never sees half a file).
            Failure to write is not an error: the tables are only built again next time. */
        void writeSelfPairCache(const std::string &dir, std::uint64_t key,
                                const std::vector<std::vector<std::uint64_t>> &bits);
    }  // namespace validity
}  // namespace michi

#endif
