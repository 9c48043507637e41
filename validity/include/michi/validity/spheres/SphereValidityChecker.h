#ifndef MICHI_VALIDITY_SPHERES_SPHERE_VALIDITY_CHECKER_
#define MICHI_VALIDITY_SPHERES_SPHERE_VALIDITY_CHECKER_

#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/robot/CollisionBodies.h>
#include <michi/validity/scene/Scene.h>
#include <michi/validity/spheres/SphereModel.h>

#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <Eigen/Core>

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace michi
{
    namespace validity
    {
        class SphereObstacles;
        class SelfPairTable;
        class SphereKinematics;

        /** \brief Collision checking of an arm with the spheres of a SphereModel (which enclose its links) against a
            scene, in structure-of-arrays form: forward kinematics of the links, then every sphere centre of a
            link at once (Eigen arrays of floats, radii padded for rounding), then per obstacle the spheres of
            every link whose bounding sphere reaches the obstacle's (boxes, spheres, cylinders, capsules and
            extruded polygons in closed form, meshes through a bounding-sphere tree of their triangles), then the
            self-collision pairs (non-adjacent, not allowed) sphere against sphere; the first hit ends the check.
            Because the spheres enclose the links, a state it accepts is free for the real geometry (it may
            reject states whose real geometry is free: false_invalid). clearance() is a lower bound of the real
            distance to the scene (a conservative clearance). Safe from several threads: the scene is read
            through an immutable snapshot, renewed when Scene::changeCount() moves (moving obstacles). */
        class SphereValidityChecker : public ompl::base::StateValidityChecker
        {
        public:
            /** \param exactSelf when given (an FCL checker of the same bodies): self pairs whose relative pose
                depends on one or two joint values (a wrist, which sits close by construction) are decided by
                tables built once with FCL on the real geometry (certified over each cell), and bodies the group
                does not move are decided once by FCL. With setExactStates(true), a state check also hands other
                pairs whose spheres overlap to an FCL collision query between the two links, and a link whose
                spheres touch an obstacle to an FCL query of that link against the scene (no state is then judged
                in collision that is not, outside the tables' cells next to contact). */
            SphereValidityChecker(const ompl::base::SpaceInformationPtr &si,
                                  std::shared_ptr<const RobotGroupBodies> bodies, SphereModelPtr spheres,
                                  ScenePtr scene, FclValidityCheckerPtr exactSelf = nullptr);
            ~SphereValidityChecker() override;

            bool isValid(const ompl::base::State *state) const override;
            bool isValid(const ompl::base::State *state, double &dist) const override;
            double clearance(const ompl::base::State *state) const override;

            /** \brief Validity of group values (bodies()->dimension() values). */
            bool isValidConfiguration(const double *values) const;
            /** \brief The same with every sphere grown by \e inflation[s] metres (sphereCount() values), and
                for self pairs a table decides, every group value within \e valueSpan[v] of values[v]: true means
                nothing touches while each sphere moves by up to its inflation. With an inflation, spheres decide
                every other self pair (no FCL query). */
            bool isFreeInflated(const double *values, const float *inflation, const float *valueSpan) const;
            /** \brief The same with each body's largest inflation given (\e bodyInflation, bodyCount() values, at least
                the largest inflation of the body's spheres), as bodyInflations() makes it: a motion validator that
                scales one inflation piece by piece scales those too instead of having them found for every piece. */
            bool isFreeInflated(const double *values, const float *inflation, const float *valueSpan,
                                const float *bodyInflation) const;
            /** \brief The largest of \e inflation (sphereCount() values) over each body's spheres, into
                \e bodyInflation (bodyCount() values). */
            void bodyInflations(const float *inflation, float *bodyInflation) const;
            /** \brief The spheres (and self-pair tables) alone, without asking FCL: true means free for the
                spheres, hence for the real geometry; false may be a state whose real geometry is free (a grasp:
                the hand's spheres stand out of its surface). */
            bool spheresFree(const double *values) const;
            /** \brief Whether a state check asks FCL about links whose spheres touch (default false). Off, a
                state is decided by the spheres and the self-pair tables alone (tens of times faster; a few per
                cent of free states near contact read as blocked); on, FCL settles those, so that no free state is
                judged in collision. Set before use. */
            void setExactStates(bool exact)
            {
                exactStates_ = exact;
                exactObstacles_.clear();
                exactPairs_.clear();
                exactEverywhere_ = true;
            }
            bool exactStates() const
            {
                return exactStates_;
            }
            /** \brief What the spheres touch at some group values (sphereContacts()): the obstacles by name and the
                self pairs (indices into bodies()->selfCheckPairs()) that spheres rather than a table decide. */
            struct Contacts
            {
                std::vector<std::string> obstacles;  ///< sorted, unique
                std::vector<int> selfPairs;          ///< sorted, unique
                bool empty() const
                {
                    return obstacles.empty() && selfPairs.empty();
                }
            };
            /** \brief Every obstacle and self pair that the spheres, each grown by \e margin metres, touch at \e values
                (no early exit; bodies the group does not move and pairs a table decides are left out: FCL and the
                tables decide those whatever the setting). */
            Contacts sphereContacts(const double *values, double margin = 0.) const;
            /** \brief setExactStates(true), but FCL settles only these contacts: a body whose spheres touch an
                obstacle named in \e contacts, and the self pairs in it; the spheres alone decide every other contact.
                A grasp's goal needs FCL for the hand and the object it holds, not for every link that meets the table
                on the way (dataset problems whose goal the spheres reject: 5.6 us a state check and 138 us a motion
                with every contact settled, docs/checking.md). Never less safe: FCL only turns a contact the spheres
                report into a free answer when the real geometry is free. */
            void setExactContacts(Contacts contacts)
            {
                exactStates_ = !contacts.empty();
                exactObstacles_ = std::move(contacts.obstacles);
                exactPairs_.assign(bodies_->selfCheckPairs().size(), 0);
                for (int k : contacts.selfPairs)
                    if (k >= 0 && static_cast<std::size_t>(k) < exactPairs_.size())
                        exactPairs_[static_cast<std::size_t>(k)] = 1;
                exactEverywhere_ = false;
            }
            /** \brief The FCL checker of the same bodies given at construction (may be null). */
            const FclValidityCheckerPtr &exact() const
            {
                return exact_;
            }
            /** \brief Self pairs decided by a table over one or two joint values (see selfPairTables). */
            std::size_t tabulatedPairs() const;
            /** \brief Were this checker's self-pair tables read from the cache folder ($MICHI_CACHE_DIR, else
                $XDG_CACHE_HOME/michi or ~/.cache/michi) rather than built with FCL? */
            bool selfPairTablesFromDisk() const
            {
                return tablesFromDisk_;
            }
            /** \brief "panda_hand touches obstacle 'can'" or "link1 touches link4" (spheres); empty when valid. */
            std::string describeCollision(const double *values) const;
            /** \brief Lower bound of the distance between the robot and the scene (<= 0 when the spheres touch). */
            double clearanceConfiguration(const double *values) const;

            std::size_t sphereCount() const
            {
                return radius_.size();
            }
            /** \brief How far sphere \e s's centre can move per unit of group value \e variable (metres per
                radian or per metre), for any configuration: spheres x dimension. */
            const Eigen::MatrixXf &displacementCoefficients() const
            {
                return coefficients_;
            }
            /** \brief Bodies (links with spheres), and how far any point of a body's geometry can move per unit
                of each group value: bodyCount() x dimension. */
            std::size_t bodyCount() const
            {
                return bodyLink_.size();
            }
            const Eigen::MatrixXf &bodyDisplacementCoefficients() const
            {
                return bodyCoefficients_;
            }
            const std::shared_ptr<const RobotGroupBodies> &bodies() const
            {
                return bodies_;
            }
            const SphereModelPtr &spheres() const
            {
                return spheres_;
            }
            const ScenePtr &scene() const
            {
                return scene_;
            }

        private:
            struct Scratch;
            void toReals(const ompl::base::State *state, std::vector<double> &values) const;
            /** Frames and bodies' bounding spheres for \e values into \e s; no sphere is placed yet. \e tableCells:
                also the self-pair tables' cells of a state check (a motion piece reads ranges instead). */
            void place(const double *values, Scratch &s, bool tableCells) const;
            /** Sizes a thread's scratch arrays for this checker. */
            void prepare(Scratch &s) const;
            /** World centres of body \e b's spheres into \e s (once per state). */
            void placeBody(std::size_t b, Scratch &s) const;
            /** Spheres of \e body (radii \e r) that reach into the bounding sphere of \e other, placed in the world
                into \e g (x, y, z, r blocks of maxBodySpheres_, then scratch): their count. */
            int spheresNear(Scratch &s, const float *r, std::size_t body, std::size_t other, float *g) const;
            /** Does body \e b (sphere radii \e r, bound in s.bodyRadius) touch obstacle \e o of \e obs? Its bounding
                sphere against the obstacle's own shape first, its spheres (placed on demand) only then. */
            bool bodyTouches(Scratch &s, std::size_t b, const SphereObstacles &obs, int o, const float *r) const;
            /** Do bodies \e a and \e b (radii \e r) have two spheres that touch? */
            bool spheresTouch(Scratch &s, const float *r, std::size_t a, std::size_t b) const;
            bool collides(Scratch &s, const double *values, const float *inflation, const float *valueSpan,
                          const float *bodyInflation, bool useExact, std::string *why) const;
            void makeSelfPairTables();
            const SphereObstacles &obstacles() const;

            std::shared_ptr<const RobotGroupBodies> bodies_;
            SphereModelPtr spheres_;
            ScenePtr scene_;
            // per robot body (link with spheres): its spheres are [begin_[b], begin_[b + 1])
            std::vector<int> bodyLink_;
            std::vector<int> begin_;
            std::size_t maxBodySpheres_{0};            ///< spheres of the largest body
            std::uint64_t id_{0};                      ///< unique among the process's checkers (per-thread scratch)
            std::vector<Eigen::Vector3f> bodyCentre_;  ///< bounding sphere of the body's spheres, link frame
            std::vector<float> bodyRadius_;
            std::vector<float> cx_, cy_, cz_, radius_;  ///< sphere centres in the link frame, padded radii
            std::unique_ptr<SphereKinematics> kinematics_;
            std::vector<int> bodyFrame_;                ///< frame (SphereKinematics) each body rides on
            std::vector<float> fx_, fy_, fz_;           ///< sphere centres in their body's frame
            std::vector<Eigen::Vector3f> frameCentre_;  ///< bounding sphere centres in the body's frame
            bool exactStates_{false};
            /** with exactStates_: FCL settles every contact (setExactStates), or only those named below
                (setExactContacts) */
            bool exactEverywhere_{true};
            std::vector<std::string> exactObstacles_;  ///< sorted obstacle names FCL settles
            std::vector<char> exactPairs_;             ///< per bodies_->selfCheckPairs(): FCL settles the pair
            bool tablesFromDisk_{false};
            /** the state space when it is a RealVectorStateSpace: states are read in place, without copyToReals */
            const ompl::base::RealVectorStateSpace *realVector_{nullptr};
            std::vector<std::pair<int, int>> selfPairs_;
            std::vector<int> selfPairIndex_;
            /** self pairs (selfPairs_ indices) not between two static bodies: decided by a table, by spheres */
            std::vector<int> tablePairs_, spherePairs_;
            std::vector<int> robotBody_;     ///< index of each body in bodies_->bodies()
            std::vector<char> static_;       ///< body not moved by the group (decided by FCL when exact_ is given)
            bool staticSelfBlocked_{false};  ///< index of each pair in bodies_->selfCheckPairs()
            FclValidityCheckerPtr exact_;
            /** per self pair (selfPairs_ order): its table, or null when spheres (and FCL) decide it; the tables
                depend on the robot only and are shared by checkers of the same robot and sphere model */
            std::shared_ptr<const std::vector<std::shared_ptr<const SelfPairTable>>> pairTables_;
            Eigen::MatrixXf bodyCoefficients_;
            Eigen::MatrixXf coefficients_;
            std::vector<double> fullTemplate_;  ///< the whole robot's configuration (other joints fixed)
            // scene snapshots: every one made is kept (a query may still read an older one)
            mutable std::mutex snapshotMutex_;
            mutable std::vector<std::unique_ptr<SphereObstacles>> snapshots_;
            mutable std::atomic<const SphereObstacles *> current_{nullptr};
        };

        using SphereValidityCheckerPtr = std::shared_ptr<SphereValidityChecker>;
    }  // namespace validity
}  // namespace michi

#endif
