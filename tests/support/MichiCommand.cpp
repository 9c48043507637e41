#include "support/MichiCommand.h"

#include <array>
#include <cstdio>
#include <sys/wait.h>

namespace michi
{
    namespace test
    {
        CommandRun runMichi(const std::string &args)
        {
            const std::string command = std::string(MICHI_BINARY_DIR) + "/bin/michi " + args + " 2>&1";
            CommandRun run{-1, ""};
            FILE *pipe = popen(command.c_str(), "r");
            if (pipe == nullptr)
                return run;
            std::array<char, 4096> buffer{};
            std::size_t n;
            while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
                run.output.append(buffer.data(), n);
            const int status = pclose(pipe);
            run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            return run;
        }
    }  // namespace test
}  // namespace michi
