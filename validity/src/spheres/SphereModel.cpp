#include <michi/validity/spheres/SphereModel.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <limits>
#include <queue>

namespace michi
{
    namespace validity
    {
        namespace
        {
            /** A small relative and absolute margin added to every radius so rounding never leaves a corner out. */
            double padded(double r)
            {
                return r * (1. + 1e-9) + 1e-9;
            }

            /** The sphere about the corners \e points[idx...]: the centre of their bounding box, moved a few steps
                towards the farthest corner (Badoiu-Clarkson), radius to the farthest corner. */
            LinkSphere coverPoints(const std::vector<Eigen::Vector3d> &points)
            {
                Eigen::Vector3d lo = points.front(), hi = points.front();
                for (const auto &p : points)
                {
                    lo = lo.cwiseMin(p);
                    hi = hi.cwiseMax(p);
                }
                auto farthest = [&](const Eigen::Vector3d &c, double &r)
                {
                    std::size_t best = 0;
                    r = -1.;
                    for (std::size_t i = 0; i < points.size(); ++i)
                    {
                        const double d = (points[i] - c).squaredNorm();
                        if (d > r)
                        {
                            r = d;
                            best = i;
                        }
                    }
                    r = std::sqrt(r);
                    return best;
                };
                LinkSphere bestSphere;
                Eigen::Vector3d c = 0.5 * (lo + hi);
                // Each iteration scans every point: fewer steps for big meshes keep building a link's cover within
                // milliseconds.
                const int iterations = points.size() > 20000 ? 20 : 100;
                double r = 0.;
                farthest(c, r);
                bestSphere.centre = c;
                bestSphere.radius = r;
                for (int i = 1; i <= iterations; ++i)
                {
                    const std::size_t f = farthest(c, r);
                    // Every candidate's radius reaches its farthest point, so every candidate encloses all points:
                    // keeping the smallest is always safe, even though the iteration does not shrink the radius
                    // monotonically.
                    if (r < bestSphere.radius)
                    {
                        bestSphere.centre = c;
                        bestSphere.radius = r;
                    }
                    // Badoiu-Clarkson step: move 1/(i+1) of the way to the farthest point; converges to the minimum
                    // enclosing ball.
                    c += (points[f] - c) / static_cast<double>(i + 1);
                }
                farthest(c, r);
                if (r < bestSphere.radius)
                {
                    bestSphere.centre = c;
                    bestSphere.radius = r;
                }
                bestSphere.radius = padded(bestSphere.radius);
                return bestSphere;
            }

            /** Split triangles (three corners each, flattened) until no edge is longer than \e maxEdge. */
            std::vector<Eigen::Vector3d> splitLong(const std::vector<Eigen::Vector3d> &tris, double maxEdge)
            {
                std::vector<Eigen::Vector3d> out;
                std::vector<std::array<Eigen::Vector3d, 3>> stack;
                for (std::size_t t = 0; t + 2 < tris.size(); t += 3)
                    stack.push_back({tris[t], tris[t + 1], tris[t + 2]});
                while (!stack.empty())
                {
                    const auto tri = stack.back();
                    stack.pop_back();
                    int longest = 0;
                    double length = 0.;
                    for (int e = 0; e < 3; ++e)
                    {
                        const double l = (tri[(e + 1) % 3] - tri[e]).norm();
                        if (l > length)
                        {
                            length = l;
                            longest = e;
                        }
                    }
                    // A long thin triangle would tie far-apart corners into one cluster and force a large sphere. The
                    // cap bounds time and memory; a triangle left whole is still enclosed, only less tightly.
                    if (length <= maxEdge || out.size() > 3000000)
                    {
                        out.insert(out.end(), tri.begin(), tri.end());
                        continue;
                    }
                    const Eigen::Vector3d &a = tri[longest], &b = tri[(longest + 1) % 3], &c = tri[(longest + 2) % 3];
                    // Halving the longest edge keeps the pieces from getting ever thinner.
                    const Eigen::Vector3d m = 0.5 * (a + b);
                    stack.push_back({a, m, c});
                    stack.push_back({m, b, c});
                }
                return out;
            }

