#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/fcl/FclContact.h>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <ompl/base/SpaceInformation.h>

#include <cmath>
#include <array>
#include <atomic>
#include <sstream>

namespace michi
{
    namespace validity
    {
        namespace
        {
            /** OMPL's satisfiesBounds() lets a NaN through (every comparison with it is false), and FCL took a NaN
                pose for free (test NonFiniteStates.AreInvalidForEveryChecker): such a state is refused before the
                geometry. */
            bool allFinite(const double *values, std::size_t n)
            {
                for (std::size_t i = 0; i < n; ++i)
                    if (!std::isfinite(values[i]))
                        return false;
                return true;
            }

            struct CollisionData
            {
                const fcl::CollisionObjectd *query{nullptr};
                const std::string *hit{nullptr};
                bool done{false};
            };

            bool collisionCallback(fcl::CollisionObjectd *o1, fcl::CollisionObjectd *o2, void *raw)
            {
                auto *data = static_cast<CollisionData *>(raw);
                // The broad phase calls back until a call returns true; one contact answers a validity query.
                if (data->done)
                    return true;
                if (objectsTouch(o1, o2))
                {
                    data->done = true;
                    // The manager may pass the query object as either argument: the obstacle is the other one.
                    data->hit = &Scene::obstacleName(o1 == data->query ? o2 : o1);
                }
                return data->done;
            }

            struct DistanceData
            {
                fcl::DistanceRequestd request;
                const fcl::CollisionObjectd *query{nullptr};
                double best{std::numeric_limits<double>::infinity()};
                const std::string *obstacle{nullptr};
                Eigen::Vector3d robotPoint{Eigen::Vector3d::Zero()};
                Eigen::Vector3d otherPoint{Eigen::Vector3d::Zero()};
            };

            bool distanceCallback(fcl::CollisionObjectd *o1, fcl::CollisionObjectd *o2, void *raw, double &dist)
            {
                auto *data = static_cast<DistanceData *>(raw);
                fcl::DistanceResultd result;
                fcl::distance(o1, o2, data->request, result);
                if (result.min_distance < data->best)
                {
                    const bool queryFirst = o1 == data->query;
                    data->best = result.min_distance;
                    data->obstacle = &Scene::obstacleName(queryFirst ? o2 : o1);
                    data->robotPoint = result.nearest_points[queryFirst ? 0 : 1];
                    data->otherPoint = result.nearest_points[queryFirst ? 1 : 0];
                }
                // Reporting the best distance so far lets the broad phase skip every obstacle whose bounding box is
                // farther away.
                dist = data->best;
                // In contact (or penetrating): no nearer obstacle can change the answer, so the broad phase may stop.
                return data->best <= 0.;
            }

            /** FCL objects of every body shape (made once: FCL's constructor computes the local bounding box over
                every mesh vertex, which used to be most of a check's time), posed for one configuration. */
            struct BodyObjects
            {
                std::vector<std::vector<std::unique_ptr<fcl::CollisionObjectd>>> objects;
                std::vector<std::vector<Eigen::Isometry3d>> origins;  ///< shape origin in the body frame
                std::vector<Eigen::Isometry3d> poses;

                explicit BodyObjects(const CollisionBodies &bodies)
                {
                    const auto &all = bodies.bodies();
                    objects.resize(all.size());
                    origins.resize(all.size());
                    for (std::size_t b = 0; b < all.size(); ++b)
                        for (const auto &s : all[b].shapes)
                            for (const auto &g : s.shape->geometries())
                            {
                                objects[b].push_back(std::make_unique<fcl::CollisionObjectd>(g));
                                origins[b].push_back(s.origin);
                            }
                }

                void pose(const CollisionBodies &bodies, const double *values)
                {
                    bodies.bodyPoses(values, poses);
                    for (std::size_t b = 0; b < poses.size(); ++b)
                        for (std::size_t k = 0; k < objects[b].size(); ++k)
                        {
                            // World pose of the shape = body pose in the world times the shape's fixed origin in the
                            // body frame.
                            objects[b][k]->setTransform(poses[b] * origins[b][k]);
                            // setTransform() does not move the world bounding box, and the scene's broad phase only
                            // looks at that box: without this the query would test the previous configuration's box.
                            objects[b][k]->computeAABB();
                        }
                }
            };
        }  // namespace

