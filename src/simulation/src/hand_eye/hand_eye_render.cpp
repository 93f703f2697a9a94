// renderHandEyeImage: one camera image of the board, the white image of the calibration capture
// renderer (calibration_sequence.hpp): the board under the projector's white plus room light.
#include "binpick/simulation/calibration_sequence.hpp"
#include "binpick/simulation/hand_eye_session.hpp"

namespace binpick::simulation {
namespace {

CalibrationSequenceParams renderParams(const HandEyeSessionParams& params) {
  CalibrationSequenceParams render;
  render.board = params.board;
  render.poses = params.poses;  // the wall behind the board goes beyond its farthest pose
  render.rig = params.rig;
  render.pattern_set.projector_width = params.rig.projector.width;
  render.pattern_set.projector_height = params.rig.projector.height;
  return render;
}

}  // namespace

cv::Mat renderHandEyeImage(const CalibrationBoard& board, const Eigen::Isometry3d& T_camera_board,
                           const HandEyeSessionParams& params, uint64_t noise_seed) {
  return renderCalibrationWhiteImage(board, T_camera_board, renderParams(params), noise_seed);
}

}  // namespace binpick::simulation
