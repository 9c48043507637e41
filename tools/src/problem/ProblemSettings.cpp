#include "ProblemYaml.h"

#include <michi/tools/problem/Dataset.h>

namespace michi
{
    namespace tools
    {
        namespace problem_file
        {
            namespace
            {
                void readJMapSettings(const Reader &r, const YAML::Node &n, const std::string &key,
                                      validity::JMapCheckerSettings &settings)
                {
                    if (!n.IsMap())
                        r.fail(key, "expected a mapping (mode, slices, tiles, tolerance, fallback_band)");
                    r.keys(n, key, {"mode", "slices", "tiles", "tolerance", "fallback_band"});
                    if (n["mode"])
                    {
                        const std::string mode = r.text(n["mode"], key + ".mode");
                        if (mode == "conservative")
                            settings.mode = validity::JMapCheckerSettings::Mode::CONSERVATIVE;
                        else if (mode == "exact_fallback")
                            settings.mode = validity::JMapCheckerSettings::Mode::EXACT_FALLBACK;
                        else
                            r.fail(key + ".mode", "expected conservative or exact_fallback, got '" + mode + "'");
                    }
                    if (n["slices"])
                    {
                        settings.map.slices = static_cast<int>(r.count(n["slices"], key + ".slices"));
                        // 72 is 5 degrees; 3600 is 0.1 degree, finer than any arm's map needs (memory and build
                        // time grow with the slices)
                        if (settings.map.slices > 3600)
                            r.fail(key + ".slices", "expected at most 3600 slices");
                    }
                    if (n["tiles"])
                        settings.tiles = static_cast<int>(r.count(n["tiles"], key + ".tiles"));
                    // Every tile needs at least one slice of its own (each gets slices / tiles, rounded up).
                    if (settings.tiles > settings.map.slices)
                        r.fail(key + ".tiles", "must not exceed slices");
                    // The line walk's circle radius: it trades tightness for vertex count; containment does not depend
                    // on it (jmap.md).
                    settings.map.tolerance = r.number(n, "tolerance", key, settings.map.tolerance);
                    if (!(settings.map.tolerance > 0.))
                        r.fail(key + ".tolerance", "expected a positive number of radians");
                    settings.fallbackBand = r.number(n, "fallback_band", key, settings.fallbackBand);
                    if (!(settings.fallbackBand >= 0.))
                        r.fail(key + ".fallback_band", "expected a non-negative number of radians");
                }

                void readGridSettings(const Reader &r, const YAML::Node &n, const std::string &key,
                                      validity::GridCheckerSettings &settings)
                {
                    if (!n.IsMap())
                        r.fail(key, "expected a mapping (resolution, headings)");
                    r.keys(n, key, {"resolution", "headings"});
                    if (n["resolution"])
                    {
                        settings.resolution = r.number(n["resolution"], key + ".resolution");
                        if (!(settings.resolution >= 1e-4) || settings.resolution > 1e3)
                            r.fail(key + ".resolution", "expected a number of metres in [0.0001, 1000]");
                    }
                    if (n["headings"])
                    {
                        settings.headings = r.count(n["headings"], key + ".headings");
                        // The table holds a bit per cell and heading: 1024 headings of a 2064 x 2064 table (64room)
                        // would be over half a GB.
                        if (settings.headings < 1 || settings.headings > 1024)
                            r.fail(key + ".headings", "expected a number of heading bins in 1..1024");
                    }
                }
            }  // namespace

