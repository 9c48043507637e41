// Issue 13's property: for every bundled robot and scene, every link that has collision geometry in its URDF takes
// part in collision checking (a link dropped on load would let paths run through obstacles). The URDF is read here
// independently (its text), not through michi's loader.
#include "support/TestScenes.h"

#include <michi/tools/bench/PlanningContext.h>
#include <michi/tools/problem/Problem.h>

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>

namespace fs = boost::filesystem;
using namespace michi;

namespace
{
    /** <collision> elements per link name, read from the URDF's text. */
    std::map<std::string, int> collisionsPerLink(const std::string &urdfFile)
    {
        std::ifstream in(urdfFile);
        std::stringstream text;
        text << in.rdbuf();
        const std::string s = text.str();
        std::map<std::string, int> counts;
        const std::regex link(R"re(<link\s+name\s*=\s*"([^"]+)"\s*(/>|>))re");
        for (auto it = std::sregex_iterator(s.begin(), s.end(), link); it != std::sregex_iterator(); ++it)
        {
            const std::string name = (*it)[1];
            if ((*it)[2] == "/>")
                continue;
            const std::size_t start = static_cast<std::size_t>(it->position() + it->length());
            const std::size_t end = s.find("</link>", start);
            const std::string body = s.substr(start, end - start);
            int n = 0;
            for (std::size_t p = body.find("<collision"); p != std::string::npos; p = body.find("<collision", p + 1))
                ++n;
            if (n > 0)
                counts[name] = n;
        }
        return counts;
    }
}  // namespace

TEST(LinksInChecking, EveryLinkWithCollisionGeometryIsChecked)
{
    int problems = 0, links = 0, probed = 0;
    for (const auto &entry : fs::directory_iterator(test::sourcePath("problems")))
    {
        if (entry.path().extension() != ".yaml")
            continue;
        const tools::Problem problem = tools::loadProblem(entry.path().string());
        if (problem.kind != tools::Problem::Kind::ARM)
            continue;
        ++problems;
        const auto expected = collisionsPerLink(problem.model->source());
        ASSERT_FALSE(expected.empty()) << problem.model->source();
        const tools::PlanningContext ctx = tools::makePlanningContext(problem);
        std::map<std::string, const validity::Body *> bodies;
        for (const auto &b : ctx.bodies->bodies())
            bodies[b.name] = &b;
        for (const auto &kv : expected)
        {
            ++links;
            ASSERT_TRUE(bodies.count(kv.first))
                << entry.path().filename() << ": link '" << kv.first << "' has collision geometry but is not checked";
            EXPECT_EQ(static_cast<int>(bodies[kv.first]->shapes.size()), kv.second) << kv.first;
        }
        // and checking sees each primitive: a small ball at a shape's centre makes the start invalid
        std::vector<double> start;
        ctx.setup->getSpaceInformation()->getStateSpace()->copyToReals(
            start, ctx.setup->getProblemDefinition()->getStartState(0));
        std::vector<Eigen::Isometry3d> poses;
        ctx.bodies->bodyPoses(start.data(), poses);
        const auto &all = ctx.bodies->bodies();
        for (std::size_t b = 0; b < all.size(); ++b)
            for (const auto &shape : all[b].shapes)
            {
                if (shape.shape->type() == validity::Shape::Type::MESH)
                    continue;  // a mesh's frame origin need not lie on the mesh
                const Eigen::Vector3d centre = poses[b] * shape.origin.translation();
                validity::Obstacle ball{"probe", validity::Shape::sphere(0.002), Eigen::Isometry3d::Identity(), {}};
                ball.pose.translation() = centre;
                problem.scene->add(ball);
                EXPECT_FALSE(ctx.checker->isValidConfiguration(start.data()))
                    << entry.path().filename() << ": a ball at the centre of link '" << all[b].name << "' is not seen";
                problem.scene->remove("probe");
                ++probed;
            }
    }
    EXPECT_GE(problems, 5);
    EXPECT_GE(links, 20);
    EXPECT_GE(probed, 10);
}
