// Fuzz target: an experience query file (michi::tools::readExperienceQueries), the queries of a problem that is
// problems/xarm6_ring.yaml with its `experience.queries` pointing at the fuzzed file.
#include "FuzzSupport.h"

#include <michi/tools/problem/ExperienceQueries.h>
#include <michi/tools/problem/Problem.h>

#include <fstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    static const std::string problemFile = []
    {
        const std::string file = michi_fuzz::problemsCopy() + "/fuzz_experience_problem.yaml";
        std::ofstream(file) << "experience:\n  queries: experience/fuzz_queries.yaml\n  training_time: 5\n";
        return file;
    }();
    static const michi::tools::Problem problem =
        michi::tools::loadProblem(michi_fuzz::problemsCopy() + "/xarm6_ring.yaml");
    michi_fuzz::writeInput("experience/fuzz_queries.yaml", data, size);
    michi_fuzz::expectCleanResult(
        [&]
        {
            michi::tools::readExperienceQueries(problemFile, problem);
        });
    return 0;
}
