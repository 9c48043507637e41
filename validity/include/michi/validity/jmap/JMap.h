#ifndef MICHI_VALIDITY_JMAP_
#define MICHI_VALIDITY_JMAP_

#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/jmap/PlanarArm.h>
#include <michi/validity/scene/Polygon2.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

/* J-map (joint map) of N. Kawarazaki and T. Nagata, "Generation of Collision-free Path of a Manipulator by
   Means of Joint-map" (1991): the configuration-space obstacles of two joints (theta1 horizontal, theta2
   vertical) drawn as polygons.

   How a map is made (JMap::build):
   1. The axis-1 range [lo1, hi1] is cut into `slices` equal cells [b_i, b_i+1] (step h); slice i stands for its
      whole cell, not only for its centre c_i. Each cell is cut into `columns` equal columns (default 2).
   2. For every column an interval source gives the axis-2 intervals in which the arm MAY collide for SOME
      theta1 in the column (cellIntervals()). They contain the true intervals of every theta1 in it (below, a
      "cell" of half width h/2 is a column, whose half width is h / (2 columns)):
      - PlanarIntervalSource (exact geometry, capsules against polygons): the true intervals at the cell
        centre of the arm whose capsules are inflated by the largest workspace motion a rotation of joint 1 by
        h/2 can cause: rho * 2 sin(h/4), rho = the capsule's reach from joint 1's axis (PlanarArm::reachFrom).
        If the arm at (theta1, theta2) touches an obstacle with |theta1 - c_i| <= h/2, the same arm at
        (c_i, theta2) is within that distance of the obstacle, so theta2 is in the inflated interval.
        This is the margin that makes the map conservative between slices; it is derived from the step and the
        arm's geometry, not from the shape of the intervals (whose end points can move arbitrarily fast in
        theta2 per theta1 near tangencies, so no Lipschitz bound on end points exists in general).
      - FclIntervalSource (any URDF): a theta2 sweep certified with FCL distances and displacement bounds.
      The true intervals AT the centre (intervals()) are kept for pictures.
   3. Polygons (the paper's procedure, made conservative): the column intervals are chained into theta2-monotone
      pieces (an interval of column i continues an interval of column i+1 when they overlap and neither overlaps
      anything else there; at a split or merge a piece ends and new ones begin, and the union below joins them
      again). Each piece gives a lower and an upper chain of end points: every interval spans its whole column,
      so the chains are staircases with their corners at the column borders (the union of the piece's
      rectangles column x interval). Each chain is thinned with the paper's line walk: circles of radius r
      (`tolerance`) on the end points; from end point i a line is drawn to i+k (k = 2, 3, ...) as long as it
      crosses every circle in between AND passes outside (below the lower / above the upper) every end point in
      between; when it fails, point i+k-1 becomes a vertex and the walk restarts there. The extra condition
      keeps containment; r only trades tightness for vertex count: with r below the column width the walk only
      straightens flat and evenly sloped runs (planar_2link, 72 slices x 2 columns: r = 0.03 -> 626 vertices,
      3.5 % of all states falsely invalid; r = 0.1 -> 389 vertices, 5.0 %).
      The pieces' polygons are united (Boost.Geometry) into one polygon per connected collision region (a
      region enclosing free space gets an inner ring). Regions touching the axis-2 limits, or the axis-1 limits,
      are extended `borderMargin` beyond them, so a state on a joint limit is inside too. The axes are not
      wrapped: a region crossing theta = +-pi of a continuous joint is two polygons, one at each side.
   4. Point queries (collides) use a slab index: the polygons' vertex x values cut the plane into vertical slabs
      in which no edges cross; each slab keeps its edges sorted by height, and a query is one table look-up in x
      plus a binary search in y (tens of nanoseconds).

   Stacks (JMapStack): for 3 joints one 2-D map over joints 2 and 3 per cell of joint 1 (each map conservative
   for every joint-1 value in its cell). Grown maps: the same arm on obstacles grown by the hand length
   (growObstacles()); bottleneck = grown map - map (bottleneck()). */

