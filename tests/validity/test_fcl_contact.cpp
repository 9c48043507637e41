// Tests of michi::validity::objectsTouch: a Shape's mesh is tested through its collision-only OBB tree, and the
// answer must be FCL's own on the OBBRSS tree the mesh is placed with (the Panda's collision meshes against every
// primitive, an extruded polygon and another mesh, at random poses near contact), including a mesh wholly inside a
// box and a box wholly inside a mesh's bounds. The extruded polygon must keep the OBBRSS path: FCL's OBB of a convex
// piece does not hold it, and with it this test found missed contacts. Spheres, capsules, cylinders and meshes are
// called apart by their enclosing capsules before FCL is asked: the same comparison covers them, and every mesh
// vertex must lie inside its capsule.

#include <michi/validity/fcl/FclContact.h>
#include <michi/validity/scene/Shape.h>

#include <fcl/narrowphase/collision.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace michi;
using validity::Shape;
using validity::ShapePtr;

namespace
{
    ShapePtr pandaMesh(const std::string &name)
    {
        return Shape::meshFromFile(std::string(MICHI_SOURCE_DIR) + "/problems/robots/panda/meshes/collision/" + name +
                                   ".obj");
    }

    /** FCL's answer on the objects as placed (OBBRSS trees, libccd). */
    bool fclCollides(const fcl::CollisionObjectd &a, const fcl::CollisionObjectd &b)
    {
        fcl::CollisionRequestd request;
        fcl::CollisionResultd result;
        return fcl::collide(&a, &b, request, result) > 0;
    }

    /** Random poses of \e b about \e a within \e reach metres: returns how many touch (every answer must match). */
    int compareAtRandomPoses(const ShapePtr &a, const ShapePtr &b, double reach, int poses, std::uint32_t seed)
    {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> offset(-reach, reach), angle(-M_PI, M_PI), unit(-1., 1.);
        int touching = 0;
        for (int i = 0; i < poses; ++i)
        {
            Eigen::Vector3d axis(unit(rng), unit(rng), unit(rng));
            if (axis.norm() < 1e-3)
                axis = Eigen::Vector3d::UnitZ();
            const Eigen::Isometry3d pose = Eigen::Translation3d(offset(rng), offset(rng), offset(rng)) *
                                           Eigen::AngleAxisd(angle(rng), axis.normalized());
            fcl::CollisionObjectd oa(a->geometries().front(), Eigen::Isometry3d::Identity());
            fcl::CollisionObjectd ob(b->geometries().front(), pose);
            const bool expected = fclCollides(oa, ob);
            EXPECT_EQ(validity::objectsTouch(&oa, &ob), expected) << "pose " << i;
            EXPECT_EQ(validity::objectsTouch(&ob, &oa), expected) << "pose " << i << " (objects swapped)";
            touching += expected ? 1 : 0;
        }
        return touching;
    }
}  // namespace

TEST(FclContact, MeshesHaveACollisionOnlyObbTree)
{
    const ShapePtr link = pandaMesh("link4");
    ASSERT_NE(link->collisionMesh(), nullptr);
    EXPECT_EQ(link->collisionMesh()->getNodeType(), fcl::BV_OBB);
    EXPECT_EQ(Shape::owner(link->geometries().front().get()), link.get());
    EXPECT_EQ(Shape::box(Eigen::Vector3d(1, 1, 1))->collisionMesh(), nullptr);
}

TEST(FclContact, MeshAgainstPrimitivesAsFclSays)
{
    const std::vector<ShapePtr> obstacles{Shape::box(Eigen::Vector3d(0.6, 0.8, 0.05)), Shape::sphere(0.08),
                                          Shape::cylinder(0.05, 0.3), Shape::capsule(0.04, 0.2),
                                          Shape::prism({{0, 0}, {0.2, 0}, {0.2, 0.1}, {0.1, 0.05}, {0, 0.1}}, 0., 0.2)};
    for (const char *name : {"link4", "hand", "link6"})
        for (std::size_t o = 0; o < obstacles.size(); ++o)
        {
            SCOPED_TRACE(std::string(name) + " against obstacle " + std::to_string(o));
            const int touching = compareAtRandomPoses(pandaMesh(name), obstacles[o], 0.25, 300, 7 + o);
            // near contact: both answers occur, so the comparison tests something
            EXPECT_GT(touching, 10);
            EXPECT_LT(touching, 290);
        }
}

TEST(FclContact, MeshAgainstMeshAsFclSays)
{
    const int touching = compareAtRandomPoses(pandaMesh("link4"), pandaMesh("link6"), 0.2, 300, 3);
    EXPECT_GT(touching, 10);
    EXPECT_LT(touching, 290);
}

