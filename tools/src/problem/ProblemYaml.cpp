#include "ProblemYaml.h"

#include <michi/validity/InputFile.h>
#include <michi/validity/Limits.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace problem_file
        {
            namespace
            {
                /** Throws on the first mapping that holds a key twice (yaml-cpp would keep only one of them).
                    \e budget: values still to visit. Written out, a file has at most about as many values as
                    characters; aliases (*name) repeat a subtree without writing it, and nested ones repeat it
                    exponentially (a "billion laughs" file), so a walk past the budget stops with an error instead
                    of running for hours. */
                void rejectDuplicateKeys(const std::string &file, const YAML::Node &n, const std::string &key,
                                         int depth, std::size_t &budget)
                {
                    if (depth > 200)  // deeper nesting is no michi file; stop before the stack does
                        throw ProblemError(file, key, "nested more than 200 levels deep");
                    if (budget == 0)
                        throw ProblemError(file, key,
                                           "more values than the file has characters: aliases (*name) repeat "
                                           "too much of it");
                    --budget;
                    if (n.IsMap())
                    {
                        std::set<std::string> seen;
                        for (const auto &kv : n)
                        {
                            // every reader takes keys as names: a list or mapping as a key ("? [a, b] : 1") is
                            // refused here, once, rather than as yaml-cpp's "bad conversion" wherever it is read
                            if (!kv.first.IsScalar())
                                throw ProblemError(file, key.empty() ? "?" : key + ".?",
                                                   "a key must be a plain name, not a list or a mapping (line " +
                                                       std::to_string(kv.first.Mark().line + 1) + ")");
                            const std::string k = kv.first.Scalar();
                            const std::string child = key.empty() ? k : key + "." + k;
                            if (!seen.insert(k).second)
                                throw ProblemError(file, child,
                                                   "duplicate key (line " + std::to_string(kv.first.Mark().line + 1) +
                                                       "): each key may appear once");
                            rejectDuplicateKeys(file, kv.second, child, depth + 1, budget);
                        }
                    }
                    else if (n.IsSequence())
                        for (std::size_t i = 0; i < n.size(); ++i)
                            rejectDuplicateKeys(file, n[i], key + "[" + std::to_string(i) + "]", depth + 1, budget);
                }

                YAML::Node parseYamlFile(const std::string &file)
                {
                    std::string text;
                    try
                    {
                        text = validity::readInputFile(file);
                    }
                    catch (const validity::InputFileError &e)
                    {
                        throw ProblemError(file, "", e.reason());
                    }
                    YAML::Node root;
                    try
                    {
                        root = YAML::Load(text);
                    }
                    catch (const YAML::Exception &e)
                    {
                        throw ProblemError(file, "",
                                           "not valid YAML (line " + std::to_string(e.mark.line + 1) + ", column " +
                                               std::to_string(e.mark.column + 1) + "): " + e.msg);
                    }
                    std::size_t budget = 2 * text.size() + 1000;
                    rejectDuplicateKeys(file, root, "", 0, budget);
                    return root;
                }
            }  // namespace

            namespace
            {
                /** The parsed tree per file, size and modification time: every section reader (dual_arm,
                    experience, extras.replan) asks for the problem file again, and each file is parsed once.
                    \e copy gets what the caller keeps out of the cached tree, under the cache's lock. */
                YAML::Node cachedYaml(const std::string &file,
                                      const std::function<YAML::Node(const YAML::Node &)> &copy)
                {
                    struct Cached
                    {
                        std::uintmax_t size;
                        std::filesystem::file_time_type time;
                        YAML::Node root;
                    };
                    static std::mutex cacheMutex;
                    static std::map<std::string, Cached> cache;
                    std::error_code ec;
                    const auto size = std::filesystem::file_size(file, ec);
                    const auto time =
                        ec ? std::filesystem::file_time_type() : std::filesystem::last_write_time(file, ec);
                    if (!ec)
                    {
                        std::lock_guard<std::mutex> lock(cacheMutex);
                        auto it = cache.find(file);
                        if (it != cache.end() && it->second.size == size && it->second.time == time)
                            return copy(it->second.root);
                    }
                    // parsed outside the lock: several threads may read several files at once
                    YAML::Node root = parseYamlFile(file);
                    if (ec)
                        return copy(root);
                    std::lock_guard<std::mutex> lock(cacheMutex);
                    return copy(cache.insert_or_assign(file, Cached{size, time, root}).first->second.root);
                }
            }  // namespace

            YAML::Node loadYaml(const std::string &file)
            {
                // a copy: callers may change their tree, never the cached one
                return cachedYaml(file,
                                  [](const YAML::Node &root)
                                  {
                                      return YAML::Clone(root);
                                  });
            }

            YAML::Node loadYamlSection(const std::string &file, const std::string &key)
            {
                return cachedYaml(file,
                                  [&key](const YAML::Node &root)
                                  {
                                      const YAML::Node section = root.IsMap() ? root[key] : YAML::Node();
                                      return section ? YAML::Clone(section) : YAML::Node(YAML::NodeType::Undefined);
                                  });
            }

            void Reader::fail(const std::string &key, const std::string &message) const
            {
                throw ProblemError(file_, key, message);
            }

            YAML::Node Reader::require(const YAML::Node &map, const std::string &name, const std::string &key) const
            {
                if (!map.IsMap())
                    fail(key, "expected a mapping");
                const YAML::Node n = map[name];
                if (!n)
                    fail(key.empty() ? name : key + "." + name, "missing (required)");
                return n;
            }

            double Reader::number(const YAML::Node &n, const std::string &key) const
            {
                if (!n.IsScalar())
                    fail(key, "expected a number");
                const std::string text = n.Scalar();
                // accept "pi", "-pi/2", "0.5*pi" as conveniences for joint values
                try
                {
                    const double v = parseNumber(text);
                    // any count, time or size michi reads is far below 1e12; beyond it squares and sums of
                    // values stop being exact and products overflow in the geometry code
                    if (std::abs(v) > 1e12)
                        fail(key, "number " + text + " is out of range (|value| above 1e12)");
                    return v;
                }
                catch (const ProblemError &)
                {
                    throw;
                }
                catch (const std::exception &)
                {
                    fail(key, "expected a number, got '" + text + "'");
                }
            }

            double Reader::number(const YAML::Node &map, const std::string &name, const std::string &key,
                                  double fallback) const
            {
                const YAML::Node n = map[name];
                return n ? number(n, key.empty() ? name : key + "." + name) : fallback;
            }

            std::vector<double> Reader::numbers(const YAML::Node &n, const std::string &key, std::size_t size) const
            {
                if (!n.IsSequence())
                    fail(key, size ? "expected a list of " + std::to_string(size) + " numbers"
                                   : "expected a list of numbers");
                if (size && n.size() != size)
                    fail(key, "expected " + std::to_string(size) + " numbers, got " + std::to_string(n.size()));
                std::vector<double> values;
                for (std::size_t i = 0; i < n.size(); ++i)
                    values.push_back(number(n[i], key + "[" + std::to_string(i) + "]"));
                return values;
            }

            double Reader::coordinate(const YAML::Node &n, const std::string &key) const
            {
                const double v = number(n, key);
                if (!validity::isGeometryValue(v))
                    fail(key, "coordinate " + validity::geometryValueProblem(v));
                return v;
            }

            std::vector<double> Reader::coordinates(const YAML::Node &n, const std::string &key, std::size_t size) const
            {
                const auto values = numbers(n, key, size);
                for (std::size_t i = 0; i < values.size(); ++i)
                    if (!validity::isGeometryValue(values[i]))
                        fail(key + "[" + std::to_string(i) + "]",
                             "coordinate " + validity::geometryValueProblem(values[i]));
                return values;
            }

            std::string Reader::text(const YAML::Node &n, const std::string &key) const
            {
                if (!n.IsScalar())
                    fail(key, "expected a string");
                return n.Scalar();
            }

            unsigned int Reader::count(const YAML::Node &n, const std::string &key) const
            {
                const double v = number(n, key);
                // Checked as a double first: a cast of a negative, fractional or huge value to unsigned would wrap
                // silently.
                if (!(v >= 1.) || v != std::floor(v) || v > 1e9)
                    fail(key, "expected a positive integer");
                return static_cast<unsigned int>(v);
            }

            bool Reader::flag(const YAML::Node &n, const std::string &key) const
            {
                // Only these two spellings: a misspelt value is an error instead of a silent false.
                if (!n.IsScalar() || (n.Scalar() != "true" && n.Scalar() != "false"))
                    fail(key, "expected true or false");
                return n.Scalar() == "true";
            }

            std::string Reader::path(const YAML::Node &n, const std::string &key) const
            {
                const fs::path p = fs::path(text(n, key));
                // Relative to the problem file, not the working directory: a problem folder works from wherever michi
                // runs.
                const fs::path full = p.is_absolute() ? p : fs::path(file_).parent_path() / p;
                if (!fs::exists(full))
                    fail(key, "file '" + full.string() + "' does not exist");
                // a folder or a device here would fail later with a message that names no key
                try
                {
                    validity::requireInputFile(full.string());
                }
                catch (const validity::InputFileError &e)
                {
                    fail(key, "'" + full.string() + "' " + e.reason());
                }
                return full.lexically_normal().string();
            }

            Eigen::Isometry3d Reader::pose(const YAML::Node &n, const std::string &key) const
            {
                if (!n.IsMap())
                    fail(key, "expected a pose {xyz: [x, y, z], rpy: [roll, pitch, yaw]}");
                Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
                for (const char *name : {"xyz", "position"})
                    if (n[name])
                    {
                        const auto v = coordinates(n[name], key + "." + name, 3);
                        t.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
                    }
                if (n["rpy"])
                {
                    const auto r = numbers(n["rpy"], key + ".rpy", 3);
                    // R = Rz(yaw) Ry(pitch) Rx(roll), URDF's convention: roll, pitch, yaw about fixed axes.
                    t.linear() = (Eigen::AngleAxisd(r[2], Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(r[1], Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(r[0], Eigen::Vector3d::UnitX()))
                                     .toRotationMatrix();
                }
                else if (n["orientation"])
                {
                    const auto q = numbers(n["orientation"], key + ".orientation", 4);
                    // Files give [x, y, z, w] as ROS does; Eigen's constructor takes w first.
                    const Eigen::Quaterniond quat(q[3], q[0], q[1], q[2]);
                    if (quat.norm() < 1e-9)
                        fail(key + ".orientation", "quaternion has zero norm");
                    t.linear() = quat.normalized().toRotationMatrix();
                }
                for (const auto &kv : n)
                {
                    const std::string k = kv.first.as<std::string>();
                    if (k != "xyz" && k != "position" && k != "rpy" && k != "orientation")
                        fail(key + "." + k, "unknown pose key (expected xyz/rpy or position/orientation)");
                }
                return t;
            }

            std::vector<Eigen::Vector2d> Reader::polygon(const YAML::Node &n, const std::string &key) const
            {
                if (!n.IsSequence() || n.size() < 3)
                    fail(key, "expected a list of at least 3 [x, y] points");
                std::vector<Eigen::Vector2d> points;
                for (std::size_t i = 0; i < n.size(); ++i)
                {
                    const auto p = coordinates(n[i], key + "[" + std::to_string(i) + "]", 2);
                    points.emplace_back(p[0], p[1]);
                }
                return points;
            }

            double Reader::parseNumber(std::string text)
            {
                text.erase(std::remove_if(text.begin(), text.end(), ::isspace), text.end());
                double sign = 1.;
                if (!text.empty() && (text[0] == '-' || text[0] == '+'))
                {
                    sign = text[0] == '-' ? -1. : 1.;
                    text = text.substr(1);
                }
                const auto pi = text.find("pi");
                if (pi == std::string::npos)
                {
                    std::size_t used = 0;
                    const double v = std::stod(text, &used);
                    // stod stops at the first character it cannot read: "1.5m" must be an error, not 1.5.
                    if (used != text.size() || !std::isfinite(v))
                        throw std::invalid_argument(text);
                    return sign * v;
                }
                // forms: pi, k*pi, pi/d, k*pi/d
                double factor = 1., divisor = 1.;
                const std::string before = text.substr(0, pi), after = text.substr(pi + 2);
                if (!before.empty())
                {
                    if (before.back() != '*')
                        throw std::invalid_argument(text);
                    // Recursive, so factor and divisor may carry their own sign or be plain numbers ("-0.5*pi",
                    // "pi/-4").
                    factor = parseNumber(before.substr(0, before.size() - 1));
                }
                if (!after.empty())
                {
                    if (after[0] != '/')
                        throw std::invalid_argument(text);
                    divisor = parseNumber(after.substr(1));
                    if (divisor == 0.)
                        throw std::invalid_argument(text);
                }
                return sign * factor * M_PI / divisor;
            }

            void Reader::keys(const YAML::Node &n, const std::string &key, const std::set<std::string> &allowed) const
            {
                if (!n || !n.IsMap())  // absent (or not a mapping: the caller's own check reports that)
                    return;
                for (const auto &kv : n)
                {
                    const std::string k = kv.first.as<std::string>();
                    if (!allowed.count(k))
                    {
                        std::string list;
                        for (const auto &a : allowed)
                            list += (list.empty() ? "" : ", ") + a;
                        fail(key.empty() ? k : key + "." + k, "unknown key (expected one of " + list + ")");
                    }
                }
            }
        }  // namespace problem_file
    }      // namespace tools
}  // namespace michi
