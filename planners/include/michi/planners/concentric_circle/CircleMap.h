#ifndef MICHI_PLANNERS_CIRCLE_MAP_
#define MICHI_PLANNERS_CIRCLE_MAP_

#include <michi/validity/scene/Polygon2.h>

#include <Eigen/Core>

#include <array>
#include <functional>
#include <memory>
#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief An obstacle edge AB of a 2-D map (for the oval potential). */
        struct Edge2
        {
            Eigen::Vector2d a;
            Eigen::Vector2d b;
        };

        /** \brief The 2-D plane the concentric-circle method works on (paper 000): which points are free, which
            straight segments are free (visibility), and, when the map knows its obstacles as polygons, the
            obstacle edges seen from a point. Coordinates are unwrapped: an axis that wraps (a continuous joint)
            is not clipped; the map itself wraps values when it evaluates them. Implementations are immutable
            during a search. */
        class CircleMap
        {
        public:
            virtual ~CircleMap() = default;
            /** \brief Axis ranges (lo, hi) and whether an axis wraps with period hi - lo. */
            Eigen::Vector2d lo{Eigen::Vector2d::Constant(-1.)};
            Eigen::Vector2d hi{Eigen::Vector2d::Constant(1.)};
            std::array<bool, 2> wraps{{false, false}};

            /** \brief True when \e p is inside the ranges (wrapping axes: always) and collision-free. */
            virtual bool isFree(const Eigen::Vector2d &p) const = 0;
            /** \brief True when the straight segment from \e a to \e b (both free) is free. */
            virtual bool isVisible(const Eigen::Vector2d &a, const Eigen::Vector2d &b) const = 0;
            /** \brief Points strictly between \e a and \e b where the motion the map stands for kinks (a hand
                map's arm-path vertices); the segment means the polyline a, these, b. Default: none. */
            virtual std::vector<Eigen::Vector2d> breakpoints(const Eigen::Vector2d &a, const Eigen::Vector2d &b) const;
            /** \brief Append the obstacle edges within \e range of \e p whose both end points are visible from
                \e p. Returns false when the map has no polygons (then the search takes the blocked runs it
                sampled on the circles as edges). */
            virtual bool obstacleEdges(const Eigen::Vector2d &p, double range, std::vector<Edge2> &edges) const;

            /** \brief The free arcs of a circle in one pass (paper 000's sections of a circle between obstacle
                regions), for the \e n points at angles phase + 2 pi i / n: \e arc[i] is the index of the free arc
                holding point i, -1 where the point is blocked or out of range. Returns false when the map cannot
                (then the search tests the points one by one and takes runs of free points as arcs). Default:
                false. */
            virtual bool freeArcs(const Eigen::Vector2d &centre, double radius, double phase, int n,
                                  std::vector<int> &arc) const;

            /** \brief True when \e p lies within the ranges of the non-wrapping axes. */
            bool inRange(const Eigen::Vector2d &p) const;
        };

        using CircleMapPtr = std::shared_ptr<const CircleMap>;

        /** \brief A map from two functions (a projection of an OMPL space: validity checker and motion
            validator of the lifted states). */
        class CallbackCircleMap : public CircleMap
        {
        public:
            using PointTest = std::function<bool(const Eigen::Vector2d &)>;
            using SegmentTest = std::function<bool(const Eigen::Vector2d &, const Eigen::Vector2d &)>;
            using Breaks =
                std::function<std::vector<Eigen::Vector2d>(const Eigen::Vector2d &, const Eigen::Vector2d &)>;

            CallbackCircleMap(PointTest isFree, SegmentTest isVisible, Breaks breaks = {});
            bool isFree(const Eigen::Vector2d &p) const override;
            bool isVisible(const Eigen::Vector2d &a, const Eigen::Vector2d &b) const override;
            std::vector<Eigen::Vector2d> breakpoints(const Eigen::Vector2d &a, const Eigen::Vector2d &b) const override;

        private:
            PointTest isFree_;
            SegmentTest isVisible_;
            Breaks breaks_;
        };

        /** \brief A map whose obstacles are polygons (a J-map): points and segments are tested against the
            polygons (Boost.Geometry point-in-polygon and an R-tree of the edges), obstacle edges seen from a
            point are those whose both end points are visible from it. Touching a polygon counts as blocked.
            Axes do not wrap. */
        class PolygonCircleMap : public CircleMap
        {
        public:
            PolygonCircleMap(validity::MultiPolygon2 obstacles, const Eigen::Vector2d &lo, const Eigen::Vector2d &hi);
            ~PolygonCircleMap() override;
            bool isFree(const Eigen::Vector2d &p) const override;
            bool isVisible(const Eigen::Vector2d &a, const Eigen::Vector2d &b) const override;
            bool obstacleEdges(const Eigen::Vector2d &p, double range, std::vector<Edge2> &edges) const override;
            /** \brief The arcs between the circle's crossings with the polygon edges, each free or blocked as its
                middle is; a point on a crossing (touching a polygon) is blocked. */
            bool freeArcs(const Eigen::Vector2d &centre, double radius, double phase, int n,
                          std::vector<int> &arc) const override;
            const validity::MultiPolygon2 &obstacles() const
            {
                return obstacles_;
            }
            /** \brief A faster test of "inside or on a polygon" for isFree() (e.g. the J-map's slab index over
                the same polygons); without one, Boost.Geometry's covered_by walks every polygon's edges. */
            void setInsideTest(std::function<bool(const Eigen::Vector2d &)> inside)
            {
                inside_ = std::move(inside);
            }

        private:
            /** true when segment [a, b] touches an edge other than \e skipA / \e skipB (edge indices, -1: none) */
            bool blocked(const Eigen::Vector2d &a, const Eigen::Vector2d &b, int skipVertexEdge1,
                         int skipVertexEdge2) const;
            struct Index;
            validity::MultiPolygon2 obstacles_;
            std::vector<Edge2> edges_;
            std::vector<int> prev_;  ///< per edge: the edge ending at its first vertex
            std::vector<int> next_;  ///< per edge: the edge starting at its second vertex
            std::unique_ptr<Index> index_;
            std::function<bool(const Eigen::Vector2d &)> inside_;
        };
    }  // namespace planners
}  // namespace michi

#endif