        /** Body objects for one query at a time, kept per thread. A thread takes the set of its own slot (or, when
            that is empty, another slot's, or makes one) and puts it back there, so two threads checking at once never
            share a set, and each keeps working on the objects its own core last wrote. The pool this replaces kept
            the sets behind one mutex (the last one returned went to whichever thread came next) and counted queries
            in one shared atomic: on the xArm6, where a check takes about 2 us, two threads checked 1.06 times as
            many states per second as one, with the counter's locked add and the mutex among the hottest
            instructions; now 1.7 times (tests/micro/bench_validity isValidThreads, docs/checking.md). */
        class FclValidityChecker::ObjectPool
        {
            static constexpr std::size_t SLOTS = 16;
            /** A cache line each: the owning thread's exchanges and counts do not disturb the other slots. */
            struct alignas(64) Slot
            {
                std::atomic<BodyObjects *> objects{nullptr};
                std::atomic<std::uint64_t> queries{0};
            };

        public:
            explicit ObjectPool(const CollisionBodies &bodies) : bodies_(bodies)
            {
            }
            ~ObjectPool()
            {
                for (auto &slot : slots_)
                    delete slot.objects.load();
            }

            /** The posed objects of one query; put back into the pool on destruction. */
            class Lease
            {
            public:
                Lease(ObjectPool &pool, BodyObjects *objects, std::size_t slot)
                    : pool_(pool), objects_(objects), slot_(slot)
                {
                }
                Lease(const Lease &) = delete;
                Lease &operator=(const Lease &) = delete;
                ~Lease()
                {
                    pool_.release(objects_, slot_);
                }
                const std::vector<std::vector<std::unique_ptr<fcl::CollisionObjectd>>> &objects() const
                {
                    return objects_->objects;
                }

            private:
                ObjectPool &pool_;
                BodyObjects *objects_;
                std::size_t slot_;
            };

            /** \e count: a collision query (counted in queryCount()), not a distance query. */
            Lease acquire(const double *values, bool count)
            {
                const std::size_t home = threadSlot();
                if (count)
                    // relaxed: a statistic, read only after the queries it counts
                    slots_[home].queries.fetch_add(1, std::memory_order_relaxed);
                BodyObjects *objects = slots_[home].objects.exchange(nullptr, std::memory_order_acquire);
                // the own slot is empty at a thread's first query, or when a thread with the same slot is querying:
                // take a set another slot keeps before making one (FCL's constructors are the slow part)
                for (std::size_t k = 1; objects == nullptr && k < SLOTS; ++k)
                    objects = slots_[(home + k) % SLOTS].objects.exchange(nullptr, std::memory_order_acquire);
                if (objects == nullptr)
                    objects = new BodyObjects(bodies_);
                try
                {
                    objects->pose(bodies_, values);
                }
                catch (...)
                {
                    release(objects, home);
                    throw;
                }
                return Lease(*this, objects, home);
            }

            std::uint64_t queries() const
            {
                std::uint64_t n = 0;
                for (const auto &slot : slots_)
                    n += slot.queries.load(std::memory_order_relaxed);
                return n;
            }

        private:
            void release(BodyObjects *objects, std::size_t slot)
            {
                BodyObjects *empty = nullptr;
                if (slots_[slot].objects.compare_exchange_strong(empty, objects, std::memory_order_release))
                    return;
                // another thread of this slot put its set back first: keep this one in any empty slot, else drop it
                for (std::size_t k = 1; k < SLOTS; ++k)
                {
                    empty = nullptr;
                    if (slots_[(slot + k) % SLOTS].objects.compare_exchange_strong(empty, objects,
                                                                                   std::memory_order_release))
                        return;
                }
                delete objects;
            }
            /** Threads get slots in the order they first query (any checker): distinct for up to SLOTS threads. */
            static std::size_t threadSlot()
            {
                static std::atomic<std::size_t> next{0};
                thread_local const std::size_t slot = next.fetch_add(1, std::memory_order_relaxed) % SLOTS;
                return slot;
            }
            const CollisionBodies &bodies_;
            std::array<Slot, SLOTS> slots_;
        };

