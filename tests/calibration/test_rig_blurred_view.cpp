// A defocused chessboard view among sharp ones, rendered by the virtual cell: the detector still
// finds the board, so only the calibration's per-view RMS can tell. It must be flagged as an
// outlier with a warning naming it, and left out with drop_outliers.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "binpick/calibration/rig_calibrator.hpp"
#include "rig_depth_error.hpp"
#include "rig_test_data.hpp"

namespace binpick::calibration {
namespace {

using test::anyWarningNames;
using test::blurredViewData;
using test::qualityOf;

std::vector<RigView> readViews(const test::BlurredViewData& data) {
  std::vector<RigView> views;
  for (const std::string& directory : data.views) views.push_back(readRigView(directory, data.layout));
  return views;
}

double translationErrorMm(const RigCalibrationResult& result, const io::RigCalibration& truth) {
  return 1e3 * (result.rig.T_projector_camera.translation() - truth.T_projector_camera.translation()).norm();
}

TEST(RigBlurredView, ABlurredChessboardViewIsFlaggedAndDroppedOnRequest) {
  const test::BlurredViewData& data = blurredViewData();
  const std::vector<RigView> views = readViews(data);
  ASSERT_TRUE(views.back().board.complete()) << views.back().board.problem;

  const RigCalibrationResult kept = calibrateRig(views, data.layout);
  const io::RigViewQuality& blurred = qualityOf(kept, data.blurred);
  RecordProperty("blurred_camera_rms_px", std::to_string(blurred.camera_rms_px));
  RecordProperty("blurred_projector_rms_px", std::to_string(blurred.projector_rms_px));
  EXPECT_TRUE(blurred.used);
  EXPECT_TRUE(blurred.outlier);
  EXPECT_TRUE(anyWarningNames(kept, data.blurred, "outlier"));
  for (const io::RigViewQuality& view : kept.quality.views) {
    if (view.name != data.blurred) {
      EXPECT_FALSE(view.outlier) << view.name << ": camera " << view.camera_rms_px << " px, projector "
                                 << view.projector_rms_px << " px";
    }
  }

  RigCalibrationParams params;
  params.drop_outliers = true;
  const RigCalibrationResult dropped = calibrateRig(views, data.layout, params);
  EXPECT_FALSE(qualityOf(dropped, data.blurred).used);
  EXPECT_TRUE(anyWarningNames(dropped, data.blurred, "dropped"));
  EXPECT_EQ(dropped.quality.viewsUsed(), static_cast<int>(views.size()) - 1);
  RecordProperty("kept_translation_error_mm", std::to_string(translationErrorMm(kept, data.params.rig)));
  RecordProperty("dropped_translation_error_mm", std::to_string(translationErrorMm(dropped, data.params.rig)));
  EXPECT_LT(translationErrorMm(dropped, data.params.rig), 1.0);

  // Depth: the rig with the blurred view kept against the one without it, each against the true
  // rig's (median |dz| over planes at 0.75-1.05 m).
  const double kept_mm = test::medianDepthErrorMm(kept.rig, data.params.rig);
  const double dropped_mm = test::medianDepthErrorMm(dropped.rig, data.params.rig);
  RecordProperty("kept_median_depth_error_mm", std::to_string(kept_mm));
  RecordProperty("dropped_median_depth_error_mm", std::to_string(dropped_mm));
  std::printf("median depth error against the true rig: blurred view kept %.3f mm, dropped %.3f mm\n", kept_mm,
              dropped_mm);
  // Measured: kept 0.035 mm, dropped 0.033 mm. Before the decoder read the black squares along
  // their stripes, 0.28 and 0.067 mm: the projector corners were fitted to the white squares
  // alone, whose pixels beside the corner the blur biases outward from it (and 0.91 and 0.24 mm
  // before the chessboard's corners were refined on the flattened image with a window sized to
  // the squares). The kept view still stands out by its projector corners (RMS 0.63 px against
  // its camera's 0.13 px), but no longer moves the rig.
  EXPECT_LT(kept_mm, 0.10);
  EXPECT_LT(dropped_mm, 0.06);
}

}  // namespace
}  // namespace binpick::calibration
