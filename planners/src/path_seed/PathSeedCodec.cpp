#include <michi/planners/path_seed/PathSeedCodec.h>

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>

namespace michi
{
    namespace planners
    {
        namespace
        {
            /// A start-goal vector shorter than this is a point: its direction is undefined.
            constexpr double DEGENERATE = 1e-12;

            /** x turned by the rotation that takes unit \e from to unit \e to, in their plane (identity on the
                rest). Antiparallel: a half turn in the plane of \e from and the coordinate axis least aligned
                with it. */
            template <typename Vec>
            Vec rotateInPlane(const Vec &from, const Vec &to, const Vec &x)
            {
                const double c = from.dot(to);
                Vec u = to - c * from;
                double s = u.norm();
                if (s < 1e-12)
                {
                    if (c > 0.)
                        return x;
                    Eigen::Index axis = 0;
                    from.cwiseAbs().minCoeff(&axis);
                    u = Vec::Zero(from.size());
                    u[axis] = 1.;
                    u -= u.dot(from) * from;
                    u.normalize();
                    const double a = x.dot(from), b = x.dot(u);
                    return x - 2. * a * from - 2. * b * u;
                }
                u /= s;
                const double a = x.dot(from), b = x.dot(u);
                // The rotation by angle t (cos t = c, sin t = s) in the plane spanned by from and u: x's components a
                // (along from) and b (along u) turn as a 2-D vector, everything orthogonal to the plane is kept.
                return x + (a * (c - 1.) - b * s) * from + (a * s + b * (c - 1.)) * u;
            }

            Eigen::Vector3d block(const Eigen::VectorXd &x, unsigned int b)
            {
                // Paper 001 splits N = 6 into joints 1-3 and 4-6 because the cross product exists in 3-D only. For N
                // not a multiple of 3 (left open by the paper) the last block is padded with zeros, which no step below
                // moves.
                Eigen::Vector3d out = Eigen::Vector3d::Zero();
                for (unsigned int k = 0; k < 3; ++k)
                    if (3 * b + k < x.size())
                        out[k] = x[3 * b + k];
                return out;
            }

            void setBlock(Eigen::VectorXd &x, unsigned int b, const Eigen::Vector3d &value)
            {
                for (unsigned int k = 0; k < 3; ++k)
                    if (3 * b + k < x.size())
                        x[3 * b + k] = value[k];
            }

            void checkPath(const std::vector<Eigen::VectorXd> &path)
            {
                if (path.size() < 2)
                    throw std::invalid_argument("encodePath: a path needs a start and a goal");
                for (const auto &p : path)
                {
                    if (p.size() != path.front().size() || p.size() == 0)
                        throw std::invalid_argument("encodePath: states of different dimensions");
                    if (!p.allFinite())
                        throw std::invalid_argument("encodePath: a state is not finite");
                }
            }

            PathSeedCode encodeBlocks(const std::vector<Eigen::VectorXd> &path)
            {
                PathSeedCode seed;
                seed.variant = SeedVariant::BLOCKS;
                seed.dimension = static_cast<unsigned int>(path.front().size());
                const unsigned int B = seed.blocks();
                const std::size_t M = path.size() - 2;
                const Eigen::VectorXd &s = path.front(), &g = path.back();
                const Eigen::VectorXd V = g - s;
                const double V2 = V.squaredNorm();
                seed.axis.assign(3 * B, 0.);
                seed.ratio.resize(M * B);
                seed.deviation.resize(M * B);
                seed.direction.resize(M * 3 * B);
                for (unsigned int b = 0; b < B; ++b)
                {
                    // Table 1, Step 1 (per block): v = g - s, e = v / |v|
                    const Eigen::Vector3d sb = block(s, b), vb = block(g, b) - sb;
                    const double nv = vb.norm();
                    const bool moves = nv > DEGENERATE;
                    // A zero axis marks a block that does not move between start and goal; decoding reads it as such
                    // (seedMoves).
                    const Eigen::Vector3d e = moves ? Eigen::Vector3d(vb / nv) : Eigen::Vector3d::Zero();
                    for (unsigned int k = 0; k < 3; ++k)
                        seed.axis[3 * b + k] = e[k];
                    for (std::size_t m = 0; m < M; ++m)
                    {
                        // Table 1, Step 2: foot of perpendicular l, ratio r, deviation tau, direction delta
                        const Eigen::Vector3d wb = block(path[m + 1], b);
                        double r;
                        if (moves)
                            r = (wb - sb).dot(vb) / (nv * nv);
                        else  // a block that does not move: the waypoint's ratio on the full line
                            r = V2 > DEGENERATE * DEGENERATE ? (path[m + 1] - s).dot(V) / V2 : 0.;
                        const Eigen::Vector3d l = sb + r * vb;
                        const Eigen::Vector3d d = wb - l;
                        double tau = d.norm();
                        Eigen::Vector3d delta = Eigen::Vector3d::Zero();
                        if (tau > 0.)
                        {
                            if (moves)
                            {
                                // delta = e x d / |e x d| (Table 1); since d is perpendicular to e, delta x e points
                                // along d again, which is how decoding recovers the offset's direction for a new e~.
                                const Eigen::Vector3d c = e.cross(d);
                                const double nc = c.norm();
                                if (nc > 0.)
                                    delta = c / nc;
                                else
                                    tau = 0.;  // d below rounding: the waypoint is on the line
                            }
                            else
                                delta = d / tau;
                        }
                        seed.ratio[m * B + b] = r;
                        seed.deviation[m * B + b] = tau;
                        for (unsigned int k = 0; k < 3; ++k)
                            seed.direction[m * 3 * B + 3 * b + k] = delta[k];
                    }
                }
                return seed;
            }

