#include <michi/tools/problem/PathFile.h>
#include <michi/tools/FileOutput.h>
#include <michi/validity/InputFile.h>

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace michi
{
    namespace tools
    {
        void writePathFile(const std::string &file, const std::vector<std::string> &names,
                           const std::vector<std::vector<double>> &states, const std::string &comment)
        {
            std::ostringstream out;
            if (!comment.empty())
                out << "# " << comment << "\n";
            out << "#";
            for (const auto &n : names)
                out << " " << n;
            // 17 significant digits: a path read back with readPathFile() holds the very same doubles.
            out << "\n" << std::setprecision(17);
            for (const auto &s : states)
            {
                for (std::size_t i = 0; i < s.size(); ++i)
                    out << (i ? " " : "") << s[i];
                out << "\n";
            }
            writeAtomically(out.str(), file);  // the one atomic write (FileOutput.h)
        }

        std::vector<std::vector<double>> readPathFile(const std::string &file)
        {
            validity::requireInputFile(file);
            std::ifstream in(file);
            if (!in)
                throw std::runtime_error(file + ": cannot open path file");
            std::vector<std::vector<double>> states;
            std::string line;
            for (int number = 1; std::getline(in, line); ++number)
            {
                if (line.empty() || line[0] == '#')
                    continue;
                std::istringstream fields(line);
                std::vector<double> state;
                double v;
                while (fields >> v)
                    state.push_back(v);
                // A field that is not a number stops the read before the end of the line (not eof): such a line is an
                // error, not a shorter state.
                if (!fields.eof() || (!states.empty() && state.size() != states.front().size()) || state.empty())
                    throw std::runtime_error(file + ":" + std::to_string(number) + ": malformed state");
                states.push_back(state);
            }
            return states;
        }
    }  // namespace tools
}  // namespace michi