            void readPlanners(const Reader &r, const YAML::Node &list, Problem &problem)
            {
                if (!list)
                {
                    for (const char *name :
                         // No list: one OMPL baseline of each kind (bidirectional tree, roadmap, asymptotically optimal
                         // tree, informed batch search), so every benchmark has a reference.
                         {"geometric::RRTConnect", "geometric::PRM", "geometric::RRTstar", "geometric::BITstar"})
                        problem.planners.push_back(PlannerSpec{name, {}, {}});
                    return;
                }
                if (!list.IsSequence() || list.size() == 0)
                    r.fail("planners", "expected a non-empty list of planner names or {name, params}");
                for (std::size_t i = 0; i < list.size(); ++i)
                {
                    const std::string key = "planners[" + std::to_string(i) + "]";
                    PlannerSpec spec;
                    if (list[i].IsScalar())
                        spec.name = list[i].Scalar();
                    else if (list[i].IsMap())
                    {
                        spec.name = r.text(r.require(list[i], "name", key), key + ".name");
                        for (const auto &kv : list[i])
                        {
                            const std::string k = kv.first.as<std::string>();
                            if (k != "name" && k != "params" && k != "checker")
                                r.fail(key + "." + k, "unknown key (expected name, params, checker)");
                        }
                        if (const YAML::Node checker = list[i]["checker"])
                        {
                            spec.checker = r.text(checker, key + ".checker");
                            if (spec.checker != "fcl" && spec.checker != "jmap" && spec.checker != "grid" &&
                                spec.checker != "spheres")
                                r.fail(key + ".checker",
                                       "expected fcl, jmap, grid or spheres, got '" + spec.checker + "'");
                        }
                        if (const YAML::Node params = list[i]["params"])
                        {
                            if (!params.IsMap())
                                r.fail(key + ".params", "expected a mapping of parameter name to value");
                            // Kept as text: OMPL's ParamSet parses each value with the planner's own setter
                            // (applyPlannerParams).
                            for (const auto &kv : params)
                                spec.params[kv.first.as<std::string>()] =
                                    r.text(kv.second, key + ".params." + kv.first.as<std::string>());
                        }
                    }
                    else
                        r.fail(key, "expected a planner name or {name, params, checker}");
                    // runs are named by planner (and checker): a second entry would be a second set of parameters
                    // under the same name, and michi plan would take one of them silently
                    for (const auto &earlier : problem.planners)
                        if (earlier.name == spec.name && earlier.checker == spec.checker)
                            r.fail(key, "'" + spec.name + "'" +
                                            (spec.checker.empty() ? "" : " on checker " + spec.checker) +
                                            " is listed twice");
                    problem.planners.push_back(spec);
                }
            }

            void readBenchmark(const Reader &r, const YAML::Node &b, Problem &problem)
            {
                if (!b)
                    return;
                if (!b.IsMap())
                    r.fail("benchmark", "expected a mapping (time_limit, runs, memory_limit, seed, simplify)");
                auto &s = problem.benchmark;
                for (const auto &kv : b)
                {
                    const std::string k = kv.first.as<std::string>(), key = "benchmark." + k;
                    if (k == "time_limit")
                    {
                        s.timeLimit = r.number(kv.second, key);
                        if (!(s.timeLimit > 0.))
                            r.fail(key, "expected a positive number of seconds");
                    }
                    else if (k == "memory_limit")
                    {
                        s.memoryLimit = r.number(kv.second, key);
                        if (!(s.memoryLimit > 0.))
                            r.fail(key, "expected a positive number of megabytes");
                    }
                    else if (k == "runs")
                        s.runs = r.count(kv.second, key);
                    else if (k == "seed")
                        // At least 1: ompl::RNG::setSeed() ignores a seed of 0 (with a warning), which would leave runs
                        // unseeded.
                        s.seed = r.count(kv.second, key);
                    else if (k == "simplify")
                        s.simplify = r.flag(kv.second, key);
                    else if (k == "queries")
                    {
                        s.queries = r.text(kv.second, key);
                        try
                        {
                            parseQuerySelection(s.queries);
                        }
                        catch (const std::invalid_argument &e)
                        {
                            r.fail(key, e.what());
                        }
                    }
                    else if (k == "objective")
                    {
                        s.objective = r.text(kv.second, key);
                        if (s.objective != "length" && s.objective != "clearance")
                            r.fail(key, "expected length or clearance, got '" + s.objective + "'");
                    }
                    else
                        r.fail(key,
                               "unknown key (expected time_limit, runs, memory_limit, seed, simplify, queries, "
                               "objective)");
                }
            }

