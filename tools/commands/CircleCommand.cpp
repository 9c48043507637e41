#include <michi/tools/commands/CircleCommand.h>

#include <michi/tools/pictures/CirclePicture.h>
#include <michi/tools/bench/PathCertificate.h>
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/pictures/SvgPlot.h>
#include <michi/tools/viewer/ReplayPage.h>

#include <boost/filesystem.hpp>

#include <sstream>
#include <stdexcept>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        std::string runCircles(const Problem &input, const CircleOptions &options)
        {
            // A copy: --checker changes this run only, not the caller's problem.
            Problem problem = input;
            if (!options.checker.empty())
            {
                if (options.checker != "fcl" && options.checker != "jmap")
                    throw std::invalid_argument("--checker expects fcl or jmap, got '" + options.checker + "'");
                problem.checker = options.checker;
            }
            PlanningContext ctx = makePlanningContext(problem, options.query);
            const auto si = ctx.setup->getSpaceInformation();
            auto planner = std::make_shared<planners::ConcentricCircle>(si);
            applyPlannerParams(*planner, PlannerSpec{"michi::ConcentricCircle", options.params, {}}, problem.file);
            ctx.setup->setPlanner(planner);
            const auto status = ctx.setup->solve(options.timeLimit);
            std::ostringstream out;
            out << problem.name << ": ConcentricCircle " << statusText(status) << " in "
                << ctx.setup->getLastPlanComputationTime() << " s, mode " << planner->usedMode() << "\n";
            if (!fs::exists(options.outDir))
                fs::create_directories(options.outDir);
            const auto names = problem.valueNames();
            // Pictures of every stage are written before the status is looked at: when the search fails they are what
            // shows why.
            for (std::size_t k = 0; k < planner->stages().size(); ++k)
            {
                const auto &stage = planner->stages()[k];
                CirclePictureOptions picture;
                picture.view = options.view;
                picture.title = problem.name + ": concentric circles, " + stage.name + " map";
                if (stage.name == "surface")
                {
                    // The surface stage searches a plane through start and goal in joint space, not two joints' own
                    // axes.
                    picture.axis1 = "u: along start -> goal in joint space";
                    picture.axis2 = "v: across, on the restriction plane";
                }
                else if (stage.name == "hand")
                {
                    picture.axis1 = "arc length along the arm path";
                    picture.axis2 = names.size() > 2 ? names[2] : "hand";
                }
                else if (names.size() >= 2)
                {
                    picture.axis1 = names[planner->getAxis1()];
                    picture.axis2 = names[planner->getAxis2()];
                }
                const std::string file =
                    (fs::path(options.outDir) / (problem.name + "-cc-" + stage.name + ".svg")).string();
                writeCircleSvg(stage, file, picture);
                const auto &search = *stage.search;
                out << "  " << stage.name << ": " << search.rings().size() << " circles, " << search.nodes().size() - 2
                    << " candidates, " << search.links().size() << " links, " << search.paths().size() << " paths, "
                    << search.recursions() << " recursions -> " << file << "\n";
            }
            if (status != ompl::base::PlannerStatus::EXACT_SOLUTION)
            {
                // the summary of the failed search goes to the progress stream, the error stays one line
                if (options.progress != nullptr)
                    *options.progress << out.str() << std::flush;
                throw std::runtime_error(problem.file + ": ConcentricCircle found no path (" + statusText(status) +
                                         "); pictures of the search are in " + options.outDir);
            }
            auto &path = ctx.setup->getSolutionPath();
            // Re-checked with FCL as michi plan and michi bench do: a path the sampling motion validator let through
            // a corner is reported as a failure, with the search's pictures for finding out why, never as a path.
            const PathCertificate certificate = certifyPath(path, *ctx.checker);
            if (!certificate.certified)
            {
                if (options.progress != nullptr)
                    *options.progress << out.str() << std::flush;
                throw std::runtime_error(problem.file + ": ConcentricCircle's path is NOT certified by FCL (" +
                                         certificate.reason + "); pictures of the search are in " + options.outDir);
            }
            std::vector<std::vector<double>> states;
            for (const auto *s : path.getStates())
            {
                states.emplace_back();
                ctx.setup->getStateSpace()->copyToReals(states.back(), s);
            }
            const std::string robot = (fs::path(options.outDir) / (problem.name + "-cc-robot.svg")).string();
            writeProblemSvg(problem, {PlotPath{"ConcentricCircle", states}}, robot, options.query);
            out << "  path: " << states.size() << " states, length " << path.length() << ", clearance "
                << path.clearance() << " -> " << robot << "\n";
            if (options.html)
            {
                const std::string page = (fs::path(options.outDir) / (problem.name + ".html")).string();
                writeReplayPage(problem, {PlotPath{"ConcentricCircle", states}}, page);
                out << "  replay: " << page << "\n";
            }
            return out.str();
        }
    }  // namespace tools
}  // namespace michi
