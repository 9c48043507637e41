#include <michi/tools/problem/MoveItImport.h>
#include "ProblemYaml.h"
#include <michi/validity/InputFile.h>
#include <michi/tools/problem/Problem.h>

#include <tinyxml2.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

using michi::validity::Obstacle;
using michi::validity::RobotModel;
using michi::validity::Shape;

namespace michi
{
    namespace tools
    {
        namespace
        {
            // ---------------------------------------------------------------------------------------------------
            // SRDF

            /** "<group> line 16": the element and where it is, for error keys. */
            std::string elementKey(const tinyxml2::XMLElement *e)
            {
                return "<" + std::string(e->Name()) + "> line " + std::to_string(e->GetLineNum());
            }

            std::string attribute(const std::string &file, const tinyxml2::XMLElement *e, const char *name)
            {
                const char *value = e->Attribute(name);
                if (!value || !*value)
                    throw ProblemError(file, elementKey(e), "attribute '" + std::string(name) + "' missing");
                return value;
            }

            int srdfLink(const std::string &file, const tinyxml2::XMLElement *e, const char *name,
                         const RobotModel &model)
            {
                const std::string link = attribute(file, e, name);
                try
                {
                    return model.linkIndex(link);
                }
                catch (const std::out_of_range &)
                {
                    throw ProblemError(file, elementKey(e),
                                       std::string(name) + " '" + link + "': no such link in robot '" + model.name() +
                                           "' (" + model.source() + ")");
                }
            }

            int srdfJoint(const std::string &file, const tinyxml2::XMLElement *e, const RobotModel &model)
            {
                const std::string joint = attribute(file, e, "name");
                try
                {
                    return model.jointIndex(joint);
                }
                catch (const std::out_of_range &)
                {
                    throw ProblemError(file, elementKey(e),
                                       "joint '" + joint + "': no such joint in robot '" + model.name() + "' (" +
                                           model.source() + ")");
                }
            }

            // ---------------------------------------------------------------------------------------------------
            // YAML (MoveIt messages written as YAML)

            /** Typed access to a MoveIt message in YAML; every mistake is a ProblemError naming file and key. */
            class MessageReader : public problem_file::Reader
            {
            public:
                using problem_file::Reader::Reader;

                YAML::Node load(const std::string &what) const
                {
                    const YAML::Node root = problem_file::loadYaml(file());  // names the file (and line)
                    if (!root.IsMap())
                        fail("", "expected a mapping at the top level (a MoveIt " + what + ")");
                    return root;
                }

                /** A MoveIt message may write a missing field as null: that is missing too. */
                YAML::Node require(const YAML::Node &map, const std::string &name, const std::string &key) const
                {
                    const YAML::Node n = Reader::require(map, name, key);
                    if (n.IsNull())
                        fail(key.empty() ? name : key + "." + name, "missing (required)");
                    return n;
                }

                std::string text(const YAML::Node &n, const std::string &key) const
                {
                    if (n.IsNull())
                        return "";
                    if (!n.IsScalar())
                        fail(key, "expected a string");
                    return n.Scalar();
                }

                bool flag(const YAML::Node &n, const std::string &key) const
                {
                    if (n.IsScalar())
                    {
                        std::string s = n.Scalar();
                        std::transform(s.begin(), s.end(), s.begin(), ::tolower);
                        if (s == "true" || s == "1")
                            return true;
                        if (s == "false" || s == "0")
                            return false;
                    }
                    fail(key, "expected true or false");
                }

                YAML::Node sequence(const YAML::Node &n, const std::string &key) const
                {
                    if (!n.IsSequence())
                        fail(key, "expected a list");
                    return n;
                }

                /** Optional list: an absent or null node is an empty list. */
                std::size_t optionalSize(const YAML::Node &n, const std::string &key) const
                {
                    if (!n || n.IsNull())
                        return 0;
                    return sequence(n, key).size();
                }

                std::vector<double> numbers(const YAML::Node &n, const std::string &key) const
                {
                    return Reader::numbers(n, key);
                }

                std::vector<std::string> texts(const YAML::Node &n, const std::string &key) const
                {
                    sequence(n, key);
                    std::vector<std::string> values;
                    for (std::size_t i = 0; i < n.size(); ++i)
                        values.push_back(text(n[i], key + "[" + std::to_string(i) + "]"));
                    return values;
                }

