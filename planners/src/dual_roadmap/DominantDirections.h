#ifndef MICHI_PLANNERS_DUAL_ROADMAP_DOMINANT_DIRECTIONS_
#define MICHI_PLANNERS_DUAL_ROADMAP_DOMINANT_DIRECTIONS_

#include <Eigen/Core>

namespace michi
{
    namespace planners
    {
        /** \brief Paper 002's dominant degrees of freedom: the few coordinated directions along which the robot's
            coherent motions go. Taken as the \e k principal directions of \e motions (one displacement per row: the
            experienced local paths near a query), each scaled by the standard deviation of \e states (one position
            per row) along it, so that Gaussian steps along the columns cover the region the experience spans. The
            result has one column per direction (fewer when there are fewer motions than directions); empty when
            \e motions has no rows or \e k is 0. */
        Eigen::MatrixXd dominantDirections(const Eigen::MatrixXd &motions, const Eigen::MatrixXd &states,
                                           unsigned int k);
    }  // namespace planners
}  // namespace michi

#endif
