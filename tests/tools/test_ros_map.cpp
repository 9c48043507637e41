// ROS map_server maps as scene.map.ros (issue 14): the bundled problems/ros_office.yaml (YAML + PNG) loads with its
// walls, desks and unknown space as obstacles; map_server's trinary and scale modes, negate and thresholds on small
// PGM images; and every bad map file or key gives a one-line error naming the file and the key.
#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <ompl/base/ScopedState.h>

#include <boost/filesystem.hpp>
#include "support/MichiCommand.h"

#include <gtest/gtest.h>

#include <png.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <set>
#include <vector>

namespace fs = boost::filesystem;
namespace ob = ompl::base;

namespace
{
    class RosMaps : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            dir_ = fs::temp_directory_path() / fs::unique_path("michi-rosmap-%%%%%%%%");
            fs::create_directories(dir_);
            // one row of 4 pixels: black, ROS's unknown grey, white, mid grey (P2, maximum 255)
            write("row.pgm", "P2\n4 1\n255\n0 205 254 100\n");
        }
        void TearDown() override
        {
            fs::remove_all(dir_);
        }
        std::string write(const std::string &name, const std::string &text)
        {
            std::ofstream(dir_ / name) << text;
            return (dir_ / name).string();
        }
        /** A problem whose scene is the ROS map file \e map (written with \e text). */
        std::string problem(const std::string &mapText, const std::string &sceneMap = "{ros: m.yaml}")
        {
            write("m.yaml", mapText);
            return write("p.yaml",
                         "name: p\nrobot: {type: se2, footprint: [[-0.01, -0.01], [0.01, -0.01], "
                         "[0.01, 0.01], [-0.01, 0.01]], bounds: {x: [0, 12], y: [0, 1]}}\n"
                         "scene: {map: " +
                             sceneMap + "}\nstart: [10.5, 0.5, 0]\ngoal: [10.6, 0.5, 0]\n");
        }
        /** The columns of the one-row map's occupied cells. */
        std::set<int> occupied(const std::string &mapText)
        {
            const auto p = michi::tools::loadProblem(problem(mapText));
            std::set<int> columns;
            for (const auto &o : p.scene->obstacles())
            {
                const double x0 = o.pose.translation().x() - 0.5 * o.shape->size().x();
                const double x1 = o.pose.translation().x() + 0.5 * o.shape->size().x();
                for (int c = 0; c < 8; ++c)
                    if (c + 0.5 > x0 && c + 0.5 < x1)
                        columns.insert(c);
            }
            return columns;
        }
        /** A one-row PNG map of \e samples (per pixel \e channels values: grey, grey + alpha or RGBA), 8 or 16
            bits a sample, as stored (not converted between linear and sRGB). */
        void writePng(const std::string &name, const std::vector<int> &samples, int channels, bool sixteen)
        {
            png_image png;
            std::memset(&png, 0, sizeof(png));
            png.version = PNG_IMAGE_VERSION;
            png.width = static_cast<png_uint_32>(samples.size() / channels);
            png.height = 1;
            png.format = channels == 1 ? PNG_FORMAT_GRAY : channels == 2 ? PNG_FORMAT_GA : PNG_FORMAT_RGBA;
            if (sixteen)
            {
                // libpng's simplified writer takes 16-bit samples as linear and premultiplied by alpha: given
                // opaque or grey-only pixels here, it writes them as they are
                png.format |= PNG_FORMAT_FLAG_LINEAR;
                std::vector<std::uint16_t> data(samples.begin(), samples.end());
                ASSERT_NE(png_image_write_to_file(&png, (dir_ / name).c_str(), 0, data.data(), 0, nullptr), 0)
                    << png.message;
            }
            else
            {
                std::vector<std::uint8_t> data(samples.begin(), samples.end());
                ASSERT_NE(png_image_write_to_file(&png, (dir_ / name).c_str(), 0, data.data(), 0, nullptr), 0)
                    << png.message;
            }
        }
        std::string error(const std::string &path)
        {
            return michi::test::problemLoadError(path, false);
        }
        fs::path dir_;
    };
}  // namespace

