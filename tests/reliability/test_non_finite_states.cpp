// A state holding a NaN or an infinity is invalid for every checker. OMPL's RealVectorStateSpace::satisfiesBounds()
// lets a NaN through (every comparison with it is false), so each checker must refuse it before its geometry: given
// a NaN, a pose, a table lookup or a map point can read as free.
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

using namespace michi;

namespace
{
    struct Case
    {
        std::string problem, checker;
    };

    /** Each value of a valid state in turn replaced by \e bad: the checker must refuse every one. */
    void expectRefused(const Case &c, double bad)
    {
        const auto problem = tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/" + c.problem + ".yaml");
        tools::ContextOptions options;
        options.checker = c.checker;
        const auto ctx = tools::makePlanningContext(problem, options);
        const auto si = ctx.setup->getSpaceInformation();
        const auto space = si->getStateSpace();
        ompl::base::State *state = si->allocState();
        std::vector<double> values = problem.queries.front().start;
        space->copyFromReals(state, values);
        ASSERT_TRUE(si->isValid(state)) << c.problem << " " << c.checker << ": the start must be valid";
        for (std::size_t d = 0; d < values.size(); ++d)
        {
            std::vector<double> v = values;
            v[d] = bad;
            space->copyFromReals(state, v);
            EXPECT_FALSE(si->isValid(state)) << c.problem << " " << c.checker << ": value " << d << " = " << bad;
            double clearance = -1.;
            EXPECT_FALSE(si->getStateValidityChecker()->isValid(state, clearance))
                << c.problem << " " << c.checker << ": value " << d << " = " << bad << " (with clearance)";
        }
        si->freeState(state);
    }
}  // namespace

TEST(NonFiniteStates, AreInvalidForEveryChecker)
{
    // planar_3dof_hand on the J-map: the hand's value reaches FCL through the J-map checker's fallback
    const std::vector<Case> cases{{"planar_2link", "fcl"},         {"planar_2link", "jmap"},
                                  {"planar_3dof_hand", "jmap"},    {"panda_table_pick", "fcl"},
                                  {"panda_table_pick", "spheres"}, {"movingai_arena", "fcl"},
                                  {"movingai_arena", "grid"}};
    for (const auto &c : cases)
    {
        expectRefused(c, std::numeric_limits<double>::quiet_NaN());
        expectRefused(c, std::numeric_limits<double>::infinity());
    }
}
