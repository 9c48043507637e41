#include "support/MichiCommand.h"

#include <michi/tools/bench/PlanningContext.h>

#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <sstream>
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

        std::string problemLoadError(const std::string &path, bool plan)
        {
            try
            {
                const auto problem = tools::loadProblem(path);
                if (plan)
                    tools::makePlanningContext(problem);
            }
            catch (const std::exception &e)
            {
                const std::string what = e.what();
                EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
                return what;
            }
            ADD_FAILURE() << path << " loaded without error";
            return "";
        }

        std::string problemFile(const std::string &name)
        {
            return std::string(MICHI_SOURCE_DIR) + "/problems/" + name + ".yaml";
        }

        std::string slurp(const std::string &file)
        {
            std::ifstream in(file, std::ios::binary);
            std::stringstream s;
            s << in.rdbuf();
            return s.str();
        }
    }  // namespace test
}  // namespace michi
