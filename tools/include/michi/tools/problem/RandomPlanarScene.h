#ifndef MICHI_TOOLS_RANDOM_PLANAR_SCENE_
#define MICHI_TOOLS_RANDOM_PLANAR_SCENE_

#include <michi/tools/problem/Problem.h>

#include <ompl/util/RandomNumbers.h>

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief Settings of randomPolygons(). */
        struct RandomPolygonOptions
        {
            int count{8};
            Eigen::Vector2d lo{-1., -1.};  ///< centres are drawn uniformly in [lo, hi]
            Eigen::Vector2d hi{1., 1.};
            double minRadius{0.05};  ///< vertices lie between minRadius and maxRadius from the centre
            double maxRadius{0.2};
            int minSides{3};
            int maxSides{8};
            /** \brief Keep every polygon at least this far from \e keepClearCentre (0: no constraint). */
            double keepClearRadius{0.};
            Eigen::Vector2d keepClearCentre{0., 0.};
        };

        /** \brief Random simple polygons, star-shaped about their centre (so often non-convex), drawn from \e rng.
            Each centre is drawn in [lo, hi] until the polygon's disk of maxRadius keeps keepClearRadius from
            keepClearCentre; then 3..8 vertex angles (sorted and spread halfway towards even spacing, so no two
            vertices nearly coincide) and a radius per vertex. Throws std::invalid_argument for bad options or when
            no centre is found in 10000 draws. */
        std::vector<std::vector<Eigen::Vector2d>> randomPolygons(ompl::RNG &rng, const RandomPolygonOptions &options);

        /** \brief The same from a local ompl::RNG seeded with \e seed: the same polygons for the same seed, and the
            global seed is neither used nor changed. */
        std::vector<std::vector<Eigen::Vector2d>> randomPolygons(std::uint_fast32_t seed,
                                                                 const RandomPolygonOptions &options = {});

        /** \brief Settings of randomPlanarScene(). */
        struct RandomPlanarSceneOptions
        {
            int polygons{6};        ///< obstacles per scene
            double extent{1.};      ///< polygon centres lie within this many metres of the arm's base in x and y
            double keepClear{0.1};  ///< metres kept free around the arm's base (joint 1's axis)
            double zMin{-0.5};      ///< the polygons are extruded over [zMin, zMax] around the arm's plane
            double zMax{0.5};
            double minQueryDistance{1.};  ///< joint-space distance between start and goal (radians)
            /** \brief For a two-joint group with bounded joints, the goal must be linked to the start by
                tools::GridComponents at this step (radians) with the problem's motion validator; 0: not checked. */
            double reachabilityStep{0.05};
            int maxSamples{100000};  ///< random states drawn for the start and the goal together
        };

        /** \brief What randomPlanarScene() makes: the problem and its obstacle outlines (problem.scene's prisms). */
        struct RandomPlanarScene
        {
            Problem problem;
            std::vector<std::vector<Eigen::Vector2d>> polygons;
        };

        /** \brief A random planar scene for the arm of \e arm: the template's robot, planners, benchmark and
            collision settings; as scene, \e options.polygons random star-shaped polygons (randomPolygons(), centres
            within \e extent of the base of the arm, \e keepClear kept free around it) extruded over [zMin, zMax];
            one query whose start and goal are random states that the FCL checker calls valid and so does every
            checker the template plans with (collision.checker and the planners' own, e.g. planar_2link's jmap), at
            least \e minQueryDistance apart and, for a two-joint group, linked through the grid of GridComponents
            under each of those checkers (so a path exists for every planner); for more joints they are not proved
            connected. Everything comes from one local ompl::RNG
            seeded with \e seed (the polygons first, so they equal randomPolygons(seed, ...)). The scene is named
            scene_<seed>. Throws ProblemError (key "robot") unless \e arm is an arm whose every movable
            joint rotates about z, and std::runtime_error when no start or goal is found. */
        RandomPlanarScene randomPlanarScene(const Problem &arm, std::uint_fast32_t seed,
                                            const RandomPlanarSceneOptions &options = {});

        /** \brief Settings of writeRandomScenes(). */
        struct RandomScenesOptions
        {
            std::string arm{"problems/planar_2link.yaml"};  ///< the template problem file
            std::string outDir;
            unsigned int count{50};  ///< scenes, seeds seed, seed + 1, ...
            std::uint_fast32_t seed{1};
            RandomPlanarSceneOptions scene;
        };

        /** \brief `michi random-scenes`: write DIR/scene_<seed>.yaml for count seeds. Each file keeps the template
            file's robot block (its URDF referenced by a path relative to DIR), planners, benchmark and collision
            blocks, and has the random scene, start and goal of randomPlanarScene() written with round-trip
            precision. Every file is loaded back and its start and goal checked before anything is moved into
            DIR (staged output: on an error DIR is left as it was). Returns the written file names. */
        std::vector<std::string> writeRandomScenes(const RandomScenesOptions &options);
    }  // namespace tools
}  // namespace michi

#endif
