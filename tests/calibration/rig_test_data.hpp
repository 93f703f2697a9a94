#pragma once
// Test support: a camera + projector calibration sequence of the virtual cell, rendered once per
// build tree and shared by every test process, with the views a calibration must refuse or
// skip beside it. The camera is the virtual rig's at half resolution (the same lens and field of
// view; a ChArUco square still spans some 25 pixels), and the patterns are Gray codes without
// phase shifts: what Moreno & Taubin calibrated with, and 44 images per view instead of 52.
#include <string>
#include <vector>

#include "binpick/calibration/board_layout.hpp"
#include "binpick/calibration/rig_calibrator.hpp"
#include "binpick/calibration/rig_views.hpp"
#include "binpick/simulation/calibration_sequence.hpp"

namespace binpick::test {

struct RigTestData {
  std::string directory;
  std::string sequence;                          // DIR/sequence: pose_000 ... and truth/
  std::vector<std::string> views;                // the pose_NNN capture directories, in order
  std::string no_board;                          // the board outside the camera's view
  std::string half_out;                          // the board half out of the camera image, on its left
  std::string no_rows;                           // a good pose captured without row codes
  simulation::CalibrationSequenceParams params;  // what rendered the sequence (rig = the truth)
  calibration::BoardLayout layout;
};

// The sequence's parameters: 10 ChArUco poses, seed 1.
simulation::CalibrationSequenceParams rigTestParams();

// Rendered on first use (some 20 s), then read from disk.
const RigTestData& rigTestData();

// A chessboard sequence of the virtual rig at full resolution with one view defocused: pose_NNN as rendered, and
// `blurred`, pose `blurred_pose`'s capture with every image blurred by a Gaussian of
// kBlurSigmaPx camera pixels. `views`: the sharp poses but `blurred_pose`, then `blurred`.
struct BlurredViewData {
  std::vector<std::string> views;
  std::string blurred;
  int blurred_pose = 4;
  simulation::CalibrationSequenceParams params;
  calibration::BoardLayout layout;
};
constexpr double kBlurSigmaPx = 5.0;
// Rendered on first use, then read from disk.
const BlurredViewData& blurredViewData();

// The test sequence's rig and board with patterns of code step 2 (each Gray code covering 2 x 2
// projector pixels), `count` poses: views whose decoded codes are not projector pixels.
struct CodeStepData {
  std::vector<std::string> views;
  simulation::CalibrationSequenceParams params;
  calibration::BoardLayout layout;
};
// Rendered on first use, then read from disk.
const CodeStepData& codeStepData();

// Capture directories read and measured with the default view params.
std::vector<calibration::RigView> readTestViews(const std::vector<std::string>& directories);

// Whether a warning names `view` and contains `text`.
bool anyWarningNames(const calibration::RigCalibrationResult& result, const std::string& view, const std::string& text);
// The quality entry of `view`; throws std::runtime_error when there is none.
const io::RigViewQuality& qualityOf(const calibration::RigCalibrationResult& result, const std::string& view);

}  // namespace binpick::test
