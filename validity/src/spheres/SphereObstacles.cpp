#include "SphereObstacles.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace michi
{
    namespace validity
    {
        namespace
        {
            using ArrayC = Eigen::Map<const Eigen::ArrayXf>;
            /** At most 256 values on the stack: no allocation per query. */
            using Arr = Eigen::Array<float, Eigen::Dynamic, 1, 0, 256, 1>;

            /** Closest point of triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5). */
            Eigen::Vector3f closestOnTriangle(const Eigen::Vector3f &p, const Eigen::Vector3f &a,
                                              const Eigen::Vector3f &b, const Eigen::Vector3f &c)
            {
                const Eigen::Vector3f ab = b - a, ac = c - a, ap = p - a;
                const float d1 = ab.dot(ap), d2 = ac.dot(ap);
                if (d1 <= 0.f && d2 <= 0.f)
                    return a;
                const Eigen::Vector3f bp = p - b;
                const float d3 = ab.dot(bp), d4 = ac.dot(bp);
                if (d3 >= 0.f && d4 <= d3)
                    return b;
                const float vc = d1 * d4 - d3 * d2;
                if (vc <= 0.f && d1 >= 0.f && d3 <= 0.f)
                    return a + d1 / (d1 - d3) * ab;
                const Eigen::Vector3f cp = p - c;
                const float d5 = ab.dot(cp), d6 = ac.dot(cp);
                if (d6 >= 0.f && d5 <= d6)
                    return c;
                const float vb = d5 * d2 - d1 * d6;
                if (vb <= 0.f && d2 >= 0.f && d6 <= 0.f)
                    return a + d2 / (d2 - d6) * ac;
                const float va = d3 * d6 - d5 * d4;
                if (va <= 0.f && (d4 - d3) >= 0.f && (d5 - d6) >= 0.f)
                    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
                const float denom = 1.f / (va + vb + vc);
                return a + ab * (vb * denom) + ac * (vc * denom);
            }

            /** Distance from p to a simple polygon in its plane: 0 inside, else to the nearest edge. */
            float polygonDistance(const std::vector<Eigen::Vector2f> &poly, const Eigen::Vector2f &p)
            {
                bool inside = false;
                float best = std::numeric_limits<float>::infinity();
                const std::size_t n = poly.size();
                for (std::size_t i = 0, j = n - 1; i < n; j = i++)
                {
                    const Eigen::Vector2f &a = poly[j], &b = poly[i];
                    if ((b.y() > p.y()) != (a.y() > p.y()) &&
                        p.x() < (a.x() - b.x()) * (p.y() - b.y()) / (a.y() - b.y()) + b.x())
                        // Even-odd crossing count along +x; the edge distances are gathered in the same pass.
                        inside = !inside;
                    const Eigen::Vector2f ab = b - a;
                    // The floor keeps a repeated vertex (a zero-length edge) from dividing by zero.
                    const float t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-30f), 0.f, 1.f);
                    best = std::min(best, (a + t * ab - p).squaredNorm());
                }
                return inside ? 0.f : std::sqrt(best);
            }
        }  // namespace

        SphereObstacles::SphereObstacles(const Scene &scene)
        {
            version_ = scene.changeCount();
            static std::atomic<std::uint64_t> serials{0};
            serial_ = ++serials;
            for (const auto &o : scene.obstacles())
            {
                const auto &shape = *o.shape;
                const Eigen::Isometry3d pose = o.pose;
                Frame f;
                // The inverse rotation: the kernels map a world point into the obstacle's frame as rt * (p - t).
                f.rt = pose.linear().transpose().cast<float>();
                f.t = pose.translation().cast<float>();
                const Eigen::Vector3d &s = shape.size();
                Eigen::Vector3f size = Eigen::Vector3f::Zero();
                Eigen::Vector3d centre = pose.translation();
                double bound = shape.boundingRadius();
                int kind = BOX, index = -1;
                switch (shape.type())
                {
                    case Shape::Type::BOX:
                        kind = BOX;
                        // Half extents: the box kernel measures how far a point sticks out past each face.
                        size = (0.5 * s).cast<float>();
                        break;
                    case Shape::Type::SPHERE:
                        kind = SPHERE;
                        size = Eigen::Vector3f(static_cast<float>(s.x()), 0.f, 0.f);
                        break;
                    case Shape::Type::CYLINDER:
                        kind = CYLINDER;
                        size = Eigen::Vector3f(static_cast<float>(s.x()), static_cast<float>(0.5 * s.z()), 0.f);
                        break;
                    case Shape::Type::CAPSULE:
                        kind = CAPSULE;
                        size = Eigen::Vector3f(static_cast<float>(s.x()), static_cast<float>(0.5 * s.z()), 0.f);
                        break;
                    case Shape::Type::PRISM:
                    {
                        kind = PRISM;
                        Prism p;
                        for (const auto &v : shape.outline())
                            p.outline.push_back(v.cast<float>());
                        p.zMin = static_cast<float>(s.x());
                        p.zMax = static_cast<float>(s.y());
                        index = static_cast<int>(prisms_.size());
                        prisms_.push_back(std::move(p));
                        break;
                    }
                    case Shape::Type::MESH:
                    {
                        kind = MESH;
                        index = static_cast<int>(meshes_.size());
                        addMesh(o);
                        // The root node's sphere is about the vertices themselves, tighter than the shape's radius
                        // about its origin.
                        centre = meshes_.back().nodes.front().centre.cast<double>();
                        bound = meshes_.back().nodes.front().radius;
                        break;
                    }
                }
                names_.push_back(o.name);
                kind_.push_back(kind);
                index_.push_back(index);
                frames_.push_back(f);
                size_.push_back(size);
                bx_.push_back(static_cast<float>(centre.x()));
                by_.push_back(static_cast<float>(centre.y()));
                bz_.push_back(static_cast<float>(centre.z()));
                // Grown a little so that the float sphere still encloses the shape after rounding: candidates() must
                // never drop an obstacle a robot sphere touches.
                br_.push_back(static_cast<float>(bound * (1. + 1e-6) + 1e-5));
            }
            // Padding of the broad phase to whole blocks: far away (squares stay finite in float) and of radius 0.
            while (bx_.size() % BLOCK != 0)
            {
                bx_.push_back(1e15f);
                by_.push_back(1e15f);
                bz_.push_back(1e15f);
                br_.push_back(0.f);
            }
        }

        void SphereObstacles::addMesh(const Obstacle &obstacle)
        {
            Mesh mesh;
            const auto &shape = *obstacle.shape;
            const int n = static_cast<int>(shape.triangles().size());
            std::vector<Eigen::Vector3f> corners;
            std::vector<Eigen::Vector3f> centroid(n);
            for (int t = 0; t < n; ++t)
            {
                Eigen::Vector3f c = Eigen::Vector3f::Zero();
                for (int k = 0; k < 3; ++k)
                {
                    // Corners are stored in the world frame: a mesh query then needs no transform per sphere (frames_
                    // is unused for meshes).
                    const Eigen::Vector3f v = (obstacle.pose * shape.vertices()[shape.triangles()[t][k]]).cast<float>();
                    corners.push_back(v);
                    c += v / 3.f;
                }
                centroid[t] = c;
            }
            std::vector<int> order(n);
            std::iota(order.begin(), order.end(), 0);
            // nodes: bounding sphere of the triangles' corners, split at the median of the longest extent
            struct Task
            {
                int node, first, count;
            };
            mesh.nodes.push_back({});
            std::vector<Task> tasks{{0, 0, n}};
            while (!tasks.empty())
            {
                const Task task = tasks.back();
                tasks.pop_back();
                Eigen::Vector3f lo = corners[3 * order[task.first]], hi = lo;
                for (int i = task.first; i < task.first + task.count; ++i)
                    for (int k = 0; k < 3; ++k)
                    {
                        lo = lo.cwiseMin(corners[3 * order[i] + k]);
                        hi = hi.cwiseMax(corners[3 * order[i] + k]);
                    }
                const Eigen::Vector3f c = 0.5f * (lo + hi);
                float r = 0.f;
                for (int i = task.first; i < task.first + task.count; ++i)
                    for (int k = 0; k < 3; ++k)
                        r = std::max(r, (corners[3 * order[i] + k] - c).norm());
                // Grown for float round-off, as br_ above: a node must enclose its triangles or the walk would prune a
                // contact.
                MeshNode node{c, r * (1.f + 1e-5f) + 1e-6f, -1, -1, task.first, task.count};
                // Leaves of at most 4 triangles; a median split keeps the tree balanced, so its depth is about log2(n /
                // 4) and the 64-entry stack of meshDistance() cannot overflow on any mesh that fits in memory.
                if (task.count > 4)
                {
                    int axis = 0;
                    (hi - lo).maxCoeff(&axis);
                    const auto first = order.begin() + task.first;
                    const auto mid = first + task.count / 2;
                    std::nth_element(first, mid, first + task.count,
                                     [&](int a, int b)
                                     {
                                         return centroid[a][axis] < centroid[b][axis];
                                     });
                    node.left = static_cast<int>(mesh.nodes.size());
                    node.right = node.left + 1;
                    mesh.nodes.push_back({});
                    mesh.nodes.push_back({});
                    tasks.push_back({node.left, task.first, task.count / 2});
                    tasks.push_back({node.right, task.first + task.count / 2, task.count - task.count / 2});
                }
                mesh.nodes[task.node] = node;
            }
            mesh.corners.reserve(corners.size());
            for (int t : order)
                for (int k = 0; k < 3; ++k)
                    mesh.corners.push_back(corners[3 * t + k]);
            meshes_.push_back(std::move(mesh));
        }

        int SphereObstacles::candidates(const Eigen::Vector3f &c, float r, int *out) const
        {
            // Blocks of BLOCK obstacles (the arrays are padded to whole blocks with spheres that meet nothing): the
            // overlap tests of a block have a fixed count and no branch, so they compile to whole SIMD lanes; the
            // indices are collected after, without a branch per obstacle.
            using Block = Eigen::Array<float, BLOCK, 1>;
            using BlockMap = Eigen::Map<const Block>;
            int count = 0;
            for (std::size_t first = 0; first < bx_.size(); first += BLOCK)
            {
                const Block dx = BlockMap(bx_.data() + first) - c.x(), dy = BlockMap(by_.data() + first) - c.y(),
                            dz = BlockMap(bz_.data() + first) - c.z(), rr = BlockMap(br_.data() + first) + r;
                // Two spheres overlap when their centres are closer than the sum of the radii; no square root.
                const Block gap = dx * dx + dy * dy + dz * dz - rr * rr;
                if ((gap >= 0.f).all())
                    continue;  // the usual case: nothing near in this block
                for (std::size_t o = 0; o < BLOCK; ++o)
                {
                    out[count] = static_cast<int>(first + o);
                    count += gap[static_cast<Eigen::Index>(o)] < 0.f;
                }
            }
            return count;
        }

        bool SphereObstacles::hitsSphere(int o, const Eigen::Vector3f &c, float r) const
        {
            // One sphere (a body's bound): the kernel of squaredDistances() on fixed one-element arrays, which cost
            // no more than scalar code (the batch's dynamic arrays cost more than the arithmetic for one sphere).
            // A mesh goes through hits(), whose tree walk stops at the radius.
            if (kind_[o] == MESH)
            {
                const float one[4] = {c.x(), c.y(), c.z(), r};
                return hits(o, SphereBatch{one, one + 1, one + 2, one + 3, 1});
            }
            using One = Eigen::Array<float, 1, 1>;
            const One x = One::Constant(c.x()), y = One::Constant(c.y()), z = One::Constant(c.z());
            One d2;
            squaredDistancesOf<One>(o, x, y, z, d2);
            return d2(0) < r * r;
        }

        float SphereObstacles::boundDistance(int o, const Eigen::Vector3f &c, float r) const
        {
            return (Eigen::Vector3f(bx_[o], by_[o], bz_[o]) - c).norm() - br_[o] - r;
        }

        void SphereObstacles::squaredDistances(int o, const SphereBatch &b, float *out) const
        {
            const ArrayC x(b.x, b.n), y(b.y, b.n), z(b.z, b.n);
            Eigen::Map<Eigen::ArrayXf> d2(out, b.n);
            squaredDistancesOf<Arr>(o, x, y, z, d2);
        }

        template <typename A, typename In, typename Out>
        void SphereObstacles::squaredDistancesOf(int o, const In &x, const In &y, const In &z, Out &d2) const
        {
            const int n = static_cast<int>(x.size());
            const Frame &f = frames_[o];
            const Eigen::Vector3f &s = size_[o];
            const A dx = x - f.t.x(), dy = y - f.t.y(), dz = z - f.t.z();
            switch (kind_[o])
            {
                case SPHERE:
                    d2 = (dx.square() + dy.square() + dz.square()).sqrt() - s.x();
                    // Clamped at 0 before squaring: a centre inside the obstacle has a negative distance, whose square
                    // would look far.
                    d2 = d2.max(0.f).square();
                    break;
                case BOX:
                {
                    const auto &m = f.rt;
                    const A qx = ((m(0, 0) * dx + m(0, 1) * dy + m(0, 2) * dz).abs() - s.x()).max(0.f);
                    const A qy = ((m(1, 0) * dx + m(1, 1) * dy + m(1, 2) * dz).abs() - s.y()).max(0.f);
                    const A qz = ((m(2, 0) * dx + m(2, 1) * dy + m(2, 2) * dz).abs() - s.z()).max(0.f);
                    // Distance to a box = length of how far the point lies outside each pair of faces (0 inside).
                    d2 = qx.square() + qy.square() + qz.square();
                    break;
                }
                case CYLINDER:
                case CAPSULE:
                {
                    const auto &m = f.rt;
                    const A px = m(0, 0) * dx + m(0, 1) * dy + m(0, 2) * dz;
                    const A py = m(1, 0) * dx + m(1, 1) * dy + m(1, 2) * dz;
                    const A pz = m(2, 0) * dx + m(2, 1) * dy + m(2, 2) * dz;
                    const A radial = (px.square() + py.square()).sqrt();
                    const A qz = (pz.abs() - s.y()).max(0.f);
                    if (kind_[o] == CYLINDER)
                        // Cylinder: outside the radius and outside the caps are independent, so the two excesses add in
                        // squares.
                        d2 = (radial - s.x()).max(0.f).square() + qz.square();
                    else
                        // Capsule: distance to its axis segment (radial and past-the-end parts) minus the radius.
                        d2 = ((radial.square() + qz.square()).sqrt() - s.x()).max(0.f).square();
                    break;
                }
                case PRISM:
                {
                    const Prism &p = prisms_[index_[o]];
                    const auto &m = f.rt;
                    for (int i = 0; i < n; ++i)
                    {
                        const Eigen::Vector3f local = m * Eigen::Vector3f(dx[i], dy[i], dz[i]);
                        const float planar = polygonDistance(p.outline, local.head<2>());
                        const float qz = std::max({p.zMin - local.z(), local.z() - p.zMax, 0.f});
                        d2[i] = planar * planar + qz * qz;
                    }
                    break;
                }
                case MESH:
                {
                    const Mesh &mesh = meshes_[index_[o]];
                    for (int i = 0; i < n; ++i)
                    {
                        const float d = meshDistance(mesh, Eigen::Vector3f(x[i], y[i], z[i]),
                                                     std::numeric_limits<float>::infinity());
                        d2[i] = d * d;
                    }
                    break;
                }
            }
        }

        float SphereObstacles::meshDistance(const Mesh &mesh, const Eigen::Vector3f &p, float limit) const
        {
            // best-first would be tighter; depth-first with pruning by the best so far is enough here
            float best = limit;
            int stack[64];
            int top = 0;
            stack[top++] = 0;
            while (top > 0)
            {
                const MeshNode &node = mesh.nodes[stack[--top]];
                // Nothing in this node's sphere can beat the best distance so far (or the caller's limit).
                if ((node.centre - p).norm() - node.radius >= best)
                    continue;
                if (node.left < 0)
                {
                    for (int t = node.first; t < node.first + node.count; ++t)
                    {
                        const Eigen::Vector3f q =
                            closestOnTriangle(p, mesh.corners[3 * t], mesh.corners[3 * t + 1], mesh.corners[3 * t + 2]);
                        best = std::min(best, (q - p).norm());
                    }
                    continue;
                }
                if (top + 2 > 64)
                    return 0.f;  // cannot happen for a balanced tree; answer "touching" rather than miss
                const float dl = (mesh.nodes[node.left].centre - p).squaredNorm();
                const float dr = (mesh.nodes[node.right].centre - p).squaredNorm();
                // the nearer child is visited first
                // The farther child is pushed first so the nearer one is popped first: best shrinks sooner and prunes
                // more.
                stack[top++] = dl < dr ? node.right : node.left;
                stack[top++] = dl < dr ? node.left : node.right;
            }
            return best;
        }

        bool SphereObstacles::hits(int o, const SphereBatch &b) const
        {
            if (kind_[o] == MESH)
            {
                const Mesh &mesh = meshes_[index_[o]];
                const DistanceGrid *grid = grid_.load(std::memory_order_acquire);
                const MeshField *field =
                    grid != nullptr ? &grid->meshFields[static_cast<std::size_t>(index_[o])] : nullptr;
                for (int i = 0; i < b.n; ++i)
                {
                    const Eigen::Vector3f p(b.x[i], b.y[i], b.z[i]);
                    const int known = field != nullptr ? field->decide(p, b.r[i]) : 0;
                    if (known != 0)
                    {
                        if (known > 0)
                            return true;
                        continue;
                    }
                    // The radius as the limit: the walk only has to find something nearer than the sphere's surface.
                    if (meshDistance(mesh, p, b.r[i]) < b.r[i])
                        return true;
                }
                return false;
            }
            // Batches of 256: the kernels' arrays live on the stack with at most 256 entries (Arr above).
            float d2[256];
            for (int first = 0; first < b.n; first += 256)
            {
                const int n = std::min(256, b.n - first);
                const SphereBatch part{b.x + first, b.y + first, b.z + first, b.r + first, n};
                squaredDistances(o, part, d2);
                const ArrayC r(part.r, n);
                if ((Eigen::Map<const Eigen::ArrayXf>(d2, n) < r.square()).any())
                    return true;
            }
            return false;
        }

        float SphereObstacles::distance(int o, const SphereBatch &b) const
        {
            float d2[256];
            float best = std::numeric_limits<float>::infinity();
            for (int first = 0; first < b.n; first += 256)
            {
                const int n = std::min(256, b.n - first);
                const SphereBatch part{b.x + first, b.y + first, b.z + first, b.r + first, n};
                squaredDistances(o, part, d2);
                best = std::min(best, (Eigen::Map<const Eigen::ArrayXf>(d2, n).sqrt() - ArrayC(part.r, n)).minCoeff());
            }
            return best;
        }
    }  // namespace validity
}  // namespace michi
