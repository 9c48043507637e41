#include <michi/validity/fcl/FclContact.h>
#include <michi/validity/scene/Shape.h>

#include <fcl/narrowphase/collision.h>

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
        }  // namespace

        bool objectsTouch(const fcl::CollisionObjectd *a, const fcl::CollisionObjectd *b)
        {
            // Disjoint world boxes first: FCL's narrow phase sets up a traversal (relative pose, solver, request)
            // before its first bounding-volume test, and most self pairs of an arm are far apart (a quarter of a
            // Panda state check went to those setups). The scene's broad phase has already tested its pairs' boxes.
            if (!a->getAABB().overlap(b->getAABB()))
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
