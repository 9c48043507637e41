#ifndef MICHI_TOOLS_FILE_OUTPUT_
#define MICHI_TOOLS_FILE_OUTPUT_

#include <boost/filesystem/path.hpp>

#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief Write \e text to FILE.tmp, then rename it to \e file, so a failure leaves nothing behind;
            throws std::runtime_error naming the file. */
        void writeAtomically(const std::string &text, const std::string &file);

        /** \brief \e text quoted for a POSIX shell (single quotes). */
        std::string shellQuote(const std::string &text);

        /** \brief The last non-empty line of a text file (empty when it cannot be read): the line to quote from a
            tool's log in an error message. */
        std::string lastLine(const std::string &file);

        /** \brief \e text as a JSON string literal (quotes, backslashes and control characters escaped). */
        std::string jsonString(const std::string &text);

        /** \brief A folder of outputs written all-or-nothing: files go to a hidden staging folder beside the output
            folder, and commit() moves them in (replacing entries of the same name); without commit() the staging
            folder is removed, so a failure leaves the output folder as it was. The staging folder is removed on
            every exit path: exceptions, and SIGINT/SIGTERM/SIGHUP/SIGQUIT and crash signals (the process then
            dies of the same signal); one left by a process killed with SIGKILL is removed by the next run.
            Throws std::runtime_error naming the folder when it cannot be made (e.g. a file in the way). */
        class StagedDirectory
        {
        public:
            explicit StagedDirectory(const std::string &outDir);
            ~StagedDirectory();
            StagedDirectory(const StagedDirectory &) = delete;
            StagedDirectory &operator=(const StagedDirectory &) = delete;

            /** \brief Where to write the staged entry \e name. */
            boost::filesystem::path path(const std::string &name) const;

            /** \brief At commit(), when nothing named \e name was staged, remove the file \e name from the output
                folder if it contains \e mark: an optional output of an earlier run that this run does not write
                (a replay page from a run with --html) would otherwise sit beside results it does not belong to.
                Anything else of that name (a folder, a link, a file without the mark) is not michi's output and
                is left alone. */
            void removeStale(const std::string &name, const std::string &mark);

            /** \brief Move every staged entry into the output folder (and remove the stale files of removeStale()). */
            void commit();

            /** \brief The output folder (absolute). */
            const boost::filesystem::path &out() const
            {
                return out_;
            }

        private:
            /** Moves each staged entry (first) to its place in the output folder (second). */
            static void moveAll(const std::vector<std::pair<boost::filesystem::path, boost::filesystem::path>> &moves);

            boost::filesystem::path out_;
            boost::filesystem::path dir_;
            std::vector<std::pair<std::string, std::string>> stale_;  ///< removeStale(): name, mark
            int slot_{-1};  ///< registration for removal on a signal (FileOutput.cpp)
        };
    }  // namespace tools
}  // namespace michi

#endif
