#include "support/TestScenes.h"

#include <michi/state_spaces/JointStateSpace.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace fs = std::filesystem;

namespace michi
{
    namespace test
    {
        std::string sourcePath(const std::string &relative)
        {
            return (fs::path(MICHI_SOURCE_DIR) / relative).string();
        }

        std::string planarArmUrdf(const std::vector<double> &linkLengths, const PlanarArmOptions &options)
        {
            if (linkLengths.empty())
                throw std::invalid_argument("a planar arm needs at least one link");
            std::ostringstream out;
            out << std::setprecision(17);
            out << "<?xml version=\"1.0\"?>\n<robot name=\"" << options.name << "\">\n";
            out << "  <link name=\"base_link\"/>\n";
            for (std::size_t i = 0; i < linkLengths.size(); ++i)
            {
                const double length = linkLengths[i];
                out << "  <link name=\"link" << i + 1 << "\">\n"
                    << "    <collision>\n";
                if (options.linkShape == PlanarArmOptions::LinkShape::BOX)
                    out << "      <origin xyz=\"" << 0.5 * length << " 0 0\" rpy=\"0 0 0\"/>\n"
                        << "      <geometry><box size=\"" << length << " " << 2. * options.linkRadius << " "
                        << 2. * options.linkRadius << "\"/></geometry>\n";
                else
                    out << "      <origin xyz=\"" << 0.5 * length << " 0 0\" rpy=\"0 " << M_PI / 2 << " 0\"/>\n"
                        << "      <geometry><cylinder radius=\"" << options.linkRadius << "\" length=\"" << length
                        << "\"/></geometry>\n";
                out << "    </collision>\n"
                    << "  </link>\n";
                out << "  <joint name=\"joint" << i + 1 << "\" type=\""
                    << (options.continuous ? "continuous" : "revolute") << "\">\n"
                    << "    <parent link=\"" << (i == 0 ? std::string("base_link") : "link" + std::to_string(i))
                    << "\"/>\n"
                    << "    <child link=\"link" << i + 1 << "\"/>\n"
                    << "    <origin xyz=\"" << (i == 0 ? 0. : linkLengths[i - 1]) << " 0 0\" rpy=\"0 0 0\"/>\n"
                    << "    <axis xyz=\"0 0 1\"/>\n";
                if (!options.continuous)
                    out << "    <limit lower=\"" << -options.jointLimit << "\" upper=\"" << options.jointLimit
                        << "\" effort=\"10\" velocity=\"1\"/>\n";
                out << "  </joint>\n";
            }
            out << "</robot>\n";
            return out.str();
        }

        validity::RobotModelPtr planarArmModel(const std::vector<double> &linkLengths, const PlanarArmOptions &options)
        {
            return validity::RobotModel::fromUrdfString(planarArmUrdf(linkLengths, options),
                                                        "<" + options.name + " urdf>", fs::temp_directory_path());
        }

