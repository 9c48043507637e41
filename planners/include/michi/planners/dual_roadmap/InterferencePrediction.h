#ifndef MICHI_PLANNERS_DUAL_ROADMAP_INTERFERENCE_PREDICTION_
#define MICHI_PLANNERS_DUAL_ROADMAP_INTERFERENCE_PREDICTION_

#include <michi/planners/dual_roadmap/NonStopExecutor.h>
#include <michi/validity/scene/Scene.h>

#include <ompl/base/SpaceInformation.h>

#include <Eigen/Geometry>

#include <string>

namespace michi
{
    namespace planners
    {
        /** \brief Paper 002's prediction of moving obstacles, for a user's own OMPL code: each moving obstacle is
            represented over a prediction horizon by \e copies of its (usually grown) shape, spread along its
            observed constant velocity, in a validity::Scene that the robot's checker reads. The executor's
            interference check (NonStopHooks::firstInterference) then asks firstInterference() on that scene.
            Copies are named "<name>~<i>"; copy 0 is at the observed pose, the last one where the obstacle will be
            after the horizon. */
        class PredictedObstacles
        {
        public:
            /** \e copies >= 1 (1: the observed pose only), \e horizon in seconds >= 0. */
            PredictedObstacles(validity::ScenePtr scene, int copies, double horizon);

            /** Add a moving obstacle (all its copies at \e pose). */
            void add(const std::string &name, validity::ShapePtr shape, const Eigen::Isometry3d &pose);

            /** A new observation: copy i goes to pose + velocity * horizon * i / (copies - 1). */
            void observe(const std::string &name, const Eigen::Isometry3d &pose, const Eigen::Vector3d &velocity);
            /** Observations of several obstacles at once (names[k] at poses[k], moving at velocities[k]): the scene
                changes once for all of them. Copies whose pose is unchanged are not moved. */
            void observe(const std::vector<std::string> &names, const std::vector<Eigen::Isometry3d> &poses,
                         const std::vector<Eigen::Vector3d> &velocities);

            const validity::ScenePtr &scene() const
            {
                return scene_;
            }
            int copies() const
            {
                return copies_;
            }
            double horizon() const
            {
                return horizon_;
            }

            static std::string copyName(const std::string &name, int copy);

        private:
            validity::ScenePtr scene_;
            int copies_;
            double horizon_;
        };

        /** \brief Arc length (the space's distance) along \e path, from its first state, to the first place where a
            motion of the path is invalid for \e si (its validity checker and motion validator, e.g. on a
            PredictedObstacles scene), looking no further than \e lookahead; infinity when the looked-at part is
            free. A state outside the bounds counts as an interference at its segment's start. */
        double firstInterference(const ompl::base::SpaceInformationPtr &si, const ConfigurationPath &path,
                                 double lookahead);
    }  // namespace planners
}  // namespace michi

#endif
