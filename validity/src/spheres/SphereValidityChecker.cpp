#include <michi/validity/spheres/SphereValidityChecker.h>

#include "SelfPairCache.h"
#include "SelfPairTable.h"
#include "SphereKinematics.h"
#include "SphereObstacles.h"

#include <ompl/base/SpaceInformation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <thread>
#include <tuple>

namespace michi
{
    namespace validity
    {
        /** Per-thread working arrays of a query. */
        struct SphereValidityChecker::Scratch
        {
            std::uint64_t owner{0};  ///< id_ of the checker the arrays are sized for (0: none)
            std::vector<FloatFrame> frames;
            std::vector<char> placed;  ///< per body: its spheres are placed for this state
            std::vector<float> x, y, z, r;
            std::vector<Eigen::Vector3f> bodyCentre;
            std::vector<float> bodyRadius;
            std::vector<int> candidates;
            std::vector<char> pairNear;          ///< per sphere pair: bounding spheres overlap
            std::vector<std::size_t> tableCell;  ///< per table pair: the cell of the state place() was given
            std::vector<char> tableInside;       ///< per table pair: that cell is in the table
            std::vector<double> values;
            std::vector<char> wantBodies, wantPairs;
            std::vector<double> obstacleDistances, selfDistances;
            std::vector<float> gathered;  ///< per body of a pair: its spheres near the other body (x, y, z, r), margins
            std::vector<int> survivors;   ///< indices of one body's spheres near the other body
        };

        namespace
        {
            /** Rounding of float sphere centres (coordinates of a few metres) is far below this margin (metres),
                which every sphere radius is grown by. */
            constexpr float FLOAT_MARGIN = 1e-5f;
        }  // namespace

