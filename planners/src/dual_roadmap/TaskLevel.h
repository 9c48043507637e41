#ifndef MICHI_PLANNERS_DUAL_ROADMAP_TASK_LEVEL_
#define MICHI_PLANNERS_DUAL_ROADMAP_TASK_LEVEL_

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief The upper level of paper 002's hierarchical roadmap for arms: the hand's position (the task space,
            the dominant DOF of a reaching motion) on a grid of cells around a query. It knows no obstacle: the
            lower level (the joint-space working roadmap) tells it where its states were found valid or invalid
            (mark()), and a cell where invalid states outnumber valid ones is expensive to cross. route() is a
            shortest way of the hand from the query's start to its goal through the cells: the task-space waypoints
            the lower level realises as joint states (DualRoadmap, Jacobian micro-motions). */
        class TaskLevel
        {
        public:
            /** \brief A new query (or scene): the grid spans the box around \e from and \e to grown by \e margin,
                in cells of \e cell (at most about 32^3 of them: larger cells when the box is large); earlier marks
                are forgotten. An end that is not finite leaves no grid (route() is then false). */
            void begin(const Eigen::Vector3d &from, const Eigen::Vector3d &to, double cell, double margin);
            /** \brief A joint state whose hand is at \e hand was found \e valid (or invalid) in this scene; kept
                until the next begin(). Marks outside the grid are ignored. */
            void mark(const Eigen::Vector3d &hand, bool valid);
            /** \brief Forget the marks of the last round (markRound()), keep mark()'s. */
            void beginRound();
            /** \brief As mark(), until the next beginRound(): for records that the caller reads afresh every round
                (a roadmap's vertices, whose records change between rounds). */
            void markRound(const Eigen::Vector3d &hand, bool valid);
            /** \brief The hand's way from the begin()'s \e from to its \e to over the cells (26 neighbours, each
                step its length, times \e blockedCost (at least 1) in a cell whose invalid marks outnumber its valid
                ones, both kinds of mark counted), as the centres of the cells passed, \e from first and \e to last.
                False (and \e waypoints empty) when there is no grid. */
            bool route(double blockedCost, std::vector<Eigen::Vector3d> &waypoints);
            /** \brief Cells of the current grid (for tests). */
            std::size_t cellCount() const
            {
                return valid_.size();
            }
            /** \brief Whether the cell of \e p counts as blocked (more invalid marks than valid ones). */
            bool blocked(const Eigen::Vector3d &p) const;

        private:
            long cellOf(const Eigen::Vector3d &p) const;
            static void count(std::vector<std::uint16_t> &counts, long cell);
            bool blockedCell(std::size_t c) const
            {
                return invalid_[c] + roundInvalid_[c] > valid_[c] + roundValid_[c];
            }
            Eigen::Vector3d centre(long c) const;

            Eigen::Vector3d origin_{Eigen::Vector3d::Zero()}, from_, to_;
            double cell_{0.};
            int n_[3]{0, 0, 0};
            std::vector<std::uint16_t> valid_, invalid_, roundValid_, roundInvalid_;
            // the search's buffers, kept between routes
            std::vector<double> g_;
            std::vector<long> pred_;
            std::vector<std::uint8_t> closed_;
        };
    }  // namespace planners
}  // namespace michi

#endif
