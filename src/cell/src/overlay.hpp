#pragma once
// The picture of a cycle: the camera image with the detected parts drawn where the camera sees
// them, coloured by pick order, with their grasps. For operators and the saved artefacts.
// Stateless function: thread-safe.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "binpick/io/lens.hpp"

namespace binpick::cell {

struct OverlayPart {
  Eigen::Isometry3d T_camera_model = Eigen::Isometry3d::Identity();  // metres
  int pick_rank = -1;  // 0 = picked first; -1 = detected, not picked (drawn in red)
  // Drawn as an axis tripod (x red, y green, z blue), kOverlayTripodLength long.
  std::optional<Eigen::Isometry3d> T_camera_grasp;
};

constexpr double kOverlayTripodLength = 0.02;  // metres: visible next to parts of a few cm

// The colour of a part's points (BGR): picks from green (rank 0) to yellow (the last rank among
// `parts`), parts not picked red.
cv::Scalar overlayRankColour(int pick_rank, int last_rank);

// An 8-bit BGR image: `image` (8- or 16-bit grey, 16-bit scaled to 8 bit) with each part's
// `model_points` (model frame, metres) projected through `camera` (distortion included) as dots
// in its rank colour, a filled disc of that colour at the projected model origin with the rank
// number beside it (picks only), and the grasp tripods. Points behind the camera or outside the
// image are skipped. Throws core::Error on an empty image, one that is not single-channel
// 8- or 16-bit, one whose size differs from the camera's, or an invalid camera.
cv::Mat renderOverlay(const cv::Mat& image, const io::LensIntrinsics& camera,
                      const std::vector<Eigen::Vector3f>& model_points, const std::vector<OverlayPart>& parts);

}  // namespace binpick::cell
