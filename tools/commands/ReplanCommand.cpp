#include <michi/tools/commands/ReplanCommand.h>

#include "ReplanMethodRun.h"
#include "ReplanReport.h"

#include <michi/tools/FileOutput.h>
#include <michi/tools/problem/Problem.h>

#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace michi
{
    namespace tools
    {
        namespace
        {
            using namespace replan;  // the pieces of michi replan (ReplanTypes.h, ReplanMethodRun.h, ReplanReport.h)

            /** The problem's static obstacles and its movers (two or more key frames); throws without a mover. */
            void splitObstacles(const Problem &problem, const ReplanSettings &settings,
                                std::vector<validity::Obstacle> &statics, std::vector<Mover> &movers)
            {
                const auto obstacles = problem.scene->obstacles();
                for (std::size_t i = 0; i < obstacles.size(); ++i)
                {
                    const auto &o = obstacles[i];
                    // A single key frame is a pose, not a motion: such an obstacle stands where that key frame puts it.
                    if (o.trajectory.size() < 2)
                    {
                        validity::Obstacle s = o;
                        if (!s.trajectory.empty())
                            s.pose = s.trajectory.front().pose;
                        s.trajectory.clear();
                        statics.push_back(s);
                        continue;
                    }
                    Mover m;
                    m.name = o.name;
                    m.shape = o.shape;
                    m.grown = grow(*o.shape, settings.margin, problem.file, "scene.obstacles (" + o.name + ")");
                    m.trajectory = o.trajectory;
                    movers.push_back(m);
                }
                if (movers.empty())
                    throw ProblemError(problem.file, "scene.obstacles",
                                       "michi replan needs a moving obstacle (one with a trajectory of two or more key "
                                       "frames)");
            }

            /** Episode \e e's key frames of every mover: its timing shifted and its speed scaled, drawn from the
                seed and the episode only (the same draws for every method). */
            std::vector<std::vector<validity::TimedPose>> episodeTrajectories(const std::vector<Mover> &movers,
                                                                              const ReplanSettings &settings,
                                                                              unsigned int seed, unsigned int e)
            {
                std::vector<std::vector<validity::TimedPose>> out;
                // A generator per episode, from the seed and the episode number alone: episode e is the same for every
                // method and whatever ran before it.
                ompl::RNG rng(seed * 100003u + e);
                for (const auto &m : movers)
                {
                    const double shift = rng.uniformReal(-settings.timingJitter, settings.timingJitter);
                    const double speed = rng.uniformReal(1. - settings.speedJitter, 1. + settings.speedJitter);
                    const double t0 = m.trajectory.front().time;
                    std::vector<validity::TimedPose> tr = m.trajectory;
                    for (auto &k : tr)
                        // Shifted start (never before 0) and time stretched by 1 / speed: the same path, driven earlier
                        // or later, faster or slower.
                        k.time = std::max(0., t0 + shift) + (k.time - t0) / speed;
                    out.push_back(tr);
                }
                return out;
            }
        }  // namespace

        std::vector<validity::Obstacle> replanEpisodeObstacles(const std::string &problemFile, unsigned int seed,
                                                               unsigned int episode)
        {
            const Problem problem = loadProblem(problemFile);
            const ReplanSettings settings = readSettings(problemFile);
            std::vector<validity::Obstacle> statics;
            std::vector<Mover> movers;
            splitObstacles(problem, settings, statics, movers);
            const auto trajectories = episodeTrajectories(movers, settings, seed, episode);
            std::vector<validity::Obstacle> out;
            for (std::size_t k = 0; k < movers.size(); ++k)
            {
                validity::Obstacle o;
                o.name = movers[k].name;
                o.shape = movers[k].shape;
                o.trajectory = trajectories[k];
                o.pose = validity::Scene::poseAt(o.trajectory, 0.);
                out.push_back(o);
            }
            return out;
        }

        std::string runReplan(const ReplanOptions &options)
        {
            if (options.episodes == 0)
                throw std::invalid_argument("--episodes must be a positive integer");
            // before anything draws a seed from OMPL's seed generator: then every planner's and sampler's random
            // numbers follow from --seed (reproducible runs, extras.replan.real_time 0)
            ompl::RNG::setSeed(options.seed);
            const Problem problem = loadProblem(options.problemFile);
            const ReplanSettings settings = readSettings(options.problemFile);
            std::vector<validity::Obstacle> statics;
            std::vector<Mover> movers;
            splitObstacles(problem, settings, statics, movers);

            std::vector<Method> methods;
            const auto all = allMethods();
            if (options.methods.empty())
                methods = all;
            else
                for (const auto &name : options.methods)
                {
                    auto it = std::find_if(all.begin(), all.end(),
                                           [&](const Method &m)
                                           {
                                               return m.id == name || m.label == name;
                                           });
                    if (it == all.end())
                    {
                        std::string known;
                        for (const auto &m : all)
                            known += (known.empty() ? "" : ", ") + m.id;
                        throw std::invalid_argument("--methods: unknown method '" + name + "' (known: " + known + ")");
                    }
                    // replan.json lists each method once (a second run under the same key was a duplicate JSON key)
                    if (std::any_of(methods.begin(), methods.end(),
                                    [&](const Method &m)
                                    {
                                        return m.id == it->id;
                                    }))
                        throw std::invalid_argument("--methods: '" + name + "' names method '" + it->id +
                                                    "' a second time");
                    methods.push_back(*it);
                }

            // the episodes' obstacle timings: the same draws for every method
            std::vector<std::vector<std::vector<validity::TimedPose>>> episodes(options.episodes);
            for (unsigned int e = 0; e < options.episodes; ++e)
                episodes[e] = episodeTrajectories(movers, settings, options.seed, e);

            std::vector<Results> results(methods.size());
            std::vector<Frame> frames;
            std::vector<Trace> traces(options.html ? methods.size() : 0);  // the first episode of every method
            for (std::size_t mi = 0; mi < methods.size(); ++mi)
            {
                // One planner per method, kept across all episodes: what DualRoadmap learns (and LazyPRM's roadmap)
                // carries over from episode to episode.
                MethodRun run(problem, statics, movers, settings, methods[mi]);
                const auto begin = std::chrono::steady_clock::now();
                for (unsigned int e = 0; e < options.episodes; ++e)
                {
                    run.episode(episodes[e], results[mi], mi == 0 && e == 0 ? &frames : nullptr,
                                e == 0 && options.html ? &traces[mi] : nullptr);
                    if (options.progress != nullptr)
                        *options.progress << "\r" << methods[mi].label << ": episode " << (e + 1) << "/"
                                          << options.episodes << std::flush;
                }
                results[mi].wallSeconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
                if (options.progress != nullptr)
                    *options.progress << "\n";
            }

            const std::string json = reportJson(problem, options.seed, settings, methods, results);

            // staged output: nothing in DIR unless everything was written (an old episode/ folder is replaced)
            StagedDirectory stage(options.outDir);
            writeFrames(stage, problem, statics, movers, frames, settings.frames);
            if (options.html)
            {
                std::vector<std::string> labels;
                for (const auto &m : methods)
                    labels.push_back(m.label);
                writeEpisodeReplay(stage.path(problem.name + ".html").string(), problem, statics, movers, labels,
                                   traces);
            }
            writeAtomically(json, stage.path("replan.json").string());
            stage.commit();
            return json;
        }
    }  // namespace tools
}  // namespace michi
