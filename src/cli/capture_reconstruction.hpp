#pragma once
// Shared by `reconstruct` and `detect --capture`: a capture directory and its calibration in, the
// reconstructed cloud out, with a one-line summary on stderr.
#include <optional>
#include <string>

#include "binpick/reconstruction/reconstruction.hpp"

namespace binpick::cli {

struct CaptureInput {
  std::string capture_dir;
  std::optional<std::string> calibration;  // default: CAPTURE_DIR/calib.yaml
  std::optional<std::string> config;       // settings file with a `reconstruction:` section
  std::optional<int> threads;
};

reconstruction::Reconstruction reconstructCaptureDirectory(const CaptureInput& input);

}  // namespace binpick::cli