            PathSeedCode encodeRotation(const std::vector<Eigen::VectorXd> &path)
            {
                PathSeedCode seed;
                seed.variant = SeedVariant::ROTATION;
                const Eigen::Index N = path.front().size();
                seed.dimension = static_cast<unsigned int>(N);
                const std::size_t M = path.size() - 2;
                const Eigen::VectorXd &s = path.front();
                const Eigen::VectorXd V = path.back() - s;
                const double nv = V.norm();
                const bool moves = nv > DEGENERATE;
                const Eigen::VectorXd e = moves ? Eigen::VectorXd(V / nv) : Eigen::VectorXd::Zero(N);
                seed.axis.assign(e.data(), e.data() + N);
                seed.ratio.resize(M);
                seed.deviation.resize(M);
                seed.direction.resize(M * N);
                for (std::size_t m = 0; m < M; ++m)
                {
                    const Eigen::VectorXd ws = path[m + 1] - s;
                    // Rotation variant (michi's, for any N): r and tau as in the paper on the full vector; delta is the
                    // unit offset itself, turned at decoding by the rotation that takes the old line's direction to the
                    // new one, since no N-D cross product is needed for that.
                    const double r = moves ? ws.dot(V) / (nv * nv) : 0.;
                    const Eigen::VectorXd d = ws - r * V;
                    const double tau = d.norm();
                    seed.ratio[m] = r;
                    seed.deviation[m] = tau;
                    for (Eigen::Index k = 0; k < N; ++k)
                        seed.direction[m * N + k] = tau > 0. ? d[k] / tau : 0.;
                }
                return seed;
            }

            void decodeBlocks(const PathSeedCode &seed, const Eigen::VectorXd &s, const Eigen::VectorXd &g,
                              std::vector<Eigen::VectorXd> &out)
            {
                const unsigned int B = seed.blocks();
                const std::size_t M = seed.waypoints();
                for (unsigned int b = 0; b < B; ++b)
                {
                    // Table 2, Step 1 (per block): v~ = g~ - s~, e~ = v~ / |v~|
                    const Eigen::Vector3d sb = block(s, b), vb = block(g, b) - sb;
                    const double nv = vb.norm();
                    const Eigen::Vector3d e0(seed.axis[3 * b], seed.axis[3 * b + 1], seed.axis[3 * b + 2]);
                    // The stored axis is a unit vector or zero: comparing with 0.5 is robust to rounding in the file.
                    const bool seedMoves = e0.squaredNorm() > 0.5;
                    const bool moves = nv > DEGENERATE;
                    const Eigen::Vector3d e = moves ? Eigen::Vector3d(vb / nv) : e0;
                    for (std::size_t m = 0; m < M; ++m)
                    {
                        // Table 2, Step 2: l~ = s~ + r v~, w~ = l~ + tau (delta x e~)
                        const double r = seed.ratio[m * B + b], tau = seed.deviation[m * B + b];
                        const double *dp = &seed.direction[m * 3 * B + 3 * b];
                        const Eigen::Vector3d delta(dp[0], dp[1], dp[2]);
                        Eigen::Vector3d w = sb + r * vb;
                        if (tau > 0.)
                        {
                            if (!seedMoves)
                                w += tau * delta;  // the seed's block did not move: its offset as it was
                            else if (!moves)
                                w += tau * delta.cross(e0);  // the new block does not move: the seed's offset
                            else
                            {
                                // Table 2, Step 2: tau (delta x e~), normalised here: delta is perpendicular to the
                                // seed's e but not in general to e~, and an unnormalised cross product would shrink the
                                // offset.
                                const Eigen::Vector3d c = delta.cross(e);
                                const double nc = c.norm();
                                if (nc > 1e-9)
                                    w += (tau / nc) * c;
                                else  // delta parallel to e~: the seed's offset turned from e to e~
                                    w += tau * rotateInPlane<Eigen::Vector3d>(e0, e, delta.cross(e0));
                            }
                        }
                        setBlock(out[m + 1], b, w);
                    }
                }
            }

