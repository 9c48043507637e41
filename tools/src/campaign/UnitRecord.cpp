#include <michi/tools/campaign/UnitRecord.h>
#include <michi/tools/FileOutput.h>

#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace michi
{
    namespace tools
    {
        namespace
        {
            /** a value on one line: line breaks escaped as \n, backslashes doubled */
            // One key=value per line is what keeps the format line-oriented: a cause or setting with a line break (a
            // planner's error message) must not start a line that reads as another key.
            std::string escape(const std::string &text)
            {
                std::string out;
                for (char c : text)
                {
                    if (c == '\\')
                        out += "\\\\";
                    else if (c == '\n')
                        out += "\\n";
                    else if (c == '\r')
                        out += "\\r";
                    else
                        out += c;
                }
                return out;
            }

            std::string unescape(const std::string &text)
            {
                std::string out;
                for (std::size_t i = 0; i < text.size(); ++i)
                {
                    if (text[i] != '\\' || i + 1 == text.size())
                    {
                        out += text[i];
                        continue;
                    }
                    const char next = text[++i];
                    out += next == 'n' ? '\n' : next == 'r' ? '\r' : next;
                }
                return out;
            }

            std::string number(double v)
            {
                std::ostringstream s;
                // 17 significant digits: a double written and read back is the same double, so merged figures equal the
                // unit's own.
                s << std::setprecision(17) << v;
                return s.str();
            }
        }  // namespace

        std::string formatUnitRecord(const UnitRecord &r)
        {
            std::ostringstream out;
            auto line = [&](const std::string &key, const std::string &value)
            {
                out << key << "=" << escape(value) << "\n";
            };
            line("id", std::to_string(r.id));
            line("campaign", r.campaign);
            line("dataset", r.dataset);
            line("problem", r.problem);
            line("problem_file", r.problemFile);
            line("query", std::to_string(r.query));
            line("query_label", r.queryLabel);
            line("planner_name", r.plannerName);
            line("planner_label", r.plannerLabel);
            line("planner", r.planner);
            for (const auto &kv : r.params)
                line("param." + kv.first, kv.second);
            line("checker", r.checker);
            line("run", std::to_string(r.run));
            line("seed", std::to_string(r.seed));
            line("time_limit", number(r.timeLimit));
            line("memory_limit", number(r.memoryLimit));
            line("michi_version", r.michiVersion);
            line("outcome", r.outcome);
            line("cause", r.cause);
            line("signal", std::to_string(r.signal));
            line("wall_time", number(r.wallTime));
            line("setup_info", r.setupInfo);
            for (const auto &s : r.settings)
                line("setting", s);
            for (const auto &kv : r.properties)
                line("property." + kv.first, kv.second);
            for (const auto &name : r.progressNames)
                line("progress_name", name);
            for (const auto &sample : r.progress)
            {
                // values are numbers as OMPL prints them; ',' cannot occur in one
                std::string joined;
                for (std::size_t i = 0; i < sample.size(); ++i)
                    joined += (i ? "," : "") + sample[i];
                line("progress_sample", joined);
            }
            line("end", "1");  // a record without it was cut short
            return out.str();
        }

        UnitRecord parseUnitRecord(const std::string &text, const std::string &source)
        {
            UnitRecord r;
            std::istringstream in(text);
            std::string l;
            bool ended = false;
            std::size_t lineNumber = 0;
            auto bad = [&](const std::string &what)
            {
                return std::runtime_error(source + ": line " + std::to_string(lineNumber) + ": " + what);
            };
            try
            {
                while (std::getline(in, l))
                {
                    ++lineNumber;
                    const auto eq = l.find('=');
                    if (eq == std::string::npos)
                        throw bad("expected key=value");
                    const std::string key = l.substr(0, eq), value = unescape(l.substr(eq + 1));
                    // Every key is known; an unknown one (a record of another michi version, or a damaged file) is an
                    // error rather than silently dropped data.
                    if (key == "id")
                        r.id = std::stoul(value);
                    else if (key == "campaign")
                        r.campaign = value;
                    else if (key == "dataset")
                        r.dataset = value;
                    else if (key == "problem")
                        r.problem = value;
                    else if (key == "problem_file")
                        r.problemFile = value;
                    else if (key == "query")
                        r.query = std::stoul(value);
                    else if (key == "query_label")
                        r.queryLabel = value;
                    else if (key == "planner_name")
                        r.plannerName = value;
                    else if (key == "planner_label")
                        r.plannerLabel = value;
                    else if (key == "planner")
                        r.planner = value;
                    else if (key.rfind("param.", 0) == 0)
                        r.params[key.substr(6)] = value;
                    else if (key == "checker")
                        r.checker = value;
                    else if (key == "run")
                        r.run = static_cast<unsigned int>(std::stoul(value));
                    else if (key == "seed")
                        r.seed = static_cast<std::uint32_t>(std::stoul(value));
                    else if (key == "time_limit")
                        r.timeLimit = std::stod(value);
                    else if (key == "memory_limit")
                        r.memoryLimit = std::stod(value);
                    else if (key == "michi_version")
                        r.michiVersion = value;
                    else if (key == "outcome")
                        r.outcome = value;
                    else if (key == "cause")
                        r.cause = value;
                    else if (key == "signal")
                        r.signal = std::stoi(value);
                    else if (key == "wall_time")
                        r.wallTime = std::stod(value);
                    else if (key == "setup_info")
                        r.setupInfo = value;
                    else if (key == "setting")
                        r.settings.push_back(value);
                    else if (key.rfind("property.", 0) == 0)
                        r.properties[key.substr(9)] = value;
                    else if (key == "progress_name")
                        r.progressNames.push_back(value);
                    else if (key == "progress_sample")
                    {
                        std::vector<std::string> sample;
                        std::istringstream cells(value);
                        for (std::string cell; std::getline(cells, cell, ',');)
                            sample.push_back(cell);
                        if (value.empty() || value.back() == ',')
                            sample.emplace_back();  // getline drops a last empty value
                        r.progress.push_back(std::move(sample));
                    }
                    else if (key == "end")
                        ended = true;
                    else
                        throw bad("unknown key '" + key + "'");
                }
            }
            catch (const std::logic_error &)  // std::stoul and friends
            {
                throw bad("expected a number");
            }
            if (!ended)
                throw std::runtime_error(source + ": incomplete unit record (no end line)");
            for (const auto &sample : r.progress)
                if (sample.size() != r.progressNames.size())
                    throw std::runtime_error(source + ": a progress sample has " + std::to_string(sample.size()) +
                                             " values for " + std::to_string(r.progressNames.size()) +
                                             " progress properties");
            // The summary and the database read outcomes by name: any other word would be counted as neither solved nor
            // failed.
            if (r.outcome != "done" && r.outcome != "crash" && r.outcome != "timeout" && r.outcome != "error" &&
                r.outcome != "pending")
                throw std::runtime_error(source + ": outcome '" + r.outcome +
                                         "' is not done, crash, timeout, error or pending");
            return r;
        }

        void writeUnitRecord(const UnitRecord &record, const std::string &file)
        {
            writeAtomically(formatUnitRecord(record), file);
        }

        UnitRecord readUnitRecord(const std::string &file)
        {
            std::ifstream in(file);
            if (!in)
                throw std::runtime_error(file + ": cannot read the unit record");
            std::stringstream s;
            s << in.rdbuf();
            return parseUnitRecord(s.str(), file);
        }
    }  // namespace tools
}  // namespace michi