                /** [x, y, z] or {x, y, z} (a geometry_msgs Point or Vector3). */
                Eigen::Vector3d vector3(const YAML::Node &n, const std::string &key) const
                {
                    if (n.IsSequence())
                    {
                        if (n.size() != 3)
                            fail(key, "expected 3 numbers [x, y, z], got " + std::to_string(n.size()));
                        return Eigen::Vector3d(coordinate(n[0], key + "[0]"), coordinate(n[1], key + "[1]"),
                                               coordinate(n[2], key + "[2]"));
                    }
                    if (n.IsMap())
                    {
                        // An absent field is 0, as in a ROS message written with defaults left out.
                        Eigen::Vector3d v = Eigen::Vector3d::Zero();
                        for (int i = 0; i < 3; ++i)
                        {
                            const char *c = i == 0 ? "x" : i == 1 ? "y" : "z";
                            if (n[c])
                                v[i] = coordinate(n[c], key + "." + c);
                        }
                        return v;
                    }
                    fail(key, "expected [x, y, z] or {x, y, z}");
                }

                /** [x, y, z, w] or {x, y, z, w}; all zeros is the identity (MoveIt does the same). */
                Eigen::Quaterniond quaternion(const YAML::Node &n, const std::string &key) const
                {
                    double q[4] = {0., 0., 0., 0.};  // x, y, z, w
                    if (n.IsSequence())
                    {
                        if (n.size() != 4)
                            fail(key, "expected 4 numbers [x, y, z, w], got " + std::to_string(n.size()));
                        for (int i = 0; i < 4; ++i)
                            q[i] = coordinate(n[i], key + "[" + std::to_string(i) + "]");
                    }
                    else if (n.IsMap())
                    {
                        for (int i = 0; i < 4; ++i)
                        {
                            const char *c = i == 0 ? "x" : i == 1 ? "y" : i == 2 ? "z" : "w";
                            if (n[c])
                                q[i] = coordinate(n[c], key + "." + c);
                        }
                    }
                    else
                        fail(key, "expected a quaternion [x, y, z, w] or {x, y, z, w}");
                    const Eigen::Quaterniond quat(q[3], q[0], q[1], q[2]);
                    if (quat.norm() == 0.)
                        return Eigen::Quaterniond::Identity();
                    // Normalizing a nearly zero quaternion would turn rounding noise into an arbitrary rotation.
                    if (quat.norm() < 1e-6)
                        fail(key, "quaternion of nearly zero norm");
                    return quat.normalized();
                }

                /** {position, orientation} (geometry_msgs Pose) or {translation, rotation} (Transform). */
                Eigen::Isometry3d pose(const YAML::Node &n, const std::string &key) const
                {
                    if (!n.IsMap())
                        fail(key, "expected a pose {position: [x, y, z], orientation: [x, y, z, w]}");
                    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
                    // Pose and Transform name their fields differently; either is accepted so both message types read
                    // the same.
                    for (const char *name : {"position", "translation"})
                        if (n[name])
                            t.translation() = vector3(n[name], key + "." + name);
                    for (const char *name : {"orientation", "rotation"})
                        if (n[name])
                            t.linear() = quaternion(n[name], key + "." + name).toRotationMatrix();
                    return t;
                }
            };

