// `michi random-scenes`: random planar scene problem files for the arm of a template problem.
#include <michi/tools/problem/RandomPlanarScene.h>
#include <michi/validity/InputFile.h>

#include <michi/tools/FileOutput.h>
#include <michi/tools/bench/PlanningContext.h>

#include <ompl/util/Console.h>

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <filesystem>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace michi
{
    namespace tools
    {
        namespace
        {
            namespace sfs = std::filesystem;

            /** shortest text that reads back as the same double */
            std::string number(double v)
            {
                char buffer[64];
                // std::to_chars without a precision writes the shortest text that reads back as the same double, so the
                // file's start and goal are exactly the ones checked (verified after writing, below).
                const auto r = std::to_chars(buffer, buffer + sizeof(buffer), v);
                return std::string(buffer, r.ptr);
            }

            std::string list(const std::vector<double> &values)
            {
                std::string s = "[";
                for (std::size_t i = 0; i < values.size(); ++i)
                    s += (i ? ", " : "") + number(values[i]);
                return s + "]";
            }

            /** the template's \e key block as YAML text ("key:\n  ...\n"), empty when the template has none */
            std::string block(const YAML::Node &root, const std::string &key, const YAML::Node *replacement = nullptr)
            {
                const YAML::Node node = replacement != nullptr ? *replacement : root[key];
                if (!node)
                    return "";
                YAML::Emitter out;
                out << YAML::BeginMap << YAML::Key << key << YAML::Value << node << YAML::EndMap;
                return std::string(out.c_str()) + "\n";
            }

            std::string sceneText(const RandomPlanarScene &random, std::uint_fast32_t seed, const std::string &armFile,
                                  const YAML::Node &root, const YAML::Node &robot,
                                  const RandomPlanarSceneOptions &options)
            {
                const Problem &p = random.problem;
                std::ostringstream out;
                out << "# " << p.name << ": a random planar scene, made by `michi random-scenes` (scene seed " << seed
                    << ").\n"
                    << "#\n"
                    << "# What it models: the arm of " << armFile << " among " << random.polygons.size()
                    << " random star-shaped polygons\n"
                    << "# (centres within " << number(options.extent) << " m of the arm's base, "
                    << number(options.keepClear) << " m around the base kept free), extruded over z in ["
                    << number(options.zMin) << ", " << number(options.zMax) << "].\n"
                    << "# Start and goal are random states that FCL calls valid, at least "
                    << number(options.minQueryDistance) << " rad apart"
                    << (p.dimension() == 2 && options.reachabilityStep > 0.
                            ? ",\n# linked by a grid search (step " + number(options.reachabilityStep) +
                                  " rad) with the problem's motion validator, so a path exists.\n"
                            : ";\n# they are not proved to be connected.\n")
                    << "# Where the data come from: generated (a local ompl::RNG seeded with " << seed
                    << "; michi::tools::randomPlanarScene); the\n"
                    << "# robot, planners, benchmark and collision blocks are copied from " << armFile << ".\n";
                out << "name: " << p.name << "\n";
                out << "description: >-\n  " << p.description << "\n";
                out << block(root, "robot", &robot);
                // an empty list written as such: "obstacles:" alone reads as null, which the loader refuses
                out << "scene:\n  obstacles:" << (random.polygons.empty() ? " []" : "") << "\n";
                for (std::size_t i = 0; i < random.polygons.size(); ++i)
                {
                    out << "    - name: polygon" << i << "\n      polygon:\n        points: [";
                    for (std::size_t k = 0; k < random.polygons[i].size(); ++k)
                        out << (k ? ", " : "") << "[" << number(random.polygons[i][k].x()) << ", "
                            << number(random.polygons[i][k].y()) << "]";
                    out << "]\n        z: [" << number(options.zMin) << ", " << number(options.zMax) << "]\n";
                }
                out << "start: " << list(p.queries[0].start) << "\n";
                out << "goal: " << list(p.queries[0].goal) << "\n";
                for (const char *key : {"planners", "benchmark", "collision"})
                    out << block(root, key);
                return out.str();
            }

            std::string withoutTrailingSlash(std::string s)
            {
                while (s.size() > 1 && s.back() == '/')
                    s.pop_back();
                return s;
            }
        }  // namespace

        std::vector<std::string> writeRandomScenes(const RandomScenesOptions &options)
        {
            if (options.outDir.empty())
                throw std::invalid_argument("no output folder given");
            if (options.count == 0)
                throw std::invalid_argument("no scenes to write (count 0)");
            if (options.seed > std::numeric_limits<std::uint32_t>::max() - (options.count - 1))
                throw std::invalid_argument("seed + count - 1 exceeds 4294967295");
            const Problem arm = loadProblem(options.arm);
            const YAML::Node root =
                YAML::Load(validity::readInputFile(options.arm));  // loadProblem() has parsed it already
            if (!root["robot"] || !root["robot"]["urdf"])
                throw ProblemError(options.arm, "robot.urdf", "random-scenes needs an arm given by a URDF file");

            // the URDF, referenced relative to the output folder (the staging folder is its sibling)
            const std::string outDir = withoutTrailingSlash(options.outDir);
            const sfs::path urdf = sfs::weakly_canonical(
                sfs::absolute(sfs::path(options.arm).parent_path() / root["robot"]["urdf"].as<std::string>()));
            const sfs::path out = sfs::weakly_canonical(sfs::absolute(outDir));
            sfs::path reference = urdf.lexically_relative(out);
            // No relative path between them (another root): the absolute path still works.
            if (reference.empty())
                reference = urdf;
            YAML::Node robot = YAML::Clone(root["robot"]);
            robot["urdf"] = reference.string();

            StagedDirectory stage(outDir);
            std::vector<std::string> written;
            for (unsigned int k = 0; k < options.count; ++k)
            {
                const std::uint_fast32_t seed = options.seed + k;
                const RandomPlanarScene random = randomPlanarScene(arm, seed, options.scene);
                const std::string name = random.problem.name + ".yaml";
                const std::string staged = stage.path(name).string();
                writeAtomically(sceneText(random, seed, options.arm, root, robot, options.scene), staged);
                // read it back: the file must load, and give the same start and goal, valid
                const Problem loaded = loadProblem(staged);
                if (loaded.queries.size() != 1 || loaded.queries[0].start != random.problem.queries[0].start ||
                    loaded.queries[0].goal != random.problem.queries[0].goal)
                    throw std::logic_error(name + ": the written start and goal do not read back unchanged");
                // Checks start and goal with FCL in the scene as written: a file that would fail michi bench is never
                // committed.
                makePlanningContext(loaded);
                written.push_back((sfs::path(outDir) / name).string());
            }
            stage.commit();
            return written;
        }
    }  // namespace tools
}  // namespace michi
