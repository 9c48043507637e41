#include "viewer/ReplayShapes.h"
#include "viewer/ReplayJson.h"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace replay
        {
            namespace
            {
                struct Mesh
                {
                    std::vector<Eigen::Vector3d> vertices;
                    std::vector<Eigen::Vector3i> triangles;
                };

                /** The outline extruded over [zMin, zMax]: caps from the ear-clipping triangulation the checker
                    uses for the prism's convex pieces, and one quad per edge. */
                Mesh prismMesh(const validity::Shape &shape)
                {
                    Mesh mesh;
                    const auto &outline = shape.outline();
                    const int n = static_cast<int>(outline.size());
                    const double zMin = shape.size().x(), zMax = shape.size().y();
                    for (const auto &p : outline)
                        mesh.vertices.emplace_back(p.x(), p.y(), zMin);
                    for (const auto &p : outline)
                        mesh.vertices.emplace_back(p.x(), p.y(), zMax);
                    for (const auto &t : validity::triangulatePolygon(outline))
                    {
                        // Bottom cap with the order reversed so that it faces down, the top cap faces up.
                        mesh.triangles.emplace_back(t[0], t[2], t[1]);
                        mesh.triangles.emplace_back(n + t[0], n + t[1], n + t[2]);
                    }
                    for (int i = 0; i < n; ++i)
                    {
                        const int j = (i + 1) % n;
                        mesh.triangles.emplace_back(i, j, n + j);
                        mesh.triangles.emplace_back(i, n + j, n + i);
                    }
                    return mesh;  // the page draws both sides, so the outline's orientation does not matter
                }

                /** Vertex clustering: vertices in one cell of a grid over the mesh's bounds become one (their mean),
                    triangles that collapse are dropped. One pass, with cells sized so that a surface spanning the
                    bounds keeps about MAX_MESH_TRIANGLES: enough to see the shape, and the page stays small. */
                Mesh decimated(const validity::Shape &shape)
                {
                    const auto &vertices = shape.vertices();
                    const auto &triangles = shape.triangles();
                    Mesh mesh{vertices, triangles};
                    if (triangles.size() <= MAX_MESH_TRIANGLES || vertices.empty())
                        return mesh;
                    Eigen::Vector3d lo = vertices.front(), hi = vertices.front();
                    for (const auto &v : vertices)
                    {
                        lo = lo.cwiseMin(v);
                        hi = hi.cwiseMax(v);
                    }
                    // a surface's triangle count grows with the square of the cells per side (two per cell); one cell
                    // less leaves room for the extra cell a vertex on the upper bound falls into
                    const double cellsPerSide =
                        std::floor(std::sqrt(static_cast<double>(MAX_MESH_TRIANGLES) / 2.)) - 1.;
                    const double cell = std::max((hi - lo).maxCoeff() / cellsPerSide, 1e-9);
                    std::unordered_map<long long, int> cells;
                    std::vector<Eigen::Vector3d> sums;
                    std::vector<int> counts, remap(vertices.size());
                    for (std::size_t i = 0; i < vertices.size(); ++i)
                    {
                        const Eigen::Vector3d c = ((vertices[i] - lo) / cell).array().floor();
                        const long long key =
                            // Cell coordinates stay below cellsPerSide + 1 (far less than 4096), so this key is unique
                            // per cell.
                            (static_cast<long long>(c.x()) * 4096 + static_cast<long long>(c.y())) * 4096 +
                            static_cast<long long>(c.z());
                        auto it = cells.find(key);
                        if (it == cells.end())
                        {
                            it = cells.emplace(key, static_cast<int>(sums.size())).first;
                            sums.push_back(Eigen::Vector3d::Zero());
                            counts.push_back(0);
                        }
                        sums[it->second] += vertices[i];
                        ++counts[it->second];
                        remap[i] = it->second;
                    }
                    mesh.vertices.clear();
                    for (std::size_t i = 0; i < sums.size(); ++i)
                        mesh.vertices.push_back(sums[i] / counts[i]);
                    mesh.triangles.clear();
                    for (const auto &t : triangles)
                    {
                        const Eigen::Vector3i r(remap[t[0]], remap[t[1]], remap[t[2]]);
                        // Two corners merged into one cell: the triangle has no area left to draw.
                        if (r[0] != r[1] && r[1] != r[2] && r[0] != r[2])
                            mesh.triangles.push_back(r);
                    }
                    return mesh;
                }

                void appendVector(std::string &out, const Eigen::Vector3d &v)
                {
                    out += '[';
                    for (int i = 0; i < 3; ++i)
                    {
                        if (i)
                            out += ',';
                        appendFixed(out, v[i], POSITION_DECIMALS);
                    }
                    out += ']';
                }

                void appendMesh(std::string &out, const Mesh &mesh)
                {
                    out += "{\"type\":\"mesh\",\"vertices\":[";
                    bool first = true;
                    for (const auto &v : mesh.vertices)
                        for (int i = 0; i < 3; ++i)
                        {
                            if (!first)
                                out += ',';
                            first = false;
                            appendFixed(out, v[i], POSITION_DECIMALS);
                        }
                    out += "],\"triangles\":[";
                    first = true;
                    for (const auto &t : mesh.triangles)
                        for (int i = 0; i < 3; ++i)
                        {
                            if (!first)
                                out += ',';
                            first = false;
                            out += std::to_string(t[i]);
                        }
                    out += "]}";
                }

                void appendShape(std::string &out, const validity::Shape &shape)
                {
                    using Type = validity::Shape::Type;
                    const Eigen::Vector3d &size = shape.size();
                    switch (shape.type())
                    {
                        case Type::BOX:
                            out += "{\"type\":\"box\",\"size\":";
                            appendVector(out, size);
                            out += '}';
                            return;
                        case Type::SPHERE:
                            out += "{\"type\":\"sphere\",\"radius\":";
                            appendFixed(out, size.x(), POSITION_DECIMALS);
                            out += '}';
                            return;
                        case Type::CYLINDER:
                        case Type::CAPSULE:
                            out += shape.type() == Type::CYLINDER ? "{\"type\":\"cylinder\",\"radius\":"
                                                                  : "{\"type\":\"capsule\",\"radius\":";
                            appendFixed(out, size.x(), POSITION_DECIMALS);
                            out += ",\"length\":";
                            appendFixed(out, size.z(), POSITION_DECIMALS);
                            out += '}';
                            return;
                        case Type::PRISM:
                            appendMesh(out, prismMesh(shape));
                            return;
                        case Type::MESH:
                            appendMesh(out, decimated(shape));
                            return;
                    }
                }
            }  // namespace

            int ShapeTable::index(const validity::ShapePtr &shape)
            {
                // A link's shapes are drawn once per path, and obstacles may share a shape: each shape goes into the
                // page once, and everything that uses it refers to its index.
                const auto it = indices_.find(shape.get());
                if (it != indices_.end())
                    return it->second;
                if (count_)
                    json_ += ',';
                appendShape(json_, *shape);
                indices_.emplace(shape.get(), count_);
                // Kept alive so the address used as a key cannot be reused by another shape while the table lives.
                kept_.push_back(shape);
                return count_++;
            }

            std::string ShapeTable::json() const
            {
                return "[" + json_ + "]";
            }
        }  // namespace replay
    }      // namespace tools
}  // namespace michi
