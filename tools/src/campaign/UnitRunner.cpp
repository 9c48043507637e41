// One work unit in its own process: OMPL's Benchmark with one run, so the run's properties are exactly those
// `michi bench` logs, plus the counts and path a campaign keeps to re-draw and re-certify the run later.
#include <michi/tools/campaign/UnitRunner.h>
#include <michi/tools/bench/PathCertificate.h>
#include <michi/tools/bench/PlannerRegistry.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/ExperienceQueries.h>

#include <ompl/base/StateValidityChecker.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/RandomNumbers.h>

#include <atomic>
#include <iomanip>
#include <sstream>

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;

namespace michi
{
    namespace tools
    {
        namespace
        {
            /** Counts the state checks that go through the space information (planners and OMPL's motion
                validators ask it), passing every question to the checker it wraps. */
            class CountingChecker : public ob::StateValidityChecker
            {
            public:
                CountingChecker(const ob::SpaceInformationPtr &si, ob::StateValidityCheckerPtr inner)
                    : ob::StateValidityChecker(si), inner_(std::move(inner))
                {
                    // The wrapped checker's specs: planners that ask how clearance is computed get the real answer.
                    specs_ = inner_->getSpecs();
                }

                bool isValid(const ob::State *state) const override
                {
                    ++count_;
                    return inner_->isValid(state);
                }

                bool isValid(const ob::State *state, double &dist) const override
                {
                    ++count_;
                    return inner_->isValid(state, dist);
                }

                double clearance(const ob::State *state) const override
                {
                    return inner_->clearance(state);
                }

                std::uint64_t count() const
                {
                    return count_.load();
                }

            private:
                ob::StateValidityCheckerPtr inner_;
                mutable std::atomic<std::uint64_t> count_{0};  // planners may check from several threads
            };

            std::uint64_t motionCount(const ob::SpaceInformationPtr &si)
            {
                const auto &mv = si->getMotionValidator();
                return mv ? static_cast<std::uint64_t>(mv->getValidMotionCount()) + mv->getInvalidMotionCount() : 0;
            }

            /** the path's states as "a b c|d e f": no ';' (the log's separator) */
            std::string pathText(const og::PathGeometric &path)
            {
                std::ostringstream s;
                // Nine digits: enough to re-draw the path and re-certify it later, short enough for the log's
                // 65536-character field.
                s << std::setprecision(9);
                const auto space = path.getSpaceInformation()->getStateSpace();
                std::vector<double> values;
                for (std::size_t i = 0; i < path.getStateCount(); ++i)
                {
                    space->copyToReals(values, path.getState(i));
                    s << (i ? "|" : "");
                    for (std::size_t j = 0; j < values.size(); ++j)
                        s << (j ? " " : "") << values[j];
                }
                return s.str();
            }
        }  // namespace

