#include "overlay_drawing.hpp"

#include <opencv2/imgproc.hpp>
#include <string>

namespace binpick::cell::overlay_detail {

namespace {

// Points this close to the camera's plane project to absurd pixels: treat them as behind it.
constexpr double kMinDepth = 1e-6;  // metres

// Projects a point in front of the camera, keeping pixels outside the image.
std::optional<Eigen::Vector2d> projectInFront(const io::LensIntrinsics& camera, const Eigen::Vector3d& point) {
  if (!(point.z() > kMinDepth)) return std::nullopt;
  const Eigen::Vector2d pixel = camera.project(point);
  if (!pixel.allFinite()) return std::nullopt;
  return pixel;
}

bool withinMargin(const io::LensIntrinsics& camera, const Eigen::Vector2d& pixel, double margin) {
  return pixel.x() >= -margin && pixel.y() >= -margin && pixel.x() < camera.width + margin &&
         pixel.y() < camera.height + margin;
}

cv::Point rounded(const Eigen::Vector2d& pixel) { return {cvRound(pixel.x()), cvRound(pixel.y())}; }

}  // namespace

int strokeWidth(const cv::Mat& canvas) { return std::max(1, canvas.cols / 1000); }

std::optional<cv::Point> pixelOf(const io::LensIntrinsics& camera, const Eigen::Vector3d& point) {
  const std::optional<Eigen::Vector2d> pixel = projectInFront(camera, point);
  if (!pixel) return std::nullopt;
  const cv::Point at = rounded(*pixel);
  if (at.x < 0 || at.y < 0 || at.x >= camera.width || at.y >= camera.height) return std::nullopt;
  return at;
}

void drawModelPoints(cv::Mat& canvas, const io::LensIntrinsics& camera,
                     const std::vector<Eigen::Vector3f>& model_points, const Eigen::Isometry3d& T_camera_model,
                     const cv::Scalar& colour) {
  const int radius = strokeWidth(canvas) - 1;  // 0: single pixels on small images
  for (const Eigen::Vector3f& point : model_points) {
    const std::optional<cv::Point> at = pixelOf(camera, T_camera_model * point.cast<double>());
    if (!at) continue;
    if (radius == 0) {
      canvas.at<cv::Vec3b>(*at) = cv::Vec3b(colour[0], colour[1], colour[2]);
    } else {
      cv::circle(canvas, *at, radius, colour, cv::FILLED);
    }
  }
}

void drawGraspTripod(cv::Mat& canvas, const io::LensIntrinsics& camera, const Eigen::Isometry3d& T_camera_grasp,
                     double length) {
  const cv::Scalar axis_colours[3] = {{0, 0, 255}, {0, 255, 0}, {255, 0, 0}};  // BGR: x, y, z
  const Eigen::Vector3d origin = T_camera_grasp.translation();
  const std::optional<Eigen::Vector2d> from = projectInFront(camera, origin);
  // One image size around the image: far enough for clipping, near enough for the lens model.
  const double margin = std::max(camera.width, camera.height);
  if (!from || !withinMargin(camera, *from, margin)) return;
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d end = origin + T_camera_grasp.linear().col(axis) * length;
    const std::optional<Eigen::Vector2d> to = projectInFront(camera, end);
    if (!to || !withinMargin(camera, *to, margin)) continue;
    // Not antialiased: the axes keep their exact colours (the tests look at them).
    cv::line(canvas, rounded(*from), rounded(*to), axis_colours[axis], strokeWidth(canvas), cv::LINE_8);
  }
}

void drawOriginMarker(cv::Mat& canvas, const io::LensIntrinsics& camera, const Eigen::Isometry3d& T_camera_model,
                      const cv::Scalar& colour, int pick_rank) {
  const std::optional<cv::Point> at = pixelOf(camera, T_camera_model.translation());
  if (!at) return;
  const int stroke = strokeWidth(canvas);
  const int radius = 3 * stroke;
  cv::circle(canvas, *at, radius, colour, cv::FILLED);
  if (pick_rank < 0) return;
  // Beside the disc, not on it, so the disc's colour stays visible; white on a black outline
  // reads on any background.
  const std::string label = std::to_string(pick_rank);
  const cv::Point text_at = *at + cv::Point(radius + 2 * stroke, -radius - 2 * stroke);
  const double scale = 0.5 * stroke;
  cv::putText(canvas, label, text_at, cv::FONT_HERSHEY_SIMPLEX, scale, {0, 0, 0}, 3 * stroke, cv::LINE_AA);
  cv::putText(canvas, label, text_at, cv::FONT_HERSHEY_SIMPLEX, scale, {255, 255, 255}, stroke, cv::LINE_AA);
}

}  // namespace binpick::cell::overlay_detail
