#include <michi/validity/fcl/FclContact.h>
#include <michi/validity/scene/Shape.h>

#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>

#include <algorithm>
#include <cmath>

namespace michi
{
    namespace validity
    {
        namespace
        {
            /** The geometry to test \e o with against a mesh's OBB tree: a Shape's mesh's OBB tree, a primitive's own
                geometry; null where the OBB tree must not be used (a mesh made elsewhere, a convex piece). */
            const fcl::CollisionGeometryd *collisionGeometry(const fcl::CollisionObjectd *o)
            {
                const fcl::CollisionGeometryd *g = o->collisionGeometry().get();
                if (o->getObjectType() != fcl::OT_BVH)
                {
                    // Only primitives whose OBB FCL makes directly. Its OBB of a Convex (an extruded polygon's
                    // piece) fits the box in the vertices' principal axes and then replaces those axes by the
                    // pose's, so the box no longer holds the polygon: contacts were missed (FclContact tests).
                    switch (o->getNodeType())
                    {
                        case fcl::GEOM_BOX:
                        case fcl::GEOM_SPHERE:
                        case fcl::GEOM_CYLINDER:
                        case fcl::GEOM_CAPSULE:
                            return g;
                        default:
                            return nullptr;
                    }
                }
                const Shape *shape = Shape::owner(g);
                return shape != nullptr ? shape->collisionMesh() : nullptr;
            }

            /** The capsule that holds a sphere (a segment of length 0), a capsule, a cylinder (its axis, its radius) or
                a Shape's mesh (Shape::enclosingCapsule()), as the segment p-q and the radius r; false for other
                geometry. */
            bool enclosingCapsule(const fcl::CollisionObjectd *o, Eigen::Vector3d &p, Eigen::Vector3d &q, double &r)
            {
                const fcl::CollisionGeometryd *g = o->collisionGeometry().get();
                double half = 0.;
                switch (o->getNodeType())
                {
                    case fcl::GEOM_SPHERE:
                        r = static_cast<const fcl::Sphered *>(g)->radius;
                        break;
                    case fcl::GEOM_CAPSULE:
                        r = static_cast<const fcl::Capsuled *>(g)->radius;
                        half = 0.5 * static_cast<const fcl::Capsuled *>(g)->lz;
                        break;
                    case fcl::GEOM_CYLINDER:
                        r = static_cast<const fcl::Cylinderd *>(g)->radius;
                        half = 0.5 * static_cast<const fcl::Cylinderd *>(g)->lz;
                        break;
                    default:
                    {
                        // a mesh made by Shape: the capsule that holds its vertices, hence its triangles
                        const Shape *shape =
                            o->getObjectType() == fcl::OT_BVH ? Shape::owner(g) : static_cast<const Shape *>(nullptr);
                        const Shape::Capsule *c = shape != nullptr ? shape->enclosingCapsule() : nullptr;
                        if (c == nullptr)
                            return false;
                        p = o->getTransform() * c->a;
                        q = o->getTransform() * c->b;
                        r = c->radius;
                        return true;
                    }
                }
                // FCL's capsules and cylinders are centred on their frame's origin, along its z axis
                const Eigen::Vector3d axis = half * o->getRotation().col(2);
                p = o->getTranslation() - axis;
                q = o->getTranslation() + axis;
                return true;
            }

            /** Squared distance between the segments p1-q1 and p2-q2 (closest points by clamping the parameters of
                the two lines, one then the other; degenerate segments are points). */
            double segmentsDistance2(const Eigen::Vector3d &p1, const Eigen::Vector3d &q1, const Eigen::Vector3d &p2,
                                     const Eigen::Vector3d &q2)
            {
                const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, w = p1 - p2;
                const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(w);
                double s = 0., t = 0.;
                const double tiny = 1e-18;
                if (a <= tiny && e <= tiny)
                    return w.squaredNorm();
                if (a <= tiny)
                    t = std::clamp(f / e, 0., 1.);
                else
                {
                    const double c = d1.dot(w);
                    if (e <= tiny)
                        s = std::clamp(-c / a, 0., 1.);
                    else
                    {
                        const double b = d1.dot(d2), denom = a * e - b * b;
                        // parallel lines: any s, take the start of the first segment
                        s = denom > tiny ? std::clamp((b * f - c * e) / denom, 0., 1.) : 0.;
                        t = (b * s + f) / e;
                        if (t < 0.)
                        {
                            t = 0.;
                            s = std::clamp(-c / a, 0., 1.);
                        }
                        else if (t > 1.)
                        {
                            t = 1.;
                            s = std::clamp((b - c) / a, 0., 1.);
                        }
                    }
                }
                return (w + s * d1 - t * d2).squaredNorm();
            }

            /** Two spheres, capsules, cylinders or meshes whose enclosing capsules are apart by more than a
                micrometre: apart, without libccd's iterative test (cylinder pairs through it were a fifth of an xArm6
                state check in perf) or a walk of a mesh's tree. Only a "free" answer is given this way; nearer pairs
                still go to FCL. */
            bool roundShapesApart(const fcl::CollisionObjectd *a, const fcl::CollisionObjectd *b)
            {
                Eigen::Vector3d pa, qa, pb, qb;
                double ra = 0., rb = 0.;
                if (!enclosingCapsule(a, pa, qa, ra) || !enclosingCapsule(b, pb, qb, rb))
                    return false;
                const double reach = ra + rb + 1e-6;
                return segmentsDistance2(pa, qa, pb, qb) > reach * reach;
            }
        }  // namespace

        bool objectsTouch(const fcl::CollisionObjectd *a, const fcl::CollisionObjectd *b)
        {
            // Disjoint world boxes first: FCL's narrow phase sets up a traversal (relative pose, solver, request)
            // before its first bounding-volume test, and most self pairs of an arm are far apart (a quarter of a
            // Panda state check went to those setups). The scene's broad phase has already tested its pairs' boxes.
            if (!a->getAABB().overlap(b->getAABB()))
                return false;
            if (roundShapesApart(a, b))
                return false;
            fcl::CollisionRequestd request;
            fcl::CollisionResultd result;
            if (a->getObjectType() == fcl::OT_BVH || b->getObjectType() == fcl::OT_BVH)
            {
                // Two trees must have the same bounding-volume type (FCL has no OBB-against-OBBRSS query), so both
                // are swapped or neither.
                const fcl::CollisionGeometryd *ga = collisionGeometry(a), *gb = collisionGeometry(b);
                if (ga != nullptr && gb != nullptr)
                    return fcl::collide(ga, a->getTransform(), gb, b->getTransform(), request, result) > 0;
            }
            // FCL's default request (it stops at the first contact) with its default solver, libccd; but libccd calls
            // two convex polytopes (SE(2) footprints, extruded polygons) in contact when they are up to 4.4 cm apart
            // (31 of 200,000 poses near dynamic_mobile_passage's block), so its contacts between two of them are
            // confirmed by FCL's own GJK, which agreed with an exact polygon test at every pose (docs/checking.md,
            // test ConvexPrismsCollideExactlyAsPolygons). Only a contact is asked twice: the answer is never "free"
            // where libccd says free.
            if (fcl::collide(a, b, request, result) == 0)
                return false;
            if (a->getNodeType() != fcl::GEOM_CONVEX || b->getNodeType() != fcl::GEOM_CONVEX)
                return true;
            request.gjk_solver_type = fcl::GST_INDEP;
            fcl::CollisionResultd again;
            return fcl::collide(a, b, request, again) > 0;
        }
    }  // namespace validity
}  // namespace michi