        SphereValidityChecker::SphereValidityChecker(const ompl::base::SpaceInformationPtr &si,
                                                     std::shared_ptr<const RobotGroupBodies> bodies,
                                                     SphereModelPtr spheres, ScenePtr scene,
                                                     FclValidityCheckerPtr exactSelf)
            : ompl::base::StateValidityChecker(si)
            , bodies_(std::move(bodies))
            , spheres_(std::move(spheres))
            , scene_(std::move(scene))
            , exact_(std::move(exactSelf))
        {
            static std::atomic<std::uint64_t> checkers{0};
            id_ = ++checkers;
            // The spheres enclose the links, so their distance to an obstacle is a lower bound of the links' own
            // distance.
            specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::BOUNDED_APPROXIMATE;
            if (si->getStateSpace()->getDimension() != bodies_->dimension())
                throw std::invalid_argument(
                    "state space has dimension " + std::to_string(si->getStateSpace()->getDimension()) +
                    ", the robot's configuration has " + std::to_string(bodies_->dimension()) + " values");
            const auto &model = *bodies_->model();
            if (spheres_->linkCount() != model.links().size())
                throw std::invalid_argument("sphere model has " + std::to_string(spheres_->linkCount()) +
                                            " links, robot '" + model.name() + "' has " +
                                            std::to_string(model.links().size()));
            std::vector<int> bodyOfRobotBody(bodies_->bodies().size(), -1);
            begin_.push_back(0);
            for (std::size_t b = 0; b < bodies_->bodies().size(); ++b)
            {
                const int link = bodies_->bodyLink(b);
                const auto &sp = spheres_->linkSpheres(link);
                // A link without geometry has no spheres and nothing to collide: it gets no body here.
                if (sp.empty())
                    continue;
                bodyOfRobotBody[b] = static_cast<int>(bodyLink_.size());
                robotBody_.push_back(static_cast<int>(b));
                bodyLink_.push_back(link);
                Eigen::Vector3d lo = sp.front().centre, hi = lo;
                for (const auto &s : sp)
                {
                    cx_.push_back(static_cast<float>(s.centre.x()));
                    cy_.push_back(static_cast<float>(s.centre.y()));
                    cz_.push_back(static_cast<float>(s.centre.z()));
                    radius_.push_back(static_cast<float>(s.radius) + FLOAT_MARGIN);
                    lo = lo.cwiseMin(s.centre);
                    hi = hi.cwiseMax(s.centre);
                }
                const Eigen::Vector3d c = 0.5 * (lo + hi);
                double r = 0.;
                for (const auto &s : sp)
                    r = std::max(r, (s.centre - c).norm() + s.radius);
                bodyCentre_.push_back(c.cast<float>());
                // The body's bounding sphere holds every sphere of the link, so a body whose bound misses an obstacle
                // needs no per-sphere test.
                bodyRadius_.push_back(static_cast<float>(r) + 2.f * FLOAT_MARGIN);
                begin_.push_back(static_cast<int>(radius_.size()));
                maxBodySpheres_ = std::max(maxBodySpheres_, sp.size());
            }
            for (std::size_t k = 0; k < bodies_->selfCheckPairs().size(); ++k)
            {
                const auto &p = bodies_->selfCheckPairs()[k];
                if (bodyOfRobotBody[p.first] >= 0 && bodyOfRobotBody[p.second] >= 0)
                {
                    selfPairs_.emplace_back(bodyOfRobotBody[p.first], bodyOfRobotBody[p.second]);
                    selfPairIndex_.push_back(static_cast<int>(k));
                }
            }

            // how far a sphere centre moves per unit of each group value: a rotation by dq moves a point at
            // distance rho from the joint's origin by at most rho * dq, and rho is bounded by the distances along
            // the chain (any configuration); a prismatic joint moves it by dq
            const auto &vars = bodies_->variables();
            coefficients_ = Eigen::MatrixXf::Zero(static_cast<long>(radius_.size()), static_cast<long>(vars.size()));
            for (std::size_t b = 0; b < bodyLink_.size(); ++b)
                for (int s = begin_[b]; s < begin_[b + 1]; ++s)
                {
                    double distance = Eigen::Vector3d(cx_[s], cy_[s], cz_[s]).norm() + FLOAT_MARGIN;
                    for (int j = model.links()[bodyLink_[b]].parentJoint; j >= 0;
                         j = model.links()[model.joints()[j].parentLink].parentJoint)
                    {
                        const RobotJoint &joint = model.joints()[j];
                        const bool prismatic = joint.type == RobotJoint::Type::PRISMATIC;
                        if (joint.variable >= 0)
                        {
                            const auto it = std::find(vars.begin(), vars.end(), joint.variable);
                            // Grown by 1e-6 so float rounding cannot make a bound smaller than the true displacement.
                            if (it != vars.end())
                                coefficients_(s, it - vars.begin()) =
                                    static_cast<float>((prismatic ? 1. : distance) * (1. + 1e-6));
                        }
                        distance += joint.origin.translation().norm() +
                                    (prismatic ? std::max(std::abs(joint.lower), std::abs(joint.upper)) : 0.);
                    }
                }
            // a point of a link's geometry lies in one of its spheres, so it moves at most as the sphere's centre
            // plus the sphere's radius times the rotation
            bodyCoefficients_ = Eigen::MatrixXf::Zero(static_cast<long>(bodyLink_.size()), coefficients_.cols());
            for (std::size_t b = 0; b < bodyLink_.size(); ++b)
                for (int s = begin_[b]; s < begin_[b + 1]; ++s)
                    for (long j = 0; j < coefficients_.cols(); ++j)
                    {
                        const bool prismatic = model.variableJoint(vars[j]).type == RobotJoint::Type::PRISMATIC;
                        const float c = coefficients_(s, j) > 0.f && !prismatic ? coefficients_(s, j) + radius_[s]
                                                                                : coefficients_(s, j);
                        bodyCoefficients_(b, j) = std::max(bodyCoefficients_(b, j), c);
                    }
            fullTemplate_ = bodies_->fullConfiguration(std::vector<double>(vars.size(), 0.).data());
            // Sphere centres in the frame their body rides on (a fixed joint's offset folded in), so that a state
            // places a sphere with one rotation and translation from the frames SphereKinematics makes.
            kinematics_ = std::make_unique<SphereKinematics>(model, vars, fullTemplate_, bodyLink_);
            for (std::size_t b = 0; b < bodyLink_.size(); ++b)
            {
                const RigidFrame &offset = kinematics_->offsetOf(b);
                bodyFrame_.push_back(kinematics_->frameOf(b));
                frameCentre_.push_back((offset.r * bodyCentre_[b].cast<double>() + offset.t).cast<float>());
                for (int i = begin_[b]; i < begin_[b + 1]; ++i)
                {
                    const Eigen::Vector3d c = offset.r * Eigen::Vector3d(cx_[i], cy_[i], cz_[i]) + offset.t;
                    fx_.push_back(static_cast<float>(c.x()));
                    fy_.push_back(static_cast<float>(c.y()));
                    fz_.push_back(static_cast<float>(c.z()));
                }
            }
            if (exact_ && exact_->bodies() != bodies_)
                throw std::invalid_argument("the exact self-collision checker must check the same bodies");
            // bodies the group does not move (a base on the floor): with FCL at hand, their contacts are decided
            // once on the real geometry (once per scene change for obstacles), not by spheres in every state
            static_.assign(bodyLink_.size(), 0);
            if (exact_)
                for (std::size_t b = 0; b < bodyLink_.size(); ++b)
                    static_[b] = bodyCoefficients_.row(static_cast<long>(b)).isZero() ? 1 : 0;
            if (exact_)
            {
                std::vector<char> wantBodies(bodies_->bodies().size(), 0),
                    wantPairs(bodies_->selfCheckPairs().size(), 0);
                bool any = false;
                for (std::size_t k = 0; k < selfPairs_.size(); ++k)
                    if (static_[selfPairs_[k].first] && static_[selfPairs_[k].second])
                        any = wantPairs[selfPairIndex_[k]] = 1;
                std::vector<double> obstacle, self;
                if (any)
                {
                    const std::vector<double> values(bodies_->dimension(), 0.);  // any: these bodies do not move
                    exact_->bodyDistances(values.data(), wantBodies, wantPairs, obstacle, self);
                }
                for (std::size_t k = 0; k < self.size(); ++k)
                    staticSelfBlocked_ = staticSelfBlocked_ || self[k] <= 0.;
            }
            if (exact_)
                makeSelfPairTables();
            // the pairs in two lists, so that a state check runs two tight loops instead of testing per pair which
            // case it is: table lookups, then bounding-sphere tests of the pairs the spheres decide
            for (std::size_t k = 0; k < selfPairs_.size(); ++k)
            {
                const auto &p = selfPairs_[k];
                if (static_[p.first] && static_[p.second])
                    continue;
                if (pairTables_ && (*pairTables_)[k])
                    tablePairs_.push_back(static_cast<int>(k));
                else
                    spherePairs_.push_back(static_cast<int>(k));
            }
            realVector_ = dynamic_cast<const ompl::base::RealVectorStateSpace *>(si->getStateSpace().get());
            // the first snapshot of the scene
            obstacles();
        }

