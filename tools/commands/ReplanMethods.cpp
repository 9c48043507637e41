#include "ReplanTypes.h"

namespace michi
{
    namespace tools
    {
        namespace replan
        {
            std::vector<Method> allMethods()
            {
                return {
                    // The last field: smooth the path with OMPL's simplifier. DualRoadmap smooths its own paths
                    // (paper 002: redundant parts removed), so only the baselines get OMPL's, inside their latency.
                    {"dual", "michi::DualRoadmap", "michi::DualRoadmap", {}, Method::Reuse::DUAL, false},
                    {"rrtconnect", "geometric::RRTConnect", "geometric::RRTConnect", {}, Method::Reuse::SCRATCH, true},
                    {"prm", "geometric::PRM", "geometric::PRM", {}, Method::Reuse::SCRATCH, true},
                    {"lazyprm",
                     "geometric::LazyPRM (roadmap kept)",
                     "geometric::LazyPRM",
                     {},
                     Method::Reuse::KEEP_ROADMAP,
                     true},
                    {"dual-no-learning",
                     "michi::DualRoadmap (no learning roadmap)",
                     "michi::DualRoadmap",
                     {{"use_learning", "0"}},
                     Method::Reuse::DUAL,
                     false},
                    // paper 002's narrowing to the dominant degrees of freedom (two directions), measured against
                    // "dual" in the same run; not the default (docs/dual-roadmap.md: no gain shown)
                    {"dual-dominant",
                     "michi::DualRoadmap (dominant DOF)",
                     "michi::DualRoadmap",
                     {{"dominant_dofs", "2"}},
                     Method::Reuse::DUAL,
                     false},
                    // paper 002's hierarchical roadmap for arms (the hand's route in task space over the joint-space
                    // roadmap), measured against "dual" in the same run; on a robot without a hand (SE(2)) it is
                    // "dual"
                    {"dual-task-level",
                     "michi::DualRoadmap (task level)",
                     "michi::DualRoadmap",
                     {{"task_level", "1"}},
                     Method::Reuse::DUAL,
                     false},
                    // the executor's ablations, with DualRoadmap planning: no time-scale adaptation; and stop and
                    // replan (no planning while moving, hence no deformation or retiming either)
                    {"dual-no-retiming",
                     "michi::DualRoadmap (no retiming)",
                     "michi::DualRoadmap",
                     {},
                     Method::Reuse::DUAL,
                     false,
                     false},
                    {"stop-and-replan",
                     "michi::DualRoadmap (stop and replan)",
                     "michi::DualRoadmap",
                     {},
                     Method::Reuse::DUAL,
                     false,
                     false,
                     false},
                };
            }
        }  // namespace replan
    }      // namespace tools
}  // namespace michi