            /** A shape_msgs/SolidPrimitive: type by name or number, dimensions as MoveIt orders them. */
            std::shared_ptr<const Shape> readPrimitive(const MessageReader &r, const YAML::Node &p,
                                                       const std::string &key)
            {
                if (!p.IsMap())
                    r.fail(key, "expected a primitive {type, dimensions}");
                std::string type = r.text(r.require(p, "type", key), key + ".type");
                std::transform(type.begin(), type.end(), type.begin(), ::tolower);
                // shape_msgs/SolidPrimitive's constants: BOX = 1, SPHERE = 2, CYLINDER = 3, CONE = 4, PRISM = 5.
                static const std::map<std::string, std::string> numbers{
                    {"1", "box"}, {"2", "sphere"}, {"3", "cylinder"}, {"4", "cone"}, {"5", "prism"}};
                if (numbers.count(type))
                    type = numbers.at(type);
                const auto d = r.numbers(r.require(p, "dimensions", key), key + ".dimensions");
                auto expect = [&](std::size_t size, const std::string &meaning)
                {
                    if (d.size() != size)
                        r.fail(key + ".dimensions", "a " + type + " needs " + std::to_string(size) + " dimensions " +
                                                        meaning + ", got " + std::to_string(d.size()));
                    for (std::size_t i = 0; i < d.size(); ++i)
                        if (!(d[i] > 0.))
                            r.fail(key + ".dimensions[" + std::to_string(i) + "]", "expected a positive size");
                };
                if (type == "box")
                {
                    expect(3, "[x, y, z]");
                    return Shape::box(Eigen::Vector3d(d[0], d[1], d[2]));
                }
                if (type == "sphere")
                {
                    expect(1, "[radius]");
                    return Shape::sphere(d[0]);
                }
                if (type == "cylinder")
                {
                    expect(2, "[height, radius]");
                    // MoveIt orders a cylinder's dimensions [height, radius]; Shape::cylinder takes (radius, length).
                    return Shape::cylinder(d[1], d[0]);
                }
                if (type == "cone" || type == "prism")
                    // Refused, not skipped: a scene read without one of its obstacles would let paths pass through it.
                    r.fail(key + ".type", "primitive type '" + type + "' is not supported (box, sphere, cylinder)");
                r.fail(key + ".type", "unknown primitive type '" + type + "' (expected box, sphere, cylinder)");
            }

            /** A shape_msgs/Mesh: vertices [{x, y, z}] and triangles [{vertex_indices: [a, b, c]}]. */
            std::shared_ptr<const Shape> readMesh(const MessageReader &r, const YAML::Node &m, const std::string &key)
            {
                if (!m.IsMap())
                    r.fail(key, "expected a mesh {vertices, triangles}");
                const YAML::Node vertices = r.sequence(r.require(m, "vertices", key), key + ".vertices");
                const YAML::Node triangles = r.sequence(r.require(m, "triangles", key), key + ".triangles");
                std::vector<Eigen::Vector3d> points;
                for (std::size_t i = 0; i < vertices.size(); ++i)
                    points.push_back(r.vector3(vertices[i], key + ".vertices[" + std::to_string(i) + "]"));
                std::vector<Eigen::Vector3i> faces;
                for (std::size_t i = 0; i < triangles.size(); ++i)
                {
                    const std::string k = key + ".triangles[" + std::to_string(i) + "]";
                    const YAML::Node t =
                        // A shape_msgs/MeshTriangle {vertex_indices: [a, b, c]}, or the bare list.
                        triangles[i].IsMap() ? r.require(triangles[i], "vertex_indices", k) : triangles[i];
                    const auto idx = r.numbers(t, k);
                    if (idx.size() != 3)
                        r.fail(k, "expected 3 vertex indices");
                    Eigen::Vector3i face;
                    for (int c = 0; c < 3; ++c)
                    {
                        // numbers() reads doubles: an index must also be a whole number.
                        if (idx[c] < 0 || idx[c] >= static_cast<double>(points.size()) || idx[c] != std::floor(idx[c]))
                            r.fail(k, "vertex index " + std::to_string(idx[c]) + " outside [0, " +
                                          std::to_string(points.size()) + ")");
                        face[c] = static_cast<int>(idx[c]);
                    }
                    faces.push_back(face);
                }
                if (faces.empty())
                    r.fail(key + ".triangles", "expected at least one triangle");
                return Shape::mesh(std::move(points), std::move(faces), r.file() + ":" + key);
            }

            int rootLink(const RobotModel &model)
            {
                for (std::size_t l = 0; l < model.links().size(); ++l)
                    if (model.links()[l].parentJoint < 0)
                        return static_cast<int>(l);
                return 0;
            }

