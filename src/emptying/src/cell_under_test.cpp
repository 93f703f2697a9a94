#include "cell_under_test.hpp"

#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>

#include "binpick/cell/cell_config.hpp"
#include "binpick/cell/cell_setup.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/pose_yaml.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/io/rig_calibration.hpp"

namespace binpick::emptying::detail {
namespace fs = std::filesystem;

// The capture the next TRIGGER takes: the pile as it lies now.
class VirtualCamera : public acquisition::CaptureSource {
 public:
  void show(io::Capture capture) {
    std::lock_guard lock(mutex_);
    capture_ = std::move(capture);
  }
  std::string description() const override { return "virtual cell camera"; }

 private:
  io::Capture nextCapture(const core::CancelFlag* /*cancel*/) override {
    std::lock_guard lock(mutex_);
    if (!capture_) throw core::Error("virtual camera: no capture rendered yet");
    return *capture_;  // images share their pixels: no copy
  }

  std::mutex mutex_;
  std::optional<io::Capture> capture_;
};

namespace {

// Seconds the robot waits for a reply: the cell's own deadlines (15 s per stage) answer first.
constexpr std::chrono::milliseconds kReplyTimeout{60000};
// The robot base 0.6 m from the bin's centre along x, as in the demo cell.
const Eigen::Vector3d kBaseToBin(0.6, 0.0, 0.0);

std::string vector3(const Eigen::Vector3d& v) {
  std::ostringstream text;
  text.precision(9);
  text << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return text.str();
}

std::string quaternion(const Eigen::Matrix3d& rotation) {
  const Eigen::Quaterniond q(rotation);
  std::ostringstream text;
  text.precision(9);
  text << "[" << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << "]";
  return text.str();
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream file(path);
  file << text;
  if (!file) throw core::Error(path.string() + ": cannot write");
}

// The detector's crop, as config/virtual-cell.yaml: the bin's inside from 3 mm above the floor up to
// 0.1 m below the camera, 3 mm inside the walls, in the camera frame (the camera looks straight down).
std::string detectionSettings(const simulation::PileParams& pile) {
  constexpr double kInset = 0.003, kBelowCamera = 0.1;
  const double near_z = kBelowCamera, far_z = pile.camera_height - kInset;
  std::ostringstream text;
  text << "# The virtual cell's bin: the detector's crop in the camera frame (metres).\n"
       << "detection:\n  scene:\n    crop:\n"
       << "      pose:\n"
       << core::poseYaml(Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 0.5 * (near_z + far_z))), "        ")
       << "      half_extents: "
       << vector3({0.5 * pile.bin_length - kInset, 0.5 * pile.bin_width - kInset, 0.5 * (far_z - near_z)}) << "\n";
  return text.str();
}

std::string gripperSettings(const picking::GripperParams& g) {
  std::ostringstream text;
  text.precision(9);
  text << "  gripper: {type: " << picking::gripperTypeName(g.type) << ", cup_diameter: " << g.cup_diameter
       << ", cup_length: " << g.cup_length << ", seal_tolerance: " << g.seal_tolerance
       << ", max_lean_deg: " << g.max_lean_deg << ", nose_angle_deg: " << g.nose_angle_deg << ", stroke: " << g.stroke
       << ", finger_width: " << g.finger_width << ", finger_depth: " << g.finger_depth
       << ", finger_thickness: " << g.finger_thickness << ", tool_radius: " << g.tool_radius
       << ", tool_length: " << g.tool_length << "}\n";
  return text.str();
}

