#include <michi/tools/commands/JMapReport.h>
#include <michi/tools/FileOutput.h>

#include <michi/tools/pictures/JMapPicture.h>
#include <michi/tools/pictures/SvgPlot.h>
#include <michi/tools/problem/ProblemJMap.h>
#include <michi/tools/bench/PlanningContext.h>

#include <ompl/util/RandomNumbers.h>

#include <boost/filesystem.hpp>

#include <chrono>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace
        {
            double seconds(std::chrono::steady_clock::time_point since)
            {
                return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
            }
        }  // namespace

        std::string runJMapReport(const Problem &problem, const JMapReportOptions &options)
        {
            if (options.outDir.empty())
                throw std::invalid_argument("no output folder given");
            PlanningContext ctx = makePlanningContext(problem);
            const JMapProblem jp = makeJMapProblem(problem, ctx);
            const auto &settings = problem.jmap;
            std::ostream *log = options.progress;

            // the whole map at once (for the picture and the counts); the checker builds its own tiles lazily
            if (log)
                *log << "michi jmap: building " << settings.map.slices << " slices ("
                     << (jp.planar ? "planar exact" : "fcl sweep") << ")" << std::endl;
            const auto mapStart = std::chrono::steady_clock::now();
            const auto source = jp.makeSource(jp.axes);
            validity::JMapSettings mapSettings = settings.map;
            if (log)
            {
                // an arm swept by FCL (xarm6_ring: about five minutes here) reports where it is every few seconds
                auto shown = mapStart;
                mapSettings.progress = [log, mapStart, shown](int done, int total) mutable
                {
                    const auto now = std::chrono::steady_clock::now();
                    if (done == total || std::chrono::duration<double>(now - shown).count() < 5.)
                        return;
                    shown = now;
                    const double spent = seconds(mapStart);
                    *log << "michi jmap: " << done << " of " << total << " slices in " << static_cast<int>(spent)
                         << " s, about " << static_cast<int>(spent / done * (total - done) + 0.5) << " s left"
                         << std::endl;
                };
            }
            const validity::JMapPtr map = validity::JMap::build(*source, mapSettings);
            validity::JMapPtr grown;
            validity::MultiPolygon2 neck;
            if (jp.planar && jp.handLength > 0.)
            {
                // The paper's grown J-map: the arm without its hand among obstacles grown by the hand's length;
                // grown minus plain is where only the hand can collide (the bottleneck).
                const auto grownSource = std::make_shared<validity::PlanarIntervalSource>(
                    jp.arm, validity::growObstacles(problem.scene->polygons2d(), jp.handLength), jp.axes, jp.armLinks);
                grown = validity::JMap::build(*grownSource, settings.map);
                neck = validity::bottleneck(*grown, *map);
            }

            // a 3-joint arm: the paper's stack, one map over joints 2 and 3 per theta1 cell (the whole arm)
            std::size_t stackSlices = 0;
            double stackSeconds = 0.;
            if (jp.planar && problem.groupVariables.size() >= 3)
            {
                const int outer = problem.groupVariables[0];
                const auto base = validity::planarAxes(*jp.arm, problem.groupVariables[1], problem.groupVariables[2],
                                                       jp.axes.configuration);
                const auto arm = jp.arm;
                const auto polygons = problem.scene->polygons2d();
                validity::JMapStack stack(
                    [arm, polygons](const validity::JMapAxes &axes)
                    {
                        return std::make_shared<validity::PlanarIntervalSource>(arm, polygons, axes);
                    },
                    base, outer, problem.model->variableJoint(outer).lower, problem.model->variableJoint(outer).upper,
                    settings.map.slices, settings.map);
                if (log)
                    *log << "michi jmap: building a stack of " << stack.size() << " maps" << std::endl;
                const auto stackStart = std::chrono::steady_clock::now();
                stack.buildAll();
                stackSeconds = seconds(stackStart);
                stackSlices = stack.size();
            }

            // verification: the checker (conservative mode, all tiles built) against FCL on the same states
            validity::JMapCheckerSettings conservative = settings;
            // Conservative mode: the map alone answers, so the counts below measure the map, not the FCL fallback.
            conservative.mode = validity::JMapCheckerSettings::Mode::CONSERVATIVE;
            validity::JMapValidityChecker checker(ctx.setup->getSpaceInformation(), ctx.checker, jp.makeSource, jp.axes,
                                                  jp.coversRobot, conservative);
            const double mapSeconds = seconds(mapStart);
            if (log)
                *log << "michi jmap: maps built in " << mapSeconds << " s; building the checker's "
                     << checker.tileCount() << " tiles" << std::endl;
            const auto tilesStart = std::chrono::steady_clock::now();
            // tile by tile, with progress when the maps were slow (the FCL sweep against meshes: minutes)
            const double tileWidth = (jp.axes.hi1 - jp.axes.lo1) / static_cast<double>(checker.tileCount());
            for (std::size_t k = 0; k < checker.tileCount(); ++k)
            {
                // Every tile built before the timing below: the query times are look-ups, not first-query builds.
                checker.tile(jp.axes.lo1 + (static_cast<double>(k) + 0.5) * tileWidth);
                if (log && mapSeconds > 2.)
                    *log << "michi jmap: tile " << k + 1 << "/" << checker.tileCount() << " built ("
                         << seconds(tilesStart) << " s)" << std::endl;
            }
            const double tileSeconds = seconds(tilesStart);
            std::uint64_t unsafe = 0, falseInvalid = 0, jmapInvalid = 0, fclInvalid = 0;
            double jmapNs = 0., fclNs = 0.;
            if (options.verify > 0)
            {
                if (log)
                    *log << "michi jmap: verifying " << options.verify << " states against FCL" << std::endl;
                // A generator of its own: the verification states depend on --seed only, not on what drew numbers
                // before.
                ompl::RNG rng(options.seed);
                const std::size_t dim = problem.dimension();
                std::vector<double> lo(dim), hi(dim), states(options.verify * dim);
                for (std::size_t i = 0; i < dim; ++i)
                {
                    const auto &j = problem.model->variableJoint(problem.groupVariables[i]);
                    lo[i] = j.lower;
                    hi[i] = j.upper;
                }
                for (std::uint64_t n = 0; n < options.verify; ++n)
                    for (std::size_t i = 0; i < dim; ++i)
                        states[n * dim + i] = rng.uniformReal(lo[i], hi[i]);
                std::vector<char> jmapValid(options.verify), fclValid(options.verify);
                auto start = std::chrono::steady_clock::now();
                for (std::uint64_t n = 0; n < options.verify; ++n)
                    // The same states for both checkers, all generated before either is timed.
                    jmapValid[n] = checker.isValidConfiguration(&states[n * dim]);
                jmapNs = seconds(start) * 1e9 / static_cast<double>(options.verify);
                start = std::chrono::steady_clock::now();
                for (std::uint64_t n = 0; n < options.verify; ++n)
                    fclValid[n] = ctx.checker->isValidConfiguration(&states[n * dim]);
                fclNs = seconds(start) * 1e9 / static_cast<double>(options.verify);
                for (std::uint64_t n = 0; n < options.verify; ++n)
                {
                    // Unsafe: the map calls a colliding state free (must be 0, the map contains every collision). False
                    // invalid: the price of that containment.
                    unsafe += jmapValid[n] && !fclValid[n];
                    falseInvalid += !jmapValid[n] && fclValid[n];
                    jmapInvalid += !jmapValid[n];
                    fclInvalid += !fclValid[n];
                }
            }

            std::ostringstream json;
            json << std::setprecision(10) << "{\n"
                 << "  \"problem\": \"" << problem.name << "\",\n"
                 << "  \"source\": \"" << source->name() << "\",\n"
                 << "  \"axes\": [\"" << problem.model->variableJoint(jp.axes.axis1).name << "\", \""
                 << problem.model->variableJoint(jp.axes.axis2).name << "\"],\n"
                 << "  \"slices\": " << map->slices().size() << ",\n"
                 << "  \"polygons\": " << map->polygons().size() << ",\n"
                 << "  \"tolerance\": " << settings.map.tolerance << ",\n"
                 << "  \"build_seconds\": " << map->buildSeconds() << ",\n"
                 << "  \"checker_tiles\": " << checker.tileCount() << ",\n"
                 << "  \"checker_build_seconds\": " << tileSeconds << ",\n"
                 << "  \"checker_answers_alone\": " << (checker.answersAlone() ? "true" : "false") << ",\n"
                 << "  \"grown_polygons\": " << (grown ? grown->polygons().size() : 0) << ",\n"
                 << "  \"hand_length\": " << jp.handLength << ",\n"
                 << "  \"stack_slices\": " << stackSlices << ",\n"
                 << "  \"stack_build_seconds\": " << stackSeconds << ",\n"
                 << "  \"bottleneck_area\": " << boost::geometry::area(neck) << ",\n"
                 << "  \"checked_states\": " << options.verify << ",\n"
                 << "  \"unsafe_states\": " << unsafe << ",\n"
                 << "  \"false_invalid_states\": " << falseInvalid << ",\n"
                 << "  \"false_invalid_fraction\": "
                 << (options.verify ? static_cast<double>(falseInvalid) / options.verify : 0.) << ",\n"
                 << "  \"jmap_invalid_fraction\": "
                 << (options.verify ? static_cast<double>(jmapInvalid) / options.verify : 0.) << ",\n"
                 << "  \"fcl_invalid_fraction\": "
                 << (options.verify ? static_cast<double>(fclInvalid) / options.verify : 0.) << ",\n"
                 << "  \"jmap_query_ns\": " << jmapNs << ",\n"
                 << "  \"fcl_query_ns\": " << fclNs << ",\n"
                 << "  \"seed\": " << options.seed << "\n"
                 << "}\n";

            // staged output: nothing in DIR unless everything was written
            StagedDirectory stage(options.outDir);
            JMapPictureOptions picture;
            picture.title =
                problem.name + ": J-map (" + source->name() + ", " + std::to_string(map->slices().size()) + " slices)";
            picture.axis1 = problem.model->variableJoint(jp.axes.axis1).name;
            picture.axis2 = problem.model->variableJoint(jp.axes.axis2).name;
            picture.grown = grown;
            picture.bottleneck = neck;
            picture.start = {problem.queries[0].start[0], problem.queries[0].start[1]};
            picture.goal = {problem.queries[0].goal[0], problem.queries[0].goal[1]};
            writeJMapSvg(*map, stage.path("jmap.svg").string(), picture);
            svgToPng(stage.path("jmap.svg").string(), stage.path("jmap.png").string());  // none without rsvg-convert
            writeAtomically(json.str(), stage.path("jmap.json").string());
            stage.commit();
            return json.str();
        }
    }  // namespace tools
}  // namespace michi
