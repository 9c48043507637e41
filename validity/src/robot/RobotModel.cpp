#include <michi/validity/robot/RobotModel.h>
#include <michi/validity/InputFile.h>
#include <michi/validity/Limits.h>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>
#include <urdf_world/types.h>

#include <boost/filesystem.hpp>

#include <algorithm>
#include <fstream>
#include <functional>
#include <mutex>
#include <set>
#include <sstream>
#include <string>

namespace fs = boost::filesystem;

namespace michi
{
    namespace validity
    {
        namespace
        {
            /** Collects urdfdom's console_bridge messages so a parse failure becomes one line naming the file. */
            class CollectingHandler : public console_bridge::OutputHandler
            {
            public:
                void log(const std::string &text, console_bridge::LogLevel level, const char *, int) override
                {
                    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && first.empty())
                        first = text;
                }
                std::string first;
            };

            std::mutex consoleMutex;  // console_bridge's handler is process-wide

            /** A URDF origin as a transform. Every number is checked first: a nan or infinite origin used to make
                FCL's bounding boxes nan, and a link with such a box never collides with anything. */
            Eigen::Isometry3d toIsometry(const urdf::Pose &p, const std::string &what)
            {
                const double values[] = {p.position.x, p.position.y, p.position.z};
                const char *axes[] = {"x", "y", "z"};
                for (int i = 0; i < 3; ++i)
                    if (!isGeometryValue(values[i]))
                        throw UrdfError(what + " origin " + axes[i] + " " + geometryValueProblem(values[i]));
                const double q[] = {p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z};
                for (double v : q)
                    if (!std::isfinite(v))
                        throw UrdfError(what + " origin rotation is not finite");
                // A zero quaternion has no direction: normalizing it below would give nan.
                if (std::abs(q[0]) + std::abs(q[1]) + std::abs(q[2]) + std::abs(q[3]) < 1e-12)
                    throw UrdfError(what + " origin rotation is zero");
                Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
                t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
                // Normalized: a file's quaternion is rounded, and a rotation that is not orthonormal would stretch
                // the geometry.
                t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                                 .normalized()
                                 .toRotationMatrix();
                return t;
            }

            /** How deep the elements of \e xml nest (a scan of the tags, skipping comments, declarations, CDATA
                and quoted attribute values). urdfdom's TinyXML parser recurses once per level and overflows the
                stack on a file nested 200,000 deep; a URDF nests a handful of levels. Malformed text ends the scan
                early: the parser then says what is wrong. */
            std::size_t xmlNestingDepth(const std::string &xml)
            {
                std::size_t depth = 0, deepest = 0, i = 0;
                const std::size_t n = xml.size();
                auto skipPast = [&](const char *end)
                {
                    const std::size_t at = xml.find(end, i);
                    i = at == std::string::npos ? n : at + std::char_traits<char>::length(end);
                };
                while ((i = xml.find('<', i)) != std::string::npos)
                {
                    if (xml.compare(i, 4, "<!--") == 0)
                        skipPast("-->");
                    else if (xml.compare(i, 9, "<![CDATA[") == 0)
                        skipPast("]]>");
                    else if (xml.compare(i, 2, "<?") == 0)
                        skipPast("?>");
                    else if (xml.compare(i, 2, "<!") == 0)
                        skipPast(">");
                    else
                    {
                        const bool closing = i + 1 < n && xml[i + 1] == '/';
                        // to the tag's end, past quoted values (which may hold '>')
                        char quote = 0;
                        std::size_t j = i + 1;
                        for (; j < n && (quote != 0 || xml[j] != '>'); ++j)
                            if (quote != 0 ? xml[j] == quote : (xml[j] == '"' || xml[j] == '\''))
                                quote = quote != 0 ? 0 : xml[j];
                        if (j >= n)
                            break;
                        const bool selfClosing = xml[j - 1] == '/';
                        if (closing)
                            depth = depth > 0 ? depth - 1 : 0;
                        else if (!selfClosing)
                            deepest = std::max(deepest, ++depth);
                        i = j + 1;
                    }
                }
                return deepest;
            }

