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
            (Amanatides and Woo's voxel walk) and the motion is valid when all of them are. As each entry is free
            for all its poses, a valid motion is free along its whole length (conservative like the table).
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
            bool check(const ompl::base::State *s1, const ompl::base::State *s2,
                       std::pair<ompl::base::State *, double> *lastValid) const;
            GridValidityCheckerPtr checker_;
            const state_spaces::TurnMoveTurnStateSpace *turnMoveTurn_{nullptr};
            mutable std::atomic<std::uint64_t> visited_{0};
        };
    }  // namespace validity
}  // namespace michi

#endif