            void readAllowedCollisions(const MessageReader &r, const YAML::Node &acm, const RobotModel &model,
                                       MoveItScene &scene)
            {
                const std::string key = "allowed_collision_matrix";
                if (!acm.IsMap())
                    r.fail(key, "expected a mapping (entry_names, entry_values)");
                auto isLink = [&](const std::string &name)
                {
                    try
                    {
                        model.linkIndex(name);
                        return true;
                    }
                    catch (const std::out_of_range &)
                    {
                        return false;
                    }
                };
                // explicit entries: MoveIt sets entry (i, j) and (j, i) from entry_values[i][j] row by row, so the
                // last row written (the larger index) decides a pair that is not symmetric
                std::map<std::pair<std::string, std::string>, bool> entries;
                if (acm["entry_names"] && !acm["entry_names"].IsNull())
                {
                    const auto names = r.texts(acm["entry_names"], key + ".entry_names");
                    const YAML::Node rows = r.sequence(r.require(acm, "entry_values", key), key + ".entry_values");
                    if (rows.size() != names.size())
                        r.fail(key + ".entry_values", std::to_string(rows.size()) + " rows for " +
                                                          std::to_string(names.size()) + " entry_names");
                    for (std::size_t i = 0; i < rows.size(); ++i)
                    {
                        const std::string k = key + ".entry_values[" + std::to_string(i) + "]";
                        const YAML::Node row = rows[i].IsMap() ? r.require(rows[i], "enabled", k) : rows[i];
                        r.sequence(row, k);
                        if (row.size() != names.size())
                            r.fail(k, std::to_string(row.size()) + " values for " + std::to_string(names.size()) +
                                          " entry_names");
                        for (std::size_t j = 0; j < row.size(); ++j)
                        {
                            const bool v = r.flag(row[j], k + "[" + std::to_string(j) + "]");
                            if (i != j)
                                entries[std::minmax(names[i], names[j])] = v;
                        }
                    }
                }
                std::map<std::string, bool> defaults;
                if (acm["default_entry_names"] && !acm["default_entry_names"].IsNull())
                {
                    const auto names = r.texts(acm["default_entry_names"], key + ".default_entry_names");
                    const YAML::Node values =
                        r.sequence(r.require(acm, "default_entry_values", key), key + ".default_entry_values");
                    if (values.size() != names.size())
                        r.fail(key + ".default_entry_values", std::to_string(values.size()) + " values for " +
                                                                  std::to_string(names.size()) +
                                                                  " default_entry_names");
                    for (std::size_t i = 0; i < names.size(); ++i)
                        defaults[names[i]] =
                            r.flag(values[i], key + ".default_entry_values[" + std::to_string(i) + "]");
                }
                std::set<std::pair<std::string, std::string>> allowed;
                // MoveIt's matrix may name world objects too; michi keeps pairs of robot links (the robot's
                // self-collision pairs).
                for (const auto &e : entries)
                    if (e.second && isLink(e.first.first) && isLink(e.first.second))
                        allowed.insert(e.first);
                for (const auto &d : defaults)
                    if (d.second && isLink(d.first))
                        for (const auto &link : model.links())
                        {
                            const auto pair = std::minmax(d.first, link.name);
                            // A default applies only where no explicit entry names the pair, as MoveIt looks the
                            // default up last.
                            if (link.name != d.first && !entries.count(pair))
                                allowed.insert(pair);
                        }
                scene.allowedCollisions.assign(allowed.begin(), allowed.end());
            }
        }  // namespace