            std::string resolveMesh(const std::string &uri, const std::string &baseDir, const std::string &source)
            {
                std::vector<fs::path> candidates;
                const std::string pkg = "package://", file = "file://";
                if (uri.rfind(pkg, 0) == 0)
                {
                    const fs::path rest = uri.substr(pkg.size());  // <package>/<path>
                    fs::path inside;
                    for (auto it = ++rest.begin(); it != rest.end(); ++it)
                        inside /= *it;
                    // Without ROS there is no package index: try the layouts robots ship in (the package folder beside
                    // or above the URDF, or the URDF inside the package itself, as MotionBenchMaker's Panda is laid
                    // out).
                    candidates = {fs::path(baseDir) / rest, fs::path(baseDir) / ".." / rest,
                                  fs::path(baseDir) / inside};
                }
                else if (uri.rfind(file, 0) == 0)
                    candidates = {fs::path(uri.substr(file.size()))};
                else if (fs::path(uri).is_absolute())
                    candidates = {fs::path(uri)};
                else
                    candidates = {fs::path(baseDir) / uri};
                for (const auto &c : candidates)
                    if (fs::exists(c))
                        return c.lexically_normal().string();
                throw UrdfError(source + ": mesh '" + uri + "' not found (looked in " + candidates.front().string() +
                                ")");
            }
        }  // namespace

        std::shared_ptr<RobotModel> RobotModel::fromUrdfFile(const std::string &path)
        {
            std::string xml;
            try
            {
                xml = readInputFile(path);
            }
            catch (const InputFileError &e)
            {
                throw UrdfError(path + ": cannot read URDF file: " + e.reason());
            }
            const std::string baseDir = fs::absolute(fs::path(path)).parent_path().string();
            return fromUrdfString(xml, path, baseDir);
        }

