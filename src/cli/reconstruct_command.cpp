// binpick reconstruct --capture DIR: `binpick reconstruct --help`.
// Decodes a capture's pattern images and triangulates them into an organized point cloud in the
// camera frame (metres, with the white image as intensity). --status writes why each pixel has
// no point, as an 8-bit image of PixelStatus values (docs/reconstruction.md). The summary (points,
// pixels without a point per reason, times, warnings) goes to stdout, followed by the calibration
// check: how far the decoded rays miss each other under the calibration (calibration_fit.hpp).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "arguments.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/capture.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "binpick/reconstruction/calibration_fit.hpp"
#include "binpick/reconstruction/reconstruction_config.hpp"
#include "capture_reconstruction.hpp"
#include "commands.hpp"

namespace binpick::cli {
namespace {

// Two decimals near zero (a fitting calibration), fewer for the large gaps of one that does not.
std::string measure(double value) {
  char text[32];
  std::snprintf(text, sizeof text, value < 1.0 ? "%.2f" : value < 100.0 ? "%.1f" : "%.0f", value);
  return text;
}

std::string percent(double share) {
  char text[32];
  std::snprintf(text, sizeof text, share < 0.1 ? "%.1f%%" : "%.0f%%", 100.0 * share);
  return text;
}

// "calibration check: decoded rays miss each other by 2.1 mm (median), 1.3 projector px; 4% of
// pixels beyond the 1.5 px epipolar limit", and a warning when most pixels are beyond it.
void printCalibrationFit(const reconstruction::CalibrationFit& fit, std::ostream& out) {
  if (!fit.measured()) {
    out << "calibration check: no pixel decoded both a column and a row\n";
    return;
  }
  out << "calibration check: decoded rays miss each other by " << measure(fit.median_gap_mm) << " mm (median), "
      << measure(fit.median_epipolar_px) << " projector px; " << percent(fit.beyond_limit_share)
      << " of pixels beyond the " << measure(fit.epipolar_limit_px) << " px epipolar limit\n";
  // Ten times the limit is no calibration error a recalibration leaves behind: the rays belong to
  // another rig, or the codes to another scale.
  if (fit.median_epipolar_px > 10.0 * fit.epipolar_limit_px) {
    out << "warning: the calibration does not fit this capture: the decoded rays miss each other (another rig's "
           "calibration, or patterns coded at a fraction of the projector's resolution: a code step?)\n";
  } else if (fit.median_epipolar_px > fit.epipolar_limit_px) {
    out << "warning: most decoded pixels lie beyond the epipolar limit (their rows disagree with the calibration): "
           "recalibrate, or loosen reconstruction.triangulation.max_epipolar_error\n";
  }
}

// The check decodes the capture once more: the reconstruction keeps no decoded coordinates. A
// capture without rows has nothing to check, as a column alone always meets the camera ray.
void checkCalibration(const CaptureInput& input, std::ostream& out) {
  if (!io::readCaptureMetadata(input.capture_dir).pattern_set.row_codes) {
    out << "calibration check: none (the capture has no row codes to check the calibration against)\n";
    return;
  }
  reconstruction::ReconstructionParams params;
  if (input.config) params = reconstruction::loadReconstructionParams(*input.config);
  if (input.threads) params.setThreads(*input.threads);
  const io::RigCalibration rig = io::readRigCalibration(
      input.calibration.value_or((std::filesystem::path(input.capture_dir) / "calib.yaml").string()));
  const io::Capture capture = io::readCapture(input.capture_dir, input.threads.value_or(0));
  const reconstruction::DecodedCapture decoded = reconstruction::decodeCapture(capture, params.decode);
  printCalibrationFit(reconstruction::measureCalibrationFit(rig, decoded, params.triangulation), out);
}

int run(const Arguments& args) {
  CaptureInput input;
  input.capture_dir = args.required("--capture");
  input.calibration = args.value("--calib");
  input.config = args.value("--config");
  input.threads = args.integer("--threads");
  const std::string out = args.value("--out").value_or("cloud.ply");
  const auto status_path = args.value("--status");
  const reconstruction::Reconstruction result = reconstructCaptureDirectory(input, std::cout);
  checkCalibration(input, std::cout);
  io::writePointCloud(out, result.cloud);
  if (status_path && !cv::imwrite(*status_path, result.status)) {
    throw core::Error(*status_path + ": cannot write the status image");
  }
  return 0;
}

}  // namespace

void addReconstructCommand(CLI::App& program, CommandTable& table) {
  CLI::App& command = table.add(program, "reconstruct", "Decode a capture into an organized point cloud", run);
  addText(command, "--capture", "DIR", "The capture directory (docs/capture-format.md)")->required();
  addText(command, "--calib", "FILE", "The rig calibration (default: the capture's calib.yaml)");
  addText(command, "--config", "FILE", "Settings whose reconstruction: section applies (config/reconstruction.yaml)");
  addInteger(command, "--threads", "N", "Threads (default 0: all cores)");
  addText(command, "--out", "FILE", "Write the cloud here (default cloud.ply)");
  addText(command, "--status", "FILE", "Write why each pixel has no point, as an 8-bit image");
}

}  // namespace binpick::cli