        FclValidityChecker::~FclValidityChecker() = default;

        std::uint64_t FclValidityChecker::queryCount() const
        {
            return pool_->queries();
        }

        FclValidityChecker::FclValidityChecker(const ompl::base::SpaceInformationPtr &si, CollisionBodiesPtr bodies,
                                               ScenePtr scene)
            : ompl::base::StateValidityChecker(si), bodies_(std::move(bodies)), scene_(std::move(scene))
        {
            pool_ = std::make_unique<ObjectPool>(*bodies_);
            // EXACT: clearance() is FCL's distance to the nearest obstacle, not an estimate or a bound.
            specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::EXACT;
            if (si->getStateSpace()->getDimension() != bodies_->dimension())
                throw std::invalid_argument(
                    "state space has dimension " + std::to_string(si->getStateSpace()->getDimension()) +
                    ", the robot's configuration has " + std::to_string(bodies_->dimension()) + " values");
        }

        void FclValidityChecker::toReals(const ompl::base::State *state, std::vector<double> &values) const
        {
            si_->getStateSpace()->copyToReals(values, state);
        }

        bool FclValidityChecker::isValid(const ompl::base::State *state) const
        {
            // OMPL's convention: a state outside the bounds is invalid whatever the geometry (and costs no kinematics).
            if (!si_->satisfiesBounds(state))
                return false;
            std::vector<double> values;
            toReals(state, values);
            return isValidConfiguration(values.data());
        }

        bool FclValidityChecker::isValid(const ompl::base::State *state, double &dist) const
        {
            std::vector<double> values;
            toReals(state, values);
            if (!si_->satisfiesBounds(state) || !isValidConfiguration(values.data()))
            {
                dist = 0.;
                return false;
            }
            dist = clearanceConfiguration(values.data());
            return true;
        }

        double FclValidityChecker::clearance(const ompl::base::State *state) const
        {
            std::vector<double> values;
            toReals(state, values);
            return clearanceConfiguration(values.data());
        }

        bool FclValidityChecker::isValidConfiguration(const double *values) const
        {
            // here rather than in isValid(state): the J-map checker's fallback and other callers pass raw values
            return allFinite(values, bodies_->dimension()) && describeCollision(values).empty();
        }

        std::string FclValidityChecker::describeCollision(const double *values) const
        {
            const auto lease = pool_->acquire(values, true);
            const auto &objects = lease.objects();
            const auto &bodies = bodies_->bodies();
            {
                // Shared lock only while the scene is read: a thread moving an obstacle takes it exclusively, so a
                // query never sees half of a move. The self pairs below read no scene, so they run after the lock is
                // released.
                auto lock = scene_->lockShared();
                for (std::size_t b = 0; b < objects.size(); ++b)
                    for (const auto &object : objects[b])
                    {
                        CollisionData data;
                        data.query = object.get();
                        scene_->manager().collide(object.get(), &data, collisionCallback);
                        if (data.done)
                            return bodies[b].name + " touches obstacle '" + *data.hit + "'";
                    }
            }
            for (const auto &pair : bodies_->selfCheckPairs())
                for (const auto &a : objects[pair.first])
                    for (const auto &b : objects[pair.second])
                    {
                        if (objectsTouch(a.get(), b.get()))
                            return bodies[pair.first].name + " touches " + bodies[pair.second].name;
                    }
            return "";
        }

        bool FclValidityChecker::pairCollides(const double *values, std::size_t pair) const
        {
            const auto lease = pool_->acquire(values, true);
            const auto &objects = lease.objects();
            const auto &p = bodies_->selfCheckPairs().at(pair);
            for (const auto &a : objects[p.first])
                for (const auto &b : objects[p.second])
                {
                    if (objectsTouch(a.get(), b.get()))
                        return true;
                }
            return false;
        }

        bool FclValidityChecker::bodyCollides(const double *values, std::size_t body) const
        {
            const auto lease = pool_->acquire(values, true);
            auto lock = scene_->lockShared();
            for (const auto &object : lease.objects().at(body))
            {
                CollisionData data;
                data.query = object.get();
                scene_->manager().collide(object.get(), &data, collisionCallback);
                if (data.done)
                    return true;
            }
            return false;
        }