        std::shared_ptr<RobotModel> RobotModel::fromUrdfString(const std::string &xml, const std::string &source,
                                                               const std::string &baseDir)
        {
            // a URDF nests a handful of levels (robot, link, collision, geometry, shape)
            const std::size_t maxDepth = 100;
            if (xmlNestingDepth(xml) > maxDepth)
                throw UrdfError(source + ": not a valid URDF: elements nested more than " + std::to_string(maxDepth) +
                                " levels deep");
            urdf::ModelInterfaceSharedPtr urdfModel;
            {
                std::lock_guard<std::mutex> lock(consoleMutex);
                CollectingHandler handler;
                // The handler is a local: it must be removed (restorePreviousOutputHandler) on every path out of this
                // block, and the mutex keeps two threads from swapping the process-wide handler under each other.
                console_bridge::useOutputHandler(&handler);
                try
                {
                    urdfModel = urdf::parseURDF(xml);
                }
                catch (const std::exception &e)
                {
                    // urdfdom throws on some malformed input (bad numbers) instead of logging it; both end in the same
                    // one-line error.
                    handler.first = e.what();
                }
                console_bridge::restorePreviousOutputHandler();
                if (!urdfModel)
                    throw UrdfError(source + ": not a valid URDF: " +
                                    (handler.first.empty() ? std::string("parse failed") : handler.first));
                // urdfdom logs some errors and goes on without the element: a collision origin of "nan 0 0" is
                // "Could not parse collision element" and the link is left without geometry, so paths would pass
                // through obstacles. Any error it reports rejects the file.
                if (!handler.first.empty())
                    throw UrdfError(source + ": not a valid URDF: " + handler.first);
            }
            if (!urdfModel->getRoot())
                throw UrdfError(source + ": URDF has no root link");

            // urdfdom links hold their children by shared_ptr: a self-loop joint is a cycle that would never be
            // freed, so the children are dropped when this function leaves, whichever way it leaves
            struct BreakCycles
            {
                urdf::ModelInterfaceSharedPtr model;
                ~BreakCycles()
                {
                    for (auto &kv : model->links_)
                    {
                        kv.second->child_links.clear();
                        kv.second->child_joints.clear();
                    }
                }
            } breakCycles{urdfModel};
            std::shared_ptr<RobotModel> model(new RobotModel);
            model->name_ = urdfModel->getName();
            model->source_ = source;

            // breadth-first over the tree so every parent precedes its children
            std::vector<urdf::LinkConstSharedPtr> queue{urdfModel->getRoot()};
            std::map<std::string, int> linkIds;
            std::set<std::string> reached{urdfModel->getRoot()->name};
            for (std::size_t head = 0; head < queue.size(); ++head)
            {
                const auto ulink = queue[head];
                RobotLink link;
                link.name = ulink->name;
                for (const auto &collision : ulink->collision_array)
                {
                    if (!collision || !collision->geometry)
                        continue;
                    LinkCollision lc;
                    lc.origin = toIsometry(collision->origin, source + ": link '" + ulink->name + "': <collision>");
                    const auto &g = collision->geometry;
                    try
                    {
                        switch (g->type)
                        {
                            case urdf::Geometry::BOX:
                            {
                                const auto *b = static_cast<const urdf::Box *>(g.get());
                                lc.shape = Shape::box(Eigen::Vector3d(b->dim.x, b->dim.y, b->dim.z));
                                break;
                            }
                            case urdf::Geometry::SPHERE:
                                lc.shape = Shape::sphere(static_cast<const urdf::Sphere *>(g.get())->radius);
                                break;
                            case urdf::Geometry::CYLINDER:
                            {
                                const auto *c = static_cast<const urdf::Cylinder *>(g.get());
                                lc.shape = Shape::cylinder(c->radius, c->length);
                                break;
                            }
                            case urdf::Geometry::MESH:
                            {
                                const auto *m = static_cast<const urdf::Mesh *>(g.get());
                                lc.shape = Shape::meshFromFile(resolveMesh(m->filename, baseDir, source),
                                                               Eigen::Vector3d(m->scale.x, m->scale.y, m->scale.z));
                                break;
                            }
                        }
                    }
                    // Errors from resolveMesh() already name the file and the URI; only the others need the link's name
                    // added.
                    catch (const UrdfError &)
                    {
                        throw;
                    }
                    catch (const std::exception &e)
                    {
                        throw UrdfError(source + ": link '" + ulink->name + "': " + e.what());
                    }
                    link.collisions.push_back(lc);
                }
                linkIds[link.name] = static_cast<int>(model->links_.size());
                model->links_.push_back(std::move(link));
                for (const auto &child : ulink->child_links)
                {
                    // urdfdom accepts a joint whose child is its own parent, or a loop of joints: the walk would
                    // then never end (a tree reaches every link once)
                    if (!child || !reached.insert(child->name).second)
                        throw UrdfError(source + ": link '" + (child ? child->name : std::string("?")) +
                                        "' is reached twice: the joints form a cycle (a URDF must be a tree)");
                    queue.push_back(child);
                }
            }
            // a joint whose child is its own parent makes urdfdom give that link a parent, so it is no root, yet no
            // walk from the root reaches it: it and everything below it would silently leave collision checking
            if (queue.size() != urdfModel->links_.size())
                for (const auto &kv : urdfModel->links_)
                    if (!reached.count(kv.first))
                        throw UrdfError(source + ": link '" + kv.first + "' is not connected to the root '" +
                                        urdfModel->getRoot()->name + "' (a joint cycle?)");
            // joints in the same breadth-first order (the parent joint of each non-root link)
            for (std::size_t l = 1; l < queue.size(); ++l)
            {
                const auto &ujoint = queue[l]->parent_joint;
                RobotJoint joint;
                joint.name = ujoint->name;
                joint.parentLink = linkIds.at(ujoint->parent_link_name);
                joint.childLink = linkIds.at(ujoint->child_link_name);
                joint.origin =
                    toIsometry(ujoint->parent_to_joint_origin_transform, source + ": joint '" + joint.name + "':");
                Eigen::Vector3d axis(ujoint->axis.x, ujoint->axis.y, ujoint->axis.z);
                switch (ujoint->type)
                {
                    case urdf::Joint::REVOLUTE:
                        joint.type = RobotJoint::Type::REVOLUTE;
                        break;
                    case urdf::Joint::CONTINUOUS:
                        joint.type = RobotJoint::Type::CONTINUOUS;
                        break;
                    case urdf::Joint::PRISMATIC:
                        joint.type = RobotJoint::Type::PRISMATIC;
                        break;
                    case urdf::Joint::FIXED:
                        joint.type = RobotJoint::Type::FIXED;
                        break;
                    default:
                        throw UrdfError(source + ": joint '" + joint.name +
                                        "': floating and planar joints are not supported");
                }
                if (joint.movable())
                {
                    if (!axis.allFinite())
                        throw UrdfError(source + ": joint '" + joint.name + "': axis is not finite");
                    // scaled by its largest component first: the norm of (0, 0, 1e300) overflows to inf, and
                    // normalized() would then give a zero axis, a joint that silently never moves
                    const double largest = axis.cwiseAbs().maxCoeff();
                    if (largest > 0.)
                        axis /= largest;
                    if (axis.norm() < 1e-12)
                        throw UrdfError(source + ": joint '" + joint.name + "': zero axis");
                    // URDF allows an axis of any length; the kinematics needs a unit axis so that q is radians (or
                    // metres).
                    joint.axis = axis.normalized();
                    if (joint.type == RobotJoint::Type::CONTINUOUS)
                    {
                        // A continuous joint has no limits in URDF; planning spaces treat it as an angle on [-pi, pi]
                        // that wraps.
                        joint.lower = -M_PI;
                        joint.upper = M_PI;
                    }
                    else
                    {
                        if (!ujoint->limits)
                            throw UrdfError(source + ": joint '" + joint.name + "': <limit> missing");
                        joint.lower = ujoint->limits->lower;
                        joint.upper = ujoint->limits->upper;
                        if (!isGeometryValue(joint.lower) || !isGeometryValue(joint.upper))
                            throw UrdfError(
                                source + ": joint '" + joint.name + "': limit " +
                                geometryValueProblem(isGeometryValue(joint.lower) ? joint.upper : joint.lower));
                        if (!(joint.lower <= joint.upper))
                            throw UrdfError(source + ": joint '" + joint.name + "': lower limit above upper");
                    }
                    // Configuration vectors list the movable joints in this breadth-first order.
                    joint.variable = static_cast<int>(model->variableJoints_.size());
                    model->variableJoints_.push_back(static_cast<int>(model->joints_.size()));
                }
                model->links_[joint.childLink].parentJoint = static_cast<int>(model->joints_.size());
                model->jointOrder_.push_back(static_cast<int>(model->joints_.size()));
                model->joints_.push_back(joint);
            }
            // URDF <mimic> on a movable joint: it moves with the joint it names. Resolved once every joint is known;
            // a name that is no movable joint of this URDF would leave the mimic joint wherever its own value put it,
            // not where the real robot holds it.
            for (std::size_t l = 1; l < queue.size(); ++l)
            {
                const auto &ujoint = queue[l]->parent_joint;
                const int self = model->jointIndex(ujoint->name);
                RobotJoint &joint = model->joints_[static_cast<std::size_t>(self)];
                if (!ujoint->mimic || !joint.movable())
                    continue;
                const std::string what =
                    source + ": joint '" + joint.name + "': <mimic joint=\"" + ujoint->mimic->joint_name + "\">";
                int master = -1;
                try
                {
                    master = model->jointIndex(ujoint->mimic->joint_name);
                }
                catch (const std::out_of_range &)
                {
                    throw UrdfError(what + " names no joint of this URDF");
                }
                if (!model->joints_[master].movable() || master == self)
                    throw UrdfError(what + " must name another movable joint");
                if (!isGeometryValue(ujoint->mimic->multiplier) || !isGeometryValue(ujoint->mimic->offset))
                    throw UrdfError(what + ": multiplier or offset " +
                                    geometryValueProblem(isGeometryValue(ujoint->mimic->multiplier)
                                                             ? ujoint->mimic->offset
                                                             : ujoint->mimic->multiplier));
                joint.mimic = master;
                joint.mimicMultiplier = ujoint->mimic->multiplier;
                joint.mimicOffset = ujoint->mimic->offset;
            }
            for (const auto &joint : model->joints_)
                if (joint.mimic >= 0 && model->joints_[joint.mimic].mimic >= 0)
                    throw UrdfError(source + ": joint '" + joint.name + "' mimics '" +
                                    model->joints_[joint.mimic].name + "', itself a mimic joint: not supported");
            model->computeDisplacementBounds();
            return model;
        }

