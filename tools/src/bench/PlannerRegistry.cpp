#include <michi/tools/bench/PlannerRegistry.h>

#include <michi/planners/heading_lattice/HeadingLattice.h>
#include <michi/planners/concentric_circle/ConcentricCircle.h>
#include <michi/planners/dual_roadmap/DualRoadmap.h>
#include <michi/planners/experience/ExperiencePeers.h>
#include <michi/planners/path_seed/PathSeed.h>

#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/est/ProjEST.h>
#include <ompl/geometric/planners/fmt/BFMT.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/ABITstar.h>
#include <ompl/geometric/planners/informedtrees/AITstar.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/pdst/PDST.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/prm/SPARS.h>
#include <ompl/geometric/planners/prm/SPARStwo.h>
#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/LazyRRT.h>
#include <ompl/geometric/planners/rrt/LBTRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/geometric/planners/sst/SST.h>
#include <ompl/geometric/planners/stride/STRIDE.h>

#include "bench/TestPlanners.h"

#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace tools
    {
        namespace
        {
            template <typename P>
            ob::PlannerAllocator allocator()
            {
                return [](const ob::SpaceInformationPtr &si)
                {
                    return std::make_shared<P>(si);
                };
            }

            /** A stock planner without the progress properties that are not safe to read while it plans.
                OMPL's Benchmark samples progress properties from a second thread; in OMPL 1.5.2 BIT*'s (and
                ABIT*'s) "current graph vertices" and "current free states" copy the nearest-neighbour structure
                the planner is modifying, which crashed `michi bench` (segfault in GNAT::list, seen on
                planar_3dof_hand). Scalar counters and the best cost stay. */
            template <typename P>
            class WithSafeProgress : public P
            {
            public:
                explicit WithSafeProgress(const ob::SpaceInformationPtr &si) : P(si)
                {
                    for (const char *name : {"current graph vertices INTEGER", "current free states INTEGER"})
                        this->plannerProgressProperties_.erase(name);
                }
            };
        }  // namespace

        const std::map<std::string, ob::PlannerAllocator> &plannerAllocators()
        {
            // OMPL's stock geometric planners under MoveIt's ids. Those that use a projection (KPIECE1,
            // BKPIECE1, LBKPIECE1, ProjEST, SBL, PDST, STRIDE) take the space's default projection: michi's
            // joint spaces register one that works on OMPL 1.5.2. michi's own planners are in this map under
            // "michi::<Name>" (the registry name; the C++ class is michi::planners::<Name>).
            // A std::map: list-planners and the "known:" message come out sorted, and a name is found by exact match
            // only.
            static const std::map<std::string, ob::PlannerAllocator> registry{
                {"geometric::ABITstar", allocator<WithSafeProgress<og::ABITstar>>()},
                {"geometric::AITstar", allocator<og::AITstar>()},
                {"geometric::BFMT", allocator<og::BFMT>()},
                {"geometric::BiEST", allocator<og::BiEST>()},
                {"geometric::BiTRRT", allocator<og::BiTRRT>()},
                {"geometric::BITstar", allocator<WithSafeProgress<og::BITstar>>()},
                {"geometric::BKPIECE1", allocator<og::BKPIECE1>()},
                {"geometric::EST", allocator<og::EST>()},
                {"geometric::FMT", allocator<og::FMT>()},
                {"geometric::InformedRRTstar", allocator<og::InformedRRTstar>()},
                {"geometric::KPIECE1", allocator<og::KPIECE1>()},
                {"geometric::LazyPRM", allocator<og::LazyPRM>()},
                {"geometric::LazyPRMstar", allocator<og::LazyPRMstar>()},
                {"geometric::LazyRRT", allocator<og::LazyRRT>()},
                {"geometric::LBKPIECE1", allocator<og::LBKPIECE1>()},
                {"geometric::LBTRRT", allocator<og::LBTRRT>()},
                {"geometric::PDST", allocator<og::PDST>()},
                {"geometric::PRM", allocator<og::PRM>()},
                {"geometric::PRMstar", allocator<og::PRMstar>()},
                {"geometric::ProjEST", allocator<og::ProjEST>()},
                {"geometric::RRT", allocator<og::RRT>()},
                {"geometric::RRTConnect", allocator<og::RRTConnect>()},
                {"geometric::RRTstar", allocator<og::RRTstar>()},
                {"geometric::SBL", allocator<og::SBL>()},
                {"geometric::SPARS", allocator<og::SPARS>()},
                {"geometric::SPARStwo", allocator<og::SPARStwo>()},
                {"geometric::SST", allocator<og::SST>()},
                {"geometric::STRIDE", allocator<og::STRIDE>()},
                {"geometric::TRRT", allocator<og::TRRT>()},
                {"michi::HeadingLattice", allocator<michi::planners::HeadingLattice>()},
                {"michi::ConcentricCircle", allocator<michi::planners::ConcentricCircle>()},
                {"michi::DualRoadmap", allocator<michi::planners::DualRoadmap>()},
                {"michi::PathSeed", allocator<michi::planners::PathSeed>()},
                {"experience::Lightning", allocator<michi::planners::LightningPlanner>()},
                {"experience::Thunder", allocator<michi::planners::ThunderPlanner>()},
            };
            return registry;
        }

        std::vector<std::string> plannerNames()
        {
            std::vector<std::string> names;
            for (const auto &kv : plannerAllocators())
                names.push_back(kv.first);
            return names;
        }

        bool isTestPlanner(const std::string &name)
        {
            const char *enabled = std::getenv("MICHI_TEST_PLANNERS");
            // Only with MICHI_TEST_PLANNERS=1: planners that crash or hang on purpose must never be reachable by
            // accident, not even by a typo in a campaign file.
            return enabled != nullptr && std::strcmp(enabled, "1") == 0 &&
                   (name == "test::Segfault" || name == "test::Hang");
        }

        std::string statusText(const ob::PlannerStatus &status)
        {
            if (status == ob::PlannerStatus::ABORT)
                return "Abort: the search ended without a path";
            return status.asString();
        }

        void requirePlannerName(const std::string &name)
        {
            if (isTestPlanner(name) || plannerAllocators().count(name) != 0)
                return;
            std::ostringstream known;
            for (const auto &n : plannerNames())
                known << " " << n;
            throw std::invalid_argument("unknown planner '" + name + "' (known:" + known.str() + ")");
        }

        ob::PlannerPtr allocatePlanner(const std::string &name, const ob::SpaceInformationPtr &si)
        {
            if (isTestPlanner(name))
                return allocateTestPlanner(name, si);
            requirePlannerName(name);
            return plannerAllocators().at(name)(si);
        }
    }  // namespace tools
}  // namespace michi
