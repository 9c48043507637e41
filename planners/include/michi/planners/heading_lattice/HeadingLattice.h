#ifndef MICHI_PLANNERS_HEADING_LATTICE_
#define MICHI_PLANNERS_HEADING_LATTICE_

#include <ompl/base/Planner.h>
#include <ompl/geometric/PathGeometric.h>

#include <boost/graph/adjacency_list.hpp>

#include <cstdint>
#include <vector>

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

           Edges are checked lazily (LazyPRM's way): a path found by A* is checked edge by edge, colliding edges
           (and the turn edges of a run whose corrected motions collide) are removed
           and A* runs again. The graph (nodes and the edges found so far) is kept across queries (new start and
           goal, new problem definition) as long as the map is the same: the same validity checker, motion
           validator and state space settings, and, when the checker is michi's FclValidityChecker, the same
           scene change count. clear() forgets it, as OMPL's planners do. Without randomness, the same query on the
           same map gives the same path every time.

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

            /** \brief Spacing of the nodes along x and y (metres, > 0). */
            void setCellSize(double size);
            double getCellSize() const
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
            /** \brief A node of the lattice. */
            struct Node
            {
                double x, y;
                unsigned int heading;  ///< k: heading k * getHeadingStep()
                unsigned int group;    ///< index of the heading-0 grid point (i, j): i * rows + j
            };
            /** \brief The nodes of the built graph (vertex order; empty before the first solve()). */
            const std::vector<Node> &nodes() const
            {
                return nodes_;
            }
            /** \brief The heading step in use (2 pi / heading count). */
            double getHeadingStep() const;
            unsigned int getHeadingCount() const
            {
                return headings_;
            }
            /** \brief Edges of the built graph between lattice nodes, as vertex index pairs (each direction). */
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
            /** \brief How many times the graph was built since construction (for tests of the reuse). */
            unsigned int buildCount() const
            {
                return buildCount_;
            }

        private:
            struct EdgeProperty
            {
                double weight;
                std::uint8_t kind;     ///< 0 move, 1 turn, 2 query (start / goal connection, checked)
                std::uint8_t checked;  ///< motion known to be valid
            };
            using Graph =
                boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS, boost::no_property, EdgeProperty>;
            using Vertex = Graph::vertex_descriptor;

            /** \brief What the graph was built for; a different key means a different map. */
            struct MapKey
            {
                const void *checker{nullptr};
                const void *motionValidator{nullptr};
                const void *scene{nullptr};
                std::uint64_t sceneChanges{0};
                std::vector<double> settings;
                bool operator==(const MapKey &o) const
                {
                    return checker == o.checker && motionValidator == o.motionValidator && scene == o.scene &&
                           sceneChanges == o.sceneChanges && settings == o.settings;
                }
            };
            MapKey currentKey() const;
            /** \brief Build the lattice; false (and an empty graph) if ptc stopped it. */
            bool build(const ompl::base::PlannerTerminationCondition &ptc);
            void freeGraph();
            void setNodeState(unsigned int vertex, ompl::base::State *state) const;
            void setState(ompl::base::State *state, double x, double y, double yaw) const;
            double headingAngle(unsigned int k) const;
            /** \brief Add a query vertex for \e state joined to nearby nodes (from it if \e start, else to it). */
            bool connectQueryState(const ompl::base::State *state, bool start);
            /** \brief A* from the start vertices to any goal vertex; the vertex path, empty if none. */
            std::vector<Vertex> search(const ompl::base::PlannerTerminationCondition &ptc, bool &stopped);
            /** \brief Check the unchecked edges of \e path; remove the colliding ones. True if all are valid. */
            bool checkEdges(const std::vector<Vertex> &path);
            /** \brief The corrected path of \e path as states, every motion checked; removes the turn edges of a
                run that cannot be followed and returns false then. */
            bool makePath(const std::vector<Vertex> &path, ompl::geometric::PathGeometric &out);
            void removeEdgePair(Vertex a, Vertex b);

            double cellSize_{0.25};
            double angleStep_{0.39269908169872414};  // pi / 8
            double connectionCells_{2.};

            unsigned int headings_{0};
            double x0_{0.}, y0_{0.};
            unsigned int columns_{0}, rows_{0};
            bool reversible_{true};  ///< the space allows driving backwards
            double turnCost_{0.};    ///< cost of one heading step in place

            Graph graph_;
            bool built_{false};
            MapKey key_;
            std::vector<Node> nodes_;  ///< lattice vertices 0 .. nodes_.size()-1; query vertices follow
            std::vector<ompl::base::State *> queryStates_;
            std::vector<char> queryIsStart_;
            mutable std::vector<ompl::base::State *> exportStates_;
            std::vector<std::vector<double>> rawPath_;
            double lastBuildTime_{0.};
            unsigned int buildCount_{0};
        };
    }  // namespace planners
}  // namespace michi

#endif