        void RobotModel::applyMimic(double *q) const
        {
            for (const auto &joint : joints_)
                if (joint.mimic >= 0)
                    q[joint.variable] = joint.mimicMultiplier * q[joints_[joint.mimic].variable] + joint.mimicOffset;
        }

        const RobotJoint *RobotModel::mimicTiedTo(std::size_t variable) const
        {
            const RobotJoint &joint = variableJoint(variable);
            for (const RobotJoint &other : joints_)
                if (other.mimic >= 0 && (&other == &joint || &joints_[other.mimic] == &joint))
                    return &other;
            return nullptr;
        }

        std::vector<std::string> RobotModel::variableNames() const
        {
            std::vector<std::string> names;
            for (int j : variableJoints_)
                names.push_back(joints_[j].name);
            return names;
        }

        int RobotModel::linkIndex(const std::string &name) const
        {
            for (std::size_t i = 0; i < links_.size(); ++i)
                if (links_[i].name == name)
                    return static_cast<int>(i);
            throw std::out_of_range("robot '" + name_ + "' has no link '" + name + "'");
        }

        int RobotModel::jointIndex(const std::string &name) const
        {
            for (std::size_t i = 0; i < joints_.size(); ++i)
                if (joints_[i].name == name)
                    return static_cast<int>(i);
            throw std::out_of_range("robot '" + name_ + "' has no joint '" + name + "'");
        }

