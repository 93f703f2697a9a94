#include "rig_test_data.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "binpick/io/capture.hpp"

namespace binpick::test {
namespace {

namespace fs = std::filesystem;

// The version suffix changes whenever the rendering below does: old data is then never reused.
constexpr const char* kDataName = "rig_calibration_v1";
constexpr const char* kBlurredDataName = "rig_calibration_blurred_v3";
constexpr const char* kCodeStepDataName = "rig_calibration_code_step2_v1";

// A board pose of the sequence moved sideways by `offset_x` (camera metres).
Eigen::Isometry3d shifted(const Eigen::Isometry3d& pose, double offset_x) {
  Eigen::Isometry3d moved = pose;
  moved.translation().x() += offset_x;
  return moved;
}

void writeExtraView(const simulation::CalibrationSequenceParams& params, const Eigen::Isometry3d& pose,
                    const std::string& directory) {
  const simulation::CalibrationBoard board(params.board, params.texel_size);
  io::writeCapture(directory, simulation::renderCalibrationCapture(board, pose, params, 99));
}

Eigen::Vector3d boardCentre(const simulation::CalibrationSequenceParams& params, const Eigen::Isometry3d& pose) {
  const simulation::CalibrationBoard board(params.board, params.texel_size);
  const Eigen::Vector2d centre = board.printedFace().center();
  return pose * Eigen::Vector3d(centre.x(), centre.y(), 0.0);
}

// The sequence, then the views a calibration must not use as they are.
void renderData(const std::string& directory) {
  const simulation::CalibrationSequenceParams params = rigTestParams();
  const std::vector<Eigen::Isometry3d> poses = simulation::writeCalibrationSequence(directory + "/sequence", params);
  const Eigen::Isometry3d& pose = poses.front();
  // 2 m sideways at under 1.1 m: far outside the camera's 0.8-wide field of view.
  writeExtraView(params, shifted(pose, 2.0), directory + "/no_board");
  // The camera's left image edge lies at x = -0.40 z; the board, 0.30 m wide, is moved so that
  // its centre sits there, where the projector (whose field reaches x = -0.41 z) still lights it.
  const Eigen::Vector3d centre = boardCentre(params, pose);
  writeExtraView(params, shifted(pose, -0.40 * centre.z() - centre.x()), directory + "/half_out");
  simulation::CalibrationSequenceParams columns_only = params;
  columns_only.pattern_set.row_codes = false;
  writeExtraView(columns_only, pose, directory + "/no_rows");
}

// At the camera's full resolution (the half-resolution views fit to 0.15-0.2 px, too coarse to
// single out a blurred view), 9 poses: 8 remain when the blurred one is dropped.
simulation::CalibrationSequenceParams blurredViewParams() {
  simulation::CalibrationSequenceParams params = rigTestParams();
  params.rig = simulation::makeVirtualRig();
  params.board.type = calibration::BoardType::Chessboard;
  params.poses.count = 9;
  return params;
}

std::string poseName(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "pose_%03d", index);
  return name;
}

// The chessboard sequence, then one of its views defocused: every image of the capture blurred.
void renderBlurredData(const std::string& directory) {
  const BlurredViewData defaults;
  simulation::writeCalibrationSequence(directory + "/sequence", blurredViewParams());
  io::Capture capture = io::readCapture(directory + "/sequence/" + poseName(defaults.blurred_pose));
  for (cv::Mat& image : capture.images) cv::GaussianBlur(image, image, cv::Size(), kBlurSigmaPx);
  io::writeCapture(directory + "/blurred", std::move(capture));
}

// Six poses of the test sequence's rig at code step 2.
simulation::CalibrationSequenceParams codeStepParams() {
  simulation::CalibrationSequenceParams params = rigTestParams();
  params.pattern_set.code_step = 2;
  params.poses.count = 6;
  params.poses.seed = 3;
  return params;
}

// Rendered aside, then renamed into place: a process never sees half the data, and when two
// processes render at once, the first rename wins and the other's copy is removed.
std::string renderedDirectory(const char* name, const char* last_file,
                              const std::function<void(const std::string&)>& render) {
  const fs::path directory = fs::path(BINPICK_TEST_DATA_DIR) / name;
  if (fs::exists(directory / last_file)) return directory.string();
  const fs::path aside = directory.string() + ".partial-" + std::to_string(::getpid());
  fs::remove_all(aside);
  render(aside.string());
  std::error_code taken;
  fs::rename(aside, directory, taken);
  if (taken) fs::remove_all(aside);
  return directory.string();
}

RigTestData loadData() {
  RigTestData data;
  data.params = rigTestParams();
  data.layout = data.params.board.layout();
  data.directory = renderedDirectory(kDataName, "no_rows/capture.json", renderData);
  data.sequence = data.directory + "/sequence";
  for (int i = 0; i < data.params.poses.count; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "/pose_%03d", i);
    data.views.push_back(data.sequence + name);
  }
  data.no_board = data.directory + "/no_board";
  data.half_out = data.directory + "/half_out";
  data.no_rows = data.directory + "/no_rows";
  return data;
}

}  // namespace

