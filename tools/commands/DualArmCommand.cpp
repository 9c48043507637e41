#include <michi/tools/commands/DualArmCommand.h>
#include <michi/tools/FileOutput.h>

#include <michi/planners/dual_arm/ManipulabilityObjective.h>
#include <michi/tools/pictures/DualArmPicture.h>
#include <michi/tools/problem/DualArmProblem.h>
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/pictures/SvgPlot.h>
#include <michi/tools/viewer/ReplayPage.h>

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace fs = boost::filesystem;

namespace michi
{
    namespace tools
    {
        namespace
        {
            double secondsSince(std::chrono::steady_clock::time_point since)
            {
                return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
            }

            std::string vec(const Eigen::Vector3d &v)
            {
                std::ostringstream s;
                s << std::setprecision(6) << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
                return s.str();
            }

            std::string list(const std::vector<double> &v)
            {
                std::ostringstream s;
                s << std::setprecision(6) << "[";
                for (std::size_t i = 0; i < v.size(); ++i)
                    s << (i ? ", " : "") << v[i];
                s << "]";
                return s.str();
            }

            std::vector<double> groupValues(const std::vector<double> &full, const std::vector<int> &vars)
            {
                std::vector<double> v;
                for (int i : vars)
                    v.push_back(full[i]);
                return v;
            }

            /** Share of each joint in the total joint motion. */
            std::vector<double> shares(const std::vector<double> &motion)
            {
                double total = 0.;
                for (double m : motion)
                    total += m;
                std::vector<double> s;
                for (double m : motion)
                    s.push_back(total > 0. ? m / total : 0.);
                return s;
            }

            /** Context options: the other arm fixed at \e fixed and one query start -> goal of the group. */
            ContextOptions withQuery(const std::vector<double> &fixed, const std::vector<double> &start,
                                     const std::vector<double> &goal)
            {
                ContextOptions options;
                options.fixedValues = fixed;
                options.start = start;
                options.goal = goal;
                return options;
            }

            struct PathReport
            {
                bool solved{false};
                std::string status;
                std::vector<std::vector<double>> states;  ///< group values, interpolated
                double minW{0.}, meanW{0.}, length{0.}, manipulabilityCost{0.}, lengthCost{0.};
                std::vector<double> jointMotion;
                unsigned int invalidMotions{0};
                std::shared_ptr<PathReport> raw;  ///< the planner's path before simplification
            };

            /** Evaluate a path of group values: w at each state, joint motion, both objectives' costs, OMPL's
                motion validator on every segment. */
            void evaluate(const ompl::base::SpaceInformationPtr &si, const planners::ManipulabilityObjective &manip,
                          const std::vector<std::vector<double>> &states, PathReport &r)
            {
                r.states = states;
                ompl::base::PathLengthOptimizationObjective lengthObjective(si);
                r.minW = std::numeric_limits<double>::infinity();
                r.meanW = 0.;
                r.length = 0.;
                r.jointMotion.assign(states.empty() ? 0 : states[0].size(), 0.);
                ompl::base::Cost mc = manip.identityCost(), lc = lengthObjective.identityCost();
                auto *a = si->allocState();
                auto *b = si->allocState();
                for (std::size_t i = 0; i < states.size(); ++i)
                {
                    si->getStateSpace()->copyFromReals(b, states[i]);
                    // Both objectives' costs are computed for every path, whichever objective planned it, so the two
                    // plans compare on the same scales.
                    const double w = manip.manipulability(b);
                    r.minW = std::min(r.minW, w);
                    r.meanW += w / static_cast<double>(states.size());
                    if (i > 0)
                    {
                        r.length += si->distance(a, b);
                        for (std::size_t j = 0; j < states[i].size(); ++j)
                            r.jointMotion[j] += std::abs(states[i][j] - states[i - 1][j]);
                        mc = manip.combineCosts(mc, manip.motionCost(a, b));
                        lc = lengthObjective.combineCosts(lc, lengthObjective.motionCost(a, b));
                        // OMPL's own motion validator on each segment: the report says whether a path (or the IK
                        // stirring motion, which no planner made) is valid as OMPL sees it.
                        if (!si->checkMotion(a, b))
                            ++r.invalidMotions;
                    }
                    std::swap(a, b);
                }
                si->freeState(a);
                si->freeState(b);
                r.manipulabilityCost = mc.value();
                r.lengthCost = lc.value();
            }