            /** Cover triangles with at most \e budget spheres: split the part whose sphere stands out of the link
                most along the longest extent of its triangles' centroids, at the median. \e whole: the link's
                surface before long triangles were split (for the inside test). */
            std::vector<LinkSphere> coverTriangles(const std::vector<Eigen::Vector3d> &tris,
                                                   const std::vector<Eigen::Vector3d> &whole, int budget)
            {
                struct Part
                {
                    std::vector<int> triangles;
                    LinkSphere sphere;
                    double bulge{0.};  ///< how far the sphere may stand out of the link (estimate)
                    bool operator<(const Part &o) const
                    {
                        return bulge < o.bulge;
                    }
                };
                // Points of the whole link's surface (corners and centroids, thinned to a few thousand): the distance
                // from a candidate centre to the nearest of them estimates how deep inside the link it lies.
                std::vector<Eigen::Vector3d> surface;
                {
                    const std::size_t n = tris.size() / 3, stride = std::max<std::size_t>(1, 2 * n / 6000);
                    for (std::size_t t = 0; t < n; t += stride)
                    {
                        surface.push_back(tris[3 * t]);
                        surface.push_back((tris[3 * t] + tris[3 * t + 1] + tris[3 * t + 2]) / 3.);
                    }
                }
                // Inside the link or not, by the winding number of its (unsplit) surface about the point: about 1
                // inside a closed surface, about 0 outside, and robust to small holes and either orientation of
                // the whole mesh (its magnitude is tested).
                auto inside = [&](const Eigen::Vector3d &c)
                {
                    double w = 0.;
                    for (std::size_t t = 0; t + 2 < whole.size(); t += 3)
                    {
                        const Eigen::Vector3d a = whole[t] - c, b = whole[t + 1] - c, d = whole[t + 2] - c;
                        const double la = a.norm(), lb = b.norm(), ld = d.norm();
                        const double num = a.dot(b.cross(d));
                        const double den = la * lb * ld + a.dot(b) * ld + a.dot(d) * lb + b.dot(d) * la;
                        w += 2. * std::atan2(num, den);
                    }
                    return std::abs(w) > 2. * M_PI;  // |winding number| > 1/2
                };
                auto depth = [&](const Eigen::Vector3d &c)
                {
                    double best = std::numeric_limits<double>::infinity();
                    for (const auto &p : surface)
                        best = std::min(best, (p - c).squaredNorm());
                    return std::sqrt(best);
                };
                const int n = static_cast<int>(tris.size() / 3);
                std::vector<Eigen::Vector3d> centroid(n);
                for (int t = 0; t < n; ++t)
                    centroid[t] = (tris[3 * t] + tris[3 * t + 1] + tris[3 * t + 2]) / 3.;
                auto makePart = [&](std::vector<int> ids)
                {
                    Part p;
                    std::vector<Eigen::Vector3d> corners;
                    corners.reserve(3 * ids.size());
                    for (int t : ids)
                        for (int k = 0; k < 3; ++k)
                            corners.push_back(tris[3 * t + k]);
                    std::sort(corners.begin(), corners.end(),
                              [](const Eigen::Vector3d &a, const Eigen::Vector3d &b)
                              {
                                  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
                              });
                    // Neighbouring triangles share corners: deduplicated, coverPoints() scans each point once. A sphere
                    // holding a triangle's three corners holds the whole triangle (a ball is convex), so corners are
                    // all it needs.
                    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
                    p.sphere = coverPoints(corners);
                    // A sphere centred on a flat patch stands out of the surface by its whole radius. Moved inwards
                    // (against the patch's normal), a larger sphere that still holds the patch's corners stands out
                    // by its radius less its depth inside the link, which is much less for a thick link. Any centre
                    // is safe (the radius always reaches every corner); the depth only chooses among them.
                    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
                    double area = 0.;
                    for (int t : ids)
                    {
                        const Eigen::Vector3d n = (tris[3 * t + 1] - tris[3 * t]).cross(tris[3 * t + 2] - tris[3 * t]);
                        normal += n;
                        area += n.norm();
                    }
                    p.bulge = p.sphere.radius - depth(p.sphere.centre);
                    if (area > 0. && normal.norm() > 0.2 * area)
                    {
                        normal.normalize();
                        const Eigen::Vector3d c0 = p.sphere.centre;
                        const double r0 = p.sphere.radius;
                        // candidates better than the surface-centred sphere, best first; the inside test (a pass
                        // over the whole mesh) runs only until one passes
                        std::vector<std::pair<double, LinkSphere>> better;
                        for (double sign : {1., -1.})
                            for (double k : {0.25, 0.5, 1., 1.5, 2., 3., 4.})
                            {
                                const Eigen::Vector3d c = c0 - sign * k * r0 * normal;
                                double r = 0.;
                                for (const auto &q : corners)
                                    r = std::max(r, (q - c).squaredNorm());
                                r = std::sqrt(r);
                                const double bulge = r - depth(c);
                                if (bulge < p.bulge)
                                    better.push_back({bulge, {c, padded(r)}});
                            }
                        std::sort(better.begin(), better.end(),
                                  [](const auto &a, const auto &b)
                                  {
                                      return a.first < b.first;
                                  });
                        for (const auto &candidate : better)
                            if (inside(candidate.second.centre))
                            {
                                p.bulge = candidate.first;
                                p.sphere = candidate.second;
                                break;
                            }
                    }
                    p.triangles = std::move(ids);
                    return p;
                };
                std::vector<int> all(n);
                std::iota(all.begin(), all.end(), 0);
                // Largest sphere on top: each split spends the budget where the cover is loosest.
                std::priority_queue<Part> open;
                std::vector<LinkSphere> done;
                open.push(makePart(std::move(all)));
                while (!open.empty() && static_cast<int>(open.size() + done.size()) < budget)
                {
                    Part p = open.top();
                    open.pop();
                    // A single triangle cannot be split further; its sphere is final.
                    if (p.triangles.size() < 2)
                    {
                        done.push_back(p.sphere);
                        continue;
                    }
                    // the axis whose median cut gives the smaller larger child: a tube is cut across its length
                    // (axis-centred spheres hug it), never along (half-rings need spheres as large as rings)
                    Part bestLeft, bestRight;
                    double bestRadius = std::numeric_limits<double>::infinity();
                    for (int axis = 0; axis < 3; ++axis)
                    {
                        std::vector<int> ids = p.triangles;
                        auto mid = ids.begin() + static_cast<long>(ids.size() / 2);
                        std::nth_element(ids.begin(), mid, ids.end(),
                                         [&](int a, int b)
                                         {
                                             return centroid[a][axis] < centroid[b][axis];
                                         });
                        Part left = makePart(std::vector<int>(ids.begin(), mid));
                        Part right = makePart(std::vector<int>(mid, ids.end()));
                        const double r = std::max(left.bulge, right.bulge);
                        if (r < bestRadius)
                        {
                            bestRadius = r;
                            bestLeft = std::move(left);
                            bestRight = std::move(right);
                        }
                    }
                    open.push(std::move(bestLeft));
                    open.push(std::move(bestRight));
                }
                while (!open.empty())
                {
                    done.push_back(open.top().sphere);
                    open.pop();
                }
                return done;
            }

