#ifndef MICHI_VALIDITY_FCL_FCL_CONTACT_
#define MICHI_VALIDITY_FCL_FCL_CONTACT_

#include <fcl/narrowphase/collision_object.h>

namespace michi
{
    namespace validity
    {
        /** \brief Do two placed FCL objects touch? FCL's boolean collision query, with three choices of michi's:
            - a mesh made by Shape is tested through its collision-only OBB tree (Shape::collisionMesh()) rather
              than the OBBRSS tree it was placed with, when the other object is a box, sphere, cylinder or capsule or
              a mesh with such a tree too: the same triangles, so the same answer, without FCL fitting an OBBRSS
              around the primitive (an eigen-decomposition) on every query (convex pieces keep the OBBRSS tree:
              FCL's OBB of a convex is wrong);
            - two convex pieces that libccd calls in contact are asked again with FCL's own GJK, which does not
              call apart prisms in contact (docs/checking.md);
            - spheres, capsules, cylinders and Shape meshes (Shape::enclosingCapsule()) whose enclosing capsules are
              more than a micrometre apart are apart without FCL (a capsule holds each of them, so FCL would say
              apart too); nearer pairs are FCL's to decide.
            The objects' own geometries are used whenever the first does not apply (a mesh whose FCL user data is
            null). A mesh's geometry must carry either no user data or the Shape that made it (Shape::owner(); the
            geometries of michi's scenes and robots all come from Shape). Both
            objects' world bounding boxes must be current (computeAABB() after setTransform(), as FCL's broad phase
            needs them too): objects whose boxes are apart are answered without the narrow phase. */
        bool objectsTouch(const fcl::CollisionObjectd *a, const fcl::CollisionObjectd *b);
    }  // namespace validity
}  // namespace michi

#endif
