#ifndef MICHI_PLANNERS_CIRCLE_LIFTS_
#define MICHI_PLANNERS_CIRCLE_LIFTS_

#include <michi/planners/concentric_circle/CircleMap.h>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/SpaceInformation.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

/* How ConcentricCircle turns an OMPL space into 2-D maps and map points back into states: the projection on two
   state values (the rest interpolated between start and goal), the hand map of the arm -> hand hierarchy
   (arm-path arc length x hand value), the J-map polygons of a JMapValidityChecker, and the arm's own map without
   the hand's links (planar arms). */

namespace michi
{
    namespace planners
    {
        /** \brief Range of one value of copyToReals and whether it wraps (SO(2): [-pi, pi)). */
        struct ValueAxis
        {
            double lo{0.};
            double hi{0.};
            bool wraps{false};
        };

        /** \brief The axes of every value of \e space (compound spaces of real vector and SO(2) parts);
            throws ompl::Exception for other spaces. */
        std::vector<ValueAxis> valueAxes(const ompl::base::StateSpace &space);

        /** \brief copyFromReals + enforceBounds (wraps SO(2) values). */
        void setStateValues(const ompl::base::StateSpace &space, const std::vector<double> &values,
                            ompl::base::State *state);

        /** \brief The plane of values \e axis1, \e axis2; the other values are interpolated between start and
            goal by the point's progress along the start-goal direction in the plane (t in [0, 1]). Points are
            checked with the space's validity checker, segments with its motion validator. */
        class ProjectionLift
        {
        public:
            ProjectionLift(ompl::base::SpaceInformationPtr si, std::vector<double> start, std::vector<double> goal,
                           int axis1, int axis2);
            ~ProjectionLift();
            /** \brief Start and goal in the plane (the goal's image nearest to the start on wrapping axes). */
            const Eigen::Vector2d &start2() const
            {
                return start2_;
            }
            const Eigen::Vector2d &goal2() const
            {
                return goal2_;
            }
            /** \brief Full values (unwrapped) of plane point \e p. */
            std::vector<double> values(const Eigen::Vector2d &p) const;
            void lift(const Eigen::Vector2d &p, ompl::base::State *state) const;
            /** \brief The map: ranges of the two values, validity checker, motion validator. */
            std::shared_ptr<CircleMap> makeMap() const;
            const ompl::base::SpaceInformationPtr &si() const
            {
                return si_;
            }
            int axis1() const
            {
                return axis1_;
            }
            int axis2() const
            {
                return axis2_;
            }
            const std::vector<ValueAxis> &axes() const
            {
                return axes_;
            }

        private:
            ompl::base::SpaceInformationPtr si_;
            std::vector<double> start_, goal_;
            int axis1_, axis2_;
            std::vector<ValueAxis> axes_;
            Eigen::Vector2d start2_, goal2_;
            ompl::base::State *a_, *b_;  ///< scratch states
        };

        /** \brief The hand map of the arm -> hand hierarchy (paper 000, section 4): x = arc length along the arm
            path (the paper's arm-path index, continuous), y = the hand value; the arm values follow the path,
            the remaining values are interpolated between start and goal by x / length. A straight segment is
            the polyline through the arm path's vertices (breakpoints()); each piece is checked with the space's
            motion validator, points with its validity checker. */
        class HandLift
        {
        public:
            /** \param from, to the window of arc lengths the map spans (paper 000: the stretch of the arm path in
                the bottleneck; to < 0: the whole path). Before a window that starts after the path's start, the
                hand turns from its start value to its goal value, and the map starts there; after the window it
                keeps its goal value (outsideBefore(), outsideAfter()). */
            HandLift(ompl::base::SpaceInformationPtr si, std::vector<double> start, std::vector<double> goal, int axis1,
                     int axis2, int hand, std::vector<Eigen::Vector2d> armPath, double from = 0., double to = -1.);
            ~HandLift();
            const Eigen::Vector2d &start2() const
            {
                return start2_;
            }
            const Eigen::Vector2d &goal2() const
            {
                return goal2_;
            }
            std::vector<double> values(const Eigen::Vector2d &p) const;
            void lift(const Eigen::Vector2d &p, ompl::base::State *state) const;
            std::vector<Eigen::Vector2d> breakpoints(const Eigen::Vector2d &a, const Eigen::Vector2d &b) const;
            std::shared_ptr<CircleMap> makeMap() const;
            /** \brief Arc length of the arm path at each of its vertices. */
            const std::vector<double> &arcLengths() const
            {
                return s_;
            }
            const std::vector<Eigen::Vector2d> &armPath() const
            {
                return arm_;
            }
            /** \brief Total arc length of the arm path. */
            double length() const
            {
                return length_;
            }
            /** \brief Map points of the arm path's vertices before the window (from the path's start on), the hand
                turning linearly with arc length to the window's entry value. */
            std::vector<Eigen::Vector2d> outsideBefore() const;
            /** \brief Map points of the arm path's vertices after the window, at the goal's hand value (to the
                path's end). */
            std::vector<Eigen::Vector2d> outsideAfter() const;

