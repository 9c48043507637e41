#ifndef MICHI_PLANNERS_PATH_SEED_LIBRARY_
#define MICHI_PLANNERS_PATH_SEED_LIBRARY_

#include <michi/planners/path_seed/PathSeedCodec.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief A path seed file that cannot be read: what() is "<file>: line <n>: <what was expected>". */
        class PathSeedFileError : public std::runtime_error
        {
        public:
            using std::runtime_error::runtime_error;
        };

        /** \brief One learned seed and the query it came from (retrieval compares queries). */
        struct SeedRecord
        {
            Eigen::VectorXd start;
            Eigen::VectorXd goal;
            PathSeedCode code;
            double length{0.};    ///< joint-space length of the path it was encoded from
            std::uint64_t id{0};  ///< unique in its library (order of addition), for markUsed()
            std::size_t uses{0};  ///< solutions it took part in (markUsed; not saved to files)
        };

        /** \brief A library of path seeds (paper 001): seeds learned from solved paths, saved to and loaded
            from a versioned text file, retrieved for a new query by the nearness of their queries
            (distance sqrt(|s - s'|^2 + |g - g'|^2), the nearest first). Thread-safe. */
        class PathSeedLibrary
        {
        public:
            /** \brief First line of a library file; the number is the format version. */
            static constexpr const char *FILE_MAGIC = "michi-path-seed-library";
            static constexpr int FILE_VERSION = 1;

            explicit PathSeedLibrary(SeedVariant variant = SeedVariant::BLOCKS);

            /** \brief Encode \e path (start, waypoints, goal) and keep it. Throws std::invalid_argument when its
                dimension differs from the library's (set by the first seed), or when its seed is not finite (joint
                values too large to encode: save() could not write it as a file load() reads). */
            void add(const std::vector<Eigen::VectorXd> &path);

            /** \brief Up to \e k seeds whose queries are nearest to (start, goal), nearest first. */
            std::vector<SeedRecord> candidates(const Eigen::VectorXd &start, const Eigen::VectorXd &goal,
                                               std::size_t k) const;

            /** \brief At most \e seeds seeds (0: no bound). Past the bound the library forgets the seed that took
                part in the fewest solutions, the oldest of those first (a seed just added has had no chance to be
                used, so it goes last among the unused); already past it, seeds are forgotten now. */
            void setCapacity(std::size_t seeds);
            std::size_t capacity() const;
            /** \brief Seed \e id took part in a solution (no effect when it was forgotten). */
            void markUsed(std::uint64_t id);

            std::size_t size() const;
            unsigned int dimension() const;
            SeedVariant variant() const
            {
                return variant_;
            }
            /** \brief Copy of seed \e i. */
            SeedRecord seed(std::size_t i) const;
            void clear();

            /** \brief Write the library (temporary file, then renamed: never half-written). Throws
                std::runtime_error when the file cannot be written. */
            void save(const std::string &file) const;
            /** \brief Read a library file; throws PathSeedFileError naming the file, the line and what was
                expected (wrong magic, unsupported version, truncated or non-numeric data). */
            static std::shared_ptr<PathSeedLibrary> load(const std::string &file);

        private:
            SeedVariant variant_;
            unsigned int dimension_{0};
            /** forget seeds past capacity_ (mutex_ held) */
            void shrink();
            std::vector<SeedRecord> seeds_;
            std::size_t capacity_{0};
            std::uint64_t nextId_{0};
            mutable std::mutex mutex_;
        };

        using PathSeedLibraryPtr = std::shared_ptr<PathSeedLibrary>;
    }  // namespace planners
}  // namespace michi

#endif
