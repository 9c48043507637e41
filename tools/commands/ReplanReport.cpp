#include "ReplanReport.h"

#include <michi/tools/FileOutput.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace michi
{
    namespace tools
    {
        namespace replan
        {
            namespace
            {
                double percentile(std::vector<double> v, double p)
                {
                    if (v.empty())
                        return std::numeric_limits<double>::quiet_NaN();
                    std::sort(v.begin(), v.end());
                    const std::size_t rank =
                        // Nearest rank: the percentile is a latency that actually occurred, never an interpolation
                        // between two.
                        static_cast<std::size_t>(std::ceil(p / 100. * static_cast<double>(v.size())));
                    return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
                }

                std::string num(double v)
                {
                    if (!std::isfinite(v))
                        // JSON has no NaN: a figure with no data (no replan found a path) is null.
                        return "null";
                    std::ostringstream s;
                    s << std::setprecision(6) << v;
                    return s.str();
                }

                void writeResults(std::ostream &out, const Results &r, const std::string &indent)
                {
                    out << indent << "\"episodes\": " << r.episodes << ",\n"
                        << indent << "\"reached_goal\": " << r.reached << ",\n"
                        << indent << "\"collisions\": " << r.collisions << ",\n"
                        << indent << "\"collision_steps\": " << r.collisionSteps << ",\n"
                        << indent << "\"stops\": " << r.stops << ",\n"
                        << indent << "\"deformations\": " << r.deformations << ",\n"
                        << indent << "\"retimings\": " << r.retimings << ",\n"
                        << indent << "\"replans\": " << r.replans << ",\n"
                        << indent << "\"replans_found\": " << r.replanLatency.size() << ",\n"
                        << indent << "\"cancelled_queries\": " << r.cancelled << ",\n"
                        << indent << "\"planning_failures\": " << r.failures << ",\n"
                        << indent << "\"obstacle_waits\": " << r.obstacleWaits << ",\n"
                        << indent << "\"motion_collisions\": " << r.motionCollisions << ",\n"
                        << indent << "\"unavoidable_collisions\": " << r.unavoidableCollisions << ",\n"
                        << indent << "\"replan_latency_ms_median\": " << num(percentile(r.replanLatency, 50.)) << ",\n"
                        << indent << "\"replan_latency_ms_p95\": " << num(percentile(r.replanLatency, 95.)) << ",\n"
                        << indent << "\"replan_wall_ms_median\": " << num(percentile(r.replanWall, 50.)) << ",\n"
                        << indent << "\"replan_cpu_ms_median\": " << num(percentile(r.replanCpu, 50.)) << ",\n"
                        << indent << "\"initial_plan_ms_median\": " << num(percentile(r.initialLatency, 50.)) << ",\n"
                        << indent << "\"time_to_goal_s_median\": " << num(percentile(r.timeToGoal, 50.)) << ",\n"
                        << indent << "\"learning_edges\": " << r.learningEdges << ",\n"
                        << indent << "\"episode_end_s\": [";
                    for (std::size_t i = 0; i < r.episodeEnd.size(); ++i)
                        out << (i > 0 ? ", " : "") << num(r.episodeEnd[i]);
                    // every replan's charged latency in the order they happened: a median over a handful of replans
                    // moves with each of them, so the list lets a reader see which ones set it
                    out << "],\n" << indent << "\"replan_latencies_ms\": [";
                    for (std::size_t i = 0; i < r.replanLatency.size(); ++i)
                        out << (i > 0 ? ", " : "") << num(r.replanLatency[i]);
                    out << "],\n" << indent << "\"wall_seconds\": " << num(r.wallSeconds);
                }
            }  // namespace

            std::string reportJson(const Problem &problem, unsigned int seed, const ReplanSettings &settings,
                                   const std::vector<Method> &methods, const std::vector<Results> &results)
            {
                std::ostringstream json;
                json << "{\n  \"scenario\": " << jsonString(problem.name)
                     << ",\n  \"problem\": " << jsonString(problem.file) << ",\n  \"seed\": " << seed
                     << ",\n  \"method\": " << jsonString(methods[0].label) << ",\n";
                writeResults(json, results[0], "  ");
                json << ",\n  \"settings\": {\"dt\": " << num(settings.dt)
                     << ", \"sense_period\": " << num(settings.sensePeriod) << ", \"speed\": " << num(settings.speed)
                     << ", \"deceleration\": " << num(settings.deceleration)
                     << ", \"safety_distance\": " << num(settings.safetyDistance)
                     << ", \"margin\": " << num(settings.margin)
                     << ", \"prediction_horizon\": " << num(settings.predictionHorizon)
                     << ", \"planning_time\": " << num(settings.planningTime)
                     << ", \"real_time\": " << num(settings.realTime) << ", \"clock\": \""
                     << (settings.cpuClock ? "cpu" : "wall") << "\""
                     << ", \"planning_delay\": " << num(settings.planningDelay)
                     << ", \"planning_work\": " << num(settings.planningWork)
                     << ", \"episode_time\": " << num(settings.episodeTime)
                     << ", \"timing_jitter\": " << num(settings.timingJitter)
                     << ", \"speed_jitter\": " << num(settings.speedJitter)
                     << ", \"deformation\": " << (settings.deformation ? "true" : "false")
                     << ", \"obstacles_yield\": " << (settings.obstaclesYield ? "true" : "false") << "},\n";
                json << "  \"baselines\": {";
                for (std::size_t mi = 1; mi < methods.size(); ++mi)
                {
                    json << (mi > 1 ? "," : "") << "\n    " << jsonString(methods[mi].label) << ": {\n";
                    writeResults(json, results[mi], "      ");
                    const double ratio =
                        // Above 1: the baseline's median replan took longer than the first method's (DualRoadmap's),
                        // charged the same way.
                        percentile(results[mi].replanLatency, 50.) / percentile(results[0].replanLatency, 50.);
                    json << ",\n      \"median_latency_ratio_to_method\": " << num(ratio) << "\n    }";
                }
                json << "\n  }\n}\n";
                return json.str();
            }

        }  // namespace replan
    }      // namespace tools
}  // namespace michi
