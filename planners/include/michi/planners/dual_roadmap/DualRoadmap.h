#ifndef MICHI_PLANNERS_DUAL_ROADMAP_
#define MICHI_PLANNERS_DUAL_ROADMAP_

#include <ompl/base/Planner.h>
#include <ompl/datastructures/NearestNeighbors.h>
#include <ompl/util/Exception.h>
#include <ompl/util/RandomNumbers.h>

#include <michi/planners/dual_roadmap/RoadmapSearch.h>

#include <Eigen/Core>

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <deque>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace planners
    {
        class TaskLevel;

        /**
           @anchor michiDualRoadmap
           @par Short description
           A PRM-like planner with two roadmaps, made for replanning while the world changes. The
           <em>learning roadmap</em> keeps every local path (edge) that was ever found collision-free, across
           queries and scene changes (and across runs: saveLearningRoadmap() / loadLearningRoadmap()). The
           <em>working roadmap</em> belongs to the current scene. An empty working roadmap (the first query, after
           clear() or loadLearningRoadmap()) is seeded with the learning-roadmap edges nearest the query (seed_edges
           of them). When the scene changes, nothing is rebuilt: every vertex and edge of the working roadmap becomes
           "unknown" (a scene epoch is incremented, no work per vertex) and is re-checked lazily, only where a
           candidate shortest path goes, so the work of a query after a change is local to the query and to the
           part of its path the change touched; an owner that knows where the scene changed says so
           (notifySceneChanged(ChangeRegion)) and what was proved elsewhere stays known. With lazy_seeding = 0 the
           working roadmap is instead rebuilt at every change from learning edges checked at once; the ablation
           (use_learning = 0) rebuilds it empty. Start and goal are
           connected to their nearest vertices and the roadmap is expanded by uniform samples only when no candidate
           path is left, with edges checked lazily (as LazyPRM does). Edges that the search proved valid are added to
           the learning roadmap. The path found is smoothed (redundant vertices removed, shortcuts).

           How the planner learns that the scene changed (it only has \e si): either the owner calls
           notifySceneChanged(), or it installs a change counter with setSceneChangeCounter() (for michi's
           validity::Scene: `[scene] { return scene->changeCount(); }`) which solve() compares with the value it
           saw last. Without either, every solve() is treated as a new scene (always safe: nothing checked in an
           earlier solve() is trusted).

           clear() forgets the working roadmap and the query, not the learning roadmap (the experience, as OMPL's
           experience planners keep their database); clearLearningRoadmap() forgets it. Works in any state space
           that supports copyToReals / copyFromReals (for the file) and a uniform sampler.

           @par External documentation
           E. Yoshida, F. Kanehiro, K. Yokoi, P. Gergondet, "Online replanning for reactive robot motion: practical
           aspects", IROS 2010, pp. 5927-5933, DOI 10.1109/IROS.2010.5649645; E. Yoshida, F. Kanehiro, "Reactive
           robot motion using path replanning and deformation", ICRA 2011, pp. 5457-5462,
           DOI 10.1109/ICRA.2011.5980361. See docs/dual-roadmap.md.
        */
        class DualRoadmap : public ompl::base::Planner
        {
        public:
            explicit DualRoadmap(const ompl::base::SpaceInformationPtr &si);
            ~DualRoadmap() override;

            ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
            /** \brief Forget the working roadmap and the query (the learning roadmap stays). */
            void clear() override;
            void setup() override;
            /** \brief Working roadmap vertices (tag 0) and edges, then the learning roadmap's vertices (tag 1) and
                edges. */
            void getPlannerData(ompl::base::PlannerData &data) const override;

            /** \brief The scene changed: nothing the working roadmap proved before is trusted in the next solve().
                Thread-safe. */
            void notifySceneChanged();
            /** \brief Whether a scene change may have changed the validity of the motion from \e a to \e b (a == b:
                of the state a). Conservative: true when unsure. */
            using ChangeRegion = std::function<bool(const ompl::base::State *a, const ompl::base::State *b)>;
            /** \brief The scene changed only where \e affects says, since the scene of the last solve(): what the
                working roadmap proved valid or invalid elsewhere stays known (the change is "local"), the rest is
                re-checked lazily. Thread-safe; the next solve() takes it as the change it detects (with a change
                counter, the counter must also have moved). An empty function: the whole scene changed. */
            void notifySceneChanged(ChangeRegion affects);
            /** \brief A function returning a number that changes whenever the scene changes; solve() compares it
                with the value of its previous solve(). An empty function: every solve() is a new scene. */
            void setSceneChangeCounter(std::function<std::uint64_t()> counter);

            /** \brief Forget the learning roadmap. */
            void clearLearningRoadmap();
            /** \brief Write the learning roadmap to a text file (states as reals); throws std::runtime_error
                naming the file. */
            void saveLearningRoadmap(const std::string &file) const;
            /** \brief Replace the learning roadmap by the one in \e file; throws std::runtime_error naming the file
                and what is wrong (other space, dimension, malformed). */
            void loadLearningRoadmap(const std::string &file);

            std::size_t learningVertexCount() const
            {
                return learnStates_.size();
            }
            std::size_t learningEdgeCount() const
            {
                return learnEdges_.size();
            }
            std::size_t workingVertexCount() const;
            std::size_t workingEdgeCount() const;
            /** \brief Learning edges the working roadmap held for the current scene when it began: seeded into an
                empty or rebuilt working roadmap, or kept from the previous scene (to be re-checked lazily). */
            std::size_t seededEdgeCount() const
            {
                return seeded_;
            }
            /** \brief What the last solve() did, in counts (not time): a test or a profile can compare planners'
                work without a clock. */
            struct Work
            {
                std::uint64_t stateChecks{0};   ///< isValid() calls (seeding, lazy vertex checks, edge probes, samples)
                std::uint64_t motionChecks{0};  ///< checkMotion() calls (seeding, lazy edge checks)
                std::uint64_t samples{0};       ///< samples drawn to expand the roadmap (uniform or dominant_dofs)
                std::uint64_t searches{0};      ///< A* searches
                std::uint64_t expansions{0};    ///< vertices the searches expanded
            };
            const Work &lastWork() const
            {
                return work_;
            }

            /** \brief Use the learning roadmap (seed from it, add to it); false is the ablation: a plain lazy
                roadmap rebuilt at every scene change. */
            void setUseLearning(bool use)
            {
                useLearning_ = use;
            }
            bool getUseLearning() const
            {
                return useLearning_;
            }
            /** \brief Learning edges put into an empty working roadmap: those nearest the query's start and goal. */
            void setSeedEdges(unsigned int n)
            {
                seedEdges_ = n;
            }
            unsigned int getSeedEdges() const
            {
                return seedEdges_;
            }
            /** \brief Neighbours each new vertex is connected to (lazily). */
            void setMaxNearestNeighbors(unsigned int k)
            {
                k_ = k;
            }
            unsigned int getMaxNearestNeighbors() const
            {
                return k_;
            }
            /** \brief Longest edge, as a fraction of the space's maximum extent. */
            void setRangeFraction(double f)
            {
                rangeFraction_ = f;
            }
            double getRangeFraction() const
            {
                return rangeFraction_;
            }
            /** \brief Uniform samples added per expansion round. */
            void setBatchSize(unsigned int n)
            {
                batchSize_ = n;
            }
            unsigned int getBatchSize() const
            {
                return batchSize_;
            }
            /** \brief Smooth found paths (remove redundant vertices, shortcut). */
            void setSmooth(bool smooth)
            {
                smooth_ = smooth;
            }
            bool getSmooth() const
            {
                return smooth_;
            }
            /** \brief true: seed and keep the working roadmap lazily (states and motions re-checked only on a
                candidate path, also after a scene change); false: rebuild it at every scene change from learning
                edges whose states and motion are checked at once, so it holds only local paths proved valid. */
            void setLazySeeding(bool lazy)
            {
                lazySeeding_ = lazy;
            }
            bool getLazySeeding() const
            {
                return lazySeeding_;
            }
            /** \brief The learning roadmap stops growing at this many edges. */
            void setMaxLearningEdges(unsigned int n)
            {
                maxLearningEdges_ = n;
            }
            unsigned int getMaxLearningEdges() const
            {
                return maxLearningEdges_;
            }

            /** \brief The working roadmap takes no more uniform samples beyond this many vertices. A roadmap kept
                from earlier queries is then started afresh once (seeded from the learning roadmap near the query);
                a query that fills a roadmap of its own and finds no path fails (the executor asks again later, when
                the moving obstacles have moved) instead of filling the roadmap, and every later search, with
                samples. */
            void setMaxWorkingVertices(unsigned int n)
            {
                maxWorkingVertices_ = n;
            }
            unsigned int getMaxWorkingVertices() const
            {
                return maxWorkingVertices_;
            }
            /** \brief Start a full working roadmap kept from earlier queries afresh, once per query, and drop one
                that a failed query filled before the next query (default); false: the query fails as on a roadmap
                it filled itself, and the roadmap is kept (the ablation of these rules). */
            void setRestartWhenFull(bool restart)
            {
                restartWhenFull_ = restart;
            }
            bool getRestartWhenFull() const
            {
                return restartWhenFull_;
            }
            /** \brief Times a full working roadmap kept from earlier queries was started afresh
                (setMaxWorkingVertices), since construction. */
            std::size_t workingRestarts() const
            {
                return restarts_;
            }

            /** \brief Weight factor, in the search, of an edge not (yet) proved valid in the current scene: > 1
                makes the search prefer motions that need no check, so after a local change a path goes round
                what must be re-checked (fewer checks, possibly longer paths); 1: plain shortest paths. */
            void setUnknownEdgePenalty(double f)
            {
                unknownPenalty_ = f;
            }
            double getUnknownEdgePenalty() const
            {
                return unknownPenalty_;
            }

            /** \brief Further weight factor, in the search, of an unknown edge that was found invalid (or leads to a
                state found invalid) in one of the last 32 scenes: a change near it made the record stale, but a
                moving obstacle that blocked it a moment ago most likely still does, so the search tries other
                unknown edges first (each refutation costs a motion check and a search). 1: no memory. */
            void setRefutedEdgePenalty(double f)
            {
                refutedPenalty_ = f;
            }
            double getRefutedEdgePenalty() const
            {
                return refutedPenalty_;
            }

            /** \brief Weight of the heuristic in the roadmap search (weighted A*): 1 gives the shortest path in the
                search's edge costs; w > 1 a path at most w times as costly, found after expanding far fewer vertices.
                A query searches once per refuted edge, and on a working roadmap of thousands of vertices the
                searches can be most of a query's time. Default 1: weight 2 lowered the median replanning latency
                but tripled the failed queries (a full working roadmap with no path for the query;
                docs/dual-roadmap.md, 2026-11-27). */
            void setSearchWeight(double w)
            {
                if (!(w >= 1.))
                    throw ompl::Exception("DualRoadmap: search_weight must be at least 1");
                searchWeight_ = w;
                ++goalSet_;  // the cached heuristic values hold the old weight
            }
            double getSearchWeight() const
            {
                return searchWeight_;
            }

            /** \brief The most edge_probes (its declared range and the setter's bound). */
            static constexpr unsigned int MAX_EDGE_PROBES = 15;
            /** \brief States inside an unproved edge checked before its motion check (at 1/2, 1/4, 3/4, ... of the
                motion): one found invalid refutes the edge for the price of a state check. Most edges of a lazy
                candidate path that fail, fail there, and a failing motion check walks far before it finds the
                collision; an edge that passes gets its full motion check as before. 0: none. */
            void setEdgeProbes(unsigned int n)
            {
                // the declared range: each probe is a state check of every unproved edge a search takes, and a count
                // near UINT_MAX never ended
                if (n > MAX_EDGE_PROBES)
                    throw ompl::Exception("DualRoadmap: edge_probes must be in [0, " + std::to_string(MAX_EDGE_PROBES) +
                                          "]");
                edgeProbes_ = n;
            }
            unsigned int getEdgeProbes() const
            {
                return edgeProbes_;
            }

            /** \brief A motion proved valid before a local scene change (notifySceneChanged(ChangeRegion)) that the
                change may affect is re-checked only over its affected parts: it is halved \e depth times at most,
                the change region asked about each part, and only runs of affected parts of 1/2^depth of the motion
                are checked again (the rest stands proved, as whole motions the change does not touch do). Long
                edges (smoothing shortcuts) then cost what the change touches, not their whole length. Used where
                the space interpolates a part as the motion passes through it (checked at each part's middle),
                else the whole motion is checked. 0: always the whole motion. */
            void setRecheckDepth(unsigned int depth)
            {
                recheckDepth_ = depth;
            }
            unsigned int getRecheckDepth() const
            {
                return recheckDepth_;
            }

            /** \brief Paper 002's narrowing of the search to the dominant degrees of freedom: when a query must
                sample, half of each batch is drawn near the start-goal line along the \e n principal directions of
                the learning roadmap's local paths nearest the query (each as far as those paths' states spread
                along it), not in the other directions; the other half stays uniform. 0 (default): uniform only. */
            void setDominantDofs(unsigned int n)
            {
                dominantDofs_ = n;
            }
            unsigned int getDominantDofs() const
            {
                return dominantDofs_;
            }

            /** \brief The hand (end effector) of a state, for the task level (setTaskLevel()): its position and,
                when \e jacobian is not null, its 3 x n Jacobian, d position / d reals (StateSpace::copyToReals
                order). An arm's owner installs it (handTaskMap(): the last body of the robot group, RobotModel's
                Jacobian; `michi bench` and `michi replan` do so); without one the task level does nothing. */
            using TaskMap =
                std::function<void(const ompl::base::State *state, Eigen::Vector3d &hand, Eigen::MatrixXd *jacobian)>;
            void setTaskMap(TaskMap map);
            /** \brief Paper 002's hierarchical roadmap for arms: when a query must sample, a quarter of each batch
                is drawn from each end of the query along the hand's way through the task space (TaskLevel: a grid
                of hand positions where the cells the working roadmap's states were found invalid in cost more), each
                waypoint realised as a joint state by Jacobian-transpose micro-motions from the previous one (no
                inverse); the other half stays uniform. Needs setTaskMap(). false (default): uniform only. */
            void setTaskLevel(bool on)
            {
                taskLevel_ = on;
            }
            bool getTaskLevel() const
            {
                return taskLevel_;
            }
            /** \brief Side of the task level's cells, in metres of hand position. */
            void setTaskCell(double cell)
            {
                if (!(cell > 0.))
                    throw ompl::Exception("DualRoadmap: task_cell must be positive");
                taskCell_ = cell;
            }
            double getTaskCell() const
            {
                return taskCell_;
            }

        private:
            // Validity in a scene is recorded as the scene's epoch (epoch_): a scene change makes every record stale
            // at once, without touching the roadmap.
            struct VertexProperties
            {
                ompl::base::State *state{nullptr};
                long learnId{-1};            ///< index in the learning roadmap, -1 when not (yet) there
                std::uint64_t validIn{0};    ///< epoch in which the state was proved valid
                std::uint64_t invalidIn{0};  ///< epoch in which it was found invalid
                std::uint64_t refutedIn{0};  ///< epoch in which it was last found invalid (kept when that is stale)
            };
            struct EdgeProperties
            {
                std::uint64_t validIn{0};    ///< epoch in which the motion was proved valid
                std::uint64_t invalidIn{0};  ///< epoch in which it was found invalid
                std::uint64_t refutedIn{0};  ///< epoch in which it was last found invalid (kept when that is stale)
                std::uint64_t provedIn{0};   ///< epoch of its last proof (kept when stale; 0 once refuted)
                bool learned{false};         ///< in the learning roadmap (proved valid in some scene)
            };
            using Graph = FlatRoadmap<VertexProperties, EdgeProperties>;
            using Vertex = Graph::Vertex;
            using Edge = Graph::Edge;

            void freeWorking();
            /** \brief The dominant directions (setDominantDofs) for a query from \e start to \e goal, from the
                learning roadmap's local paths nearest them: dominant_ (reals x directions); empty when too few. */
            void findDominantDirections(const ompl::base::State *start, const ompl::base::State *goal);
            /** \brief A state near the start-goal line (dominantFrom_ to dominantTo_) along the dominant directions. */
            void sampleDominant(ompl::base::State *state);
            /** \brief The hand of vertex \e v (the task map's, cached: a vertex's state never changes). */
            const Eigen::Vector3d &handOf(Vertex v);
            /** \brief The task level's part of an expansion batch (setTaskLevel()): the hand's route from \e start
                to \e goal over the cells, realised from both ends as joint states added to the working roadmap. */
            void expandAlongTaskRoute(const ompl::base::State *start, const ompl::base::State *goal,
                                      const ompl::base::PlannerTerminationCondition &ptc);
            /** \brief From \e q (reals), Jacobian-transpose steps that bring the hand to \e target. */
            void moveHandTowards(std::vector<double> &q, const Eigen::Vector3d &target);
            /** \brief Put the learning edges nearest \e near (the query's states) into the empty working roadmap. */
            void seedWorking(const std::vector<const ompl::base::State *> &near,
                             const ompl::base::PlannerTerminationCondition &ptc);
            Vertex addWorkingVertex(ompl::base::State *state, long learnId);
            /** \brief The edge a - b (its length the states' distance), added unless it exists (second: added). */
            std::pair<Edge, bool> addEdgeOnce(Vertex a, Vertex b);
            /** \brief A start or goal: the vertex of a recent query's at the same state, else a new one; valid in
                this scene. */
            Vertex addQueryVertex(const ompl::base::State *state);
            /** \brief \e v joins the recent query vertices (at most 8) that addQueryVertex() reuses. */
            Vertex rememberQueryVertex(Vertex v);
            /** \brief No change since epoch \e since (> 0) affects the motion \e a -> \e b (a == b: the state). */
            bool unaffectedSince(std::uint64_t since, const ompl::base::State *a, const ompl::base::State *b) const;
            /** A proof (\e stamp: the epoch it was made in) of the state or motion a-b, renewed to this epoch
                when no scene change since touched it, else forgotten; true when it holds now. */
            bool stillProved(std::uint64_t &stamp, const ompl::base::State *a, const ompl::base::State *b) const
            {
                // The common cases without a call: made in this scene, or never (the search asks for every arc it
                // relaxes, and an out-of-line call through the library's PLT was a sizeable part of its loop).
                if (stamp == epoch_ || stamp == 0)
                    return stamp != 0;
                return renewProof(stamp, a, b);
            }
            /** stillProved() for a proof made in an earlier scene. */
            bool renewProof(std::uint64_t &stamp, const ompl::base::State *a, const ompl::base::State *b) const;
            /** \brief Scenes over which a refutation raises an unknown edge's weight (setRefutedEdgePenalty()). */
            static constexpr std::uint64_t REFUTED_MEMORY = 32;
            /** \brief A refutation made in epoch \e refutedIn (0: none) is recent (setRefutedEdgePenalty()). */
            bool recentlyRefuted(std::uint64_t refutedIn) const
            {
                return refutedIn != 0 && epoch_ - refutedIn < REFUTED_MEMORY;
            }
            bool knownValid(Vertex v)
            {
                auto &p = graph_[v];
                return stillProved(p.validIn, p.state, p.state);
            }
            bool knownInvalid(Vertex v)
            {
                auto &p = graph_[v];
                return stillProved(p.invalidIn, p.state, p.state);
            }
            /** stillProved() for a record of edge \e e: its ends' states are read only when it must be renewed. */
            bool edgeRecordHolds(std::uint64_t &stamp, Edge e)
            {
                if (stamp == epoch_ || stamp == 0)
                    return stamp != 0;
                const auto &ends = graph_.ends(e);
                return renewProof(stamp, graph_[ends.first].state, graph_[ends.second].state);
            }
            bool knownValidEdge(Edge e)
            {
                return edgeRecordHolds(graph_.edge(e).validIn, e);
            }
            bool knownInvalidEdge(Edge e)
            {
                return edgeRecordHolds(graph_.edge(e).invalidIn, e);
            }
            /** \brief Motion \e a -> \e b valid in this scene, from the roadmap's records or checked (and recorded
                as an edge: a proved shortcut is a local path like any other). */
            bool motionValid(Vertex a, Vertex b);
            /** \brief One of the setEdgeProbes() states inside the motion \e a -> \e b is invalid (so is the motion).
             */
            bool refutedByProbes(Vertex a, Vertex b);
            /** \brief The motion of edge \e e from \e a to \e b, not known in this scene, checked: over the parts a
                local change since its last proof may affect (setRecheckDepth()), else whole. */
            bool checkEdgeMotion(Edge e, Vertex a, Vertex b);
            /** \brief Into \e parts, the pieces [t0, t1] of the motion a -> b that a change since epoch \e since
                may affect, halving [t0, t1] down to \e depth more levels (adjacent pieces merged). */
            void affectedParts(std::uint64_t since, Vertex a, Vertex b, double t0, double t1, unsigned int depth,
                               std::vector<std::pair<double, double>> &parts);
            /** \brief Record the motion of edge \e e (from \e a to \e b) as valid in this scene, and learn it. */
            void acceptEdge(Edge e, Vertex a, Vertex b);
            /** \brief Record the motion of edge \e e as invalid in this scene. */
            void refuteEdge(Edge e);
            /** \brief Redundant vertices removed (paper 002: found paths are smoothed): from each kept vertex, the
                farthest later one reachable by a valid straight motion among a halving sequence of candidates. */
            std::vector<Vertex> shortcut(const std::vector<Vertex> &path,
                                         const ompl::base::PlannerTerminationCondition &ptc);
            void connectLazily(Vertex v);
            bool sceneChanged();
            /** \brief A* from start to any goal vertex, into \e path; empty when none is reachable. */
            void shortestPath(Vertex start, const std::vector<Vertex> &goals, std::vector<Vertex> &path);
            /** \brief Check the states and motions of \e path not yet proved valid in this scene; every invalid state
                and the first invalid motion are marked so (impassable for this scene's searches). */
            bool validatePath(const std::vector<Vertex> &path, const ompl::base::PlannerTerminationCondition &ptc);
            long learnVertex(Vertex v);
            void learnEdge(Vertex a, Vertex b);

            Graph graph_;
            std::shared_ptr<ompl::NearestNeighbors<Vertex>> nn_;
            std::vector<Vertex> startVertices_;
            std::vector<Vertex> goalVertices_;
            std::vector<Vertex>
                queryHistory_;  ///< start and goal vertices of recent queries, reused for the same state
            ompl::base::StateSamplerPtr sampler_;

            std::vector<ompl::base::State *> learnStates_;
            std::vector<std::pair<std::size_t, std::size_t>> learnEdges_;
            std::set<std::pair<std::size_t, std::size_t>> learnEdgeSet_;

            std::function<std::uint64_t()> counter_;
            std::uint64_t lastCount_{0};
            bool haveCount_{false};
            std::atomic<bool> changed_{true};
            std::size_t seeded_{0};
            std::uint64_t epoch_{1};  ///< the current scene
            /** changes that led to the last epochs (oldest first; the last one led to epoch_); an empty region: the
                whole scene changed */
            std::deque<ChangeRegion> history_;
            std::mutex regionMutex_;
            bool haveRegion_{false};  ///< a region was given for the change not yet taken
            ChangeRegion pendingRegion_;
            RoadmapAStar astar_;
            // the heuristic (distance to the nearest goal vertex) of a vertex, computed once per goal set: valid
            // where heuristicStamp_ equals goalSet_
            std::vector<double> heuristic_;
            std::vector<std::uint64_t> heuristicStamp_;
            std::uint64_t goalSet_{0};
            std::vector<Vertex> heuristicGoals_;  ///< the goal vertices goalSet_ stands for
            std::size_t learnedWorkingEdges_{0};  ///< working edges that are in the learning roadmap
            Work work_;
            std::atomic<std::size_t> learningEdgeCountAtomic_{0};  ///< for the progress property (other thread)

            bool useLearning_{true};
            unsigned int dominantDofs_{0};
            Eigen::MatrixXd dominant_;                       ///< this query's dominant directions (columns), if any
            std::vector<double> dominantFrom_, dominantTo_;  ///< the query's start and goal as reals
            std::vector<double> dominantSample_;             ///< sampleDominant()'s reals
            /** made at the first narrowed sample: with dominant_dofs 0 every random sequence stays as it was */
            std::unique_ptr<ompl::RNG> rng_;
            TaskMap taskMap_;
            bool taskLevel_{false};
            double taskCell_{0.05};
            std::unique_ptr<TaskLevel> task_;          ///< made at the first task-level batch
            std::vector<Eigen::Vector3d> vertexHand_;  ///< handOf()'s cache (NaN: not computed yet)
            bool taskBegun_{false};                    ///< task_ holds this query's grid
            unsigned int seedEdges_{50};
            unsigned int k_{10};
            double rangeFraction_{0.3};
            unsigned int batchSize_{20};
            bool smooth_{true};
            bool lazySeeding_{true};
            unsigned int maxLearningEdges_{50000};
            unsigned int maxWorkingVertices_{2000};
            std::size_t restarts_{0};
            bool refill_{false};
            bool restartWhenFull_{true};
            double unknownPenalty_{1.5};
            double refutedPenalty_{10.};
            double searchWeight_{1.};
            unsigned int edgeProbes_{3};
            unsigned int recheckDepth_{4};
            ompl::base::State *probe_{nullptr};          ///< refutedByProbes()' state (made in setup())
            std::array<ompl::base::State *, 4> part_{};  ///< checkEdgeMotion()'s states (made in setup())
        };
    }  // namespace planners
}  // namespace michi

#endif
