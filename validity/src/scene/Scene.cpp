#include <michi/validity/scene/Scene.h>
#include <michi/validity/Limits.h>

#include <algorithm>
#include <mutex>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

namespace bg = boost::geometry;

namespace michi
{
    namespace validity
    {
        Scene::Scene() = default;

        void Scene::place(Entry &entry, const Eigen::Isometry3d &pose)
        {
            entry.obstacle.pose = pose;
            for (auto &object : entry.objects)
            {
                object->setTransform(pose);
                // The broad phase sorts objects by their world bounding box, which setTransform() alone leaves at the
                // old pose.
                object->computeAABB();
            }
        }

        void Scene::rebuildManager()
        {
            manager_.clear();
            std::vector<fcl::CollisionObjectd *> objects;
            for (auto &entry : entries_)
                for (auto &object : entry->objects)
                    objects.push_back(object.get());
            manager_.registerObjects(objects);
            manager_.setup();
        }

        void Scene::add(Obstacle obstacle)
        {
            std::vector<Obstacle> one;
            one.push_back(std::move(obstacle));
            add(std::move(one));
        }

        void Scene::add(std::vector<Obstacle> obstacles)
        {
            // everything is checked before anything changes, so a bad obstacle leaves the scene as it was
            std::unordered_set<std::string> newNames;
            for (auto &obstacle : obstacles)
            {
                if (!obstacle.shape)
                    throw std::invalid_argument("obstacle '" + obstacle.name + "' has no shape");
                // FCL's broad phase crashes on boxes that overflow (coordinates near sqrt(DBL_MAX)) and ignores nan
                requireGeometryPose(obstacle.pose, "obstacle '" + obstacle.name + "'");
                for (const auto &key : obstacle.trajectory)
                {
                    if (!std::isfinite(key.time))
                        throw std::invalid_argument("obstacle '" + obstacle.name + "': key frame time is not finite");
                    requireGeometryPose(key.pose, "obstacle '" + obstacle.name + "' key frame");
                }
                if (!newNames.insert(obstacle.name).second)
                    throw std::invalid_argument("scene already has an obstacle named '" + obstacle.name + "'");
                // Files may list key frames in any order; poseAt() finds the bracketing pair by binary search, which
                // needs them sorted.
                std::sort(obstacle.trajectory.begin(), obstacle.trajectory.end(),
                          [](const TimedPose &a, const TimedPose &b)
                          {
                              return a.time < b.time;
                          });
            }
            // Names already in the scene are checked under the exclusive lock, so two threads adding the same name
            // cannot both pass.
            std::unique_lock<std::shared_mutex> lock(mutex_);
            for (const auto &e : entries_)
                if (newNames.count(e->obstacle.name))
                    throw std::invalid_argument("scene already has an obstacle named '" + e->obstacle.name + "'");
            for (auto &obstacle : obstacles)
            {
                auto entry = std::make_unique<Entry>();
                entry->obstacle = std::move(obstacle);
                for (const auto &g : entry->obstacle.shape->geometries())
                {
                    entry->objects.push_back(std::make_unique<fcl::CollisionObjectd>(g));
                    // Collision callbacks get FCL objects only; the user data names the obstacle (obstacleName()). The
                    // pointer stays valid because each Entry lives behind a unique_ptr and does not move when entries_
                    // grows.
                    entry->objects.back()->setUserData(&entry->obstacle.name);
                }
                // A moving obstacle starts where its trajectory is at the scene's current time, not at its static pose.
                const Eigen::Isometry3d pose = entry->obstacle.trajectory.empty()
                                                   ? entry->obstacle.pose
                                                   : poseAt(entry->obstacle.trajectory, time_);
                place(*entry, pose);
                entries_.push_back(std::move(entry));
            }
            // one broad-phase build for the whole batch: rebuilding per obstacle made loading a 10,000-box map
            // quadratic (28 s)
            rebuildManager();
            ++changeCount_;
        }

        bool Scene::remove(const std::string &name)
        {
            std::unique_lock<std::shared_mutex> lock(mutex_);
            auto it = std::find_if(entries_.begin(), entries_.end(),
                                   [&](const std::unique_ptr<Entry> &e)
                                   {
                                       return e->obstacle.name == name;
                                   });
            if (it == entries_.end())
                return false;
            entries_.erase(it);
            rebuildManager();
            ++changeCount_;
            return true;
        }

        void Scene::setPose(const std::string &name, const Eigen::Isometry3d &pose)
        {
            std::unique_lock<std::shared_mutex> lock(mutex_);
            for (auto &e : entries_)
                if (e->obstacle.name == name)
                {
                    place(*e, pose);
                    // Refits the broad-phase tree to the moved boxes, cheaper than the full rebuild that add() and
                    // remove() do.
                    manager_.update();
                    ++changeCount_;
                    return;
                }
            throw std::out_of_range("scene has no obstacle named '" + name + "'");
        }

