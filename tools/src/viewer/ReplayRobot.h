#ifndef MICHI_TOOLS_SRC_VIEWER_REPLAY_ROBOT_
#define MICHI_TOOLS_SRC_VIEWER_REPLAY_ROBOT_

// Private to michi_tools: the robot of a replay page as rigid bodies whose poses michi computes per state
// (ReplayRobot.cpp). The arm's links are the ones the SVG pictures draw (svg_plot::RobotGeometry), so both show the
// same robot.

#include "pictures/SvgRobot.h"
#include "viewer/ReplayShapes.h"

#include <michi/tools/problem/Problem.h>

#include <Eigen/Geometry>

#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace replay
        {
            /** A rigid body of the robot: collision shapes (ShapeTable indices) placed in the body's frame. */
            struct Body
            {
                std::string name;
                std::vector<std::pair<int, Eigen::Isometry3d>> parts;
            };

            class RobotBodies
            {
            public:
                /** ARM: one body per link a planned joint moves that has collision geometry, plus the end link
                    (for the trace) even without; SE2: the footprint extruded to the robot's height. */
                RobotBodies(const Problem &problem, ShapeTable &shapes, const std::vector<double> &fixedValues = {});

                const std::vector<Body> &bodies() const
                {
                    return bodies_;
                }
                /** The body whose origin the end-effector trace follows, or -1. */
                int endBody() const
                {
                    return endBody_;
                }
                /** True when the robot moves in planes parallel to x-y (SE2, planar arms): the page looks from above.
                 */
                bool planar() const
                {
                    return problem_.kind == Problem::Kind::SE2 || !geometry_.spatial();
                }
                /** The world pose of every body at the planned values \e values. */
                std::vector<Eigen::Isometry3d> poses(const std::vector<double> &values) const;

                /** "[[shape,pose],...]": the links no planned joint moves, placed in the world once. */
                std::string staticPartsJson(ShapeTable &shapes) const;

                /** "[{"name":...,"parts":[[shape,pose],...]},...]" */
                std::string bodiesJson() const;

            private:
                /** The full configuration: \e values for the planned joints, fixed_ for the others. */
                std::vector<double> fullConfiguration(const std::vector<double> &values) const;

                const Problem &problem_;
                std::vector<double> fixed_;
                svg_plot::RobotGeometry geometry_;
                std::vector<Body> bodies_;
                std::vector<int> links_;  ///< ARM: the link of each body
                int endBody_{-1};
            };
        }  // namespace replay
    }      // namespace tools
}  // namespace michi

#endif
