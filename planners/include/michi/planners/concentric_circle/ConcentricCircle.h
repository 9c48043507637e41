#ifndef MICHI_PLANNERS_CONCENTRIC_CIRCLE_
#define MICHI_PLANNERS_CONCENTRIC_CIRCLE_

#include <michi/planners/concentric_circle/CircleMap.h>
#include <michi/planners/concentric_circle/ConcentricCircleSearch.h>

#include <ompl/base/Planner.h>
#include <ompl/util/Exception.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace michi
{
    namespace planners
    {
        class CapsuleClearance;

        /**
           @anchor michiConcentricCircle
           @par Short description
           The concentric-circle potential method: circles around the start at a fixed spacing until the goal,
           each cut into \e divisions points; an oval potential (attraction -Kg/Dg to the goal, repulsion Kp/Dp^2
           with Dp = |PA| + |PB| - |AB| from every obstacle edge AB visible from P) picks one candidate per free
           arc; candidates of adjacent circles that see each other are linked, and chains of links are paths
           (several: left and right around obstacles); the best by length or clearance is the solution. Where no
           chain exists, unlinked points become a new start and goal (recursion) until \e max_recursions. The
           method is deterministic.

           Modes (parameter \e mode):
           - \c jmap: the space's validity checker is a michi::validity::JMapValidityChecker over exactly the two
             joints of the state: circles, potential and visibility on the J-map polygons; every path is then
             re-checked with the space's motion validator (links it rejects are dropped).
           - \c projection: any space: the plane of two state values (\e axis1, \e axis2), the other values
             interpolated between start and goal along the start-goal direction; points checked with the space's
             validity checker, visibility with its motion validator; the potential's obstacle edges are the
             blocked runs of the circles. Continuous (SO(2)) values wrap.
           - \c hierarchy (3 or more values, the paper's arm -> hand split): the arm (\e axis1, \e axis2) is
             planned first, checked without the links moved by the other values when the checker's robot is a
             planar arm (exact capsule geometry of michi::validity::PlanarArm), else as in projection mode; then,
             along each arm path (best first), a hand map (arm-path arc length x \e hand_axis) is planned with the
             space's own checker and motion validator; the first hand path found gives the full path.
           - \c surface (3 or more values, the paper's trajectory-restriction surface): the plane in joint space
             through start and goal at orientation \e surface_angle about the start-goal line; points and segments
             checked with the space's checker and motion validator; if no path is found on it, the planes turned
             by 45, 90 and 135 degrees are tried.
           - \c auto: jmap when possible; for 3 or more values hierarchy when the robot is a planar arm, then
             surface; else projection.
           Every returned path passes the space's motion validator.

           @par External documentation
           N. Kawarazaki and T. Nagata, "Generation of Collision-free Path of a Manipulator by Means of
           Joint-map", 1991 (michi: docs/concentric-circle.md).
        */
        class ConcentricCircle : public ompl::base::Planner
        {
        public:
            /** \brief One 2-D search of the last solve and how its points become states. */
            struct Stage
            {
                std::string name;  ///< "jmap", "projection", "arm", "hand"
                std::shared_ptr<CircleMap> map;
                std::shared_ptr<ConcentricCircleSearch> search;
                std::function<void(const Eigen::Vector2d &, ompl::base::State *)> lift;
                int chosenPath{-1};  ///< index into search->paths() that the solution uses (-1: none)
            };

            explicit ConcentricCircle(const ompl::base::SpaceInformationPtr &si);
            ~ConcentricCircle() override;

            ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
            void clear() override;
            void setup() override;
            void getPlannerData(ompl::base::PlannerData &data) const override;

            void setRingSpacing(double v)
            {
                requireSetting(v > 0. && std::isfinite(v), "ring_spacing must be a positive number");
                settings_.ringSpacing = v;
            }
            double getRingSpacing() const
            {
                return settings_.ringSpacing;
            }
            void setDivisions(int v)
            {
                requireSetting(v >= 8 && v <= 720, "divisions must be in [8, 720]");
                settings_.divisions = v;
            }
            int getDivisions() const
            {
                return settings_.divisions;
            }
            void setPointSpacing(double v)
            {
                requireSetting(v >= 0. && std::isfinite(v), "point_spacing must be 0 or a positive number");
                settings_.pointSpacing = v;
            }
            double getPointSpacing() const
            {
                return settings_.pointSpacing;
            }
            void setKGoal(double v)
            {
                requireSetting(v >= 0. && std::isfinite(v), "k_goal must be 0 or a positive number");
                settings_.kGoal = v;
            }
            double getKGoal() const
            {
                return settings_.kGoal;
            }
            void setKObstacle(double v)
            {
                requireSetting(v >= 0. && std::isfinite(v), "k_obstacle must be 0 or a positive number");
                settings_.kObstacle = v;
            }
            double getKObstacle() const
            {
                return settings_.kObstacle;
            }
            void setPotentialRange(double v)
            {
                requireSetting(v >= 0. && std::isfinite(v), "potential_range must be 0 or a positive number");
                settings_.potentialRange = v;
            }
            double getPotentialRange() const
            {
                return settings_.potentialRange;
            }
            void setMaxArcPoints(int v)
            {
                requireSetting(v >= 0, "max_arc_points must be 0 or more");
                settings_.maxArcPoints = v;
            }
            int getMaxArcPoints() const
            {
                return settings_.maxArcPoints;
            }
            void setArcEnds(bool v)
            {
                settings_.arcEnds = v;
            }
            bool getArcEnds() const
            {
                return settings_.arcEnds;
            }
            void setMaxRecursions(int v)
            {
                requireSetting(v >= 0, "max_recursions must be 0 or more");
                settings_.maxRecursions = v;
            }
            int getMaxRecursions() const
            {
                return settings_.maxRecursions;
            }
            void setOuterRings(bool v)
            {
                settings_.outerRings = v;
            }
            bool getOuterRings() const
            {
                return settings_.outerRings;
            }
            void setMaxPaths(int v)
            {
                requireSetting(v >= 1, "max_paths must be at least 1");
                settings_.maxPaths = v;
            }
            int getMaxPaths() const
            {
                return settings_.maxPaths;
            }
            /** \brief "michi" (default) or "paper": the candidate rule (ConcentricCircleSettings::candidates). */
            void setCandidates(const std::string &v);
            const std::string &getCandidates() const
            {
                return settings_.candidates;
            }
            /** \brief "length" (shortest) or "clearance" (largest minimum clearance) picks the solution. */
            void setObjective(const std::string &v);
            const std::string &getObjective() const
            {
                return objective_;
            }
            /** \brief "auto", "jmap", "projection", "hierarchy" or "surface". */
            void setMode(const std::string &v);
            const std::string &getMode() const
            {
                return mode_;
            }
            void setAxis1(int v)
            {
                requireValueIndex("axis1", v, 0);
                axis1_ = v;
            }
            int getAxis1() const
            {
                return axis1_;
            }
            void setAxis2(int v)
            {
                requireValueIndex("axis2", v, 0);
                axis2_ = v;
            }
            int getAxis2() const
            {
                return axis2_;
            }
            /** \brief Orientation of the trajectory-restriction plane about the start-goal line (radians). */
            void setSurfaceAngle(double v)
            {
                surfaceAngle_ = v;
            }
            double getSurfaceAngle() const
            {
                return surfaceAngle_;
            }
            /** \brief The hand value of hierarchy mode (-1: the first value that is neither axis). */
            void setHandAxis(int v)
            {
                requireValueIndex("hand_axis", v, -1);
                handAxis_ = v;
            }
            int getHandAxis() const
            {
                return handAxis_;
            }

            /** \brief Cells of axis 1 of the arm's J-map in hierarchy mode (0: no J-map, the capsule geometry). */
            void setArmSlices(int v)
            {
                if (v < 0)
                    throw ompl::Exception(getName(), "arm_slices must be >= 0");
                armSlices_ = v;
            }
            int getArmSlices() const
            {
                return armSlices_;
            }
            /** \brief The arm J-map's line-walk tolerance r (radians) in hierarchy mode. */
            void setArmTolerance(double v)
            {
                if (!(v > 0.))
                    throw ompl::Exception(getName(), "arm_tolerance must be > 0");
                armTolerance_ = v;
            }
            double getArmTolerance() const
            {
                return armTolerance_;
            }
            /** \brief Hand maps of hierarchy mode span only the stretch of the arm path in the grown map (the
                paper's bottleneck); false: the whole arm path. */
            void setHandInBottleneck(bool v)
            {
                handInBottleneck_ = v;
            }
            bool getHandInBottleneck() const
            {
                return handInBottleneck_;
            }
            /** \brief The arm map the last hierarchy solve used: "jmap", "capsules" or "projection" (empty: none). */
            const std::string &armMapKind() const
            {
                return armMapKind_;
            }

            /** \brief The searches of the last solve (for pictures and tests). */
            const std::vector<Stage> &stages() const
            {
                return stages_;
            }
            /** \brief The mode the last solve used ("jmap", "projection", "hierarchy"). */
            const std::string &usedMode() const
            {
                return usedMode_;
            }
            /** \brief Every full path the last solve found and checked (the solution is one of them). */
            const std::vector<std::vector<ompl::base::State *>> &fullPaths() const
            {
                return fullPaths_;
            }

        private:
            /** Setters refuse what would make the search nonsense or endless (a ring spacing of 0, negative counts),
                as the command line refuses values outside the declared ranges: C++ callers set them directly. */
            void requireSetting(bool ok, const char *what) const
            {
                if (!ok)
                    throw ompl::Exception(getName(), what);
            }

            /** A setting that names one value of the state (axis1, axis2, hand_axis) must name one of this space's:
                out of range it was accepted and the solve failed later with "no path". */
            void requireValueIndex(const char *name, int v, int lowest) const
            {
                const int n = static_cast<int>(si_->getStateDimension());
                if (v < lowest || v >= n)
                    throw ompl::Exception(getName(), std::string(name) + " = " + std::to_string(v) +
                                                         " is not a value of the " + std::to_string(n) +
                                                         "-value state (" + std::to_string(lowest) + " to " +
                                                         std::to_string(n - 1) + ")");
            }
            struct Axes;
            bool solveJMap(const std::vector<double> &start, const std::vector<double> &goal,
                           const ompl::base::PlannerTerminationCondition &ptc);
            bool solveProjection(const std::vector<double> &start, const std::vector<double> &goal,
                                 const ompl::base::PlannerTerminationCondition &ptc);
            bool solveHierarchy(const std::vector<double> &start, const std::vector<double> &goal,
                                const ompl::base::PlannerTerminationCondition &ptc);
            /** the hand stage along arm path \e armPathIndex over the window [from, to] of its arc length (to < 0:
                all of it); true when it gave full paths */
            bool solveHand(const std::vector<double> &start, const std::vector<double> &goal, int hand,
                           std::size_t armPathIndex, const std::vector<Eigen::Vector2d> &armPath, double from,
                           double to, const ompl::base::PlannerTerminationCondition &ptc);
            bool solveSurface(const std::vector<double> &start, const std::vector<double> &goal,
                              const ompl::base::PlannerTerminationCondition &ptc);
            /** states of path \e i of stage \e s (every segment checked with the motion validator); empty when
                a segment fails */
            std::vector<ompl::base::State *> liftPath(const Stage &stage, std::size_t i, bool check);
            void freePaths();
            /** the path's cost (length, or negated clearance): exact when below \e bound; otherwise some value at
                or above it (the clearance walk stops once the path cannot beat \e bound) */
            double pathCost(const std::vector<ompl::base::State *> &states,
                            double bound = std::numeric_limits<double>::infinity()) const;
            /** the setting "clearance", or a MaximizeMinClearanceObjective on the problem definition */
            bool selectsClearance() const;

            ConcentricCircleSettings settings_;
            std::string objective_{"length"};
            std::string mode_{"auto"};
            int axis1_{0};
            int axis2_{1};
            int handAxis_{-1};
            int armSlices_{720};
            double armTolerance_{0.01};
            bool handInBottleneck_{true};
            std::string armMapKind_;
            double surfaceAngle_{0.};

            std::vector<Stage> stages_;
            /** The J-map's polygons as a circle map, made in setup() (it depends on the checker only, not on the
                query); \e jmapChecker_ is the checker it was made from, so a changed checker is noticed. */
            std::shared_ptr<CircleMap> jmapMap_;
            const void *jmapChecker_{nullptr};
            std::uint64_t jmapGeneration_{0};  ///< the scene's changeCount() when jmapMap_ was made
            /** The planar arm's capsule clearance the push climbs (null: not a planar arm, the checker's
                clearance() instead), made for \e capsuleChecker_ at the scene's \e capsuleGeneration_. */
            std::shared_ptr<const CapsuleClearance> capsules_;
            const void *capsuleChecker_{nullptr};
            std::uint64_t capsuleGeneration_{0};
            /** capsules_ for the current checker and scene */
            void refreshCapsules();
            void refreshJMapMap();
            std::string usedMode_;
            std::vector<std::vector<ompl::base::State *>> fullPaths_;
            int bestPath_{-1};
            /** states of the exported graph (planner data) */
            mutable std::vector<std::vector<ompl::base::State *>> stageStates_;
        };
    }  // namespace planners
}  // namespace michi

#endif
