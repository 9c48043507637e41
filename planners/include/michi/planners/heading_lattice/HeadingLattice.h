#ifndef MICHI_PLANNERS_HEADING_LATTICE_
#define MICHI_PLANNERS_HEADING_LATTICE_

#include <michi/planners/heading_lattice/PagedArray.h>

#include <ompl/base/Planner.h>
#include <ompl/geometric/PathGeometric.h>

#include <cstdint>
#include <array>
#include <limits>
#include <string>
#include <vector>

namespace michi
{
    namespace validity
    {
        class GridValidityChecker;
        class Scene;
    }  // namespace validity
}  // namespace michi

namespace michi
{
    namespace planners
    {
        /**
           @anchor mHeadingLattice
           @par Short description
           A deterministic graph for a robot that can only turn in place and drive straight (a long rectangle, a
           differential drive), in an SE(2) space (best in state_spaces::TurnMoveTurnStateSpace). For every heading
           θ_k = k·angle_step, nodes are laid along the heading's direction with spacing cell_size: where
           |tan θ| ≤ 1 at (x, y + x tan θ), else at (x + y / tan θ, y), x = i·cell_size, y = j·cell_size (the
           paper's equations (1)-(3), measured from the space's lower bounds). Nodes where the robot collides are
           left out. Each node of heading 0 at (i, j) forms a group with the one node of every other heading
           within cell_size of it (the lattice rows make this correspondence one-to-one). Edges join neighbours
           along a heading (driving straight; only forwards when the space forbids reversing) and adjacent headings
           of a group (turning in place). A* (Boost.Graph) searches it from the start to the goal, which are
           joined to the nodes within connection_cells·cell_size of them. Nodes of a group do not share a
           position, so the path is corrected: each run of turns is moved to the centre between the positions
           before and after it (the paper's Fig. 3; if the robot cannot follow that, to where the lines of the
           headings before and after meet). Every motion of the returned path is checked with the space's
           motion validator (the footprint, densely).

           The lattice is implicit and made on demand around the search (issue 14): a node is an id
           (group * headings + k) into flat arrays holding its validity (checked with si->isValid the first time
           the search or the heuristic needs it, then cached) and the state of its drive and turn edges. A* runs
           on that graph with an admissible heuristic: the larger of the straight-line distance to the goal and a
           2-D search over the groups with a free node (reverse resumable A*: from the goal's groups, directed at
           the start, kept per goal and map), divided by the most an 8-connected path exceeds a straight drive;
           heuristic_weight > 1 makes it weighted A* (fewer expansions, a path at most that factor longer).
           Node and search arrays are paged (PagedArray): memory follows what the search touched. Edges are checked
           lazily (LazyPRM's way): a path found by A* is checked edge by edge with the space's motion validator, the
           results cached; on a colliding edge (or turn edges of a run whose corrected motions collide) A* runs
           again. The lattice is kept across queries (new start and goal, new problem definition) as long as the
           map is the same: the same validity checker, motion validator and state space settings. When the
           checker is michi's FclValidityChecker and its scene changes (an obstacle added, removed or moved: a
           door closes), or the checker is michi's GridValidityChecker and its refresh() took in such a change,
           only the nodes and edges within reach of the obstacles that changed are forgotten (checked again when
           needed), counted in lastUpdate() and work(). clear() forgets everything, as
           OMPL's planners do. Without randomness, the same query on the same map gives the same path every time.

           @par External documentation
           K. Fujimoto, T. Moriya, Y. Nakayama, 移動方向を限定したロボットの経路生成のためのグラフ作成方法
           (Generating roadmap for mobile robot under constraint of moving direction). docs/heading-lattice.md.
        */
        class HeadingLattice : public ompl::base::Planner
        {
        public:
            explicit HeadingLattice(const ompl::base::SpaceInformationPtr &si);
            ~HeadingLattice() override;

            void setup() override;
            ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
            /** \brief Forget the graph and the query. */
            void clear() override;
            /** \brief Forget start and goal states only; the graph stays. */
            void clearQuery();
            void setProblemDefinition(const ompl::base::ProblemDefinitionPtr &pdef) override;
            /** \brief Every node (tag: its heading index), every edge known or not yet checked (weight: cost),
                start and goal states and their connections. */
            void getPlannerData(ompl::base::PlannerData &data) const override;

