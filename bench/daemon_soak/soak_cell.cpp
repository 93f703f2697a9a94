#include "soak_cell.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"
#include "cell_scene.hpp"

namespace binpick::bench::soak {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

std::string emitted(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return std::string(out.c_str()) + "\n";
}

// Bytes no YAML reader makes a calibration of: what a failing disk or a wrong copy leaves.
std::string garbage() {
  std::string bytes = "\x7f" "ELF\x02\x01\x01 {[ camera_matrix: !!opencv-matrix ]]\n";
  for (int i = 0; i < 256; ++i) bytes += static_cast<char>((i * 37 + 11) % 256);
  return bytes;
}

// The recipe's estimation settings with detection on `threads` threads.
std::string detectionSettings(const std::string& original_path, int threads) {
  YAML::Node settings = YAML::LoadFile(original_path);
  settings["detection"]["threads"] = threads;
  return emitted(settings);
}

// The test bin's settings with every file the soak changes or writes (calibration, caches,
// estimation settings) in `directory`, and every stage on `threads` threads, so the soak leaves
// the shared scene alone and the machine's other cores free.
std::string soakSettings(const std::string& directory, int threads) {
  YAML::Node settings = YAML::Load(cell::testing::cellConfigYaml(cell::testing::cellScene()));
  YAML::Node recipe = settings["recipes"][0];
  const std::string detection_path = directory + "/detection.yaml";
  core::writeFileAtomically(detection_path, detectionSettings(recipe["settings"].as<std::string>(), threads));
  recipe["settings"] = detection_path;
  recipe["cache"] = directory + "/l_bracket.cache";
  settings["recipes"][1]["cache"] = directory + "/second.cache";
  settings["source"]["replay"]["threads"] = threads;
  settings["reconstruction"]["threads"] = threads;
  settings["calibration"] = directory + "/calib.yaml";
  // A visitor's FAILED must not shrink the main robot's cycles: a part is avoided in no later cycle.
  settings["limits"]["avoid_cycles"] = 0;
  return emitted(settings);
}

}  // namespace

const char* reloadKindName(ReloadKind kind) {
  switch (kind) {
    case ReloadKind::Valid: return "valid";
    case ReloadKind::Garbage: return "garbage";
    case ReloadKind::Truncated: return "truncated";
    case ReloadKind::Removed: return "removed";
  }
  return "?";
}

std::string SoakCell::sceneDirectory() { return cell::testing::cellScene().directory; }

SoakCell::SoakCell(const std::string& directory, int threads)
    : directory_(directory),
      settings_path_(directory + "/binpickd.yaml"),
      calibration_path_(directory + "/calib.yaml") {
  fs::create_directories(directory);
  calibration_ = core::readFile(cell::testing::cellScene().calibration);
  settings_ = soakSettings(directory, threads);
  core::writeFileAtomically(calibration_path_, calibration_);
  core::writeFileAtomically(settings_path_, settings_);
}

void SoakCell::start() {
  notify_ = std::make_unique<cell::testing::NotifySocket>(directory_ + "/notify");
  cell::testing::DaemonOptions options;
  options.config_path = settings_path_;
  options.port_file = directory_ + "/port";
  options.notify_socket = notify_->path();
  options.stderr_file = logPath();
  daemon_ = std::make_unique<cell::testing::DaemonProcess>(options);
  port_ = daemon_->port();
  if (!notify_->waitFor("READY=1", 120s)) throw core::Error("binpickd did not report READY=1; see " + logPath());
  notifications_ = std::make_unique<NotifyListener>(*notify_);
}

void SoakCell::prepareReload(ReloadKind kind) {
  core::writeFileAtomically(settings_path_, settings_);
  switch (kind) {
    case ReloadKind::Valid:
      core::writeFileAtomically(calibration_path_, calibration_);
      break;
    case ReloadKind::Garbage:
      core::writeFileAtomically(calibration_path_, garbage());
      break;
    case ReloadKind::Truncated:  // a copy cut short: the projector and the rig's pose missing
      core::writeFileAtomically(calibration_path_, calibration_.substr(0, calibration_.size() / 2));
      break;
    case ReloadKind::Removed:
      fs::remove(calibration_path_);
      break;
  }
}

}  // namespace binpick::bench::soak
