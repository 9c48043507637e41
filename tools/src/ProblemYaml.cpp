#include "ProblemYaml.h"

#include <boost/filesystem.hpp>

#include <algorithm>
#include <cmath>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace problem_file
        {
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
                    return parseNumber(text);
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
                return n ? number(n, key + "." + name) : fallback;
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

            std::string Reader::text(const YAML::Node &n, const std::string &key) const
            {
                if (!n.IsScalar())
                    fail(key, "expected a string");
                return n.Scalar();
            }

            unsigned int Reader::count(const YAML::Node &n, const std::string &key) const
            {
                const double v = number(n, key);
                if (!(v >= 1.) || v != std::floor(v) || v > 1e9)
                    fail(key, "expected a positive integer");
                return static_cast<unsigned int>(v);
            }

            bool Reader::flag(const YAML::Node &n, const std::string &key) const
            {
                if (!n.IsScalar() || (n.Scalar() != "true" && n.Scalar() != "false"))
                    fail(key, "expected true or false");
                return n.Scalar() == "true";
            }

            std::string Reader::path(const YAML::Node &n, const std::string &key) const
            {
                const fs::path p = fs::path(text(n, key));
                const fs::path full = p.is_absolute() ? p : fs::path(file_).parent_path() / p;
                if (!fs::exists(full))
                    fail(key, "file '" + full.string() + "' does not exist");
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
                        const auto v = numbers(n[name], key + "." + name, 3);
                        t.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
                    }
                if (n["rpy"])
                {
                    const auto r = numbers(n["rpy"], key + ".rpy", 3);
                    t.linear() = (Eigen::AngleAxisd(r[2], Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(r[1], Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(r[0], Eigen::Vector3d::UnitX()))
                                     .toRotationMatrix();
                }
                else if (n["orientation"])
                {
                    const auto q = numbers(n["orientation"], key + ".orientation", 4);
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
                    const auto p = numbers(n[i], key + "[" + std::to_string(i) + "]", 2);
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
