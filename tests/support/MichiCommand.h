// Runs the built `michi` command for the command-line tests.
#ifndef MICHI_TESTS_SUPPORT_MICHI_COMMAND_
#define MICHI_TESTS_SUPPORT_MICHI_COMMAND_

#include <string>
#include <utility>

namespace michi
{
    namespace test
    {
        /** \brief What a run of `michi` gave: its exit code (128 + signal when killed) and stdout + stderr. */
        struct CommandRun
        {
            int exitCode;
            std::string output;
        };

        /** \brief Run build/bin/michi with \e args (a shell command line) and capture both output streams. */
        CommandRun runMichi(const std::string &args);

        /** \brief A bundled problem: problems/<name>.yaml of the source tree. */
        std::string problemFile(const std::string &name);

        /** \brief The bytes of a file (empty when it cannot be read): what a command wrote. */
        std::string slurp(const std::string &file);
        /** \brief Load problem file \e path (and, with \e plan, make its planning context) and return the error
            message, which must be one line; fails the calling test if loading succeeds. */
        std::string problemLoadError(const std::string &path, bool plan = false);

        /** \brief The same for a path object (boost::filesystem::path, std::filesystem::path). */
        template <typename Path, typename = decltype(std::declval<const Path &>().string())>
        std::string slurp(const Path &file)
        {
            return slurp(std::string(file.string()));
        }
    }  // namespace test
}  // namespace michi

#endif
