#ifndef MICHI_PLANNERS_PATH_SEED_
#define MICHI_PLANNERS_PATH_SEED_

#include <michi/planners/experience/ExperiencePlanner.h>
#include <michi/planners/path_seed/PathSeedLibrary.h>
#include <michi/planners/path_seed/PathSeedRepair.h>

#include <ompl/base/Planner.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/Exception.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace michi
{
    namespace planners
    {
        /**
           @anchor michiPathSeed
           @par Short description
           Experience planner built on path seeds: solved paths are stored as seeds that do not depend on start,
           goal or link lengths (per waypoint: the ratio r of its foot of perpendicular on the start-goal line,
           its deviation norm tau and its direction delta). For a new query the seeds of the nearest stored
           queries are decoded for the new start and goal and checked (states first, then motions round-robin in
           bisection order, to fail fast); the first valid one is the solution. When none is valid, the decoded
           paths and the seeds' own paths moved to the new goal or start are stitched lazily into one valid path
           where they allow it. Failing that, the decoded paths are repaired (RRT-Connect between the nearest valid
           waypoints, then shortcutting; the paper uses STOMP, which michi measured and removed: docs/path-seed.md)
           while RRT-Connect from
           scratch races in a second thread, as in OMPL's Lightning: the first valid path wins. Solutions that did
           not come from recall or stitching are learned as new seeds (parameter learn). clear() forgets the query,
           never the library.
           @par External documentation
           T. Watanabe and T. Nishida, "Implementation and evaluation of information extraction methods for paths
           of articulated robots" (path seeds; in Japanese). See docs/path-seed.md for the decisions michi took
           where the paper is silent.
        */
        class PathSeed : public ompl::base::Planner, public ExperiencePlanner
        {
        public:
            explicit PathSeed(const ompl::base::SpaceInformationPtr &si);
            ~PathSeed() override;

            ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
            void clear() override;
            void setup() override;
            void getPlannerData(ompl::base::PlannerData &data) const override;

            void addExperience(const ompl::geometric::PathGeometric &path) override;
            std::size_t experienceCount() const override;
            /** \brief Same as setLibraryFile(): a path seed library file (PathSeedLibrary::save). */
            bool loadExperience(const std::string &file) override;

            /** \brief Load a library file (PathSeedLibrary::load; throws PathSeedFileError for a bad file) and use
                it; an empty name keeps the current library. When the variant was set (setVariant) to another than the
                file's, the file is refused (ompl::Exception naming the file and both variants). */
            void setLibraryFile(const std::string &file);
            const std::string &getLibraryFile() const
            {
                return libraryFile_;
            }
            /** \brief Write the current library. */
            void saveLibrary(const std::string &file) const;
            const PathSeedLibraryPtr &getLibrary() const
            {
                return library_;
            }
            void setLibrary(PathSeedLibraryPtr library);

            /** \brief Number of library seeds decoded per query (nearest queries first). */
            void setCandidates(unsigned int k)
            {
                candidates_ = k;
            }
            unsigned int getCandidates() const
            {
                return candidates_;
            }
            /** \brief At most this many seeds in the library (0: no bound; PathSeedLibrary::setCapacity): with
                learn on, the seeds that took part in the fewest solutions are forgotten first. */
            void setMaxSeeds(unsigned int seeds);
            unsigned int getMaxSeeds() const
            {
                return maxSeeds_;
            }
            /** \brief "rrtconnect" (default) or "none". */
            void setRepair(const std::string &method);
            const std::string &getRepair() const
            {
                return repair_;
            }
            /** \brief "blocks" (the paper's, default) or "rotation". Changing it empties the library, unless the
                library was loaded from library_file: a file of another variant is refused (ompl::Exception naming the
                file and both variants), whichever of the two is set first. */
            void setVariant(const std::string &variant);
            std::string getVariant() const;
            /** \brief Race RRT-Connect from scratch in a second thread (default); without it, RRT-Connect runs
                after a failed recall. */
            void setRace(bool race)
            {
                race_ = race;
            }
            bool getRace() const
            {
                return race_;
            }
            /** \brief Learn solutions that did not come from a valid recall as new seeds. */
            void setLearn(bool learn)
            {
                learn_ = learn;
            }
            bool getLearn() const
            {
                return learn_;
            }
            /** \brief Before repairing, stitch the decoded candidates into one valid path when they allow it
                (stitchPaths(): a lazy shortest path over their states and segments; default on). */
            void setStitch(bool stitch)
            {
                stitch_ = stitch;
            }
            bool getStitch() const
            {
                return stitch_;
            }
            /** \brief Stitching also uses each candidate seed's own path moved to end at the new goal and to
                start at the new start (default on). */
            void setAnchored(bool anchored)
            {
                anchored_ = anchored;
            }
            bool getAnchored() const
            {
                return anchored_;
            }
            /** \brief Stitching joins each state to this many nearest states of every other path. */
            void setStitchNeighbours(unsigned int k)
            {
                neighbours_ = k;
            }
            unsigned int getStitchNeighbours() const
            {
                return neighbours_;
            }
            /** \brief The most check_threads (its declared range and the setter's bound). */
            static constexpr unsigned int MAX_CHECK_THREADS = 8;
            /** \brief Threads that share the state checks of recall and stitching (default 1: none; on a loaded machine
             * more threads were slower). */
            void setCheckThreads(unsigned int threads)
            {
                // the declared range: helper threads are started for the planner's life, and 100,000 of them (or -1,
                // which wraps) ended the process with std::system_error
                if (threads > MAX_CHECK_THREADS)
                    throw ompl::Exception("PathSeed: check_threads must be in [1, " +
                                          std::to_string(MAX_CHECK_THREADS) + "]");
                threads_ = std::max(1u, threads);
            }
            unsigned int getCheckThreads() const
            {
                return threads_;
            }
            /** \brief Step of the RRT-Connect runs (from scratch and in repair); 0: OMPL's default. */
            void setRange(double range)
            {
                range_ = range;
            }
            double getRange() const
            {
                return range_;
            }
            /** \brief Shortcut attempts after an RRT-Connect repair. */
            void setShortcutSteps(unsigned int steps)
            {
                shortcutSteps_ = steps;
            }
            unsigned int getShortcutSteps() const
            {
                return shortcutSteps_;
            }

            /** \brief What gave the last solution: "recall", "stitch", "repair", "scratch" or "" (none). */
            std::string getLastSource() const;
            /** \brief State validity checks spent on recall and repair in the last solve (not the racer's). */
            unsigned long getLastRecallChecks() const
            {
                return lastChecks_;
            }

        private:
            /** Decode and check (fail-fast) the seeds of the nearest queries; true with the first valid in \e out.
                The decoded paths stay in decoded_. */
            bool recall(const ompl::base::State *start, const ompl::base::State *goal,
                        const ompl::base::PlannerTerminationCondition &ptc, ompl::geometric::PathGeometric &out);
            /** Stitch the decoded and anchored paths (stitchPaths()); true with a valid \e out. */
            bool stitch(const ompl::base::PlannerTerminationCondition &ptc, ompl::geometric::PathGeometric &out);
            /** Repair the decoded paths one by one (nearest first); true with a valid \e out. */
            bool repair(const ompl::base::PlannerTerminationCondition &ptc, ompl::geometric::PathGeometric &out);
            bool fromScratch(const ompl::base::State *start, const ompl::base::PlannerTerminationCondition &ptc,
                             ompl::geometric::PathGeometric &out);
            Eigen::VectorXd toVector(const ompl::base::State *state) const;
            /** Continuous joints (SO(2) components) of \e path made continuous: each waypoint's value is its
                predecessor's plus the wrapped difference, so a path across +-pi is encoded without the 2 pi jump. */
            void unwrap(std::vector<Eigen::VectorXd> &path) const;
            /** \e goal's continuous joints moved by 2 pi k to within pi of \e start's: the short way round, the way
                the state space interpolates, is the start-goal line a seed decodes on. */
            Eigen::VectorXd nearestGoal(const Eigen::VectorXd &start, const Eigen::VectorXd &goal) const;
            void learn(const ompl::geometric::PathGeometric &path);

            PathSeedLibraryPtr library_;
            std::string libraryFile_;
            /// library_ is the one loaded from libraryFile_ (setLibraryFile), which setVariant() must not replace
            bool libraryFromFile_{false};
            /// the variant setVariant() asked for, if it was called: a library file of another variant is refused
            std::optional<SeedVariant> variant_;
            std::vector<char> continuous_;  ///< per value of a state: an SO(2) component (wraps at +-pi)
            unsigned int candidates_{10};
            unsigned int maxSeeds_{0};
            std::vector<std::uint64_t> candidateIds_;  ///< library ids of the decoded_ paths' seeds
            std::string repair_{"rrtconnect"};
            bool race_{true};
            bool stitch_{true};
            bool learn_{true};
            double range_{0.};
            unsigned int shortcutSteps_{20};

            /// what the last solve built, for getPlannerData: decoded candidates, the solution, the racer's data
            std::vector<ompl::geometric::PathGeometric> decoded_;
            std::vector<ompl::geometric::PathGeometric> anchoredPaths_;  ///< seeds' own paths moved to s~ or g~
            bool anchored_{true};
            unsigned int neighbours_{3};
            unsigned int threads_{1};
            /// helpers for the shared-out checks, made at the first solve() with check_threads > 1 and kept
            std::unique_ptr<CheckThreads> checkThreads_;
            std::vector<ompl::geometric::PathGeometric> solution_;
            ompl::base::PlannerPtr scratch_;
            std::atomic<int> lastSource_{0};
            std::atomic<unsigned long> lastChecks_{0};
        };
    }  // namespace planners
}  // namespace michi

#endif