        SrdfModel readSrdf(const std::string &path, const RobotModel &model)
        {
            try
            {
                validity::requireInputFile(path);
            }
            catch (const validity::InputFileError &e)
            {
                throw ProblemError(path, "", e.reason());
            }
            tinyxml2::XMLDocument doc;
            const tinyxml2::XMLError status = doc.LoadFile(path.c_str());
            if (status == tinyxml2::XML_ERROR_FILE_NOT_FOUND || status == tinyxml2::XML_ERROR_FILE_COULD_NOT_BE_OPENED)
                throw ProblemError(path, "", "cannot open the SRDF file");
            if (status != tinyxml2::XML_SUCCESS)
            {
                std::string message = doc.ErrorStr() ? doc.ErrorStr() : "";
                // tinyxml2's message may span lines; michi reports every error on one line.
                std::replace(message.begin(), message.end(), '\n', ' ');
                throw ProblemError(path, "line " + std::to_string(doc.ErrorLineNum()), "not valid XML: " + message);
            }
            const tinyxml2::XMLElement *root = doc.RootElement();
            if (!root || std::string(root->Name()) != "robot")
                throw ProblemError(path, root ? elementKey(root) : "",
                                   "expected an SRDF document (root element <robot>)");
            SrdfModel srdf;
            srdf.robotName = root->Attribute("name") ? root->Attribute("name") : "";

            std::map<std::string, const tinyxml2::XMLElement *> groupElements;
            std::vector<std::string> groupOrder;
            for (const tinyxml2::XMLElement *e = root->FirstChildElement(); e; e = e->NextSiblingElement())
            {
                const std::string name = e->Name();
                if (name == "disable_collisions")
                {
                    const int a = srdfLink(path, e, "link1", model), b = srdfLink(path, e, "link2", model);
                    srdf.disabledCollisions.emplace_back(model.links()[a].name, model.links()[b].name);
                }
                else if (name == "passive_joint")
                    srdfJoint(path, e, model);  // MoveIt's top-level form: the joint must exist, it is not planned
                else if (name == "group")
                {
                    const std::string group = attribute(path, e, "name");
                    if (!groupElements.emplace(group, e).second)
                        throw ProblemError(path, elementKey(e), "group '" + group + "' is defined twice");
                    groupOrder.push_back(group);
                }
            }

            // groups: movable joints as variable indices; subgroups may be defined after their users
            std::map<std::string, std::set<int>> resolved;
            std::set<std::string> resolving;
            std::function<const std::set<int> &(const std::string &, const tinyxml2::XMLElement *)> resolve =
                [&](const std::string &group, const tinyxml2::XMLElement *user) -> const std::set<int> &
            {
                if (resolved.count(group))
                    return resolved[group];
                const auto found = groupElements.find(group);
                if (found == groupElements.end())
                    throw ProblemError(path, elementKey(user), "subgroup '" + group + "': no such group");
                // resolving holds the groups being expanded: meeting one again means a cycle, which would recurse
                // forever.
                if (!resolving.insert(group).second)
                    throw ProblemError(path, elementKey(user), "group '" + group + "' contains itself");
                std::set<int> variables;
                auto addJoint = [&](int joint)
                {
                    const auto &j = model.joints()[joint];
                    if (j.movable())
                        variables.insert(j.variable);
                };
                for (const tinyxml2::XMLElement *c = found->second->FirstChildElement(); c; c = c->NextSiblingElement())
                {
                    const std::string kind = c->Name();
                    if (kind == "joint")
                        addJoint(srdfJoint(path, c, model));
                    else if (kind == "passive_joint")
                        srdfJoint(path, c, model);  // checked, not planned
                    else if (kind == "link")
                    {
                        // MoveIt's rule: a group's <link> brings in the joint above that link.
                        const int link = srdfLink(path, c, "name", model);
                        if (model.links()[link].parentJoint >= 0)
                            addJoint(model.links()[link].parentJoint);
                    }
                    else if (kind == "chain")
                    {
                        const int base = srdfLink(path, c, "base_link", model);
                        const int tip = srdfLink(path, c, "tip_link", model);
                        const std::vector<int> toBase = model.chainTo(base), toTip = model.chainTo(tip);
                        // The chain's joints are those on the path from the root to tip that are not also above base:
                        // the base's path must be a prefix of the tip's.
                        if (toBase.size() > toTip.size() || !std::equal(toBase.begin(), toBase.end(), toTip.begin()))
                            throw ProblemError(path, elementKey(c),
                                               "tip_link '" + model.links()[tip].name + "' is not below base_link '" +
                                                   model.links()[base].name + "'");
                        for (std::size_t k = toBase.size(); k < toTip.size(); ++k)
                            addJoint(toTip[k]);
                    }
                    else if (kind == "group")
                    {
                        const auto &sub = resolve(attribute(path, c, "name"), c);
                        variables.insert(sub.begin(), sub.end());
                    }
                }
                resolving.erase(group);
                return resolved[group] = variables;
            };
            for (const auto &group : groupOrder)
            {
                const auto &variables = resolve(group, groupElements[group]);
                std::vector<std::string> joints;
                for (int v : variables)  // std::set: configuration order
                    joints.push_back(model.variableJoint(v).name);
                if (!joints.empty())
                    srdf.groups[group] = joints;
            }
            return srdf;
        }