            /** \brief Spacing of the nodes along x and y (metres, > 0), or 0 (the default): automatic, chosen when the
                lattice is built. On a scene read from an occupancy grid (validity::Scene::gridCellSize() r > 0, through
                michi's FCL or grid checker) half a map cell, so that a door one cell wide has a row of nodes through
                its middle, but not below the robot's reach R (where the robot spans several cells, finer rows only
                multiply the nodes) nor above the paper's 0.25 m: min(0.25, max(r / 2, R)); elsewhere 0.25 m. */
            void setCellSize(double size);
            /** \brief The setting: 0 for automatic (see effectiveCellSize()). */
            double getCellSize() const
            {
                return cellSizeSetting_;
            }
            /** \brief The spacing the lattice uses: the setting, or the automatic choice once the lattice is built
                (0.25 before). */
            double effectiveCellSize() const
            {
                return cellSize_;
            }
            /** \brief Heading step (radians); rounded so that a whole number (>= 4) of steps make a full turn. */
            void setAngleStep(double step);
            double getAngleStep() const
            {
                return angleStep_;
            }
            /** \brief Start and goal are joined to the nodes within this many cell sizes (> 0; doubled up to
                three times while none can be joined). */
            void setConnectionCells(double cells);
            double getConnectionCells() const
            {
                return connectionCells_;
            }
            /** \brief A* multiplies its admissible heuristic by this (>= 1): weighted A* (Pohl), a path at most
                this many times the lattice's shortest, found with fewer expansions. 1 (default): the shortest. */
            void setHeuristicWeight(double weight);
            double getHeuristicWeight() const
            {
                return heuristicWeight_;
            }
            /** \brief After the paper's path correction, replace runs of the path by single moves of the robot
                (one motion of a TurnMoveTurnStateSpace; in a plain SE(2) space a turn on the spot, a drive along the
                heading and a turn on the spot) where the motion validator accepts them and the path gets no
                longer: the lattice's fixed headings and cell centres otherwise leave zig-zags (default on; off:
                the corrected lattice path as the paper gives it). Deterministic; every motion of the returned path
                is checked. */
            void setShortcut(bool shortcut)
            {
                shortcut_ = shortcut;
            }
            bool getShortcut() const
            {
                return shortcut_;
            }
            /** \brief A node of the lattice. */
            struct Node
            {
                double x, y;
                unsigned int heading;  ///< k: heading k * getHeadingStep()
                unsigned int group;    ///< index of the heading-0 grid point (i, j): i * rows + j
            };
            /** \brief The nodes checked so far and found free, in id order (the lattice is made on demand, around
                the searches; empty before the first solve()). */
            const std::vector<Node> &nodes() const;
            /** \brief The heading step in use (2 pi / heading count). */
            double getHeadingStep() const;
            unsigned int getHeadingCount() const
            {
                return headings_;
            }
            /** \brief Edges between nodes() not known to collide, as index pairs into nodes() (each direction). */
            std::vector<std::pair<unsigned int, unsigned int>> latticeEdges() const;
            /** \brief The path A* found in the last successful solve(), before correction (lattice nodes plus the
                start and goal), for pictures; empty if none. */
            const std::vector<std::vector<double>> &rawPath() const
            {
                return rawPath_;
            }
            /** \brief Seconds the last graph build took (0 if the graph was reused). */
            double lastBuildTime() const
            {
                return lastBuildTime_;
            }
            /** \brief How many times the lattice was laid out from scratch since construction (a new map,
                new settings, clear()); scene changes are updates, not builds. */
            unsigned int buildCount() const
            {
                return buildCount_;
            }
            /** \brief How many times a scene change was taken in as an update (only the nodes and edges near
                the obstacles that changed forgotten). */
            unsigned int updateCount() const
            {
                return updateCount_;
            }
            /** \brief Work done since construction, counted: every validity check of a node, every motion
                check (lattice edges, start and goal joins, path correction), A* searches and expansions. */
            struct WorkCounters
            {
                std::uint64_t nodeChecks{0};       ///< si->isValid on lattice nodes
                std::uint64_t edgeChecks{0};       ///< lattice edges checked (each may take several checkMotion)
                std::uint64_t nodeRechecks{0};     ///< node checks of nodes a scene change made stale
                std::uint64_t edgeRechecks{0};     ///< edge checks of edges a scene change made stale
                std::uint64_t queryChecks{0};      ///< start / goal joins and path correction motions checked
                std::uint64_t searches{0};         ///< A* runs
                std::uint64_t expansions{0};       ///< A* vertex expansions
                std::uint64_t heuristicGroups{0};  ///< groups settled by the 2-D heuristic
                std::uint64_t shortcutChecks{0};   ///< motions checked by the final shortcut (setShortcut)
            };
            const WorkCounters &work() const
            {
                return work_;
            }
            /** \brief What the last update (scene change) did. */
            struct UpdateReport
            {
                std::size_t changedObstacles{0};  ///< obstacles added, removed or moved
                std::size_t nodesReset{0};        ///< checked nodes forgotten (checked again when a search needs them)
                std::size_t edgesReset{0};        ///< checked edges forgotten
                std::size_t nodesKnown{0};        ///< checked nodes before the update (what a rebuild would redo)
                std::size_t edgesKnown{0};        ///< checked edges before the update
            };
            const UpdateReport &lastUpdate() const
            {
                return lastUpdate_;
            }
            /** \brief Is lattice node (x, y, heading k) known free, known blocked, or unchecked (1, 2, 0)? */
            int nodeStatusAt(double x, double y, unsigned int k) const;

