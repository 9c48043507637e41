#include <michi/planners/dual_arm/DualArmWorkspace.h>

#include <ompl/util/RandomNumbers.h>

#include <fcl/narrowphase/collision.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace michi
{
    namespace planners
    {
        Eigen::Vector3d WorkspaceGrid::centre(std::size_t index) const
        {
            const auto c = cell(index);
            // Cells are addressed by their lower corner; a cell stands for the point at its centre.
            return origin + resolution * Eigen::Vector3d(c[0] + 0.5, c[1] + 0.5, c[2] + 0.5);
        }

        std::array<int, 3> WorkspaceGrid::cell(std::size_t index) const
        {
            const int i = static_cast<int>(index % size[0]);
            const int j = static_cast<int>((index / size[0]) % size[1]);
            const int k = static_cast<int>(index / (static_cast<std::size_t>(size[0]) * size[1]));
            return {{i, j, k}};
        }

        /** Boolean FCL checks between chosen link pairs of the robot, with a bounding-sphere pre-test. */
        struct DualArmWorkspace::Collision
        {
            struct Piece
            {
                std::shared_ptr<fcl::CollisionGeometryd> geometry;
                Eigen::Isometry3d origin;
                double radius;
            };
            std::vector<std::vector<Piece>> pieces;  ///< per link
            std::vector<std::pair<int, int>> largePairs, smallPairs, betweenPairs;

            bool collide(const std::vector<Eigen::Isometry3d> &links,
                         const std::vector<std::pair<int, int>> &pairs) const
            {
                return firstHit(links, pairs) >= 0;
            }

            /** Index in \e pairs of the first colliding pair, -1 when none. */
            int firstHit(const std::vector<Eigen::Isometry3d> &links,
                         const std::vector<std::pair<int, int>> &pairs) const
            {
                fcl::CollisionRequestd request;
                for (const auto &pair : pairs)
                    for (const auto &a : pieces[pair.first])
                        for (const auto &b : pieces[pair.second])
                        {
                            const Eigen::Isometry3d ta = links[pair.first] * a.origin;
                            const Eigen::Isometry3d tb = links[pair.second] * b.origin;
                            // Bounding spheres about the shapes' origins: most link pairs are far apart, and this test
                            // is far cheaper than FCL's.
                            if ((ta.translation() - tb.translation()).norm() > a.radius + b.radius)
                                continue;
                            fcl::CollisionResultd result;
                            if (fcl::collide(a.geometry.get(), ta, b.geometry.get(), tb, request, result) > 0)
                                return static_cast<int>(&pair - pairs.data());
                        }
                return -1;
            }
        };

        DualArmWorkspace::DualArmWorkspace(validity::RobotModelPtr model, ArmTask large, ArmTask small,
                                           std::vector<double> home, DualArmSettings settings)
            : model_(std::move(model))
            , large_(std::move(large))
            , small_(std::move(small))
            , home_(std::move(home))
            , settings_(settings)
        {
            if (home_.size() != model_->variableCount())
                throw std::invalid_argument("dual arm: home configuration has " + std::to_string(home_.size()) +
                                            " values, the robot has " + std::to_string(model_->variableCount()));
            small_.arm.requireRows(settings_.rows);  // a short arm's full manipulability is 0 everywhere
            for (int v : large_.arm.variables())
                if (small_.arm.owns(v))
                    throw std::invalid_argument("dual arm: the two arms share joint '" +
                                                model_->variableJoint(static_cast<std::size_t>(v)).name + "'");
            if (!(settings_.resolution > 0.) || !(settings_.stirSide > 0.) || !(settings_.stirStep > 0.))
                throw std::invalid_argument("dual arm: resolution, stirring side and step must be positive");

            auto collision = std::make_shared<Collision>();
            const auto &links = model_->links();
            collision->pieces.resize(links.size());
            // A link belongs to the arm of any joint on its chain from the root; links moved by neither arm are the
            // base.
            std::vector<int> owner(links.size(), 0);  // 0: fixed (base), 1: large arm, 2: small arm
            for (std::size_t l = 0; l < links.size(); ++l)
            {
                for (const auto &c : links[l].collisions)
                    for (const auto &g : c.shape->geometries())
                        collision->pieces[l].push_back({g, c.origin, c.shape->boundingRadius()});
                for (int j : model_->chainTo(static_cast<int>(l)))
                {
                    const int v = model_->joints()[j].variable;
                    if (v >= 0 && large_.arm.owns(v))
                        owner[l] = 1;
                    else if (v >= 0 && small_.arm.owns(v))
                        owner[l] = 2;
                }
            }
            for (const auto &p : model_->selfCollisionPairs())
            {
                const int a = owner[p.first], b = owner[p.second];
                // The robot's allowed self-collision pairs split three ways: large arm against small arm (1 + 2), and
                // each arm against itself or the base. Solving one arm then checks only its own pairs, before the other
                // arm is known.
                if (a + b == 3)
                    collision->betweenPairs.push_back(p);
                else if (a == 1 || b == 1)
                    collision->largePairs.push_back(p);
                else if (a == 2 || b == 2)
                    collision->smallPairs.push_back(p);
            }
            collision_ = collision;
        }

        bool DualArmWorkspace::armFree(const ArmTask &task, const std::vector<double> &q) const
        {
            std::vector<Eigen::Isometry3d> links;
            model_->forwardKinematics(q.data(), links);
            return !collision_->collide(links, &task == &large_ ? collision_->largePairs : collision_->smallPairs);
        }

        bool DualArmWorkspace::armsApart(const std::vector<double> &q) const
        {
            std::vector<Eigen::Isometry3d> links;
            model_->forwardKinematics(q.data(), links);
            return !collision_->collide(links, collision_->betweenPairs);
        }

        void DualArmWorkspace::sampleSeeds(const ArmTask &task, std::vector<std::vector<double>> &seeds,
                                           std::vector<Eigen::Vector3d> &tips) const
        {
            // A seeded RNG of its own (not OMPL's global one): the work space is the same in every run with the same
            // settings. The offset (a prime) gives the two arms different sample sequences.
            ompl::RNG rng(settings_.seed + (&task == &large_ ? 0u : 7919u));
            seeds.clear();
            tips.clear();
            std::vector<double> q = home_;
            for (unsigned int s = 0; s < settings_.seedSamples; ++s)
            {
                for (int v : task.arm.variables())
                {
                    const auto &joint = model_->variableJoint(static_cast<std::size_t>(v));
                    q[v] = joint.type == validity::RobotJoint::Type::CONTINUOUS
                               ? rng.uniformReal(-M_PI, M_PI)
                               : rng.uniformReal(joint.lower, joint.upper);
                }
                // pull the sample onto the hand-orientation constraint, keeping roughly its hand position
                HandTarget target = task.hand;
                target.position = task.arm.toolPose(q).translation();
                if (!solveHandIk(task.arm, target, q, settings_.ik))
                    continue;
                std::vector<double> values;
                for (int v : task.arm.variables())
                    values.push_back(q[v]);
                seeds.push_back(values);
                tips.push_back(task.arm.toolPose(q).translation());
            }
        }

        std::vector<std::size_t> DualArmWorkspace::nearestSeeds(const ArmTask &task, const Eigen::Vector3d &p) const
        {
            // Seeds whose hands were nearest the target converge fastest and to a nearby branch of the IK.
            const auto &tips = &task == &large_ ? largeTips_ : smallTips_;
            std::vector<std::pair<double, std::size_t>> d;
            d.reserve(tips.size());
            for (std::size_t i = 0; i < tips.size(); ++i)
                d.emplace_back((tips[i] - p).squaredNorm(), i);
            const std::size_t k = std::min<std::size_t>(settings_.seedsPerCell, d.size());
            std::partial_sort(d.begin(), d.begin() + static_cast<long>(k), d.end());
            std::vector<std::size_t> out;
            for (std::size_t i = 0; i < k; ++i)
                out.push_back(d[i].second);
            return out;
        }

        bool DualArmWorkspace::solveArm(const ArmTask &task, const Eigen::Vector3d &p, std::vector<double> &q,
                                        const std::vector<std::vector<double>> &extraSeeds) const
        {
            HandTarget target = task.hand;
            target.position = p;
            const auto &vars = task.arm.variables();
            const auto &samples = &task == &large_ ? largeSeeds_ : smallSeeds_;
            auto attempt = [&](const std::vector<double> &values)
            {
                for (std::size_t i = 0; i < vars.size(); ++i)
                    q[vars[i]] = values[i];
                return solveHandIk(task.arm, target, q, settings_.ik) && armFree(task, q);
            };
            // The caller's own seeds first (e.g. the solution at a neighbouring point), so solutions stay on one IK
            // branch.
            for (const auto &s : extraSeeds)
                if (attempt(s))
                    return true;
            for (std::size_t s : nearestSeeds(task, p))
                if (attempt(samples[s]))
                    return true;
            return false;
        }

        bool DualArmWorkspace::solveBoth(const Eigen::Vector3d &p, std::vector<double> &q) const
        {
            std::vector<double> large, small;
            for (int v : large_.arm.variables())
                large.push_back(q[v]);
            for (int v : small_.arm.variables())
                small.push_back(q[v]);
            return solveArm(large_, p, q, {large}) && solveArm(small_, p, q, {small}) && armsApart(q);
        }

        StirringMotion DualArmWorkspace::stir(const Eigen::Vector3d &centre, const std::vector<double> &q0) const
        {
            StirringMotion m;
            const double h = 0.5 * settings_.stirSide;
            const std::array<Eigen::Vector3d, 4> corners{
                {centre + Eigen::Vector3d(-h, -h, 0.), centre + Eigen::Vector3d(h, -h, 0.),
                 centre + Eigen::Vector3d(h, h, 0.), centre + Eigen::Vector3d(-h, h, 0.)}};
            // hand targets: a lead-in from the centre to the first corner (not part of the motion), then the square
            // Paper 004, task B: the small arm's hand draws a square (3 cm in the paper) in a horizontal plane, sampled
            // every stirStep. Each target's IK starts from the previous solution, so the states follow one continuous
            // branch.
            const int perEdge = std::max(1, static_cast<int>(std::ceil(settings_.stirSide / settings_.stirStep)));
            std::vector<std::pair<Eigen::Vector3d, bool>> targets;
            const int leadIn =
                std::max(1, static_cast<int>(std::ceil((corners[0] - centre).norm() / settings_.stirStep)));
            for (int s = 1; s < leadIn; ++s)
                targets.emplace_back(centre + (corners[0] - centre) * (static_cast<double>(s) / leadIn), false);
            targets.emplace_back(corners[0], true);
            for (int e = 0; e < 4; ++e)
                for (int s = 1; s <= perEdge; ++s)
                    targets.emplace_back(
                        corners[e] + (corners[(e + 1) % 4] - corners[e]) * (static_cast<double>(s) / perEdge), true);
            std::vector<double> q = q0;
            HandTarget target = small_.hand;
            m.minManipulability = std::numeric_limits<double>::infinity();
            m.jointMotion.assign(small_.arm.size(), 0.);
            for (const auto &t : targets)
            {
                const std::vector<double> before = q;
                target.position = t.first;
                std::ostringstream where;
                where << "(" << t.first.x() << ", " << t.first.y() << ", " << t.first.z() << ")";
                if (!solveHandIk(small_.arm, target, q, settings_.ik))
                {
                    m.failure = "the small arm cannot follow the square at " + where.str();
                    return m;
                }
                double jump = 0.;
                for (int v : small_.arm.variables())
                    jump = std::max(jump, std::abs(q[v] - before[v]));
                // A joint change of more than 0.5 rad between targets a few millimetres apart means IK jumped to
                // another branch: the arm could not follow the square continuously there.
                if (jump > 0.5)
                {
                    m.failure = "the small arm's solution jumps (" + std::to_string(jump) + " rad) at " + where.str();
                    return m;
                }
                // Lead-in targets only bring the hand to the first corner; they are not part of the stirring motion.
                if (!t.second)
                    continue;
                if (!armFree(small_, q) || !armsApart(q))
                {
                    m.failure = "collision at " + where.str();
                    return m;
                }
                // Paper 004: w = sqrt(det(J J^T)) (Yoshikawa), the small arm's dexterity at this point of the motion.
                const double w = small_.arm.manipulability(q, settings_.rows);
                if (!m.states.empty())
                    for (std::size_t i = 0; i < small_.arm.size(); ++i)
                        m.jointMotion[i] +=
                            std::abs(q[small_.arm.variables()[i]] - m.states.back()[small_.arm.variables()[i]]);
                m.states.push_back(q);
                m.hand.push_back(t.first);
                m.manipulability.push_back(w);
                m.minManipulability = std::min(m.minManipulability, w);
            }
            m.valid = true;
            return m;
        }

        bool DualArmWorkspace::moveToNearest(std::uint8_t flag, const Eigen::Vector3d &centroid,
                                             Eigen::Vector3d &position, std::size_t &cell) const
        {
            double best = std::numeric_limits<double>::infinity();
            bool found = false;
            for (std::size_t c = 0; c < flags_.size(); ++c)
                if (flags_[c] & flag)
                {
                    const double d = (grid_.centre(c) - centroid).squaredNorm();
                    if (d < best)
                    {
                        best = d;
                        cell = c;
                        found = true;
                    }
                }
            if (found)
                position = grid_.centre(cell);
            return found;
        }

        std::size_t DualArmWorkspace::count(Flag flag) const
        {
            return static_cast<std::size_t>(std::count_if(flags_.begin(), flags_.end(),
                                                          [flag](std::uint8_t f)
                                                          {
                                                              return (f & flag) != 0;
                                                          }));
        }

        double DualArmWorkspace::volume(Flag flag) const
        {
            return static_cast<double>(count(flag)) * std::pow(grid_.resolution, 3);
        }

        void DualArmWorkspace::compute()
        {
            const auto start = std::chrono::steady_clock::now();
            sampleSeeds(large_, largeSeeds_, largeTips_);
            sampleSeeds(small_, smallSeeds_, smallTips_);
            for (const ArmTask *task : {&large_, &small_})
                if ((task == &large_ ? largeSeeds_ : smallSeeds_).empty())
                    throw std::runtime_error("dual arm: no joint-space sample of the " + task->name + " arm (to '" +
                                             task->arm.tipLinkName() + "') satisfies its hand orientation (" +
                                             std::to_string(settings_.seedSamples) +
                                             " samples pulled onto it by IK within the joint limits)");

            // the grid covers both arms' reach spheres (above the floor z = 0)
            Eigen::Vector3d cl, cs;
            double rl = 0., rs = 0.;
            large_.arm.reachSphere(cl, rl);
            small_.arm.reachSphere(cs, rs);
            Eigen::Vector3d lo = (cl.array() - rl).min(cs.array() - rs).matrix();
            Eigen::Vector3d hi = (cl.array() + rl).max(cs.array() + rs).matrix();
            // Nothing is placed below the floor, so cells there would only cost IK calls.
            lo.z() = std::max(lo.z(), 0.);
            const double res = settings_.resolution;
            grid_.resolution = res;
            for (int a = 0; a < 3; ++a)
            {
                grid_.origin[a] = std::floor(lo[a] / res) * res;
                grid_.size[a] = std::max(1, static_cast<int>(std::ceil((hi[a] - grid_.origin[a]) / res)));
            }
            const std::size_t n = grid_.cells();
            flags_.assign(n, 0);
            smallW_.assign(n, 0.f);
            configs_.assign(n, {});
            std::vector<std::vector<double>> largeQ(n), smallQ(n);

            // each arm's work space by flood fill: IK at the cells holding the constrained samples' hands, then
            // outwards cell by cell, every cell seeded with its solved neighbour's solution (a cell is tried
            // from at most two different neighbours)
            for (int a = 0; a < 2; ++a)
            {
                const ArmTask &task = a == 0 ? large_ : small_;
                auto &solutions = a == 0 ? largeQ : smallQ;
                const auto &samples = a == 0 ? largeSeeds_ : smallSeeds_;
                const auto &tips = a == 0 ? largeTips_ : smallTips_;
                const Eigen::Vector3d centre = a == 0 ? cl : cs;
                const double radius = a == 0 ? rl : rs;
                std::vector<std::uint8_t> tries(n, 0);
                std::vector<std::size_t> queue;
                std::vector<double> q = home_;
                HandTarget target = task.hand;
                auto attempt = [&](std::size_t c, const std::vector<double> &seed)
                {
                    // Each cell is solved once; a failed cell may be tried again from one other neighbour, whose seed
                    // may be on a better IK branch, but not from all six (the fill would cost six IK runs per
                    // unreachable cell).
                    if (!solutions[c].empty() || tries[c] >= 2)
                        return;
                    const Eigen::Vector3d p = grid_.centre(c);
                    // Outside the reach sphere IK cannot succeed: skip it rather than let it run to its iteration
                    // limit.
                    if ((p - centre).norm() > radius)
                        return;
                    ++tries[c];
                    for (std::size_t i = 0; i < seed.size(); ++i)
                        q[task.arm.variables()[i]] = seed[i];
                    target.position = p;
                    if (!solveHandIk(task.arm, target, q, settings_.ik) || !armFree(task, q))
                        return;
                    std::vector<double> values;
                    for (int v : task.arm.variables())
                        values.push_back(q[v]);
                    solutions[c] = values;
                    flags_[c] |= a == 0 ? REACH_LARGE : REACH_SMALL;
                    queue.push_back(c);
                };
                for (std::size_t s = 0; s < samples.size(); ++s)
                {
                    const Eigen::Vector3d rel = (tips[s] - grid_.origin) / res;
                    const int i = static_cast<int>(std::floor(rel.x())), j = static_cast<int>(std::floor(rel.y())),
                              k = static_cast<int>(std::floor(rel.z()));
                    if (i >= 0 && j >= 0 && k >= 0 && i < grid_.size[0] && j < grid_.size[1] && k < grid_.size[2])
                        attempt(grid_.index(i, j, k), samples[s]);
                }
                // Breadth-first: the queue grows while it is walked, each solved cell seeding its six face neighbours.
                for (std::size_t head = 0; head < queue.size(); ++head)
                {
                    const std::size_t c = queue[head];
                    const auto ijk = grid_.cell(c);
                    for (int d = 0; d < 6; ++d)
                    {
                        auto nb = ijk;
                        nb[d / 2] += d % 2 ? 1 : -1;
                        if (nb[d / 2] < 0 || nb[d / 2] >= grid_.size[d / 2])
                            continue;
                        attempt(grid_.index(nb[0], nb[1], nb[2]), solutions[c]);
                    }
                }
            }
            for (std::size_t c = 0; c < n; ++c)
            {
                if (flags_[c] & REACH_SMALL)
                {
                    std::vector<double> both = home_;
                    for (std::size_t i = 0; i < small_.arm.size(); ++i)
                        both[small_.arm.variables()[i]] = smallQ[c][i];
                    smallW_[c] = static_cast<float>(small_.arm.manipulability(both, settings_.rows));
                    if (flags_[c] & REACH_LARGE)
                    {
                        for (std::size_t i = 0; i < large_.arm.size(); ++i)
                            both[large_.arm.variables()[i]] = largeQ[c][i];
                        if (armsApart(both))
                        {
                            // Paper 004: the common work space is where both arms reach with their fixed hand
                            // orientations and do not collide.
                            flags_[c] |= COMMON;
                            configs_[c] = both;
                            // The manipulability area: the small arm's w above the threshold (0.0040 in the paper).
                            if (smallW_[c] > settings_.threshold)
                                flags_[c] |= AREA;
                        }
                    }
                }
            }
            const auto mid = std::chrono::steady_clock::now();
            workspaceSeconds_ = std::chrono::duration<double>(mid - start).count();
            if (count(COMMON) == 0)
            {
                std::size_t both = 0;
                for (auto f : flags_)
                    both += (f & REACH_LARGE) && (f & REACH_SMALL);
                // "both N but collide there" only when some cell is reached by both: with none, the arms' work
                // spaces do not overlap at all.
                throw std::runtime_error(
                    "dual arm: the two arms have no common work space (large arm reaches " +
                    std::to_string(count(REACH_LARGE)) + " cells, small arm " + std::to_string(count(REACH_SMALL)) +
                    (both == 0 ? std::string(", no cell is reached by both")
                               : ", both " + std::to_string(both) + " but the arms collide in every one of them") +
                    ")");
            }

            auto centroidOf = [this](std::uint8_t flag)
            {
                Eigen::Vector3d sum = Eigen::Vector3d::Zero();
                std::size_t k = 0;
                for (std::size_t c = 0; c < flags_.size(); ++c)
                    if (flags_[c] & flag)
                    {
                        sum += grid_.centre(c);
                        ++k;
                    }
                return Eigen::Vector3d(sum / static_cast<double>(k));
            };
            // a work position: the centroid itself when both arms reach it (and, for B, stir there), else the
            // nearest cell with the flag
            auto place = [this](std::uint8_t flag, const Eigen::Vector3d &centroid, Eigen::Vector3d &position,
                                std::vector<double> &config)
            {
                std::size_t cell = 0;
                moveToNearest(flag, centroid, position, cell);
                config = configs_[cell];
                std::vector<double> atCentroid = configs_[cell];
                if (solveBoth(centroid, atCentroid))
                {
                    if (flag == STIR)
                    {
                        const StirringMotion m = stir(centroid, atCentroid);
                        // For task B the whole stirring motion must stay in the manipulability area, not only its
                        // centre.
                        if (!m.valid || !(m.minManipulability > settings_.threshold))
                            return;
                    }
                    position = centroid;
                    config = atCentroid;
                }
            };
            // Task A (hand-over): the centroid of the common work space is the work position (paper 004).
            centroidA_ = centroidOf(COMMON);
            place(COMMON, centroidA_, positionA_, configA_);

            // Task B (stirring): the positions from which the whole square keeps w above the threshold; their centroid
            // is the work position.
            // why the cells failed, for the error when none succeeds: the square could not be completed (the first
            // reason kept), or it was completed but w dropped to the threshold or below on the way
            std::size_t incomplete = 0, belowThreshold = 0;
            std::string firstFailure;
            double bestMinW = 0.;
            for (std::size_t c = 0; c < n; ++c)
                if (flags_[c] & AREA)
                {
                    const StirringMotion m = stir(grid_.centre(c), configs_[c]);
                    if (m.valid && m.minManipulability > settings_.threshold)
                        flags_[c] |= STIR;
                    else if (!m.valid)
                    {
                        if (incomplete++ == 0)
                            firstFailure = m.failure;
                    }
                    else
                    {
                        ++belowThreshold;
                        bestMinW = std::max(bestMinW, m.minManipulability);
                    }
                }
            stirSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - mid).count();
            if (count(STIR) == 0)
            {
                // %g-like numbers: a threshold of 1e-9 printed with 6 fixed decimals read "w > 0.000000"
                std::ostringstream why;
                why << "dual arm: no position keeps the whole stirring motion in the manipulability area (w > "
                    << settings_.threshold << "): ";
                if (count(AREA) == 0)
                {
                    float maxW = 0.f;
                    for (std::size_t c = 0; c < n; ++c)
                        if (flags_[c] & COMMON)
                            maxW = std::max(maxW, smallW_[c]);
                    why << "no cell of the common work space (" << count(COMMON)
                        << " cells) has the small arm's w above it (the highest is " << maxW << ")";
                }
                else
                {
                    why << "of the " << count(AREA) << " cells of the manipulability area, ";
                    if (incomplete > 0)
                        why << incomplete << " cannot complete the stirring square of side " << settings_.stirSide
                            << " m (first: " << firstFailure << ")" << (belowThreshold > 0 ? " and " : "");
                    if (belowThreshold > 0)
                        why << belowThreshold << " complete it but w drops to the threshold or below on the way "
                            << "(the best keeps w >= " << bestMinW << ")";
                }
                throw std::runtime_error(why.str());
            }
            centroidB_ = centroidOf(STIR);
            place(STIR, centroidB_, positionB_, configB_);
        }
    }  // namespace planners
}  // namespace michi
