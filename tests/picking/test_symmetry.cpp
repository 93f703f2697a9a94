// Symmetry expansion: a symmetric part's pick does not depend on which of its equivalent poses
// the detector reported.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "picking_test_support.hpp"

namespace binpick::picking {
namespace {

using namespace binpick::picking::test;

// A random pose over the bin's centre, tilted up to 25 degrees.
Eigen::Isometry3d randomPartPose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(0.0, 360.0), tilt(-25.0, 25.0);
  std::uniform_real_distribution<double> x(-0.05, 0.05), y(-0.04, 0.04), z(0.03, 0.08);
  return pose({x(rng), y(rng), z(rng)}, rotZ(angle(rng)) * rotY(tilt(rng)) * rotZ(angle(rng)));
}

TEST(PickingSymmetry, FourFoldPartTurnedAQuarterGetsTheSamePick) {
  PickParams params;
  params.grasps = {{"off_axis", pose({0.03, 0.01, 0.02}, rotX(180))}};
  params.symmetry.discrete = {rotZ(0), rotZ(90), rotZ(180), rotZ(270)};
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Isometry3d T_base_model = randomPartPose(rng);
    const Eigen::Isometry3d T_base_turned = T_base_model * pose({0, 0, 0}, rotZ(90));
    const PickPlan plan = planPicks({{T_base_model, 1.0}}, {}, params);
    const PickPlan turned = planPicks({{T_base_turned, 1.0}}, {}, params);
    ASSERT_TRUE(picksOne(plan)) << "trial " << trial;
    ASSERT_TRUE(picksOne(turned)) << "trial " << trial;
    EXPECT_TRUE(samePose(plan.picks[0].T_base_grasp, turned.picks[0].T_base_grasp, 1e-3, 1e-3)) << "trial " << trial;
  }
}

// The taught grasp approaches 40 degrees off the part's axis; a part leaning 30 degrees the
// wrong way puts it at 70 degrees (beyond max_tilt), its half-turn twin at 10 degrees.
TEST(PickingSymmetry, TwinOfATooSteepGraspIsPicked) {
  PickParams params;
  const Eigen::Isometry3d T_model_grasp = pose({0.02, 0, 0.02}, rotY(40) * rotX(180));
  params.grasps = {{"leaning", T_model_grasp}};
  const DetectedPart leaning = part({0, 0, 0.06}, rotY(30));

  const PickPlan without_symmetry = planPicks({leaning}, {}, params);
  EXPECT_TRUE(without_symmetry.picks.empty());
  EXPECT_EQ(without_symmetry.rejected.tilt, 1);

  params.symmetry.discrete = {rotZ(0), rotZ(180)};
  const PickPlan plan = planPicks({leaning}, {}, params);
  ASSERT_TRUE(picksOne(plan));
  EXPECT_NEAR(plan.picks[0].tilt_deg, 10.0, 1e-6);
  const Eigen::Isometry3d twin = leaning.T_base_model * pose({0, 0, 0}, rotZ(180)) * T_model_grasp;
  EXPECT_TRUE(samePose(plan.picks[0].T_base_grasp, twin, 1e-3, 1e-3));
}

// Tool x against base +x projected normal to the approach, degrees.
double wristAngleDeg(const Eigen::Isometry3d& T_base_grasp) {
  const Eigen::Vector3d approach = T_base_grasp.linear().col(2);
  const Eigen::Vector3d reference =
      Eigen::Vector3d::UnitX() - approach.x() * approach;  // base x minus its approach part
  const double cosine = T_base_grasp.linear().col(0).dot(reference.normalized());
  return degrees(std::acos(std::clamp(cosine, -1.0, 1.0)));
}

TEST(PickingSymmetry, ContinuousAxisGivesACanonicalWristAngle) {
  PickParams params = topGraspParams();
  params.symmetry.continuous_axis = Eigen::Vector3d(0, 0, 2);  // not unit: normalised
  params.continuous_symmetry_steps = 36;
  const double step_deg = 360.0 / params.continuous_symmetry_steps;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> spin(0.0, 360.0), tilt(-20.0, 20.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d lean = rotX(tilt(rng)) * rotY(tilt(rng));
    const DetectedPart spun = part({0.03, -0.02, 0.05}, lean * rotZ(spin(rng)));
    const DetectedPart unspun = part({0.03, -0.02, 0.05}, lean);
    const PickPlan plan = planPicks({spun}, {}, params);
    const PickPlan reference = planPicks({unspun}, {}, params);
    ASSERT_TRUE(picksOne(plan)) << "trial " << trial;
    ASSERT_TRUE(picksOne(reference)) << "trial " << trial;
    const Eigen::Isometry3d& pick = plan.picks[0].T_base_grasp;
    // The nearest of the turns lies within half a step of the canonical angle.
    EXPECT_LE(wristAngleDeg(pick), step_deg / 2 + 1e-6) << "trial " << trial;
    EXPECT_TRUE(samePose(pick, reference.picks[0].T_base_grasp, 1e-3, step_deg)) << "trial " << trial;
    const Eigen::Vector3d top = spun.T_base_model * Eigen::Vector3d(0, 0, 0.02);
    EXPECT_LE(1000.0 * (pick.translation() - top).norm(), 1e-3) << "trial " << trial;
  }
}

// An upside-down cylinder is picked at its other end: the half turn about x combined with the
// turns about the axis.
TEST(PickingSymmetry, ContinuousAndDiscreteSymmetriesCombine) {
  PickParams params = topGraspParams();
  params.symmetry.continuous_axis = Eigen::Vector3d::UnitZ();
  const DetectedPart upside_down = part({0.01, 0.02, 0.05}, rotX(180) * rotZ(17));

  const PickPlan without_flip = planPicks({upside_down}, {}, params);
  EXPECT_EQ(without_flip.rejected.tilt, 1);

  params.symmetry.discrete = {rotX(0), rotX(180)};
  const PickPlan plan = planPicks({upside_down}, {}, params);
  ASSERT_TRUE(picksOne(plan));
  EXPECT_NEAR(plan.picks[0].tilt_deg, 0.0, 1e-6);
  const Eigen::Vector3d other_end(0.01, 0.02, 0.07);  // 20 mm above the origin, again
  EXPECT_LE(1000.0 * (plan.picks[0].T_base_grasp.translation() - other_end).norm(), 1e-3);
  EXPECT_LE(wristAngleDeg(plan.picks[0].T_base_grasp), 5.0 + 1e-6);
}

}  // namespace
}  // namespace binpick::picking
