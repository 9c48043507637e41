#include <michi/tools/pictures/PathSeedFigure.h>

#include <michi/planners/path_seed/PathSeedCodec.h>
#include <michi/tools/problem/ExperienceQueries.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/pictures/SvgPlot.h>

#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include <sstream>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace tools
    {
        std::string writePathSeedFigure(const Problem &problem, std::size_t training, std::size_t heldOut,
                                        const std::string &variant, unsigned int seed, const std::string &file)
        {
            const auto &exp = problem.experience;
            if (training >= exp.training.size())
                throw ProblemError(problem.file, "experience",
                                   "training query " + std::to_string(training) + " requested, there are " +
                                       std::to_string(exp.training.size()));
            if (heldOut >= exp.heldOut.size())
                throw ProblemError(problem.file, "experience",
                                   "held-out query " + std::to_string(heldOut) + " requested, there are " +
                                       std::to_string(exp.heldOut.size()));
            const planners::SeedVariant v = planners::seedVariantFromName(variant);
            ompl::RNG::setSeed(seed);
            // the training query alone
            const PlanningContext ctx = makePlanningContext(problem, 0);
            const auto paths = solveTrainingQueries(problem, ctx, nullptr, training);
            if (paths.empty())
                throw std::runtime_error("RRT-Connect did not solve training query " + std::to_string(training));
            og::PathGeometric original = paths.front();
            const auto space = ctx.setup->getStateSpace();
            std::vector<Eigen::VectorXd> states;
            for (const auto *s : original.getStates())
            {
                std::vector<double> r;
                space->copyToReals(r, s);
                states.push_back(Eigen::Map<const Eigen::VectorXd>(r.data(), r.size()));
            }
            const auto code = planners::encodePath(states, v);
            auto toPlot = [](const std::string &label, const std::vector<Eigen::VectorXd> &path)
            {
                PlotPath p;
                p.label = label;
                for (const auto &x : path)
                    p.states.emplace_back(x.data(), x.data() + x.size());
                return p;
            };
            // Decoded for its own start and goal, the seed should give the original path back: the error measures what
            // the encoding loses.
            const auto same = planners::decodePath(code, states.front(), states.back());
            double error = 0.;
            for (std::size_t i = 0; i < same.size(); ++i)
                error = std::max(error, (same[i] - states[i]).cwiseAbs().maxCoeff());
            const Query &q = exp.heldOut[heldOut];
            const Eigen::VectorXd s = Eigen::Map<const Eigen::VectorXd>(q.start.data(), q.start.size());
            const Eigen::VectorXd g = Eigen::Map<const Eigen::VectorXd>(q.goal.data(), q.goal.size());
            const auto decoded = planners::decodePath(code, s, g);
            og::PathGeometric decodedPath(ctx.setup->getSpaceInformation());
            ob::ScopedState<> st(space);
            for (const auto &x : decoded)
            {
                st = std::vector<double>(x.data(), x.data() + x.size());
                decodedPath.append(st.get());
            }
            // A decoded path is only a guess for the new query; whether it is valid says if it could be used as it is.
            const bool valid = decodedPath.check();

            // draw with the held-out query's start and goal (titled as query 0)
            PictureOverride drawn;
            drawn.query = &q;
            writeProblemSvg(problem,
                            {toPlot("original (training query " + std::to_string(training) + ")", states),
                             toPlot("decoded for its own start and goal", same),
                             toPlot("decoded for held-out query " + std::to_string(heldOut), decoded)},
                            file, 0, drawn);
            std::ostringstream report;
            report << "michi path-seed-figure: wrote " << file << ": training query " << training << " ("
                   << states.size() - 2 << " waypoints, length " << original.length() << "), " << variant
                   << " seed; reproduction error " << error << "; decoded for held-out query " << heldOut << ": length "
                   << decodedPath.length() << ", " << (valid ? "valid" : "invalid (needs stitching or repair)");
            return report.str();
        }
    }  // namespace tools
}  // namespace michi