            PathReport plan(const Problem &problem, const planners::ArmChain &small, const DualArmSpec &spec,
                            const std::vector<double> &fixed, const std::vector<double> &start,
                            const std::vector<double> &goal, bool manipulability, double time)
            {
                PathReport r;
                PlanningContext ctx = makePlanningContext(problem, withQuery(fixed, start, goal));
                const auto si = ctx.setup->getSpaceInformation();
                auto manip = std::make_shared<planners::ManipulabilityObjective>(
                    si, small, problem.groupVariables, fixed, spec.settings.rows, spec.settings.threshold);
                manip->setWeight(spec.weight);
                ompl::base::OptimizationObjectivePtr objective = manip;
                if (!manipulability)
                    objective = std::make_shared<ompl::base::PathLengthOptimizationObjective>(si);
                ctx.setup->setOptimizationObjective(objective);
                ctx.setup->setPlanner(allocatePlanner(spec.planner, si));
                const auto status = ctx.setup->solve(time);
                r.status = status.asString();
                r.solved = status == ompl::base::PlannerStatus::EXACT_SOLUTION;
                if (!r.solved)
                    return r;
                const auto statesOf = [&si](ompl::geometric::PathGeometric path)
                {
                    // States about 0.02 apart in joint space: the minimum and mean manipulability are read along the
                    // path, not only at its few waypoints.
                    path.interpolate(
                        std::max<unsigned int>(2, static_cast<unsigned int>(std::ceil(path.length() / 0.02))));
                    std::vector<std::vector<double>> states;
                    for (const auto *s : path.getStates())
                    {
                        std::vector<double> v;
                        si->getStateSpace()->copyToReals(v, s);
                        states.push_back(v);
                    }
                    return states;
                };
                ompl::geometric::PathGeometric path = ctx.setup->getSolutionPath();
                // The raw path is reported too: after simplification both objectives can end on the same straight
                // line (dual-arm.md), which would hide what the objective did.
                r.raw = std::make_shared<PathReport>();
                r.raw->solved = true;
                r.raw->status = "as planned";
                evaluate(si, *manip, statesOf(path), *r.raw);
                // shortcut and smooth with the same objective (a change is kept only when it lowers that cost)
                ompl::geometric::PathSimplifier simplifier(si, ctx.setup->getProblemDefinition()->getGoal(), objective);
                simplifier.simplify(path, 0.5 * time);
                const std::vector<std::vector<double>> states = statesOf(path);
                evaluate(si, *manip, states, r);
                return r;
            }

            /** The stirring motion checked and costed through OMPL (the large arm fixed where it holds the cup). */
            PathReport checkStirring(const Problem &problem, const planners::ArmChain &small, const DualArmSpec &spec,
                                     const planners::StirringMotion &m)
            {
                PathReport r;
                if (!m.valid)
                {
                    r.status = m.failure;
                    return r;
                }
                std::vector<std::vector<double>> states;
                for (const auto &q : m.states)
                    states.push_back(groupValues(q, problem.groupVariables));
                PlanningContext ctx =
                    makePlanningContext(problem, withQuery(m.states.front(), states.front(), states.back()));
                const auto si = ctx.setup->getSpaceInformation();
                planners::ManipulabilityObjective manip(si, small, problem.groupVariables, m.states.front(),
                                                        spec.settings.rows, spec.settings.threshold);
                evaluate(si, manip, states, r);
                r.solved = r.invalidMotions == 0;
                r.status = r.solved ? "valid" : std::to_string(r.invalidMotions) + " motions invalid";
                return r;
            }

            std::string pathJson(const PathReport &r, const std::string &indent)
            {
                std::ostringstream s;
                s << std::setprecision(6) << "{\n"
                  << indent << "  \"solved\": " << (r.solved ? "true" : "false") << ",\n"
                  << indent << "  \"status\": " << jsonString(r.status);
                if (!r.states.empty())
                    s << ",\n"
                      << indent << "  \"states\": " << r.states.size() << ",\n"
                      << indent << "  \"min_manipulability\": " << r.minW << ",\n"
                      << indent << "  \"mean_manipulability\": " << r.meanW << ",\n"
                      << indent << "  \"joint_space_length\": " << r.length << ",\n"
                      << indent << "  \"manipulability_cost\": " << r.manipulabilityCost << ",\n"
                      << indent << "  \"joint_motion\": " << list(r.jointMotion) << ",\n"
                      << indent << "  \"joint_motion_share\": " << list(shares(r.jointMotion)) << ",\n"
                      << indent << "  \"invalid_motions\": " << r.invalidMotions;
                if (r.raw)
                    s << ",\n" << indent << "  \"before_simplification\": " << pathJson(*r.raw, indent + "  ");
                s << "\n" << indent << "}";
                return s.str();
            }
        }  // namespace

