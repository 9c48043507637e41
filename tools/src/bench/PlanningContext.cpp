#include <michi/tools/bench/PlanningContext.h>
#include "problem/ProblemYaml.h"

#include <michi/state_spaces/JointStateSpace.h>
#include <michi/state_spaces/TurnMoveTurnStateSpace.h>
#include <michi/tools/problem/TurnMoveTurnBodies.h>
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/planners/dual_roadmap/HandTaskMap.h>
#include <michi/tools/problem/ProblemJMap.h>
#include <michi/validity/fcl/ConservativeMotionValidator.h>
#include <michi/validity/jmap/JMapMotionValidator.h>
#include <michi/validity/fcl/WorkspaceMotionValidator.h>
#include <michi/validity/grid/GridMotionValidator.h>
#include <michi/validity/spheres/SphereMotionValidator.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <mutex>
#include <tuple>
#include <sstream>

namespace ob = ompl::base;

namespace michi
{
    namespace tools
    {
        namespace
        {
            /** robot.motion turn_move_turn: turn weight defaults to the footprint's circumradius. */
            state_spaces::TurnMoveTurnStateSpacePtr makeTurnMoveTurnSpace(const Problem &problem)
            {
                const auto &b = problem.se2Bounds;
                double weight = problem.se2Motion.turnWeight;
                if (!(weight > 0.))
                    // A turn by theta moves the footprint's farthest point by up to circumradius * theta: with that
                    // weight a turn costs about what the body's motion is worth in metres.
                    weight = validity::PlanarRigidBody(problem.footprint).circumradius();
                return state_spaces::makeTurnMoveTurnStateSpace(b[0], b[1], b[2], b[3], weight,
                                                                problem.se2Motion.backward);
            }
        }  // namespace

        ob::StateSpacePtr makeStateSpace(const Problem &problem)
        {
            if (problem.kind == Problem::Kind::SE2)
            {
                const auto &b = problem.se2Bounds;
                if (problem.se2Motion.model == "turn_move_turn")
                    return makeTurnMoveTurnSpace(problem);
                return state_spaces::makeSe2StateSpace(b[0], b[1], b[2], b[3]);
            }
            std::vector<state_spaces::JointSpec> joints;
            for (int v : problem.groupVariables)
            {
                const auto &j = problem.model->variableJoint(v);
                joints.push_back(state_spaces::JointSpec{j.name, j.lower, j.upper,
                                                         j.type == validity::RobotJoint::Type::CONTINUOUS});
            }
            return state_spaces::makeJointStateSpace(joints);
        }

        namespace
        {
            void setState(ob::ScopedState<> &state, const std::vector<double> &values)
            {
                state.getSpace()->copyFromReals(state.get(), values);
                state.getSpace()->enforceBounds(state.get());  // wraps SO(2) values into [-pi, pi)
            }

            void checkEndpoint(const Problem &problem, const PlanningContext &ctx, const std::vector<double> &values,
                               const std::string &key)
            {
                ob::ScopedState<> state(ctx.setup->getStateSpace());
                setState(state, values);
                if (!ctx.setup->getSpaceInformation()->satisfiesBounds(state.get()))
                    throw ProblemError(problem.file, key, "outside the state space bounds");
                // Always FCL (the fast checker is installed later): an invalid start or goal gets an exact message
                // naming what touches what.
                const std::string collision = ctx.checker->describeCollision(values.data());
                if (!collision.empty())
                    throw ProblemError(problem.file, key, "in collision: " + collision);
            }

            /** Most states one motion check may test. OMPL's planners read their termination condition between motion
                checks, never inside one, so settings that make a single check test billions of states (a
                max_step of 0.1 mm over kilometres of bounds, a valid_segment_fraction of 1e-12, a turn weight of
                1e12 m/rad, which stretches every turn's share of the motion) hung `michi plan` past any time limit.
                A million states is about 1-10 s of FCL checks for one motion; the bundled problems need at most a few
                thousand. */
            constexpr double MAX_STATES_PER_MOTION = 1e6;

            std::string shortNumber(double value)
            {
                std::ostringstream out;
                out << std::setprecision(3) << value;
                return out.str();
            }

