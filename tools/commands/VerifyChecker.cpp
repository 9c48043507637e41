#include <michi/tools/commands/VerifyChecker.h>
#include <michi/tools/bench/PathCertificate.h>
#include <michi/tools/bench/PlanningContext.h>
#include <michi/validity/fcl/ConservativeMotionValidator.h>

#include <ompl/base/SpaceInformation.h>
#include <ompl/util/RandomNumbers.h>

#include <chrono>
#include <iomanip>
#include <sstream>

namespace ob = ompl::base;

namespace michi
{
    namespace tools
    {
        std::string VerifyCheckerResult::json() const
        {
            auto quote = [](const std::string &s)
            {
                std::string out = "\"";
                for (char c : s)
                {
                    if (c == '"' || c == '\\')
                        out += '\\';
                    // Control characters are dropped: JSON forbids them raw, and no problem or checker name needs them.
                    if (static_cast<unsigned char>(c) >= 0x20)
                        out += c;
                }
                return out + "\"";
            };
            std::ostringstream j;
            j << std::setprecision(6);
            j << "{\"problem\": " << quote(problem) << ", \"checker\": " << quote(checker) << ", \"states\": " << states
              << ", \"motions\": " << motions << ", \"seed\": " << seed << ", \"unsafe_states\": " << unsafeStates
              << ", \"unsafe_motions\": " << unsafeMotions << ", \"false_invalid_fraction\": " << falseInvalidFraction()
              << ", \"reference_valid_states\": " << referenceValid << ", \"valid_motions\": " << motionsValid
              << ", \"query_ns\": " << queryNs << ", \"reference_query_ns\": " << referenceQueryNs
              << ", \"speedup\": " << (queryNs > 0. ? referenceQueryNs / queryNs : 0.)
              << ", \"motion_ns\": " << motionNs << ", \"build_s\": " << buildSeconds << "}";
            return j.str();
        }

