// listHandEyeViews: pairs every robot pose of DIR/poses.txt with its image DIR/VIEW.png.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include "binpick/calibration/hand_eye_views.hpp"
#include "binpick/calibration/robot_pose_file.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/image_file.hpp"

namespace binpick::calibration {
namespace {

namespace fs = std::filesystem;

// The view names of DIR's PNG images (the file name without .png).
std::set<std::string> imageViews(const fs::path& directory) {
  std::set<std::string> views;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory, error)) {
    if (entry.is_regular_file() && entry.path().extension() == ".png") {
      views.insert(entry.path().stem().string());
    }
  }
  if (error) throw core::Error(directory.string() + ": cannot list the directory: " + error.message());
  return views;
}

}  // namespace

std::vector<HandEyeViewFile> listHandEyeViews(const std::string& directory) {
  const fs::path root(directory);
  if (!fs::is_directory(root)) throw core::Error(directory + ": not a directory of hand-eye views");
  const std::string poses_path = (root / "poses.txt").string();
  if (!fs::exists(poses_path)) {
    throw core::Error(poses_path + ": missing; a views directory holds poses.txt and one image per view");
  }
  const RobotPoseFile poses = readRobotPoseFile(poses_path);
  std::set<std::string> images = imageViews(root);

  std::vector<HandEyeViewFile> views;
  for (const RobotPose& pose : poses.poses) {
    const fs::path image = root / (pose.view + ".png");
    if (images.erase(pose.view) == 0) {
      throw core::Error(poses_path + ":" + std::to_string(pose.line) + ": view " + pose.view +
                        " has a robot pose but no image " + image.string());
    }
    views.push_back({pose.view, pose.T_base_flange, image.string(), poses.orientation});
  }
  if (!images.empty()) {
    const std::string view = *images.begin();
    throw core::Error((root / (view + ".png")).string() + ": view " + view + " has an image but no robot pose in " +
                      poses_path + " (" + std::to_string(images.size()) + " image(s) without a pose, " +
                      std::to_string(poses.poses.size()) + " pose(s))");
  }
  return views;
}

}  // namespace binpick::calibration