            /** Spheres holding a whole box (extents \e size, placed at \e pose): the box cut into a grid of
                equal cells (at most \e budget), each cell's circumscribed sphere. */
            std::vector<LinkSphere> coverBox(const Eigen::Vector3d &size, const Eigen::Isometry3d &pose, int budget)
            {
                Eigen::Vector3i cells(1, 1, 1);
                for (;;)
                {
                    // split the axis whose cells are longest while the budget allows it
                    Eigen::Vector3d cell = size.cwiseQuotient(cells.cast<double>());
                    int axis = 0;
                    // Splitting the longest cell side keeps cells near cubes, which have the smallest diagonal (sphere)
                    // for their volume.
                    cell.maxCoeff(&axis);
                    Eigen::Vector3i next = cells;
                    ++next[axis];
                    if (next.prod() > budget)
                        break;
                    cells = next;
                }
                const Eigen::Vector3d cell = size.cwiseQuotient(cells.cast<double>());
                std::vector<LinkSphere> out;
                for (int i = 0; i < cells.x(); ++i)
                    for (int j = 0; j < cells.y(); ++j)
                        for (int k = 0; k < cells.z(); ++k)
                        {
                            const Eigen::Vector3d c =
                                -0.5 * size + cell.cwiseProduct(Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
                            // The circumscribed sphere of a cell: half its diagonal, about its centre.
                            out.push_back({pose * c, padded(0.5 * cell.norm())});
                        }
                return out;
            }

            /** Spheres holding a whole cylinder: slices along the axis, each slice's circumscribed sphere; a flat
                cylinder is covered as the box around it. */
            std::vector<LinkSphere> coverCylinder(double radius, double length, const Eigen::Isometry3d &pose,
                                                  int budget)
            {
                // A flat cylinder: each slice's sphere would be at least as wide as the cylinder, so a grid over its
                // box does better.
                if (length < radius)
                    return coverBox(Eigen::Vector3d(2. * radius, 2. * radius, length), pose, budget);
                const int n = std::max(1, budget);
                const double slice = length / n;
                std::vector<LinkSphere> out;
                for (int i = 0; i < n; ++i)
                {
                    const double z = -0.5 * length + (i + 0.5) * slice;
                    // The sphere through the slice's two rims: radius out, half a slice up and down.
                    out.push_back({pose * Eigen::Vector3d(0., 0., z), padded(std::hypot(radius, 0.5 * slice))});
                }
                return out;
            }

            double linkSize(const std::vector<Eigen::Vector3d> &tris)
            {
                if (tris.empty())
                    return 0.;
                Eigen::Vector3d lo = tris.front(), hi = tris.front();
                for (const auto &p : tris)
                {
                    lo = lo.cwiseMin(p);
                    hi = hi.cwiseMax(p);
                }
                return (hi - lo).norm();
            }

            /** Cover one link: primitives by their own rule, meshes (and what else has triangles) by clusters. */
            std::vector<LinkSphere> coverLink(const RobotLink &link, const SphereModelSettings &settings)
            {
                std::vector<LinkSphere> out;
                const int shapes = static_cast<int>(link.collisions.size());
                if (shapes == 0)
                    return out;
                const int share = std::max(1, settings.spheresPerLink / shapes);
                RobotLink meshPart;
                for (const auto &c : link.collisions)
                {
                    const auto &s = c.shape->size();
                    switch (c.shape->type())
                    {
                        case Shape::Type::SPHERE:
                            out.push_back({c.origin.translation(), padded(s.x())});
                            break;
                        case Shape::Type::BOX:
                            for (const auto &sp : coverBox(s, c.origin, share))
                                out.push_back(sp);
                            break;
                        case Shape::Type::CYLINDER:
                            for (const auto &sp : coverCylinder(s.x(), s.z(), c.origin, share))
                                out.push_back(sp);
                            break;
                        case Shape::Type::CAPSULE:
                            // The cylinder part, plus one sphere of the capsule's radius at each end, which holds that
                            // hemispherical cap.
                            for (const auto &sp : coverCylinder(s.x(), s.z(), c.origin, std::max(1, share - 2)))
                                out.push_back(sp);
                            out.push_back({c.origin * Eigen::Vector3d(0., 0., 0.5 * s.z()), padded(s.x())});
                            out.push_back({c.origin * Eigen::Vector3d(0., 0., -0.5 * s.z()), padded(s.x())});
                            break;
                        default:
                            meshPart.collisions.push_back(c);
                    }
                }
                if (!meshPart.collisions.empty())
                {
                    auto tris = SphereModel::surfaceTriangles(meshPart, settings.circleSides);
                    const int meshBudget =
                        std::max(1, settings.spheresPerLink * static_cast<int>(meshPart.collisions.size()) / shapes);
                    // Edge length relative to the link's size, with a 0.1 mm floor so a tiny link is not split without
                    // end.
                    const auto whole = tris;
                    tris = splitLong(tris, std::max(1e-4, settings.maxTriangleFraction * linkSize(tris)));
                    for (const auto &sp : coverTriangles(tris, whole, meshBudget))
                        out.push_back(sp);
                }
                return out;
            }
        }  // namespace