namespace michi
{
    namespace validity
    {
        /** \brief A closed interval [lo, hi] of joint values. */
        struct JointInterval
        {
            double lo{0.};
            double hi{0.};
        };

        /** \brief Sort, then merge intervals that overlap or touch (closer than \e gap). */
        std::vector<JointInterval> mergeIntervals(std::vector<JointInterval> intervals, double gap = 0.);

        /** \brief Which two joints the map is drawn over, and where the other joints are. Indices are
            configuration indices of the robot model (RobotModel::variableJoint order). */
        struct JMapAxes
        {
            int axis1{0};  ///< horizontal axis (theta1)
            int axis2{1};  ///< vertical axis (theta2), usually a joint below axis1 (the elbow)
            /** \brief A full configuration: values of the other joints (the axis entries are ignored). */
            std::vector<double> configuration;
            /** \brief Per configuration value (empty: all 0): joint v may be anywhere in configuration[v] +-
                halfWidths[v], and the map is conservative for all of these (a stack's outer slice). */
            std::vector<double> halfWidths;
            /** \brief Axis ranges; lo >= hi means "the joint limits". */
            double lo1{0.}, hi1{0.}, lo2{0.}, hi2{0.};
        };

        /** \brief Where the theta2 collision intervals of a J-map come from. Implementations are immutable and
            thread-safe (const methods may run concurrently). */
        class JMapIntervalSource
        {
        public:
            virtual ~JMapIntervalSource() = default;
            /** \brief The axes, with ranges resolved (lo < hi). */
            virtual const JMapAxes &axes() const = 0;
            /** \brief The true collision intervals of axis 2 at axis-1 value \e theta1 (others at their
                configuration values), clipped to the axis-2 range, sorted and disjoint. */
            virtual std::vector<JointInterval> intervals(double theta1) const = 0;
            /** \brief Intervals of axis 2 that contain every collision for every axis-1 value in [lo, hi] (and
                the other joints anywhere within their half widths); sorted, disjoint, clipped to the range. */
            virtual std::vector<JointInterval> cellIntervals(double lo, double hi) const = 0;
            /** \brief Exact (or the source's best) test of one state (others at their configuration values). */
            virtual bool collides(double theta1, double theta2) const = 0;
            /** \brief Short name for logs and pictures ("planar exact", "fcl sweep"). */
            virtual std::string name() const = 0;
        };

        using JMapIntervalSourcePtr = std::shared_ptr<const JMapIntervalSource>;

        /** \brief Exact intervals of a planar arm (PlanarArm capsules) among polygons. For each theta1: a capsule
            not moved by axis 2 that touches an obstacle makes the whole axis-2 range collide; each capsule moved
            by axis 2 turns about that joint, and its collision set in theta2 is bounded by critical angles (the
            centre segment's line passes at the radius from a polygon vertex; an end point's circle about the
            joint meets an edge's line offset by the radius or a vertex's disk; the segment is parallel to an
            edge); the critical angles are sorted and every piece between two is classified by an exact test at
            its midpoint (Boost.Geometry distance(segment, polygons) <= radius), every critical angle itself too
            (isolated touching angles become zero-width intervals). Interval ends are widened by 1e-9 rad
            against rounding. */
        class PlanarIntervalSource : public JMapIntervalSource
        {
        public:
            /** \param links link indices (PlanarArm::links()) that are part of the arm; empty: every link
                (exclude a hand to build the paper's arm map). */
            PlanarIntervalSource(PlanarArmPtr arm, MultiPolygon2 obstacles, JMapAxes axes, std::vector<int> links = {});

            const JMapAxes &axes() const override
            {
                return axes_;
            }
            std::vector<JointInterval> intervals(double theta1) const override;
            std::vector<JointInterval> cellIntervals(double lo, double hi) const override;
            bool collides(double theta1, double theta2) const override;
            std::string name() const override
            {
                return "planar exact";
            }

