#include <michi/tools/problem/DualArmProblem.h>
#include "ProblemYaml.h"
#include <michi/tools/bench/PlannerRegistry.h>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace michi
{
    namespace tools
    {
        namespace
        {
            /** The dual_arm section through the problem file's own Reader (numbers, keys, errors naming the file
                and key); only what this section adds is here. */
            class SectionReader : public problem_file::Reader
            {
            public:
                using problem_file::Reader::Reader;

                void keys(const YAML::Node &n, const std::string &key, const std::set<std::string> &known) const
                {
                    // Checked here: Reader::keys() skips a node that is not a mapping, leaving that report to its
                    // caller.
                    if (!n.IsMap())
                        fail(key, "expected a mapping");
                    Reader::keys(n, key, known);
                }
                double positive(const YAML::Node &n, const std::string &key) const
                {
                    const double v = number(n, key);
                    if (!(v > 0.))
                        fail(key, "expected a positive number");
                    return v;
                }
                unsigned int count(const YAML::Node &n, const std::string &key) const
                {
                    const unsigned int v = Reader::count(n, key);
                    if (v > 10000000u)
                        fail(key, "expected a positive integer up to 10000000");
                    return v;
                }
                Eigen::Vector3d vector(const YAML::Node &n, const std::string &key) const
                {
                    const auto v = coordinates(n, key, 3);
                    return Eigen::Vector3d(v[0], v[1], v[2]);
                }
                Eigen::Vector3d unit(const YAML::Node &n, const std::string &key) const
                {
                    const Eigen::Vector3d v = vector(n, key);
                    if (v.norm() < 1e-9)
                        fail(key, "expected a non-zero direction");
                    // Directions are normalized here, so a file may write [0, 0, -2] for straight down.
                    return v.normalized();
                }
            };

            DualArmArmSpec readArm(const SectionReader &r, const YAML::Node &n, const std::string &key,
                                   const Problem &problem)
            {
                r.keys(n, key, {"tip", "tool_point", "hand"});
                DualArmArmSpec arm;
                if (!n["tip"])
                    r.fail(key + ".tip", "missing (required)");
                arm.tip = r.text(n["tip"], key + ".tip");
                try
                {
                    problem.model->linkIndex(arm.tip);
                }
                catch (const std::exception &)
                {
                    r.fail(key + ".tip", "no link '" + arm.tip + "' in the robot");
                }
                if (n["tool_point"])
                    arm.toolPoint = r.vector(n["tool_point"], key + ".tool_point");
                if (!n["hand"])
                    r.fail(key + ".hand",
                           "missing (required: {tool_axis: [x, y, z], along: [x, y, z]} or "
                           "{tool_axis: [...], perpendicular_to: [...]})");
                const YAML::Node h = n["hand"];
                const std::string hk = key + ".hand";
                r.keys(h, hk, {"tool_axis", "along", "perpendicular_to"});
                if (h["tool_axis"])
                    arm.hand.toolAxis = r.unit(h["tool_axis"], hk + ".tool_axis");
                // Two hand constraints at once would contradict each other (or one would be silently ignored).
                if (static_cast<bool>(h["along"]) == static_cast<bool>(h["perpendicular_to"]))
                    r.fail(hk, "give exactly one of along and perpendicular_to");
                if (h["along"])
                {
                    arm.hand.mode = planners::HandTarget::Mode::AXIS_ALONG;
                    arm.hand.direction = r.unit(h["along"], hk + ".along");
                }
                else
                {
                    arm.hand.mode = planners::HandTarget::Mode::AXIS_PERPENDICULAR;
                    arm.hand.direction = r.unit(h["perpendicular_to"], hk + ".perpendicular_to");
                }
                return arm;
            }
        }  // namespace

        DualArmSpec loadDualArmSpec(const Problem &problem)
        {
            SectionReader r(problem.file);
            // parsed once, by loadProblem(); only this section is copied
            const YAML::Node n = problem_file::loadYamlSection(problem.file, "dual_arm");
            if (problem.kind != Problem::Kind::ARM)
                r.fail("robot", "the dual-arm analysis needs a URDF robot");
            if (!n)
                r.fail("dual_arm", "missing (required by michi dualarm; see docs/dual-arm.md)");
            r.keys(n, "dual_arm",
                   {"large", "small", "resolution", "threshold", "manipulability_rows", "stirring", "seed_samples",
                    "seeds_per_cell", "seed", "planning", "paper_handover"});
            DualArmSpec spec;
            for (const char *arm : {"large", "small"})
                if (!n[arm])
                    r.fail(std::string("dual_arm.") + arm, "missing (required)");
            spec.large = readArm(r, n["large"], "dual_arm.large", problem);
            spec.small = readArm(r, n["small"], "dual_arm.small", problem);
            auto &s = spec.settings;
            if (n["resolution"])
            {
                s.resolution = r.positive(n["resolution"], "dual_arm.resolution");
                if (s.resolution < 0.005)
                    r.fail("dual_arm.resolution", "expected at least 0.005 m (finer grids take too long)");
            }
            if (n["threshold"])
                s.threshold = r.positive(n["threshold"], "dual_arm.threshold");
            if (n["manipulability_rows"])
            {
                const std::string rows = r.text(n["manipulability_rows"], "dual_arm.manipulability_rows");
                if (rows == "position")
                    s.rows = planners::ManipulabilityRows::POSITION;
                else if (rows == "full")
                    s.rows = planners::ManipulabilityRows::FULL;
                else
                    r.fail("dual_arm.manipulability_rows", "expected position or full, got '" + rows + "'");
            }
            if (const YAML::Node st = n["stirring"])
            {
                r.keys(st, "dual_arm.stirring", {"side", "step"});
                if (st["side"])
                    s.stirSide = r.positive(st["side"], "dual_arm.stirring.side");
                if (st["step"])
                    s.stirStep = r.positive(st["step"], "dual_arm.stirring.step");
                if (s.stirStep > s.stirSide)
                    r.fail("dual_arm.stirring.step", "expected a step no longer than the side");
                // a hand's small square, traced with an IK solve per step: beyond an arm's reach, or millions of
                // steps, it would only exhaust memory
                if (s.stirSide > 2.)
                    r.fail("dual_arm.stirring.side", "expected at most 2 m (the side of a hand's stirring square)");
                if (s.stirSide / s.stirStep > 10000.)
                    r.fail("dual_arm.stirring.step", "expected at most 10000 steps along the side");
            }
            if (n["seed_samples"])
                s.seedSamples = r.count(n["seed_samples"], "dual_arm.seed_samples");
            if (n["seeds_per_cell"])
                s.seedsPerCell = r.count(n["seeds_per_cell"], "dual_arm.seeds_per_cell");
            if (n["seed"])
                s.seed = r.count(n["seed"], "dual_arm.seed");
            if (const YAML::Node p = n["planning"])
            {
                r.keys(p, "dual_arm.planning", {"planner", "time", "weight"});
                if (p["weight"])
                    spec.weight = r.positive(p["weight"], "dual_arm.planning.weight");
                if (p["planner"])
                {
                    spec.planner = r.text(p["planner"], "dual_arm.planning.planner");
                    // here, not after the work-space maps are computed
                    try
                    {
                        requirePlannerName(spec.planner);
                    }
                    catch (const std::invalid_argument &e)
                    {
                        r.fail("dual_arm.planning.planner", e.what());
                    }
                }
                if (p["time"])
                    spec.planningTime = r.positive(p["time"], "dual_arm.planning.time");
            }
            if (n["paper_handover"])
            {
                const Eigen::Vector3d v = r.vector(n["paper_handover"], "dual_arm.paper_handover");
                spec.paperHandover = {{v.x(), v.y(), v.z()}};
            }
            const planners::ArmChain small(problem.model, spec.small.tip, spec.small.toolPoint);
            const planners::ArmChain large(problem.model, spec.large.tip, spec.large.toolPoint);
            // Checked here, so the error names the file and key (DualArmWorkspace's own check names only the tip).
            const bool full = s.rows == planners::ManipulabilityRows::FULL;
            if (small.size() < (full ? 6u : 3u))
                r.fail("dual_arm.small.tip", "the small arm (root to '" + spec.small.tip + "') has " +
                                                 std::to_string(small.size()) +
                                                 " joints: with manipulability_rows: " + (full ? "full" : "position") +
                                                 " its manipulability is 0 in every configuration (use " +
                                                 (full ? "manipulability_rows: position or " : "") +
                                                 "an arm with at least " + (full ? "6" : "3") + " joints)");
            // the planned group must be the small arm's joints (the approach motions are planned for it)
            if (problem.groupVariables != small.variables())
                r.fail("robot.group", "expected the small arm's joints (root to '" + spec.small.tip +
                                          "', in chain order): the approach motions are planned for it");
            // Arms that share a joint cannot be placed independently: the work-space analysis moves one with the other
            // fixed.
            for (int v : large.variables())
                if (small.owns(v))
                    r.fail("dual_arm.large.tip", "the two arms share joint '" +
                                                     problem.model->variableJoint(static_cast<std::size_t>(v)).name +
                                                     "'");
            return spec;
        }

        planners::ArmTask makeArmTask(const Problem &problem, const DualArmArmSpec &arm, const std::string &name)
        {
            return planners::ArmTask{name, planners::ArmChain(problem.model, arm.tip, arm.toolPoint), arm.hand};
        }
    }  // namespace tools
}  // namespace michi
