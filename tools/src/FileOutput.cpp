#include <michi/tools/FileOutput.h>

#include <boost/filesystem.hpp>

#include <unistd.h>

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

        std::string jsonString(const std::string &text)
        {
            std::string out = "\"";
            for (char c : text)
            {
                if (c == '"' || c == '\\')
                    out += '\\';
                if (static_cast<unsigned char>(c) < 0x20)
                {
                    char code[8];
                    std::snprintf(code, sizeof code, "\\u%04x", static_cast<unsigned int>(c));
                    out += code;
                }
                else
                    out += c;
            }
            return out + "\"";
        }

        StagedDirectory::StagedDirectory(const std::string &outDir)
            : out_(boost::filesystem::absolute(outDir))
            , dir_(out_.parent_path() / ("." + out_.filename().string() + ".partial-" + std::to_string(getpid())))
        {
            boost::filesystem::remove_all(dir_);
            boost::filesystem::create_directories(dir_);
        }

        StagedDirectory::~StagedDirectory()
        {
            boost::system::error_code ec;
            boost::filesystem::remove_all(dir_, ec);
        }

        boost::filesystem::path StagedDirectory::path(const std::string &name) const
        {
            return dir_ / name;
        }

        void StagedDirectory::commit()
        {
            namespace fs = boost::filesystem;
            fs::create_directories(out_);
            for (const auto &entry : fs::directory_iterator(dir_))
            {
                const fs::path target = out_ / entry.path().filename();
                if (fs::is_directory(target))
                    fs::remove_all(target);
                fs::rename(entry.path(), target);
            }
        }
    }  // namespace tools
}  // namespace michi
