#ifndef MICHI_VALIDITY_LIMITS_
#define MICHI_VALIDITY_LIMITS_

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>
#include <string>

namespace michi
{
    namespace validity
    {
        /** \brief Largest coordinate or size (metres) michi's geometry accepts. FCL squares coordinates when it
            builds bounding volumes, so anything near sqrt(DBL_MAX) = 1.3e154 overflows to inf and crashes its
            broad phase; 1e6 m (1,000 km) is far beyond any robot's workspace yet keeps every square, sum and
            product of geometry finite with room to spare. Numbers are checked where they enter (problem files,
            URDFs, meshes, maps), so a bad value is named there and never reaches FCL. */
        constexpr double MAX_COORDINATE = 1e6;

        /** \brief Largest occupancy grid (cells) a map may have: 100 million cells (a 10,000 x 10,000 image,
            1 km square at 0.1 m) holds every MovingAI map and keeps a map's tables under a few GB. */
        constexpr unsigned long long MAX_MAP_CELLS = 100000000ULL;

        /** \brief True when \e v is finite and |v| <= MAX_COORDINATE. */
        inline bool isGeometryValue(double v)
        {
            return std::isfinite(v) && std::abs(v) <= MAX_COORDINATE;
        }

        /** \brief Why \e v is not a geometry value ("" when it is), for messages. */
        inline std::string geometryValueProblem(double v)
        {
            if (std::isnan(v))
                return "is not a number (nan)";
            if (!std::isfinite(v))
                return "is infinite";
            if (std::abs(v) > MAX_COORDINATE)
                return "is out of range (|value| above 1e6 m)";
            return "";
        }

        /** \brief Throws std::invalid_argument("<what> <problem>") unless \e v is a geometry value. */
        inline void requireGeometryValue(double v, const std::string &what)
        {
            if (!isGeometryValue(v))
                throw std::invalid_argument(what + " " + geometryValueProblem(v));
        }

        /** \brief A rigid transform with finite rotation and a translation within MAX_COORDINATE. */
        inline void requireGeometryPose(const Eigen::Isometry3d &pose, const std::string &what)
        {
            for (int i = 0; i < 3; ++i)
                requireGeometryValue(pose.translation()[i], what + " position");
            if (!pose.linear().allFinite())
                throw std::invalid_argument(what + " orientation is not finite");
        }
    }  // namespace validity
}  // namespace michi

#endif