            /** \brief Intervals at \e theta1 with every capsule of link l inflated by \e inflation[l] (metres). */
            std::vector<JointInterval> inflatedIntervals(double theta1, const std::vector<double> &inflation) const;
            /** \brief The inflation (per link, metres) that makes cellIntervals() of a cell of half width \e half
                conservative: sum over uncertain joints j of reachFrom(j, l) * 2 sin(w_j / 2). */
            std::vector<double> cellInflation(double half) const;
            /** \brief Sub-samples per cell (default 1): cellIntervals() covers a cell with this many sub-cells,
                each computed at its centre with the inflation of a sub-cell, and returns their union; tighter
                intervals for proportionally more work (JMapSettings::columns is usually the better knob: it
                also keeps the sub-cells apart in the polygons). */
            void setSubsamples(int n)
            {
                subsamples_ = n < 1 ? 1 : n;
            }
            int getSubsamples() const
            {
                return subsamples_;
            }
            const PlanarArmPtr &arm() const
            {
                return arm_;
            }
            const MultiPolygon2 &obstacles() const
            {
                return obstacles_;
            }

        private:
            PlanarArmPtr arm_;
            MultiPolygon2 obstacles_;
            JMapAxes axes_;
            std::vector<char> useLink_;
            int subsamples_{1};
        };

        /** \brief Intervals of any URDF arm from FCL: a sweep over theta2 certified by distances. At a sample
            (theta1 = cell centre c, theta2 = s) each body b has obstacle distance d_b (FclValidityChecker::
            bodyDistances, self pairs too); moving axis 1 by at most h/2 and axis 2 by |t| moves body b by at
            most B1_b h/2 + B2_b |t| (B = RobotModel::displacementBound(variable, link), configuration-independent
            bounds, plus the other joints' half widths), so [s - w, s + w] with w = min_b (d_b - margin - B1_b h/2
            - ...) / B2_b is certified free. The sweep advances by the certified width; where it is below `step`
            (near or in contact), [s, s + step] is reported as colliding. So every true collision lies inside a
            reported interval (the result is conservative; its looseness is about B1 h/2 in workspace terms,
            plus one step). Needs a checker whose bodies are RobotGroupBodies whose group contains both axes
            and every joint with a half width. */
        class FclIntervalSource : public JMapIntervalSource
        {
        public:
            /** \param step smallest sweep advance (radians) \param margin metres subtracted from every FCL
                distance (FCL/libccd tolerance) */
            FclIntervalSource(FclValidityCheckerPtr checker, JMapAxes axes, double step = 0.002, double margin = 1e-5);

            const JMapAxes &axes() const override
            {
                return axes_;
            }
            std::vector<JointInterval> intervals(double theta1) const override;
            std::vector<JointInterval> cellIntervals(double lo, double hi) const override;
            bool collides(double theta1, double theta2) const override;
            std::string name() const override
            {
                return "fcl sweep";
            }
            /** \brief Number of FCL distance queries made so far. */
            std::uint64_t queries() const;

        private:
            std::vector<JointInterval> sweep(double theta1, double half) const;
            FclValidityCheckerPtr checker_;
            JMapAxes axes_;
            double step_;
            double margin_;
            std::vector<int> groupIndex_;  ///< configuration index -> group value index (-1: not in group)
            std::vector<double> bound1_, bound2_, boundOther_;  ///< per body
            std::vector<char> moves2_;                          ///< per body: moved by axis 2
            mutable std::atomic<std::uint64_t> queries_{0};
        };

        /** \brief Settings of JMap::build(). */
        struct JMapSettings
        {
            int slices{72};  ///< cells of axis 1 (72 over [-pi, pi]: 5 degree steps; the paper gives no step)
            /** \brief Columns per slice: each slice's cell is cut into this many equal columns, each with its
                own conservative intervals (cellIntervals of the column); the polygons enclose the columns. More
                columns: tighter polygons for proportionally more interval work. */
            int columns{2};
            double tolerance{0.03};     ///< r, radius of the line walk's circles (radians of the map)
            double borderMargin{1e-3};  ///< how far polygons touching the axis limits extend beyond them
            /** \brief Compute every slice's true intervals at its centre (the paper's segments, for pictures
                and checks); false leaves JMapSlice::trueIntervals empty and saves a third of the build. */
            bool trueIntervals{true};
            /** \brief Called by JMap::build() after each slice with (slices done, slices): an arm swept by FCL takes
                minutes, and a command shows how far it got. Empty: nothing is called. */
            std::function<void(int, int)> progress;
        };

