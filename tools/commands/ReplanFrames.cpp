#include "ReplanReport.h"

#include <michi/tools/pictures/SvgPlot.h>
#include <michi/tools/viewer/ReplayPage.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <iomanip>
#include <sstream>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace replan
        {
            void writeFrames(const StagedDirectory &stage, const Problem &problem,
                             const std::vector<validity::Obstacle> &statics, const std::vector<Mover> &movers,
                             const std::vector<Frame> &frames, double count)
            {
                fs::create_directories(stage.path("episode"));
                const std::size_t want = std::max<std::size_t>(1, static_cast<std::size_t>(count));
                std::vector<std::size_t> chosen;
                for (std::size_t i = 0; i < want && !frames.empty(); ++i)
                    chosen.push_back(frames.size() == 1 ? 0
                                                        : i * (frames.size() - 1) / std::max<std::size_t>(1, want - 1));
                // Fewer frames recorded than asked for: the evenly spread indices repeat, and each picture is drawn
                // once.
                chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
                int n = 0;
                for (std::size_t idx : chosen)
                {
                    const Frame &f = frames[idx];
                    auto scene = std::make_shared<validity::Scene>();
                    for (const auto &o : statics)
                        scene->add(o);
                    for (std::size_t k = 0; k < movers.size(); ++k)
                    {
                        validity::Obstacle o;
                        o.name = movers[k].name;
                        o.shape = movers[k].shape;
                        // Each picture shows the movers where they were at the frame's time (as sensed), a still of the
                        // episode.
                        o.pose = k < f.poses.size() ? f.poses[k] : validity::Scene::poseAt(movers[k].trajectory, 0.);
                        scene->add(o);
                    }
                    std::ostringstream name;
                    name << "frame_" << std::setw(2) << std::setfill('0') << n++ << ".svg";
                    std::ostringstream label;
                    label << std::fixed << std::setprecision(1) << "t = " << f.time << " s: executed";
                    std::vector<PlotPath> paths{PlotPath{label.str(), f.executed}};
                    if (f.plan.size() > 1)
                        paths.push_back(PlotPath{"current plan", f.plan});
                    PictureOverride still;
                    still.scene = scene;
                    writeProblemSvg(problem, paths, (stage.path("episode") / name.str()).string(), 0, still);
                }
            }

            void writeEpisodeReplay(const std::string &file, const Problem &problem,
                                    const std::vector<validity::Obstacle> &statics, const std::vector<Mover> &movers,
                                    const std::vector<std::string> &labels, const std::vector<Trace> &traces)
            {
                if (traces.empty() || traces.size() != labels.size())
                    throw std::logic_error("replan replay: one trace per method expected");
                // every few simulation steps a frame: about this many over the longest episode (the page blends
                // linearly between frames; an executed step is short, so a few steps blend as they moved)
                constexpr std::size_t FRAMES = 500;
                std::size_t longest = 0;
                for (std::size_t i = 0; i < traces.size(); ++i)
                    if (traces[i].times.size() > traces[longest].times.size())
                        longest = i;
                const std::size_t steps = traces[longest].times.size();
                if (steps == 0)
                    throw std::logic_error("replan replay: an empty trace");
                const std::size_t every = std::max<std::size_t>(1, (steps - 1 + FRAMES - 1) / FRAMES);
                const auto sampled = [every](std::size_t n)
                {
                    std::vector<std::size_t> at;
                    for (std::size_t i = 0; i < n; i += every)
                        at.push_back(i);
                    // The last step is always kept: the page must end where the episode ended (goal reached or time
                    // up).
                    if (n > 0 && at.back() != n - 1)
                        at.push_back(n - 1);
                    return at;
                };

                std::vector<PlotPath> paths;
                ReplayOptions replay;
                for (std::size_t m = 0; m < traces.size(); ++m)
                {
                    const Trace &trace = traces[m];
                    std::ostringstream label;
                    label << std::fixed << std::setprecision(2) << labels[m] << ": "
                          << (trace.reached ? "reached the goal at " : "not at the goal by ") << trace.times.back()
                          << " s" << (trace.collided ? ", collided" : "");
                    PlotPath path{label.str(), {}};
                    std::vector<double> times;
                    for (std::size_t i : sampled(trace.times.size()))
                    {
                        path.states.push_back(trace.states[i]);
                        times.push_back(trace.times[i]);
                    }
                    paths.push_back(path);
                    replay.times.push_back(times);
                }

                // the moving obstacles where the first method's simulation had them, as key frames at the frames'
                // times (after its episode: its obstacle motions as they were at its end)
                const Trace &first = traces.front();
                auto scene = std::make_shared<validity::Scene>();
                for (const auto &o : statics)
                    scene->add(o);
                const auto at = sampled(steps);
                for (std::size_t k = 0; k < movers.size(); ++k)
                {
                    validity::Obstacle o;
                    o.name = movers[k].name;
                    o.shape = movers[k].shape;
                    for (std::size_t i : at)
                    {
                        const double t = traces[longest].times[i];
                        o.trajectory.push_back(validity::TimedPose{
                            t, i < first.poses.size() ? first.poses[i][k]
                                                      : validity::Scene::poseAt(first.trajectories[k], t)});
                    }
                    o.pose = o.trajectory.front().pose;
                    scene->add(o);
                }
                replay.scene = scene;
                writeReplayPage(problem, paths, file, replay);
            }
        }  // namespace replan
    }      // namespace tools
}  // namespace michi
