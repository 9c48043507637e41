#include <michi/tools/FileOutput.h>

#include <boost/filesystem.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <climits>
#include <csignal>
#include <mutex>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <utility>
#include <vector>

namespace michi
{
    namespace tools
    {
        void writeAtomically(const std::string &text, const std::string &file)
        {
            // Beside the target, on the same file system: rename() replaces the file in one step there, so a reader (or
            // a resumed campaign) sees the old file or the whole new one, never half of it.
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
                // Inside single quotes the shell takes everything literally except the quote itself: close, add an
                // escaped quote, reopen.
                quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
            return quoted + "'";
        }

        std::string lastLine(const std::string &file)
        {
            std::ifstream in(file);
            std::string line, last;
            while (std::getline(in, line))
                if (!line.empty())
                    last = line;
            return last;
        }

        std::string jsonString(const std::string &text)
        {
            std::string out = "\"";
            for (char c : text)
            {
                if (c == '"' || c == '\\')
                    out += '\\';
                // JSON forbids raw control characters in strings; bytes >= 0x80 (UTF-8) pass through unchanged.
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

        namespace
        {
            /** The file that lists what michi wrote into a folder inside an output folder (StagedDirectory::commit). */
            const char *const OUTPUT_MARK = ".michi-output";

            /** Paths of the files under \e folder, relative to it, sorted; the list file itself left out. */
            std::vector<std::string> filesUnder(const boost::filesystem::path &folder)
            {
                namespace fs = boost::filesystem;
                std::vector<std::string> names;
                boost::system::error_code ec;
                for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
                    if (!fs::is_directory(it->path()))
                    {
                        const std::string name = it->path().lexically_relative(folder).generic_string();
                        if (name != OUTPUT_MARK)
                            names.push_back(name);
                    }
                std::sort(names.begin(), names.end());
                return names;
            }

            /** Whether every file under \e folder is one that michi listed when it wrote the folder (an empty folder
                is michi's too): only then may a new run replace the folder whole. */
            bool writtenByMichi(const boost::filesystem::path &folder)
            {
                const std::vector<std::string> present = filesUnder(folder);
                if (present.empty())
                    return true;
                std::ifstream in((folder / OUTPUT_MARK).string());
                if (!in)
                    return false;
                std::vector<std::string> listed;
                for (std::string line; std::getline(in, line);)
                    listed.push_back(line);
                std::sort(listed.begin(), listed.end());
                return std::includes(listed.begin(), listed.end(), present.begin(), present.end());
            }

            // Staging folders that exist right now, so that a signal (Ctrl-C, kill, a crash) removes them too.
            // The handler may only call async-signal-safe functions: it forks and execs rm on paths copied into
            // fixed buffers when the folder was made (no allocation, no locks in the handler).
            constexpr std::size_t MAX_STAGED = 32;
            struct StagedSlot
            {
                std::atomic<bool> used{false};
                char path[PATH_MAX]{};
            };
            std::array<StagedSlot, MAX_STAGED> stagedSlots;
            std::mutex stagedMutex;  // taken by register/unregister only, never by the handler
            const int CLEANUP_SIGNALS[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGSEGV, SIGBUS, SIGFPE, SIGABRT, SIGILL};

            extern "C" void removeStagedAndReraise(int sig)
            {
                for (auto &slot : stagedSlots)
                {
                    if (!slot.used.load())
                        continue;
                    const pid_t child = fork();
                    if (child == 0)
                    {
                        char rm[] = "/bin/rm", flags[] = "-rf", dashes[] = "--";
                        char *argv[] = {rm, flags, dashes, slot.path, nullptr};
                        // execve with an absolute path and an empty environment: no PATH lookup, which is not
                        // async-signal-safe.
                        char *envp[] = {nullptr};
                        execve(rm, argv, envp);
                        _exit(127);
                    }
                    if (child > 0)
                    {
                        int status = 0;
                        waitpid(child, &status, 0);
                    }
                }
                // then die of the same signal, as the default action would have (exit status, core dump)
                signal(sig, SIG_DFL);
                raise(sig);
            }

            void installCleanupHandlers()
            {
                static std::once_flag once;
                std::call_once(once,
                               []
                               {
                                   for (int sig : CLEANUP_SIGNALS)
                                   {
                                       struct sigaction action
                                       {
                                       };
                                       struct sigaction previous
                                       {
                                       };
                                       // keep a handler the embedding program installed; take over only defaults
                                       if (sigaction(sig, nullptr, &previous) != 0 || previous.sa_handler != SIG_DFL)
                                           continue;
                                       action.sa_handler = removeStagedAndReraise;
                                       sigemptyset(&action.sa_mask);
                                       // SA_RESETHAND: a second signal while cleaning up takes the default action
                                       // instead of re-entering the handler.
                                       action.sa_flags = SA_RESETHAND;
                                       sigaction(sig, &action, nullptr);
                                   }
                               });
            }

            int registerStaged(const std::string &path)
            {
                if (path.size() >= PATH_MAX)
                    return -1;
                installCleanupHandlers();
                std::lock_guard<std::mutex> lock(stagedMutex);
                for (std::size_t i = 0; i < stagedSlots.size(); ++i)
                    if (!stagedSlots[i].used.load())
                    {
                        std::memcpy(stagedSlots[i].path, path.c_str(), path.size() + 1);
                        stagedSlots[i].used.store(true);
                        return static_cast<int>(i);
                    }
                return -1;  // more than MAX_STAGED at once: still removed on normal exits and exceptions
            }

            void unregisterStaged(int slot)
            {
                if (slot < 0)
                    return;
                std::lock_guard<std::mutex> lock(stagedMutex);
                stagedSlots[static_cast<std::size_t>(slot)].used.store(false);
            }

            /** Staging folders of the same output left by a process that no longer runs (killed with SIGKILL,
                which no handler sees): ".<name>.partial-<pid>" beside the output folder. */
            void removeAbandonedStaging(const boost::filesystem::path &out)
            {
                namespace fs = boost::filesystem;
                boost::system::error_code ec;
                const std::string prefix = "." + out.filename().string() + ".partial-";
                for (fs::directory_iterator it(out.parent_path(), ec), end; !ec && it != end; it.increment(ec))
                {
                    const std::string name = it->path().filename().string();
                    if (name.compare(0, prefix.size(), prefix) != 0)
                        continue;
                    char *used = nullptr;
                    const long pid = std::strtol(name.c_str() + prefix.size(), &used, 10);
                    if (pid <= 0 || *used != '\0')
                        continue;
                    // Signal 0 only asks whether the process exists: a folder of a process still running (another michi
                    // writing the same output) is left alone.
                    if (kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
                    {
                        boost::system::error_code ignored;
                        fs::remove_all(it->path(), ignored);
                    }
                }
            }
        }  // namespace

        StagedDirectory::StagedDirectory(const std::string &outDir)
            : out_(boost::filesystem::absolute(outDir))
            , dir_(out_.parent_path() / ("." + out_.filename().string() + ".partial-" + std::to_string(getpid())))
        {
            namespace fs = boost::filesystem;
            // name what is wrong with --out in one line (a raw boost::filesystem error names no option)
            for (fs::path p = out_.parent_path(); !p.empty(); p = p.parent_path())
            {
                boost::system::error_code ec;
                const fs::file_status status = fs::status(p, ec);
                if (fs::exists(status))
                {
                    if (!fs::is_directory(status))
                        throw std::runtime_error("output folder '" + out_.string() + "': '" + p.string() +
                                                 "' is a file, not a folder");
                    break;
                }
                if (p == p.parent_path())
                    break;
            }
            {
                boost::system::error_code ec;
                if (fs::exists(out_, ec) && !fs::is_directory(out_, ec))
                    throw std::runtime_error("output folder '" + out_.string() + "' is a file, not a folder");
                // before any work, not when the results are moved in at the end
                if (fs::exists(out_, ec) && access(out_.c_str(), W_OK | X_OK) != 0)
                    throw std::runtime_error("output folder '" + out_.string() + "' is not writable");
            }
            removeAbandonedStaging(out_);
            boost::system::error_code ec;
            // A folder of this very pid is a leftover of an earlier process that had the same id: start clean.
            fs::remove_all(dir_, ec);
            fs::create_directories(dir_, ec);
            if (ec)
                throw std::runtime_error("output folder '" + out_.string() + "': cannot create '" + dir_.string() +
                                         "': " + ec.message());
            slot_ = registerStaged(dir_.string());
        }

        StagedDirectory::~StagedDirectory()
        {
            unregisterStaged(slot_);
            boost::system::error_code ec;
            boost::filesystem::remove_all(dir_, ec);
        }

        boost::filesystem::path StagedDirectory::path(const std::string &name) const
        {
            return dir_ / name;
        }

        void StagedDirectory::removeStale(const std::string &name, const std::string &mark)
        {
            stale_.emplace_back(name, mark);
        }

        void StagedDirectory::commit()
        {
            namespace fs = boost::filesystem;
            boost::system::error_code ec;
            fs::create_directories(out_, ec);
            if (ec)
                throw std::runtime_error("output folder '" + out_.string() + "': cannot create it: " + ec.message());
            // Every entry is checked before any is moved, so a refusal leaves the output folder as it was. Only what
            // michi wrote is ever replaced: a file by a file, and a folder by a folder only when michi listed every
            // file in it (OUTPUT_MARK) or it is empty. A user's folder that happens to have an output's name (a folder
            // "summary.md", notes kept in "episode/") was deleted with everything in it before.
            std::vector<std::pair<fs::path, fs::path>> moves;
            for (const auto &entry : fs::directory_iterator(dir_))
            {
                const fs::path target = out_ / entry.path().filename();
                const bool stagedFolder = fs::is_directory(entry.path());
                const fs::file_status status = fs::symlink_status(target, ec);
                if (fs::exists(status))
                {
                    if (stagedFolder != fs::is_directory(status))
                        throw std::runtime_error("output folder '" + out_.string() + "': '" + target.string() +
                                                 "' is in the way (michi writes a " +
                                                 (stagedFolder ? "folder" : "file") + " there); move it away");
                    if (stagedFolder && !writtenByMichi(target))
                        throw std::runtime_error("output folder '" + out_.string() + "': '" + target.string() +
                                                 "' holds files michi did not write (it replaces that folder whole); "
                                                 "move them away or choose another folder");
                }
                moves.emplace_back(entry.path(), target);
            }
            // Before the moves: a file that cannot be removed is reported while the folder still holds the earlier
            // run's outputs whole.
            for (const auto &stale : stale_)
            {
                const fs::path target = out_ / stale.first;
                if (fs::exists(fs::symlink_status(dir_ / stale.first, ec)) ||
                    !fs::is_regular_file(fs::symlink_status(target, ec)))
                    continue;
                std::ifstream in(target.string(), std::ios::binary);
                const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
                if (text.find(stale.second) == std::string::npos)
                    continue;
                fs::remove(target, ec);
                if (ec)
                    throw std::runtime_error("output folder '" + out_.string() + "': cannot remove '" +
                                             target.string() + "' of an earlier run: " + ec.message());
            }
            try
            {
                moveAll(moves);
            }
            catch (const fs::filesystem_error &e)
            {
                // one line that names the folder the user gave, not the staging folder beside it
                throw std::runtime_error("output folder '" + out_.string() +
                                         "': cannot move the results in: " + e.code().message());
            }
        }

        void StagedDirectory::moveAll(
            const std::vector<std::pair<boost::filesystem::path, boost::filesystem::path>> &moves)
        {
            namespace fs = boost::filesystem;
            for (const auto &move : moves)
            {
                if (fs::is_directory(move.first))
                {
                    // the list that lets a later run replace this folder (and nothing a user added to it)
                    std::ofstream mark(fs::path(move.first / OUTPUT_MARK).string());
                    for (const std::string &name : filesUnder(move.first))
                        mark << name << "\n";
                    // rename() cannot replace a non-empty folder
                    if (fs::is_directory(move.second))
                        fs::remove_all(move.second);
                }
                fs::rename(move.first, move.second);
            }
        }
    }  // namespace tools
}  // namespace michi
