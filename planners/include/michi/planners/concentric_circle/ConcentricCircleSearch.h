#ifndef MICHI_PLANNERS_CONCENTRIC_CIRCLE_SEARCH_
#define MICHI_PLANNERS_CONCENTRIC_CIRCLE_SEARCH_

#include <michi/planners/concentric_circle/CircleMap.h>

#include <ompl/base/PlannerTerminationCondition.h>

#include <Eigen/Core>

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief Settings of the concentric-circle method (they feed ConcentricCircle's declared parameters). */
        struct ConcentricCircleSettings
        {
            double ringSpacing{0.1};  ///< radial distance between two circles (map units, radians for J-maps)
            int divisions{72};        ///< points per circle (the paper: 72, every 5 degrees)
            /** \brief Large circles get more than \e divisions points so that neighbouring points are at most
                this far apart (0: always \e divisions, as in the paper, whose circles stay small). */
            double pointSpacing{0.1};
            double kGoal{1.};        ///< Kg of the attraction -Kg / Dg
            double kObstacle{1e-3};  ///< Kp of the repulsion Kp / Dp^2
            /** \brief Obstacle edges farther than this from P are left out of the repulsion sum (their term is
                below Kp / range^2; the paper sums over every visible edge). */
            double potentialRange{0.3};
            /** \brief A free arc longer than this many points is cut into equal pieces, one candidate each (0:
                one candidate per arc, as in the paper). One minimum on a long arc is often out of sight of the
                next circle's candidates although the arcs overlap; the pieces keep the circles linked. */
            int maxArcPoints{9};
            /** \brief Also make the two end points of every free arc (next to the obstacles) candidates, so
                chains can follow obstacle boundaries (the paper: only the minimum). */
            bool arcEnds{true};
            int maxRecursions{8};  ///< sub-problems (new start and goal between unlinked points) before giving up
            /** \brief After the paper's circles (until the goal is reached) fail, keep adding circles around the
                start until they cover the whole map before recursing. */
            bool outerRings{true};
            int maxPaths{16};  ///< distinct paths kept (left / right around obstacles, ...)
            /** \brief "michi" (the settings above) or "paper": the paper's candidate rule, which overrides them
                with one minimum-potential point per free arc, no arc end points, and exactly \e divisions (72)
                points on every circle (maxArcPoints 0, arcEnds false, pointSpacing 0). */
            std::string candidates{"michi"};
        };

        /** \brief One node of the link graph: the start, the goal, a recursion's start/goal, or a candidate
            (minimum-potential point of a free arc). */
        struct CcNode
        {
            Eigen::Vector2d p{Eigen::Vector2d::Zero()};
            int set{-1};   ///< circle set (-1: the start or the goal)
            int ring{-1};  ///< ring index in rings() (-1: not on a ring)
            double potential{0.};
        };

        /** \brief One circle: its sample points, which are free, and its candidates. */
        struct CcRing
        {
            int set{0};
            int index{0};  ///< 1 for the innermost circle of its set
            double radius{0.};
            Eigen::Vector2d centre{Eigen::Vector2d::Zero()};
            std::vector<Eigen::Vector2d> points;
            std::vector<char> free;
            /** per point: the free arc holding it, from the circle's crossings with the map's polygons (-1:
                blocked); empty when the map has none (the arcs are then the runs of free points) */
            std::vector<int> arc;
            /** per free point: its potential (equation 3), or, for a point that cannot be its piece's minimum, the
                lower bound that showed it (the attraction alone, above the minimum; 0 for blocked points) */
            std::vector<double> potential;
            std::vector<int> candidates;      ///< node ids
            std::vector<Edge2> blockedEdges;  ///< chords of the blocked runs (potential without polygons)
            bool linked{false};               ///< candidates computed and linked
        };

        /** \brief Circles around one start towards one goal (the first set; recursions add more). */
        struct CcSet
        {
            int centreNode{0};
            int goalNode{1};
            double spacing{0.1};
            int divisions{72};
            double goalRadius{0.};
            int goalRings{1};        ///< circles until the goal is reached
            int maxRings{1};         ///< circles that cover the map
            std::vector<int> rings;  ///< indices into rings(), innermost first
        };

        /** \brief The concentric-circle potential method of Kawarazaki & Nagata (paper 000) on a 2-D map:
            circles around the start at a fixed spacing until the goal; every circle cut into \e divisions
            points; the oval potential Phi = -Kg / |PG| + sum Kp / Dp^2 (Dp = |PA| + |PB| - |AB| over obstacle
            edges AB visible from P); one candidate per free arc (its minimum-potential point); candidates of
            adjacent circles linked when they see each other; paths are chains of links from the start to the
            goal (found by Dijkstra over the links). When none exists: more circles until the map is covered
            (outerRings), then recursion: the two closest unlinked nodes (one linked to the start, one to the
            goal) become a new start and goal, with circles at half the spacing and twice the divisions.
            Deterministic: no randomness. */
        class ConcentricCircleSearch
        {
        public:
            ConcentricCircleSearch(const CircleMap &map, ConcentricCircleSettings settings);

            /** \brief The potential of paper 000 at \e p for \e goal, equation (3): the attraction -Kg / |PG| (1)
                plus, over the obstacle edges AB within potentialRange of P whose both end points P sees, the
                repulsion Kp / Dp^2 (2), Dp = |PA| + |PB| - |AB|. Maps without polygons: the blocked runs of
                the circles stand for the edges, as in the search (this one uses none before a search ran). */
            double potentialAt(const Eigen::Vector2d &p, const Eigen::Vector2d &goal) const;

            /** \brief Plan from \e start to \e goal (both must be free). True when at least one path was found. */
            bool run(const Eigen::Vector2d &start, const Eigen::Vector2d &goal,
                     const ompl::base::PlannerTerminationCondition &ptc);

            /** \brief Drop a link (e.g. one a finer motion check rejected) and recollect the paths. */
            void removeLink(int a, int b);
            /** \brief Recollect paths from the current links (after removeLink). True when one exists. */
            bool collectPaths();

            const std::vector<CcNode> &nodes() const
            {
                return nodes_;
            }
            const std::vector<CcRing> &rings() const
            {
                return rings_;
            }
            const std::vector<CcSet> &sets() const
            {
                return sets_;
            }
            /** \brief Links checked for visibility, as node pairs (a < b). Links are proposed between candidates
                and checked lazily, when a shortest path uses them (whether a path exists does not change). */
            std::vector<std::pair<int, int>> links() const;
            /** \brief Paths as node ids from node 0 (start) to node 1 (goal), shortest first. */
            const std::vector<std::vector<int>> &paths() const
            {
                return paths_;
            }
            /** \brief Points of path \e i with the map's breakpoints and wrapping resolved (each point the image
                nearest to the previous one). */
            std::vector<Eigen::Vector2d> pathPoints(std::size_t i) const;
            /** \brief Length of path \e i in the map plane. */
            double pathLength(std::size_t i) const;
            int recursions() const
            {
                return recursions_;
            }
            /** \brief Per node: 1 when linked (through any chain) to node \e from. */
            std::vector<char> component(int from) const;
            /** \brief \e to shifted by whole periods on wrapping axes to lie within half a period of \e from. */
            Eigen::Vector2d image(const Eigen::Vector2d &from, const Eigen::Vector2d &to) const;

        private:
            bool runCircles(const Eigen::Vector2d &start, const Eigen::Vector2d &goal,
                            const ompl::base::PlannerTerminationCondition &ptc);
            int addNode(const Eigen::Vector2d &p, int set, int ring);
            void addLink(int a, int b, bool unchecked = false);
            bool tryLink(int a, int b);
            /** a link whose visibility is checked only when a path uses it (lazily, as LazyPRM) */
            void proposeLink(int a, int b);
            bool validateLink(int a, int b);
            bool validatePath(const std::vector<int> &path);
            /** a path from the start to the goal on checked links (checkedSearch)? */
            bool lazyConnect();
            int addSet(int centre, int goal, double spacing, int divisions, bool cover);
            /** sample ring k (1-based) of set s if not yet sampled; returns its index in rings_ */
            int sampleRing(int s, int k, const ompl::base::PlannerTerminationCondition &ptc);
            /** sample rings k and k + 1, make the candidates of k and link them; false when terminated */
            bool linkRing(int s, int k, const ompl::base::PlannerTerminationCondition &ptc);
            double potential(const Eigen::Vector2d &p, const Eigen::Vector2d &goal, int s, int k) const;
            bool connected();
            /** Dijkstra from \e source (\e target < 0: the whole tree; true) or A* to \e target (false when
                unreachable), checking each link where it would shorten a distance and removing those that fail */
            bool checkedSearch(int source, int target, std::vector<double> &dist, std::vector<int> &parent);

            const CircleMap &map_;
            ConcentricCircleSettings settings_;
            std::vector<CcNode> nodes_;
            std::vector<CcRing> rings_;
            std::vector<CcSet> sets_;
            /** one direction of a link; both directions carry the same \e unchecked flag */
            struct Arc
            {
                int to;
                double length;
                bool unchecked;  ///< proposed, visibility not yet checked
            };
            /** validateLink() for the link of adjacency_[a][i] (no search for it, as the shortest-path searches'
                inner loop has it at hand) */
            bool validateArc(int a, std::size_t i);
            std::vector<std::vector<Arc>> adjacency_;
            std::vector<std::vector<int>> paths_;
            std::set<std::pair<int, int>> tried_;
            int recursions_{0};
            unsigned long version_{0};  ///< changes whenever a link is added or removed
            const ompl::base::PlannerTerminationCondition *ptc_{nullptr};  ///< of the running search
        };
    }  // namespace planners
}  // namespace michi

#endif
