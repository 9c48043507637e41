// Paper 002's interference prediction as a user's own OMPL code uses it (planners::PredictedObstacles,
// planners::firstInterference): copies of a moving obstacle along its observed velocity, and the arc length to the
// first blocked motion of a path.
#include "support/TestScenes.h"

#include <michi/planners/dual_roadmap/InterferencePrediction.h>
#include <michi/state_spaces/JointStateSpace.h>
#include <michi/validity/fcl/ConservativeMotionValidator.h>
#include <michi/validity/fcl/FclValidityChecker.h>
#include <michi/validity/scene/Shape.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace michi;

TEST(InterferencePrediction, CopiesSpreadAlongTheVelocityOverTheHorizon)
{
    auto scene = std::make_shared<validity::Scene>();
    planners::PredictedObstacles predicted(scene, 3, 2.);
    predicted.add("cart", validity::Shape::sphere(0.1), Eigen::Isometry3d::Identity());
    EXPECT_EQ(scene->size(), 3u);
    predicted.observe("cart", Eigen::Isometry3d(Eigen::Translation3d(1., 0., 0.)), Eigen::Vector3d(0.5, 0., 0.));
    std::map<std::string, double> x;
    for (const auto &o : scene->obstacles())
        x[o.name] = o.pose.translation().x();
    EXPECT_DOUBLE_EQ(x["cart~0"], 1.);   // observed
    EXPECT_DOUBLE_EQ(x["cart~1"], 1.5);  // half the horizon
    EXPECT_DOUBLE_EQ(x["cart~2"], 2.);   // after 2 s at 0.5 m/s
    EXPECT_THROW(planners::PredictedObstacles(scene, 0, 1.), std::invalid_argument);
}

TEST(InterferencePrediction, ObstaclesObservedTogetherChangeTheSceneOnce)
{
    auto scene = std::make_shared<validity::Scene>();
    planners::PredictedObstacles predicted(scene, 3, 2.);
    predicted.add("cart", validity::Shape::sphere(0.1), Eigen::Isometry3d::Identity());
    predicted.add("dog", validity::Shape::sphere(0.1), Eigen::Isometry3d::Identity());
    const auto count = scene->changeCount();
    predicted.observe({"cart", "dog"},
                      {Eigen::Isometry3d(Eigen::Translation3d(1., 0., 0.)),
                       Eigen::Isometry3d(Eigen::Translation3d(0., 1., 0.))},
                      {Eigen::Vector3d(0.5, 0., 0.), Eigen::Vector3d(0., -1., 0.)});
    EXPECT_EQ(scene->changeCount(), count + 1);
    std::map<std::string, Eigen::Vector3d> at;
    for (const auto &o : scene->obstacles())
        at[o.name] = o.pose.translation();
    // each copy where observe() of that obstacle alone puts it
    EXPECT_DOUBLE_EQ(at["cart~2"].x(), 2.);
    EXPECT_DOUBLE_EQ(at["dog~0"].y(), 1.);
    EXPECT_DOUBLE_EQ(at["dog~1"].y(), 0.);
    EXPECT_DOUBLE_EQ(at["dog~2"].y(), -1.);
    // the same observation again moves nothing
    predicted.observe("dog", Eigen::Isometry3d(Eigen::Translation3d(0., 1., 0.)), Eigen::Vector3d(0., -1., 0.));
    EXPECT_EQ(scene->changeCount(), count + 1);
    EXPECT_THROW(predicted.observe(std::vector<std::string>{"cart"}, {}, {}), std::invalid_argument);
}

TEST(InterferencePrediction, FirstInterferenceIsTheArcToTheFirstBlockedMotion)
{
    // a planar 2-link arm sweeping joint 1 from 0 towards pi/2; a predicted copy sits at 45 degrees
    const auto model = validity::RobotModel::fromUrdfFile(test::sourcePath("problems/robots/planar_2link.urdf"));
    auto bodies = std::make_shared<validity::RobotGroupBodies>(model, std::vector<int>{0, 1},
                                                               std::vector<double>(model->variableCount(), 0.));
    auto scene = std::make_shared<validity::Scene>();
    planners::PredictedObstacles predicted(scene, 2, 1.);
    predicted.add("box", validity::Shape::sphere(0.05), Eigen::Isometry3d::Identity());
    auto space = state_spaces::makeJointStateSpace({{"joint1", -M_PI, M_PI, false}, {"joint2", -M_PI, M_PI, false}});
    auto si = std::make_shared<ompl::base::SpaceInformation>(space);
    auto checker = std::make_shared<validity::FclValidityChecker>(si, bodies, scene);
    si->setStateValidityChecker(checker);
    si->setMotionValidator(std::make_shared<validity::ConservativeMotionValidator>(si, checker));
    si->setup();
    const planners::ConfigurationPath path{{0., 0.}, {0.4, 0.}, {0.8, 0.}, {1.2, 0.}, {1.5, 0.}};
    // far away (observed and predicted): the whole path is free
    predicted.observe("box", Eigen::Isometry3d(Eigen::Translation3d(5., 5., 0.)), Eigen::Vector3d::Zero());
    EXPECT_TRUE(std::isinf(planners::firstInterference(si, path, 10.)));
    // observed away from the arm but predicted on its way at 45 degrees, 0.3 m out (on link 1)
    const Eigen::Vector3d on(0.3 * std::cos(M_PI / 4), 0.3 * std::sin(M_PI / 4), 0.);
    predicted.observe("box", Eigen::Isometry3d(Eigen::Translation3d(on + Eigen::Vector3d(0., 2., 0.))),
                      Eigen::Vector3d(0., -2., 0.));
    const double arc = planners::firstInterference(si, path, 10.);
    EXPECT_GT(arc, 0.4);       // the first segment is free
    EXPECT_LT(arc, M_PI / 4);  // blocked before link 1 reaches the copy at 45 degrees
    // a lookahead that ends before the copy sees nothing
    EXPECT_TRUE(std::isinf(planners::firstInterference(si, path, 0.35)));
}