        int RobotModel::variableIndex(const std::string &jointName) const
        {
            const int j = jointIndex(jointName);
            if (joints_[j].variable < 0)
                throw std::out_of_range("joint '" + jointName + "' of robot '" + name_ + "' is fixed");
            return joints_[j].variable;
        }

        void RobotModel::forwardKinematics(const double *q, std::vector<Eigen::Isometry3d> &linkPoses) const
        {
            linkPoses.resize(links_.size());
            linkPoses[rootLink_] = basePose_;
            // jointOrder_ is breadth-first, so a joint's parent link is posed before the joint is reached.
            for (int j : jointOrder_)
            {
                const RobotJoint &joint = joints_[j];
                // URDF's convention: child = parent * joint origin * motion, the axis given in the joint frame.
                Eigen::Isometry3d t = linkPoses[joint.parentLink] * joint.origin;
                if (joint.type == RobotJoint::Type::REVOLUTE || joint.type == RobotJoint::Type::CONTINUOUS)
                {
                    // About a coordinate axis (most arms' URDFs): two columns mix, where the general rotation builds
                    // a matrix from the axis and multiplies by it (8 % of an FCL state check of the xArm6, perf)
                    const Eigen::Vector3d &a = joint.axis;
                    const int k = a.y() == 0. && a.z() == 0.   ? 0
                                  : a.x() == 0. && a.z() == 0. ? 1
                                  : a.x() == 0. && a.y() == 0. ? 2
                                                               : -1;
                    if (k >= 0 && std::abs(a[k]) == 1.)
                    {
                        const double angle = a[k] * q[joint.variable];
                        const double s = std::sin(angle), c = std::cos(angle);
                        const int i = (k + 1) % 3, j = (k + 2) % 3;
                        auto r = t.linear();
                        const Eigen::Vector3d ci = r.col(i), cj = r.col(j);
                        r.col(i) = c * ci + s * cj;
                        r.col(j) = c * cj - s * ci;
                    }
                    else
                        t.rotate(Eigen::AngleAxisd(q[joint.variable], joint.axis));
                }
                else if (joint.type == RobotJoint::Type::PRISMATIC)
                    t.translate(q[joint.variable] * joint.axis);
                linkPoses[joint.childLink] = t;
            }
        }

