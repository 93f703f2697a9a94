// Reading a capture directory and reconstructing it.
#include "capture_reconstruction.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/io/capture.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "binpick/reconstruction/reconstruction_config.hpp"

namespace binpick::cli {
namespace {

void printSummary(const reconstruction::Reconstruction& result, double read_ms, std::ostream& out) {
  char times[160];
  std::snprintf(times, sizeof times, "read %.0f ms, decode %.1f ms, triangulate %.1f ms, filter %.1f ms", read_ms,
                result.timings.decode, result.timings.triangulate, result.timings.filter);
  out << result.validPoints() << " points of " << result.cloud.size() << " pixels (" << times << "); no point:";
  for (std::size_t status = 1; status < result.counts.size(); ++status) {
    if (result.counts[status] == 0) continue;
    out << " " << reconstruction::statusName(static_cast<reconstruction::PixelStatus>(status)) << " "
        << result.counts[status];
  }
  out << "\n";
  for (const std::string& warning : result.warnings) out << "warning: " << warning << "\n";
}

// The library says "capture: ..."; the user gave a directory, so the message names it.
[[noreturn]] void rethrowNamingDirectory(const core::Error& error, const std::string& directory) {
  const std::string message = error.what();
  const std::string prefix = "capture: ";
  if (message.compare(0, prefix.size(), prefix) != 0) throw error;
  throw core::Error("capture " + directory + ": " + message.substr(prefix.size()));
}

}  // namespace

reconstruction::Reconstruction reconstructCaptureDirectory(const CaptureInput& input, std::ostream& summary) {
  const core::Stopwatch reading;
  reconstruction::ReconstructionParams params;
  if (input.config) params = reconstruction::loadReconstructionParams(*input.config);
  if (input.threads) params.setThreads(*input.threads);
  const std::string calibration =
      input.calibration.value_or((std::filesystem::path(input.capture_dir) / "calib.yaml").string());
  const io::RigCalibration rig = io::readRigCalibration(calibration);
  const io::Capture capture = io::readCapture(input.capture_dir, input.threads.value_or(0));
  const double read_ms = reading.elapsedMs();
  const reconstruction::Reconstructor reconstructor(rig, params);
  reconstruction::Reconstruction result;
  try {
    result = reconstructor.reconstruct(capture);
  } catch (const core::Error& error) {
    rethrowNamingDirectory(error, input.capture_dir);
  }
  printSummary(result, read_ms, summary);
  return result;
}

}  // namespace binpick::cli
