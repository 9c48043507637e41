#ifndef MICHI_TOOLS_TASK_REGION_QUERIES_
#define MICHI_TOOLS_TASK_REGION_QUERIES_

#include <michi/tools/problem/Problem.h>

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief A region of hand poses: the tool point anywhere in an axis-aligned box, the tool's axis within
            \e cone radians of \e direction (rotation about the axis free). */
        struct TaskRegion
        {
            std::string name;
            Eigen::Vector3d lower{Eigen::Vector3d::Zero()}, upper{Eigen::Vector3d::Zero()};
            Eigen::Vector3d direction{Eigen::Vector3d::UnitX()};  ///< unit, world frame
            double cone{0.};                                      ///< radians, in [0, pi]
        };

        /** \brief Task regions of an arm problem (a YAML file, docs/path-seed.md):
            \code
            tip_link: link6           # the hand's link
            tool_axis: [0, 0, 1]      # the hand's approach axis in that link's frame
            tool_point: [0, 0, 0]     # optional: the tool point in that link's frame
            regions:
              - {name: through, box: {min: [0.55, -0.05, 0.3], max: [0.62, 0.05, 0.4]}, direction: [1, 0, 0],
                 cone: 0.3}
              - ...
            pairs: [[above, through], ...]   # optional: (start region, goal region); default every ordered
                                             # pair of two different regions
            \endcode */
        struct TaskRegions
        {
            std::string file;
            std::string tipLink;
            Eigen::Vector3d toolAxis{Eigen::Vector3d::UnitZ()};
            Eigen::Vector3d toolPoint{Eigen::Vector3d::Zero()};
            std::vector<TaskRegion> regions;
            std::vector<std::pair<std::size_t, std::size_t>> pairs;  ///< indices into regions
        };

        /** \brief Read task regions; throws ProblemError naming the file and key for anything malformed (unknown
            link, a box with min above max, a zero direction, an unknown region in pairs). */
        TaskRegions readTaskRegions(const std::string &file, const Problem &problem);

        /** \brief \e count queries whose start and goal are drawn independently: for query i a (start region,
            goal region) pair uniformly from regions.pairs, then in each region a uniform tool point and a uniform
            axis direction within the cone, solved by damped-least-squares IK from random joint values (up to
            \e ikAttempts seeds); a pose whose solutions are outside the joint limits or in collision (FCL) is
            drawn again. The first \e training are the training set, the rest held out: the same distribution,
            and no query repeats another. Deterministic for a seed. Throws std::runtime_error when a region
            yields no valid state in 2000 poses, or when the regions keep giving states already drawn (more than
            100 draws per query). */
        ExperienceQueries generateTaskRegionQueries(const Problem &problem, const TaskRegions &regions,
                                                    std::size_t count, std::size_t training, unsigned int seed);
    }  // namespace tools
}  // namespace michi

#endif
