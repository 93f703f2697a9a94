#pragma once
// Shared by `reconstruct` and `detect --capture`: a capture directory and its calibration in, the
// reconstructed cloud out, with a one-line summary (and a line per warning) on `summary`.
#include <iostream>
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

// Errors about the capture name its directory: "capture DIR: ...". `detect` keeps the summary on
// stderr (its stdout may carry the result); `reconstruct` prints it on stdout.
reconstruction::Reconstruction reconstructCaptureDirectory(const CaptureInput& input,
                                                           std::ostream& summary = std::cerr);

}  // namespace binpick::cli
