#ifndef MICHI_VALIDITY_FCL_VALIDITY_CHECKER_
#define MICHI_VALIDITY_FCL_VALIDITY_CHECKER_

#include <michi/validity/robot/CollisionBodies.h>
#include <michi/validity/scene/Scene.h>

#include <ompl/base/StateValidityChecker.h>

#include <atomic>
#include <limits>
#include <memory>
#include <string>

namespace michi
{
    namespace validity
    {
        /** \brief The nearest pair of points between the robot and the scene (or itself). */
        struct Proximity
        {
            double distance{std::numeric_limits<double>::infinity()};  ///< < 0 or 0 when in collision
            int body{-1};                                              ///< robot body index
            int otherBody{-1};                                         ///< self pair: the other body, else -1
            std::string obstacle;                                      ///< scene obstacle name, empty for self
            Eigen::Vector3d robotPoint{Eigen::Vector3d::Zero()};       ///< P on the robot, world frame
            Eigen::Vector3d otherPoint{Eigen::Vector3d::Zero()};       ///< Q on the obstacle, world frame
        };

        /** \brief Collision checking of a robot against a scene and itself with FCL. isValid() is a boolean
            collision query; clearance() is FCL's exact distance to the nearest obstacle (self distance is not
            included). Safe to call from several threads at once: every query takes its own set of the robot's FCL
            objects from a pool (built once, only posed per query) and holds the scene's shared lock. States are read
           through StateSpace::copyToReals, so any space whose reals are the bodies' configuration works (joint spaces,
           SE2). */
        class FclValidityChecker : public ompl::base::StateValidityChecker
        {
        public:
            FclValidityChecker(const ompl::base::SpaceInformationPtr &si, CollisionBodiesPtr bodies, ScenePtr scene);
            ~FclValidityChecker() override;

            bool isValid(const ompl::base::State *state) const override;
            /** \brief Validity and clearance in one query. */
            bool isValid(const ompl::base::State *state, double &dist) const override;
            double clearance(const ompl::base::State *state) const override;

            /** \brief Same queries on a raw configuration (bodies()->dimension() values). */
            bool isValidConfiguration(const double *values) const;
            /** \brief Distance to the nearest obstacle; <= 0 in collision. */
            double clearanceConfiguration(const double *values) const;
            /** \brief Nearest robot/scene pair, and self pairs when \e includeSelf. With \e relativeError r > 0
                FCL may stop early: the returned distance d is an upper bound and d / (1 + r) a lower bound of the
                true one (cheaper for meshes). */
            Proximity proximity(const double *values, bool includeSelf = false, double relativeError = 0.) const;
            /** \brief Distance of each body to the scene (\e obstacle, one per body) and of each self-check pair
                (\e self, in selfCheckPairs() order). Entries whose flag in \e wantBodies / \e wantPairs is 0 are
                skipped and set to +inf (so a body that does not move costs nothing). */
            void bodyDistances(const double *values, const std::vector<char> &wantBodies,
                               const std::vector<char> &wantPairs, std::vector<double> &obstacle,
                               std::vector<double> &self) const;
            /** \brief Do the two bodies of self-check pair \e pair (selfCheckPairs() order) touch? A boolean FCL
                query on their real geometry, cheaper than a distance. */
            bool pairCollides(const double *values, std::size_t pair) const;
            /** \brief Does body \e body (bodies() order) touch the scene? A boolean FCL query of that body only. */
            bool bodyCollides(const double *values, std::size_t body) const;
            /** \brief "link3 touches obstacle 'wall'" or "link1 touches link4"; empty when valid. */
            std::string describeCollision(const double *values) const;

            const CollisionBodiesPtr &bodies() const
            {
                return bodies_;
            }
            const ScenePtr &scene() const
            {
                return scene_;
            }
            /** \brief Number of collision queries answered so far (all threads). */
            std::uint64_t queryCount() const;

        private:
            class ObjectPool;
            void toReals(const ompl::base::State *state, std::vector<double> &values) const;
            CollisionBodiesPtr bodies_;
            ScenePtr scene_;
            std::unique_ptr<ObjectPool> pool_;  ///< FCL objects of the bodies, one set per concurrent query
        };

        using FclValidityCheckerPtr = std::shared_ptr<FclValidityChecker>;
    }  // namespace validity
}  // namespace michi

#endif
