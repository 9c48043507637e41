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
            if (!fs::is_regular_file(status))
                throw InputFileError(path, "not a regular file (a device, FIFO or socket)");
            const std::uint64_t size = fs::file_size(path, ec);
            if (ec)
                throw InputFileError(path, "cannot read: " + ec.message());
            if (size > maxBytes)
                throw InputFileError(path, "file of " + std::to_string(size) + " bytes is above the limit of " +
                                               std::to_string(maxBytes) + " bytes");
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
