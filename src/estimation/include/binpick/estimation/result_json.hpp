#pragma once
// The detection result as JSON, the schema scripts rely on (docs/detect-output.md):
// {"detections": [{"pose": 4x4 rows, "score", "coverage", "icp_rmse", "seen_through", "twin_margin",
//                  "sure", "votes"}...],
//  "timing_ms": {"prepare_scene", "voting", "verification", "selection", "icp", "total"},
//  "counts": {"scene_points", "candidates", "refreshes"}}
// Poses are T_camera_model in the input's units. Thread-safe.
#include <nlohmann/json.hpp>

#include "binpick/estimation/detector.hpp"

namespace binpick::estimation {

nlohmann::json toJson(const DetectionResult& result);

// A rigid pose as {"translation": [x, y, z], "quaternion_wxyz": [w, x, y, z]} (saved cycles, the
// bin-emptying report).
nlohmann::json poseJson(const Eigen::Isometry3d& pose);

}  // namespace binpick::estimation