// The board pose of each view's image, and the solve over the views that have one.
namespace binpick::calibration {
namespace {

cv::Mat readViewImage(const HandEyeViewFile& file, const io::LensIntrinsics& camera) {
  const cv::Mat image = io::readImageFile(file.image_path);
  const std::string prefix = "view " + file.name + " (" + file.image_path + "): ";
  if (image.empty()) throw core::Error(prefix + "cannot read the image");
  if (image.channels() != 1 || (image.depth() != CV_8U && image.depth() != CV_16U)) {
    throw core::Error(prefix + "the image must be 8- or 16-bit grey");
  }
  if (image.cols != camera.width || image.rows != camera.height) {
    throw core::Error(prefix + "the image is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                      " but the camera calibration is " + std::to_string(camera.width) + "x" +
                      std::to_string(camera.height));
  }
  return image;
}

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[200];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

}  // namespace

void BoardViewParams::validate() const {
  detection.validate();
  core::requireField(std::isfinite(min_corner_share) && min_corner_share > 0.0 && min_corner_share <= 1.0,
                     "BoardViewParams", "min_corner_share", "in (0, 1]", min_corner_share);
  core::requireField(std::isfinite(max_rms_px) && max_rms_px > 0.0, "BoardViewParams", "max_rms_px", "positive",
                     max_rms_px);
}

MeasuredView measureView(const HandEyeViewFile& file, const BoardLayout& layout, const io::LensIntrinsics& camera,
                         const BoardViewParams& params) {
  params.validate();
  MeasuredView view;
  view.name = file.name;
  view.T_base_flange = file.T_base_flange;
  view.orientation = file.orientation;
  const BoardDetection detection = detectBoard(readViewImage(file, camera), layout, params.detection);
  view.corners = static_cast<int>(detection.ids.size());
  view.expected = detection.expected;
  if (!detection.found()) {
    view.problem = "board not found: " + detection.problem;
    return view;
  }
  const double share = static_cast<double>(view.corners) / std::max(view.expected, 1);
  if (share < params.min_corner_share) {
    view.problem = format(
        "board mostly out of the image or hidden: %.0f of %.0f corners seen, "
        "needs %.0f%%",
        view.corners, view.expected, 100.0 * params.min_corner_share);
    return view;
  }
  const std::optional<BoardPose> pose = estimateBoardPose(detection, layout, camera);
  if (!pose) {
    view.problem = format("no board pose from its %.0f corners", view.corners);
    return view;
  }
  view.rms_px = pose->rms_px;
  if (!(pose->rms_px <= params.max_rms_px)) {
    view.problem = format(
        "the board pose fits its corners to %.2f px RMS (max %.2f): wrong camera "
        "intrinsics or board layout, or a blurred image",
        pose->rms_px, params.max_rms_px);
    return view;
  }
  view.T_camera_board = pose->T_camera_board;
  if (!detection.complete()) {
    view.note = format("partial board: %.0f of %.0f corners seen", view.corners, view.expected);
  }
  return view;
}

namespace {

// Every angle of a pose in degrees below this (a little above pi) while the views need 15
// degrees of motion: radians written where degrees were expected.
constexpr double kRadiansLimit = 3.2;
constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

bool inDegrees(core::Orientation orientation) {
  return orientation == core::Orientation::EulerZYX || orientation == core::Orientation::FixedXYZ ||
         orientation == core::Orientation::EulerXYZ;
}

// Throws when the poses' angles all look like radians and read as radians they fit.
void rejectRadiansAsDegrees(const std::vector<MeasuredView>& measured, const std::vector<HandEyeView>& views,
                            const HandEyeParams& params) {
  if (views.empty() || !measured.front().orientation || !inDegrees(*measured.front().orientation)) return;
  const core::Orientation orientation = *measured.front().orientation;
  std::vector<HandEyeView> as_radians = views;
  for (HandEyeView& view : as_radians) {
    std::vector<double> angles = core::orientationValues(view.T_base_flange.linear(), orientation);
    for (double& angle : angles) {
      if (!(std::abs(angle) < kRadiansLimit)) return;
      angle *= kDegreesPerRadian;
    }
    view.T_base_flange.linear() = core::rotationFromValues(angles, orientation);
  }
  HandEyeResult fit;
  try {
    fit = solveHandEye(as_radians, params);
  } catch (const core::Error&) {
    return;  // read as radians they do not fit either: let the solve say what is wrong
  }
  if (!fit.ok()) return;
  throw core::Error("hand-eye: the robot orientations look like radians, expected degrees (" +
                    core::orientationName(orientation) + "): every angle is below " +
                    format("%.1f, and read as radians the views fit to %.3f mm, %.4f deg RMS", kRadiansLimit,
                           fit.rms_mm, fit.rms_deg) +
                    "; write the angles in degrees");
}

}  // namespace

HandEyeResult solveMeasuredViews(const std::vector<MeasuredView>& views, const HandEyeParams& params) {
  std::vector<HandEyeView> usable;
  std::ostringstream unusable;
  for (const MeasuredView& view : views) {
    if (view.usable()) {
      usable.push_back({view.name, view.T_base_flange, *view.T_camera_board});
    } else {
      unusable << "; " << view.name << ": " << view.problem;
    }
  }
  if (static_cast<int>(usable.size()) < params.min_views) {
    throw core::Error("hand-eye needs at least " + std::to_string(params.min_views) + " usable views, got " +
                      std::to_string(usable.size()) + " of " + std::to_string(views.size()) + unusable.str());
  }
  rejectRadiansAsDegrees(views, usable, params);
  return solveHandEye(usable, params);
}

}  // namespace binpick::calibration
