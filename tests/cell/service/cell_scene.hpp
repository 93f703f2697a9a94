#pragma once
// Test support: a bin of l_brackets in the virtual cell written once per test process as the
// daemon would find it on disk (a capture directory for replay, calib.yaml, the part's mesh), the
// truth, and binpickd settings text pointing at it.
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace binpick::cell::testing {

struct CellScene {
  std::string directory;                          // holds capture/ (with calib.yaml), part.ply, empty/ (an empty bin)
  std::string capture;                            // capture/
  std::string empty_capture;                      // empty/: the same bin with no parts
  std::string calibration;                        // capture/calib.yaml
  std::string model;                              // part.ply
  std::vector<Eigen::Isometry3d> T_base_objects;  // truth, robot base frame
  Eigen::Isometry3d T_base_camera = Eigen::Isometry3d::Identity();
};

// Rendered once per build tree (12 parts, the virtual rig) and shared by all test processes.
const CellScene& cellScene();

// binpickd settings for the scene: replay of `replay_path` (default: the capture), port 0, the
// l_bracket's grasps; `extra` is appended (YAML top-level keys, e.g. "limits: {...}\n").
std::string cellConfigYaml(const CellScene& scene, const std::string& extra = "", const std::string& replay_path = "");

}  // namespace binpick::cell::testing
