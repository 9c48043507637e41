#ifndef MICHI_TOOLS_PATH_FILE_
#define MICHI_TOOLS_PATH_FILE_

#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief Write a path as text: a comment header naming the values, then one state per line (the layout
            of OMPL's PathGeometric::printAsMatrix). Written to FILE.tmp and renamed. */
        void writePathFile(const std::string &file, const std::vector<std::string> &names,
                           const std::vector<std::vector<double>> &states, const std::string &comment = "");

        /** \brief Read a path file written by writePathFile; throws std::runtime_error naming the file and line. */
        std::vector<std::vector<double>> readPathFile(const std::string &file);
    }  // namespace tools
}  // namespace michi

#endif
