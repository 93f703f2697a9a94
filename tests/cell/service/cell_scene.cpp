#include "cell_scene.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "binpick/io/capture.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"

namespace binpick::cell::testing {
namespace {

namespace fs = std::filesystem;

// The robot base: the bin floor's centre at (0.6, 0, 0), z up.
Eigen::Isometry3d baseFromBin() {
  Eigen::Isometry3d T_base_bin = Eigen::Isometry3d::Identity();
  T_base_bin.translation() = Eigen::Vector3d(0.6, 0.0, 0.0);
  return T_base_bin;
}

simulation::PileScene writePile(simulation::PileParams params, int objects, const io::TriangleMesh& part,
                                const std::string& directory) {
  params.objects = objects;
  io::PatternSetSpec patterns;
  patterns.projector_width = params.rig.projector.width;
  patterns.projector_height = params.rig.projector.height;
  const simulation::PhotometryParams photometry;
  simulation::PileCapture pile = simulation::generatePileCapture(part, params, patterns, photometry);
  io::writeCapture(directory,
                   simulation::recordedCapture(std::move(pile.images), params, patterns, photometry, "test bin"));
  io::writeRigCalibration(directory + "/calib.yaml", params.rig);
  return std::move(pile.scene);
}

void writePoses(std::ostream& out, const std::vector<Eigen::Isometry3d>& poses) {
  out.precision(17);
  for (const Eigen::Isometry3d& pose : poses) {
    for (int i = 0; i < 16; ++i) out << pose.matrix()(i / 4, i % 4) << (i == 15 ? "\n" : " ");
  }
}

std::vector<Eigen::Isometry3d> readPoses(std::istream& in) {
  std::vector<Eigen::Isometry3d> poses;
  Eigen::Matrix4d m;
  while (in >> m(0, 0)) {
    for (int i = 1; i < 16; ++i) in >> m(i / 4, i % 4);
    poses.emplace_back(m);
  }
  return poses;
}

// Renders the scene into `directory` (capture/, empty/, part.ply, poses.txt: T_base_camera, then
// the truth of every part in the base frame).
void renderScene(const std::string& directory) {
  fs::create_directories(directory);
  const simulation::Part part = simulation::makePart("l_bracket");
  io::writeMesh(directory + "/part.ply", part.mesh);
  simulation::PileParams params;
  params.seed = 5;
  const simulation::PileScene pile = writePile(params, 12, part.mesh, directory + "/capture");
  writePile(params, 0, part.mesh, directory + "/empty");
  const Eigen::Isometry3d T_base_camera = baseFromBin() * pile.T_camera_bin.inverse();
  std::vector<Eigen::Isometry3d> poses{T_base_camera};
  for (const simulation::ObjectTruth& object : pile.objects) poses.push_back(T_base_camera * object.T_camera_object);
  std::ofstream file(directory + "/poses.txt");
  writePoses(file, poses);
}

// The scene is rendered once per build tree and shared by every test process: ctest runs each
// test in its own process, and rendering takes seconds. Rendered aside, then renamed into place,
// so a process never sees half a scene.
std::string sceneDirectory() {
  const fs::path directory = fs::path(BINPICK_TEST_DATA_DIR) / "cell_scene_v1";
  if (fs::exists(directory / "poses.txt")) return directory.string();
  const fs::path aside = directory.string() + ".partial-" + std::to_string(getpid());
  renderScene(aside.string());
  std::error_code taken;
  fs::rename(aside, directory, taken);
  if (taken) fs::remove_all(aside);  // another process finished first: use theirs
  return directory.string();
}

CellScene loadScene() {
  CellScene scene;
  scene.directory = sceneDirectory();
  scene.capture = scene.directory + "/capture";
  scene.empty_capture = scene.directory + "/empty";
  scene.calibration = scene.capture + "/calib.yaml";
  scene.model = scene.directory + "/part.ply";
  std::ifstream file(scene.directory + "/poses.txt");
  std::vector<Eigen::Isometry3d> poses = readPoses(file);
  scene.T_base_camera = poses.at(0);
  scene.T_base_objects.assign(poses.begin() + 1, poses.end());
  return scene;
}

std::string poseYaml(const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  const Eigen::Vector3d t = pose.translation();
  std::ostringstream text;
  text.precision(12);
  text << "{translation: [" << t.x() << ", " << t.y() << ", " << t.z() << "], rotation: [" << q.w() << ", " << q.x()
       << ", " << q.y() << ", " << q.z() << "]}";
  return text.str();
}

// A sanitizer build (scripts/sanitize.sh) runs a cycle 5 to 20 times slower than a release build:
// there the stages get ten times the product's deadlines (15 s each), unless the test sets its
// own. Elsewhere `extra` is left as it is.
std::string withSanitizerDeadlines(std::string extra) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  if (extra.find("capture_timeout_ms") != std::string::npos ||
      extra.find("processing_timeout_ms") != std::string::npos) {
    return extra;
  }
  const std::string deadlines = "capture_timeout_ms: 150000, processing_timeout_ms: 150000";
  const std::string limits = "limits: {";
  const std::size_t at = extra.find(limits);
  if (at == std::string::npos)
    return extra + (extra.empty() || extra.back() == '\n' ? "" : "\n") + limits + deadlines + "}\n";
  const std::size_t inside = at + limits.size();
  const bool empty = extra.find_first_not_of(' ', inside) == extra.find('}', inside);
  return extra.insert(inside, deadlines + (empty ? "" : ", "));
#else
  return extra;
#endif
}

}  // namespace

const CellScene& cellScene() {
  static const CellScene scene = loadScene();
  return scene;
}

std::string cellConfigYaml(const CellScene& scene, const std::string& extra, const std::string& replay_path) {
  std::ostringstream yaml;
  yaml << "source: {mode: replay, replay: {path: " << (replay_path.empty() ? scene.capture : replay_path)
       << ", loop: true}}\n"
       << "calibration: " << scene.calibration << "\n"
       << "hand_eye: {T_base_camera: " << poseYaml(scene.T_base_camera) << "}\n"
       << "recipes:\n"
       << "  - name: l_bracket\n"
       << "    model: " << scene.model << "\n"
       << "    cache: " << scene.directory << "/part.cache\n"
       << "    settings: " << BINPICK_CONFIG_DIR << "/virtual-cell.yaml\n"
       << "    grasps:\n"
       << "      - {name: long leg outside, translation: [0.0124, -0.0126, 0], rotation: [-90, 0, 0], convention: "
          "euler_xyz}\n"
       << "      - {name: long leg inside, translation: [0.0164, -0.0046, 0], rotation: [90, 0, 0], convention: "
          "euler_xyz}\n"
       << "  - {name: second, model: " << scene.model << ", grasps: [{translation: [0, 0, 0]}]}\n"
       << "picking: {bin: {T_base_bin: {translation: [0.6, 0, 0]}}, max_tilt_deg: 80, order: highest_first}\n"
       << "robot: {bind_address: 127.0.0.1, port: 0}\n"
       << withSanitizerDeadlines(extra);
  return yaml.str();
}

}  // namespace binpick::cell::testing