        namespace
        {
            /** Cells per joint value of a self-pair table (one value: 1024 cells; two: 256 x 256, 8 KiB). */
            constexpr int TABLE_CELLS_1D = 4096, TABLE_CELLS_2D = 1024;
        }  // namespace

        void SphereValidityChecker::makeSelfPairTables()
        {
            const auto &model = *bodies_->model();
            const auto &vars = bodies_->variables();
            // group values on the tree path between two links: the joints above one link and not the other
            auto rootJoints = [&](int link)
            {
                std::set<int> joints;
                for (int j = model.links()[link].parentJoint; j >= 0;
                     j = model.links()[model.joints()[j].parentLink].parentJoint)
                    joints.insert(j);
                return joints;
            };
            // the tables depend on the robot, its group and the sphere model (the displacement bounds): shared
            using Key =
                std::tuple<const RobotModel *, std::vector<int>, std::vector<std::pair<int, int>>, const SphereModel *>;
            // Building the tables costs FCL distances over a whole grid (about 0.7 s for the Panda): checkers made for
            // the same robot, group and sphere model share them. The cache holds weak pointers, so the tables die with
            // the last checker that uses them.
            static std::mutex mutex;
            static std::map<Key, std::weak_ptr<const std::vector<std::shared_ptr<const SelfPairTable>>>> cache;
            const Key key{&model, vars, bodies_->selfCheckPairs(), spheres_.get()};
            std::lock_guard<std::mutex> lock(mutex);
            pairTables_ = cache[key].lock();
            if (pairTables_)
                return;
            auto tables = std::make_shared<std::vector<std::shared_ptr<const SelfPairTable>>>(selfPairs_.size());
            // what each table needs; the tables are then built in parallel (FCL distances, thread-safe)
            struct Job
            {
                std::size_t k;
                std::vector<int> on;  ///< group indices of the values on the path
                std::vector<double> lo, hi, closing;
                std::vector<char> wrap;
            };
            std::vector<Job> jobs;
            for (std::size_t k = 0; k < selfPairs_.size(); ++k)
            {
                const auto &p = selfPairs_[k];
                if (static_[p.first] && static_[p.second])
                    continue;
                const std::set<int> a = rootJoints(bodyLink_[p.first]), b = rootJoints(bodyLink_[p.second]);
                Job job;
                job.k = k;
                for (const std::set<int> *one : {&a, &b})
                    for (int j : *one)
                        if ((one == &a ? b : a).count(j) == 0 && model.joints()[j].variable >= 0)
                        {
                            const auto it = std::find(vars.begin(), vars.end(), model.joints()[j].variable);
                            if (it != vars.end())
                                job.on.push_back(static_cast<int>(it - vars.begin()));
                        }
                std::sort(job.on.begin(), job.on.end());
                job.on.erase(std::unique(job.on.begin(), job.on.end()), job.on.end());
                // A table over one or two values (1024 or 256 x 256 cells); pairs that depend on more values, or on
                // none of the group's, stay with the spheres and FCL.
                if (job.on.empty() || job.on.size() > 2)
                    continue;
                for (int v : job.on)
                {
                    const RobotJoint &joint = model.variableJoint(vars[v]);
                    const bool continuous = joint.type == RobotJoint::Type::CONTINUOUS;
                    job.lo.push_back(continuous ? -M_PI : joint.lower);
                    job.hi.push_back(continuous ? M_PI : joint.upper);
                    job.wrap.push_back(continuous ? 1 : 0);
                    // the two bodies close in at most as fast as both move
                    job.closing.push_back(static_cast<double>(bodyCoefficients_(p.first, v)) +
                                          static_cast<double>(bodyCoefficients_(p.second, v)));
                }
                jobs.push_back(std::move(job));
            }
            // The tables on disk (SelfPairCache.h), keyed by everything they are built from: the robot's geometry
            // and joints, the values of the joints the group does not move, and each table's pair, values, ranges,
            // closing speeds and cells. A file that does not check out is ignored and the tables built again.
            Fnv64 hash;
            // The version names the certification rule and the file layout: change it with either, so that files
            // written by an older build are not read as proofs.
            hash.text("michi self-pair tables v1");
            hashRobotGeometry(model, hash);
            hash.bytes(fullTemplate_.data(), fullTemplate_.size() * sizeof(double));
            for (const Job &job : jobs)
            {
                hash.value(job.k);
                hash.text(model.links()[bodyLink_[selfPairs_[job.k].first]].name);
                hash.text(model.links()[bodyLink_[selfPairs_[job.k].second]].name);
                for (std::size_t d = 0; d < job.on.size(); ++d)
                {
                    hash.value(vars[job.on[d]]);
                    hash.value(job.lo[d]);
                    hash.value(job.hi[d]);
                    hash.value(job.wrap[d]);
                    hash.value(job.closing[d]);
                }
                hash.value(job.on.size() == 1 ? TABLE_CELLS_1D : TABLE_CELLS_2D);
            }
            const std::string cacheDir = selfPairCacheDir();
            std::vector<std::vector<std::uint64_t>> stored;
            if (!jobs.empty() && readSelfPairCache(cacheDir, hash.digest(), jobs.size(), stored))
            {
                try
                {
                    for (std::size_t i = 0; i < jobs.size(); ++i)
                    {
                        const Job &job = jobs[i];
                        (*tables)[job.k] = std::make_shared<SelfPairTable>(
                            job.on, job.lo, job.hi, job.wrap, job.closing,
                            job.on.size() == 1 ? TABLE_CELLS_1D : TABLE_CELLS_2D, std::move(stored[i]));
                    }
                    tablesFromDisk_ = true;
                    pairTables_ = tables;
                    cache[key] = tables;
                    return;
                }
                catch (const std::invalid_argument &)
                {
                    // a stored table of another size: built again below
                }
            }
            std::atomic<std::size_t> next{0};
            auto work = [&]
            {
                std::vector<double> values(vars.size(), 0.), obstacle, self;
                std::vector<char> wantBodies(bodies_->bodies().size(), 0),
                    wantPairs(bodies_->selfCheckPairs().size(), 0);
                for (std::size_t i = next++; i < jobs.size(); i = next++)
                {
                    const Job &job = jobs[i];
                    const std::size_t pairIndex = static_cast<std::size_t>(selfPairIndex_[job.k]);
                    auto distance = [&](const double *at)
                    {
                        for (std::size_t d = 0; d < job.on.size(); ++d)
                            values[job.on[d]] = at[d];
                        wantPairs.assign(wantPairs.size(), 0);
                        wantPairs[pairIndex] = 1;
                        exact_->bodyDistances(values.data(), wantBodies, wantPairs, obstacle, self);
                        return self[pairIndex];
                    };
                    (*tables)[job.k] =
                        std::make_shared<SelfPairTable>(job.on, job.lo, job.hi, job.wrap, job.closing,
                                                        job.on.size() == 1 ? TABLE_CELLS_1D : TABLE_CELLS_2D, distance);
                }
            };
            const std::size_t helpers =
                // One helper fewer than cores: the calling thread works through the jobs too.
                std::min<std::size_t>(jobs.size(), std::max(1u, std::thread::hardware_concurrency())) -
                (jobs.empty() ? 0 : 1);
            std::vector<std::thread> threads;
            for (std::size_t t = 0; t < helpers; ++t)
                threads.emplace_back(work);
            work();
            for (auto &t : threads)
                t.join();
            pairTables_ = tables;
            cache[key] = tables;
            if (!jobs.empty())
            {
                std::vector<std::vector<std::uint64_t>> bits;
                for (const Job &job : jobs)
                    bits.push_back((*tables)[job.k]->bits());
                writeSelfPairCache(cacheDir, hash.digest(), bits);
            }
        }

