#include <michi/tools/problem/TaskRegionQueries.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/ExperienceQueries.h>
#include "ProblemYaml.h"

#include <michi/planners/HandIk.h>

#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

namespace michi
{
    namespace tools
    {
        namespace
        {
            using problem_file::Reader;

            Eigen::Vector3d vector3(const Reader &r, const YAML::Node &n, const std::string &key)
            {
                const auto v = r.coordinates(n, key, 3);
                return Eigen::Vector3d(v[0], v[1], v[2]);
            }

            Eigen::Vector3d unitVector(const Reader &r, const YAML::Node &n, const std::string &key)
            {
                const Eigen::Vector3d v = vector3(r, n, key);
                if (!(v.norm() > 1e-9))
                    r.fail(key, "expected a non-zero direction");
                return v.normalized();
            }

            TaskRegion readRegion(const Reader &r, const YAML::Node &n, const std::string &key)
            {
                if (!n.IsMap())
                    r.fail(key, "expected a mapping (name, box, direction, cone)");
                r.keys(n, key, {"name", "box", "direction", "cone"});
                TaskRegion region;
                region.name = r.text(r.require(n, "name", key), key + ".name");
                const YAML::Node box = r.require(n, "box", key);
                if (!box.IsMap())
                    r.fail(key + ".box", "expected a mapping (min, max)");
                r.keys(box, key + ".box", {"min", "max"});
                region.lower = vector3(r, r.require(box, "min", key + ".box"), key + ".box.min");
                region.upper = vector3(r, r.require(box, "max", key + ".box"), key + ".box.max");
                if (!(region.lower.array() <= region.upper.array()).all())
                    r.fail(key + ".box", "min must not exceed max in any coordinate");
                region.direction = unitVector(r, r.require(n, "direction", key), key + ".direction");
                region.cone = r.number(r.require(n, "cone", key), key + ".cone");
                if (!(region.cone >= 0. && region.cone <= M_PI))
                    r.fail(key + ".cone", "expected an angle in [0, pi] radians");
                return region;
            }

            /** A unit vector within \e cone of \e axis, uniform over that cap of the sphere. */
            Eigen::Vector3d sampleCone(ompl::RNG &rng, const Eigen::Vector3d &axis, double cone)
            {
                const double c = 1. - rng.uniform01() * (1. - std::cos(cone));
                const double s = std::sqrt(std::max(0., 1. - c * c));
                const double phi = rng.uniformReal(-M_PI, M_PI);
                const Eigen::Vector3d b1 = axis.unitOrthogonal(), b2 = axis.cross(b1);
                return (c * axis + s * (std::cos(phi) * b1 + std::sin(phi) * b2)).normalized();
            }

            /** Draws valid group states with the hand in a region. */
            class RegionSampler
            {
            public:
                RegionSampler(const Problem &problem, const TaskRegions &regions, const PlanningContext &ctx,
                              ompl::RNG &rng)
                    : problem_(problem)
                    , regions_(regions)
                    , ctx_(ctx)
                    , rng_(rng)
                    , arm_(problem.model, regions.tipLink, regions.toolPoint)
                {
                    for (int v : arm_.variables())
                        if (std::find(problem.groupVariables.begin(), problem.groupVariables.end(), v) ==
                            problem.groupVariables.end())
                            throw ProblemError(regions.file, "tip_link",
                                               "the chain to " + regions.tipLink + " moves joint '" +
                                                   problem.model->variableJoint(static_cast<std::size_t>(v)).name +
                                                   "', which is not in the planned group");
                }

                std::vector<double> sample(const TaskRegion &region)
                {
                    planners::HandTarget target;
                    target.mode = planners::HandTarget::Mode::AXIS_ALONG;
                    target.toolAxis = regions_.toolAxis;
                    // Poses are drawn again when IK fails or its solutions collide: a region may hold poses the arm
                    // cannot take (out of reach, or through an obstacle), and those are not part of the task.
                    for (int pose = 0; pose < 2000; ++pose)
                    {
                        for (int k = 0; k < 3; ++k)
                            target.position[k] = rng_.uniformReal(region.lower[k], region.upper[k]);
                        target.direction = sampleCone(rng_, region.direction, region.cone);
                        for (int seed = 0; seed < IK_SEEDS; ++seed)
                        {
                            std::vector<double> q = ctx_.fixedValues;
                            for (int v : problem_.groupVariables)
                            {
                                const auto &j = problem_.model->variableJoint(static_cast<std::size_t>(v));
                                const bool bounded = j.type != validity::RobotJoint::Type::CONTINUOUS;
                                q[static_cast<std::size_t>(v)] =
                                    bounded ? rng_.uniformReal(j.lower, j.upper) : rng_.uniformReal(-M_PI, M_PI);
                            }
                            if (!planners::solveHandIk(arm_, target, q))
                                continue;
                            std::vector<double> values;
                            for (int v : problem_.groupVariables)
                            {
                                // rounded to the 6 decimals the queries file keeps (the values checked are the
                                // values written), inwards at a joint limit: IK may stop on the limit itself
                                const auto &j = problem_.model->variableJoint(static_cast<std::size_t>(v));
                                double x = std::round(q[static_cast<std::size_t>(v)] * 1e6) / 1e6;
                                if (j.type != validity::RobotJoint::Type::CONTINUOUS)
                                {
                                    if (x > j.upper)
                                        x = std::floor(j.upper * 1e6) / 1e6;
                                    if (x < j.lower)
                                        x = std::ceil(j.lower * 1e6) / 1e6;
                                }
                                values.push_back(x);
                            }
                            if (invalidStateReason(ctx_, values).empty())
                                return values;
                        }
                    }
                    throw std::runtime_error(regions_.file + ": region '" + region.name +
                                             "': no valid arm state in 2000 hand poses (out of reach, or blocked)");
                }

