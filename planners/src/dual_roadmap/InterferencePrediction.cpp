#include <michi/planners/dual_roadmap/InterferencePrediction.h>

#include <ompl/base/ScopedState.h>

#include <limits>
#include <stdexcept>

namespace michi
{
    namespace planners
    {
        PredictedObstacles::PredictedObstacles(validity::ScenePtr scene, int copies, double horizon)
            : scene_(std::move(scene)), copies_(copies), horizon_(horizon)
        {
            if (!scene_)
                throw std::invalid_argument("PredictedObstacles: no scene");
            if (copies_ < 1 || !(horizon_ >= 0.))
                throw std::invalid_argument("PredictedObstacles: copies must be >= 1 and the horizon >= 0");
        }

        std::string PredictedObstacles::copyName(const std::string &name, int copy)
        {
            // "~" marks a predicted copy: callers tell copies from real obstacles by it (michi replan's change region).
            return name + "~" + std::to_string(copy);
        }

        void PredictedObstacles::add(const std::string &name, validity::ShapePtr shape, const Eigen::Isometry3d &pose)
        {
            std::vector<validity::Obstacle> copies;
            for (int i = 0; i < copies_; ++i)
                copies.push_back(validity::Obstacle{copyName(name, i), shape, pose, {}});
            // All copies in one add(): the scene rebuilds its broad phase once, not once per copy.
            scene_->add(std::move(copies));
        }

        void PredictedObstacles::observe(const std::string &name, const Eigen::Isometry3d &pose,
                                         const Eigen::Vector3d &velocity)
        {
            observe(std::vector<std::string>{name}, std::vector<Eigen::Isometry3d>{pose},
                    std::vector<Eigen::Vector3d>{velocity});
        }

        void PredictedObstacles::observe(const std::vector<std::string> &names,
                                         const std::vector<Eigen::Isometry3d> &poses,
                                         const std::vector<Eigen::Vector3d> &velocities)
        {
            if (poses.size() != names.size() || velocities.size() != names.size())
                throw std::invalid_argument("PredictedObstacles::observe: names, poses and velocities differ in size");
            std::vector<std::pair<std::string, Eigen::Isometry3d>> moved;
            moved.reserve(names.size() * static_cast<std::size_t>(copies_));
            for (std::size_t k = 0; k < names.size(); ++k)
                for (int i = 0; i < copies_; ++i)
                {
                    // constant-velocity prediction: the copies sample the swept region evenly, the last one at the
                    // horizon, so a path that stays clear of all of them stays clear of the obstacle's likely way
                    Eigen::Isometry3d p = poses[k];
                    const double f = copies_ > 1 ? static_cast<double>(i) / (copies_ - 1) : 0.;
                    p.translation() += velocities[k] * horizon_ * f;
                    moved.emplace_back(copyName(names[k], i), p);
                }
            // One scene update for every copy of every obstacle: one broad-phase refit and one change, where a
            // setPose() per copy refitted the whole tree each time (30 refits per query in michi replan's
            // passage scenario, charged to every planner's latency).
            scene_->setPoses(moved);
        }

        double firstInterference(const ompl::base::SpaceInformationPtr &si, const ConfigurationPath &path,
                                 double lookahead)
        {
            const double inf = std::numeric_limits<double>::infinity();
            if (path.empty())
                return inf;
            const auto &space = si->getStateSpace();
            ompl::base::ScopedState<> a(si), b(si);
            auto load = [&](const Configuration &q, ompl::base::State *s)
            {
                space->copyFromReals(s, q);
                space->enforceBounds(s);  // wraps SO(2) values as the space keeps them
            };
            load(path[0], a.get());
            double arc = 0.;
            for (std::size_t i = 1; i < path.size() && arc < lookahead; ++i)
            {
                load(path[i], b.get());
                const double len = si->distance(a.get(), b.get());
                std::pair<ompl::base::State *, double> last(nullptr, 0.);
                if (!si->satisfiesBounds(b.get()) || !si->checkMotion(a.get(), b.get(), last))
                    return arc + last.second * len;  // the motion validator's last valid fraction of the segment
                arc += len;
                si->copyState(a.get(), b.get());
            }
            return inf;
        }
    }  // namespace planners
}  // namespace michi
