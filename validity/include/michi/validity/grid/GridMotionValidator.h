#ifndef MICHI_VALIDITY_GRID_GRID_MOTION_VALIDATOR_
#define MICHI_VALIDITY_GRID_GRID_MOTION_VALIDATOR_

#include <michi/validity/grid/GridValidityChecker.h>

#include <ompl/base/MotionValidator.h>

#include <vector>

namespace michi
{
    namespace state_spaces
    {
        class TurnMoveTurnStateSpace;
    }
    namespace validity
    {
        /** \brief Continuous motion checking on the grid checker's table, with no step size: a motion of OMPL's
            SE2StateSpace (x, y and yaw linear, yaw the short way round) or of state_spaces::TurnMoveTurnStateSpace
            (turn in place, drive straight, turn in place: three such pieces) is a set of straight segments in
            (x, y, yaw); every table entry (cell x heading bin) that a segment passes through is visited
            (Amanatides and Woo's voxel walk). A valid entry is free for all its poses; in an invalid one (near
            obstacles) the segment's own poses are tested exactly (HeadingTable::freePose) at spacings of at most
            a quarter cell of footprint motion, the footprint grown by half the spacing, so a valid motion is free
            along its whole length and one-cell doors the table closes stay open to the motions that fit.
            Thread-safe. */
        class GridMotionValidator : public ompl::base::MotionValidator
        {
        public:
            GridMotionValidator(const ompl::base::SpaceInformationPtr &si, GridValidityCheckerPtr checker);

            bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const override;
            bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                             std::pair<ompl::base::State *, double> &lastValid) const override;

            /** \brief A straight segment in (x, y, yaw), yaw unwrapped (yaw1 + turn), over motion fractions
                [t0, t1]. */
            struct Piece
            {
                double x0, y0, yaw0, x1, y1, yaw1;
                double t0, t1;
            };
            /** \brief The pieces of the motion between two poses in the space's interpolation. */
            std::vector<Piece> pieces(const double *from, const double *to) const;
            /** \brief Walk the pieces: true when every entry is valid; otherwise \e contact is the fraction at which
                the motion enters the first invalid entry and \e lastFree a fraction strictly inside the last valid
                one (0 when the first entry is invalid). */
            bool walk(const std::vector<Piece> &pieces, double *contact = nullptr, double *lastFree = nullptr) const;
            /** \brief Number of table entries visited so far (all threads). */
            std::uint64_t entriesVisited() const
            {
                return visited_.load();
            }

        private:
            /** \brief Footprint motion (in table cells) between the exact tests in an invalid entry. */
            static constexpr double EXACT_SPACING = 0.25;
            /** \brief Is the piece free for fractions [ua, ub] of it (exact tests, footprint grown to cover the
                poses between them)? */
            bool exactSpan(const Piece &piece, double ua, double ub) const;
            bool check(const ompl::base::State *s1, const ompl::base::State *s2,
                       std::pair<ompl::base::State *, double> *lastValid) const;
            GridValidityCheckerPtr checker_;
            const state_spaces::TurnMoveTurnStateSpace *turnMoveTurn_{nullptr};
            mutable std::atomic<std::uint64_t> visited_{0};
        };
    }  // namespace validity
}  // namespace michi

#endif