        /** \brief One cell of axis 1. */
        struct JMapSlice
        {
            double theta1{0.};  ///< cell centre
            double lo{0.};      ///< cell borders
            double hi{0.};
            std::vector<JointInterval> trueIntervals;  ///< source.intervals(theta1): the segments of the paper
            /** \brief Conservative intervals of each column (equal parts of [lo, hi], left to right): what the
                polygons enclose. Empty: one column whose intervals are \e intervals. */
            std::vector<std::vector<JointInterval>> columns;
            std::vector<JointInterval> intervals;  ///< union of the columns: conservative for the whole cell
        };

        class JMapIndex;

        /** \brief A 2-D J-map: slices, the polygons that contain the collision region, and fast queries.
            Immutable once built; const methods are thread-safe. Coordinates: x = axis 1, y = axis 2 (radians). */
        class JMap
        {
        public:
            /** \brief Build from \e source (every slice, then the polygons, then the index). */
            static std::shared_ptr<const JMap> build(const JMapIntervalSource &source,
                                                     const JMapSettings &settings = {});
            /** \brief Polygons from given slices (for tests and for maps whose slices come from elsewhere);
                \e lo2 / \e hi2 is the axis-2 range. */
            static std::shared_ptr<const JMap> fromSlices(std::vector<JMapSlice> slices, double lo2, double hi2,
                                                          const JMapSettings &settings = {});
            /** \brief A map of given polygons, without slices (tests, and polygons made elsewhere); \e lo1 .. \e hi2
                are the axes' ranges. */
            static std::shared_ptr<const JMap> fromPolygons(MultiPolygon2 polygons, double lo1, double hi1, double lo2,
                                                            double hi2);
            ~JMap();

            /** \brief True when (theta1, theta2) lies inside (or on the boundary of) a polygon. Points outside
                the map's ranges (beyond borderMargin) are reported free. */
            bool collides(double theta1, double theta2) const;
            /** \brief The first contact of the straight segment from (theta1a, theta2a) to (theta1b, theta2b) with
                a polygon, as a fraction t in [0, 1] of the segment (0 when it starts inside), or +infinity when the
                whole segment is free. Exact up to rounding; a slab walk of two binary searches per slab crossed. */
            double firstContact(double theta1a, double theta2a, double theta1b, double theta2b) const;
            /** \brief Euclidean distance in the map plane (radians) from the point to the nearest polygon
                boundary, capped at \e maxDistance (returned when nothing is closer). */
            double distanceToBoundary(double theta1, double theta2, double maxDistance) const;
            /** \brief collides() and distanceToBoundary() < band: a state the checker may re-check exactly. */
            bool nearBoundary(double theta1, double theta2, double band) const
            {
                return distanceToBoundary(theta1, theta2, band) < band;
            }
            /** \brief Index of the slice whose cell holds \e theta1 (clamped to the range). */
            std::size_t sliceIndex(double theta1) const;

            const std::vector<JMapSlice> &slices() const
            {
                return slices_;
            }
            /** \brief The J-map polygons: one per connected collision region (clockwise, closed). */
            const MultiPolygon2 &polygons() const
            {
                return polygons_;
            }
            /** \brief Polygons of the theta2-monotone pieces before the union (for pictures and debugging). */
            const std::vector<Polygon2> &pieces() const
            {
                return pieces_;
            }
            const JMapSettings &settings() const
            {
                return settings_;
            }
            double lo1() const
            {
                return lo1_;
            }
            double hi1() const
            {
                return hi1_;
            }
            double lo2() const
            {
                return lo2_;
            }
            double hi2() const
            {
                return hi2_;
            }
            /** \brief Wall-clock seconds of build() (intervals + polygons + index). */
            double buildSeconds() const
            {
                return buildSeconds_;
            }