        std::size_t SphereValidityChecker::tabulatedPairs() const
        {
            std::size_t n = 0;
            if (pairTables_)
                for (const auto &t : *pairTables_)
                    n += t ? 1 : 0;
            return n;
        }

        SphereValidityChecker::~SphereValidityChecker() = default;

        const SphereObstacles &SphereValidityChecker::obstacles() const
        {
            const std::uint64_t version = scene_->changeCount();
            const SphereObstacles *current = current_.load(std::memory_order_acquire);
            // Lock-free when the scene has not changed since the last snapshot (the common case); otherwise a new
            // snapshot is made under the mutex, checking again in case another thread made it first.
            if (current != nullptr && current->version() == version)
                return *current;
            std::lock_guard<std::mutex> lock(snapshotMutex_);
            current = current_.load(std::memory_order_acquire);
            if (current != nullptr && current->version() == scene_->changeCount())
                return *current;
            // Old snapshots are kept, never freed: another thread may still be reading the one it loaded.
            snapshots_.push_back(std::make_unique<SphereObstacles>(*scene_));
            if (exact_)
            {
                std::vector<char> wantBodies(bodies_->bodies().size(), 0),
                    wantPairs(bodies_->selfCheckPairs().size(), 0);
                bool any = false;
                for (std::size_t b = 0; b < bodyLink_.size(); ++b)
                    if (static_[b])
                        any = wantBodies[robotBody_[b]] = 1;
                std::vector<double> obstacle, self;
                if (any)
                {
                    // Any values: the bodies asked about are those the group does not move.
                    std::vector<double> values(bodies_->dimension(), 0.);
                    exact_->bodyDistances(values.data(), wantBodies, wantPairs, obstacle, self);
                }
                for (double d : obstacle)
                    snapshots_.back()->staticBlocked = snapshots_.back()->staticBlocked || d <= 0.;
            }
            current_.store(snapshots_.back().get(), std::memory_order_release);
            return *snapshots_.back();
        }