        UnitRecord runUnit(const UnitRecord &spec)
        {
            // first: every ompl::RNG made from here on draws from this seed
            ompl::RNG::setSeed(spec.seed);
            UnitRecord record = spec;
            const Problem problem = loadProblem(spec.problemFile);
            ContextOptions options;
            options.query = spec.query;
            if (spec.checker != "problem")
                options.checker = spec.checker;
            PlanningContext ctx = makePlanningContext(problem, options);
            const auto si = ctx.setup->getSpaceInformation();
            auto counting = std::make_shared<CountingChecker>(si, si->getStateValidityChecker());
            // Wraps whichever checker the context installed, so validity_checks counts the same thing for every
            // checker.
            si->setStateValidityChecker(counting);

            ob::PlannerPtr planner = allocatePlanner(spec.planner, si);
            applyPlannerParams(*planner, PlannerSpec{spec.planner, spec.params, {}}, spec.problemFile);
            // The unit's planner name (with the checker when a campaign compares checkers): the log and database group
            // runs by it.
            planner->setName(spec.plannerName);
            // Before the benchmark, so training is not part of the run's time (as in michi bench).
            trainExperiencePlanners(problem, ctx, {planner}, nullptr);

            ot::Benchmark benchmark(*ctx.setup, problem.name);
            benchmark.addPlanner(planner);
            std::uint64_t checks0 = 0, motions0 = 0, fcl0 = 0;
            benchmark.setPreRunEvent(
                [&](const ob::PlannerPtr &)
                {
                    // Counters are read as differences over the run: checks made while training or setting up are not
                    // the run's.
                    checks0 = counting->count();
                    motions0 = motionCount(si);
                    fcl0 = ctx.checker->queryCount();
                });
            benchmark.setPostRunEvent(
                [&](const ob::PlannerPtr &p, ot::Benchmark::RunProperties &run)
                {
                    run["unit INTEGER"] = std::to_string(spec.id);
                    run["seed INTEGER"] = std::to_string(spec.seed);
                    run["query INTEGER"] = std::to_string(spec.query);
                    run["checker VARCHAR(16)"] = ctx.checkerName;
                    run["outcome VARCHAR(16)"] = "done";
                    run["crash_signal INTEGER"] = "0";
                    run["validity_checks INTEGER"] = std::to_string(counting->count() - checks0);
                    run["motion_checks INTEGER"] = std::to_string(motionCount(si) - motions0);
                    run["fcl_queries INTEGER"] = std::to_string(ctx.checker->queryCount() - fcl0);
                    bool solved = run.count("solved BOOLEAN") && run["solved BOOLEAN"] == "1";
                    const auto pdef = p->getProblemDefinition();
                    const auto solution = pdef ? pdef->getSolutionPath() : nullptr;
                    const auto *path = solution ? solution->as<og::PathGeometric>() : nullptr;
                    if (solved)
                    {
                        // a fast checker's mistake is never reported as solved (as in `michi bench`)
                        const PathCertificate certificate = path ? certifyPath(*path, *ctx.checker) : PathCertificate{};
                        if (!certificate.certified)
                        {
                            solved = false;
                            run["solved BOOLEAN"] = "0";
                            // OMPL's own check (path->check() with the planner's checker) said correct: FCL says not
                            run["correct solution BOOLEAN"] = "0";
                            run["certificate VARCHAR(256)"] = certificate.reason;
                        }
                    }
                    run["certified_paths INTEGER"] = solved ? "1" : "0";
                    run["path VARCHAR(65536)"] = path ? pathText(*path) : "";
                });
            // saveConsoleOutput=false: OMPL would otherwise leave a .console file in the working directory
            ot::Benchmark::Request request(spec.timeLimit, problem.benchmark.memoryLimit, 1, 0.05, false, false,
                                           problem.benchmark.simplify);
            benchmark.benchmark(request);

            const auto &experiment = benchmark.getRecordedExperimentData();
            if (experiment.planners.size() != 1 || experiment.planners[0].runs.size() != 1)
                throw std::runtime_error("OMPL's Benchmark recorded no run");
            const auto &planned = experiment.planners[0];
            record.outcome = "done";
            record.memoryLimit = experiment.maxMem;
            record.setupInfo = experiment.setupInfo;
            record.properties.clear();
            for (const auto &kv : planned.runs[0])
                record.properties[kv.first] = kv.second;
            record.settings.clear();
            for (const auto &kv : planned.common)
                record.settings.push_back(kv.first + " = " + kv.second);
            // the anytime planners' progress (best cost over time), which the log's progress section carries
            record.progressNames = planned.progressPropertyNames;
            record.progress.clear();
            if (!planned.runsProgressData.empty())
                for (const auto &point : planned.runsProgressData[0])
                {
                    std::vector<std::string> sample;
                    for (const auto &name : record.progressNames)
                    {
                        const auto it = point.find(name);
                        sample.push_back(it == point.end() ? "" : it->second);
                    }
                    record.progress.push_back(std::move(sample));
                }
            return record;
        }
    }  // namespace tools
}  // namespace michi