        private:
            ompl::base::SpaceInformationPtr si_;
            std::vector<double> start_, goal_;
            int axis1_, axis2_, hand_;
            std::vector<ValueAxis> axes_;
            std::vector<Eigen::Vector2d> arm_;
            std::vector<double> s_;
            double length_{0.};
            double from_{0.}, to_{0.};  ///< the window of arc lengths the map spans
            Eigen::Vector2d start2_, goal2_;
            ompl::base::State *a_, *b_;
        };

        /** \brief The paper's trajectory-restriction surface (section 4): the plane in joint space through start
            and goal spanned by e1 = (goal - start) / |goal - start| and e2 = cos(angle) n1 + sin(angle) n2, where n1,
            n2 are the two coordinate axes least aligned with e1, made orthonormal to e1 (Gram-Schmidt). A plane
            point (u, v) is the state start + u e1 + v e2; u spans [-margin, |goal - start| + margin], v spans
            [-margin, margin]. Points are checked with the space's validity checker (the J-map stack cut onto the
            plane, point by point), segments (straight in joint space too) with its motion validator. */
        class SurfaceLift
        {
        public:
            SurfaceLift(ompl::base::SpaceInformationPtr si, std::vector<double> start, std::vector<double> goal,
                        double angle, double margin = M_PI);
            ~SurfaceLift();
            const Eigen::Vector2d &start2() const
            {
                return start2_;
            }
            const Eigen::Vector2d &goal2() const
            {
                return goal2_;
            }
            std::vector<double> values(const Eigen::Vector2d &p) const;
            void lift(const Eigen::Vector2d &p, ompl::base::State *state) const;
            std::shared_ptr<CircleMap> makeMap() const;

        private:
            ompl::base::SpaceInformationPtr si_;
            std::vector<double> start_;
            std::vector<double> e1_, e2_;
            double margin_;
            Eigen::Vector2d start2_, goal2_;
            ompl::base::State *a_, *b_;
        };

        /** \brief True when the space's checker is michi's FCL (or J-map) checker of a robot whose joints all turn
            about z (a planar arm). */
        bool isPlanarArm(const ompl::base::SpaceInformationPtr &si);

        /** \brief The J-map polygons of the space's checker when it is a michi::validity::JMapValidityChecker
            over exactly the two values of the state (every tile built, polygons united), else null. */
        std::shared_ptr<CircleMap> makeJMapCircleMap(const ompl::base::SpaceInformationPtr &si);

        /** \brief The arm stage of the hierarchy (paper 000, section 3): the arm's map, and where the hand can
            collide at all. */
        struct ArmMaps
        {
            std::shared_ptr<CircleMap> map;
            /** "jmap": the J-map polygons of the arm's links without the hand (the paper); "capsules": the exact
                capsule geometry of those links, segments sampled every 0.005 rad (when the start or goal lies
                inside the conservative polygons); "projection": the space's checker on the plane of the two
                values (not a planar arm) */
            std::string kind;
            /** True where the arm lies in the grown map (the arm's links against the obstacles grown by the
                hand's reach): only there can the hand touch an obstacle, the paper's bottleneck (grown map minus
                map) for an arm configuration that is free. Empty when there is no planar model or no hand. */
            std::function<bool(const Eigen::Vector2d &)> inGrown;
        };

        /** \brief The arm's maps for the hierarchy. When the space's checker is michi's FCL (or J-map) checker of
            a planar arm (every joint about z): the J-map (\e slices cells of axis 1, line-walk tolerance
            \e tolerance) of the arm's links without the links that the values \e handValues move, as the paper
            builds the arm's J-map; the capsule geometry when the start or goal is inside its polygons; and the
            grown map. Otherwise \e arm's projection map. The J-map's build stops between slices once \e ptc
            (when given) is true; the maps are then the capsules' and the caller is out of time. */
        ArmMaps makeArmMaps(const ompl::base::SpaceInformationPtr &si, const ProjectionLift &arm,
                            const std::vector<int> &handValues, int slices, double tolerance,
                            const ompl::base::PlannerTerminationCondition *ptc = nullptr);
    }  // namespace planners
}  // namespace michi

#endif