        void SphereValidityChecker::toReals(const ompl::base::State *state, std::vector<double> &values) const
        {
            si_->getStateSpace()->copyToReals(values, state);
        }

        void SphereValidityChecker::prepare(Scratch &s) const
        {
            // Sized once per thread and checker, not on every query: a thread's scratch follows the last checker that
            // used it, known by its id (an address could be a new checker's).
            s.tableCell.resize(tablePairs_.size());
            s.tableInside.resize(tablePairs_.size());
            s.frames.resize(kinematics_->frameCount());
            const std::size_t n = radius_.size(), nb = bodyLink_.size();
            s.x.resize(n);
            s.y.resize(n);
            s.z.resize(n);
            s.r.resize(n);
            s.bodyCentre.resize(nb);
            s.bodyRadius.resize(nb);
            s.placed.resize(nb);
            s.pairNear.resize(spherePairs_.size());
            s.gathered.resize(10 * maxBodySpheres_);
            s.survivors.resize(maxBodySpheres_);
            s.owner = id_;
        }

        void SphereValidityChecker::place(const double *values, Scratch &s, bool tableCells) const
        {
            // the self-pair tables' cells first, their words prefetched: on fresh states each is a cache miss, and the
            // loads then overlap the kinematics instead of stalling the pair loop (verify-checker, Panda: 475 -> 385
            // ns)
            if (s.owner != id_)
                prepare(s);
            for (std::size_t i = 0; tableCells && i < tablePairs_.size(); ++i)
            {
                const SelfPairTable &table = *(*pairTables_)[static_cast<std::size_t>(tablePairs_[i])];
                s.tableInside[i] = table.cellOf(values, s.tableCell[i]);
                if (s.tableInside[i])
                    __builtin_prefetch(table.wordOf(s.tableCell[i]));
            }
            // Joints outside the planned group and fixed joints are folded into the kinematics' offsets: only the
            // group's values are read per query.
            kinematics_->framesFloat(values, s.frames.data());
            const std::size_t nb = bodyLink_.size();
            std::fill(s.placed.begin(), s.placed.end(), 0);
            for (std::size_t b = 0; b < nb; ++b)
            {
                const FloatFrame &f = s.frames[bodyFrame_[b]];
                const Eigen::Vector3f &c = frameCentre_[b];
                const Eigen::Array4f centre = f.c0 * c.x() + f.c1 * c.y() + f.c2 * c.z() + f.t;
                s.bodyCentre[b] = centre.head<3>().matrix();
            }
        }

        void SphereValidityChecker::placeBody(std::size_t b, Scratch &s) const
        {
            // Spheres are placed only for bodies whose bounding sphere reaches something: far from obstacles and
            // from other links, a body costs its bounding sphere alone.
            if (s.placed[b])
                return;
            s.placed[b] = 1;
            using Map = Eigen::Map<Eigen::ArrayXf>;
            using MapC = Eigen::Map<const Eigen::ArrayXf>;
            const FloatFrame &f = s.frames[bodyFrame_[b]];
            const int first = begin_[b], count = begin_[b + 1] - begin_[b];
            const MapC cx(fx_.data() + first, count), cy(fy_.data() + first, count), cz(fz_.data() + first, count);
            Map(s.x.data() + first, count) = f.c0(0) * cx + f.c1(0) * cy + f.c2(0) * cz + f.t(0);
            Map(s.y.data() + first, count) = f.c0(1) * cx + f.c1(1) * cy + f.c2(1) * cz + f.t(1);
            Map(s.z.data() + first, count) = f.c0(2) * cx + f.c1(2) * cy + f.c2(2) * cz + f.t(2);
        }

