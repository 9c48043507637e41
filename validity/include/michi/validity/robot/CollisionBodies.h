#ifndef MICHI_VALIDITY_COLLISION_BODIES_
#define MICHI_VALIDITY_COLLISION_BODIES_

#include <michi/validity/robot/RobotModel.h>
#include <michi/validity/scene/Shape.h>

#include <Eigen/Geometry>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace validity
    {
        /** \brief A rigid part of a robot: shapes fixed in one frame. */
        struct Body
        {
            std::string name;
            std::vector<LinkCollision> shapes;
        };

        /** \brief What a validity checker needs of a robot: bodies whose poses follow from a vector of reals
            (the state as `StateSpace::copyToReals` gives it). Implementations are immutable and thread-safe. */
        class CollisionBodies
        {
        public:
            virtual ~CollisionBodies() = default;
            /** \brief Number of reals in a configuration. */
            virtual std::size_t dimension() const = 0;
            virtual const std::vector<Body> &bodies() const = 0;
            /** \brief World pose of every body for configuration \e values. */
            virtual void bodyPoses(const double *values, std::vector<Eigen::Isometry3d> &poses) const = 0;
            /** \brief Body pairs that must not touch each other. */
            virtual const std::vector<std::pair<int, int>> &selfCheckPairs() const = 0;
            /** \brief Upper bound on how far any point of any body moves between two configurations (metres),
                used by the conservative motion validator. */
            virtual double displacementBound(const double *from, const double *to) const = 0;
            /** \brief The same bound for each body separately (bodies that do not move get 0). */
            virtual void bodyDisplacementBounds(const double *from, const double *to,
                                                std::vector<double> &bounds) const = 0;
        };

        using CollisionBodiesPtr = std::shared_ptr<const CollisionBodies>;

        /** \brief The links of a RobotModel moved by a group of its joints; the other joints keep fixed values. */
        class RobotGroupBodies : public CollisionBodies
        {
        public:
            /** \param variables configuration indices the group moves, in state order
                \param fixedValues a full configuration giving the values of the other joints */
            RobotGroupBodies(RobotModelPtr model, std::vector<int> variables, std::vector<double> fixedValues);

            std::size_t dimension() const override
            {
                return variables_.size();
            }
            const std::vector<Body> &bodies() const override
            {
                return bodies_;
            }
            void bodyPoses(const double *values, std::vector<Eigen::Isometry3d> &poses) const override;
            const std::vector<std::pair<int, int>> &selfCheckPairs() const override
            {
                return pairs_;
            }
            double displacementBound(const double *from, const double *to) const override;
            void bodyDisplacementBounds(const double *from, const double *to,
                                        std::vector<double> &bounds) const override;

            /** \brief The full configuration for group values \e values. */
            std::vector<double> fullConfiguration(const double *values) const;
            const RobotModelPtr &model() const
            {
                return model_;
            }
            const std::vector<int> &variables() const
            {
                return variables_;
            }
            /** \brief Link index of body \e body. */
            int bodyLink(std::size_t body) const
            {
                return bodyLinks_[body];
            }

        private:
            RobotModelPtr model_;
            std::vector<int> variables_;
            std::vector<double> fixedValues_;
            std::vector<Body> bodies_;
            std::vector<int> bodyLinks_;
            std::vector<std::pair<int, int>> pairs_;
        };

        /** \brief A rigid robot moving in the plane (x, y, yaw): a footprint polygon extruded over a height.
            Configuration: x, y, yaw (the order of OMPL's SE2StateSpace). */
        class PlanarRigidBody : public CollisionBodies
        {
        public:
            PlanarRigidBody(std::vector<Eigen::Vector2d> footprint, double zMin = 0., double zMax = 1.);

            std::size_t dimension() const override
            {
                return 3;
            }
            const std::vector<Body> &bodies() const override
            {
                return bodies_;
            }
            void bodyPoses(const double *values, std::vector<Eigen::Isometry3d> &poses) const override;
            const std::vector<std::pair<int, int>> &selfCheckPairs() const override
            {
                return pairs_;
            }
            double displacementBound(const double *from, const double *to) const override;
            void bodyDisplacementBounds(const double *from, const double *to,
                                        std::vector<double> &bounds) const override;
            const std::vector<Eigen::Vector2d> &footprint() const
            {
                return footprint_;
            }
            /** \brief Radius of the smallest circle about the body origin that contains the footprint. */
            double circumradius() const
            {
                return circumradius_;
            }

        private:
            std::vector<Eigen::Vector2d> footprint_;
            std::vector<Body> bodies_;
            std::vector<std::pair<int, int>> pairs_;
            double circumradius_{0.};
        };
    }  // namespace validity
}  // namespace michi

#endif
