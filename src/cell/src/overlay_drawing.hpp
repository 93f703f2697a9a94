#pragma once
// Internal: the pieces of the overlay, each drawn onto an 8-bit BGR canvas the camera's size.
// Stateless functions: thread-safe for different canvases.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "binpick/io/lens.hpp"

namespace binpick::cell::overlay_detail {

// Line width and dot radius in pixels: one per 1000 image columns, so that overlays of large
// sensors stay readable when scaled down on a screen.
int strokeWidth(const cv::Mat& canvas);

// The pixel a camera-frame point lands on; nullopt behind the camera or outside the image.
std::optional<cv::Point> pixelOf(const io::LensIntrinsics& camera, const Eigen::Vector3d& point);

void drawModelPoints(cv::Mat& canvas, const io::LensIntrinsics& camera,
                     const std::vector<Eigen::Vector3f>& model_points, const Eigen::Isometry3d& T_camera_model,
                     const cv::Scalar& colour);
// x red, y green, z blue; an axis with an end behind the camera or far outside the image is
// skipped (the lens model is meaningless there), otherwise clipped to the image.
void drawGraspTripod(cv::Mat& canvas, const io::LensIntrinsics& camera, const Eigen::Isometry3d& T_camera_grasp,
                     double length);
// A disc at the projected model origin, and the rank number beside it for picks (rank >= 0).
void drawOriginMarker(cv::Mat& canvas, const io::LensIntrinsics& camera, const Eigen::Isometry3d& T_camera_model,
                      const cv::Scalar& colour, int pick_rank);

}  // namespace binpick::cell::overlay_detail
