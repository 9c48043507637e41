#include <michi/tools/problem/ProblemJMap.h>

#include <michi/validity/jmap/PlanarArm.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <mutex>

namespace michi
{
    namespace tools
    {
        namespace
        {
            /** Most distance queries an FCL-sweep J-map may need (at a few ms per query on mesh arms: hours). */
            constexpr double MAX_SWEEP_QUERIES = 5e6;
        }  // namespace

        JMapProblem makeJMapProblem(const Problem &problem, const PlanningContext &ctx)
        {
            if (problem.kind != Problem::Kind::ARM || problem.groupVariables.size() < 2)
                throw ProblemError(problem.file, "robot", "a J-map needs an arm with at least two planned joints");
            JMapProblem jp;
            const auto &model = *problem.model;
            const int axis1 = problem.groupVariables[0], axis2 = problem.groupVariables[1];
            std::vector<double> configuration = ctx.fixedValues;  // the context's (the problem's unless overridden)
            // The two axes are the map's coordinates: their values here are placeholders; the other joints keep the
            // context's.
            configuration[axis1] = 0.;
            configuration[axis2] = 0.;
            // With more planned joints the map covers the arm only (a pre-filter); FCL checks the rest (jmap.md).
            jp.coversRobot = problem.groupVariables.size() == 2;
            try
            {
                jp.arm = validity::PlanarArm::fromModel(model);
                jp.planar = true;
            }
            catch (const std::invalid_argument &)
            {
                jp.planar = false;  // not every joint about z: the FCL sweep works for any arm
            }
            if (jp.planar)
            {
                jp.axes = validity::planarAxes(*jp.arm, axis1, axis2, configuration);
                // the arm map leaves out the links that other planned joints move (the hand)
                for (std::size_t l = 0; l < jp.arm->links().size(); ++l)
                {
                    bool hand = false;
                    for (std::size_t g = 2; g < problem.groupVariables.size(); ++g)
                        hand = hand || jp.arm->moves(problem.groupVariables[g], static_cast<int>(l));
                    if (!hand)
                        jp.armLinks.push_back(static_cast<int>(l));
                    else
                        jp.handLength =
                            std::max(jp.handLength, jp.arm->reachFrom(problem.groupVariables[2], static_cast<int>(l)));
                }
                const auto arm = jp.arm;
                const auto links = jp.armLinks;
                const auto scene = ctx.scene;
                // The scene's outlines are united once per scene version, not once per tile: on a map of thousands
                // of obstacles the union is what a tile cost.
                struct United
                {
                    std::mutex mutex;
                    std::uint64_t version{std::numeric_limits<std::uint64_t>::max()};
                    validity::MultiPolygon2 polygons;
                };
                auto united = std::make_shared<United>();
                jp.makeSource = [arm, links, scene, united](const validity::JMapAxes &axes)
                {
                    std::lock_guard<std::mutex> lock(united->mutex);
                    // the version is read first: a change during the union makes the next tile unite again
                    const std::uint64_t version = scene->changeCount();
                    if (version != united->version)
                    {
                        united->polygons = scene->polygons2d();
                        united->version = version;
                    }
                    return std::make_shared<validity::PlanarIntervalSource>(arm, united->polygons, axes, links);
                };
            }
            else
            {
                jp.axes.axis1 = axis1;
                jp.axes.axis2 = axis2;
                jp.axes.configuration = configuration;
                jp.axes.lo1 = model.variableJoint(axis1).lower;
                jp.axes.hi1 = model.variableJoint(axis1).upper;
                jp.axes.lo2 = model.variableJoint(axis2).lower;
                jp.axes.hi2 = model.variableJoint(axis2).upper;
                // the sweep needs the other planned joints fixed: a checker over exactly the two axes
                auto bodies = std::make_shared<validity::RobotGroupBodies>(
                    problem.model, std::vector<int>{axis1, axis2}, configuration);
                auto checker = ctx.checker;
                auto si = ctx.setup->getSpaceInformation();
                jp.makeSource = [bodies, checker](const validity::JMapAxes &axes)
                {
                    auto space = std::make_shared<ompl::base::RealVectorStateSpace>(2);
                    ompl::base::RealVectorBounds b(2);
                    b.setLow(0, axes.lo1 - 1.);
                    b.setHigh(0, axes.hi1 + 1.);
                    b.setLow(1, axes.lo2 - 1.);
                    b.setHigh(1, axes.hi2 + 1.);
                    space->setBounds(b);
                    auto two = std::make_shared<ompl::base::SpaceInformation>(space);
                    auto fcl = std::make_shared<validity::FclValidityChecker>(two, bodies, checker->scene());
                    return std::make_shared<validity::FclIntervalSource>(fcl, axes);
                };
            }
            return jp;
        }