TEST(FclContact, RoundPrimitivesAsFclSays)
{
    // spheres, capsules and cylinders (an xArm6's links are cylinders) are answered "apart" by their enclosing
    // capsules before libccd: every pair at random poses near contact must still get FCL's own answer, from both sides
    const std::vector<ShapePtr> round{Shape::sphere(0.06), Shape::capsule(0.04, 0.25), Shape::cylinder(0.05, 0.3),
                                      Shape::cylinder(0.12, 0.02)};
    for (std::size_t i = 0; i < round.size(); ++i)
        for (std::size_t j = i; j < round.size(); ++j)
        {
            SCOPED_TRACE("shapes " + std::to_string(i) + " and " + std::to_string(j));
            const int touching = compareAtRandomPoses(round[i], round[j], 0.3, 2000, 11 + 5 * i + j);
            EXPECT_GT(touching, 20);
            EXPECT_LT(touching, 1980);
        }
}

TEST(FclContact, CylinderEndFacesNearlyTouchingAsFclSays)
{
    // two cylinders end to end on one axis, then side by side: the enclosing capsules overlap, so FCL decides
    const ShapePtr c = Shape::cylinder(0.05, 0.3);
    fcl::CollisionObjectd a(c->geometries().front(), Eigen::Isometry3d::Identity());
    for (const double gap : {-1e-3, 1e-3, 0.02, 0.06})
    {
        fcl::CollisionObjectd endToEnd(c->geometries().front(),
                                       Eigen::Isometry3d(Eigen::Translation3d(0., 0., 0.3 + gap)));
        EXPECT_EQ(validity::objectsTouch(&a, &endToEnd), fclCollides(a, endToEnd)) << "end to end, gap " << gap;
        EXPECT_EQ(validity::objectsTouch(&a, &endToEnd), gap < 0.) << "end to end, gap " << gap;
        fcl::CollisionObjectd side(c->geometries().front(), Eigen::Isometry3d(Eigen::Translation3d(0.1 + gap, 0., 0.)));
        EXPECT_EQ(validity::objectsTouch(&a, &side), gap < 0.) << "side by side, gap " << gap;
    }
}

TEST(FclContact, EnclosingCapsuleHoldsEveryVertexOfEveryPandaMesh)
{
    // objectsTouch() calls two objects apart when their enclosing capsules are: that is sound only if every vertex (and
    // so every triangle, the capsule being convex) lies inside
    for (const char *name : {"link0", "link1", "link2", "link3", "link4", "link5", "link6", "link7", "hand", "finger"})
    {
        const ShapePtr mesh = pandaMesh(name);
        const Shape::Capsule *c = mesh->enclosingCapsule();
        ASSERT_NE(c, nullptr) << name;
        const Eigen::Vector3d axis = c->b - c->a;
        double farthest = 0.;
        for (const auto &v : mesh->vertices())
        {
            const double t =
                axis.squaredNorm() > 0. ? std::clamp((v - c->a).dot(axis) / axis.squaredNorm(), 0., 1.) : 0.;
            farthest = std::max(farthest, (v - (c->a + t * axis)).norm());
        }
        EXPECT_LE(farthest, c->radius) << name;
        // and it is tight enough to be worth asking: no larger than the sphere about the origin that holds the mesh
        EXPECT_LT(c->radius, mesh->boundingRadius()) << name;
    }
    EXPECT_EQ(Shape::cylinder(0.1, 0.2)->enclosingCapsule(), nullptr);
}

TEST(FclContact, MeshInsideABoxTouchesIt)
{
    // FCL tests the mesh's triangles against the solid box: a link wholly inside collides, though no triangle
    // crosses a face; a box wholly inside the link's surface does not (FCL's meshes are surfaces).
    const ShapePtr hand = pandaMesh("hand");
    fcl::CollisionObjectd inside(hand->geometries().front(), Eigen::Isometry3d::Identity());
    fcl::CollisionObjectd big(Shape::box(Eigen::Vector3d(2, 2, 2))->geometries().front(),
                              Eigen::Isometry3d::Identity());
    EXPECT_TRUE(fclCollides(inside, big));
    EXPECT_TRUE(validity::objectsTouch(&inside, &big));
    fcl::CollisionObjectd tiny(Shape::box(Eigen::Vector3d(1e-3, 1e-3, 1e-3))->geometries().front(),
                               Eigen::Isometry3d(Eigen::Translation3d(0, 0, 0.05)));
    EXPECT_EQ(validity::objectsTouch(&inside, &tiny), fclCollides(inside, tiny));
}
