#ifndef MICHI_STATE_SPACES_JOINT_STATE_SPACE_
#define MICHI_STATE_SPACES_JOINT_STATE_SPACE_

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/StateSpace.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <string>
#include <vector>

namespace michi
{
    namespace state_spaces
    {
        /** \brief One joint of a joint space. */
        struct JointSpec
        {
            std::string name;
            double lower{0.};
            double upper{0.};
            bool continuous{false};  ///< wraps around (SO(2)); lower/upper are then ignored
        };

        /** \brief Joint space of an arm whose joints are all bounded: a RealVectorStateSpace with named
            dimensions and a default projection that works on Debian's OMPL 1.5.2 (whose identity projection
            aborts on 1-D and 2-D spaces), so KPIECE1, SBL, ProjEST, PDST run on it. */
        class BoundedJointStateSpace : public ompl::base::RealVectorStateSpace
        {
        public:
            explicit BoundedJointStateSpace(const std::vector<JointSpec> &joints);
            void registerProjections() override;
        };

        /** \brief Joint space with at least one continuous joint: a compound of one subspace per joint
            (RealVectorStateSpace(1) for bounded joints, SO2StateSpace for continuous ones), in joint order, so
            copyToReals/copyFromReals give the joint values in order. Registers a default projection. */
        class CompoundJointStateSpace : public ompl::base::CompoundStateSpace
        {
        public:
            explicit CompoundJointStateSpace(const std::vector<JointSpec> &joints);
            void registerProjections() override;
        };

        /** \brief The joint space for \e joints: BoundedJointStateSpace when none is continuous, else
            CompoundJointStateSpace. Throws std::invalid_argument for an empty list or lower > upper. */
        ompl::base::StateSpacePtr makeJointStateSpace(const std::vector<JointSpec> &joints);

        /** \brief Projection onto the first min(3, dimension) values of copyToReals, with cell sizes of 1/20 of
            each dimension's extent. Replaces OMPL 1.5.2's identity projection, which aborts on small spaces. */
        class LeadingValuesProjection : public ompl::base::ProjectionEvaluator
        {
        public:
            explicit LeadingValuesProjection(const ompl::base::StateSpace *space, unsigned int dims = 0);
            unsigned int getDimension() const override;
            void defaultCellSizes() override;
            void project(const ompl::base::State *state, Eigen::Ref<Eigen::VectorXd> projection) const override;

        private:
            unsigned int dims_;
        };

        /** \brief Bound x and y of an SE(2) space (yaw wraps); throws std::invalid_argument unless min < max. */
        void setSe2Bounds(ompl::base::SE2StateSpace &space, double xMin, double xMax, double yMin, double yMax);

        /** \brief SE(2) space whose default projection (x, y) works on Debian's OMPL 1.5.2. */
        ompl::base::StateSpacePtr makeSe2StateSpace(double xMin, double xMax, double yMin, double yMax);
    }  // namespace state_spaces
}  // namespace michi

#endif