        std::string runDualArm(const Problem &problem, const DualArmOptions &options)
        {
            if (options.outDir.empty())
                throw std::invalid_argument("no output folder given");
            const auto start = std::chrono::steady_clock::now();
            const DualArmSpec spec = loadDualArmSpec(problem);
            std::ostream *log = options.progress;
            std::vector<double> home = problem.fixedValues;
            for (std::size_t i = 0; i < problem.groupVariables.size(); ++i)
                // Home: the problem's fixed joints, with the small arm at query 0's start (its rest pose, where
                // approaches begin).
                home[problem.groupVariables[i]] = problem.queries[0].start[i];

            planners::DualArmWorkspace ws(problem.model, makeArmTask(problem, spec.large, "large"),
                                          makeArmTask(problem, spec.small, "small"), home, spec.settings);
            if (log)
                *log << "michi dualarm: work spaces on a " << spec.settings.resolution << " m grid" << std::endl;
            ws.compute();
            const auto &small = ws.small().arm;
            if (log)
                *log << "michi dualarm: common work space " << ws.count(planners::DualArmWorkspace::COMMON)
                     << " cells, stirring area " << ws.count(planners::DualArmWorkspace::STIR) << " cells ("
                     << ws.workspaceSeconds() + ws.stirSeconds() << " s)" << std::endl;

            // stirring at B (manipulability criterion) and at A (work space only, as in the paper's first try)
            const planners::StirringMotion stirB = ws.stir(ws.typeBPosition(), ws.typeBConfiguration());
            const planners::StirringMotion stirA = ws.stir(ws.typeAPosition(), ws.typeAConfiguration());
            // B is the answer of the analysis: a stirring motion that fails there is an error, while a failure at A is
            // a result.
            if (!stirB.valid)
                throw std::runtime_error("the stirring motion at the type B position fails: " + stirB.failure);
            const PathReport checkB = checkStirring(problem, small, spec, stirB);
            const PathReport checkA = checkStirring(problem, small, spec, stirA);

            // approach motions of the small arm from home, planned with OMPL with and without the objective
            const double time = options.planningTime > 0. ? options.planningTime : spec.planningTime;
            const auto homeGroup = groupValues(home, problem.groupVariables);
            std::vector<double> fixedA = ws.typeAConfiguration(), fixedB = stirB.states.front();
            for (std::size_t i = 0; i < problem.groupVariables.size(); ++i)
            {
                // The large arm at its work pose, the small arm's own values replaced by home: only the small arm moves
                // in these plans.
                fixedA[problem.groupVariables[i]] = homeGroup[i];
                fixedB[problem.groupVariables[i]] = homeGroup[i];
            }
            if (log)
                *log << "michi dualarm: planning the approach motions with " << spec.planner << " (" << time
                     << " s each)" << std::endl;
            const auto goalA = groupValues(ws.typeAConfiguration(), problem.groupVariables);
            const auto goalB = groupValues(stirB.states.front(), problem.groupVariables);
            // Each approach planned twice, with the manipulability objective and with path length, under the same
            // planner and time, so the difference is the objective's.
            const PathReport handoverWith = plan(problem, small, spec, fixedA, homeGroup, goalA, true, time);
            const PathReport handoverWithout = plan(problem, small, spec, fixedA, homeGroup, goalA, false, time);
            const PathReport stirStartWith = plan(problem, small, spec, fixedB, homeGroup, goalB, true, time);
            const PathReport stirStartWithout = plan(problem, small, spec, fixedB, homeGroup, goalB, false, time);

            std::vector<std::string> jointNames;
            for (int v : small.variables())
                jointNames.push_back(problem.model->variableJoint(static_cast<std::size_t>(v)).name);
            std::ostringstream json;
            json << std::setprecision(6) << "{\n"
                 << "  \"problem\": " << jsonString(problem.name) << ",\n"
                 << "  \"configuration_joint_names\": [";
            const auto names = problem.model->variableNames();
            for (std::size_t i = 0; i < names.size(); ++i)
                json << (i ? ", " : "") << jsonString(names[i]);
            json << "],\n"
                 << "  \"type_a_position\": " << vec(ws.typeAPosition()) << ",\n"
                 << "  \"type_a_centroid\": " << vec(ws.typeACentroid()) << ",\n"
                 << "  \"type_a_configuration\": " << list(ws.typeAConfiguration()) << ",\n"
                 << "  \"type_b_position\": " << vec(ws.typeBPosition()) << ",\n"
                 << "  \"type_b_centroid\": " << vec(ws.typeBCentroid()) << ",\n"
                 << "  \"type_b_configuration\": " << list(ws.typeBConfiguration()) << ",\n"
                 << "  \"paper_handover_position\": "
                 << vec(Eigen::Vector3d(spec.paperHandover[0], spec.paperHandover[1], spec.paperHandover[2])) << ",\n"
                 << "  \"resolution\": " << spec.settings.resolution << ",\n"
                 << "  \"grid_cells\": " << ws.grid().cells() << ",\n"
                 << "  \"large_workspace_volume_m3\": " << ws.volume(planners::DualArmWorkspace::REACH_LARGE) << ",\n"
                 << "  \"small_workspace_volume_m3\": " << ws.volume(planners::DualArmWorkspace::REACH_SMALL) << ",\n"
                 << "  \"common_workspace_volume_m3\": " << ws.volume(planners::DualArmWorkspace::COMMON) << ",\n"
                 << "  \"manipulability_area_volume_m3\": " << ws.volume(planners::DualArmWorkspace::AREA) << ",\n"
                 << "  \"stirring_area_volume_m3\": " << ws.volume(planners::DualArmWorkspace::STIR) << ",\n"
                 << "  \"threshold\": " << spec.settings.threshold << ",\n"
                 << "  \"manipulability_rows\": "
                 << (spec.settings.rows == planners::ManipulabilityRows::POSITION ? "\"position\"" : "\"full\"")
                 << ",\n"
                 << "  \"stirring_side\": " << spec.settings.stirSide << ",\n"
                 << "  \"stirring_states\": " << stirB.states.size() << ",\n"
                 << "  \"small_joint_names\": [";
            for (std::size_t i = 0; i < jointNames.size(); ++i)
                json << (i ? ", " : "") << jsonString(jointNames[i]);
            json << "],\n"
                 << "  \"min_manipulability_stirring\": " << stirB.minManipulability << ",\n"
                 << "  \"joint_motion_stirring\": " << list(stirB.jointMotion) << ",\n"
                 << "  \"joint_motion_share_stirring\": " << list(shares(stirB.jointMotion)) << ",\n"
                 << "  \"stirring\": " << pathJson(checkB, "  ") << ",\n"
                 << "  \"stirring_without_criterion\": " << pathJson(checkA, "  ") << ",\n"
                 << "  \"planner\": " << jsonString(spec.planner) << ",\n"
                 << "  \"planning_time\": " << time << ",\n"
                 << "  \"objective_weight\": " << spec.weight << ",\n"
                 << "  \"handover_approach_with_manipulability\": " << pathJson(handoverWith, "  ") << ",\n"
                 << "  \"handover_approach_path_length\": " << pathJson(handoverWithout, "  ") << ",\n"
                 << "  \"stirring_approach_with_manipulability\": " << pathJson(stirStartWith, "  ") << ",\n"
                 << "  \"stirring_approach_path_length\": " << pathJson(stirStartWithout, "  ") << ",\n"
                 << "  \"workspace_seconds\": " << ws.workspaceSeconds() << ",\n"
                 << "  \"stirring_area_seconds\": " << ws.stirSeconds() << ",\n"
                 << "  \"total_seconds\": " << secondsSince(start) << "\n"
                 << "}\n";

            // staged output: nothing in DIR unless everything was written
            StagedDirectory stage(options.outDir);
            std::vector<DualArmJointPlot> plots;
            auto toPlot = [&](const std::string &label, const planners::StirringMotion &m)
            {
                DualArmJointPlot p{label, {}};
                for (const auto &q : m.states)
                    p.values.push_back(groupValues(q, problem.groupVariables));
                plots.push_back(p);
            };
            toPlot("stirring at type B (manipulability area)", stirB);
            if (stirA.valid)
                toPlot("stirring at type A (work space centroid, no manipulability)", stirA);
            writeDualArmPictures(ws, stage.path("dualarm-workspace.svg").string(),
                                 stage.path("dualarm-manipulability.svg").string(),
                                 stage.path("dualarm-stirring.svg").string(), plots, problem.name);
            for (const char *name : {"dualarm-workspace", "dualarm-manipulability", "dualarm-stirring"})
                if (!svgToPng(stage.path(std::string(name) + ".svg").string(),
                              stage.path(std::string(name) + ".png").string()))
                    throw std::runtime_error(std::string("cannot render ") + name +
                                             ".png (is rsvg-convert installed? scripts/setup.sh installs it)");
            writeAtomically(json.str(), stage.path("dualarm.json").string());
            if (options.html)
            {
                // one page shows one configuration of the other joints: the stirring task's, the large arm at B
                std::vector<PlotPath> paths;
                if (stirStartWith.solved)
                    paths.push_back({"approach to stirring, manipulability objective", stirStartWith.states});
                if (stirStartWithout.solved)
                    paths.push_back({"approach to stirring, path length objective", stirStartWithout.states});
                PlotPath stirring{"stirring at type B", {}};
                for (const auto &q : stirB.states)
                    stirring.states.push_back(groupValues(q, problem.groupVariables));
                paths.push_back(stirring);
                ReplayOptions replay;
                replay.fixedValues = fixedB;
                writeReplayPage(problem, paths, stage.path(problem.name + ".html").string(), replay);
            }
            else
                // a page from an earlier run with --html would show another run's motions beside these results
                stage.removeStale(problem.name + ".html", REPLAY_PAGE_MARK);
            stage.commit();
            return json.str();
        }
    }  // namespace tools
}  // namespace michi
