// The guided session's files: appended line by line, images staged and renamed into place.
#include "hand_eye_guided_recorder.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "binpick/calibration/robot_pose_file.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/image_file.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;
using calibration::RobotPoseFile;

constexpr const char* kPosesFile = "poses.txt";
constexpr const char* kJournalFile = "received.txt";
constexpr const char* kRejectedDirectory = "rejected";
// Not *.png: the file mode takes every DIR/*.png for a view.
constexpr const char* kStagedImage = ".staged-view.part";

// The names in a poses file written in `orientation`; none when there is no file yet.
std::set<std::string> namesIn(const fs::path& path, core::Orientation orientation) {
  std::set<std::string> names;
  if (!fs::exists(path)) return names;
  const RobotPoseFile file = calibration::readRobotPoseFile(path.string());
  if (file.orientation != orientation) {
    throw core::Error(path.string() + ": its poses are in " + core::orientationName(file.orientation) +
                      " but the robot's are in " + core::orientationName(orientation) +
                      " (--orientation); continue with that convention or record to a new directory");
  }
  for (const calibration::RobotPose& pose : file.poses) names.insert(pose.view);
  return names;
}

// The file's header, and one pose's line, exactly as the file mode's own writer has them.
std::string header(core::Orientation orientation) {
  return calibration::formatRobotPoses(RobotPoseFile{orientation, {}});
}

std::string poseLine(const std::string& name, const Eigen::Isometry3d& T_base_flange, core::Orientation orientation) {
  const std::string alone = calibration::formatRobotPoses(RobotPoseFile{orientation, {{name, T_base_flange, 0}}});
  return alone.substr(header(orientation).size());
}

void appendPose(const fs::path& path, const std::string& name, const Eigen::Isometry3d& T_base_flange,
                core::Orientation orientation) {
  std::error_code error;
  const bool fresh = !fs::exists(path, error) || fs::file_size(path, error) == 0;
  std::ofstream out(path, std::ios::app);
  if (fresh) out << header(orientation);
  out << poseLine(name, T_base_flange, orientation);
  out.flush();
  if (!out) throw core::Error(path.string() + ": cannot append the pose of " + name);
}

// "view_007": the first free name from `index` on, neither listed nor on disk.
std::string freeName(const std::string& prefix, int& index, const std::set<std::string>& taken,
                     const fs::path& images) {
  for (;; ++index) {
    char name[32];
    std::snprintf(name, sizeof name, "%s_%03d", prefix.c_str(), index);
    if (taken.count(name) == 0 && !fs::exists(images / (std::string(name) + ".png"))) {
      return name;
    }
  }
}

void renameInto(const fs::path& from, const fs::path& to) {
  std::error_code error;
  fs::rename(from, to, error);
  if (error) throw core::Error(to.string() + ": cannot move the image into place: " + error.message());
}

}  // namespace

GuidedViewRecorder::GuidedViewRecorder(const std::string& directory, core::Orientation orientation)
    : directory_(directory), orientation_(orientation) {
  std::error_code error;
  fs::create_directories(fs::path(directory) / kRejectedDirectory, error);
  if (error) throw core::Error(directory + ": cannot create the views directory: " + error.message());
  views_ = namesIn(fs::path(directory) / kPosesFile, orientation);
  attempts_ = namesIn(fs::path(directory) / kJournalFile, orientation);
  namesIn(fs::path(directory) / kRejectedDirectory / kPosesFile, orientation);  // the check
  next_view_ = accepted();
  next_attempt_ = static_cast<int>(attempts_.size()) + 1;
}

std::string GuidedViewRecorder::receive(const Eigen::Isometry3d& T_base_flange) {
  const fs::path root(directory_);
  const std::string attempt = freeName("attempt", next_attempt_, attempts_, root / kRejectedDirectory);
  appendPose(root / kJournalFile, attempt, T_base_flange, orientation_);
  attempts_.insert(attempt);
  return attempt;
}

std::string GuidedViewRecorder::stage(const cv::Mat& image) {
  const std::string png = io::encodePng(image);
  if (png.empty()) throw core::Error("cannot encode the image as PNG");
  const fs::path path = fs::path(directory_) / kStagedImage;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(png.data(), static_cast<std::streamsize>(png.size()));
  out.close();
  if (!out) throw core::Error(path.string() + ": cannot write the image");
  return path.string();
}

std::string GuidedViewRecorder::accept(const Eigen::Isometry3d& T_base_flange) {
  const fs::path root(directory_);
  const std::string view = freeName("view", next_view_, views_, root);
  appendPose(root / kPosesFile, view, T_base_flange, orientation_);
  renameInto(root / kStagedImage, root / (view + ".png"));
  views_.insert(view);
  return view;
}

std::string GuidedViewRecorder::reject(const std::string& attempt, const Eigen::Isometry3d& T_base_flange) {
  const fs::path rejected = fs::path(directory_) / kRejectedDirectory;
  appendPose(rejected / kPosesFile, attempt, T_base_flange, orientation_);
  const fs::path image = rejected / (attempt + ".png");
  renameInto(fs::path(directory_) / kStagedImage, image);
  return image.string();
}

}  // namespace binpick::cli