        int SphereValidityChecker::spheresNear(Scratch &s, const float *r, std::size_t body, std::size_t other,
                                               float *g) const
        {
            // the other body's bounding sphere in the frame this body rides on (the rotation's transpose), where the
            // body's sphere centres are constants: no sphere is placed to be ruled out
            const FloatFrame &f = s.frames[static_cast<std::size_t>(bodyFrame_[body])];
            const Eigen::Array4f d =
                Eigen::Array4f(s.bodyCentre[other].x(), s.bodyCentre[other].y(), s.bodyCentre[other].z(), 0.f) - f.t;
            const float lx = (f.c0 * d).sum(), ly = (f.c1 * d).sum(), lz = (f.c2 * d).sum();
            const float reachOther = s.bodyRadius[other];
            const int first = begin_[body], count = begin_[body + 1] - first;
            const float *cx = fx_.data() + first, *cy = fy_.data() + first, *cz = fz_.data() + first, *cr = r + first;
            float *margin = g + 4 * maxBodySpheres_;
            // one pass over whole SIMD lanes (negative: the sphere reaches into the other's bound), then the
            // survivors gathered without a branch
            for (int i = 0; i < count; ++i)
            {
                const float dx = cx[i] - lx, dy = cy[i] - ly, dz = cz[i] - lz, reach = cr[i] + reachOther;
                margin[i] = dx * dx + dy * dy + dz * dz - reach * reach;
            }
            int *index = s.survivors.data(), n = 0;
            for (int i = 0; i < count; ++i)
            {
                index[n] = i;
                n += margin[i] < 0.f ? 1 : 0;
            }
            // only the survivors are placed in the world, where the two bodies' spheres are compared
            const std::size_t m = maxBodySpheres_;
            for (int k = 0; k < n; ++k)
            {
                const int i = index[k];
                g[k] = f.c0(0) * cx[i] + f.c1(0) * cy[i] + f.c2(0) * cz[i] + f.t(0);
                g[m + k] = f.c0(1) * cx[i] + f.c1(1) * cy[i] + f.c2(1) * cz[i] + f.t(1);
                g[2 * m + k] = f.c0(2) * cx[i] + f.c1(2) * cy[i] + f.c2(2) * cz[i] + f.t(2);
                g[3 * m + k] = cr[i];
            }
            return n;
        }

        bool SphereValidityChecker::bodyTouches(Scratch &s, std::size_t b, const SphereObstacles &obs, int o,
                                                const float *r) const
        {
            // a large obstacle (a table top) has a bounding sphere that reaches every body, its shape reaches few:
            // the body's spheres are placed only once the obstacle's shape is within the body's bound
            if (!obs.hitsSphere(o, s.bodyCentre[b], s.bodyRadius[b]))
                return false;
            placeBody(b, s);
            const int first = begin_[b];
            return obs.hits(o, SphereBatch{s.x.data() + first, s.y.data() + first, s.z.data() + first, r + first,
                                           begin_[b + 1] - first});
        }

        bool SphereValidityChecker::spheresTouch(Scratch &s, const float *r, std::size_t a, std::size_t b) const
        {
            // Two bodies whose bounding spheres overlap usually meet in a small lens: only the spheres of each body
            // that reach into the other's bounding sphere can touch, and only those pairs are tested (Panda, 24
            // spheres a link: a few of 24 x 24).
            const std::size_t m = maxBodySpheres_;
            float *ga = s.gathered.data(), *gb = ga + 5 * m;
            const int na = spheresNear(s, r, a, b, ga);
            if (na == 0)
                return false;
            const int nb = spheresNear(s, r, b, a, gb);
            for (int i = 0; i < na; ++i)
            {
                const float xi = ga[i], yi = ga[m + i], zi = ga[2 * m + i], ri = ga[3 * m + i];
                // No early exit inside: the compiler vectorises this loop into whole SIMD lanes.
                int any = 0;
                for (int j = 0; j < nb; ++j)
                {
                    const float dx = gb[j] - xi, dy = gb[m + j] - yi, dz = gb[2 * m + j] - zi, rr = gb[3 * m + j] + ri;
                    any |= dx * dx + dy * dy + dz * dz < rr * rr;
                }
                if (any != 0)
                    return true;
            }
            return false;
        }

        void SphereValidityChecker::bodyInflations(const float *inflation, float *bodyInflation) const
        {
            for (std::size_t b = 0; b < bodyLink_.size(); ++b)
            {
                float grow = 0.f;
                for (int i = begin_[b]; i < begin_[b + 1]; ++i)
                    grow = std::max(grow, inflation[i]);
                bodyInflation[b] = grow;
            }
        }