TEST(RosMap, BundledOfficeLoadsWithUnknownSpaceAsObstacles)
{
    const auto problem = michi::tools::loadProblem(std::string(MICHI_SOURCE_DIR) + "/problems/ros_office.yaml");
    EXPECT_GT(problem.scene->obstacles().size(), 50u);
    EXPECT_DOUBLE_EQ(problem.grid.mapResolution, 0.05);  // the grid checker's cells align with the map's
    auto ctx = michi::tools::makePlanningContext(problem);
    auto si = ctx.setup->getSpaceInformation();
    auto at = [&](double x, double y, double yaw)
    {
        ob::ScopedState<> s(si->getStateSpace());
        si->getStateSpace()->copyFromReals(s.get(), {x, y, yaw});
        return si->isValid(s.get());
    };
    EXPECT_TRUE(at(1.0, 0.5, 0.));          // the corridor
    EXPECT_TRUE(at(1.45, 1.35, M_PI / 2));  // in room A's door, facing through it
    EXPECT_FALSE(at(1.2, 1.35, 0.));        // across it, beside its post
    EXPECT_FALSE(at(6.7, 4.7, 0.));         // the storeroom nobody mapped (unknown)
    EXPECT_FALSE(at(7.45, 2.5, M_PI / 2));  // unknown space outside the outer wall, inside the image
    EXPECT_FALSE(at(1.3, 3.7, 0.));         // room A's desk
}

TEST_F(RosMaps, TrinaryScaleAndNegateAsMapServerReadsThem)
{
    const std::string base = "image: row.pgm\nresolution: 1\norigin: [0, 0, 0]\n";
    // trinary (default): p = (255 - v) / 255 = 1, 0.196, 0.004, 0.61: occupied, unknown, free, unknown
    EXPECT_EQ(occupied(base + "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"), (std::set<int>{0, 1, 3}));
    // a lower occupied threshold makes the mid grey occupied, a higher free threshold makes ROS's grey free
    EXPECT_EQ(occupied(base + "negate: 0\noccupied_thresh: 0.5\nfree_thresh: 0.3\n"), (std::set<int>{0, 3}));
    // negate: p = v / 255 = 0, 0.80, 0.996, 0.39
    EXPECT_EQ(occupied(base + "negate: 1\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"), (std::set<int>{1, 2, 3}));
    // scale: the values between the thresholds are occupancies below the occupied threshold, not obstacles
    EXPECT_EQ(occupied(base + "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: scale\n"),
              (std::set<int>{0}));
    // nav2's defaults (0.65, 0.25) when the thresholds and negate are left out
    EXPECT_EQ(occupied(base), (std::set<int>{0, 3}));
}

TEST_F(RosMaps, SixteenBitPngsAndTransparentPixelsAsMapServerReadsThem)
{
    // fractions of white 0, .3, .5, .6, .65, .7, .8, 1: occupancy 1, .7, .5, .4, .35, .3, .2, 0. A 16-bit PNG was
    // read through an sRGB conversion that made 0.3 of white read as 0.58, so dark cells came out free.
    const std::vector<double> shades{0., .3, .5, .6, .65, .7, .8, 1.};
    std::vector<int> grey16, grey8;
    for (const double v : shades)
    {
        grey16.push_back(static_cast<int>(std::lround(v * 65535)));
        grey8.push_back(static_cast<int>(std::lround(v * 255)));
    }
    writePng("g16.png", grey16, 1, true);
    writePng("g8.png", grey8, 1, false);
    const std::string thresholds =
        "resolution: 1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
        "free_thresh: 0.25\n";
    for (const std::string image : {"g16.png", "g8.png"})
    {
        // trinary: occupied above .65, unknown (blocked) from .25 to .65
        EXPECT_EQ(occupied("image: " + image + "\n" + thresholds), (std::set<int>{0, 1, 2, 3, 4, 5})) << image;
        // scale: only the occupied cells
        EXPECT_EQ(occupied("image: " + image + "\n" + thresholds + "mode: scale\n"), (std::set<int>{0, 1})) << image;
    }
    // Transparent pixels: trinary mode averages alpha in with the three colour channels (both map_servers), so a
    // transparent white pixel is unknown, not free; scale mode calls every pixel that is not opaque unknown. White
    // then black at alpha 255, 200, 128, 0.
    std::vector<int> rgba;
    for (const int colour : {255, 0})
        for (const int alpha : {255, 200, 128, 0})
            rgba.insert(rgba.end(), {colour, colour, colour, alpha});
    writePng("rgba.png", rgba, 4, false);
    // white: occupancy 1 - (3 + a) / 4 = 0, .054, .125, .25 (unknown at free_thresh .25); black: .75 and up
    EXPECT_EQ(occupied("image: rgba.png\n" + thresholds), (std::set<int>{3, 4, 5, 6, 7}));
    EXPECT_EQ(occupied("image: rgba.png\n" + thresholds + "mode: scale\n"), (std::set<int>{1, 2, 3, 4, 5, 6, 7}));
    // A colour pixel's mean is not rounded down: negated, (166, 166, 167) is occupancy 0.6523 (occupied at 0.651);
    // its integer mean 166 read 0.65098 (free). The second pixel, black, is free.
    writePng("rgb.png", {166, 166, 167, 255, 0, 0, 0, 255}, 4, false);
    EXPECT_EQ(occupied("image: rgb.png\nresolution: 1\norigin: [0, 0, 0]\nnegate: 1\noccupied_thresh: 0.651\n"
                       "free_thresh: 0.1\nmode: scale\n"),
              (std::set<int>{0}));
}

