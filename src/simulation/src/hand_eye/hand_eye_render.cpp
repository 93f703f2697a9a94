// renderHandEyeImage: one camera image of the board, the cheapest honest way: the calibration
// capture renderer (calibration_sequence.hpp) with its shortest pattern set, keeping its first
// image, the board under the projector's white plus room light.
#include "binpick/io/error.hpp"
#include "binpick/simulation/calibration_sequence.hpp"
#include "binpick/simulation/hand_eye_session.hpp"

namespace binpick::sim {
namespace {

CalibrationSequenceParams renderParams(const HandEyeSessionParams& params) {
  CalibrationSequenceParams render;
  render.board = params.board;
  render.poses = params.poses;  // the wall behind the board goes beyond its farthest pose
  render.rig = params.rig;
  // A pattern set needs one coded axis; the shorter one without phase steps renders 22 images
  // for the virtual rig's 1280x800 projector where the full set renders 52.
  render.pattern_set.projector_width = params.rig.projector.width;
  render.pattern_set.projector_height = params.rig.projector.height;
  const bool rows_shorter = params.rig.projector.height <= params.rig.projector.width;
  render.pattern_set.column_codes = !rows_shorter;
  render.pattern_set.row_codes = rows_shorter;
  render.pattern_set.phase_steps = 0;
  render.source = "binpick virtual cell: hand-eye session";
  return render;
}

}  // namespace

cv::Mat renderHandEyeImage(const CalibrationBoard& board, const Eigen::Isometry3d& T_camera_board,
                           const HandEyeSessionParams& params, uint64_t noise_seed) {
  const Capture capture = renderCalibrationCapture(board, T_camera_board, renderParams(params),
                                                   noise_seed);
  if (capture.metadata.patterns.empty() || capture.metadata.patterns.front() != "white") {
    throw Error("renderHandEyeImage: the capture does not start with the white image");
  }
  return capture.images.front();
}

}  // namespace binpick::sim
