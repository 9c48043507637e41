// Sphere models enclose every link: points sampled on each link's real surface lie inside some sphere of the link.
#include <michi/validity/spheres/SphereModel.h>

#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

using namespace michi::validity;

namespace
{
    const std::string DIR = std::string(MICHI_SOURCE_DIR) + "/problems/robots/";

    /** Points on the real surface of a link's collision geometry (cylinders on their round surface). */
    std::vector<Eigen::Vector3d> surfaceSamples(const RobotLink &link, ompl::RNG &rng, int perShape)
    {
        std::vector<Eigen::Vector3d> points;
        for (const auto &c : link.collisions)
        {
            const auto &shape = *c.shape;
            const Eigen::Vector3d &s = shape.size();
            for (int i = 0; i < perShape; ++i)
            {
                Eigen::Vector3d p;
                switch (shape.type())
                {
                    case Shape::Type::BOX:
                    {
                        p = Eigen::Vector3d(rng.uniformReal(-0.5, 0.5) * s.x(), rng.uniformReal(-0.5, 0.5) * s.y(),
                                            rng.uniformReal(-0.5, 0.5) * s.z());
                        const int axis = rng.uniformInt(0, 2);
                        p[axis] = (rng.uniformBool() ? 0.5 : -0.5) * s[axis];
                        break;
                    }
                    case Shape::Type::CYLINDER:
                    {
                        const double a = rng.uniformReal(0., 2. * M_PI);
                        const double rr = i % 3 == 0 ? s.x() * std::sqrt(rng.uniform01()) : s.x();
                        const double z =
                            i % 3 == 0 ? (rng.uniformBool() ? 0.5 : -0.5) * s.z() : rng.uniformReal(-0.5, 0.5) * s.z();
                        p = Eigen::Vector3d(rr * std::cos(a), rr * std::sin(a), z);
                        break;
                    }
                    case Shape::Type::SPHERE:
                    {
                        const Eigen::Vector3d g(rng.gaussian01(), rng.gaussian01(), rng.gaussian01());
                        p = g.normalized() * s.x();
                        break;
                    }
                    case Shape::Type::MESH:
                    {
                        const auto &t =
                            shape.triangles()[rng.uniformInt(0, static_cast<int>(shape.triangles().size()) - 1)];
                        double u = rng.uniform01(), v = rng.uniform01();
                        if (u + v > 1.)
                        {
                            u = 1. - u;
                            v = 1. - v;
                        }
                        // corners too: the farthest points of a triangle
                        if (i % 5 == 0)
                            u = 1., v = 0.;
                        const auto &A = shape.vertices()[t[0]], &B = shape.vertices()[t[1]],
                                   &C = shape.vertices()[t[2]];
                        p = A + u * (B - A) + v * (C - A);
                        break;
                    }
                    default:
                        continue;
                }
                points.push_back(c.origin * p);
            }
        }
        return points;
    }

    /** Number of sampled surface points outside every sphere of their link. */
    int outsidePoints(const RobotModel &model, const SphereModel &spheres, int perShape)
    {
        ompl::RNG rng(11);
        int outside = 0;
        for (std::size_t l = 0; l < model.links().size(); ++l)
            for (const auto &p : surfaceSamples(model.links()[l], rng, perShape))
            {
                bool in = false;
                for (const auto &s : spheres.linkSpheres(static_cast<int>(l)))
                    in = in || (p - s.centre).norm() <= s.radius;
                if (!in)
                {
                    ADD_FAILURE() << model.links()[l].name << ": point " << p.transpose() << " outside its spheres";
                    ++outside;
                    if (outside > 5)
                        return outside;
                }
            }
        return outside;
    }
}  // namespace

TEST(SphereModel, EnclosesPandaMeshes)
{
    const auto model = RobotModel::fromUrdfFile(DIR + "panda/panda.urdf");
    for (int budget : {1, 8, 24})
    {
        SphereModelSettings settings;
        settings.spheresPerLink = budget;
        const auto spheres = SphereModel::enclose(*model, settings);
        for (std::size_t l = 0; l < model->links().size(); ++l)
        {
            EXPECT_LE(static_cast<int>(spheres->linkSpheres(static_cast<int>(l)).size()), budget);
            EXPECT_EQ(spheres->linkSpheres(static_cast<int>(l)).empty(), model->links()[l].collisions.empty());
        }
        EXPECT_EQ(outsidePoints(*model, *spheres, 4000), 0) << "budget " << budget;
    }
}

TEST(SphereModel, EnclosesPrimitiveLinks)
{
    for (const char *urdf : {"xarm6.urdf", "iiwa7dof.urdf", "dual_arm.urdf"})
    {
        const auto model = RobotModel::fromUrdfFile(DIR + urdf);
        for (int budget : {1, 4, 16})
        {
            SphereModelSettings settings;
            settings.spheresPerLink = budget;
            const auto spheres = SphereModel::enclose(*model, settings);
            EXPECT_EQ(outsidePoints(*model, *spheres, 3000), 0) << urdf << " budget " << budget;
        }
    }
}

TEST(SphereModel, SpherizedUrdfGrownToEncloseTheMeshes)
{
    const auto model = RobotModel::fromUrdfFile(DIR + "panda/panda.urdf");
    const auto spheres = SphereModel::fromSpherizedUrdf(*model, DIR + "panda/panda_spherized.urdf");
    EXPECT_EQ(outsidePoints(*model, *spheres, 4000), 0);
    // the spherized file's links keep their sphere count
    const auto spherized = RobotModel::fromUrdfFile(DIR + "panda/panda_spherized.urdf");
    const int link1 = model->linkIndex("panda_link1");
    EXPECT_EQ(spheres->linkSpheres(link1).size(),
              spherized->links()[spherized->linkIndex("panda_link1")].collisions.size());
}

TEST(SphereModel, RejectsABadBudget)
{
    const auto model = RobotModel::fromUrdfFile(DIR + "planar_2link.urdf");
    SphereModelSettings settings;
    settings.spheresPerLink = 0;
    EXPECT_THROW(SphereModel::enclose(*model, settings), std::invalid_argument);
}