        VerifyCheckerResult verifyChecker(const Problem &problem, const VerifyCheckerOptions &options)
        {
            using Clock = std::chrono::steady_clock;
            VerifyCheckerResult result;
            result.problem = problem.name;
            result.checker = options.checker;
            result.seed = options.seed;
            // Before the context and the sampler exist: the same seed checks the very same states.
            ompl::RNG::setSeed(options.seed);
            ContextOptions contextOptions;
            contextOptions.checker = options.checker;
            const auto built = Clock::now();
            PlanningContext ctx = makePlanningContext(problem, contextOptions);
            // The context builds the fast checker (tables, maps, sphere models): its cost is reported beside the query
            // times.
            result.buildSeconds = std::chrono::duration<double>(Clock::now() - built).count();
            const auto si = ctx.setup->getSpaceInformation();
            const ob::StateValidityCheckerPtr fast = si->getStateValidityChecker();
            const ob::MotionValidatorPtr fastMotions = si->getMotionValidator();
            const validity::FclValidityChecker &reference = *ctx.checker;
            // The reference motion check reads states through a SpaceInformation of its own whose checker is FCL: on
            // the context's, ConservativeMotionValidator's test of the motion's end went to the fast checker, and a
            // motion the fast checker's end refused while FCL found it free counted as unsafe.
            const auto referenceSi = std::make_shared<ob::SpaceInformation>(si->getStateSpace());
            referenceSi->setStateValidityChecker(ctx.checker);
            referenceSi->setStateValidityCheckingResolution(si->getStateValidityCheckingResolution());
            referenceSi->setup();
            validity::ConservativeMotionValidator referenceMotions(referenceSi, ctx.checker);
            // the exact reference walks by FCL distances: fine for boxes and polygons, but on arm meshes a distance
            // costs tens of microseconds and a short motion near contact needs hundreds of them. For the sphere
            // checker the motions are re-checked as `michi bench` certifies paths instead: FCL collision queries
            // ten times finer than the planners' resolution
            const bool fineReference = options.checker == "spheres";
            auto referenceMotionFree = [&](ob::State *a, ob::State *b)
            {
                if (!fineReference)
                    return referenceMotions.checkMotion(a, b);
                ompl::geometric::PathGeometric segment(si, a, b);
                return certifyPath(segment, reference).certified;
            };
            auto sampler = si->allocStateSampler();
            const double near = options.motionFraction * si->getMaximumExtent();

            const std::size_t batch = 1000;  // states a planner just made are in the cache; so are these
            std::vector<ob::State *> states(batch), targets(batch), warmup(batch);
            for (std::size_t i = 0; i < batch; ++i)
            {
                states[i] = si->allocState();
                targets[i] = si->allocState();
                warmup[i] = si->allocState();
            }
            std::vector<char> fastValid(batch), refValid(batch);
            double fastSeconds = 0., refSeconds = 0., motionSeconds = 0.;
            std::size_t sink = 0;
            // Each checker's timed loop follows an untimed loop of the same checker over other uniform states, so
            // both are measured as a planner uses them, checking one state after another with their data in the
            // cache. Without it the order decided the figure: the fast checker ran right after the FCL work of the
            // motion checks, FCL right after the fast checker's small loop (docs/checking.md).
            auto timeLoop = [&](auto &&check, std::vector<char> &answers, std::size_t n)
            {
                for (std::size_t i = 0; i < n; ++i)
                    sink += check(warmup[i]) ? 1 : 0;
                const auto t0 = Clock::now();
                for (std::size_t i = 0; i < n; ++i)
                    answers[i] = check(states[i]) ? 1 : 0;
                return std::chrono::duration<double>(Clock::now() - t0).count();
            };
            for (std::size_t done = 0; done < options.states; done += batch)
            {
                const std::size_t n = std::min(batch, options.states - done);
                for (std::size_t i = 0; i < n; ++i)
                {
                    sampler->sampleUniform(states[i]);
                    sampler->sampleUniformNear(targets[i], states[i], near);
                    // sampleUniformNear() may step past a bound or past +-pi of a yaw: the motion's end must be a state
                    // of the space.
                    si->enforceBounds(targets[i]);
                    sampler->sampleUniform(warmup[i]);
                }
                fastSeconds += timeLoop(
                    [&](const ob::State *s)
                    {
                        return fast->isValid(s);
                    },
                    fastValid, n);
                refSeconds += timeLoop(
                    [&](const ob::State *s)
                    {
                        return reference.isValid(s);
                    },
                    refValid, n);
                for (std::size_t i = 0; i < n; ++i)
                {
                    sink += fastValid[i];
                    if (refValid[i])
                    {
                        ++result.referenceValid;
                        if (!fastValid[i])
                            ++result.falseInvalid;
                    }
                    else if (fastValid[i])
                        ++result.unsafeStates;
                }
                // motions: the fast motion validator; FCL (exact) on those it calls valid
                const auto m0 = Clock::now();
                for (std::size_t i = 0; i < n; ++i)
                    fastValid[i] = fastMotions->checkMotion(states[i], targets[i]) ? 1 : 0;
                motionSeconds += std::chrono::duration<double>(Clock::now() - m0).count();
                for (std::size_t i = 0; i < n; ++i)
                    // Only motions the fast validator accepts are re-checked: a refused motion is conservative, never
                    // unsafe.
                    if (fastValid[i])
                    {
                        ++result.motionsValid;
                        if (!referenceMotionFree(states[i], targets[i]))
                            ++result.unsafeMotions;
                    }
                result.states += n;
                result.motions += n;
                if (options.progress && (done / batch) % 100 == 99)
                    *options.progress << "michi verify-checker: " << result.states << " states, unsafe "
                                      << result.unsafeStates << " / " << result.unsafeMotions << std::endl;
            }
            for (std::size_t i = 0; i < batch; ++i)
            {
                si->freeState(states[i]);
                si->freeState(targets[i]);
                si->freeState(warmup[i]);
            }
            if (result.states > 0)
            {
                result.queryNs = 1e9 * fastSeconds / result.states;
                result.referenceQueryNs = 1e9 * refSeconds / result.states;
                result.motionNs = 1e9 * motionSeconds / result.motions;
            }
            // sink only keeps the fast checker's answers in use, so its timed loop cannot be optimised away.
            (void)sink;
            return result;
        }
    }  // namespace tools
}  // namespace michi
