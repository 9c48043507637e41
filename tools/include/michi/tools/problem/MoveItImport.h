#ifndef MICHI_TOOLS_MOVEIT_IMPORT_
#define MICHI_TOOLS_MOVEIT_IMPORT_

#include <michi/validity/robot/RobotModel.h>
#include <michi/validity/scene/Scene.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief What michi takes from an SRDF (MoveIt's Semantic Robot Description Format): the link pairs whose
            collisions are disabled and the planning groups. */
        struct SrdfModel
        {
            std::string robotName;
            /** \brief Every <disable_collisions link1 link2>, in file order. */
            std::vector<std::pair<std::string, std::string>> disabledCollisions;
            /** \brief Every <group> that holds at least one movable joint of the robot, as its movable joints in
                the robot's configuration order. A group's joints come from its <joint> children, its <chain
                base_link tip_link> (the joints between base and tip), its <link> children (the link's parent
                joint) and its <group> children (subgroups, defined anywhere in the file). <passive_joint>s are
                not planned and left out. */
            std::map<std::string, std::vector<std::string>> groups;
        };

        /** \brief Read an SRDF file and check every link and joint it names against \e model. Throws
            ProblemError naming the file, the element and its line for malformed XML, unknown links, joints or
            subgroups, a chain whose tip is not below its base, and cyclic subgroups. */
        SrdfModel readSrdf(const std::string &path, const validity::RobotModel &model);

        /** \brief What michi takes from a MoveIt PlanningScene YAML file. */
        struct MoveItScene
        {
            /** \brief One obstacle per primitive ("<object id>/<index>") and per mesh ("<object id>/mesh<index>")
                of world.collision_objects, posed in michi's world frame. */
            std::vector<validity::Obstacle> obstacles;
            /** \brief Pairs of robot links that allowed_collision_matrix allows to collide. */
            std::vector<std::pair<std::string, std::string>> allowedCollisions;
        };

        /** \brief Read a MoveIt PlanningScene YAML file (as written by MoveIt and by MotionBenchMaker).

            Objects: world.collision_objects[i] with id, header.frame_id, an optional object pose (MoveIt >= 1.1),
            primitives (type box [x, y, z], sphere [radius], cylinder [height, radius]; by name or by the
            shape_msgs/SolidPrimitive number) with primitive_poses, and meshes (vertices, triangles with
            vertex_indices) with mesh_poses. A primitive's world pose is frame * object pose * primitive pose, as
            MoveIt composes them. Frames: "", "world", a child_frame_id of fixed_frame_transforms, or the robot's
            root link (then the robot's base pose). Positions are lists [x, y, z] or mappings {x, y, z};
            orientations [x, y, z, w] or {x, y, z, w}; an all-zero quaternion is the identity (as in MoveIt).

            allowed_collision_matrix: entry_names / entry_values (lists of booleans, or {enabled: [...]}) and
            default_entry_names / default_entry_values; pairs of two links of \e model (when given) that are true
            become allowedCollisions; names that are not robot links (objects) are skipped.

            Not used: robot_state (the start comes from a MotionPlanRequest), link_padding, link_scale, colours.
            Rejected with a ProblemError naming the file and key: cones, planes, octomaps, attached objects,
            operations other than ADD, and anything malformed. \e model may be null (no robot links). */
        MoveItScene readMoveItScene(const std::string &path, const validity::RobotModel *model);

        /** \brief What michi takes from a MoveIt MotionPlanRequest YAML file. */
        struct MoveItRequest
        {
            std::string file;
            std::string groupName;                ///< group_name; empty when not given
            std::vector<std::string> startNames;  ///< start_state.joint_state.name
            std::vector<double> startPositions;   ///< start_state.joint_state.position
            /** \brief goal_constraints[0].joint_constraints as (joint_name, position); tolerances are not used. */
            std::vector<std::pair<std::string, double>> goal;
        };

        /** \brief Read a MoveIt MotionPlanRequest YAML file. Throws ProblemError naming the file and key when the
            start state or a joint-space goal (goal_constraints[0].joint_constraints) is missing or malformed. */
        MoveItRequest readMoveItRequest(const std::string &path);

        /** \brief Values of \e joints in \e names / \e positions (a joint state), in the order of \e joints.
            Throws ProblemError(file, key, ...) naming the first joint that is missing. */
        std::vector<double> jointValues(const std::vector<std::string> &joints, const std::vector<std::string> &names,
                                        const std::vector<double> &positions, const std::string &file,
                                        const std::string &key);
    }  // namespace tools
}  // namespace michi

#endif