        std::vector<Eigen::Isometry3d> RobotModel::forwardKinematics(const std::vector<double> &q) const
        {
            if (q.size() != variableCount())
                throw std::invalid_argument("configuration has " + std::to_string(q.size()) + " values, robot '" +
                                            name_ + "' has " + std::to_string(variableCount()) + " joints");
            std::vector<Eigen::Isometry3d> poses;
            forwardKinematics(q.data(), poses);
            return poses;
        }

        std::vector<int> RobotModel::chainTo(int link) const
        {
            std::vector<int> chain;
            for (int l = link; links_[l].parentJoint >= 0; l = joints_[links_[l].parentJoint].parentLink)
                chain.push_back(links_[l].parentJoint);
            std::reverse(chain.begin(), chain.end());
            return chain;
        }

        Eigen::MatrixXd RobotModel::jacobian(const std::vector<double> &q, int link,
                                             const Eigen::Vector3d &pointInLink) const
        {
            const auto poses = forwardKinematics(q);
            const Eigen::Vector3d p = poses[link] * pointInLink;
            // Rows 0-2: the point's linear velocity; rows 3-5: the link's angular velocity. Joints off the chain to the
            // link stay zero columns.
            Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(6, static_cast<long>(variableCount()));
            for (int j : chainTo(link))
            {
                const RobotJoint &joint = joints_[j];
                if (!joint.movable())
                    continue;
                // the joint frame after its own motion has the same axis direction and origin as before it
                const Eigen::Isometry3d frame = poses[joint.childLink];
                const Eigen::Vector3d axis = frame.linear() * joint.axis;
                if (joint.type == RobotJoint::Type::PRISMATIC)
                    jac.block<3, 1>(0, joint.variable) = axis;
                else
                {
                    jac.block<3, 1>(0, joint.variable) = axis.cross(p - frame.translation());
                    jac.block<3, 1>(3, joint.variable) = axis;
                }
            }
            return jac;
        }

        void RobotModel::allowCollision(const std::string &linkA, const std::string &linkB)
        {
            const int a = linkIndex(linkA), b = linkIndex(linkB);
            // Stored as (smaller, larger): an allowed pair has no order.
            allowed_.insert({std::min(a, b), std::max(a, b)});
        }

        bool RobotModel::isCollisionAllowed(int linkA, int linkB) const
        {
            return allowed_.count({std::min(linkA, linkB), std::max(linkA, linkB)}) > 0;
        }