            /** Refuses motion-check settings under which one motion across the space would test more than
                MAX_STATES_PER_MOTION states, naming the key to change. */
            void refuseEndlessMotionChecks(const Problem &problem, const PlanningContext &ctx,
                                           const std::string &motionValidator)
            {
                if (problem.validSegmentFraction > 0. && 1. / problem.validSegmentFraction > MAX_STATES_PER_MOTION)
                    // OMPL splits a motion into distance / (fraction x extent) segments: up to 1 / fraction of them
                    // (the discrete validator, and PathGeometric::interpolate() for every validator)
                    throw ProblemError(problem.file, "collision.valid_segment_fraction",
                                       shortNumber(problem.validSegmentFraction) +
                                           " splits a motion across the space "
                                           "into up to " +
                                           shortNumber(1. / problem.validSegmentFraction) +
                                           " states to check; the smallest fraction allowed is " +
                                           shortNumber(1. / MAX_STATES_PER_MOTION) + " (a million states)");
                if (motionValidator != "workspace")
                    return;  // the conservative validator bounds its own walk; the discrete one is covered above
                // The widest motions: corner to corner of the bounds (SE(2), turning as well) or every joint from
                // its lower to its upper limit (a continuous joint half a turn), and, for an SE(2) robot, a half turn
                // on the spot (the turn-move-turn model's turn weight decides what that costs).
                std::vector<std::pair<std::vector<double>, std::vector<double>>> motions;
                const double halfTurn = M_PI - 1e-6;
                if (problem.kind == Problem::Kind::SE2)
                {
                    const auto &b = problem.se2Bounds;
                    motions.push_back({{b[0], b[2], 0.}, {b[1], b[3], halfTurn}});
                    motions.push_back({{b[0], b[3], 0.}, {b[1], b[2], -halfTurn}});
                    const double cx = 0.5 * (b[0] + b[1]), cy = 0.5 * (b[2] + b[3]);
                    motions.push_back({{cx, cy, 0.}, {cx, cy, halfTurn}});
                }
                else
                {
                    std::vector<double> from, to;
                    for (int v : problem.groupVariables)
                    {
                        const auto &j = problem.model->variableJoint(v);
                        const bool continuous = j.type == validity::RobotJoint::Type::CONTINUOUS;
                        from.push_back(continuous ? 0. : j.lower);
                        to.push_back(continuous ? halfTurn : j.upper);
                    }
                    motions.push_back({from, to});
                }
                double widest = 0., turn = 0.;
                std::vector<double> bounds;
                for (std::size_t i = 0; i < motions.size(); ++i)
                {
                    ctx.bodies->bodyDisplacementBounds(motions[i].first.data(), motions[i].second.data(), bounds);
                    for (double d : bounds)
                    {
                        widest = std::isnan(d) ? d : std::max(widest, d);
                        if (problem.kind == Problem::Kind::SE2 && i == 2)
                            turn = std::max(turn, d);
                    }
                }
                const double states = widest / problem.maxStep;
                if (!(states <= MAX_STATES_PER_MOTION))
                {
                    // The turn weight is to blame when a turn on the spot alone is too much, or when a turn weight
                    // below the footprint's circumradius r is what makes the motions too wide: a turn-move-turn motion
                    // covers its turns in a share of the distance as small as the weight, so its checks must be
                    // r / weight times denser (TurnMoveTurnBodies), and the motion would fit without that factor.
                    double reach = 0.;
                    for (const Eigen::Vector2d &p : problem.footprint)
                        reach = std::max(reach, p.norm());
                    const double w = problem.se2Motion.turnWeight;
                    const double factor = w > 0. ? std::max(1., reach / w) : 1.;
                    const bool turnWeight =
                        w > 0. && (!(turn / problem.maxStep <= MAX_STATES_PER_MOTION) ||
                                   (factor > 1. && widest / factor / problem.maxStep <= MAX_STATES_PER_MOTION));
                    if (turnWeight && !(turn / problem.maxStep <= MAX_STATES_PER_MOTION))
                        widest = turn;
                    throw ProblemError(
                        problem.file, turnWeight ? "robot.motion.turn_weight" : "collision.max_step",
                        "one motion would test up to " + shortNumber(states) + " states: the widest motion " +
                            (turnWeight
                                 ? "(the turn weight " + shortNumber(w) + " m/rad, against the footprint's reach of " +
                                       shortNumber(reach) + " m, makes it " + shortNumber(widest) + " m of motion)"
                                 : "moves the robot up to " + shortNumber(widest) + " m" +
                                       (problem.kind == Problem::Kind::SE2 ? " (robot.bounds)" : "")) +
                            " checked every " + shortNumber(problem.maxStep) + " m (collision.max_step); at most " +
                            shortNumber(MAX_STATES_PER_MOTION) + " are allowed: " +
                            (turnWeight ? "bring the turn weight nearer the footprint's reach"
                                        : "raise collision.max_step or narrow the bounds"));
                }
            }
        }  // namespace