        double FclValidityChecker::clearanceConfiguration(const double *values) const
        {
            return proximity(values, false).distance;
        }

        Proximity FclValidityChecker::proximity(const double *values, bool includeSelf, double relativeError) const
        {
            const auto lease = pool_->acquire(values, false);
            const auto &objects = lease.objects();
            Proximity best;
            {
                auto lock = scene_->lockShared();
                for (std::size_t b = 0; b < objects.size(); ++b)
                    for (const auto &object : objects[b])
                    {
                        DistanceData data;
                        data.request.enable_nearest_points = true;
                        data.request.rel_err = relativeError;
                        data.request.gjk_solver_type = fcl::GST_INDEP;
                        data.query = object.get();
                        // Seeded with the best distance over the previous bodies, so the broad phase of each body
                        // prunes against the nearest obstacle found so far, not from infinity.
                        data.best = best.distance;
                        scene_->manager().distance(object.get(), &data, distanceCallback);
                        // obstacle stays null when no obstacle of this body beat the seed: nothing new to record.
                        if (data.obstacle != nullptr && data.best < best.distance)
                        {
                            best.distance = data.best;
                            best.body = static_cast<int>(b);
                            best.otherBody = -1;
                            best.obstacle = *data.obstacle;
                            best.robotPoint = data.robotPoint;
                            best.otherPoint = data.otherPoint;
                        }
                    }
            }
            // Self-distance stays out of clearance(): OMPL's clearance is about the environment (foundation.md).
            if (includeSelf)
                for (const auto &pair : bodies_->selfCheckPairs())
                    for (const auto &a : objects[pair.first])
                        for (const auto &b : objects[pair.second])
                        {
                            fcl::DistanceRequestd request;
                            request.enable_nearest_points = true;
                            request.rel_err = relativeError;
                            request.gjk_solver_type = fcl::GST_INDEP;
                            fcl::DistanceResultd result;
                            fcl::distance(a.get(), b.get(), request, result);
                            if (result.min_distance < best.distance)
                            {
                                best.distance = result.min_distance;
                                best.body = pair.first;
                                best.otherBody = pair.second;
                                best.obstacle.clear();
                                best.robotPoint = result.nearest_points[0];
                                best.otherPoint = result.nearest_points[1];
                            }
                        }
            return best;
        }

        void FclValidityChecker::bodyDistances(const double *values, const std::vector<char> &wantBodies,
                                               const std::vector<char> &wantPairs, std::vector<double> &obstacle,
                                               std::vector<double> &self) const
        {
            const double inf = std::numeric_limits<double>::infinity();
            const auto lease = pool_->acquire(values, false);
            const auto &objects = lease.objects();
            // Skipped bodies and pairs read +inf: an entry that was not computed must never look like a near obstacle
            // to a caller that takes a minimum.
            obstacle.assign(objects.size(), inf);
            {
                auto lock = scene_->lockShared();
                for (std::size_t b = 0; b < objects.size(); ++b)
                {
                    if (!wantBodies[b])
                        continue;
                    for (const auto &object : objects[b])
                    {
                        DistanceData data;
                        data.request.gjk_solver_type = fcl::GST_INDEP;
                        data.query = object.get();
                        // Every shape of the body shares one running minimum, so later shapes prune against the nearest
                        // obstacle of the earlier ones.
                        data.best = obstacle[b];
                        scene_->manager().distance(object.get(), &data, distanceCallback);
                        obstacle[b] = std::min(obstacle[b], data.best);
                    }
                }
            }
            const auto &pairs = bodies_->selfCheckPairs();
            self.assign(pairs.size(), inf);
            for (std::size_t k = 0; k < pairs.size(); ++k)
            {
                if (!wantPairs[k])
                    continue;
                for (const auto &a : objects[pairs[k].first])
                    for (const auto &b : objects[pairs[k].second])
                    {
                        fcl::DistanceRequestd request;
                        request.gjk_solver_type = fcl::GST_INDEP;
                        fcl::DistanceResultd result;
                        fcl::distance(a.get(), b.get(), request, result);
                        self[k] = std::min(self[k], result.min_distance);
                    }
            }
        }
    }  // namespace validity
}  // namespace michi
