#include <michi/validity/grid/BandTable.h>

#include <boost/math/constants/constants.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

namespace michi
{
    namespace validity
    {
        namespace
        {
            const double TWO_PI = boost::math::constants::two_pi<double>();

            /** Does the convex counter-clockwise polygon \e v meet the closed box [x0, x1] x [y0, y1]? (Separating
                axes: the box's two and the polygon's edge normals; touching meets.) */
            bool meetsBox(const std::vector<Eigen::Vector2d> &v, double x0, double x1, double y0, double y1)
            {
                if (x0 > x1 || y0 > y1)
                    return false;
                double xmin = v[0].x(), xmax = xmin, ymin = v[0].y(), ymax = ymin;
                for (const auto &p : v)
                {
                    xmin = std::min(xmin, p.x());
                    xmax = std::max(xmax, p.x());
                    ymin = std::min(ymin, p.y());
                    ymax = std::max(ymax, p.y());
                }
                if (xmax < x0 || xmin > x1 || ymax < y0 || ymin > y1)
                    return false;
                for (std::size_t e = 0; e < v.size(); ++e)
                {
                    const Eigen::Vector2d &a = v[e], &b = v[(e + 1) % v.size()];
                    const double nx = b.y() - a.y(), ny = a.x() - b.x();  // outward normal (counter-clockwise)
                    // the box's corner farthest inside this edge
                    const double m = nx * (nx > 0. ? x0 : x1) + ny * (ny > 0. ? y0 : y1) - (nx * a.x() + ny * a.y());
                    if (m > 0.)
                        return false;
                }
                return true;
            }
        }  // namespace

        void BandTable::layout(double resolution, double circumradius, int headings, int &positions, int &subHeadings)
        {
            const double sweep = circumradius * TWO_PI / headings;
            double best = std::numeric_limits<double>::infinity();
            for (int p : {1, 2, 4, 8})
            {
                const int s = 64 / (p * p);
                const double reach = resolution / p + sweep / s;
                if (reach < best)
                {
                    best = reach;
                    positions = p;
                    subHeadings = s;
                }
            }
        }

