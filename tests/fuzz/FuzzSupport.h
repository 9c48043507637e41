// Shared by the fuzz targets (docs/reliability.md): each target writes its input to a file in a private copy of
// problems/ (so relative references to robots, meshes and maps resolve) and calls a real reader, which must either
// succeed or throw a std::exception. A crash, an abort, another exception type, a hang or a leak is a finding.
#ifndef MICHI_TESTS_FUZZ_SUPPORT_
#define MICHI_TESTS_FUZZ_SUPPORT_

#include <ompl/util/Console.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace michi_fuzz
{
    /** \brief A private copy of the source tree's problems/ folder, made once per process in the temporary
        directory and removed at exit. */
    inline const std::string &problemsCopy()
    {
        static const std::string dir = []
        {
            namespace fs = std::filesystem;
            std::string pattern = (fs::temp_directory_path() / "michi-fuzz-XXXXXX").string();
            if (mkdtemp(pattern.data()) == nullptr)
                throw std::runtime_error("cannot make a temporary directory");
            const fs::path copy = fs::path(pattern) / "problems";
            fs::copy(fs::path(MICHI_SOURCE_DIR) / "problems", copy, fs::copy_options::recursive);
            static struct Remover
            {
                std::string root;
                ~Remover()
                {
                    std::error_code ec;
                    std::filesystem::remove_all(root, ec);
                }
            } remover{pattern};
            ompl::msg::setLogLevel(ompl::msg::LOG_NONE);  // readers warn on odd input; keep the fuzzer's output
            return copy.string();
        }();
        return dir;
    }

    /** \brief Writes \e data to \e name inside the problems copy (name may hold a sub-folder) and returns its path. */
    inline std::string writeInput(const std::string &name, const std::uint8_t *data, std::size_t size)
    {
        const std::string path = problemsCopy() + "/" + name;
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char *>(data), static_cast<std::streamsize>(size));
        if (!out)
            throw std::logic_error("cannot write the fuzz input " + path);
        return path;
    }

    /** \brief Runs \e f; a std::exception is a clean rejection of the input (printed when MICHI_FUZZ_VERBOSE is set).
        Anything else escapes (a finding). */
    template <typename F>
    void expectCleanResult(F &&f)
    {
        try
        {
            f();
        }
        catch (const std::exception &e)
        {
            static const bool verbose = std::getenv("MICHI_FUZZ_VERBOSE") != nullptr;
            if (verbose)
                std::fprintf(stderr, "rejected: %s\n", e.what());
        }
    }
}  // namespace michi_fuzz

#endif
