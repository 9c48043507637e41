#include "DominantDirections.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace michi
{
    namespace planners
    {
        Eigen::MatrixXd dominantDirections(const Eigen::MatrixXd &motions, const Eigen::MatrixXd &states,
                                           unsigned int k)
        {
            const Eigen::Index n = motions.cols();
            const Eigen::Index m = motions.rows();
            const Eigen::Index count = std::min<Eigen::Index>({static_cast<Eigen::Index>(k), n, m});
            if (count == 0)
                return Eigen::MatrixXd(n, 0);
            // A local path and its reverse are the same motion: the second moment about zero, not the covariance
            // about the mean displacement (which depends on the direction each edge happens to be stored in).
            const Eigen::MatrixXd moment = motions.transpose() * motions / static_cast<double>(m);
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(moment);
            // eigenvalues ascending: the last columns are the dominant directions
            Eigen::MatrixXd out(n, count);
            Eigen::RowVectorXd mean =
                states.rows() > 0 ? Eigen::RowVectorXd(states.colwise().mean()) : Eigen::RowVectorXd::Zero(n);
            for (Eigen::Index j = 0; j < count; ++j)
            {
                const Eigen::VectorXd d = eigen.eigenvectors().col(n - 1 - j);
                double spread = 0.;
                if (states.rows() > 1)
                {
                    const Eigen::VectorXd along = (states.rowwise() - mean) * d;
                    spread = std::sqrt(along.squaredNorm() / static_cast<double>(states.rows() - 1));
                }
                out.col(j) = spread * d;
            }
            return out;
        }
    }  // namespace planners
}  // namespace michi