        bool SphereValidityChecker::collides(Scratch &s, const double *values, const float *inflation,
                                             const float *valueSpan, const float *bodyInflation, bool useExact,
                                             std::string *why) const
        {
            const std::size_t nb = bodyLink_.size();
            const float *r = radius_.data();
            if (inflation != nullptr)
            {
                for (std::size_t i = 0; i < radius_.size(); ++i)
                    s.r[i] = radius_[i] + inflation[i];
                r = s.r.data();
                if (bodyInflation == nullptr)
                {
                    // a chain of maxima per body (not vectorised): a motion validator passes them instead
                    bodyInflations(inflation, s.bodyRadius.data());
                    bodyInflation = s.bodyRadius.data();
                }
                for (std::size_t b = 0; b < nb; ++b)
                    s.bodyRadius[b] = bodyRadius_[b] + bodyInflation[b];
            }
            else
                std::copy(bodyRadius_.begin(), bodyRadius_.end(), s.bodyRadius.begin());

            // Bodies the group does not move were decided by FCL once per scene version (staticBlocked) or once at
            // construction (staticSelfBlocked_): if they touch, every state is invalid.
            const SphereObstacles &obs = obstacles();
            if (s.candidates.size() < obs.candidateCapacity())
                s.candidates.resize(obs.candidateCapacity());
            if (obs.staticBlocked || staticSelfBlocked_)
            {
                if (why != nullptr)
                    *why = "a link the group does not move touches something (FCL)";
                return true;
            }
            for (std::size_t b = 0; b < nb; ++b)
            {
                if (static_[b])
                    continue;
                // clear of every obstacle by the snapshot's distance grid: one lookup instead of both phases
                if (obs.clears(s.bodyCentre[b], s.bodyRadius[b]))
                    continue;
                const int found = obs.candidates(s.bodyCentre[b], s.bodyRadius[b], s.candidates.data());
                if (found == 0)
                    continue;
                int hit = -1;
                for (int k = 0; k < found && hit < 0; ++k)
                    if (bodyTouches(s, b, obs, s.candidates[k], r))
                        hit = s.candidates[k];
                if (hit < 0)
                    continue;
                // the spheres stand out of the link's surface: near an obstacle (a grasp) the real geometry
                // decides, so a state is never judged in collision when it is not
                if (useExact && exact_ && inflation == nullptr &&
                    (exactEverywhere_ ||
                     std::binary_search(exactObstacles_.begin(), exactObstacles_.end(), obs.name(hit))) &&
                    !exact_->bodyCollides(values, static_cast<std::size_t>(robotBody_[b])))
                    continue;
                if (why != nullptr)
                    *why = bodies_->model()->links()[bodyLink_[b]].name + " touches obstacle '" + obs.name(hit) + "'";
                return true;
            }
            for (std::size_t i = 0; i < tablePairs_.size(); ++i)
            {
                const int k = tablePairs_[i];
                // A set table bit is a proof for its whole cell (certified with the pair's closing speed), so the table
                // answers without spheres or FCL; in a motion, freeOver() reads every cell the values sweep. A state
                // reads the cell place() found.
                const SelfPairTable &table = *(*pairTables_)[static_cast<std::size_t>(k)];
                if (valueSpan != nullptr ? table.freeOver(values, valueSpan)
                                         : s.tableInside[i] && table.cellFree(s.tableCell[i]))
                    continue;
                if (why != nullptr)
                {
                    const auto &p = selfPairs_[static_cast<std::size_t>(k)];
                    *why = bodies_->model()->links()[bodyLink_[p.first]].name + " touches " +
                           bodies_->model()->links()[bodyLink_[p.second]].name + " (self-pair table)";
                }
                return true;
            }
            // Bounding spheres of the pairs first, without a branch per pair; most are apart.
            for (std::size_t i = 0; i < spherePairs_.size(); ++i)
            {
                const auto &p = selfPairs_[static_cast<std::size_t>(spherePairs_[i])];
                const float reach = s.bodyRadius[p.first] + s.bodyRadius[p.second];
                s.pairNear[i] = (s.bodyCentre[p.first] - s.bodyCentre[p.second]).squaredNorm() < reach * reach;
            }
            for (std::size_t i = 0; i < spherePairs_.size(); ++i)
            {
                if (!s.pairNear[i])
                    continue;
                const std::size_t k = static_cast<std::size_t>(spherePairs_[i]);
                const auto &p = selfPairs_[k];
                if (!spheresTouch(s, r, static_cast<std::size_t>(p.first), static_cast<std::size_t>(p.second)))
                    continue;
                if (useExact && exact_ && inflation == nullptr &&
                    (exactEverywhere_ || exactPairs_[static_cast<std::size_t>(selfPairIndex_[k])]))
                {
                    // the spheres of two links overlap: their real geometry decides (a boolean query)
                    if (!exact_->pairCollides(values, static_cast<std::size_t>(selfPairIndex_[k])))
                        continue;
                }
                // in a motion the spheres decide: an FCL distance between two meshes near contact costs about
                // 100 microseconds, and the motion validator would ask it for every piece. A motion whose grown
                // spheres keep touching is rejected (conservative), never passed unchecked
                if (why != nullptr)
                    *why = bodies_->model()->links()[bodyLink_[p.first]].name + " touches " +
                           bodies_->model()->links()[bodyLink_[p.second]].name;
                return true;
            }
            return false;
        }

        bool SphereValidityChecker::isValidConfiguration(const double *values) const
        {
            // No inflation: a state check. The motion validator passes the spheres' growth over a piece of motion
            // instead.
            return isFreeInflated(values, nullptr, nullptr);
        }

        bool SphereValidityChecker::isFreeInflated(const double *values, const float *inflation,
                                                   const float *valueSpan) const
        {
            return isFreeInflated(values, inflation, valueSpan, nullptr);
        }

        bool SphereValidityChecker::isFreeInflated(const double *values, const float *inflation, const float *valueSpan,
                                                   const float *bodyInflation) const
        {
            // Per thread: planners and benchmarks query from several threads, and the scratch arrays are reused without
            // allocation.
            thread_local Scratch s;
            place(values, s, valueSpan == nullptr);
            return !collides(s, values, inflation, valueSpan, bodyInflation, exactStates_, nullptr);
        }

