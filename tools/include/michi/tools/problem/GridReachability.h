#ifndef MICHI_TOOLS_GRID_REACHABILITY_
#define MICHI_TOOLS_GRID_REACHABILITY_

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorBounds.h>

#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief Connected components of a grid over a 2-D bounded real vector space (a two-joint arm's joint
            space): cell centres of step about \e step, valid ones joined to their 4 neighbours by motions the
            space's motion validator accepts. Two states are linked when each reaches, in one accepted motion, a
            grid point of the same component, so reachable() never says yes for states that no path joins (with
            an exact motion validator); it can say no across passages narrower than the grid. */
        class GridComponents
        {
        public:
            /** \brief Throws std::invalid_argument unless the space is a 2-D RealVectorStateSpace and step > 0. */
            GridComponents(const ompl::base::SpaceInformationPtr &si, double step);
            ~GridComponents();
            GridComponents(const GridComponents &) = delete;
            GridComponents &operator=(const GridComponents &) = delete;

            /** \brief Components of the grid points near \e q (the cell and its 8 neighbours) that \e q reaches in
                one accepted motion; empty when none. */
            std::vector<int> attach(const std::vector<double> &q) const;
            /** \brief True when \e start and \e goal attach to a common component. */
            bool reachable(const std::vector<double> &start, const std::vector<double> &goal) const;
            /** \brief Number of components. */
            int components() const
            {
                return components_;
            }

        private:
            double value(int axis, int i) const;
            void set(ompl::base::State *s, double x, double y) const;

            ompl::base::SpaceInformationPtr si_;
            ompl::base::RealVectorBounds bounds_{2};
            int nx_{0}, ny_{0};
            int components_{0};
            std::vector<int> label_;
            ompl::base::State *a_{nullptr}, *b_{nullptr};
        };

        /** \brief GridComponents(si, step).reachable(start, goal). */
        bool gridReachable(const ompl::base::SpaceInformationPtr &si, const std::vector<double> &start,
                           const std::vector<double> &goal, double step);
    }  // namespace tools
}  // namespace michi

#endif