        const std::vector<std::string> &checkerNames()
        {
            static const std::vector<std::string> names{"fcl", "jmap", "grid", "spheres"};
            return names;
        }

        namespace
        {
            /** The one place a fast checker is made and installed in the context's space (its state validity
                checker and motion validator), over the FCL checker and the problem's FCL-based motion validator
                that the context already holds. A new checker adds its branch here and its name to
                checkerNames(). */
            void installChecker(const Problem &problem, PlanningContext &ctx, const std::string &checker)
            {
                auto si = ctx.setup->getSpaceInformation();
                ctx.checkerName = checker;
                if (checker == "fcl")
                    return;
                if (checker == "jmap")
                {
                    ctx.jmap = makeJMapChecker(problem, ctx, problem.jmap);
                    ctx.setup->setStateValidityChecker(ctx.jmap);
                    // motions too: a segment on the map; what the map cannot decide goes to an exact FCL-based
                    // validator, the problem's own when it is the conservative one. A sampling one (workspace,
                    // discrete) lets a contact shallower than its step through, and the J-map's motions would be
                    // no safer than that (verify-checker on arch_3dof with the workspace validator behind the map:
                    // 63 unsafe motions in 200,000, docs/jmap.md).
                    ob::MotionValidatorPtr fallback = ctx.referenceMotions;
                    if (!std::dynamic_pointer_cast<validity::ConservativeMotionValidator>(fallback))
                        fallback = std::make_shared<validity::ConservativeMotionValidator>(si, ctx.checker);
                    si->setMotionValidator(std::make_shared<validity::JMapMotionValidator>(si, ctx.jmap, fallback));
                    return;
                }
                if (checker == "grid")
                {
                    if (problem.kind != Problem::Kind::SE2)
                        throw ProblemError(problem.file, "collision.checker",
                                           "the grid checker is for SE2 robots (robot.type se2)");
                    try
                    {
                        // the robot's heights, as its FCL body has them: obstacles above or below it stay out
                        validity::GridCheckerSettings settings = problem.grid;
                        settings.robotZMin = 0.;
                        settings.robotZMax = problem.footprintHeight;
                        ctx.grid = std::make_shared<validity::GridValidityChecker>(si, problem.footprint, ctx.scene,
                                                                                   problem.se2Bounds, settings);
                    }
                    catch (const std::invalid_argument &e)
                    {
                        // the settings of collision.grid (a resolution too fine for the map, too many headings)
                        throw ProblemError(problem.file, "collision.grid", e.what());
                    }
                    ctx.setup->setStateValidityChecker(ctx.grid);
                    si->setMotionValidator(std::make_shared<validity::GridMotionValidator>(si, ctx.grid));
                    return;
                }
                if (checker == "spheres")
                {
                    auto group = std::dynamic_pointer_cast<const validity::RobotGroupBodies>(ctx.bodies);
                    if (!group)
                        throw ProblemError(problem.file, "collision.checker",
                                           "the sphere checker is for arms (a robot.urdf), not SE2 robots");
                    // the model depends on the robot and collision.spheres only: made once (a few ms per link)
                    static std::mutex mutex;
                    static std::map<std::tuple<const validity::RobotModel *, int, std::string>,
                                    std::weak_ptr<const validity::SphereModel>>
                        models;
                    validity::SphereModelPtr model;
                    {
                        std::lock_guard<std::mutex> lock(mutex);
                        auto &cached =
                            models[{group->model().get(), problem.spheres.perLink, problem.spheres.spherizedUrdf}];
                        model = cached.lock();
                        if (!model)
                        {
                            validity::SphereModelSettings settings;
                            settings.spheresPerLink = problem.spheres.perLink;
                            try
                            {
                                model = problem.spheres.spherizedUrdf.empty()
                                            ? validity::SphereModel::enclose(*group->model(), settings)
                                            : validity::SphereModel::fromSpherizedUrdf(
                                                  *group->model(), problem.spheres.spherizedUrdf, settings);
                            }
                            catch (const validity::UrdfError &e)
                            {
                                throw ProblemError(problem.file, "collision.spheres.urdf", e.what());
                            }
                            cached = model;
                        }
                    }
                    // ctx.checker (FCL) goes in as the exact fallback: pairs the spheres cannot decide, and links whose
                    // spheres touch an obstacle.
                    ctx.spheres =
                        std::make_shared<validity::SphereValidityChecker>(si, group, model, ctx.scene, ctx.checker);
                    ctx.setup->setStateValidityChecker(ctx.spheres);
                    si->setMotionValidator(std::make_shared<validity::SphereMotionValidator>(si, ctx.spheres));
                    return;
                }
                throw std::invalid_argument("makePlanningContext: unknown checker '" + checker + "'");
            }
        }  // namespace