        std::vector<Eigen::Vector3d> SphereModel::surfaceTriangles(const RobotLink &link, int circleSides)
        {
            std::vector<Eigen::Vector3d> tris;
            auto add = [&](const Eigen::Isometry3d &pose, const Eigen::Vector3d &a, const Eigen::Vector3d &b,
                           const Eigen::Vector3d &c)
            {
                tris.push_back(pose * a);
                tris.push_back(pose * b);
                tris.push_back(pose * c);
            };
            auto prism =
                [&](const Eigen::Isometry3d &pose, const std::vector<Eigen::Vector2d> &outline, double z0, double z1)
            {
                const std::size_t n = outline.size();
                for (std::size_t i = 0; i < n; ++i)
                {
                    const auto &p = outline[i], &q = outline[(i + 1) % n];
                    const Eigen::Vector3d a(p.x(), p.y(), z0), b(q.x(), q.y(), z0), c(q.x(), q.y(), z1),
                        d(p.x(), p.y(), z1);
                    add(pose, a, b, c);
                    add(pose, a, c, d);
                }
                for (const auto &t : triangulatePolygon(outline))
                    for (double z : {z0, z1})
                        add(pose, Eigen::Vector3d(outline[t[0]].x(), outline[t[0]].y(), z),
                            Eigen::Vector3d(outline[t[1]].x(), outline[t[1]].y(), z),
                            Eigen::Vector3d(outline[t[2]].x(), outline[t[2]].y(), z));
            };
            auto circle = [&](double r)
            {
                std::vector<Eigen::Vector2d> outline;
                // Vertices on the circumscribed polygon: its edges touch the circle from outside, so a cover of the
                // polygon holds the round surface too.
                const double grow = 1. / std::cos(M_PI / circleSides);
                for (int i = 0; i < circleSides; ++i)
                {
                    const double a = 2. * M_PI * i / circleSides;
                    outline.emplace_back(r * grow * std::cos(a), r * grow * std::sin(a));
                }
                return outline;
            };
            for (const auto &c : link.collisions)
            {
                const auto &s = c.shape->size();
                switch (c.shape->type())
                {
                    case Shape::Type::BOX:
                    {
                        const Eigen::Vector2d h(0.5 * s.x(), 0.5 * s.y());
                        prism(c.origin, {{-h.x(), -h.y()}, {h.x(), -h.y()}, {h.x(), h.y()}, {-h.x(), h.y()}},
                              -0.5 * s.z(), 0.5 * s.z());
                        break;
                    }
                    case Shape::Type::CYLINDER:
                        prism(c.origin, circle(s.x()), -0.5 * s.z(), 0.5 * s.z());
                        break;
                    case Shape::Type::CAPSULE:
                        // A capsule lies inside the cylinder of its radius that is longer by a radius at each end.
                        prism(c.origin, circle(s.x()), -0.5 * s.z() - s.x(), 0.5 * s.z() + s.x());
                        break;
                    case Shape::Type::PRISM:
                        prism(c.origin, c.shape->outline(), s.x(), s.y());
                        break;
                    case Shape::Type::MESH:
                        for (const auto &t : c.shape->triangles())
                            add(c.origin, c.shape->vertices()[t[0]], c.shape->vertices()[t[1]],
                                c.shape->vertices()[t[2]]);
                        break;
                    // Spheres have no triangles here: the callers cover them with a sphere of their own.
                    case Shape::Type::SPHERE:
                        break;
                }
            }
            return tris;
        }

