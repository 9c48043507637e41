// Runs the built `michi` command for the command-line tests.
#ifndef MICHI_TESTS_SUPPORT_MICHI_COMMAND_
#define MICHI_TESTS_SUPPORT_MICHI_COMMAND_

#include <string>

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
    }  // namespace test
}  // namespace michi

#endif