        private:
            using Vertex = std::uint32_t;  ///< lattice node id (group * K + heading), or a query vertex after them
            /** \brief A start or goal state and its connections to nearby lattice nodes (checked lazily). */
            struct QueryVertex
            {
                ompl::base::State *state{nullptr};
                bool start{false};
                double radius{0.};                 ///< connection radius in use (doubled while no connection is left)
                int attempts{0};                   ///< doublings done
                std::vector<Vertex> nodes;         ///< lattice nodes joined to it
                std::vector<double> costs;         ///< the space's distance of each connection
                std::vector<std::uint8_t> status;  ///< 0 unchecked, 1 valid, 2 invalid
            };
            /** \brief An edge between query vertices (start -> goal), checked lazily. */
            struct DirectEdge
            {
                Vertex from, to;
                double cost;
                std::uint8_t status;
            };

            /** \brief What the lattice was made for; a different key means a different lattice. */
            struct MapKey
            {
                const void *checker{nullptr};
                const void *motionValidator{nullptr};
                const void *scene{nullptr};
                std::vector<double> settings;
                bool operator==(const MapKey &o) const
                {
                    return checker == o.checker && motionValidator == o.motionValidator && scene == o.scene &&
                           settings == o.settings;
                }
            };
            /** \brief A 2-D box (x min, y min, x max, y max) an obstacle covers, by obstacle name. */
            struct ObstacleBox
            {
                std::string name;
                double box[4];
            };
            MapKey currentKey() const;
            /** \brief Lay out an empty lattice (nothing checked) for the current space and settings. */
            void build();
            /** \brief The scene changed: forget the node and edge checks near the obstacles that changed. */
            void update();
            std::vector<ObstacleBox> sceneBoxes() const;
            /** \brief The scene behind michi's FCL or grid checker (null for any other checker). */
            const validity::Scene *checkedScene() const;
            /** \brief Changes the lattice must take in: the FCL checker's scene changes, or the grid checker's
                refresh() calls that changed its table (its table, not the scene, is what the nodes were checked
                against). */
            std::uint64_t checkerChanges() const;
            void freeGraph();
            void freeQuery();
            void setNodeState(Vertex v, ompl::base::State *state) const;
            void setState(ompl::base::State *state, double x, double y, double yaw) const;
            double headingAngle(unsigned int k) const;
            void nodePosition(Vertex id, double &x, double &y) const;
            /** \brief The same for heading \e k of the group at grid point (i, j), without dividing an index. */
            void nodePosition(long i, long j, unsigned int k, double &x, double &y) const;
            /** \brief Is the node free (checked once, then cached)? */
            bool nodeValid(Vertex id);
            /** \brief The same for node \e id, heading \e k of the group at grid point (i, j), which the caller knows.
             */
            bool nodeValid(Vertex id, long i, long j, unsigned int k);
            /** \brief The next node along the node's heading line (forwards), or -1 outside the lattice. */
            std::int64_t driveNext(Vertex id) const;
            std::int64_t drivePrev(Vertex id) const;
            /** \brief Join a query state to the nodes within its radius (validity of the joins checked lazily). */
            void connectQueryState(QueryVertex &q);
            /** \brief The 2-D heuristic of group \e g (metres to the goals, a lower bound), resumed on demand. */
            double groupDistance(std::uint32_t g, const ompl::base::PlannerTerminationCondition &ptc, bool &stopped);
            void resetHeuristic();
            double heuristic(Vertex v, const ompl::base::PlannerTerminationCondition &ptc, bool &stopped);
            /** \brief A* from the starts to any goal (unchecked edges assumed valid); the vertex path. */
            std::vector<Vertex> search(const ompl::base::PlannerTerminationCondition &ptc, bool &stopped);
            /** \brief Check the unchecked edges of \e path (cached); false if one is invalid. */
            bool checkEdges(const std::vector<Vertex> &path, const ompl::base::PlannerTerminationCondition &ptc,
                            bool &stopped);
            /** \brief Where the status of the edge a -> b (0 unchecked, 1 valid, 2 invalid) is stored: the byte and
                the bit shift of its two bits; nullptr if there is no such edge. */
            std::uint8_t *edgeSlot(Vertex a, Vertex b, int &shift);
            Node nodeOf(Vertex v) const;
            void rebuildGoalLinks();
            void prepareHeuristic();
            /** \brief Check the motion of edge a -> b with the space's motion validator. */
            bool checkEdgeMotion(Vertex a, Vertex b);
            /** \brief The corrected path of \e path as states, every motion checked; marks the turn edges of a
                run that cannot be followed invalid and returns false then. */
            bool makePath(const std::vector<Vertex> &path, ompl::geometric::PathGeometric &out);
            /** \brief setShortcut()'s pass over a path whose motions are all valid (stops shortening when \e ptc
                says so). */
            void shortcutPath(ompl::geometric::PathGeometric &path, const ompl::base::PlannerTerminationCondition &ptc);
            void removeEdgePair(Vertex a, Vertex b);
            bool isLattice(Vertex v) const
            {
                return v < nodeCount_;
            }
            QueryVertex &query(Vertex v)
            {
                return queries_[v - nodeCount_];
            }

