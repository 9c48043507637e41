#ifndef MICHI_VALIDITY_INPUT_FILE_
#define MICHI_VALIDITY_INPUT_FILE_

#include <cstdint>
#include <stdexcept>
#include <string>

namespace michi
{
    namespace validity
    {
        /** \brief Largest input file michi reads whole (problem, URDF, map, scene, experience files): 1 GiB. */
        constexpr std::uint64_t MAX_INPUT_FILE_BYTES = 1ULL << 30;

        /** \brief An input file that cannot be read: what() is "<path>: <reason>", reason() the part after it. */
        class InputFileError : public std::runtime_error
        {
        public:
            InputFileError(const std::string &path, const std::string &reason)
                : std::runtime_error(path + ": " + reason), reason_(reason)
            {
            }
            const std::string &reason() const
            {
                return reason_;
            }

        private:
            std::string reason_;
        };

        /** \brief Throws InputFileError unless \e path is a regular file that can be read
            and is at most \e maxBytes long. A directory, a device such as /dev/zero or a FIFO would otherwise give
            a raw library message ("basic_filebuf::underflow ... Is a directory") or read without end. Returns the
            file's size in bytes. */
        std::uint64_t requireInputFile(const std::string &path, std::uint64_t maxBytes = MAX_INPUT_FILE_BYTES);

        /** \brief The whole content of an input file checked by requireInputFile(). */
        std::string readInputFile(const std::string &path, std::uint64_t maxBytes = MAX_INPUT_FILE_BYTES);
    }  // namespace validity
}  // namespace michi

#endif