        void chooseExactStates(const PlanningContext &ctx, const std::vector<double> &start,
                               const std::vector<double> &goal)
        {
            if (!ctx.spheres)
                return;
            // "auto" turns FCL's settling on only where the spheres alone would make the query unsolvable, a start or
            // goal they reject (a grasp: the hand's spheres stand out of its surface into the object); the callers
            // have shown both free for FCL. Other queries keep the spheres-only speed.
            // spheresFree(): the spheres alone, whatever the previous query chose
            if (ctx.sphereExactStates != "auto" ||
                (ctx.spheres->spheresFree(start.data()) && ctx.spheres->spheresFree(goal.data())))
            {
                ctx.spheres->setExactStates(ctx.sphereExactStates == "on");
                return;
            }
            // FCL settles only what the spheres, grown by a margin, touch at the start and the goal (the object
            // grasped, the shelf beside it), so that the states leading there are not refused; contacts elsewhere
            // are left to the spheres, as in a query that needs no settling
            auto contacts = ctx.spheres->sphereContacts(start.data(), EXACT_CONTACT_MARGIN);
            const auto atGoal = ctx.spheres->sphereContacts(goal.data(), EXACT_CONTACT_MARGIN);
            contacts.obstacles.insert(contacts.obstacles.end(), atGoal.obstacles.begin(), atGoal.obstacles.end());
            contacts.selfPairs.insert(contacts.selfPairs.end(), atGoal.selfPairs.begin(), atGoal.selfPairs.end());
            std::sort(contacts.obstacles.begin(), contacts.obstacles.end());
            contacts.obstacles.erase(std::unique(contacts.obstacles.begin(), contacts.obstacles.end()),
                                     contacts.obstacles.end());
            std::sort(contacts.selfPairs.begin(), contacts.selfPairs.end());
            contacts.selfPairs.erase(std::unique(contacts.selfPairs.begin(), contacts.selfPairs.end()),
                                     contacts.selfPairs.end());
            ctx.spheres->setExactContacts(std::move(contacts));
        }

        PlanningContext makePlanningContext(const Problem &problem, std::size_t query)
        {
            ContextOptions options;
            options.query = query;
            return makePlanningContext(problem, options);
        }

