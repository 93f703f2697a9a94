// Camera + projector calibration on a rendered sequence of the virtual cell: the recovered rig
// against the one that rendered it, with doubtful and outlier views among the good ones.
#include "binpick/calibration/rig_calibrator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "rig_test_data.hpp"
#include "thrown_message.hpp"

namespace binpick::calibration {
namespace {

using test::anyWarningNames;
using test::qualityOf;
using test::readTestViews;
using test::rigTestData;
constexpr double kDegree = 3.14159265358979323846 / 180.0;

std::vector<std::string> sequenceAnd(std::vector<std::string> extra) {
  std::vector<std::string> views = rigTestData().views;
  views.insert(views.end(), extra.begin(), extra.end());
  return views;
}

struct RigErrors {
  double camera_fx_px, camera_cx_px, camera_cy_px;
  double projector_fx_px, projector_cx_px, projector_cy_px;
  double baseline_mm;     // |T| recovered - true
  double translation_mm;  // |T recovered - T true|
  double rotation_deg;
};

RigErrors errorsAgainstTruth(const io::RigCalibration& rig) {
  const io::RigCalibration& truth = rigTestData().params.rig;
  const Eigen::Isometry3d& T = rig.T_projector_camera;
  const Eigen::Isometry3d& T_true = truth.T_projector_camera;
  RigErrors e{};
  e.camera_fx_px = rig.camera.fx - truth.camera.fx;
  e.camera_cx_px = rig.camera.cx - truth.camera.cx;
  e.camera_cy_px = rig.camera.cy - truth.camera.cy;
  e.projector_fx_px = rig.projector.fx - truth.projector.fx;
  e.projector_cx_px = rig.projector.cx - truth.projector.cx;
  e.projector_cy_px = rig.projector.cy - truth.projector.cy;
  e.baseline_mm = 1e3 * (T.translation().norm() - T_true.translation().norm());
  e.translation_mm = 1e3 * (T.translation() - T_true.translation()).norm();
  e.rotation_deg = Eigen::AngleAxisd(T.linear().transpose() * T_true.linear()).angle() / kDegree;
  return e;
}

void recordErrors(const RigErrors& e) {
  const auto record = [](const char* name, double value) {
    ::testing::Test::RecordProperty(name, std::to_string(value));
  };
  record("camera_fx_error_px", e.camera_fx_px);
  record("camera_cx_error_px", e.camera_cx_px);
  record("camera_cy_error_px", e.camera_cy_px);
  record("projector_fx_error_px", e.projector_fx_px);
  record("projector_cx_error_px", e.projector_cx_px);
  record("projector_cy_error_px", e.projector_cy_px);
  record("baseline_error_mm", e.baseline_mm);
  record("translation_error_mm", e.translation_mm);
  record("rotation_error_deg", e.rotation_deg);
}

// Tolerances for this sequence: 10 or 11 views, a 640 x 512 camera (fx 800) whose corners carry
// errors of 0.08 pixel (median) and a 1280 x 800 projector (fx 1560) seen through them; `scale`
// widens them for calibrations from fewer views.
void expectNearTruth(const RigErrors& e, double scale = 1.0) {
  EXPECT_LT(std::abs(e.camera_fx_px), 2.0 * scale);
  EXPECT_LT(std::abs(e.camera_cx_px), 2.0 * scale);
  EXPECT_LT(std::abs(e.camera_cy_px), 2.0 * scale);
  EXPECT_LT(std::abs(e.projector_fx_px), 4.0 * scale);
  EXPECT_LT(std::abs(e.projector_cx_px), 4.0 * scale);
  EXPECT_LT(std::abs(e.projector_cy_px), 4.0 * scale);
  EXPECT_LT(std::abs(e.baseline_mm), 0.5 * scale);
  EXPECT_LT(e.translation_mm, 1.0 * scale);
  EXPECT_LT(e.rotation_deg, 0.15 * scale);
}

// A sequence with a view in which the board is missing and one in which it is half out of the
// image: the first is skipped and the second used, each named in a warning, and the calibration
// recovers the rig that rendered the sequence.
TEST(RigCalibration, RecoversTheVirtualRigAndNamesTheDoubtfulViews) {
  const test::RigTestData& data = rigTestData();
  const RigCalibrationResult result =
      calibrateRig(readTestViews(sequenceAnd({data.no_board, data.half_out})), data.layout);

  const RigErrors e = errorsAgainstTruth(result.rig);
  recordErrors(e);
  ::testing::Test::RecordProperty("stereo_rms_px", std::to_string(result.quality.stereo_rms_px));
  expectNearTruth(e);
  EXPECT_LT(result.quality.camera_rms_px, 0.3);
  EXPECT_LT(result.quality.projector_rms_px, 0.5);
  EXPECT_LT(result.quality.stereo_rms_px, 0.5);

  EXPECT_TRUE(anyWarningNames(result, data.no_board, "board not found"));
  EXPECT_FALSE(qualityOf(result, data.no_board).used);
  EXPECT_TRUE(anyWarningNames(result, data.half_out, "partly outside the image"));
  EXPECT_TRUE(qualityOf(result, data.half_out).used);
  EXPECT_LT(qualityOf(result, data.half_out).camera_corners, data.layout.cornerCount());
  for (const std::string& view : data.views) {
    EXPECT_TRUE(qualityOf(result, view).used) << view;
    EXPECT_FALSE(qualityOf(result, view).outlier) << view;
  }
  EXPECT_EQ(result.quality.viewsUsed(), static_cast<int>(data.views.size()) + 1);
  EXPECT_FALSE(result.quality.date.empty());
}

// The same corner's camera pixel moves in both lists of the view.
void perturbCameraCorners(RigView& view, double sigma_px, uint32_t seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, sigma_px);
  std::map<int, Eigen::Vector2d> offsets;
  for (std::size_t i = 0; i < view.board.ids.size(); ++i) {
    const Eigen::Vector2d offset(noise(random), noise(random));
    offsets[view.board.ids[i]] = offset;
    view.board.pixels[i] += offset;
  }
  for (ProjectorCorner& corner : view.projector.corners) corner.camera += offsets.at(corner.id);
}

// Two bad views among good ones: one whose camera corners are noisy (a blurred image), one whose
// projector pixels are all shifted (the projector knocked during the view: each device alone
// still fits it, only the rig does not). Both are flagged; dropping them recovers the truth.
TEST(RigCalibration, OutlierViewsAreFlaggedAndDroppedOnRequest) {
  const test::RigTestData& data = rigTestData();
  std::vector<RigView> views = readTestViews(data.views);
  perturbCameraCorners(views[3], 1.5, 7);
  for (ProjectorCorner& corner : views[6].projector.corners) {
    corner.projector += Eigen::Vector2d(8.0, 3.0);
  }
  const std::vector<std::string> bad{data.views[3], data.views[6]};

  const RigCalibrationResult kept = calibrateRig(views, data.layout);
  for (const std::string& view : bad) {
    EXPECT_TRUE(qualityOf(kept, view).outlier) << view;
    EXPECT_TRUE(qualityOf(kept, view).used) << view;
    EXPECT_TRUE(anyWarningNames(kept, view, "outlier")) << view;
  }
  RigCalibrationParams params;
  params.drop_outliers = true;
  const RigCalibrationResult dropped = calibrateRig(views, data.layout, params);
  for (const std::string& view : bad) {
    EXPECT_TRUE(qualityOf(dropped, view).outlier) << view;
    EXPECT_FALSE(qualityOf(dropped, view).used) << view;
    EXPECT_TRUE(anyWarningNames(dropped, view, "dropped")) << view;
  }
  EXPECT_EQ(dropped.quality.viewsUsed(), static_cast<int>(data.views.size()) - 2);
  const RigErrors e = errorsAgainstTruth(dropped.rig);
  recordErrors(e);
  expectNearTruth(e, 1.5);  // 8 views left
  EXPECT_LT(e.translation_mm, errorsAgainstTruth(kept.rig).translation_mm / 4.0);
  EXPECT_LT(dropped.quality.stereo_rms_px, kept.quality.stereo_rms_px);

  // Fewer views than needed once the outliers are gone: an error, not a weaker calibration.
  params.min_views = static_cast<int>(data.views.size()) - 1;
  EXPECT_TRUE(test::throwsNaming([&] { calibrateRig(views, data.layout, params); },
                                 "dropping the 2 outlier views would leave 8 views"));
}

}  // namespace
}  // namespace binpick::calibration