            /** \brief The robot's reach (circumradius about its origin) from the FCL checker's bodies; 0 without. */
            double fclReach() const;
            /** \brief Automatic spacing for this space information's checker and scene (setCellSize(0)). */
            double automaticCellSize() const;

            double cellSizeSetting_{0.};             ///< what setCellSize() was given; 0: automatic
            double cellSize_{0.25};                  ///< the spacing in use (build() resolves the automatic one)
            double angleStep_{0.39269908169872414};  // pi / 8
            double connectionCells_{2.};
            double heuristicWeight_{1.};
            bool shortcut_{true};

            unsigned int headings_{0};
            double x0_{0.}, y0_{0.};
            unsigned int columns_{0}, rows_{0};
            std::uint32_t groupCount_{0};
            std::uint32_t nodeCount_{0};
            bool reversible_{true};             ///< the space allows driving backwards
            double turnCost_{0.};               ///< cost of one heading step in place
            double reach_{0.};                  ///< how far the footprint reaches from the robot's origin (for updates)
            double euclidWeight_{1.};           ///< heuristic weight of the straight-line distance (turns shift nodes)
            double shift_{0.};                  ///< the largest shift of a turn edge (build()), for shiftKey_
            std::array<double, 6> shiftKey_{};  ///< cell size, headings, window and origin shift_ was measured for
            struct HeadingGeometry
            {
                bool columns;   ///< |cos| >= |sin|: nodes at (x, y + x tan), eq. (1); else (x + y cot, y), eq. (2)
                double slope;   ///< tan (columns) or cot (rows)
                int forward;    ///< +1 / -1: sign of cos (columns) or sin (rows)
                double length;  ///< drive length to the next node
                double yaw;
                double wrappedYaw;  ///< yaw in [-pi, pi), as a state holds it (for the grid checker's pose query)
            };
            std::vector<HeadingGeometry> geometry_;

            bool built_{false};
            MapKey key_;
            std::uint64_t sceneChanges_{0};
            std::vector<ObstacleBox> boxes_;  ///< the scene's obstacles when the lattice was last made current

