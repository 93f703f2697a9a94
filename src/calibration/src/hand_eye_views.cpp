// listHandEyeViews: pairs every robot pose of DIR/poses.txt with its image DIR/VIEW.png.
#include <filesystem>
#include <set>

#include "binpick/calibration/hand_eye_views.hpp"
#include "binpick/calibration/robot_pose_file.hpp"
#include "binpick/io/error.hpp"

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
  if (error) throw Error(directory.string() + ": cannot list the directory: " + error.message());
  return views;
}

}  // namespace

std::vector<HandEyeViewFile> listHandEyeViews(const std::string& directory) {
  const fs::path root(directory);
  if (!fs::is_directory(root)) throw Error(directory + ": not a directory of hand-eye views");
  const std::string poses_path = (root / "poses.txt").string();
  if (!fs::exists(poses_path)) {
    throw Error(poses_path + ": missing; a views directory holds poses.txt and one image per view");
  }
  const RobotPoseFile poses = readRobotPoseFile(poses_path);
  std::set<std::string> images = imageViews(root);

  std::vector<HandEyeViewFile> views;
  for (const RobotPose& pose : poses.poses) {
    const fs::path image = root / (pose.view + ".png");
    if (images.erase(pose.view) == 0) {
      throw Error(poses_path + ":" + std::to_string(pose.line) + ": view " + pose.view +
                  " has a robot pose but no image " + image.string());
    }
    views.push_back({pose.view, pose.T_base_flange, image.string()});
  }
  if (!images.empty()) {
    const std::string view = *images.begin();
    throw Error((root / (view + ".png")).string() + ": view " + view +
                " has an image but no robot pose in " + poses_path + " (" +
                std::to_string(images.size()) + " image(s) without a pose, " +
                std::to_string(poses.poses.size()) + " pose(s))");
  }
  return views;
}

}  // namespace binpick::calibration
