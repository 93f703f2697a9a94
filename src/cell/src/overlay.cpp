#include "overlay.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "binpick/core/error.hpp"
#include "overlay_drawing.hpp"

namespace binpick::cell {

using namespace overlay_detail;

namespace {

void checkImage(const cv::Mat& image, const io::LensIntrinsics& camera) {
  if (image.empty()) throw core::Error("overlay: the camera image is empty");
  const bool grey = image.channels() == 1 && (image.depth() == CV_8U || image.depth() == CV_16U);
  if (!grey) {
    throw core::Error("overlay: the camera image must be 8- or 16-bit grey (got " + std::to_string(image.channels()) +
                      " channels of depth " + std::to_string(image.depth()) + ")");
  }
  camera.validate("overlay camera");
  if (image.cols != camera.width || image.rows != camera.height) {
    throw core::Error("overlay: the camera image is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                      " but the camera's lens is " + std::to_string(camera.width) + "x" +
                      std::to_string(camera.height));
  }
}

cv::Mat colourCanvas(const cv::Mat& image) {
  cv::Mat grey8 = image;
  // 65535 / 257 = 255: the full 16-bit range onto the full 8-bit range.
  if (image.depth() == CV_16U) image.convertTo(grey8, CV_8U, 1.0 / 257.0);
  cv::Mat canvas;
  cv::cvtColor(grey8, canvas, cv::COLOR_GRAY2BGR);
  return canvas;
}

int lastRank(const std::vector<OverlayPart>& parts) {
  int last = 0;
  for (const OverlayPart& part : parts) last = std::max(last, part.pick_rank);
  return last;
}

// Parts not picked first, then picks from the last to the first: the first pick ends up on top.
std::vector<const OverlayPart*> drawingOrder(const std::vector<OverlayPart>& parts) {
  std::vector<const OverlayPart*> order;
  for (const OverlayPart& part : parts) order.push_back(&part);
  std::stable_sort(order.begin(), order.end(), [](const OverlayPart* a, const OverlayPart* b) {
    const bool a_picked = a->pick_rank >= 0, b_picked = b->pick_rank >= 0;
    if (a_picked != b_picked) return !a_picked;
    return a->pick_rank > b->pick_rank;
  });
  return order;
}

}  // namespace

cv::Scalar overlayRankColour(int pick_rank, int last_rank) {
  if (pick_rank < 0) return {0, 0, 255};  // BGR red
  const double t = last_rank > 0 ? std::clamp(double(pick_rank) / last_rank, 0.0, 1.0) : 0.0;
  return {0, 255, std::round(255.0 * t)};  // green (first) .. yellow (last)
}

cv::Mat renderOverlay(const cv::Mat& image, const io::LensIntrinsics& camera,
                      const std::vector<Eigen::Vector3f>& model_points, const std::vector<OverlayPart>& parts) {
  checkImage(image, camera);
  cv::Mat canvas = colourCanvas(image);
  const int last = lastRank(parts);
  const std::vector<const OverlayPart*> order = drawingOrder(parts);
  // Layers: all points, then grasps, then origin markers, so that no part hides another's label.
  for (const OverlayPart* part : order) {
    drawModelPoints(canvas, camera, model_points, part->T_camera_model, overlayRankColour(part->pick_rank, last));
  }
  for (const OverlayPart* part : order) {
    if (part->T_camera_grasp) drawGraspTripod(canvas, camera, *part->T_camera_grasp, kOverlayTripodLength);
  }
  for (const OverlayPart* part : order) {
    drawOriginMarker(canvas, camera, part->T_camera_model, overlayRankColour(part->pick_rank, last), part->pick_rank);
  }
  return canvas;
}

}  // namespace binpick::cell
