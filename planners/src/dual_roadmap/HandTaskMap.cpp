#include <michi/planners/dual_roadmap/HandTaskMap.h>

#include <michi/planners/dual_roadmap/PathDeformation.h>
#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/spheres/SphereValidityChecker.h>

#include <limits>
#include <memory>
#include <vector>

namespace michi
{
    namespace planners
    {
        DualRoadmap::TaskMap handTaskMap(const validity::CollisionBodiesPtr &bodies,
                                         const ompl::base::StateSpacePtr &space)
        {
            if (std::dynamic_pointer_cast<const validity::RobotGroupBodies>(bodies) == nullptr ||
                bodies->bodies().empty())
                return {};
            return [bodies, space](const ompl::base::State *state, Eigen::Vector3d &hand, Eigen::MatrixXd *jacobian)
            {
                // per thread: the planner may run beside other users of the same map
                thread_local std::vector<double> q;
                thread_local std::vector<Eigen::Isometry3d> poses;
                space->copyToReals(q, state);
                if (q.size() != bodies->dimension())
                {
                    // a space that is not set up (no value locations) or not the bodies': no hand; the task level
                    // ignores NaN positions and an empty Jacobian
                    hand.setConstant(std::numeric_limits<double>::quiet_NaN());
                    if (jacobian != nullptr)
                        jacobian->resize(3, 0);
                    return;
                }
                bodies->bodyPoses(q.data(), poses);
                const int tip = static_cast<int>(poses.size()) - 1;
                hand = poses[static_cast<std::size_t>(tip)].translation();
                if (jacobian != nullptr)
                    *jacobian = pointJacobian(*bodies, q.data(), tip, hand);
            };
        }

        validity::CollisionBodiesPtr checkerBodies(const ompl::base::StateValidityCheckerPtr &checker)
        {
            if (auto fcl = std::dynamic_pointer_cast<validity::FclValidityChecker>(checker))
                return fcl->bodies();
            if (auto spheres = std::dynamic_pointer_cast<validity::SphereValidityChecker>(checker))
                return spheres->bodies();
            return nullptr;
        }
    }  // namespace planners
}  // namespace michi
