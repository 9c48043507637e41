#ifndef MICHI_TOOLS_SRC_SVG_ROBOT_
#define MICHI_TOOLS_SRC_SVG_ROBOT_

// Private to michi_tools (not installed): the robot as writeProblemSvg() draws it, projected (SvgRobot.cpp).

#include "SvgView.h"

#include <michi/tools/problem/Problem.h>

#include <Eigen/Geometry>

#include <set>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
            /** One robot pose seen through a view: what is drawn of it. */
            struct RobotPicture
            {
                std::vector<MultiPolygon2> shapes;  ///< link shadows (arm) or the footprint (SE2)
                Polyline skeleton;                  ///< arm: joint origins, root first; SE2: heading tick
                Vec2 end{Vec2::Zero()};             ///< arm: end link origin; SE2: x, y
                bool arm{false};
            };

            /** What the picture needs of the robot: its projected shapes for a state, which values wrap, and
                whether it moves out of the x-y plane. A view is an isometry applied to world coordinates before
                the x, y of the result are drawn (top view: identity). */
            class RobotGeometry
            {
            public:
                explicit RobotGeometry(const Problem &problem);

                bool wraps(std::size_t i) const
                {
                    return wraps_[i];
                }
                const std::vector<bool> &wraps() const
                {
                    return wraps_;
                }
                /** True for robots whose links leave planes parallel to x-y (they get a side view). */
                bool spatial() const
                {
                    return spatial_;
                }

                RobotPicture picture(const Values &values, const Eigen::Isometry3d &view) const;

                /** The end link's origin (arm) or x, y (SE2) at \e values: the point a trace follows. */
                Vec2 endPoint(const Values &values, const Eigen::Isometry3d &view) const;

                /** Links that no planned joint moves (drawn once), at the group's values \e values. */
                std::vector<MultiPolygon2> fixedLinks(const Values &values, const Eigen::Isometry3d &view) const;

                /** Per link: moved by a planned joint (ARM; empty for SE2). */
                const std::vector<bool> &movedLinks() const
                {
                    return moved_;
                }

                /** The link a trace follows (the end of the skeleton), or -1 (SE2, or no planned joint). */
                int endLink() const
                {
                    return skeleton_.empty() ? -1 : skeleton_.back();
                }

            private:
                Values fullConfiguration(const Values &values) const;

                /** moved_: links below a planned joint. skeleton_: links from the root to the end link, the child
                    of the deepest planned joint followed down while the tree does not branch (a flange or tool
                    frame, not one of several fingers). */
                void findMovedLinks(const std::set<int> &groupJoints);

                /** A revolute joint about a non-vertical axis or a prismatic joint along a non-horizontal one
                    moves links out of the x-y plane. Parents that only turn about z keep every axis's angle to z,
                    so one configuration decides. */
                bool movesOutOfPlane(const std::set<int> &groupJoints) const;

                void addLinkShapes(std::size_t link, const Eigen::Isometry3d &pose,
                                   std::vector<MultiPolygon2> &shapes) const;

                RobotPicture armPicture(const Values &values, const Eigen::Isometry3d &view) const;

                RobotPicture footprintPicture(const Values &values, const Eigen::Isometry3d &view) const;

                const Problem &problem_;
                std::vector<bool> wraps_;
                std::vector<bool> moved_;  ///< per link: moved by a planned joint
                std::vector<int> skeleton_;
                bool spatial_{false};
                double headingLength_{0.};
            };
        }  // namespace svg_plot
    }      // namespace tools
}  // namespace michi

#endif