simulation::CalibrationSequenceParams rigTestParams() {
  simulation::CalibrationSequenceParams params;
  params.rig.camera = params.rig.camera.scaled(0.5);
  params.pattern_set.projector_width = params.rig.projector.width;
  params.pattern_set.projector_height = params.rig.projector.height;
  params.pattern_set.phase_steps = 0;
  params.poses.count = 10;
  params.poses.seed = 1;
  return params;
}

std::vector<calibration::RigView> readTestViews(const std::vector<std::string>& directories) {
  std::vector<calibration::RigView> views;
  for (const std::string& directory : directories) {
    views.push_back(calibration::readRigView(directory, rigTestData().layout));
  }
  return views;
}

bool anyWarningNames(const calibration::RigCalibrationResult& result, const std::string& view,
                     const std::string& text) {
  return std::any_of(result.warnings.begin(), result.warnings.end(), [&](const std::string& w) {
    return w.find(view) != std::string::npos && w.find(text) != std::string::npos;
  });
}

const io::RigViewQuality& qualityOf(const calibration::RigCalibrationResult& result, const std::string& view) {
  const auto& views = result.quality.views;
  const auto it = std::find_if(views.begin(), views.end(), [&](const io::RigViewQuality& q) { return q.name == view; });
  if (it == views.end()) throw std::runtime_error("no quality entry for " + view);
  return *it;
}

const RigTestData& rigTestData() {
  static const RigTestData data = loadData();
  return data;
}

const BlurredViewData& blurredViewData() {
  static const BlurredViewData data = [] {
    BlurredViewData d;
    d.params = blurredViewParams();
    d.layout = d.params.board.layout();
    const std::string directory = renderedDirectory(kBlurredDataName, "blurred/capture.json", renderBlurredData);
    for (int i = 0; i < d.params.poses.count; ++i) {
      if (i != d.blurred_pose) d.views.push_back(directory + "/sequence/" + poseName(i));
    }
    d.blurred = directory + "/blurred";
    d.views.push_back(d.blurred);
    return d;
  }();
  return data;
}

const CodeStepData& codeStepData() {
  static const CodeStepData data = [] {
    CodeStepData d;
    d.params = codeStepParams();
    d.layout = d.params.board.layout();
    const std::string directory = renderedDirectory(
        kCodeStepDataName, "sequence/truth/board.json",
        [](const std::string& dir) { simulation::writeCalibrationSequence(dir + "/sequence", codeStepParams()); });
    for (int i = 0; i < d.params.poses.count; ++i) d.views.push_back(directory + "/sequence/" + poseName(i));
    return d;
  }();
  return data;
}

}  // namespace binpick::test
