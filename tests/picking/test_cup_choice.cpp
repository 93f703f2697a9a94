// chooseCup and upwardShare (cup_choice.hpp): the cup an integrator would pick for a part, by the
// share of the ways it can lie in which a grasp faces up.
#include <gtest/gtest.h>

#include "binpick/core/error.hpp"
#include "binpick/picking/cup_choice.hpp"
#include "binpick/simulation/parts.hpp"
#include "picking_test_support.hpp"

namespace binpick::picking {
namespace {

using namespace binpick::picking::test;

GripperParams sixMillimetreCup() {
  GripperParams gripper;
  gripper.cup_diameter = 0.006;
  return gripper;
}

CupChoice choiceFor(const std::string& name) {
  const simulation::Part part = simulation::makePart(name);
  return chooseCup(part.mesh, sixMillimetreCup(), part.symmetry, GraspGenerationParams{});
}

TEST(PickingCupChoice, OneGraspStraightDownFacesUpInAQuarterOfTheOrientations) {
  // Within 60 degrees of straight down: a cap of the sphere of area (1 - cos 60) / 2 = 1/4.
  const std::vector<Grasp> down = {topGrasp()};
  EXPECT_NEAR(upwardShare(down, {}, {}), 0.25, 0.002);
  // Its mirror across the part doubles it; a revolved part turns a grasp from the side all round.
  EXPECT_NEAR(upwardShare({topGrasp(), {"bottom", pose({0, 0, -0.02}, Eigen::Matrix3d::Identity())}}, {}, {}), 0.5,
              0.002);
  PartSymmetry turned;
  turned.continuous_axis = Eigen::Vector3d::UnitZ();
  const Grasp side{"side", pose({0.02, 0, 0}, rotY(-90))};
  EXPECT_NEAR(upwardShare({side}, turned, {}), std::sin(radians(60)), 0.01);  // the band |up.z| <= sin 60
  EXPECT_EQ(upwardShare({}, {}, {}), 0.0);
}

TEST(PickingCupChoice, AGearOnItsRimNeedsTheSmallerCup) {
  const CupChoice gear = choiceFor("gear");
  EXPECT_EQ(gear.diameter, 0.004);
  ASSERT_EQ(gear.options.size(), 2u);
  EXPECT_EQ(gear.options.front().diameter, 0.006);
  EXPECT_GT(gear.options.back().upward, gear.options.front().upward + 0.1);
}

// A shaft 10 mm across and 80 mm long: a 6 mm cup's rim sags beyond its seal tolerance on it, so
// only the two ends hold it (standing up); a 4 mm cup holds it lying down.
TEST(PickingCupChoice, AShaftTooThinForTheCupGetsTheSmallerOne) {
  const io::TriangleMesh shaft = simulation::makeLathe({{0, -0.04}, {0.005, -0.04}, {0.005, 0.04}, {0, 0.04}}, 96);
  PartSymmetry turned;
  turned.continuous_axis = Eigen::Vector3d::UnitZ();
  const CupChoice choice = chooseCup(shaft, sixMillimetreCup(), turned, GraspGenerationParams{});
  EXPECT_EQ(choice.diameter, 0.004);
  ASSERT_EQ(choice.options.size(), 2u);
  EXPECT_NEAR(choice.options[0].upward, 0.5, 0.01);
  EXPECT_GT(choice.options[1].upward, 0.95);
  EXPECT_EQ(describeCupChoice(choice).substr(0, 25), "4 mm cup (of 6 mm: 50% of");
}

TEST(PickingCupChoice, PartsTheGrippersCupFitsKeepIt) {
  for (const char* name : {"l_bracket", "switch", "bulge"}) {
    EXPECT_EQ(choiceFor(name).diameter, 0.006) << name;
  }
}

TEST(PickingCupChoice, BadInputThrows) {
  const simulation::Part part = simulation::makePart("l_bracket");
  GripperParams jaws;
  jaws.type = GripperType::Parallel;
  EXPECT_THROW(chooseCup(part.mesh, jaws, part.symmetry, {}), core::Error);
  CupChoiceParams params;
  params.min_gain = 0.0;
  EXPECT_THROW(upwardShare({topGrasp()}, {}, params), core::Error);
  params = {};
  params.series = {-0.004};
  EXPECT_THROW(chooseCup(part.mesh, sixMillimetreCup(), part.symmetry, {}, params), core::Error);
}

}  // namespace
}  // namespace binpick::picking