            void readCollision(const Reader &r, const YAML::Node &c, Problem &problem)
            {
                if (!c)
                    return;
                if (!c.IsMap())
                    r.fail("collision", "expected a mapping (motion_validator, max_step, valid_segment_fraction)");
                for (const auto &kv : c)
                {
                    const std::string k = kv.first.as<std::string>(), key = "collision." + k;
                    if (k == "valid_segment_fraction")
                    {
                        // OMPL's resolution for its discrete motion validator: a fraction of the space's extent, so it
                        // lies in (0, 1).
                        problem.validSegmentFraction = r.number(kv.second, key);
                        if (problem.validSegmentFraction <= 0. || problem.validSegmentFraction >= 1.)
                            r.fail(key, "expected a number in (0, 1)");
                    }
                    else if (k == "max_step")
                    {
                        problem.maxStep = r.number(kv.second, key);
                        // a motion is checked every max_step metres: below 0.1 mm a 1 m motion takes 10,000+
                        // checks and planning never ends in practice
                        if (!(problem.maxStep >= 1e-4) || problem.maxStep > 1e3)
                            r.fail(key, "expected a number of metres in [0.0001, 1000]");
                    }
                    else if (k == "motion_validator")
                    {
                        problem.motionValidator = r.text(kv.second, key);
                        if (problem.motionValidator != "workspace" && problem.motionValidator != "conservative" &&
                            problem.motionValidator != "discrete")
                            r.fail(key, "expected workspace, conservative or discrete, got '" +
                                            problem.motionValidator + "'");
                    }
                    else if (k == "checker")
                    {
                        problem.checker = r.text(kv.second, key);
                        if (problem.checker != "fcl" && problem.checker != "jmap" && problem.checker != "grid" &&
                            problem.checker != "spheres")
                            r.fail(key, "expected fcl, jmap, grid or spheres, got '" + problem.checker + "'");
                        if (problem.checker == "grid" && problem.kind != Problem::Kind::SE2)
                            r.fail(key, "the grid checker is for SE2 robots (robot.type se2)");
                    }
                    else if (k == "jmap")
                        readJMapSettings(r, kv.second, key, problem.jmap);
                    else if (k == "grid")
                        readGridSettings(r, kv.second, key, problem.grid);
                    else if (k == "spheres")
                    {
                        if (!kv.second.IsMap())
                            r.fail(key, "expected a mapping (per_link, urdf, exact_states)");
                        r.keys(kv.second, key, {"per_link", "urdf", "exact_states"});
                        if (kv.second["exact_states"])
                        {
                            problem.spheres.exactStates = r.text(kv.second["exact_states"], key + ".exact_states");
                            if (problem.spheres.exactStates != "auto" && problem.spheres.exactStates != "on" &&
                                problem.spheres.exactStates != "off")
                                r.fail(key + ".exact_states",
                                       "expected auto, on or off, got '" + problem.spheres.exactStates + "'");
                        }
                        if (kv.second["per_link"])
                        {
                            problem.spheres.perLink = r.count(kv.second["per_link"], key + ".per_link");
                            if (problem.spheres.perLink < 1 || problem.spheres.perLink > 1024)
                                r.fail(key + ".per_link", "expected a number of spheres per link in 1..1024");
                        }
                        if (kv.second["urdf"])
                            problem.spheres.spherizedUrdf = r.path(kv.second["urdf"], key + ".urdf");
                    }
                    else
                        r.fail(key,
                               "unknown key (expected checker, jmap, grid, spheres, motion_validator, max_step, "
                               "valid_segment_fraction)");
                }
            }
        }  // namespace problem_file
    }      // namespace tools
}  // namespace michi