        void Scene::setPoses(const std::vector<std::pair<std::string, Eigen::Isometry3d>> &poses)
        {
            std::unique_lock<std::shared_mutex> lock(mutex_);
            // names first: an unknown one leaves the scene as it was
            std::vector<Entry *> targets;
            targets.reserve(poses.size());
            for (const auto &p : poses)
            {
                const auto it = std::find_if(entries_.begin(), entries_.end(),
                                             [&](const auto &e)
                                             {
                                                 return e->obstacle.name == p.first;
                                             });
                if (it == entries_.end())
                    throw std::out_of_range("scene has no obstacle named '" + p.first + "'");
                targets.push_back(it->get());
            }
            bool moved = false;
            for (std::size_t i = 0; i < poses.size(); ++i)
                // exact comparison: a pose that differs in any bit is a move (the caches that watch changeCount()
                // must not keep a proof made for the old one)
                if (!targets[i]->obstacle.pose.matrix().cwiseEqual(poses[i].second.matrix()).all())
                {
                    place(*targets[i], poses[i].second);
                    moved = true;
                }
            if (!moved)
                return;
            // one refit for the lot: setPose() per copy refitted the whole tree every time
            manager_.update();
            ++changeCount_;
        }

        void Scene::setTime(double t)
        {
            std::unique_lock<std::shared_mutex> lock(mutex_);
            time_ = t;
            bool moved = false;
            for (auto &e : entries_)
            {
                if (e->obstacle.trajectory.empty())
                    continue;
                const Eigen::Isometry3d pose = poseAt(e->obstacle.trajectory, t);
                // Before its first and after its last key frame an obstacle holds still: not counting that as a change
                // spares every cache that watches changeCount() a rebuild.
                if (!pose.isApprox(e->obstacle.pose, 1e-12))
                {
                    place(*e, pose);
                    moved = true;
                }
            }
            if (moved)
            {
                manager_.update();
                ++changeCount_;
            }
        }

        double Scene::time() const
        {
            std::shared_lock<std::shared_mutex> lock(mutex_);
            return time_;
        }

        std::size_t Scene::size() const
        {
            std::shared_lock<std::shared_mutex> lock(mutex_);
            return entries_.size();
        }

        void Scene::forEachObstacle(const std::function<void(const Obstacle &)> &visit) const
        {
            std::shared_lock<std::shared_mutex> lock(mutex_);
            for (const auto &e : entries_)
                visit(e->obstacle);
        }

        std::vector<Obstacle> Scene::obstacles() const
        {
            std::shared_lock<std::shared_mutex> lock(mutex_);
            std::vector<Obstacle> result;
            for (const auto &e : entries_)
                result.push_back(e->obstacle);
            return result;
        }

        MultiPolygon2 Scene::polygons2d() const
        {
            // obstacles() copies under the shared lock; the union runs without holding it.
            std::vector<MultiPolygon2> parts;
            for (const auto &o : obstacles())
                parts.push_back(o.shape->footprint(o.pose));
            return uniteFootprints(std::move(parts));
        }

        std::pair<Eigen::Vector3d, Eigen::Vector3d> Scene::bounds() const
        {
            std::shared_lock<std::shared_mutex> lock(mutex_);
            if (entries_.empty())
                return {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
            Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
            Eigen::Vector3d hi = -lo;
            for (const auto &e : entries_)
                for (const auto &o : e->objects)
                {
                    // World-aligned boxes: the result encloses every obstacle, loosely for rotated ones.
                    lo = lo.cwiseMin(o->getAABB().min_);
                    hi = hi.cwiseMax(o->getAABB().max_);
                }
            return {lo, hi};
        }

        Eigen::Isometry3d Scene::poseAt(const std::vector<TimedPose> &trajectory, double t)
        {
            if (trajectory.empty())
                throw std::invalid_argument("empty trajectory");
            if (t <= trajectory.front().time)
                return trajectory.front().pose;
            if (t >= trajectory.back().time)
                return trajectory.back().pose;
            auto next = std::upper_bound(trajectory.begin(), trajectory.end(), t,
                                         [](double time, const TimedPose &p)
                                         {
                                             return time < p.time;
                                         });
            // upper_bound gives the first key frame after t, so prev->time <= t < next->time and the division below is
            // by a positive number even when two key frames share a time.
            auto prev = next - 1;
            const double s = (t - prev->time) / (next->time - prev->time);
            Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
            pose.translation() = (1. - s) * prev->pose.translation() + s * next->pose.translation();
            const Eigen::Quaterniond qa(prev->pose.linear()), qb(next->pose.linear());
            // Slerp, not a linear blend of matrices, so the orientation stays a rotation and turns at a constant rate.
            pose.linear() = qa.slerp(s, qb).toRotationMatrix();
            return pose;
        }

        const std::string &Scene::obstacleName(const fcl::CollisionObjectd *object)
        {
            return *static_cast<const std::string *>(object->getUserData());
        }
    }  // namespace validity
}  // namespace michi