        std::shared_ptr<const SphereModel> SphereModel::enclose(const RobotModel &model,
                                                                const SphereModelSettings &settings)
        {
            if (settings.spheresPerLink < 1)
                throw std::invalid_argument("spheres per link must be at least 1, got " +
                                            std::to_string(settings.spheresPerLink));
            std::shared_ptr<SphereModel> m(new SphereModel);
            for (const auto &link : model.links())
                m->spheres_.push_back(coverLink(link, settings));
            return m;
        }

        std::shared_ptr<const SphereModel> SphereModel::fromSpherizedUrdf(const RobotModel &model,
                                                                          const std::string &spherizedUrdf,
                                                                          const SphereModelSettings &settings)
        {
            const auto spherized = RobotModel::fromUrdfFile(spherizedUrdf);
            // Links it does not name are covered from their own geometry (safe), but a file that names none of the
            // robot's links is another robot's: most likely the wrong file, said rather than ignored.
            bool shared = false;
            for (const auto &link : model.links())
                for (const auto &l : spherized->links())
                    shared = shared || (l.name == link.name && !link.collisions.empty());
            if (!shared)
                throw UrdfError(spherizedUrdf + ": names none of the links of robot '" + model.name() +
                                "' that have collision geometry (a spherized URDF of another robot?)");
            std::shared_ptr<SphereModel> m(new SphereModel);
            for (const auto &link : model.links())
            {
                int other = -1;
                try
                {
                    other = spherized->linkIndex(link.name);
                }
                catch (const std::out_of_range &)
                {
                }
                std::vector<LinkSphere> seeds;
                if (other >= 0)
                    for (const auto &c : spherized->links()[other].collisions)
                    {
                        if (c.shape->type() != Shape::Type::SPHERE)
                            throw UrdfError(spherizedUrdf + ": link '" + link.name +
                                            "': collision geometry other than a sphere (" + c.shape->describe() +
                                            ") in a spherized URDF");
                        seeds.push_back({c.origin.translation(), c.shape->size().x()});
                    }
                if (seeds.empty())
                {
                    m->spheres_.push_back(coverLink(link, settings));
                    continue;
                }
                // grow the seeds to hold the real geometry: each triangle goes to the seed that grows least
                // The link's own sphere shapes are not in tris (surfaceTriangles skips them), so they join the cover as
                // seeds.
                auto tris = surfaceTriangles(link, settings.circleSides);
                for (const auto &c : link.collisions)
                    if (c.shape->type() == Shape::Type::SPHERE)
                        seeds.push_back({c.origin.translation(), c.shape->size().x()});
                for (std::size_t t = 0; t + 2 < tris.size(); t += 3)
                {
                    std::size_t best = 0;
                    double bestGrowth = std::numeric_limits<double>::infinity(), bestNeed = 0.;
                    for (std::size_t s = 0; s < seeds.size(); ++s)
                    {
                        double need = 0.;
                        for (int k = 0; k < 3; ++k)
                            need = std::max(need, (tris[t + k] - seeds[s].centre).norm());
                        const double growth = need - seeds[s].radius;
                        if (growth < bestGrowth)
                        {
                            bestGrowth = growth;
                            best = s;
                            bestNeed = need;
                        }
                    }
                    // Grown to the triangle's farthest corner, the seed holds the whole triangle (a ball is convex).
                    if (bestGrowth > 0.)
                        seeds[best].radius = bestNeed;
                }
                for (auto &s : seeds)
                    s.radius = padded(s.radius);
                m->spheres_.push_back(seeds);
            }
            return m;
        }

        std::size_t SphereModel::sphereCount() const
        {
            std::size_t n = 0;
            for (const auto &s : spheres_)
                n += s.size();
            return n;
        }
    }  // namespace validity
}  // namespace michi
