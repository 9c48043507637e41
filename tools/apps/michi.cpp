// The `michi` command: benchmark and plan on michi problem files, the methods' own studies, list the planners.
// One CLI11 table of sub-commands (the option helpers are in CommandLine.h, the sub-commands in *Commands.cpp).
// Exit codes: 0 success, 1 a failed run (bad problem file, no path, ...), 2 a usage error; every error is one line
// on stderr, `michi COMMAND: ...`.
#include "CommandLine.h"

#include <boost/filesystem/exception.hpp>

#include <filesystem>
#include <iostream>
#include <map>
#include <new>
#include <string>
#include <vector>

#ifndef MICHI_VERSION
#error "MICHI_VERSION (the project version) is set by tools/CMakeLists.txt"
#endif

using namespace michi::tools::cli;

namespace
{
    const char *FOOTER =
        "Numbers are written as in problem files (0.5, pi/4, -0.5*pi); --opt=value and --opt value both work.\n"
        "Exit codes: 0 success, 1 a failed run, 2 a usage error. `michi COMMAND --help` shows a command's options.";

    /** the sub-commands, in the order of the help text */
    const std::vector<std::pair<const char *, Runner (*)(CLI::App &)>> COMMANDS{
        {"bench", addBench},
        {"plan", addPlan},
        {"campaign", addCampaign},
        {"verify-checker", addVerifyChecker},
        {"circles", addCircles},
        {"jmap", addJMap},
        {"random-scenes", addRandomScenes},
        {"lattice", addLattice},
        {"dualarm", addDualArm},
        {"replan", addReplan},
        {"experience-queries", addExperienceQueries},
        {"path-seed-figure", addPathSeedFigure},
        {"path-seed-library", addPathSeedLibrary},
        {"list-planners", addListPlanners},
    };

    /** \e text on one line: an exception's text may hold line breaks, the error report is one line */
    std::string oneLine(std::string text)
    {
        while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
            text.pop_back();
        for (char &c : text)
            if (c == '\n' || c == '\r')
                c = ' ';
        return text;
    }

    /** CLI11's message for a parse error, reworded where it would not name the argument first */
    std::string usageMessage(const CLI::ParseError &e, const CLI::App *command)
    {
        if (dynamic_cast<const CLI::ExtrasError *>(&e) != nullptr && command != nullptr)
        {
            // CLI11 lists the extras in reverse order; report the first one the user typed
            const std::vector<std::string> extras = command->remaining();
            if (!extras.empty())
            {
                const std::string &first = extras.front();
                if (first.size() > 1 && first[0] == '-')
                    return "unknown option " + first.substr(0, first.find('='));
                return "unexpected argument '" + first + "'";
            }
        }
        if (dynamic_cast<const CLI::RequiredError *>(&e) != nullptr && command != nullptr)
        {
            // the wording of michi's earlier parsers: "bench needs --out DIR", "bench takes one problem file"
            for (const CLI::Option *option : command->get_options())
                if (option->get_required() && option->count() == 0)
                    return command->get_name() + (option->get_positional() && option->get_lnames().empty()
                                                      ? " takes one problem file"
                                                      : " needs " + option->get_name() + " " + option->get_type_name());
        }
        if (dynamic_cast<const CLI::ArgumentMismatch *>(&e) != nullptr)
        {
            // "--out: 1 required DIR missing" -> "option --out needs a value"
            const std::string what = e.what();
            const auto colon = what.find(':');
            if (colon != std::string::npos && what.find("missing") != std::string::npos)
                return "option " + what.substr(0, colon) + " needs a value";
        }
        return e.what();
    }

    /** a filesystem error as "'path': reason", without the library's function names */
    template <typename Error>
    std::string filesystemMessage(const Error &e)
    {
        std::string paths = "'" + e.path1().string() + "'";
        if (!e.path2().empty())
            paths += ", '" + e.path2().string() + "'";
        return (e.path1().empty() ? std::string("file system") : paths) + ": " + e.code().message();
    }
}  // namespace

int main(int argc, char **argv)
{
    std::vector<std::string> args(argv + 1, argv + argc);
    if (!args.empty() && args[0] == "help")  // `michi help [COMMAND]` as `michi [COMMAND] --help`
    {
        args.erase(args.begin());
        args.push_back("--help");
    }
    if (args.empty())
    {
        std::cerr << "michi: no command given (see michi --help)" << std::endl;
        return 2;
    }

    CLI::App app{
        "michi: OMPL planners from the papers in METHODS.md, and the tools to run and benchmark them on "
        "robot problems.",
        "michi"};
    app.set_version_flag("--version", std::string("michi ") + MICHI_VERSION, "print the version and exit");
    app.require_subcommand(1);
    app.footer(FOOTER);
    std::map<std::string, Runner> runners;
    for (const auto &[name, add] : COMMANDS)
        runners[name] = add(app);

    // the error prefix names the sub-command (it must come first on the command line)
    std::string command;
    if (!args[0].empty() && args[0][0] != '-')
    {
        if (runners.count(args[0]) == 0)
        {
            std::cerr << "michi: unknown command '" << args[0] << "' (see michi --help)" << std::endl;
            return 2;
        }
        command = args[0];
    }
    const std::string prefix = command.empty() ? "michi: " : "michi " + command + ": ";

    try
    {
        try
        {
            // CLI11 takes the arguments reversed (it pops them from the back)
            std::vector<std::string> reversed(args.rbegin(), args.rend());
            app.parse(reversed);
        }
        catch (const CLI::CallForHelp &e)
        {
            return app.exit(e);
        }
        catch (const CLI::CallForAllHelp &e)
        {
            return app.exit(e);
        }
        catch (const CLI::CallForVersion &e)
        {
            return app.exit(e);
        }
        catch (const CLI::ParseError &e)
        {
            const auto parsed = app.get_subcommands();
            std::cerr << prefix << oneLine(usageMessage(e, parsed.empty() ? nullptr : parsed.front())) << std::endl;
            return 2;
        }
        return runners.at(command)();
    }
    // Before std::exception, which it derives from: a usage error exits 2, a failed run 1.
    catch (const UsageError &e)
    {
        std::cerr << prefix << oneLine(e.what()) << std::endl;
        return 2;
    }
    catch (const std::bad_alloc &)
    {
        // std::bad_alloc's own text ("std::bad_alloc") tells a user nothing.
        std::cerr << prefix << "out of memory" << std::endl;
        return 1;
    }
    catch (const boost::filesystem::filesystem_error &e)
    {
        std::cerr << prefix << filesystemMessage(e) << std::endl;
        return 1;
    }
    catch (const std::filesystem::filesystem_error &e)
    {
        std::cerr << prefix << filesystemMessage(e) << std::endl;
        return 1;
    }
    catch (const std::exception &e)
    {
        std::cerr << prefix << oneLine(e.what()) << std::endl;
        return 1;
    }
}
