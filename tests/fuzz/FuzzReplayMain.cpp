// main() of a fuzz target in a build without libFuzzer (docs/reliability.md): replays every file of the folders
// (or files) given on the command line through LLVMFuzzerTestOneInput, so the seed corpus and every input that once
// crashed a reader (tests/fuzz/regressions/<target>/) run as an ordinary ctest test (label fuzz).
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size);
extern "C" __attribute__((weak)) int LLVMFuzzerInitialize(int *argc, char ***argv);

int main(int argc, char **argv)
{
    namespace fs = std::filesystem;
    if (LLVMFuzzerInitialize)
        LLVMFuzzerInitialize(&argc, &argv);
    std::vector<fs::path> files;
    for (int i = 1; i < argc; ++i)
    {
        const fs::path p(argv[i]);
        if (fs::is_directory(p))
        {
            for (const auto &e : fs::recursive_directory_iterator(p))
                if (e.is_regular_file() && e.path().filename().string()[0] != '.')
                    files.push_back(e.path());
        }
        else if (fs::is_regular_file(p))
            files.push_back(p);
        else if (!fs::exists(p))
            std::printf("replay: %s does not exist (no inputs there yet)\n", argv[i]);
    }
    std::sort(files.begin(), files.end());
    for (const auto &f : files)
    {
        std::ifstream in(f, std::ios::binary);
        const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::printf("replay: %s (%zu bytes)", f.c_str(), bytes.size());
        std::fflush(stdout);
        const auto t0 = std::chrono::steady_clock::now();
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t *>(bytes.data()), bytes.size());
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::printf(" %.3f s\n", s);
    }
    std::printf("replay: %zu inputs, no crash\n", files.size());
    return 0;
}
