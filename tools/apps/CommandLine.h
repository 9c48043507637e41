// The `michi` command line (private to the executable, not installed): option helpers shared by the sub-commands.
// Every option value is checked where it enters, and a bad one is a UsageError whose text names the option:
// main() prints it as one line `michi COMMAND: --runs: expected ...` and exits with 2.
#ifndef MICHI_TOOLS_APPS_COMMAND_LINE_
#define MICHI_TOOLS_APPS_COMMAND_LINE_

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace cli
        {
            /** \brief A bad command line (exit code 2); the text names the option. */
            struct UsageError : std::runtime_error
            {
                using std::runtime_error::runtime_error;
            };

            /** \brief What a sub-command does once its options are parsed; returns the exit code. */
            using Runner = std::function<int()>;

            /** \brief The largest seed: ompl::RNG::setSeed() takes a std::uint_fast32_t and is fed 32-bit seeds. */
            constexpr std::uint64_t MAX_SEED = std::numeric_limits<std::uint32_t>::max();
            /** \brief Time limits in seconds: more than zero and at most about 11 days. */
            constexpr double MAX_SECONDS = 1e6;

            /** \brief \e text as an integer in [lowest, highest]: decimal digits only (no sign, exponent or
                fraction), so that nothing is rounded or wraps; otherwise a UsageError naming \e option. */
            std::uint64_t parseInteger(const std::string &option, const std::string &text, std::uint64_t lowest,
                                       std::uint64_t highest);

            /** \brief \e text as a finite number written as in problem files (`0.5`, `pi/4`, `-0.5*pi`: the problem
                loader's own parser), in (lowest, highest] or, with \e lowestIncluded, [lowest, highest]. */
            double parseReal(const std::string &option, const std::string &text, double lowest, double highest,
                             bool lowestIncluded = false);

            /** \brief "A,B,C" as numbers (each as parseReal()); \e size > 0: exactly that many. */
            std::vector<double> parseRealList(const std::string &option, const std::string &text, double lowest,
                                              double highest, bool lowestIncluded = false, std::size_t size = 0);

            /** \brief "A,B,C" as its non-empty items. */
            std::vector<std::string> splitComma(const std::string &option, const std::string &text);

            enum class OutputKind
            {
                FOLDER,  ///< a folder, made if missing
                FILE     ///< a file, whose folder is made if missing
            };

            /** \brief Check an output path before any work: not empty, an existing path of the right kind (a
                folder for FOLDER, not a folder for FILE), and its nearest existing ancestor a folder; otherwise a
                UsageError that names \e option and the offending path. */
            void checkOutputPath(const std::string &option, const std::string &path, OutputKind kind);

            // ------------------------------------------------------------ adding options to a sub-command

            /** \brief A required positional PROBLEM.yaml. */
            CLI::Option *addProblem(CLI::App &command, std::string &file);

            /** \brief --out DIR (checked with checkOutputPath() when the command runs); a file output sets its own
                type name (FILE). */
            CLI::Option *addOut(CLI::App &command, std::string &path, const std::string &help, bool required = true);

            /** \brief An integer option in [lowest, highest] (parseInteger()). */
            template <typename T>
            CLI::Option *addInteger(CLI::App &command, const std::string &name, std::optional<T> &target,
                                    std::uint64_t lowest, std::uint64_t highest, const std::string &help)
            {
                static_assert(std::is_integral<T>::value, "an integer option");
                return command
                    .add_option_function<std::string>(
                        name,
                        [name, &target, lowest, highest](const std::string &text)
                        {
                            target = static_cast<T>(parseInteger(name, text, lowest, highest));
                        },
                        help + " [" + std::to_string(lowest) + ".." + std::to_string(highest) + "]")
                    ->type_name("N");
            }

            /** \brief --seed S (1..MAX_SEED). */
            CLI::Option *addSeed(CLI::App &command, std::optional<unsigned int> &seed, const std::string &help);

            /** \brief A number in (lowest, highest] (parseReal()). */
            CLI::Option *addReal(CLI::App &command, const std::string &name, std::optional<double> &target,
                                 double lowest, double highest, const std::string &help,
                                 const std::string &typeName = "X");

            /** \brief --time SECONDS in (0, MAX_SECONDS]. */
            CLI::Option *addTime(CLI::App &command, std::optional<double> &time, const std::string &help);

            /** \brief A text option whose value must be one of \e choices. */
            CLI::Option *addChoice(CLI::App &command, const std::string &name, std::optional<std::string> &target,
                                   const std::vector<std::string> &choices, const std::string &help);

            /** \brief --verbose: OMPL's log messages. */
            CLI::Option *addVerbose(CLI::App &command, bool &verbose);

            /** \brief OMPL's log level: INFO with --verbose, else \e quiet. */
            void setOmplLogLevel(bool verbose, bool errorsOnly = false);

            // ------------------------------------------------------------ the sub-commands (one table in michi.cpp)

            Runner addBench(CLI::App &michi);
            Runner addPlan(CLI::App &michi);
            Runner addListPlanners(CLI::App &michi);
            Runner addVerifyChecker(CLI::App &michi);
            Runner addCircles(CLI::App &michi);
            Runner addJMap(CLI::App &michi);
            Runner addRandomScenes(CLI::App &michi);
            Runner addLattice(CLI::App &michi);
            Runner addDualArm(CLI::App &michi);
            Runner addReplan(CLI::App &michi);
            Runner addExperienceQueries(CLI::App &michi);
            Runner addPathSeedFigure(CLI::App &michi);
            Runner addPathSeedLibrary(CLI::App &michi);
            Runner addCampaign(CLI::App &michi);
        }  // namespace cli
    }      // namespace tools
}  // namespace michi

#endif
