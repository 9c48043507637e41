#ifndef MICHI_TESTS_SUPPORT_TEST_SCENES_
#define MICHI_TESTS_SUPPORT_TEST_SCENES_

#include <michi/tools/problem/RandomPlanarScene.h>
#include <michi/validity/robot/CollisionBodies.h>
#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/robot/RobotModel.h>
#include <michi/validity/scene/Scene.h>

#include <ompl/base/SpaceInformation.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

namespace michi
{
    namespace test
    {
        /** \brief A planar polygon outline (any orientation, not closed: the last vertex is not the first). */
        using Outline = std::vector<Eigen::Vector2d>;

        /** \brief Path of a file in the source tree (\e relative to the repository root). */
        std::string sourcePath(const std::string &relative);

        /** \brief Settings of planarArmUrdf(). */
        struct PlanarArmOptions
        {
            enum class LinkShape
            {
                CYLINDER,  ///< a cylinder of radius linkRadius along the link
                BOX        ///< a box of length x 2 linkRadius x 2 linkRadius (exact FCL distances to polytopes)
            };
            LinkShape linkShape{LinkShape::CYLINDER};
            double linkRadius{0.02};  ///< radius of the cylinder (half width of the box) of every link (metres)
            double jointLimit{M_PI};  ///< revolute joints move in [-jointLimit, jointLimit]
            bool continuous{false};   ///< continuous joints instead of revolute ones
            std::string name{"planar_arm"};
        };

        /** \brief URDF of a planar serial arm: a root link "base_link" without geometry and links "link1" ..
            "linkN" joined by joints "joint1" .. "jointN" that rotate about z. Link i is a cylinder (or box) of
            length linkLengths[i-1] lying along the link's x axis from its origin to the next joint, so at q = 0 the
            arm lies on the x axis from the origin to x = sum of lengths, in the plane z = 0.
            Note FCL's accuracy: distances from a cylinder to a polytope (prism, box) go through libccd's GJK and
            are only as exact as the request's distance_tolerance (1e-6 by default); box links give polytope pairs,
            exact to rounding. */
        std::string planarArmUrdf(const std::vector<double> &linkLengths, const PlanarArmOptions &options = {});

        /** \brief planarArmUrdf() loaded as a RobotModel. */
        validity::RobotModelPtr planarArmModel(const std::vector<double> &linkLengths,
                                               const PlanarArmOptions &options = {});

        /** \brief Positions, by hand (cos/sin sums), of the joints of a planar arm and of its tip: linkLengths.size()
            + 1 points, the first at the origin. */
        std::vector<Eigen::Vector2d> planarArmPoints(const std::vector<double> &linkLengths,
                                                     const std::vector<double> &q);

        /** \brief The rectangle [lo, hi] as a counter-clockwise outline. */
        Outline boxOutline(const Eigen::Vector2d &lo, const Eigen::Vector2d &hi);
        /** \brief A regular polygon with \e sides vertices at \e radius from \e centre. */
        Outline regularPolygon(const Eigen::Vector2d &centre, double radius, int sides, double phase = 0.);
        /** \brief Absolute area of a simple polygon (shoelace). */
        double outlineArea(const Outline &outline);

        /** \brief A scene of upright prisms, one per polygon, extruded over [zMin, zMax], named prefix0, prefix1... */
        validity::ScenePtr polygonScene(const std::vector<Outline> &polygons, double zMin = -0.5, double zMax = 0.5,
                                        const std::string &prefix = "polygon");

        /** \brief Everything a test needs to check states of a robot in a scene. */
        struct CheckerSetup
        {
            validity::RobotModelPtr model;  ///< null for a planar rigid body
            validity::CollisionBodiesPtr bodies;
            validity::ScenePtr scene;
            ompl::base::SpaceInformationPtr si;
            validity::FclValidityCheckerPtr checker;
        };

        /** \brief A joint space over all movable joints of \e model (makeJointStateSpace, the URDF limits), an
            FclValidityChecker on \e scene and a set-up SpaceInformation whose state validity checking resolution is
            \e resolution (a fraction of the space's extent, as in OMPL). */
        CheckerSetup robotSetup(const validity::RobotModelPtr &model, const validity::ScenePtr &scene,
                                double resolution = 0.01);

        /** \brief robotSetup() for a planar arm among polygon obstacles (polygonScene()). */
        CheckerSetup planarArmSetup(const std::vector<double> &linkLengths, const std::vector<Outline> &obstacles,
                                    const PlanarArmOptions &options = {}, double resolution = 0.01);

        /** \brief A PlanarRigidBody with \e footprint in makeSe2StateSpace over [lo, hi] among polygon obstacles. */
        CheckerSetup planarRigidBodySetup(const Outline &footprint, const std::vector<Outline> &obstacles,
                                          const Eigen::Vector2d &lo, const Eigen::Vector2d &hi,
                                          double resolution = 0.01);

        /** \brief Random star-shaped polygons: the generator of `michi random-scenes`
            (michi/tools/RandomPlanarScene.h), the same for the same seed. */
        using RandomPolygonOptions = tools::RandomPolygonOptions;
        using tools::randomPolygons;

        /** \brief ASCII STL of an axis-aligned box with full \e extents centred at \e centre (12 triangles, outward
            normals). */
        std::string asciiStlBox(const Eigen::Vector3d &extents, const Eigen::Vector3d &centre = Eigen::Vector3d::Zero(),
                                const std::string &name = "box");

        /** \brief A fresh directory under the system temporary directory, removed with its contents on
            destruction. */
        class TempDir
        {
        public:
            explicit TempDir(const std::string &prefix = "michi_test");
            ~TempDir();
            TempDir(const TempDir &) = delete;
            TempDir &operator=(const TempDir &) = delete;

            const std::string &path() const
            {
                return path_;
            }
            /** \brief Write \e content (binary-safe) to \e relative inside the directory, creating parent
                directories; returns the full path. */
            std::string write(const std::string &relative, const std::string &content) const;

        private:
            std::string path_;
        };
    }  // namespace test
}  // namespace michi

#endif
