#include <michi/tools/problem/RandomPlanarScene.h>

#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/jmap/PlanarArm.h>
#include <michi/tools/problem/GridReachability.h>
#include <michi/tools/bench/PlanningContext.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        std::vector<std::vector<Eigen::Vector2d>> randomPolygons(ompl::RNG &rng, const RandomPolygonOptions &options)
        {
            if (options.count < 0 || options.minSides < 3 || options.maxSides < options.minSides ||
                !(options.minRadius > 0.) || options.maxRadius < options.minRadius ||
                !(options.keepClearRadius >= 0.) || !(options.lo.array() <= options.hi.array()).all())
                throw std::invalid_argument(
                    "randomPolygons: bad options (count >= 0, 3 <= minSides <= maxSides, "
                    "0 < minRadius <= maxRadius, keepClearRadius >= 0, lo <= hi)");
            std::vector<std::vector<Eigen::Vector2d>> polygons;
            for (int p = 0; p < options.count; ++p)
            {
                Eigen::Vector2d centre;
                for (int attempt = 0;; ++attempt)
                {
                    centre = Eigen::Vector2d(rng.uniformReal(options.lo.x(), options.hi.x()),
                                             rng.uniformReal(options.lo.y(), options.hi.y()));
                    // Even a polygon of the largest radius stays outside the keep-clear disk, so the arm's base is
                    // never buried.
                    if ((centre - options.keepClearCentre).norm() - options.maxRadius >= options.keepClearRadius)
                        break;
                    if (attempt > 10000)
                        throw std::invalid_argument("randomPolygons: no room outside the keep-clear disk");
                }
                const int sides = rng.uniformInt(options.minSides, options.maxSides);
                std::vector<double> angles;
                for (int i = 0; i < sides; ++i)
                    angles.push_back(rng.uniformReal(0., 2. * M_PI));
                std::sort(angles.begin(), angles.end());
                // spread the angles so that no two vertices nearly coincide
                for (int i = 0; i < sides; ++i)
                    angles[i] = 0.5 * angles[i] + 0.5 * (2. * M_PI * i / sides);
                std::vector<Eigen::Vector2d> outline;
                // One vertex per angle, in angle order around the centre: the outline is star-shaped about the centre
                // and so never crosses itself (the triangulation of a prism needs a simple polygon).
                for (double a : angles)
                    outline.push_back(centre + rng.uniformReal(options.minRadius, options.maxRadius) *
                                                   Eigen::Vector2d(std::cos(a), std::sin(a)));
                polygons.push_back(std::move(outline));
            }
            return polygons;
        }

        std::vector<std::vector<Eigen::Vector2d>> randomPolygons(std::uint_fast32_t seed,
                                                                 const RandomPolygonOptions &options)
        {
            ompl::RNG rng(seed);
            return randomPolygons(rng, options);
        }

        RandomPlanarScene randomPlanarScene(const Problem &arm, std::uint_fast32_t seed,
                                            const RandomPlanarSceneOptions &options)
        {
            if (arm.kind != Problem::Kind::ARM || !arm.model || arm.groupVariables.empty())
                throw ProblemError(arm.file, "robot", "a random planar scene needs an arm (a URDF robot)");
            validity::PlanarArmPtr planar;
            try
            {
                planar = validity::PlanarArm::fromModel(*arm.model);
            }
            catch (const std::invalid_argument &e)
            {
                throw ProblemError(arm.file, "robot",
                                   std::string("a random planar scene needs a planar arm (every movable joint about "
                                               "z): ") +
                                       e.what());
            }
            if (options.polygons < 0 || !(options.extent > 0.) || !(options.keepClear >= 0.) ||
                !(options.zMax > options.zMin) || !(options.minQueryDistance >= 0.) || options.maxSamples < 1 ||
                !(options.reachabilityStep >= 0.))
                throw std::invalid_argument(
                    "randomPlanarScene: bad options (polygons >= 0, extent > 0, keepClear >= "
                    "0, zMin < zMax, minQueryDistance >= 0, reachabilityStep >= 0, "
                    "maxSamples >= 1)");

            // the base of the arm: joint 1's axis in the plane at q = 0
            const std::vector<double> zero(arm.model->variableCount(), 0.);
            const auto &first = planar->joints()[planar->variableJoint(arm.groupVariables[0])];
            const Eigen::Vector2d base = planar->linkFrames(zero.data())[first.childLink].translation();

            ompl::RNG rng(seed);
            RandomPolygonOptions polygonOptions;
            polygonOptions.count = options.polygons;
            polygonOptions.lo = base - Eigen::Vector2d::Constant(options.extent);
            polygonOptions.hi = base + Eigen::Vector2d::Constant(options.extent);
            polygonOptions.keepClearRadius = options.keepClear;
            polygonOptions.keepClearCentre = base;
            const auto outlines = randomPolygons(rng, polygonOptions);

            RandomPlanarScene result;
            result.polygons = outlines;
            Problem &scene = result.problem;
            scene = arm;
            scene.name = "scene_" + std::to_string(seed);
            scene.file = scene.name + ".yaml";
            scene.description = "Random planar scene " + std::to_string(seed) + ": " +
                                std::to_string(options.polygons) + " random star-shaped polygons around the arm of " +
                                arm.name + " (michi random-scenes)";
            scene.scene = std::make_shared<validity::Scene>();
            for (std::size_t i = 0; i < outlines.size(); ++i)
            {
                validity::Obstacle o;
                o.name = "polygon" + std::to_string(i);
                o.shape = validity::Shape::prism(outlines[i], options.zMin, options.zMax);
                scene.scene->add(std::move(o));
            }
            // The template's experience queries belong to its own scene; they would not hold in this one.
            scene.experience = ExperienceQueries{};

            // start and goal: uniform states in the joint limits that FCL calls valid, and valid for every checker
            // the template plans with (the problem's and each planner's own: planar_2link runs ConcentricCircle and
            // RRTConnect on the J-map, whose margin refuses some states FCL calls free; before, 6 of the 50 scenes
            // of seeds 101-150 gave those planners an invalid start or goal); for two joints, also linked by the grid
            // search with the problem's motion validator under each of those checkers
            auto si = std::make_shared<ompl::base::SpaceInformation>(makeStateSpace(scene));
            validity::FclValidityChecker checker(si, scene.bodies(), scene.scene);
            const std::size_t dim = scene.dimension();
            const bool linked = dim == 2 && options.reachabilityStep > 0. &&
                                dynamic_cast<const ompl::base::RealVectorStateSpace *>(si->getStateSpace().get());
            std::vector<std::string> checkers{scene.checker};
            for (const auto &spec : scene.planners)
                if (!spec.checker.empty() &&
                    std::find(checkers.begin(), checkers.end(), spec.checker) == checkers.end())
                    checkers.push_back(spec.checker);
            // per checker: a context (made at the first start FCL accepts; its query is only a placeholder) and,
            // for two joints, its grid of components and the start's
            struct Gate
            {
                std::string checker;
                PlanningContext ctx;
                std::unique_ptr<GridComponents> grid;
                std::vector<int> startComponents;
                std::unique_ptr<ompl::base::ScopedState<>> scratch;  ///< validFor()'s state, made once per gate
            };
            std::vector<Gate> gates;
            const bool gated = linked || checkers.size() > 1 || checkers.front() != "fcl";
            // FCL's own answer is already known (checker above): only the other checkers are asked
            auto validFor = [](const Gate &gate, const std::vector<double> &q)
            {
                if (gate.checker == "fcl")
                    return true;
                ompl::base::State *state = gate.scratch->get();
                gate.scratch->getSpace()->copyFromReals(state, q);
                gate.scratch->getSpace()->enforceBounds(state);
                return gate.ctx.setup->getSpaceInformation()->isValid(state);
            };
            int samples = 0;
            auto draw = [&](const char *what)
            {
                if (samples++ >= options.maxSamples)
                    throw std::runtime_error(scene.name + ": no " + what + " found in " +
                                             std::to_string(options.maxSamples) + " random states");
                std::vector<double> q(dim);
                for (std::size_t i = 0; i < dim; ++i)
                {
                    const auto &joint = arm.model->variableJoint(arm.groupVariables[i]);
                    q[i] = rng.uniformReal(joint.lower, joint.upper);
                }
                return q;
            };
            // a start that every checker accepts and that attaches to each grid, then a goal in one of its
            // components in every grid; a start whose components give no goal in GOALS_PER_START valid, distant
            // candidates (a small pocket) is replaced
            const int GOALS_PER_START = 200;
            Query query;
            for (bool found = false; !found;)
            {
                query.start = draw("valid start");
                if (!checker.isValidConfiguration(query.start.data()))
                    continue;
                if (gated && gates.empty())
                {
                    scene.queries = {Query{query.start, query.start, {}}};
                    for (const auto &name : checkers)
                    {
                        ContextOptions contextOptions;
                        contextOptions.checker = name;
                        gates.push_back(Gate{name, makePlanningContext(scene, contextOptions), nullptr, {}, nullptr});
                        gates.back().scratch =
                            std::make_unique<ompl::base::ScopedState<>>(gates.back().ctx.setup->getStateSpace());
                        if (linked)
                            gates.back().grid = std::make_unique<GridComponents>(
                                gates.back().ctx.setup->getSpaceInformation(), options.reachabilityStep);
                    }
                }
                bool accepted = true;
                for (auto &gate : gates)
                {
                    accepted = validFor(gate, query.start) &&
                               (!linked || !(gate.startComponents = gate.grid->attach(query.start)).empty());
                    if (!accepted)
                        break;
                }
                if (!accepted)
                    continue;
                for (int candidates = 0; !found && (!linked || candidates < GOALS_PER_START);)
                {
                    query.goal = draw(linked ? "valid goal linked to the start" : "valid goal");
                    double d = 0.;
                    for (std::size_t i = 0; i < dim; ++i)
                        d += (query.goal[i] - query.start[i]) * (query.goal[i] - query.start[i]);
                    if (std::sqrt(d) < options.minQueryDistance || !checker.isValidConfiguration(query.goal.data()))
                        continue;
                    bool valid = true;
                    for (const auto &gate : gates)
                        valid = valid && validFor(gate, query.goal);
                    if (!valid)
                        continue;
                    ++candidates;
                    found = true;
                    for (const auto &gate : gates)
                    {
                        if (!linked || !found)
                            break;
                        const auto goalComponents = gate.grid->attach(query.goal);
                        found = std::find_first_of(goalComponents.begin(), goalComponents.end(),
                                                   gate.startComponents.begin(),
                                                   gate.startComponents.end()) != goalComponents.end();
                    }
                }
            }
            scene.queries = {query};
            return result;
        }
    }  // namespace tools
}  // namespace michi
