#include <michi/planners/path_seed/PathSeed.h>

#include <ompl/base/PlannerData.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/StateSpaceTypes.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Exception.h>

#include <cmath>
#include <stdexcept>
#include <thread>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace michi
{
    namespace planners
    {
        namespace
        {
            // Where the last solution came from (getLastSource()): kept in an atomic int so a benchmark thread can read
            // it.
            enum Source
            {
                NONE = 0,
                RECALL,
                STITCH,
                REPAIR,
                SCRATCH
            };
        }  // namespace

        PathSeed::PathSeed(const ob::SpaceInformationPtr &si)
            : ob::Planner(si, "PathSeed"), library_(std::make_shared<PathSeedLibrary>())
        {
            specs_.approximateSolutions = false;
            specs_.optimizingPaths = false;
            // Repair races RRT-Connect in a second thread, and the fail-fast checks may use several (threads
            // parameter).
            specs_.multithreaded = true;
            specs_.directed = false;
            specs_.recognizedGoal = ob::GOAL_SAMPLEABLE_REGION;
            declareParam<std::string>("library_file", this, &PathSeed::setLibraryFile, &PathSeed::getLibraryFile);
            declareParam<unsigned int>("candidates", this, &PathSeed::setCandidates, &PathSeed::getCandidates,
                                       "0:1:50");
            declareParam<unsigned int>("max_seeds", this, &PathSeed::setMaxSeeds, &PathSeed::getMaxSeeds, "0:1:100000");
            declareParam<std::string>("repair", this, &PathSeed::setRepair, &PathSeed::getRepair);
            declareParam<std::string>("variant", this, &PathSeed::setVariant, &PathSeed::getVariant);
            declareParam<bool>("race", this, &PathSeed::setRace, &PathSeed::getRace, "0,1");
            declareParam<bool>("learn", this, &PathSeed::setLearn, &PathSeed::getLearn, "0,1");
            declareParam<double>("range", this, &PathSeed::setRange, &PathSeed::getRange, "0.:0.1:10.");
            declareParam<bool>("stitch", this, &PathSeed::setStitch, &PathSeed::getStitch, "0,1");
            declareParam<unsigned int>("check_threads", this, &PathSeed::setCheckThreads, &PathSeed::getCheckThreads,
                                       "1:1:" + std::to_string(MAX_CHECK_THREADS));
            declareParam<bool>("anchored", this, &PathSeed::setAnchored, &PathSeed::getAnchored, "0,1");
            declareParam<unsigned int>("stitch_neighbours", this, &PathSeed::setStitchNeighbours,
                                       &PathSeed::getStitchNeighbours, "1:1:20");
            declareParam<unsigned int>("shortcut_steps", this, &PathSeed::setShortcutSteps, &PathSeed::getShortcutSteps,
                                       "0:1:1000");
            // which values wrap: a compound space's SO(2) components (michi's CompoundJointStateSpace for continuous
            // joints); every other component holds one value per dimension
            const auto space = si->getStateSpace();
            if (space->isCompound())
                for (const auto &sub : space->as<ob::CompoundStateSpace>()->getSubspaces())
                    continuous_.insert(continuous_.end(), sub->getDimension(),
                                       sub->getType() == ob::STATE_SPACE_SO2 ? 1 : 0);
            continuous_.resize(space->getDimension(), 0);
            addPlannerProgressProperty("library seeds INTEGER",
                                       [this]
                                       {
                                           return std::to_string(library_->size());
                                       });
        }

        PathSeed::~PathSeed() = default;

        namespace
        {
            std::string variantMismatch(const std::string &file, SeedVariant held, SeedVariant wanted)
            {
                return "PathSeed: library_file " + file + " holds " + seedVariantName(held) + " seeds, but variant " +
                       seedVariantName(wanted) +
                       " was requested (seeds of one variant cannot be decoded as another: make the library with "
                       "that variant, or leave the variant to the file)";
            }
        }  // namespace

        void PathSeed::setLibraryFile(const std::string &file)
        {
            if (file.empty() || file == libraryFile_)
            {
                // no file: the library (kept) is no longer the file's, and a later variant may replace it
                if (file.empty())
                    libraryFromFile_ = false;
                libraryFile_ = file;
                return;
            }
            auto lib = PathSeedLibrary::load(file);  // throws PathSeedFileError naming file and line
            // The variant may have been set first (params are applied in name order, but a caller may use any): a file
            // of another variant is refused, as setVariant() refuses a variant other than the loaded file's.
            if (variant_ && lib->variant() != *variant_)
                throw ompl::Exception(variantMismatch(file, lib->variant(), *variant_));
            // A library made for another robot would decode into meaningless states: refuse it when it is set, not at
            // solve().
            if (lib->size() > 0 && lib->dimension() != si_->getStateDimension())
                throw std::invalid_argument(file + ": path seeds of dimension " + std::to_string(lib->dimension()) +
                                            ", the state space has " + std::to_string(si_->getStateDimension()));
            library_ = lib;
            library_->setCapacity(maxSeeds_);
            libraryFile_ = file;
            libraryFromFile_ = true;
        }

        void PathSeed::setMaxSeeds(unsigned int seeds)
        {
            maxSeeds_ = seeds;
            library_->setCapacity(seeds);
        }

        void PathSeed::saveLibrary(const std::string &file) const
        {
            library_->save(file);
        }

        void PathSeed::setLibrary(PathSeedLibraryPtr library)
        {
            if (!library)
                throw std::invalid_argument("PathSeed: null library");
            library_ = std::move(library);
            library_->setCapacity(maxSeeds_);
            libraryFromFile_ = false;
        }

        void PathSeed::setRepair(const std::string &method)
        {
            // "stomp" (the paper's repair) was removed: in 100 measured runs it repaired no path (docs/path-seed.md)
            if (method != "rrtconnect" && method != "none")
                throw std::invalid_argument("PathSeed: repair must be rrtconnect or none, got '" + method + "'");
            repair_ = method;
        }

        void PathSeed::setVariant(const std::string &variant)
        {
            const SeedVariant v = seedVariantFromName(variant);  // throws for an unknown name
            // Seeds of one variant cannot be decoded as another: changing the variant starts an empty library. Not a
            // library loaded from library_file, though: OMPL applies params in name order (library_file first), and
            // replacing it would leave every run planning from scratch while the settings name the file.
            if (v != library_->variant())
            {
                if (libraryFromFile_)
                    throw ompl::Exception(variantMismatch(libraryFile_, library_->variant(), v));
                library_ = std::make_shared<PathSeedLibrary>(v);
                library_->setCapacity(maxSeeds_);
            }
            variant_ = v;
        }

        std::string PathSeed::getVariant() const
        {
            return seedVariantName(library_->variant());
        }

        std::string PathSeed::getLastSource() const
        {
            switch (lastSource_.load())
            {
                case RECALL:
                    return "recall";
                case STITCH:
                    return "stitch";
                case REPAIR:
                    return "repair";
                case SCRATCH:
                    return "scratch";
                default:
                    return "";
            }
        }

        std::size_t PathSeed::experienceCount() const
        {
            return library_->size();
        }

        bool PathSeed::loadExperience(const std::string &file)
        {
            setLibraryFile(file);
            return true;
        }

        Eigen::VectorXd PathSeed::toVector(const ob::State *state) const
        {
            std::vector<double> reals;
            si_->getStateSpace()->copyToReals(reals, state);
            return Eigen::Map<const Eigen::VectorXd>(reals.data(), reals.size());
        }

        namespace
        {
            double wrapped(double angle)  // into [-pi, pi)
            {
                return angle - 2. * M_PI * std::floor((angle + M_PI) / (2. * M_PI));
            }
        }  // namespace

        void PathSeed::unwrap(std::vector<Eigen::VectorXd> &path) const
        {
            for (std::size_t k = 0; k < continuous_.size(); ++k)
                if (continuous_[k])
                    for (std::size_t i = 1; i < path.size() && path[i].size() == path[0].size() &&
                                            static_cast<std::size_t>(path[0].size()) == continuous_.size();
                         ++i)
                        // Each waypoint its predecessor plus the short difference: a path across +-pi has no 2 pi jump
                        // in its seed.
                        path[i][k] = path[i - 1][k] + wrapped(path[i][k] - path[i - 1][k]);
        }

        Eigen::VectorXd PathSeed::nearestGoal(const Eigen::VectorXd &start, const Eigen::VectorXd &goal) const
        {
            Eigen::VectorXd g = goal;
            for (std::size_t k = 0; k < continuous_.size(); ++k)
                if (continuous_[k])
                    // The goal moved by whole turns to within pi of the start: the new start-goal line goes the short
                    // way round, as the space interpolates (path-seed.md).
                    g[k] = start[k] + wrapped(goal[k] - start[k]);
            return g;
        }

        void PathSeed::addExperience(const og::PathGeometric &path)
        {
            if (path.getStateCount() < 2)
                return;
            // a compound space's copyToReals needs its value locations, made by setup() (as Planner::setup() does)
            if (!si_->isSetup())
                si_->setup();
            std::vector<Eigen::VectorXd> p;
            for (const auto *s : const_cast<og::PathGeometric &>(path).getStates())
                p.push_back(toVector(s));
            unwrap(p);
            library_->add(p);
        }

        void PathSeed::setup()
        {
            Planner::setup();
        }

        void PathSeed::clear()
        {
            Planner::clear();
            decoded_.clear();
            candidateIds_.clear();
            solution_.clear();
            scratch_.reset();
            lastSource_ = NONE;
            lastChecks_ = 0;
        }

        bool PathSeed::recall(const ob::State *start, const ob::State *goal, const ob::PlannerTerminationCondition &ptc,
                              og::PathGeometric &out)
        {
            decoded_.clear();
            anchoredPaths_.clear();
            candidateIds_.clear();
            if (library_->size() == 0 || candidates_ == 0)
                return false;
            const Eigen::VectorXd s = toVector(start), g = nearestGoal(s, toVector(goal));
            // Seeds of the nearest stored queries (start and goal together): a seed decodes best for a query like its
            // own.
            const auto seeds = library_->candidates(s, g, candidates_);
            const auto space = si_->getStateSpace();
            std::vector<Eigen::VectorXd> decoded;
            std::vector<double> reals(s.size());
            unsigned long checks = 0;
            bool found = false;
            for (const auto &seed : seeds)
            {
                if (ptc)
                    break;
                decodePath(seed.code, s, g, decoded);
                og::PathGeometric path(si_, start);
                ob::State *state = si_->allocState();
                for (std::size_t i = 1; i + 1 < decoded.size(); ++i)
                {
                    for (std::size_t k = 0; k < reals.size(); ++k)
                        reals[k] = decoded[i][k];
                    // Decoding works on the raw reals (paper 001, Table 2); the state space gives them meaning (bounds,
                    // SO(2) wrap).
                    space->copyFromReals(state, reals);
                    space->enforceBounds(state);  // joint limits clamp, continuous joints wrap
                    path.append(state);
                }
                si_->freeState(state);
                path.append(goal);
                decoded_.push_back(path);
                candidateIds_.push_back(seed.id);
                // for stitching only: the seed's own path moved to end at the new goal, and to start at the new
                // start (exact reproduction gives it back from the seed); near a narrow goal or start the seed's
                // absolute approach often fits where the decoded one, turned with the new line, does not
                if (anchored_)
                {
                    decodePath(seed.code, seed.start, seed.goal, decoded);
                    for (const Eigen::VectorXd *shift : {&g, &s})
                    {
                        const Eigen::VectorXd delta = *shift - (shift == &g ? seed.goal : seed.start);
                        og::PathGeometric moved(si_, start);
                        ob::State *m = si_->allocState();
                        for (std::size_t i = 1; i + 1 < decoded.size(); ++i)
                        {
                            for (std::size_t k = 0; k < reals.size(); ++k)
                                reals[k] = decoded[i][k] + delta[k];
                            space->copyFromReals(m, reals);
                            space->enforceBounds(m);
                            moved.append(m);
                        }
                        si_->freeState(m);
                        moved.append(goal);
                        anchoredPaths_.push_back(moved);
                    }
                }
            }
            // nearest query first: candidates() returns the seeds in that order, and decoded_ keeps it
            std::vector<std::pair<double, std::size_t>> order;
            for (std::size_t i = 0; i < decoded_.size(); ++i)
                order.emplace_back(static_cast<double>(i), i);
            std::stable_sort(order.begin(), order.end());
            for (const auto &o : order)
            {
                if (ptc)
                    break;
                // The first decoded path that passes every state and motion check is the answer as it is: paper 001's
                // case of a new query that the seed's shape already fits, with no repair at all.
                if (checkPathFailFast(si_, decoded_[o.second], ptc, &checks, threads_, checkThreads_.get()))
                {
                    out = decoded_[o.second];
                    lastSource_ = RECALL;
                    library_->markUsed(candidateIds_[o.second]);
                    found = true;
                    break;
                }
            }
            lastChecks_ += checks;
            return found;
        }

        bool PathSeed::stitch(const ob::PlannerTerminationCondition &ptc, og::PathGeometric &out)
        {
            std::vector<og::PathGeometric> all(decoded_);
            all.insert(all.end(), anchoredPaths_.begin(), anchoredPaths_.end());
            unsigned long checks = 0;
            const bool found =
                // Stitching needs at least two paths to combine; one path that failed its checks cannot be helped by
                // itself.
                stitch_ && all.size() > 1 &&
                stitchPaths(si_, all, ptc, out, neighbours_, &checks, threads_, checkThreads_.get());
            if (found)
            {
                lastSource_ = STITCH;
                // every candidate was in the graph the stitched path came from
                for (const auto id : candidateIds_)
                    library_->markUsed(id);
            }
            lastChecks_ += checks;
            return found;
        }

        bool PathSeed::repair(const ob::PlannerTerminationCondition &ptc, og::PathGeometric &out)
        {
            bool repaired = false;
            if (repair_ != "none")
                for (std::size_t i = 0; i < decoded_.size() && !ptc && !repaired; ++i)
                {
                    og::PathGeometric path = decoded_[i];
                    // Paper 001 repairs the decoded path with STOMP (initial trajectory = the decoded path); michi
                    // replans only the invalid stretches with RRT-Connect (STOMP measured and removed, path-seed.md).
                    repaired = repairWithRRTConnect(si_, path, ptc, range_, shortcutSteps_);
                    if (repaired)
                    {
                        out = path;
                        lastSource_ = REPAIR;
                        library_->markUsed(candidateIds_[i]);
                    }
                }
            return repaired;
        }

        bool PathSeed::fromScratch(const ob::State *start, const ob::PlannerTerminationCondition &ptc,
                                   og::PathGeometric &out)
        {
            // A problem definition of its own: RRT-Connect must not add its solution to the caller's pdef_, where it
            // would compete with the one PathSeed reports.
            auto pdef = std::make_shared<ob::ProblemDefinition>(si_);
            pdef->addStartState(start);
            pdef->setGoal(pdef_->getGoal());
            auto rrt = std::make_shared<og::RRTConnect>(si_);
            if (range_ > 0.)
                rrt->setRange(range_);
            rrt->setProblemDefinition(pdef);
            rrt->setup();
            scratch_ = rrt;
            if (rrt->solve(ptc) != ob::PlannerStatus::EXACT_SOLUTION)
                return false;
            out = *pdef->getSolutionPath()->as<og::PathGeometric>();
            return true;
        }

        void PathSeed::learn(const og::PathGeometric &path)
        {
            og::PathGeometric copy(path);
            og::PathSimplifier simplifier(si_);
            simplifier.reduceVertices(copy);  // fewer waypoints: a smaller seed that decodes to fewer motions
            addExperience(copy);
        }

        ob::PlannerStatus PathSeed::solve(const ob::PlannerTerminationCondition &ptc)
        {
            checkValidity();
            lastSource_ = NONE;
            lastChecks_ = 0;
            decoded_.clear();
            solution_.clear();
            // the check helpers live as long as the planner (or until check_threads changes), not one query
            if (threads_ <= 1)
                checkThreads_.reset();
            else if (!checkThreads_ || checkThreads_->helpers() != threads_ - 1)
                checkThreads_ = std::make_unique<CheckThreads>(threads_ - 1);
            // Every solve decodes for the problem's start afresh, so the input states are read again: OMPL's
            // PlannerInputStates hands each state out once, and a second solve() without clear() found no start.
            pis_.restart();
            const ob::State *start = pis_.nextStart();
            if (start == nullptr)
            {
                OMPL_ERROR("%s: no valid start state", getName().c_str());
                return ob::PlannerStatus::INVALID_START;
            }
            const ob::State *goal = nullptr;
            // A single goal state is taken as it is; other goal regions are sampled once, since decoding needs one
            // goal.
            if (auto *gs = dynamic_cast<const ob::GoalState *>(pdef_->getGoal().get()))
                goal = gs->getState();
            else
                goal = pis_.nextGoal(ptc);
            if (goal == nullptr)
            {
                OMPL_ERROR("%s: no valid goal state", getName().c_str());
                return ptc ? ob::PlannerStatus::TIMEOUT : ob::PlannerStatus::INVALID_GOAL;
            }

            // inner ends both racers as soon as either has a path (or the caller's ptc fires).
            std::atomic<bool> done{false};
            const ob::PlannerTerminationCondition inner =
                ob::plannerOrTerminationCondition(ptc, ob::PlannerTerminationCondition(
                                                           [&done]
                                                           {
                                                               return done.load();
                                                           }));
            // recall first, alone: decoding, the fail-fast checks of the candidates and stitching are cheap, and a
            // racer would only halve the CPU they get; if they give no valid path, repair races RRT-Connect
            og::PathGeometric recalled(si_), scratch(si_);
            bool recallSolved = recall(start, goal, ptc, recalled) || (!ptc && stitch(ptc, recalled));
            bool scratchSolved = false;
            if (!recallSolved && !ptc)
            {
                std::thread racer;
                // RRT-Connect from scratch in a second thread while repair runs on this one: a query the library does
                // not fit still gets RRT-Connect's answer while repair tries.
                if (race_)
                    racer = std::thread(
                        [&]
                        {
                            scratchSolved = fromScratch(start, inner, scratch);
                            if (scratchSolved)
                                done = true;
                        });
                recallSolved = repair(inner, recalled);
                if (recallSolved)
                    done = true;
                // without racing, RRT-Connect from scratch runs only after repair has failed, with the time left
                if (racer.joinable())
                    racer.join();
                else if (!recallSolved && !ptc)
                    scratchSolved = fromScratch(start, ptc, scratch);
            }

            og::PathGeometric *result = nullptr;
            if (recallSolved)
                result = &recalled;
            else if (scratchSolved)
            {
                result = &scratch;
                lastSource_ = SCRATCH;
            }
            if (result == nullptr)
                return ptc ? ob::PlannerStatus::TIMEOUT : ob::PlannerStatus::ABORT;
            solution_.push_back(*result);
            auto path = std::make_shared<og::PathGeometric>(*result);
            ob::PlannerSolution solution(path);
            solution.setPlannerName(getName());
            pdef_->addSolutionPath(solution);
            // A recalled or stitched path is made of seeds already in the library; a repaired or new path is new
            // experience.
            if (learn_ && lastSource_ != RECALL && lastSource_ != STITCH)
                learn(*result);
            return ob::PlannerStatus::EXACT_SOLUTION;
        }

        void PathSeed::getPlannerData(ob::PlannerData &data) const
        {
            Planner::getPlannerData(data);
            if (scratch_)
                scratch_->getPlannerData(data);
            auto addPath = [&](const og::PathGeometric &path)
            {
                const auto &states =
                    const_cast<og::PathGeometric &>(path).getStates();  // OMPL 1.5: no const getStates()
                for (std::size_t i = 0; i + 1 < states.size(); ++i)
                    data.addEdge(ob::PlannerDataVertex(states[i]), ob::PlannerDataVertex(states[i + 1]));
                if (!states.empty())
                {
                    data.addStartVertex(ob::PlannerDataVertex(states.front()));
                    data.addGoalVertex(ob::PlannerDataVertex(states.back()));
                }
            };
            for (const auto &p : decoded_)
                addPath(p);
            for (const auto &p : solution_)
                addPath(p);
        }
    }  // namespace planners
}  // namespace michi