            // flat per-node arrays (index: node id)
            PagedArray<std::uint8_t> nodeState_;  ///< 0 unchecked, 1 free, 2 blocked, 3 stale (check again)
            PagedArray<std::uint8_t> edgeState_;  ///< bits 0-1: drive to driveNext(), bits 2-3: turn to heading k+1
            // A* scratch (index: vertex), reset by a stamp; paged like the node arrays (a search touches few ids)
            PagedArray<float> g_;
            PagedArray<std::uint32_t> parent_;
            PagedArray<std::uint32_t> stamp_;
            std::uint32_t searchStamp_{0};
            // the 2-D heuristic over groups (index: group), resumable Dijkstra from the goals
            /** \brief A group's distance and state (0 unseen, 1 open, 2 closed) in the 2-D search stamped \e mark >> 2
                (state: mark & 3); an entry of an older search reads as unseen, so a new goal starts a search without
                clearing an entry per group (64room: a million groups a query, with the page faults of 5 MB). */
            struct GroupEntry
            {
                float dist;
                std::uint32_t mark;
            };
            std::vector<GroupEntry> hGroups_;  ///< kept across clear() (only its stamps matter)
            std::uint32_t hStamp_{0};
            std::uint8_t hState(std::uint32_t g) const
            {
                const std::uint32_t m = hGroups_[g].mark;
                return (m >> 2) == hStamp_ ? static_cast<std::uint8_t>(m & 3u) : std::uint8_t{0};
            }
            float hDist(std::uint32_t g) const
            {
                const GroupEntry &e = hGroups_[g];
                return (e.mark >> 2) == hStamp_ ? e.dist : std::numeric_limits<float>::infinity();
            }
            void setHGroup(std::uint32_t g, float dist, std::uint8_t state)
            {
                hGroups_[g] = GroupEntry{dist, (hStamp_ << 2) | state};
            }
            void setHState(std::uint32_t g, std::uint8_t state)
            {
                hGroups_[g].mark = (hStamp_ << 2) | state;
            }
            /** \brief A new 2-D search: every group unseen (a real clear once in 2^30 searches). */
            void newHeuristicStamp();
            std::vector<std::uint8_t> groupFree_;  ///< 0 unknown, 1 some node free, 2 none
            /** \brief Open groups as a min-heap of (priority, group) packed in one integer (HeadingLatticeCommon.h):
                the order of the pairs, compared as integers. */
            std::vector<std::uint64_t> hOpen_;
            bool hReady_{false};
            /** per heading: the least weighted turning to a goal's heading, added to the heuristic
                (prepareHeuristic()) */
            std::vector<double> turnTerm_;
            std::vector<double> hGoals_;   ///< goal positions the heuristic was made for (x, y pairs)
            std::vector<double> hStarts_;  ///< start positions the 2-D search is directed at (x, y pairs)
            /** \brief Straight-line distance from group \e g's point to the nearest start (the 2-D search's A*
                heuristic). */
            float groupToStart(std::uint32_t g) const;
            /** \brief The same for the group at grid point (i, j), without dividing its index. */
            float groupToStart(long i, long j) const;
            /** \brief Direct the open 2-D search at the current starts (its closed groups stay exact). */
            void aimHeuristic();

            std::vector<QueryVertex> queries_;
            /** \brief For each lattice node joined to a goal: (query index, connection index). */
            std::vector<std::pair<Vertex, std::pair<std::uint32_t, std::uint32_t>>> goalLinks_;
            struct OpenEntry
            {
                float f, g;
                Vertex v;
            };
            std::vector<OpenEntry> open_;
            ompl::base::State *scratch_{nullptr};
            /** \brief States an edge's motion check fills (made with scratch_): an SE(2) state is three allocations,
                and a turn's check needs four states. */
            std::array<ompl::base::State *, 4> motionScratch_{};
            /** \brief Set when a turn of this query's paths was refuted: turnFree() then decides turns as the search
                meets them. */
            bool eagerTurns_{false};
            /** \brief May the search take the turn from node \e lower to the next heading's node \e upper? Lazy (true
                when unchecked) until eagerTurns_; then decided at once (grid table or motion check) and recorded. */
            bool turnFree(Vertex lower, Vertex upper);
            /** \brief The space's checker when it is michi's grid checker (else null): nodeValid() asks it about the
                node's pose directly, without making an OMPL state, with the same answer. */
            const validity::GridValidityChecker *gridChecker_{nullptr};
            std::array<double, 4> xyBounds_{};  ///< the space's x and y bounds (low x, high x, low y, high y)
            std::vector<DirectEdge> direct_;
            mutable std::vector<ompl::base::State *> exportStates_;
            mutable std::vector<Node> nodeList_;
            mutable PagedArray<std::uint32_t> nodeIndex_;  ///< node id -> index in nodeList_ (or ~0u)
            mutable bool nodeListDirty_{true};
            std::vector<std::vector<double>> rawPath_;
            double lastBuildTime_{0.};
            unsigned int buildCount_{0};
            unsigned int updateCount_{0};
            WorkCounters work_;
            UpdateReport lastUpdate_;
        };
    }  // namespace planners
}  // namespace michi

#endif