        private:
            JMap() = default;
            void finish();
            std::vector<JMapSlice> slices_;
            MultiPolygon2 polygons_;
            std::vector<Polygon2> pieces_;
            JMapSettings settings_;
            double lo1_{0.}, hi1_{0.}, lo2_{0.}, hi2_{0.};
            double buildSeconds_{0.};
            std::unique_ptr<JMapIndex> index_;
        };

        using JMapPtr = std::shared_ptr<const JMap>;

        /** \brief The polygons of a map made from slices (step 3 above), without the index: the pieces, and
            their union. */
        void jmapPolygons(const std::vector<JMapSlice> &slices, double lo2, double hi2, const JMapSettings &settings,
                          std::vector<Polygon2> &pieces, MultiPolygon2 &polygons);

        /** \brief The paper's line walk over one chain of end points (x non-decreasing, at most two points with
            the same x, e.g. a staircase): circles of radius \e r; keeps a point as a vertex when the line from the
            last vertex past it misses a circle or passes inside an end point (\e upper: the line must not pass
            below any point; else not above; 1e-12 rad of rounding allowed). Returns the kept points, first and
            last included. */
        std::vector<Point2> lineWalk(const std::vector<Point2> &chain, double r, bool upper);

        /** \brief A stack of 2-D maps for three joints (paper Fig. 2): one map over (axis1, axis2) of \e base per
            cell of joint \e outer (configuration index). Slice k is conservative for every outer value in its
            cell. Maps are built on demand by map(k) (not thread-safe) or slice(k) (no caching; thread-safe). */
        class JMapStack
        {
        public:
            using SourceFactory = std::function<JMapIntervalSourcePtr(const JMapAxes &axes)>;

            /** \param makeSource makes the 2-D source of an outer cell: it gets \e base with configuration[outer]
                = the cell centre and halfWidths[outer] = half the cell
                \param outerLo, outerHi the outer joint's range \param outerSlices number of cells */
            JMapStack(SourceFactory makeSource, JMapAxes base, int outer, double outerLo, double outerHi,
                      int outerSlices, JMapSettings settings = {});

            std::size_t size() const
            {
                return static_cast<std::size_t>(outerSlices_);
            }
            /** \brief Cell of the outer joint holding \e value (clamped). */
            std::size_t sliceIndex(double value) const;
            /** \brief Centre and borders of cell \e k. */
            double centre(std::size_t k) const;
            std::pair<double, double> cell(std::size_t k) const;
            /** \brief Build the map of cell \e k (thread-safe, not cached). */
            JMapPtr slice(std::size_t k) const;
            /** \brief The map of cell \e k, built and kept on first use (single thread only). */
            const JMapPtr &map(std::size_t k);
            /** \brief Build every map (single thread only). */
            void buildAll();
            /** \brief collides(outer value, axis1 value, axis2 value) through map(sliceIndex(outer)). */
            bool collides(double outer, double theta1, double theta2);
            int outer() const
            {
                return outer_;
            }
            const JMapAxes &base() const
            {
                return base_;
            }

        private:
            SourceFactory makeSource_;
            JMapAxes base_;
            int outer_;
            double outerLo_, outerHi_;
            int outerSlices_;
            JMapSettings settings_;
            std::vector<JMapPtr> maps_;
        };

        /** \brief Obstacles grown by \e distance (Minkowski sum with a disk; Boost.Geometry buffer with round
            joins and ends). The buffer's arcs are chords; the distance is enlarged by 1 / cos(pi / points) so
            the chords lie outside the true arcs and the result contains the exact Minkowski sum. */
        MultiPolygon2 growObstacles(const MultiPolygon2 &obstacles, double distance, int pointsPerCircle = 36);

        /** \brief The paper's bottleneck (隘路): grown map polygons minus map polygons (Boost.Geometry
            difference), where only the hand can collide. */
        MultiPolygon2 bottleneck(const JMap &grown, const JMap &plain);

        /** \brief Helpers for the common case. Axes over variables \e axis1, \e axis2 of \e arm at
            configuration \e configuration (empty: zeros), ranges from the joint limits. */
        JMapAxes planarAxes(const PlanarArm &arm, int axis1, int axis2, std::vector<double> configuration = {});
    }  // namespace validity
}  // namespace michi

#endif
