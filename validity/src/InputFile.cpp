#include <michi/validity/InputFile.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace michi
{
    namespace validity
    {
        std::uint64_t requireInputFile(const std::string &path, std::uint64_t maxBytes)
        {
            namespace fs = std::filesystem;
            std::error_code ec;
            const fs::file_status status = fs::status(path, ec);
            if (ec || !fs::exists(status))
                throw InputFileError(path, "no such file");
            if (fs::is_directory(status))
                throw InputFileError(path, "is a directory, expected a file");
            // A device or FIFO would read forever (/dev/zero) or block, and a library would report it with a raw
            // message.
            if (!fs::is_regular_file(status))
                throw InputFileError(path, "not a regular file (a device, FIFO or socket)");
            const std::uint64_t size = fs::file_size(path, ec);
            if (ec)
                throw InputFileError(path, "cannot read: " + ec.message());
            // Before reading: a huge file is refused by its size, not after filling the memory.
            if (size > maxBytes)
                throw InputFileError(path, "file of " + std::to_string(size) + " bytes is above the limit of " +
                                               std::to_string(maxBytes) + " bytes");
            // Opened once here, so a permission problem is reported with the file's name instead of by the reader that
            // follows.
            std::ifstream probe(path, std::ios::binary);
            if (!probe)
                throw InputFileError(path, "cannot open the file (permissions?)");
            return size;
        }

        std::string readInputFile(const std::string &path, std::uint64_t maxBytes)
        {
            requireInputFile(path, maxBytes);
            std::ifstream in(path, std::ios::binary);
            std::ostringstream buffer;
            buffer << in.rdbuf();
            if (!in && !in.eof())
                throw InputFileError(path, "read error");
            return buffer.str();
        }
    }  // namespace validity
}  // namespace michi
