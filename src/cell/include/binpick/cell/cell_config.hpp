#pragma once
// binpickd's settings file (config/binpickd.yaml documents every key): where captures come from,
// the calibrations, the models the cell can pick (recipes) with their grasps, the bin, the robot
// server, the stages' deadlines and the saved artefacts. Relative paths are relative to the
// settings file's directory. Every key is checked: an unknown key, a wrong type or an invalid
// value throws core::Error "FILE: key.path what was wrong". Thread-safe (no shared state).
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "binpick/acquisition/capture_source.hpp"
#include "binpick/acquisition/projector.hpp"
#include "binpick/cell/artefact_store.hpp"
#include "binpick/picking/picking.hpp"
#include "binpick/reconstruction/reconstruction.hpp"
#include "binpick/robot/robot_server.hpp"

namespace binpick::cell {

struct LiveSourceConfig {
  acquisition::CameraParams camera;
  std::string trigger = "none";  // "none" (free-running projector) or "gpio"
  acquisition::GpioTriggerParams gpio;
  acquisition::LiveParams live;  // pattern set, sequencer, reopen backoff
};

struct SourceConfig {
  enum class Mode { Replay, Live } mode = Mode::Replay;
  acquisition::ReplayParams replay;  // loop defaults to true for the daemon
  LiveSourceConfig live;
};

struct RecipeConfig {
  std::string name;
  std::string model_file;              // mesh or cloud of the part (metres)
  std::string model_cache;             // prepared-model cache ("" = none): fast restarts
  std::string settings_file;           // estimation settings (model:, detection:); "" = defaults
  std::vector<picking::Grasp> grasps;  // model frame; empty: generated from the model at startup
  // As the recipe gives it; none: found from the model's mesh at startup (io::findSymmetry), or
  // the identity alone for a model without a mesh.
  std::optional<picking::PartSymmetry> symmetry;
};

struct CycleLimits {
  int capture_timeout_ms = 15000;     // TRIGGER is answered by then (status timeout otherwise)
  int processing_timeout_ms = 15000;  // reconstruct + detect + plan after the capture
  int max_picks = 50;                 // picks kept per cycle
  // Detections whose ICP fit covers less of the model points the camera should see are reported
  // but never sent to the robot (estimation's Detection::coverage).
  double min_pick_coverage = 0.5;
  // Bin content check: fewer points than this above the floor inside the bin means "bin empty"
  // rather than "no objects detected".
  int empty_bin_max_points = 300;
  double empty_bin_min_height = 0.005;  // metres above the floor a point must be to count
  int avoid_cycles = 3;                 // a failed pick's object is avoided for that many cycles
  // Return the memory a cycle freed to the system after it (glibc's malloc_trim): the resident
  // memory stays lower, at the price of the next cycle faulting its buffers in again, which
  // costs about half a second per cycle of the demo bin (docs/binpickd.md, Figures). Off: cycle
  // time comes first on a cell PC; on where memory is tight.
  bool trim_memory_after_cycle = false;
  void validate() const;  // throws core::Error naming the field
};

// The web view (binpick::web): a read-only HTTP page and JSON API of the cell's state, off unless
// the settings have a `web:` section. Served by its own threads, so that no HTTP client can delay
// a robot's cycle.
struct WebViewConfig {
  std::string bind_address = "127.0.0.1";    // this machine only, unless told otherwise
  int port = 8080;                           // 0: any free port (tests)
  std::vector<std::string> allowed_clients;  // IPv4 addresses or CIDR blocks; empty: any
  int threads = 4;                           // requests served at once; more connections wait
  // A client that sends or reads nothing for this long is disconnected, so that a stalled
  // browser or a hostile client frees its thread.
  int timeout_ms = 5000;
  void validate() const;  // throws core::Error naming web.FIELD
};

struct CellConfig {
  std::string origin;  // the settings file, for messages
  SourceConfig source;
  std::string calibration;                         // rig calib.yaml; "" = the capture's own
  std::optional<Eigen::Isometry3d> T_base_camera;  // hand-eye; absent: picks cannot be sent
  std::vector<RecipeConfig> recipes;               // at least one; the first is selected at start
  picking::PickParams picking;                     // grasps and symmetry come from the recipe
  robot::RobotServerParams robot;
  CycleLimits limits;
  std::optional<ArtefactParams> artefacts;  // absent: nothing saved
  std::optional<WebViewConfig> web;         // absent: no web view
  reconstruction::ReconstructionParams reconstruction;
};

CellConfig loadCellConfig(const std::string& path);
// The same from YAML text; relative paths are resolved against `base_directory`.
CellConfig parseCellConfig(const std::string& yaml_text, const std::string& origin, const std::string& base_directory);

}  // namespace binpick::cell
