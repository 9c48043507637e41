#ifndef MICHI_VALIDITY_SCENE_
#define MICHI_VALIDITY_SCENE_

#include <michi/validity/scene/Polygon2.h>
#include <michi/validity/scene/Shape.h>

#include <Eigen/Geometry>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>

#include <atomic>
#include <memory>
#include <shared_mutex>
#include <string>
#include <functional>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief A pose at a time, a key frame of a moving obstacle. */
        struct TimedPose
        {
            double time{0.};
            Eigen::Isometry3d pose{Eigen::Isometry3d::Identity()};
        };

        struct Obstacle
        {
            std::string name;
            ShapePtr shape;
            Eigen::Isometry3d pose{Eigen::Isometry3d::Identity()};
            /** \brief Key frames, sorted by time; empty for a static obstacle. Between key frames the position is
                interpolated linearly and the orientation by slerp; outside them the pose is held. */
            std::vector<TimedPose> trajectory;
        };

        /** \brief The world the robot moves in: obstacles with poses, some of them moving over time, in an FCL
            broad-phase structure. Every change increments changeCount() so checkers and caches know. Queries
            take a shared lock (any number of threads), changes take an exclusive one. */
        class Scene
        {
        public:
            Scene();
            Scene(const Scene &) = delete;
            Scene &operator=(const Scene &) = delete;

            /** \brief Add an obstacle; its name must be unique (std::invalid_argument otherwise). */
            void add(Obstacle obstacle);
            /** \brief Add many obstacles with one broad-phase build (loading stays linear in their number). All are
                checked first (shape, finite poses within MAX_COORDINATE, unique names); on an error none is added. */
            void add(std::vector<Obstacle> obstacles);
            /** \brief Remove an obstacle by name; false when there is none. */
            bool remove(const std::string &name);
            /** \brief Move a (static) obstacle; throws std::out_of_range for an unknown name. */
            void setPose(const std::string &name, const Eigen::Isometry3d &pose);
            /** \brief Move several obstacles at once: one refit of the broad phase and one change for all of them
                (the copies of a prediction move together). Obstacles already at their pose are left alone, and when
                none moves the scene does not count a change. Throws std::out_of_range for an unknown name, before
                anything moves. */
            void setPoses(const std::vector<std::pair<std::string, Eigen::Isometry3d>> &poses);
            /** \brief Put every moving obstacle where its trajectory says it is at time \e t. */
            void setTime(double t);
            double time() const;

            std::size_t size() const;
            /** \brief A copy of the obstacles (a snapshot; safe while others change the scene). */
            std::vector<Obstacle> obstacles() const;
            /** \brief Call \e visit for every obstacle, in order, under the scene's shared lock: a look without the
                copy obstacles() makes (\e visit must not change the scene). */
            void forEachObstacle(const std::function<void(const Obstacle &)> &visit) const;
            /** \brief Incremented by every change (add, remove, setPose, setTime that moves something). */
            std::uint64_t changeCount() const
            {
                return changeCount_.load();
            }

            /** \brief Metres per cell of the occupancy grid (PGM, MovingAI or ROS map) the static obstacles were read
                from; 0 when they were not read from one. Gaps in such a scene are whole cells wide, so a planner
                that lays its own lattice over the scene can size it by this (HeadingLattice's automatic cell size). */
            double gridCellSize() const
            {
                return gridCellSize_;
            }
            /** \brief Set by the loader of a map (not a change of the obstacles: changeCount() stays). */
            void setGridCellSize(double metres)
            {
                gridCellSize_ = metres;
            }

            /** \brief The obstacles' shadows on the x-y plane, united (for 2-D methods and pictures). */
            MultiPolygon2 polygons2d() const;
            /** \brief Axis-aligned bounds of all obstacles (min, max); zero box when empty. */
            std::pair<Eigen::Vector3d, Eigen::Vector3d> bounds() const;

            /** \brief Pose of a trajectory at time \e t (interpolated). */
            static Eigen::Isometry3d poseAt(const std::vector<TimedPose> &trajectory, double t);

            /** \brief Shared lock for the duration of a query against manager(). */
            std::shared_lock<std::shared_mutex> lockShared() const
            {
                return std::shared_lock<std::shared_mutex>(mutex_);
            }
            /** \brief The broad-phase structure; only use it under lockShared(). */
            const fcl::DynamicAABBTreeCollisionManagerd &manager() const
            {
                return manager_;
            }
            /** \brief Name of the obstacle an FCL object of manager() belongs to. */
            static const std::string &obstacleName(const fcl::CollisionObjectd *object);

        private:
            struct Entry
            {
                Obstacle obstacle;
                std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
            };
            void place(Entry &entry, const Eigen::Isometry3d &pose);
            void rebuildManager();
            mutable std::shared_mutex mutex_;
            std::vector<std::unique_ptr<Entry>> entries_;
            fcl::DynamicAABBTreeCollisionManagerd manager_;
            std::atomic<std::uint64_t> changeCount_{0};
            double time_{0.};
            double gridCellSize_{0.};
        };

        using ScenePtr = std::shared_ptr<Scene>;

        /** \brief Obstacles from an occupancy image (binary or ASCII PGM): cells darker than \e threshold
            (0..1 of the maximum grey value) are occupied; each row's runs of occupied cells become one box.
            \e resolution is metres per cell, \e origin the world position of the lower-left corner of the image.
            Throws std::runtime_error naming the file when it cannot be read. */
        std::vector<Obstacle> occupancyObstacles(const std::string &pgmPath, double resolution,
                                                 const Eigen::Vector2d &origin, double height = 1.,
                                                 double threshold = 0.5);
    }  // namespace validity
}  // namespace michi

#endif
