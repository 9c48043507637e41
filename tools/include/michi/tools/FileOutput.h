#ifndef MICHI_TOOLS_FILE_OUTPUT_
#define MICHI_TOOLS_FILE_OUTPUT_

#include <string>

namespace michi
{
    namespace tools
    {
        /** \brief Write \e text to FILE.tmp, then rename it to \e file, so a failure leaves nothing behind;
            throws std::runtime_error naming the file. */
        void writeAtomically(const std::string &text, const std::string &file);

        /** \brief \e text quoted for a POSIX shell (single quotes). */
        std::string shellQuote(const std::string &text);
    }  // namespace tools
}  // namespace michi

#endif