TEST_F(RosMaps, OriginAndYawPlaceTheMap)
{
    const auto p = michi::tools::loadProblem(
        problem("image: row.pgm\nresolution: 0.5\norigin: [1, 0.25, 0]\n", "{ros: m.yaml, height: 2}"));
    ASSERT_FALSE(p.scene->obstacles().empty());
    const auto &first = p.scene->obstacles().front();  // cell 0: x in [1, 1.5], y in [0.25, 0.75]
    EXPECT_NEAR(first.pose.translation().x() - 0.5 * first.shape->size().x(), 1., 1e-12);
    EXPECT_NEAR(first.pose.translation().y(), 0.5, 1e-12);
    EXPECT_NEAR(first.shape->size().z(), 2., 1e-12);
    const auto turned =
        michi::tools::loadProblem(problem("image: row.pgm\nresolution: 0.5\norigin: [1, 0.25, 1.5707963267948966]\n"));
    const auto &t = turned.scene->obstacles().front();  // turned about the origin: cell 0's centre at (0.75, 0.5)
    EXPECT_NEAR(t.pose.translation().x(), 0.75, 1e-9);
    EXPECT_NEAR(t.pose.translation().y(), 0.5, 1e-9);
    EXPECT_DOUBLE_EQ(turned.grid.mapResolution, 0.);  // a turned map is not aligned with the grid checker
}

TEST_F(RosMaps, BadMapFilesNameTheFileAndKey)
{
    write("text.png", "not an image at all\n");
    struct Case
    {
        std::string map;  // the ROS map file's text
        std::string key;
    };
    const std::string ok = "resolution: 0.1\norigin: [0, 0, 0]\n";
    const std::vector<Case> cases{
        {"resolution: 0.1\norigin: [0, 0, 0]\n", "image"},
        {"image: missing.pgm\n" + ok, "image"},
        {"image: text.png\n" + ok, "image"},
        {"image: row.pgm\nresolution: -1\norigin: [0, 0, 0]\n", "resolution"},
        {"image: row.pgm\nresolution: 0.1\norigin: [0, 0]\n", "origin"},
        {"image: row.pgm\nresolution: 0.1\n", "origin"},
        {"image: row.pgm\n" + ok + "negate: 2\n", "negate"},
        {"image: row.pgm\n" + ok + "occupied_thresh: 1.5\n", "occupied_thresh"},
        {"image: row.pgm\n" + ok + "occupied_thresh: 0.3\nfree_thresh: 0.5\n", "free_thresh"},
        {"image: row.pgm\n" + ok + "mode: raw\n", "mode"},
        {"image: row.pgm\n" + ok + "colour: red\n", "colour"},
        {"[1, 2, 3]\n", "ROS map_server map"},
    };
    for (std::size_t i = 0; i < cases.size(); ++i)
    {
        const std::string what = error(problem(cases[i].map));
        EXPECT_NE(what.find((dir_ / "m.yaml").string()), std::string::npos) << "case " << i << ": " << what;
        EXPECT_NE(what.find(cases[i].key), std::string::npos) << "case " << i << ": " << what;
    }
    // and in the problem file: the keys the map file gives, or both sources
    const std::string good = "image: row.pgm\n" + ok;
    std::string what = error(problem(good, "{ros: m.yaml, resolution: 0.1}"));
    EXPECT_NE(what.find("scene.map.resolution"), std::string::npos) << what;
    EXPECT_NE(what.find("p.yaml"), std::string::npos) << what;
    what = error(problem(good, "{ros: m.yaml, pgm: row.pgm}"));
    EXPECT_NE(what.find("scene.map"), std::string::npos) << what;
    what = error(problem(good, "{ros: none.yaml}"));
    EXPECT_NE(what.find("scene.map.ros"), std::string::npos) << what;
    // a wall height of 0 is the problem file's key, not the map's
    what = error(problem(good, "{ros: m.yaml, height: 0}"));
    EXPECT_NE(what.find("scene.map.height"), std::string::npos) << what;
    EXPECT_NE(what.find("p.yaml"), std::string::npos) << what;
}
