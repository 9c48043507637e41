#include <michi/tools/FileOutput.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace michi
{
    namespace tools
    {
        void writeAtomically(const std::string &text, const std::string &file)
        {
            const std::string temporary = file + ".tmp";
            {
                std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
                if (!out)
                    throw std::runtime_error("cannot write file '" + file + "': " + std::strerror(errno));
                out << text;
                out.close();
                if (!out)
                {
                    std::remove(temporary.c_str());
                    throw std::runtime_error("cannot write file '" + file + "': write failed");
                }
            }
            if (std::rename(temporary.c_str(), file.c_str()) != 0)
            {
                const std::string reason = std::strerror(errno);
                std::remove(temporary.c_str());
                throw std::runtime_error("cannot write file '" + file + "': " + reason);
            }
        }

        std::string shellQuote(const std::string &text)
        {
            std::string quoted = "'";
            for (char c : text)
                quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
            return quoted + "'";
        }
    }  // namespace tools
}  // namespace michi