        BandTable::BandTable(const std::vector<std::vector<Eigen::Vector2d>> &pieces, double resolution, int headings,
                             double tolerance)
        {
            if (pieces.empty() || !(resolution > 0.) || headings < 1)
                throw std::invalid_argument("BandTable: needs footprint pieces, a positive resolution and headings");
            // counter-clockwise pieces
            std::vector<std::vector<Eigen::Vector2d>> ccw = pieces;
            double radius = 0.;
            for (auto &piece : ccw)
            {
                double area = 0.;
                for (std::size_t e = 0; e < piece.size(); ++e)
                {
                    const Eigen::Vector2d &a = piece[e], &b = piece[(e + 1) % piece.size()];
                    area += a.x() * b.y() - a.y() * b.x();
                    radius = std::max(radius, a.norm());
                }
                if (area < 0.)
                    std::reverse(piece.begin(), piece.end());
            }
            layout(resolution, radius, headings, positions_, subHeadings_);
            const int P = positions_, S = subHeadings_;
            const double r = resolution, step = TWO_PI / headings, sub = step / S, q = r / P;
            // yaw samples per sub-bin: a footprint point moves at most 0.05 cells between one and the next
            const int samples = std::max(1, static_cast<int>(std::ceil(sub * radius / (0.05 * r))));
            const double eps = 1e-9 * (r + radius);
            // how far a point moves from the nearest sample (plus rounding of the yaw to its bin)
            const double g = radius * (sub / samples) / 2. + 1e-9 * radius + eps;
            const double grow = g + tolerance + eps;  // "may": every obstacle within the cell grown by tolerance
            const int n = static_cast<int>(std::ceil((radius + grow) / r)) + 3;
            offsets_.resize(headings);
            std::vector<std::vector<Eigen::Vector2d>> turned(ccw.size());
            for (int k = 0; k < headings; ++k)
            {
                Offsets &o = offsets_[k];
                const int side = 2 * n + 1;
                std::vector<std::uint64_t> may(static_cast<std::size_t>(side) * side, 0),
                    blocks(static_cast<std::size_t>(side) * side, 0);
                for (int h = 0; h < S; ++h)
                    for (int t = 0; t < samples; ++t)
                    {
                        const double yaw = k * step - step / 2. + h * sub + (t + 0.5) * sub / samples;
                        const Eigen::Rotation2Dd rot(yaw);
                        for (std::size_t p = 0; p < ccw.size(); ++p)
                        {
                            turned[p].resize(ccw[p].size());
                            for (std::size_t v = 0; v < ccw[p].size(); ++v)
                                turned[p][v] = rot * ccw[p][v];
                        }
                        for (int dy = -n; dy <= n; ++dy)
                            for (int dx = -n; dx <= n; ++dx)
                            {
                                const std::size_t c = static_cast<std::size_t>(dy + n) * side + (dx + n);
                                // the cell in the entry's frame (entry cell [0, r]^2)
                                const double cx0 = dx * r, cx1 = (dx + 1) * r, cy0 = dy * r, cy1 = (dy + 1) * r;
                                // a pose of the cell is within r sqrt(2) of the cell's corner (0, 0)
                                if (std::hypot(std::max({0., cx0, -cx1}), std::max({0., cy0, -cy1})) >
                                    radius + 2. * r + grow)
                                    continue;  // beyond the footprint's reach from any pose of the cell
                                for (int py = 0; py < P; ++py)
                                    for (int px = 0; px < P; ++px)
                                    {
                                        const int s = (h * P + py) * P + px;
                                        const std::uint64_t bit = std::uint64_t{1} << s;
                                        const double ux0 = px * q, ux1 = (px + 1) * q, uy0 = py * q, uy1 = (py + 1) * q;
                                        if (!(may[c] & bit))
                                            for (const auto &piece : turned)
                                                if (meetsBox(piece, cx0 - ux1 - grow, cx1 - ux0 + grow,
                                                             cy0 - uy1 - grow, cy1 - uy0 + grow))
                                                {
                                                    may[c] |= bit;
                                                    break;
                                                }
                                        // blocks: at this sample, from every corner of the sub-square, a piece
                                        // meets the cell shrunk by g (a sample that fails clears the bit)
                                        if (t > 0 && !(blocks[c] & bit))
                                            continue;
                                        bool all = false;
                                        for (const auto &piece : turned)
                                        {
                                            bool corners = true;
                                            for (int corner = 0; corner < 4 && corners; ++corner)
                                            {
                                                const double ux = (corner & 1) ? ux1 : ux0,
                                                             uy = (corner & 2) ? uy1 : uy0;
                                                corners = meetsBox(piece, cx0 - ux + g, cx1 - ux - g, cy0 - uy + g,
                                                                   cy1 - uy - g);
                                            }
                                            if (corners)
                                            {
                                                all = true;
                                                break;
                                            }
                                        }
                                        blocks[c] = all ? (blocks[c] | bit) : (blocks[c] & ~bit);
                                    }
                            }
                    }
                // keep the box of offsets with any bit
                o.dx0 = o.dy0 = n + 1;
                o.dx1 = o.dy1 = -n - 1;
                for (int dy = -n; dy <= n; ++dy)
                    for (int dx = -n; dx <= n; ++dx)
                        if (may[static_cast<std::size_t>(dy + n) * side + (dx + n)])
                        {
                            o.dx0 = std::min(o.dx0, dx);
                            o.dx1 = std::max(o.dx1, dx);
                            o.dy0 = std::min(o.dy0, dy);
                            o.dy1 = std::max(o.dy1, dy);
                        }
                if (o.dx0 > o.dx1)
                    continue;
                if (o.dx0 == -n || o.dy0 == -n || o.dx1 == n || o.dy1 == n)
                    throw std::logic_error("BandTable: offsets reach the edge of their box");
                const int w = o.dx1 - o.dx0 + 1;
                o.may.assign(static_cast<std::size_t>(w) * (o.dy1 - o.dy0 + 1), 0);
                o.blocks.assign(o.may.size(), 0);
                reach_[0] = std::min(reach_[0], o.dx0);
                reach_[1] = std::max(reach_[1], o.dx1);
                reach_[2] = std::min(reach_[2], o.dy0);
                reach_[3] = std::max(reach_[3], o.dy1);
                for (int dy = o.dy0; dy <= o.dy1; ++dy)
                    for (int dx = o.dx0; dx <= o.dx1; ++dx)
                    {
                        const std::size_t c = static_cast<std::size_t>(dy + n) * side + (dx + n);
                        const std::size_t d = static_cast<std::size_t>(dy - o.dy0) * w + (dx - o.dx0);
                        o.may[d] = may[c];
                        o.blocks[d] = blocks[c] & may[c];
                    }
            }
        }

