#ifndef MICHI_PLANNERS_PATH_SEED_CODEC_
#define MICHI_PLANNERS_PATH_SEED_CODEC_

#include <Eigen/Core>

#include <string>
#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief How a path seed stores a waypoint's offset from the start-goal line.
            - BLOCKS: the paper's encoding (Watanabe & Nishida, Tables 1 and 2). The cross product exists in 3-D, so
              every vector is cut into blocks of three joints (joints 1-3, 4-6, ...; the last block padded with
              zeros), and each block is encoded as a 3-D path: ratio r, deviation norm tau, direction delta. For
              N = 3 this is Table 1/2 as printed, for N = 6 it is the paper's split into joints 1-3 and 4-6.
            - ROTATION: michi's variant for any N without blocks: one ratio r and deviation tau per waypoint in the
              full space, and the unit offset direction; decoding turns it by the rotation that takes the seed's
              line direction e to the new one (the rotation in the plane of e and e~, identity elsewhere). */
        enum class SeedVariant
        {
            BLOCKS,
            ROTATION
        };

        /** \brief "blocks" / "rotation"; and back (throws std::invalid_argument on anything else). */
        std::string seedVariantName(SeedVariant variant);
        SeedVariant seedVariantFromName(const std::string &name);

        /** \brief A path seed S = {R, T, Delta} (the paper's Table 1, Step 3) of a path with M waypoints between
            start and goal, in an N-joint space.

            BLOCKS, with B = ceil(N / 3) blocks: ratio and deviation hold M x B values (waypoint-major), direction
            M x 3B, axis 3B (the unit start-goal direction of each block at encoding, zero where the block did not
            move; used only for degenerate cases). ROTATION: ratio and deviation hold M values, direction M x N
            (unit offset directions, orthogonal to axis), axis N. */
        struct PathSeedCode
        {
            SeedVariant variant{SeedVariant::BLOCKS};
            unsigned int dimension{0};  ///< N
            std::vector<double> axis;
            std::vector<double> ratio;      ///< r
            std::vector<double> deviation;  ///< tau
            std::vector<double> direction;  ///< delta

            /** \brief Values per waypoint in ratio/deviation (B or 1) and per waypoint in direction (3B or N). */
            unsigned int blocks() const;
            unsigned int directionWidth() const;
            /** \brief M, the number of waypoints between start and goal. */
            std::size_t waypoints() const;
        };

        /** \brief Encode a path (start, waypoints..., goal; at least 2 states, all of dimension N) as a seed.

            Decisions the paper leaves open (docs/path-seed.md):
            - r is signed: r = (w - s)^T v / |v|^2, so a waypoint behind the start (or beyond the goal) keeps its
              side; the paper's |l - s| / |v| would fold it onto the segment.
            - BLOCKS: each block has its own line (v_b, e_b), foot of perpendicular l_b and ratio r_b. With the
              paper's single r from the full space, a block's offset w_b - l_b is not orthogonal to e_b and the
              cross products cannot give it back; per-block ratios reproduce the path exactly.
            - delta = normalize(e x (w - l)); decoding uses normalize(delta x e~), so tau is kept for any new line.
            - w - l zero (tau = 0): delta = 0, the waypoint lies on the line. A block whose start and goal coincide
              (v_b = 0, including s = g): r_b is the waypoint's ratio on the full line (0 if s = g too), delta_b the
              offset's own unit direction, laid out as it is (a translation). */
        PathSeedCode encodePath(const std::vector<Eigen::VectorXd> &path, SeedVariant variant);

        /** \brief Decode a seed for a new start and goal (the paper's Table 2): l~ = s~ + r v~,
            w~ = l~ + tau normalize(delta x e~) per block (BLOCKS), or w~ = l~ + tau Q delta with Q the rotation
            taking e to e~ (ROTATION). Returns start, M waypoints, goal. Where the new line is degenerate
            (v~_b = 0) or delta is parallel to e~, the offset keeps the seed's own direction turned from e to e~
            (or untouched): never NaN. */
        std::vector<Eigen::VectorXd> decodePath(const PathSeedCode &seed, const Eigen::VectorXd &start,
                                                const Eigen::VectorXd &goal);

        /** \brief Same, writing into \e out (resized as needed; reuses its storage). */
        void decodePath(const PathSeedCode &seed, const Eigen::VectorXd &start, const Eigen::VectorXd &goal,
                        std::vector<Eigen::VectorXd> &out);
    }  // namespace planners
}  // namespace michi

#endif