        std::vector<Eigen::Vector2d> planarArmPoints(const std::vector<double> &linkLengths,
                                                     const std::vector<double> &q)
        {
            std::vector<Eigen::Vector2d> points{Eigen::Vector2d::Zero()};
            double angle = 0.;
            for (std::size_t i = 0; i < linkLengths.size(); ++i)
            {
                angle += q[i];
                points.push_back(points.back() + linkLengths[i] * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
            }
            return points;
        }

        Outline boxOutline(const Eigen::Vector2d &lo, const Eigen::Vector2d &hi)
        {
            return {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
        }

        Outline regularPolygon(const Eigen::Vector2d &centre, double radius, int sides, double phase)
        {
            Outline outline;
            for (int i = 0; i < sides; ++i)
            {
                const double a = phase + 2. * M_PI * i / sides;
                outline.push_back(centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
            }
            return outline;
        }

        double outlineArea(const Outline &outline)
        {
            double a = 0.;
            for (std::size_t i = 0; i < outline.size(); ++i)
            {
                const auto &u = outline[i];
                const auto &v = outline[(i + 1) % outline.size()];
                a += u.x() * v.y() - v.x() * u.y();
            }
            return 0.5 * std::abs(a);
        }

        validity::ScenePtr polygonScene(const std::vector<Outline> &polygons, double zMin, double zMax,
                                        const std::string &prefix)
        {
            auto scene = std::make_shared<validity::Scene>();
            for (std::size_t i = 0; i < polygons.size(); ++i)
            {
                validity::Obstacle o;
                o.name = prefix + std::to_string(i);
                o.shape = validity::Shape::prism(polygons[i], zMin, zMax);
                scene->add(std::move(o));
            }
            return scene;
        }

        namespace
        {
            CheckerSetup finishSetup(CheckerSetup setup, const ompl::base::StateSpacePtr &space, double resolution)
            {
                setup.si = std::make_shared<ompl::base::SpaceInformation>(space);
                setup.checker = std::make_shared<validity::FclValidityChecker>(setup.si, setup.bodies, setup.scene);
                setup.si->setStateValidityChecker(setup.checker);
                setup.si->setStateValidityCheckingResolution(resolution);
                setup.si->setup();
                return setup;
            }
        }  // namespace

        CheckerSetup robotSetup(const validity::RobotModelPtr &model, const validity::ScenePtr &scene,
                                double resolution)
        {
            std::vector<state_spaces::JointSpec> joints;
            std::vector<int> variables;
            for (std::size_t v = 0; v < model->variableCount(); ++v)
            {
                const auto &joint = model->variableJoint(v);
                joints.push_back(
                    {joint.name, joint.lower, joint.upper, joint.type == validity::RobotJoint::Type::CONTINUOUS});
                variables.push_back(static_cast<int>(v));
            }
            CheckerSetup setup;
            setup.model = model;
            setup.scene = scene;
            setup.bodies = std::make_shared<validity::RobotGroupBodies>(
                model, variables, std::vector<double>(model->variableCount(), 0.));
            return finishSetup(setup, state_spaces::makeJointStateSpace(joints), resolution);
        }

        CheckerSetup planarArmSetup(const std::vector<double> &linkLengths, const std::vector<Outline> &obstacles,
                                    const PlanarArmOptions &options, double resolution)
        {
            return robotSetup(planarArmModel(linkLengths, options), polygonScene(obstacles), resolution);
        }

        CheckerSetup planarRigidBodySetup(const Outline &footprint, const std::vector<Outline> &obstacles,
                                          const Eigen::Vector2d &lo, const Eigen::Vector2d &hi, double resolution)
        {
            CheckerSetup setup;
            setup.scene = polygonScene(obstacles);
            setup.bodies = std::make_shared<validity::PlanarRigidBody>(footprint, -0.5, 0.5);
            return finishSetup(setup, state_spaces::makeSe2StateSpace(lo.x(), hi.x(), lo.y(), hi.y()), resolution);
        }

        std::string asciiStlBox(const Eigen::Vector3d &extents, const Eigen::Vector3d &centre, const std::string &name)
        {
            const Eigen::Vector3d h = 0.5 * extents;
            auto corner = [&](int i)
            {
                return Eigen::Vector3d(centre.x() + (i & 1 ? h.x() : -h.x()), centre.y() + (i & 2 ? h.y() : -h.y()),
                                       centre.z() + (i & 4 ? h.z() : -h.z()));
            };
            // each face as two triangles, counter-clockwise seen from outside
            const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
            std::ostringstream out;
            out << std::setprecision(17);
            out << "solid " << name << "\n";
            for (const auto &f : faces)
                for (const auto &tri : {std::array<int, 3>{f[0], f[1], f[2]}, std::array<int, 3>{f[0], f[2], f[3]}})
                {
                    const Eigen::Vector3d a = corner(tri[0]), b = corner(tri[1]), c = corner(tri[2]);
                    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
                    out << "  facet normal " << n.x() << " " << n.y() << " " << n.z() << "\n    outer loop\n";
                    for (const auto &v : {a, b, c})
                        out << "      vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
                    out << "    endloop\n  endfacet\n";
                }
            out << "endsolid " << name << "\n";
            return out.str();
        }

        TempDir::TempDir(const std::string &prefix)
        {
            static std::atomic<int> counter{0};
            const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
            for (int attempt = 0;; ++attempt)
            {
                const fs::path p =
                    fs::temp_directory_path() / (prefix + "_" + std::to_string(getpid()) + "_" + std::to_string(stamp) +
                                                 "_" + std::to_string(counter++));
                if (fs::create_directories(p))
                {
                    path_ = p.string();
                    return;
                }
                if (attempt > 100)
                    throw std::runtime_error("cannot create a temporary directory " + p.string());
            }
        }

        TempDir::~TempDir()
        {
            std::error_code ignored;
            fs::remove_all(path_, ignored);
        }

        std::string TempDir::write(const std::string &relative, const std::string &content) const
        {
            const fs::path p = fs::path(path_) / relative;
            fs::create_directories(p.parent_path());
            std::ofstream out(p, std::ios::binary);
            out << content;
            if (!out)
                throw std::runtime_error("cannot write " + p.string());
            return p.string();
        }
    }  // namespace test
}  // namespace michi