            private:
                static constexpr int IK_SEEDS = 20;
                const Problem &problem_;
                const TaskRegions &regions_;
                const PlanningContext &ctx_;
                ompl::RNG &rng_;
                planners::ArmChain arm_;
            };
        }  // namespace

        TaskRegions readTaskRegions(const std::string &file, const Problem &problem)
        {
            if (problem.kind != Problem::Kind::ARM)
                throw ProblemError(problem.file, "robot", "task regions need an arm problem (a URDF robot)");
            const YAML::Node root = problem_file::loadYaml(file);
            const Reader r(file);
            if (!root.IsMap())
                r.fail("", "expected a mapping (tip_link, tool_axis, tool_point, regions, pairs)");
            r.keys(root, "", {"tip_link", "tool_axis", "tool_point", "regions", "pairs"});
            TaskRegions out;
            out.file = file;
            out.tipLink = r.text(r.require(root, "tip_link", ""), "tip_link");
            try
            {
                problem.model->linkIndex(out.tipLink);
            }
            catch (const std::out_of_range &)
            {
                r.fail("tip_link", "the robot has no link '" + out.tipLink + "'");
            }
            out.toolAxis = unitVector(r, r.require(root, "tool_axis", ""), "tool_axis");
            if (const YAML::Node p = root["tool_point"])
                out.toolPoint = vector3(r, p, "tool_point");
            const YAML::Node regions = r.require(root, "regions", "");
            if (!regions.IsSequence() || regions.size() < 1)
                r.fail("regions", "expected a list of at least one region");
            std::set<std::string> names;
            for (std::size_t i = 0; i < regions.size(); ++i)
            {
                out.regions.push_back(readRegion(r, regions[i], "regions[" + std::to_string(i) + "]"));
                if (!names.insert(out.regions.back().name).second)
                    r.fail("regions[" + std::to_string(i) + "].name",
                           "'" + out.regions.back().name + "' names two regions");
            }
            auto index = [&](const YAML::Node &n, const std::string &key)
            {
                const std::string name = r.text(n, key);
                for (std::size_t i = 0; i < out.regions.size(); ++i)
                    if (out.regions[i].name == name)
                        return i;
                r.fail(key, "no region is named '" + name + "'");
            };
            if (const YAML::Node pairs = root["pairs"])
            {
                if (!pairs.IsSequence() || pairs.size() < 1)
                    r.fail("pairs", "expected a list of [start region, goal region] pairs");
                for (std::size_t i = 0; i < pairs.size(); ++i)
                {
                    const std::string key = "pairs[" + std::to_string(i) + "]";
                    if (!pairs[i].IsSequence() || pairs[i].size() != 2)
                        r.fail(key, "expected [start region, goal region]");
                    out.pairs.emplace_back(index(pairs[i][0], key + "[0]"), index(pairs[i][1], key + "[1]"));
                }
            }
            else
            {
                for (std::size_t a = 0; a < out.regions.size(); ++a)
                    for (std::size_t b = 0; b < out.regions.size(); ++b)
                        if (a != b)
                            out.pairs.emplace_back(a, b);
                if (out.pairs.empty())
                    r.fail("regions", "one region and no pairs: name at least two regions, or give pairs");
            }
            return out;
        }

        ExperienceQueries generateTaskRegionQueries(const Problem &problem, const TaskRegions &regions,
                                                    std::size_t count, std::size_t training, unsigned int seed)
        {
            if (training > count)
                throw std::invalid_argument("more training queries than queries");
            const PlanningContext ctx = makePlanningContext(problem, 0);
            ompl::RNG rng(seed);  // its own generator: the same options always write the same file
            RegionSampler sampler(problem, regions, ctx, rng);
            ExperienceQueries out;
            out.trainingTime = problem.experience.trainingTime;
            std::set<std::vector<double>> seen;
            std::size_t draws = 0;
            while (out.training.size() + out.heldOut.size() < count)
            {
                // regions so small that their states repeat would otherwise redraw for ever
                if (++draws > 100 * count)
                    throw std::runtime_error(regions.file + ": the regions give fewer than " + std::to_string(count) +
                                             " distinct start/goal pairs (boxes and cones too small?)");
                // start and goal drawn independently, the pair of regions first
                const auto &pair =
                    regions
                        .pairs[static_cast<std::size_t>(rng.uniformInt(0, static_cast<int>(regions.pairs.size()) - 1))];
                Query q;
                q.start = sampler.sample(regions.regions[pair.first]);
                q.goal = sampler.sample(regions.regions[pair.second]);
                // training and held-out sets share no state (a repeat is all but impossible; it is drawn again)
                if (seen.count(q.start) || seen.count(q.goal) || q.start == q.goal)
                    continue;
                seen.insert(q.start);
                seen.insert(q.goal);
                (out.training.size() < training ? out.training : out.heldOut).push_back(q);
            }
            return out;
        }
    }  // namespace tools
}  // namespace michi
