// The calibration check on captures of the virtual cell: under the rig that rendered them the
// decoded rays meet, under a rig with a wrong baseline or for a decoding with a wrong row they
// miss by what was done to them.
#include "calibration_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "binpick/core/error.hpp"
#include "thrown_message.hpp"
#include "virtual_capture.hpp"

namespace binpick::reconstruction {
namespace {

const testing::VirtualCapture& smallCapture(bool row_codes = true) {
  testing::CaptureOptions options;
  options.camera_scale = 0.5;
  options.row_codes = row_codes;
  return testing::virtualCapture(options);
}

const DecodedCapture& decodedSmallCapture() {
  static const DecodedCapture decoded = decodeCapture(smallCapture().capture);
  return decoded;
}

TEST(CalibrationFit, TheRigThatRenderedTheCaptureFitsIt) {
  const CalibrationFit fit = measureCalibrationFit(smallCapture().scene.rig, decodedSmallCapture());
  ASSERT_TRUE(fit.measured());
  EXPECT_GT(fit.pixels, 50000u);
  EXPECT_GT(fit.pixels_with_gap, fit.pixels * 99 / 100);
  EXPECT_LT(fit.median_gap_mm, 0.5);
  EXPECT_LT(fit.median_epipolar_px, 0.2);
  EXPECT_LT(fit.beyond_limit_share, 0.02);
  EXPECT_EQ(fit.epipolar_limit_px, 1.5);
}

// A translation with one component typed wrong (here the vertical one, 10% of the baseline):
// the epipolar planes tilt and the decoded rays no longer meet.
TEST(CalibrationFit, ATranslationTypedWrongMissesByMillimetres) {
  io::RigCalibration rig = smallCapture().scene.rig;
  rig.T_projector_camera.translation().y() += 0.1 * rig.T_projector_camera.translation().norm();
  const CalibrationFit fit = measureCalibrationFit(rig, decodedSmallCapture());
  ASSERT_TRUE(fit.measured());
  EXPECT_GT(fit.median_gap_mm, 5.0);
  EXPECT_GT(fit.median_epipolar_px, 5.0);
  EXPECT_GT(fit.beyond_limit_share, 0.9);
}

// A translation scaled as a whole (a unit mistake) scales the cloud and keeps every ray pair
// meeting: the check cannot see it (readOpenCvCalibration's plausibility check of the baseline
// and the cloud's size can).
TEST(CalibrationFit, ABaselineScaledAsAWholeStillFits) {
  io::RigCalibration rig = smallCapture().scene.rig;
  rig.T_projector_camera.translation() *= 1.2;
  const CalibrationFit fit = measureCalibrationFit(rig, decodedSmallCapture());
  EXPECT_LT(fit.median_gap_mm, 0.5);
  EXPECT_LT(fit.beyond_limit_share, 0.02);
}

// Patterns coded at 2 x 2 projector pixels but decoded as if each code were one pixel (what
// the real data set shows with the wrong code step): every projector ray is wrong.
TEST(CalibrationFit, CoordinatesAtHalfTheirScaleMissByCentimetres) {
  DecodedCapture halved = decodedSmallCapture();
  const cv::Mat column = decodedSmallCapture().column * 0.5, row = decodedSmallCapture().row * 0.5;
  halved.column = column;
  halved.row = row;
  const CalibrationFit fit = measureCalibrationFit(smallCapture().scene.rig, halved);
  ASSERT_TRUE(fit.measured());
  EXPECT_GT(fit.median_gap_mm, 10.0);
  EXPECT_GT(fit.beyond_limit_share, 0.9);
}

// Every decoded row 3 projector pixels off: the epipolar distance is those 3 pixels, less the
// part along the epipolar lines (which run nearly along the rows of this rig).
TEST(CalibrationFit, EpipolarDistanceIsInProjectorPixels) {
  DecodedCapture shifted = decodedSmallCapture();
  const cv::Mat shifted_row = decodedSmallCapture().row + 3.0;  // new pixels: the cached decoding stays
  shifted.row = shifted_row;
  TriangulationParams params;
  params.max_epipolar_error = 2.0;
  params.max_calibration_residual = 0.0;  // each pixel judged from its line
  const CalibrationFit fit = measureCalibrationFit(smallCapture().scene.rig, shifted, params);
  ASSERT_TRUE(fit.measured());
  EXPECT_NEAR(fit.median_epipolar_px, 3.0, 0.3);
  EXPECT_GT(fit.beyond_limit_share, 0.95);
  EXPECT_EQ(fit.epipolar_limit_px, 2.0);
  EXPECT_TRUE(std::isnan(fit.largest_residual_px));
}

// A shift common to all pixels is what a calibration slightly off gives: the residual field takes
// it up (reported), and the pixels are judged from it.
TEST(CalibrationFit, ASmoothOffsetIsTheCalibrationsResidual) {
  DecodedCapture shifted = decodedSmallCapture();
  const cv::Mat shifted_row = decodedSmallCapture().row + 3.0;
  shifted.row = shifted_row;
  const CalibrationFit fit = measureCalibrationFit(smallCapture().scene.rig, shifted);
  ASSERT_TRUE(fit.measured());
  EXPECT_NEAR(fit.median_epipolar_px, 3.0, 0.3);
  EXPECT_NEAR(fit.largest_residual_px, 3.0, 0.4);
  EXPECT_LT(fit.median_off_residual_px, 0.3);
  EXPECT_LT(fit.beyond_limit_share, 0.05);
  EXPECT_EQ(fit.residual_limit_px, TriangulationParams{}.max_calibration_residual);
}

TEST(CalibrationFit, ACaptureWithoutRowsHasNothingToCheck) {
  const testing::VirtualCapture& v = smallCapture(false);
  const CalibrationFit fit = measureCalibrationFit(v.scene.rig, decodeCapture(v.capture));
  EXPECT_FALSE(fit.measured());
  EXPECT_EQ(fit.pixels, 0u);
}

TEST(CalibrationFit, ADecodingOfAnotherSizeIsRefused) {
  io::RigCalibration rig = smallCapture().scene.rig;
  rig.camera = rig.camera.scaled(2.0);
  EXPECT_TRUE(test::throwsNaming([&] { measureCalibrationFit(rig, decodedSmallCapture()); },
                                 "measureCalibrationFit: the decoded capture must be the camera's"));
}

}  // namespace
}  // namespace binpick::reconstruction
