#include "ReplanTypes.h"
#include "problem/ProblemYaml.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <map>
#include <string>

namespace michi
{
    namespace tools
    {
        namespace replan
        {
            namespace
            {
                [[noreturn]] void fail(const std::string &file, const std::string &key, const std::string &what)
                {
                    throw ProblemError(file, key, what);
                }
            }  // namespace

            ReplanSettings readSettings(const std::string &file)
            {
                ReplanSettings s;
                // errors name the file (and line); only this section is copied
                const YAML::Node extras = problem_file::loadYamlSection(file, "extras");
                if (!extras || !extras.IsMap() || !extras["replan"])
                    return s;
                const YAML::Node r = extras["replan"];
                if (!r.IsMap())
                    fail(file, "extras.replan", "expected a mapping");
                std::map<std::string, double *> numbers{
                    {"dt", &s.dt},
                    {"sense_period", &s.sensePeriod},
                    {"speed", &s.speed},
                    {"deceleration", &s.deceleration},
                    {"safety_distance", &s.safetyDistance},
                    {"margin", &s.margin},
                    {"prediction_horizon", &s.predictionHorizon},
                    {"prediction_copies", &s.predictionCopies},
                    {"lookahead", &s.lookahead},
                    {"stop_margin", &s.stopMargin},
                    {"planning_time", &s.planningTime},
                    {"episode_time", &s.episodeTime},
                    {"timing_jitter", &s.timingJitter},
                    {"speed_jitter", &s.speedJitter},
                    {"real_time", &s.realTime},
                    {"planning_delay", &s.planningDelay},
                    {"planning_work", &s.planningWork},
                    {"escape_horizon", &s.escapeHorizon},
                    {"cross_time", &s.crossTime},
                    {"deformation_distance", &s.deform.startDistance},
                    {"deformation_window", &s.deform.window},
                    {"deformation_spacing", &s.deform.spacing},
                    {"frames", &s.frames},
                    {"retiming_horizon", &s.retimingHorizon},
                    {"retiming_slack", &s.retimingSlack},
                };
                std::string expected;
                for (const auto &kv : numbers)
                    expected += kv.first + ", ";
                expected += "clock, deformation, retiming, obstacles_yield, dual_roadmap_params";
                for (const auto &kv : r)
                {
                    const std::string key = kv.first.as<std::string>();
                    const std::string path = "extras.replan." + key;
                    if (key == "dual_roadmap_params")
                    {
                        if (!kv.second.IsMap())
                            fail(file, path, "expected a mapping of DualRoadmap parameter names to values");
                        for (const auto &p : kv.second)
                        {
                            if (!p.second.IsScalar())
                                fail(file, path + "." + p.first.Scalar(), "expected a value (a number or a word)");
                            s.dualParams[p.first.Scalar()] = p.second.Scalar();
                        }
                        continue;
                    }
                    if (key == "clock")
                    {
                        const std::string clock = kv.second.IsScalar() ? kv.second.as<std::string>() : "";
                        if (clock != "cpu" && clock != "wall")
                            fail(file, path, "expected cpu or wall");
                        s.cpuClock = clock == "cpu";
                        continue;
                    }
                    if (key == "deformation" || key == "obstacles_yield" || key == "retiming")
                    {
                        try
                        {
                            (key == "deformation" ? s.deformation
                             : key == "retiming"  ? s.retiming
                                                  : s.obstaclesYield) = kv.second.as<bool>();
                        }
                        catch (const std::exception &)
                        {
                            fail(file, path, "expected true or false");
                        }
                        continue;
                    }
                    auto it = numbers.find(key);
                    if (it == numbers.end())
                        fail(file, path, "unknown key (expected " + expected + ")");
                    // the problem file's own number reader: pi forms, finite, the file and key named
                    const double v = problem_file::Reader(file).number(kv.second, path);
                    // Zero turns these off (no margin, no jitter, no frames) or selects a mode (real_time 0: the
                    // reproducible model); the others are rates, periods and sizes, which must be positive.
                    const bool mayBeZero = key == "safety_distance" || key == "margin" || key == "timing_jitter" ||
                                           key == "speed_jitter" || key == "real_time" || key == "stop_margin" ||
                                           key == "prediction_horizon" || key == "frames" || key == "escape_horizon" ||
                                           key == "cross_time" || key == "planning_delay" || key == "retiming_slack";
                    if (!std::isfinite(v) || v < 0. || (!mayBeZero && v == 0.))
                        fail(file, path, mayBeZero ? "expected a number >= 0" : "expected a number > 0");
                    *it->second = v;
                }
                // Speeds are scaled by up to 1 +- speed_jitter: at 1 or more a mover could stand still or run
                // backwards.
                if (s.speedJitter >= 1.)
                    fail(file, "extras.replan.speed_jitter", "expected a fraction below 1");
                if (s.predictionCopies < 1. || s.predictionCopies > 100. ||
                    s.predictionCopies != std::floor(s.predictionCopies))
                    fail(file, "extras.replan.prediction_copies", "expected a whole number in 1..100");
                // bounded work: an episode is episode_time / dt simulation steps, each of which checks the scene
                if (s.dt < 1e-4 || s.dt > 1.)
                    fail(file, "extras.replan.dt", "expected a step in [0.0001, 1] seconds");
                if (s.episodeTime > 3600.)
                    fail(file, "extras.replan.episode_time", "expected at most 3600 simulated seconds");
                if (s.episodeTime / s.dt > 1e6)
                    fail(file, "extras.replan.dt",
                         "episode_time / dt is above 1,000,000 simulation steps per episode: use a larger dt");
                // Sensing happens between simulation steps: a period below dt could not be honoured.
                if (s.sensePeriod < s.dt)
                    fail(file, "extras.replan.sense_period", "expected at least dt");
                if (s.frames > 10000. || s.frames != std::floor(s.frames))
                    fail(file, "extras.replan.frames", "expected a whole number of frames in 0..10000");
                if (s.planningTime > 3600.)
                    fail(file, "extras.replan.planning_time", "expected at most 3600 seconds");
                // bounded work and memory: a deformation puts a point every spacing along the path (1e-9 filled
                // gigabytes and never finished)
                if (s.deform.spacing < 1e-3)
                    fail(file, "extras.replan.deformation_spacing", "expected at least 0.001 (the space's distance)");
                // the movers are grown by the margin, and shapes stay within 1e6 m (Shape's limit)
                if (s.margin > 1e3)
                    fail(file, "extras.replan.margin", "expected at most 1000 m");
                return s;
            }

            validity::ShapePtr grow(const validity::Shape &shape, double m, const std::string &file,
                                    const std::string &key)
            {
                const Eigen::Vector3d &z = shape.size();
                switch (shape.type())
                {
                    case validity::Shape::Type::BOX:
                        // Grown by the margin on every side (box extents are full widths, so twice the margin).
                        return validity::Shape::box(z + Eigen::Vector3d::Constant(2. * m));
                    case validity::Shape::Type::SPHERE:
                        return validity::Shape::sphere(z.x() + m);
                    case validity::Shape::Type::CYLINDER:
                        return validity::Shape::cylinder(z.x() + m, z.z() + 2. * m);
                    case validity::Shape::Type::CAPSULE:
                        // A capsule's length is its axis segment; the radius growth covers the ends too.
                        return validity::Shape::capsule(z.x() + m, z.z());
                    default:
                        fail(file, key,
                             "a moving obstacle must be a box, sphere, cylinder or capsule for michi replan "
                             "(it is grown by extras.replan.margin), got " +
                                 shape.describe());
                }
            }
        }  // namespace replan
    }      // namespace tools
}  // namespace michi
