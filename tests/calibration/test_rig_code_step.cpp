// Views whose patterns code 2 x 2 projector pixels per Gray code (code step 2, as many real rigs
// project): the projector's corners, its lens and calib.yaml come out in the projector's own
// pixels at its true size, so that reconstruction uses the calibration as it is.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "binpick/calibration/rig_calibrator.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "binpick/simulation/calibration_sequence.hpp"
#include "rig_test_data.hpp"
#include "temp_directory_test.hpp"

namespace binpick::calibration {
namespace {

using test::codeStepData;

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
  return values[values.size() / 2];
}

using RigCodeStep = test::TempDirectoryTest;

TEST_F(RigCodeStep, TheProjectorIsCalibratedInItsOwnPixels) {
  const test::CodeStepData& data = codeStepData();
  std::vector<RigView> views;
  for (const std::string& directory : data.views) views.push_back(readRigView(directory, data.layout));

  // The first view's projector corners against the truth, in projector pixels.
  const std::string sequence = data.views.front().substr(0, data.views.front().rfind('/'));
  const simulation::CalibrationTruth truth = simulation::readCalibrationTruth(sequence);
  std::map<int, Eigen::Vector2d> true_pixels;
  for (const simulation::CornerObservation& corner : truth.poses.front().corners) {
    true_pixels[corner.id] = corner.projector_pixel;
  }
  std::vector<double> errors;
  for (const ProjectorCorner& corner : views.front().projector.corners) {
    errors.push_back((corner.projector - true_pixels.at(corner.id)).norm());
  }
  ASSERT_GE(errors.size(), 20u);
  RecordProperty("projector_corner_median_error_px", std::to_string(median(errors)));
  EXPECT_LT(median(errors), 0.5);  // a code is 2 pixels wide: in codes they would be hundreds off

  const RigCalibrationResult result = calibrateRig(views, data.layout);
  const io::LensIntrinsics& lens = result.rig.projector;
  const io::LensIntrinsics& true_lens = data.params.rig.projector;
  RecordProperty("projector_fx_error_px", std::to_string(lens.fx - true_lens.fx));
  RecordProperty("projector_cx_error_px", std::to_string(lens.cx - true_lens.cx));
  RecordProperty("projector_cy_error_px", std::to_string(lens.cy - true_lens.cy));
  EXPECT_EQ(lens.width, true_lens.width);
  EXPECT_EQ(lens.height, true_lens.height);
  EXPECT_NEAR(lens.fx, true_lens.fx, 0.01 * true_lens.fx);
  EXPECT_NEAR(lens.fy, true_lens.fy, 0.01 * true_lens.fy);
  EXPECT_NEAR(lens.cx, true_lens.cx, 10.0);
  EXPECT_NEAR(lens.cy, true_lens.cy, 10.0);

  // calib.yaml carries the same: read back, it is the projector at its true resolution.
  const std::string path = pathOf("calib.yaml");
  io::writeRigCalibration(path, result.rig, result.quality);
  const io::RigCalibration written = io::readRigCalibration(path);
  EXPECT_EQ(written.projector.width, true_lens.width);
  EXPECT_NEAR(written.projector.fx, true_lens.fx, 0.01 * true_lens.fx);
}

}  // namespace
}  // namespace binpick::calibration