        MoveItScene readMoveItScene(const std::string &path, const RobotModel *model)
        {
            MessageReader r(path);
            const YAML::Node root = r.load("PlanningScene");
            MoveItScene scene;

            // frames objects may be given in
            // An empty frame id, world and /world all mean the planning frame; objects given in the robot's root link
            // frame are placed through the robot's base pose.
            std::map<std::string, Eigen::Isometry3d> frames{{"", Eigen::Isometry3d::Identity()},
                                                            {"world", Eigen::Isometry3d::Identity()},
                                                            {"/world", Eigen::Isometry3d::Identity()}};
            if (const YAML::Node fixed = root["fixed_frame_transforms"])
            {
                for (std::size_t i = 0; i < r.optionalSize(fixed, "fixed_frame_transforms"); ++i)
                {
                    const std::string key = "fixed_frame_transforms[" + std::to_string(i) + "]";
                    const std::string child =
                        r.text(r.require(fixed[i], "child_frame_id", key), key + ".child_frame_id");
                    const YAML::Node t = fixed[i]["transform"];
                    frames[child] = t ? r.pose(t, key + ".transform") : Eigen::Isometry3d::Identity();
                }
            }
            if (model)
                frames[model->links()[rootLink(*model)].name] = model->basePose();
            auto frame = [&](const std::string &id, const std::string &key)
            {
                const auto found = frames.find(id);
                if (found != frames.end())
                    return found->second;
                if (model)
                {
                    try
                    {
                        model->linkIndex(id);
                        r.fail(key, "objects in the frame of robot link '" + id +
                                        "' are not supported (expected world or the root link)");
                    }
                    catch (const std::out_of_range &)
                    {
                    }
                }
                r.fail(key, "unknown frame '" + id +
                                "' (expected world, the robot's root link or a "
                                "fixed_frame_transforms child_frame_id)");
            };

            if (const YAML::Node state = root["robot_state"])
                if (state.IsMap() &&
                    r.optionalSize(state["attached_collision_objects"], "robot_state.attached_collision_objects") > 0)
                    // Refused rather than ignored: an attached object moves with the robot and would otherwise be
                    // missing from every check.
                    r.fail("robot_state.attached_collision_objects", "attached objects are not supported");

            const YAML::Node world = root["world"];
            if (world && !world.IsNull())
            {
                if (!world.IsMap())
                    r.fail("world", "expected a mapping (collision_objects, octomap)");
                // An empty octomap is accepted (every PlanningScene message has the field); a non-empty one
                // holds obstacles michi cannot read.
                if (const YAML::Node octomap = world["octomap"])
                    if (octomap.IsMap() && octomap["octomap"] && octomap["octomap"]["data"] &&
                        octomap["octomap"]["data"].size() > 0)
                        r.fail("world.octomap", "octomaps are not supported");
                const YAML::Node objects = world["collision_objects"];
                std::set<std::string> ids;
                for (std::size_t i = 0; i < r.optionalSize(objects, "world.collision_objects"); ++i)
                {
                    const std::string key = "world.collision_objects[" + std::to_string(i) + "]";
                    const YAML::Node o = objects[i];
                    const std::string id = r.text(r.require(o, "id", key), key + ".id");
                    if (id.empty())
                        r.fail(key + ".id", "expected a non-empty object id");
                    if (!ids.insert(id).second)
                        r.fail(key + ".id", "duplicate object id '" + id + "'");
                    if (const YAML::Node op = o["operation"])
                    {
                        const std::string operation = r.text(op, key + ".operation");
                        // One scene file with nothing before it: REMOVE, APPEND and MOVE would refer to objects that do
                        // not exist.
                        if (operation != "0" && operation != "ADD" && operation != "add")
                            r.fail(key + ".operation", "operation '" + operation + "' is not supported (only ADD)");
                    }
                    std::string frameId;
                    if (o["header"] && o["header"].IsMap() && o["header"]["frame_id"])
                        frameId = r.text(o["header"]["frame_id"], key + ".header.frame_id");
                    // Frame, then the object's pose, then each shape's pose within the object (an absent object
                    // pose, as in older messages, is the identity).
                    const Eigen::Isometry3d objectPose =
                        frame(frameId, key + ".header.frame_id") *
                        (o["pose"] ? r.pose(o["pose"], key + ".pose") : Eigen::Isometry3d::Identity());
                    if (r.optionalSize(o["planes"], key + ".planes") > 0)
                        r.fail(key + ".planes", "planes are not supported");

                    auto addShapes =
                        [&](const char *shapesName, const char *posesName, const std::string &prefix, bool primitives)
                    {
                        const std::size_t n = r.optionalSize(o[shapesName], key + "." + shapesName);
                        const std::size_t poses = r.optionalSize(o[posesName], key + "." + posesName);
                        if (poses != n)
                            r.fail(key + "." + posesName,
                                   std::to_string(poses) + " poses for " + std::to_string(n) + " " + shapesName);
                        for (std::size_t k = 0; k < n; ++k)
                        {
                            const std::string index = "[" + std::to_string(k) + "]";
                            Obstacle obstacle;
                            // Object ids are unique (checked above), so these names are unique in the scene too.
                            obstacle.name = id + "/" + prefix + std::to_string(k);
                            obstacle.shape = primitives
                                                 ? readPrimitive(r, o[shapesName][k], key + "." + shapesName + index)
                                                 : readMesh(r, o[shapesName][k], key + "." + shapesName + index);
                            obstacle.pose = objectPose * r.pose(o[posesName][k], key + "." + posesName + index);
                            scene.obstacles.push_back(std::move(obstacle));
                        }
                    };
                    addShapes("primitives", "primitive_poses", "", true);
                    addShapes("meshes", "mesh_poses", "mesh", false);
                }
            }

            if (model)
                if (const YAML::Node acm = root["allowed_collision_matrix"])
                    if (!acm.IsNull())
                        readAllowedCollisions(r, acm, *model, scene);
            return scene;
        }

