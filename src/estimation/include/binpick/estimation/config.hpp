#pragma once
// Estimation settings from a YAML file (config/detection.yaml lists every key with its default
// and unit). Every key is optional; an unknown key, a wrong type or an invalid value
// throws core::Error naming the file and the key. Thread-safe (no shared state).
#include <string>
#include <vector>

#include "binpick/estimation/detector.hpp"
#include "binpick/estimation/model.hpp"

namespace binpick::estimation {

struct EstimationConfig {
  ModelParams model;
  DetectorParams detector;
  std::vector<std::string> warnings;  // "ORIGIN: key: ..." for a key read in an older form, naming the new one
};

EstimationConfig loadEstimationConfig(const std::string& path);
// The same from YAML text; `origin` names it in error messages.
EstimationConfig parseEstimationConfig(const std::string& yaml_text, const std::string& origin);

}  // namespace binpick::estimation
