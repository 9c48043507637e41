#include <michi/state_spaces/JointStateSpace.h>

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include <stdexcept>

namespace ob = ompl::base;

namespace michi
{
    namespace state_spaces
    {
        namespace
        {
            void checkJoints(const std::vector<JointSpec> &joints)
            {
                if (joints.empty())
                    throw std::invalid_argument("a joint space needs at least one joint");
                for (const auto &j : joints)
                    if (!j.continuous && !(j.lower < j.upper))
                        throw std::invalid_argument("joint '" + j.name + "': lower limit must be below upper");
            }
        }  // namespace

        LeadingValuesProjection::LeadingValuesProjection(const ob::StateSpace *space, unsigned int dims)
            : ob::ProjectionEvaluator(space)
            // At most 3 leading values by default: KPIECE-style planners keep a grid over the projection, and their
            // cells grow exponentially with its dimension.
            , dims_(dims == 0 ? std::min(3u, space->getDimension()) : std::min(dims, space->getDimension()))
        {
        }

        unsigned int LeadingValuesProjection::getDimension() const
        {
            return dims_;
        }

        // Our own projection because OMPL 1.5.2's RealVectorIdentityProjectionEvaluator aborts the KPIECE family on
        // 1-D/2-D spaces (DESIGN.md, known traps). Cells are 1/20 of each value's extent.
        void LeadingValuesProjection::defaultCellSizes()
        {
            // extent of each leading value: the bounds of a RealVector (sub)space, 2 pi for SO(2)
            cellSizes_.assign(dims_, 2. * M_PI / 20.);
            std::vector<double> extents;
            if (const auto *rv = dynamic_cast<const ob::RealVectorStateSpace *>(space_))
                extents = rv->getBounds().getDifference();
            else if (const auto *cs = dynamic_cast<const ob::CompoundStateSpace *>(space_))
                for (unsigned int i = 0; i < cs->getSubspaceCount() && extents.size() < dims_; ++i)
                {
                    const auto &sub = cs->getSubspace(i);
                    if (const auto *r = dynamic_cast<const ob::RealVectorStateSpace *>(sub.get()))
                        for (double d : r->getBounds().getDifference())
                            extents.push_back(d);
                    else
                        extents.push_back(2. * M_PI);
                }
            for (unsigned int i = 0; i < dims_ && i < extents.size(); ++i)
                cellSizes_[i] = extents[i] / 20.;
        }

        void LeadingValuesProjection::project(const ob::State *state, Eigen::Ref<Eigen::VectorXd> projection) const
        {
            std::vector<double> values;
            space_->copyToReals(values, state);
            for (unsigned int i = 0; i < dims_; ++i)
                projection(i) = values[i];
        }

        BoundedJointStateSpace::BoundedJointStateSpace(const std::vector<JointSpec> &joints)
            : ob::RealVectorStateSpace(static_cast<unsigned int>(joints.size()))
        {
            checkJoints(joints);
            setName("Joints" + getName());
            for (std::size_t i = 0; i < joints.size(); ++i)
            {
                if (joints[i].continuous)
                    throw std::invalid_argument("joint '" + joints[i].name +
                                                "' is continuous: use CompoundJointStateSpace");
                setDimensionName(static_cast<unsigned int>(i), joints[i].name);
                bounds_.setLow(static_cast<unsigned int>(i), joints[i].lower);
                bounds_.setHigh(static_cast<unsigned int>(i), joints[i].upper);
            }
        }

        void BoundedJointStateSpace::registerProjections()
        {
            registerDefaultProjection(std::make_shared<LeadingValuesProjection>(this));
        }

        CompoundJointStateSpace::CompoundJointStateSpace(const std::vector<JointSpec> &joints)
        {
            checkJoints(joints);
            setName("CompoundJoints" + getName());
            for (const auto &j : joints)
            {
                ob::StateSpacePtr sub;
                if (j.continuous)
                    sub = std::make_shared<ob::SO2StateSpace>();
                else
                {
                    auto rv = std::make_shared<ob::RealVectorStateSpace>(1);
                    rv->setBounds(j.lower, j.upper);
                    sub = rv;
                }
                sub->setName(j.name);
                // Weight 1 for every joint: distance is the plain sum over joints, as in the bounded space, so planners
                // behave alike whichever of the two spaces makeJointStateSpace() picks.
                addSubspace(sub, 1.);
            }
            // Locked like OMPL's own compound spaces (SE2, SE3): no one may add joints after construction.
            lock();
        }

        void CompoundJointStateSpace::registerProjections()
        {
            registerDefaultProjection(std::make_shared<LeadingValuesProjection>(this));
        }

        ob::StateSpacePtr makeJointStateSpace(const std::vector<JointSpec> &joints)
        {
            checkJoints(joints);
            for (const auto &j : joints)
                if (j.continuous)
                    return std::make_shared<CompoundJointStateSpace>(joints);
            // Only a continuous joint needs SO(2)'s wrap-around; otherwise a flat RealVector space is cheaper to copy,
            // interpolate and measure.
            return std::make_shared<BoundedJointStateSpace>(joints);
        }

        void setSe2Bounds(ob::SE2StateSpace &space, double xMin, double xMax, double yMin, double yMax)
        {
            if (!(xMin < xMax) || !(yMin < yMax))
                throw std::invalid_argument("SE(2) bounds must have min < max");
            ob::RealVectorBounds bounds(2);
            bounds.setLow(0, xMin);
            bounds.setHigh(0, xMax);
            bounds.setLow(1, yMin);
            bounds.setHigh(1, yMax);
            space.setBounds(bounds);
        }

        ob::StateSpacePtr makeSe2StateSpace(double xMin, double xMax, double yMin, double yMax)
        {
            auto space = std::make_shared<ob::SE2StateSpace>();
            setSe2Bounds(*space, xMin, xMax, yMin, yMax);
            return space;
        }
    }  // namespace state_spaces
}  // namespace michi