// binpickd's settings for the run: the virtual rig's calibration, the camera above the bin, the
// part's recipe without grasps (the cell generates them), the bin, the gripper, every cycle's
// overlay and detections saved, and the web view when asked for.
std::string cellSettings(const EmptyingParams& params, const Eigen::Isometry3d& T_base_camera, int max_cycles) {
  const simulation::PileParams& pile = params.pile;
  std::ostringstream text;
  text.precision(9);
  text << "# binpickd in the virtual cell's bin-emptying run. The virtual camera stands in for the\n"
       << "# source during the run; the replay path names where captures would be replayed from.\n"
       << "source: {mode: replay, replay: {path: captures}}\n"
       << "calibration: calib.yaml\n"
       << "hand_eye:\n  T_base_camera: {translation: " << vector3(T_base_camera.translation())
       << ", rotation: " << quaternion(T_base_camera.linear()) << ", convention: quaternion}\n"
       << "recipes:\n  - {name: part, model: part.ply, cache: model.cache, settings: detection.yaml}\n"
       << "picking:\n  bin: {length: " << pile.bin_length << ", width: " << pile.bin_width
       << ", wall_height: " << pile.bin_wall_height << ", T_base_bin: {translation: " << vector3(kBaseToBin) << "}}\n"
       << "  approach_distance: " << params.approach_distance << "\n"
       << gripperSettings(params.gripper) << "robot: {bind_address: 127.0.0.1, port: 0, orientation: euler_zyx}\n"
       << "artefacts: {directory: ../cycles, max_cycles: " << max_cycles
       << ", capture: false, cloud: false, detections: true, overlay: true}\n";
  if (params.web_port >= 0) text << "web: {bind_address: 127.0.0.1, port: " << params.web_port << "}\n";
  return text.str();
}

}  // namespace

CellUnderTest::CellUnderTest(const simulation::Part& part, const EmptyingParams& params,
                             const Eigen::Isometry3d& T_camera_bin) {
  T_base_bin_ = Eigen::Isometry3d::Identity();
  T_base_bin_.translation() = kBaseToBin;
  const Eigen::Isometry3d T_base_camera = T_base_bin_ * T_camera_bin.inverse();

  const fs::path directory = fs::path(params.out_directory) / "cell";
  fs::create_directories(directory);
  io::writeMesh((directory / "part.ply").string(), part.mesh);
  io::writeRigCalibration((directory / "calib.yaml").string(), params.pile.rig);
  writeText(directory / "detection.yaml", detectionSettings(params.pile));
  writeText(directory / "binpickd.yaml", cellSettings(params, T_base_camera, params.cycleLimit()));

  cell::CellConfig config = cell::loadCellConfig((directory / "binpickd.yaml").string());
  // The settings file's symmetry syntax covers one axis; the built-in parts declare theirs exactly.
  config.recipes.front().symmetry = part.symmetry;
  setup_ = cell::prepareCell(config);

  std::shared_ptr<web::LogRing> log_ring;
  if (config.web) {  // before the cell's threads start: spdlog's sink lists are not guarded
    log_ring = web::attachLogRing();
  }
  auto camera = std::make_unique<VirtualCamera>();
  camera_ = camera.get();
  service_ = std::make_unique<cell::CellService>(
      setup_, std::move(camera),
      [this](robot::ClientId client, const robot::Reply& reply) { server_->reply(client, reply); });
  server_ = std::make_unique<robot::RobotServer>(config.robot, *service_);
  serving_ = std::thread([this] { server_->run(); });
  try {
    if (config.web) {
      web::WebSources sources{[this] { return service_->report(); }, [this] { return server_->clients(); }, log_ring};
      web_ = std::make_unique<web::WebServer>(*config.web, std::move(sources));
    }
    robot_ = std::make_unique<robot::RobotConnection>("127.0.0.1", server_->port(), config.robot.codec,
                                                      std::chrono::milliseconds(5000));
  } catch (...) {
    stop();  // no destructor runs for a half-built object: the serving thread must end here
    throw;
  }
}

CellUnderTest::~CellUnderTest() { stop(); }

void CellUnderTest::stop() {
  web_.reset();
  robot_.reset();
  if (server_) server_->stop();
  if (serving_.joinable()) serving_.join();
  if (service_) service_->stop();
}

void CellUnderTest::show(io::Capture capture) { camera_->show(std::move(capture)); }

robot::Reply CellUnderTest::request(robot::Command command, const std::string& argument) {
  robot::Request request;
  request.command = command;
  if (!argument.empty()) request.argument = argument;
  return robot_->request(request, kReplyTimeout);
}

}  // namespace binpick::emptying::detail