        std::vector<std::pair<int, int>> RobotModel::selfCollisionPairs() const
        {
            // links welded together by fixed joints form one rigid group; a group touches its neighbours
            std::vector<int> group(links_.size());
            for (std::size_t l = 0; l < links_.size(); ++l)
            {
                int g = static_cast<int>(l);
                while (links_[g].parentJoint >= 0 && !joints_[links_[g].parentJoint].movable())
                    g = joints_[links_[g].parentJoint].parentLink;
                group[l] = g;
            }
            // Links joined by one movable joint touch at the joint by construction; checking them would reject every
            // state.
            auto parentGroup = [&](int l)
            {
                const int root = group[l];
                return links_[root].parentJoint >= 0 ? group[joints_[links_[root].parentJoint].parentLink] : -1;
            };
            std::vector<std::pair<int, int>> pairs;
            for (std::size_t a = 0; a < links_.size(); ++a)
                for (std::size_t b = a + 1; b < links_.size(); ++b)
                {
                    const int ia = static_cast<int>(a), ib = static_cast<int>(b);
                    if (links_[a].collisions.empty() || links_[b].collisions.empty())
                        continue;
                    if (group[a] == group[b] || parentGroup(ia) == group[b] || parentGroup(ib) == group[a])
                        continue;
                    if (isCollisionAllowed(ia, ib))
                        continue;
                    pairs.emplace_back(ia, ib);
                }
            return pairs;
        }

        void RobotModel::computeDisplacementBounds()
        {
            // reach[l]: radius about link l's origin that contains l and everything below it, for any motion
            std::vector<double> reach(links_.size(), 0.);
            for (std::size_t l = 0; l < links_.size(); ++l)
                for (const auto &c : links_[l].collisions)
                    reach[l] = std::max(reach[l], c.origin.translation().norm() + c.shape->boundingRadius());
            // Reverse breadth-first order: a child's reach is complete before its parent reads it. The reach adds up
            // along the tree by the triangle inequality (joint offset, prismatic stroke, then the child's reach).
            for (auto it = jointOrder_.rbegin(); it != jointOrder_.rend(); ++it)
            {
                const RobotJoint &joint = joints_[*it];
                // a prismatic joint carries its child up to max(|lower|, |upper|) away from the joint origin
                const double extension = joint.type == RobotJoint::Type::PRISMATIC
                                             ? std::max(std::abs(joint.lower), std::abs(joint.upper))
                                             : 0.;
                reach[joint.parentLink] = std::max(
                    reach[joint.parentLink], joint.origin.translation().norm() + extension + reach[joint.childLink]);
            }
            displacementBounds_.assign(variableJoints_.size(), 0.);
            for (std::size_t v = 0; v < variableJoints_.size(); ++v)
            {
                const RobotJoint &joint = joints_[variableJoints_[v]];
                // a rotation by dq moves a point at distance rho from the axis by at most rho * dq;
                // a translation moves every point below the joint by dq (prismatic reach then adds nothing)
                displacementBounds_[v] = joint.type == RobotJoint::Type::PRISMATIC ? 1. : reach[joint.childLink];
            }
            // per link: walk up from each link, growing the distance from the current frame to its geometry
            linkDisplacementBounds_.assign(variableJoints_.size(), std::vector<double>(links_.size(), 0.));
            for (std::size_t l = 0; l < links_.size(); ++l)
            {
                double distance = 0.;  // from the current frame's origin to link l's geometry, any configuration
                for (const auto &c : links_[l].collisions)
                    distance = std::max(distance, c.origin.translation().norm() + c.shape->boundingRadius());
                if (links_[l].collisions.empty())
                    continue;
                // Walking up the chain: at each joint, distance is how far link l's geometry can be from that joint's
                // origin, which is how far a radian of that joint can move it. Each step up adds the joint's offset
                // (and stroke) to the distance.
                for (int j = links_[l].parentJoint; j >= 0; j = links_[joints_[j].parentLink].parentJoint)
                {
                    const RobotJoint &joint = joints_[j];
                    if (joint.variable >= 0)
                        linkDisplacementBounds_[joint.variable][l] =
                            joint.type == RobotJoint::Type::PRISMATIC ? 1. : distance;
                    const double extension = joint.type == RobotJoint::Type::PRISMATIC
                                                 ? std::max(std::abs(joint.lower), std::abs(joint.upper))
                                                 : 0.;
                    distance += joint.origin.translation().norm() + extension;
                }
            }
        }
    }  // namespace validity
}  // namespace michi
