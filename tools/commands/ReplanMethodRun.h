#ifndef MICHI_TOOLS_SRC_REPLAN_METHOD_RUN_
#define MICHI_TOOLS_SRC_REPLAN_METHOD_RUN_

// Private to michi_tools (not installed). MethodRun's episode loop and sensing are in ReplanEpisode.cpp, the
// executor's hooks (interference checks, deformation, planning, escapes) in ReplanHooks.cpp.

#include "ReplanTypes.h"

#include <michi/planners/dual_roadmap/NonStopExecutor.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <ompl/base/Planner.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateSampler.h>

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace replan
        {
            /** Everything one method needs over all episodes. */
            class MethodRun
            {
            public:
                MethodRun(const Problem &problem, const std::vector<validity::Obstacle> &statics,
                          const std::vector<Mover> &movers, const ReplanSettings &settings, const Method &method);

                /** Run one episode whose moving obstacles follow \e trajectories; \e frames, \e trace (if not null)
                    receive its pictures' frames and its step-by-step record. */
                void episode(const std::vector<std::vector<validity::TimedPose>> &trajectories, Results &results,
                             std::vector<Frame> *frames, Trace *trace = nullptr);

            private:
                /** \brief Replace moving obstacle \e k of the world by one that follows \e trajectory. */
                void setMoverTrajectory(std::size_t k, const std::vector<validity::TimedPose> &trajectory);
                PlanningContext context(const validity::ScenePtr &scene) const;

                static void toState(const ompl::base::SpaceInformationPtr &si, const Configuration &q,
                                    ompl::base::State *s);
                static Configuration toReals(const ompl::base::SpaceInformationPtr &si, const ompl::base::State *s);

                /** Arc length to the first interference of \e path (its first state valid) within \e lookahead. */
                static double firstInterferenceFree(const ompl::base::SpaceInformationPtr &esi,
                                                    const ConfigurationPath &path, double lookahead);

                NonStopSettings executorSettings() const;

                /** Sense the world at time t: obstacle poses and velocities (from the previous sensing). */
                void sense(double t);

                NonStopHooks hooks();

                /** Replace \e s by a state valid in the planning scene reached from it by a motion that is free in
                    the world as it is now (planning thread). */
                bool escape(ompl::base::State *s, const std::atomic<bool> &cancel);

                const Problem &problem_;
                std::vector<Mover> movers_;
                ompl::base::StateSamplerPtr escapeSampler_;
                std::mutex escapeMutex_;
                std::vector<Configuration> escapeTargets_;  ///< the last escapes the planning thread made
                ReplanSettings settings_;
                Method method_;
                SensedWorld planSensed_, execSensed_, planNow_;
                validity::ScenePtr world_;
                SensedWorld moving_;  ///< the movers only, true shapes over escape_horizon (clearance, deformation)
                SensedWorld timed_;   ///< the movers only, grown, one copy each (retiming's checks in time)
                PlanningContext planCtx_, planNowCtx_, execCtx_, worldCtx_, movingCtx_, timedCtx_;
                /** the static obstacles alone: a crossing or an escape is checked against them and moving_ (which
                    holds the movers only), never against the movers alone */
                PlanningContext staticCtx_;
                ompl::base::PlannerPtr planner_;
                std::vector<std::vector<validity::TimedPose>> trajectories_;
                std::vector<validity::ScenePtr> yieldScenes_;
                std::vector<PlanningContext> yieldCtx_;
                std::vector<Eigen::Isometry3d> lastPoses_;
                std::vector<Eigen::Vector3d> lastVelocities_;  ///< of the last sensing (execution thread)
                double lastSenseTime_{0.};
                std::mutex snapshotMutex_;
                std::map<std::uint64_t, Snapshot> snapshots_;
                std::uint64_t snapshotId_{0};
            };
        }  // namespace replan
    }      // namespace tools
}  // namespace michi

#endif
