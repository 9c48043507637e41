#include "ReplanReport.h"

#include <michi/tools/pictures/SvgPlot.h>

#include <boost/filesystem.hpp>

#include <algorithm>
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
                chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
                int n = 0;
                for (std::size_t idx : chosen)
                {
                    const Frame &f = frames[idx];
                    Problem p = problem;
                    p.scene = std::make_shared<validity::Scene>();
                    for (const auto &o : statics)
                        p.scene->add(o);
                    for (std::size_t k = 0; k < movers.size(); ++k)
                    {
                        validity::Obstacle o;
                        o.name = movers[k].name;
                        o.shape = movers[k].shape;
                        o.pose = k < f.poses.size() ? f.poses[k] : validity::Scene::poseAt(movers[k].trajectory, 0.);
                        p.scene->add(o);
                    }
                    std::ostringstream name;
                    name << "frame_" << std::setw(2) << std::setfill('0') << n++ << ".svg";
                    std::ostringstream label;
                    label << std::fixed << std::setprecision(1) << "t = " << f.time << " s: executed";
                    std::vector<PlotPath> paths{PlotPath{label.str(), f.executed}};
                    if (f.plan.size() > 1)
                        paths.push_back(PlotPath{"current plan", f.plan});
                    writeProblemSvg(p, paths, (stage.path("episode") / name.str()).string());
                }
            }

        }  // namespace replan
    }      // namespace tools
}  // namespace michi