        namespace
        {
            /** The J-map of an arm whose joints are not all about z comes from an FCL sweep: per slice and column,
                distance queries walk theta2 in steps of at least FclIntervalSource's 2 mrad. That is bounded,
                but for a mesh arm (a Panda: seconds per slice) the tiles take minutes and are built inside
                solve(), where no termination condition reaches them. Too much work is an error naming the key;
                long work gets a line with its estimate before it starts. */
            void boundFclSweep(const Problem &problem, const PlanningContext &ctx, const JMapProblem &jp,
                               const validity::JMapCheckerSettings &settings)
            {
                const double range2 = jp.axes.hi2 - jp.axes.lo2;
                // The worst case: every 2 mrad step of theta2 a distance query, in every column of every slice (columns
                // + 1 for the true intervals at the slice centre).
                const double perColumn = std::ceil(range2 / 0.002);
                const double maxQueries =
                    static_cast<double>(settings.map.slices) * (settings.map.columns + 1) * perColumn;
                if (maxQueries > MAX_SWEEP_QUERIES)
                    throw ProblemError(problem.file, "collision.jmap.slices",
                                       "an FCL-sweep J-map of " + std::to_string(settings.map.slices) +
                                           " slices needs up to " + std::to_string(static_cast<long long>(maxQueries)) +
                                           " distance queries (limit " +
                                           std::to_string(static_cast<long long>(MAX_SWEEP_QUERIES)) +
                                           "): use fewer slices or collision.checker: fcl");
                // the cost of one query, measured on the first query's start (the context's problem definition has
                // no start yet while its checker is made: reading it there was a null dereference)
                std::vector<double> values = problem.queries.empty() ? std::vector<double>(problem.dimension(), 0.)
                                                                     : problem.queries.front().start;
                const auto &bodies = *ctx.checker->bodies();
                const std::vector<char> wantBodies(bodies.bodies().size(), 1);
                const std::vector<char> wantPairs(bodies.selfCheckPairs().size(), 1);
                std::vector<double> obstacle, self;
                const int samples = 3;
                const auto start = std::chrono::steady_clock::now();
                for (int i = 0; i < samples; ++i)
                    ctx.checker->bodyDistances(values.data(), wantBodies, wantPairs, obstacle, self);
                const double perQuery =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / samples;
                const double worst = perQuery * maxQueries;
                if (worst > 10.)
                    std::cerr << "michi: " << problem.file << ": the J-map checker: the J-map of this arm is an "
                              << "FCL sweep (" << settings.map.slices << " slices, " << settings.tiles
                              << " tiles built as planning reaches them): up to " << static_cast<long long>(maxQueries)
                              << " distance queries of " << perQuery * 1e3 << " ms, up to about "
                              << static_cast<long long>(worst) << " s; fewer collision.jmap.slices, or the fcl "
                              << "checker, make it shorter" << std::endl;
            }
        }  // namespace

        validity::JMapValidityCheckerPtr makeJMapChecker(const Problem &problem, const PlanningContext &ctx,
                                                         const validity::JMapCheckerSettings &settings)
        {
            const JMapProblem jp = makeJMapProblem(problem, ctx);
            if (!jp.planar)
                boundFclSweep(problem, ctx, jp, settings);
            return std::make_shared<validity::JMapValidityChecker>(ctx.setup->getSpaceInformation(), ctx.checker,
                                                                   jp.makeSource, jp.axes, jp.coversRobot, settings);
        }
    }  // namespace tools
}  // namespace michi