        MoveItRequest readMoveItRequest(const std::string &path)
        {
            MessageReader r(path);
            const YAML::Node root = r.load("MotionPlanRequest");
            MoveItRequest request;
            request.file = path;
            if (root["group_name"])
                request.groupName = r.text(root["group_name"], "group_name");

            const YAML::Node joints = r.require(r.require(root, "start_state", ""), "joint_state", "start_state");
            const std::string key = "start_state.joint_state";
            request.startNames = r.texts(r.require(joints, "name", key), key + ".name");
            request.startPositions = r.numbers(r.require(joints, "position", key), key + ".position");
            if (request.startNames.size() != request.startPositions.size())
                r.fail(key + ".position", std::to_string(request.startPositions.size()) + " positions for " +
                                              std::to_string(request.startNames.size()) + " names");
            // a joint named twice has two values: which one is meant cannot be told
            for (std::size_t i = 0; i < request.startNames.size(); ++i)
                for (std::size_t j = 0; j < i; ++j)
                    if (request.startNames[i] == request.startNames[j])
                        r.fail(key + ".name[" + std::to_string(i) + "]",
                               "joint '" + request.startNames[i] + "' is named twice");

            const YAML::Node goals = root["goal_constraints"];
            if (!goals || goals.IsNull() || (goals.IsSequence() && goals.size() == 0))
                r.fail("goal_constraints", "missing (required): a joint-space goal in goal_constraints[0]");
            r.sequence(goals, "goal_constraints");
            // goal_constraints lists alternatives; michi plans to the first.
            const YAML::Node goal = goals[0];
            if (!goal.IsMap())
                r.fail("goal_constraints[0]", "expected a mapping (joint_constraints)");
            if (r.optionalSize(goal["joint_constraints"], "goal_constraints[0].joint_constraints") == 0)
                r.fail("goal_constraints[0].joint_constraints",
                       "missing: only joint-space goals (joint_constraints) are supported");
            const YAML::Node list = goal["joint_constraints"];
            for (std::size_t i = 0; i < list.size(); ++i)
            {
                const std::string k = "goal_constraints[0].joint_constraints[" + std::to_string(i) + "]";
                request.goal.emplace_back(r.text(r.require(list[i], "joint_name", k), k + ".joint_name"),
                                          r.number(r.require(list[i], "position", k), k + ".position"));
                for (std::size_t j = 0; j + 1 < request.goal.size(); ++j)
                    if (request.goal[j].first == request.goal.back().first)
                        r.fail(k + ".joint_name", "joint '" + request.goal.back().first + "' is constrained twice");
            }
            return request;
        }

        std::vector<double> jointValues(const std::vector<std::string> &joints, const std::vector<std::string> &names,
                                        const std::vector<double> &positions, const std::string &file,
                                        const std::string &key)
        {
            std::vector<double> values;
            for (const auto &joint : joints)
            {
                // A start state lists joints in any order and often more than the group's: values are found by name.
                const auto found = std::find(names.begin(), names.end(), joint);
                if (found == names.end())
                    throw ProblemError(file, key, "no value for joint '" + joint + "' of the planned group");
                values.push_back(positions[static_cast<std::size_t>(found - names.begin())]);
            }
            return values;
        }
    }  // namespace tools
}  // namespace michi
