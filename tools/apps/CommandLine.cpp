#include "CommandLine.h"

// the problem loader's number parser (tools/src/problem, private to michi_tools): a number on the command line is
// written as in a problem file
#include "problem/ProblemYaml.h"

#include <ompl/util/Console.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace cli
        {
            namespace
            {
                /** a bound as a user writes it: 1000000, not 1e+06 */
                std::string bound(double v)
                {
                    std::ostringstream out;
                    if (v == std::floor(v) && std::abs(v) < 1e15)
                        out << static_cast<long long>(v);
                    else
                        out << v;
                    return out.str();
                }

                std::string range(double lowest, double highest, bool lowestIncluded)
                {
                    return (lowestIncluded ? ">= " : "> ") + bound(lowest) + " and <= " + bound(highest);
                }
            }  // namespace

            std::uint64_t parseInteger(const std::string &option, const std::string &text, std::uint64_t lowest,
                                       std::uint64_t highest)
            {
                // std::from_chars reads digits only (no sign, no spaces, no exponent) and reports overflow instead
                // of wrapping, so 4294967297 or 1e12 cannot turn into a small number
                std::uint64_t v = 0;
                const char *begin = text.data();
                const char *end = text.data() + text.size();
                const auto r = std::from_chars(begin, end, v);
                if (text.empty() || r.ec != std::errc() || r.ptr != end || v < lowest || v > highest)
                    throw UsageError(option + ": expected an integer in " + std::to_string(lowest) + ".." +
                                     std::to_string(highest) + ", got '" + text + "'");
                return v;
            }

            double parseReal(const std::string &option, const std::string &text, double lowest, double highest,
                             bool lowestIncluded)
            {
                double v = std::numeric_limits<double>::quiet_NaN();
                try
                {
                    v = problem_file::Reader::parseNumber(text);
                }
                catch (const std::exception &)
                {
                }
                // Written as !(v >= lowest) and so on: every comparison with NaN is false, so NaN fails each test.
                if (!std::isfinite(v) || (lowestIncluded ? !(v >= lowest) : !(v > lowest)) || !(v <= highest))
                    throw UsageError(option + ": expected a number " + range(lowest, highest, lowestIncluded) +
                                     ", got '" + text + "'");
                return v;
            }

            std::vector<double> parseRealList(const std::string &option, const std::string &text, double lowest,
                                              double highest, bool lowestIncluded, std::size_t size)
            {
                std::vector<double> values;
                // getline drops an empty last item: without this check "1,2," would pass as two numbers.
                bool ok = !text.empty() && text.back() != ',';
                std::stringstream in(text);
                for (std::string item; ok && std::getline(in, item, ',');)
                {
                    try
                    {
                        values.push_back(parseReal(option, item, lowest, highest, lowestIncluded));
                    }
                    catch (const UsageError &)
                    {
                        ok = false;
                    }
                }
                if (!ok || values.empty() || (size > 0 && values.size() != size))
                    throw UsageError(option + ": expected " + (size > 0 ? std::to_string(size) + " " : "") +
                                     "numbers " + range(lowest, highest, lowestIncluded) +
                                     " separated by commas, got '" + text + "'");
                return values;
            }

            std::vector<std::string> splitComma(const std::string &option, const std::string &text)
            {
                std::vector<std::string> parts;
                std::stringstream in(text);
                for (std::string item; std::getline(in, item, ',');)
                    parts.push_back(item);
                // "a,,b" or "a," is a typo, not a shorter list: said, rather than run without the missing name
                if (!text.empty() &&
                    (text.back() == ',' || std::find(parts.begin(), parts.end(), std::string()) != parts.end()))
                    throw UsageError(option + ": an empty name in '" + text + "' (names separated by single commas)");
                return parts;
            }

            void checkOutputPath(const std::string &option, const std::string &path, OutputKind kind)
            {
                if (path.empty())
                    throw UsageError(option + ": expected a path, got ''");
                // status() with an error code never throws: a missing path (or one under a file) is "not found"
                boost::system::error_code ec;
                const fs::path p(path);
                const fs::file_status self = fs::status(p, ec);
                if (fs::exists(self))
                {
                    if (kind == OutputKind::FOLDER && !fs::is_directory(self))
                        throw UsageError(option + ": '" + path + "' exists and is not a folder");
                    if (kind == OutputKind::FILE && fs::is_directory(self))
                        throw UsageError(option + ": '" + path + "' is a folder, expected a file name");
                    if (kind == OutputKind::FOLDER)
                        return;
                }
                // the nearest existing ancestor must be a folder, or nothing can be made below it
                for (fs::path q = p.parent_path(); !q.empty(); q = q.parent_path())
                {
                    const fs::file_status s = fs::status(q, ec);
                    if (!fs::exists(s))
                        continue;
                    if (!fs::is_directory(s))
                        throw UsageError(option + ": cannot write '" + path + "': '" + q.string() +
                                         "' is not a folder");
                    return;
                }
            }

            CLI::Option *addProblem(CLI::App &command, std::string &file)
            {
                return command.add_option("PROBLEM.yaml", file, "the problem file (docs/problem-format.md)")
                    ->required()
                    ->type_name("");
            }

            CLI::Option *addOut(CLI::App &command, std::string &path, const std::string &help, bool required)
            {
                auto *option = command.add_option("--out", path, help)->type_name("DIR");
                if (required)
                    option->required();
                return option;
            }

            CLI::Option *addSeed(CLI::App &command, std::optional<unsigned int> &seed, const std::string &help)
            {
                // ompl::RNG::setSeed ignores 0 (with a warning), so the range starts at 1
                return addInteger(command, "--seed", seed, 1, MAX_SEED, help)->type_name("S");
            }

            CLI::Option *addReal(CLI::App &command, const std::string &name, std::optional<double> &target,
                                 double lowest, double highest, const std::string &help, const std::string &typeName)
            {
                return command
                    .add_option_function<std::string>(
                        name,
                        [name, &target, lowest, highest](const std::string &text)
                        {
                            target = parseReal(name, text, lowest, highest);
                        },
                        help)
                    ->type_name(typeName);
            }

            CLI::Option *addTime(CLI::App &command, std::optional<double> &time, const std::string &help)
            {
                return addReal(command, "--time", time, 0., MAX_SECONDS, help + " [> 0, <= 1e6]", "SECONDS");
            }

            CLI::Option *addChoice(CLI::App &command, const std::string &name, std::optional<std::string> &target,
                                   const std::vector<std::string> &choices, const std::string &help)
            {
                std::string list;
                for (std::size_t i = 0; i < choices.size(); ++i)
                    list += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
                std::string typeName;
                for (const auto &c : choices)
                    typeName += (typeName.empty() ? "" : "|") + c;
                return command
                    .add_option_function<std::string>(
                        name,
                        [name, &target, choices, list](const std::string &text)
                        {
                            if (std::find(choices.begin(), choices.end(), text) == choices.end())
                                throw UsageError(name + ": expected " + list + ", got '" + text + "'");
                            target = text;
                        },
                        help)
                    ->type_name(typeName);
            }

            CLI::Option *addVerbose(CLI::App &command, bool &verbose)
            {
                return command.add_flag("--verbose", verbose, "show OMPL's log messages");
            }

            void setOmplLogLevel(bool verbose, bool errorsOnly)
            {
                ompl::msg::setLogLevel(verbose      ? ompl::msg::LOG_INFO
                                       : errorsOnly ? ompl::msg::LOG_ERROR
                                                    : ompl::msg::LOG_WARN);
            }
        }  // namespace cli
    }      // namespace tools
}  // namespace michi