        PlanningContext makePlanningContext(const Problem &problem, const ContextOptions &options)
        {
            const bool ownQuery = !options.start.empty() || !options.goal.empty();
            if (ownQuery && (options.start.size() != problem.dimension() || options.goal.size() != problem.dimension()))
                throw ProblemError(
                    problem.file, "start",
                    "a query needs start and goal of " + std::to_string(problem.dimension()) + " values");
            const std::size_t query = options.query;
            if (!ownQuery && query >= problem.queries.size())
                throw ProblemError(problem.file, "queries",
                                   "query " + std::to_string(query) + " requested, the file has " +
                                       std::to_string(problem.queries.size()));
            const std::string checker = options.checker.empty() ? problem.checker : options.checker;
            const std::string motionValidator =
                options.motionValidator.empty() ? problem.motionValidator : options.motionValidator;
            const auto &names = checkerNames();
            if (std::find(names.begin(), names.end(), checker) == names.end())
            {
                std::string list;
                for (const auto &n : names)
                    list += (list.empty() ? "" : ", ") + n;
                throw std::invalid_argument("makePlanningContext: checker must be one of " + list + ", got '" +
                                            checker + "'");
            }
            PlanningContext ctx;
            ctx.scene = options.scene ? options.scene : problem.scene;
            ctx.fixedValues = options.fixedValues.empty() ? problem.fixedValues : options.fixedValues;
            if (problem.kind == Problem::Kind::ARM && ctx.fixedValues.size() != problem.model->variableCount())
                throw std::invalid_argument("makePlanningContext: fixed values for " +
                                            std::to_string(ctx.fixedValues.size()) + " joints, the robot has " +
                                            std::to_string(problem.model->variableCount()));
            if (problem.kind == Problem::Kind::ARM)
                problem.model->applyMimic(ctx.fixedValues);  // the pictures and reports use these values too
            ctx.bodies = problem.kind == Problem::Kind::ARM
                             ? std::make_shared<validity::RobotGroupBodies>(problem.model, problem.groupVariables,
                                                                            ctx.fixedValues)
                             : problem.bodies();
            ctx.setup = std::make_shared<ompl::geometric::SimpleSetup>(makeStateSpace(problem));
            if (auto tmt = std::dynamic_pointer_cast<state_spaces::TurnMoveTurnStateSpace>(ctx.setup->getStateSpace()))
                if (auto body = std::dynamic_pointer_cast<const validity::PlanarRigidBody>(ctx.bodies))
                    ctx.bodies = std::make_shared<TurnMoveTurnBodies>(body, tmt);  // bounds of turn-move-turn motions
            auto si = ctx.setup->getSpaceInformation();
            ctx.checker = std::make_shared<validity::FclValidityChecker>(si, ctx.bodies, ctx.scene);
            ctx.setup->setStateValidityChecker(ctx.checker);
            if (motionValidator == "conservative")
                si->setMotionValidator(std::make_shared<validity::ConservativeMotionValidator>(si, ctx.checker));
            else if (motionValidator == "workspace")
                si->setMotionValidator(
                    std::make_shared<validity::WorkspaceMotionValidator>(si, ctx.checker, problem.maxStep));
            // "discrete": SpaceInformation's own DiscreteMotionValidator
            // Otherwise OMPL's default resolution (1 % of the space's extent) stays.
            if (problem.validSegmentFraction > 0.)
                si->setStateValidityCheckingResolution(problem.validSegmentFraction);
            si->setup();  // the space's value locations (copyFromReals) exist only after setup
            refuseEndlessMotionChecks(problem, ctx, motionValidator);
            // Kept before installChecker() replaces it: the J-map validator hands what the map cannot decide to this
            // FCL-based one.
            ctx.referenceMotions = si->getMotionValidator();

            const Query q = ownQuery ? Query{options.start, options.goal, {}, {}} : problem.queries[query];
            checkEndpoint(problem, ctx, q.start, ownQuery ? "start" : queryEndKey(problem, query, "start"));
            checkEndpoint(problem, ctx, q.goal, ownQuery ? "goal" : queryEndKey(problem, query, "goal"));
            ob::ScopedState<> start(ctx.setup->getStateSpace()), goal(ctx.setup->getStateSpace());
            setState(start, q.start);
            setState(goal, q.goal);
            // After the endpoint checks, so they stay FCL's whatever the checker.
            installChecker(problem, ctx, checker);
            ctx.sphereExactStates = problem.spheres.exactStates;
            chooseExactStates(ctx, q.start, q.goal);
            // The fast checkers are conservative: an end they refuse (FCL accepted it above) would otherwise show
            // only as OMPL's "Invalid start" after the whole time limit.
            if (ctx.checkerName != "fcl")
                for (const auto *values : {&q.start, &q.goal})
                {
                    ob::ScopedState<> s(ctx.setup->getStateSpace());
                    setState(s, *values);
                    if (si->isValid(s.get()))
                        continue;
                    std::string at;
                    for (double v : *values)
                        at += (at.empty() ? "" : ", ") + shortNumber(v);
                    const std::string why =
                        ctx.grid ? "the grid checker's conservative table calls it invalid (its cell or heading bin "
                                   "comes close to an obstacle)"
                                 : "the " + ctx.checkerName + " checker, which is conservative, calls it invalid";
                    const std::string help =
                        ctx.grid ? "a finer collision.grid.resolution or more headings help. " + ctx.grid->describe()
                        : ctx.spheres ? std::string("collision.spheres.exact_states auto or on lets FCL settle it")
                                      : std::string("plan with --checker fcl, or move it away from the obstacles");
                    OMPL_WARN("%s: %s (%s) is free for FCL but %s: planners will not %s it; %s", problem.file.c_str(),
                              values == &q.start ? "start" : "goal", at.c_str(), why.c_str(),
                              values == &q.start ? "start from" : "reach", help.c_str());
                }
            // no SimpleSetup::setup() here: without a planner it would pick OMPL's default one
            ctx.setup->setStartAndGoalStates(start, goal);
            // benchmark.objective: on the problem definition, where OMPL's optimizing planners (RRT*, BIT*, ...)
            // and michi's ConcentricCircle read it; without one they keep their defaults (path length)
            if (problem.benchmark.objective == "clearance")
                ctx.setup->setOptimizationObjective(std::make_shared<ob::MaximizeMinClearanceObjective>(si));
            else if (problem.benchmark.objective == "length")
                ctx.setup->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));
            return ctx;
        }

        std::string outsideDeclaredRange(const std::string &value, const std::string &range)
        {
            // OMPL declares ranges as "lower:upper" or "lower:step:upper" (numbers) or "0,1" (a flag); planners do
            // not check them themselves, so a value such as divisions: -1 used to be taken as given
            std::vector<std::string> parts;
            std::stringstream in(range);
            for (std::string part; std::getline(in, part, ':');)
                parts.push_back(part);
            // A flag's range ("0,1") or anything else that is not lower:upper or lower:step:upper holds no bounds to
            // test.
            if (parts.size() < 2 || parts.size() > 3)
                return "";
            double lower = 0., upper = 0., v = 0.;
            try
            {
                lower = problem_file::Reader::parseNumber(parts.front());
                upper = problem_file::Reader::parseNumber(parts.back());
            }
            catch (const std::exception &)
            {
                return "";  // not a numeric range: nothing to hold the value to
            }
            try
            {
                v = problem_file::Reader::parseNumber(value);
            }
            catch (const std::exception &)
            {
                return "is not a number";
            }
            if (v < lower || v > upper)
                return "is outside the declared range";
            return "";
        }

        void applyPlannerParams(ob::Planner &planner, const PlannerSpec &spec, const std::string &file,
                                const std::string &keyPrefix)
        {
            for (const auto &kv : spec.params)
            {
                // where the file sets it: under the planner's entry, or under the key the caller names
                const std::string where =
                    (keyPrefix.empty() ? "planners." + spec.name + ".params" : keyPrefix) + "." + kv.first;
                auto &params = planner.params();
                if (!params.hasParam(kv.first))
                {
                    std::vector<std::string> names;
                    params.getParamNames(names);
                    std::ostringstream known;
                    for (std::size_t i = 0; i < names.size(); ++i)
                        known << (i ? ", " : "") << names[i];
                    throw ProblemError(file, where,
                                       "unknown parameter of " + planner.getName() + " (known: " + known.str() + ")");
                }
                const std::string range = params[kv.first].getRangeSuggestion();
                const std::string problem = outsideDeclaredRange(kv.second, range);
                if (!problem.empty())
                    throw ProblemError(file, where,
                                       "value '" + kv.second + "' " + problem + " of " + planner.getName() +
                                           " (declared range " + range + ")");
                // The value as the parameter's type reads it: OMPL converts with a lexical cast that truncates 8.5
                // for an integer and takes 2 or -1 for a flag, and that cannot read the forms michi's numbers allow
                // (pi/4, 1e3 for an integer); a number is handed over in plain decimal.
                const ob::GenericParam *param = params.getParams().at(kv.first).get();
                std::string value = kv.second;
                if (dynamic_cast<const ob::SpecificParam<bool> *>(param) != nullptr)
                {
                    if (value != "0" && value != "1" && value != "true" && value != "false")
                        throw ProblemError(
                            file, where,
                            "value '" + value + "' of " + planner.getName() + ": expected 0, 1, true or false");
                }
                else
                {
                    const bool integer = dynamic_cast<const ob::SpecificParam<int> *>(param) != nullptr ||
                                         dynamic_cast<const ob::SpecificParam<unsigned int> *>(param) != nullptr ||
                                         dynamic_cast<const ob::SpecificParam<long> *>(param) != nullptr ||
                                         dynamic_cast<const ob::SpecificParam<unsigned long> *>(param) != nullptr;
                    const bool real = dynamic_cast<const ob::SpecificParam<double> *>(param) != nullptr ||
                                      dynamic_cast<const ob::SpecificParam<float> *>(param) != nullptr;
                    if (integer || real)
                    {
                        double v = 0.;
                        try
                        {
                            v = problem_file::Reader::parseNumber(value);
                        }
                        catch (const std::exception &)
                        {
                            throw ProblemError(file, where,
                                               "value '" + value + "' of " + planner.getName() + ": expected a number");
                        }
                        if (integer && (v != std::floor(v) || std::abs(v) > 9e15))
                            throw ProblemError(
                                file, where, "value '" + value + "' of " + planner.getName() + ": expected an integer");
                        std::ostringstream plain;
                        plain << std::setprecision(17) << v;
                        value = integer ? std::to_string(static_cast<long long>(v)) : plain.str();
                    }
                }
                bool accepted = false;
                try
                {
                    accepted = params.setParam(kv.first, value);
                }
                catch (const std::exception &e)
                {
                    throw ProblemError(file, where,
                                       "value '" + kv.second + "' rejected by " + planner.getName() + ": " + e.what());
                }
                if (!accepted)
                    throw ProblemError(file, where,
                                       "value '" + kv.second + "' rejected by " + planner.getName() + " (range " +
                                           params[kv.first].getRangeSuggestion() + ")");
            }
        }

        void refuseKnownCrashes(const Problem &problem, const std::string &name, const ob::SpaceInformation &si)
        {
            // Pairs with which Debian's OMPL 1.5.2 takes the process down, refused before any run starts.
            // FMT* and BFMT* do dynamic programming over their sampled graph, for a path cost that adds up along the
            // path; with MaximizeMinClearanceObjective they find no path, and FMT's destructor then frees one of
            // its motions twice (valgrind: FMT::freeMemory; a segfault on planar_2link), BFMT ran 35-47 s past a
            // 0.5 s limit on se2_corridor.
            if (problem.benchmark.objective == "clearance" && (name == "geometric::FMT" || name == "geometric::BFMT"))
                throw ProblemError(problem.file, "benchmark.objective",
                                   name +
                                       " cannot optimise clearance (OMPL 1.5.2's FMT* and BFMT* assume a path cost "
                                       "that adds up along the path, and crash on this one): use the length "
                                       "objective, or RRT*, BIT* or another optimizing planner for clearance");
            // LBTRRT's lower-bound graph aborts on an assertion (DynamicSSSP::addEdge) with the turn-move-turn
            // distance, on every bundled turn_move_turn problem
            if (name == "geometric::LBTRRT" &&
                dynamic_cast<const state_spaces::TurnMoveTurnStateSpace *>(si.getStateSpace().get()) != nullptr)
                throw ProblemError(problem.file, "robot.motion",
                                   "geometric::LBTRRT aborts on the turn_move_turn state space (an assertion in "
                                   "OMPL 1.5.2's DynamicSSSP): use motion: free, or another planner");
            // Not a crash, but the same kind of mismatch: the lattice is made of (x, y, heading) nodes, and on any
            // other space its setup() fails, which a benchmark reported as "no path" in every run.
            if (name == "michi::HeadingLattice" && problem.kind != Problem::Kind::SE2)
                throw ProblemError(problem.file, "robot.type",
                                   "michi::HeadingLattice plans for SE(2) robots only (robot.type: se2), not for "
                                   "an arm's joints");
        }

        ob::PlannerPtr makePlanner(const Problem &problem, const std::string &name, const ob::SpaceInformationPtr &si,
                                   const std::map<std::string, std::string> &extra)
        {
            PlannerSpec spec{name, {}, {}};
            for (const auto &s : problem.planners)
                if (s.name == name)
                    spec = s;
            // extra, the caller's values, wins over the problem file's for the same parameter.
            for (const auto &kv : extra)
                spec.params[kv.first] = kv.second;
            ob::PlannerPtr planner = allocatePlanner(name, si);  // std::invalid_argument for an unknown name
            refuseKnownCrashes(problem, name, *si);
            applyPlannerParams(*planner, spec, problem.file);
            // DualRoadmap's task level needs the arm's hand, which a planner made from si alone cannot know
            if (auto dual = std::dynamic_pointer_cast<planners::DualRoadmap>(planner))
                if (auto bodies = planners::checkerBodies(si->getStateValidityChecker()))
                    dual->setTaskMap(planners::handTaskMap(bodies, si->getStateSpace()));
            return planner;
        }
    }  // namespace tools
}  // namespace michi