        void BandTable::assign(const std::vector<std::uint32_t> &prefix, const std::vector<Entry> &entries)
        {
            struct Hash
            {
                std::size_t operator()(const std::pair<std::uint64_t, std::uint64_t> &e) const
                {
                    return std::hash<std::uint64_t>()(e.first * 0x9E3779B97F4A7C15ull ^ e.second);
                }
            };
            std::unordered_map<std::pair<std::uint64_t, std::uint64_t>, std::uint16_t, Hash> seen;
            patterns_.assign(1, Entry{});
            seen.emplace(std::make_pair(std::uint64_t{0}, std::uint64_t{0}), 0);
            index_.resize(entries.size());
            for (std::size_t n = 0; n < entries.size(); ++n)
            {
                const auto key = std::make_pair(entries[n].valid, entries[n].blocked);
                auto it = seen.find(key);
                if (it == seen.end())
                {
                    if (patterns_.size() > 0xFFFF)
                    {
                        index_[n] = 0;  // no room: undecided, the exact test answers
                        continue;
                    }
                    it = seen.emplace(key, static_cast<std::uint16_t>(patterns_.size())).first;
                    patterns_.push_back(entries[n]);
                }
                index_[n] = it->second;
            }
            patterns_.shrink_to_fit();
            records_.assign(prefix.size(), Record{});
            for (std::size_t w = 0; w < prefix.size(); ++w)
            {
                Record &r = records_[w];
                r.rank = prefix[w];
                const std::size_t count = w + 1 < prefix.size() ? prefix[w + 1] - prefix[w] : 0;
                for (unsigned n = 0; n < INLINE && n < count; ++n)
                    r.first[n] = index_[r.rank + n];
            }
        }

        BandTable::Entry BandTable::compute(int i, int j, int k, const std::uint64_t *occupied, std::size_t wordsPerRow,
                                            int width, int height) const
        {
            const Offsets &o = offsets_[static_cast<std::size_t>(k)];
            std::uint64_t may = 0, blocks = 0;
            const int w = o.dx1 - o.dx0 + 1;
            for (int dy = o.dy0; dy <= o.dy1; ++dy)
            {
                const int jj = j + dy;
                const std::uint64_t *m = o.may.data() + static_cast<std::size_t>(dy - o.dy0) * w;
                const std::uint64_t *b = o.blocks.data() + static_cast<std::size_t>(dy - o.dy0) * w;
                const int a0 = i + o.dx0, a1 = i + o.dx1;  // columns of this row's offsets
                if (jj < 0 || jj >= height)
                {
                    for (int t = 0; t < w; ++t)
                        may |= m[t];  // outside the grid: occupied for "may" (not for "blocks")
                    continue;
                }
                const std::uint64_t *row = occupied + static_cast<std::size_t>(jj) * wordsPerRow;
                for (int c = a0; c <= a1;)
                {
                    if (c < 0 || c >= width)
                    {
                        may |= m[c - a0];
                        ++c;
                        continue;
                    }
                    // the occupied cells of this word within [c, a1]
                    const int wordEnd = std::min(a1, std::min(width - 1, (c | 63)));
                    std::uint64_t bits = row[c >> 6] >> (c & 63);
                    const int span = wordEnd - c + 1;
                    if (span < 64)
                        bits &= (std::uint64_t{1} << span) - 1;
                    while (bits)
                    {
                        const int t = __builtin_ctzll(bits);
                        bits &= bits - 1;
                        may |= m[c + t - a0];
                        blocks |= b[c + t - a0];
                    }
                    c = wordEnd + 1;
                }
            }
            return Entry{~may, blocks};
        }
    }  // namespace validity
}  // namespace michi