            void decodeRotation(const PathSeedCode &seed, const Eigen::VectorXd &s, const Eigen::VectorXd &g,
                                std::vector<Eigen::VectorXd> &out)
            {
                const Eigen::Index N = seed.dimension;
                const std::size_t M = seed.waypoints();
                const Eigen::VectorXd V = g - s;
                const double nv = V.norm();
                const Eigen::Map<const Eigen::VectorXd> e0(seed.axis.data(), N);
                const bool turn = e0.squaredNorm() > 0.5 && nv > DEGENERATE;
                const Eigen::VectorXd e = turn ? Eigen::VectorXd(V / nv) : Eigen::VectorXd(e0);
                Eigen::VectorXd delta(N);
                for (std::size_t m = 0; m < M; ++m)
                {
                    for (Eigen::Index k = 0; k < N; ++k)
                        delta[k] = seed.direction[m * N + k];
                    Eigen::VectorXd &w = out[m + 1];
                    w = s + seed.ratio[m] * V;
                    const double tau = seed.deviation[m];
                    // Same start and goal give e = e0 and the identity rotation: the seed's own path comes back
                    // exactly (paper 001, Fig. 5).
                    if (tau > 0.)
                        w += tau * (turn ? rotateInPlane<Eigen::VectorXd>(Eigen::VectorXd(e0), e, delta) : delta);
                }
            }
        }  // namespace

        std::string seedVariantName(SeedVariant variant)
        {
            return variant == SeedVariant::BLOCKS ? "blocks" : "rotation";
        }

        SeedVariant seedVariantFromName(const std::string &name)
        {
            if (name == "blocks")
                return SeedVariant::BLOCKS;
            if (name == "rotation")
                return SeedVariant::ROTATION;
            throw std::invalid_argument("unknown path seed variant '" + name + "' (expected blocks or rotation)");
        }

        unsigned int PathSeedCode::blocks() const
        {
            // Number of 3-joint blocks, rounded up (a partial last block is zero-padded).
            return variant == SeedVariant::BLOCKS ? (dimension + 2) / 3 : 1;
        }

        unsigned int PathSeedCode::directionWidth() const
        {
            return variant == SeedVariant::BLOCKS ? 3 * blocks() : dimension;
        }

        std::size_t PathSeedCode::waypoints() const
        {
            return blocks() == 0 ? 0 : ratio.size() / blocks();
        }

        PathSeedCode encodePath(const std::vector<Eigen::VectorXd> &path, SeedVariant variant)
        {
            checkPath(path);
            return variant == SeedVariant::BLOCKS ? encodeBlocks(path) : encodeRotation(path);
        }

        void decodePath(const PathSeedCode &seed, const Eigen::VectorXd &start, const Eigen::VectorXd &goal,
                        std::vector<Eigen::VectorXd> &out)
        {
            if (start.size() != seed.dimension || goal.size() != seed.dimension)
                throw std::invalid_argument("decodePath: start/goal dimension " + std::to_string(start.size()) + "/" +
                                            std::to_string(goal.size()) + ", the seed has " +
                                            std::to_string(seed.dimension));
            const std::size_t M = seed.waypoints();
            out.resize(M + 2);
            out.front() = start;
            out.back() = goal;
            for (std::size_t m = 0; m < M; ++m)
                out[m + 1].resize(seed.dimension);
            if (seed.variant == SeedVariant::BLOCKS)
                decodeBlocks(seed, start, goal, out);
            else
                decodeRotation(seed, start, goal, out);
        }

        std::vector<Eigen::VectorXd> decodePath(const PathSeedCode &seed, const Eigen::VectorXd &start,
                                                const Eigen::VectorXd &goal)
        {
            std::vector<Eigen::VectorXd> out;
            decodePath(seed, start, goal, out);
            return out;
        }
    }  // namespace planners
}  // namespace michi