        bool SphereValidityChecker::spheresFree(const double *values) const
        {
            thread_local Scratch s;
            place(values, s, true);
            return !collides(s, values, nullptr, nullptr, nullptr, false, nullptr);
        }

        SphereValidityChecker::Contacts SphereValidityChecker::sphereContacts(const double *values, double margin) const
        {
            // collides() without its early exits, every radius grown by the margin; a rare call (once per query)
            Scratch s;
            place(values, s, true);
            const float grow = static_cast<float>(std::max(margin, 0.));
            for (std::size_t i = 0; i < radius_.size(); ++i)
                s.r[i] = radius_[i] + grow;
            for (std::size_t b = 0; b < bodyLink_.size(); ++b)
                s.bodyRadius[b] = bodyRadius_[b] + grow;
            const SphereObstacles &obs = obstacles();
            s.candidates.resize(obs.candidateCapacity());
            Contacts contacts;
            for (std::size_t b = 0; b < bodyLink_.size(); ++b)
            {
                if (static_[b])
                    continue;
                const int found = obs.candidates(s.bodyCentre[b], s.bodyRadius[b], s.candidates.data());
                for (int k = 0; k < found; ++k)
                    if (bodyTouches(s, b, obs, s.candidates[k], s.r.data()))
                        contacts.obstacles.push_back(obs.name(s.candidates[k]));
            }
            for (const int k : spherePairs_)
            {
                const auto &p = selfPairs_[static_cast<std::size_t>(k)];
                const float reach = s.bodyRadius[p.first] + s.bodyRadius[p.second];
                if ((s.bodyCentre[p.first] - s.bodyCentre[p.second]).squaredNorm() < reach * reach &&
                    spheresTouch(s, s.r.data(), static_cast<std::size_t>(p.first), static_cast<std::size_t>(p.second)))
                    contacts.selfPairs.push_back(selfPairIndex_[static_cast<std::size_t>(k)]);
            }
            std::sort(contacts.obstacles.begin(), contacts.obstacles.end());
            contacts.obstacles.erase(std::unique(contacts.obstacles.begin(), contacts.obstacles.end()),
                                     contacts.obstacles.end());
            std::sort(contacts.selfPairs.begin(), contacts.selfPairs.end());
            return contacts;
        }

        std::string SphereValidityChecker::describeCollision(const double *values) const
        {
            Scratch s;
            place(values, s, true);
            std::string why;
            collides(s, values, nullptr, nullptr, nullptr, exactStates_, &why);
            return why;
        }

        double SphereValidityChecker::clearanceConfiguration(const double *values) const
        {
            thread_local Scratch s;
            place(values, s, false);
            const SphereObstacles &obs = obstacles();
            float best = std::numeric_limits<float>::infinity();
            for (std::size_t b = 0; b < bodyLink_.size(); ++b)
            {
                placeBody(b, s);
                const int first = begin_[b];
                const SphereBatch batch{s.x.data() + first, s.y.data() + first, s.z.data() + first,
                                        radius_.data() + first, begin_[b + 1] - first};
                for (std::size_t o = 0; o < obs.size(); ++o)
                {
                    // The distance between bounding spheres is a lower bound: an obstacle that cannot beat the best so
                    // far is skipped.
                    if (obs.boundDistance(static_cast<int>(o), s.bodyCentre[b], bodyRadius_[b]) >= best)
                        continue;
                    best = std::min(best, obs.distance(static_cast<int>(o), batch));
                }
            }
            return static_cast<double>(best);
        }

        bool SphereValidityChecker::isValid(const ompl::base::State *state) const
        {
            if (realVector_ != nullptr)
            {
                // The common case (an arm's joint vector): the values are read in place; the bounds test is
                // RealVectorStateSpace::satisfiesBounds' own (a value may pass a bound by one epsilon), written so
                // that a value that is not a number fails it (every comparison with NaN is false).
                const double *v = state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
                const auto &bounds = realVector_->getBounds();
                for (std::size_t i = 0; i < bounds.low.size(); ++i)
                    if (!(v[i] - std::numeric_limits<double>::epsilon() <= bounds.high[i] &&
                          v[i] + std::numeric_limits<double>::epsilon() >= bounds.low[i]))
                        return false;
                return isValidConfiguration(v);
            }
            if (!si_->satisfiesBounds(state))
                return false;
            thread_local std::vector<double> values;
            toReals(state, values);
            // a NaN passes satisfiesBounds(): refused here, as the joint vector's bounds test above refuses it
            for (const double v : values)
                if (!std::isfinite(v))
                    return false;
            return isValidConfiguration(values.data());
        }

        bool SphereValidityChecker::isValid(const ompl::base::State *state, double &dist) const
        {
            if (!isValid(state))
            {
                dist = 0.;
                return false;
            }
            dist = clearance(state);
            return true;
        }

        double SphereValidityChecker::clearance(const ompl::base::State *state) const
        {
            thread_local std::vector<double> values;
            toReals(state, values);
            return clearanceConfiguration(values.data());
        }
    }  // namespace validity
}  // namespace michi
