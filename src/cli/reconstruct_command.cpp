// binpick reconstruct --capture DIR: `binpick reconstruct --help`.
// Decodes a capture's pattern images and triangulates them into an organized point cloud in the
// camera frame (metres, with the white image as intensity). --status writes why each pixel has
// no point, as an 8-bit image of PixelStatus values (docs/reconstruction.md). The summary (points,
// pixels without a point per reason, times, warnings) goes to stdout, followed by the calibration
// check: how far the decoded rays miss each other under the calibration (triangulation.hpp,
// CalibrationFit).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <vector>

#include "arguments.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/capture.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/io/image_file.hpp"
#include "binpick/io/rig_calibration.hpp"
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

// "calibration check: decoded rays miss each other by 2.1 mm (median), 2.3 projector px; the
// calibration's residual reaches 15 px, pixels lie 0.41 px (median) from it; 4% beyond the 1.5 px
// epipolar limit", and a warning when the calibration is worth redoing or does not fit at all.
void printCalibrationFit(const reconstruction::CalibrationFit& fit, std::ostream& out) {
  if (!fit.measured()) {
    out << "calibration check: no pixel decoded both a column and a row\n";
    return;
  }
  out << "calibration check: decoded rays miss each other by " << measure(fit.median_gap_mm) << " mm (median), "
      << measure(fit.median_epipolar_px) << " projector px; ";
  const bool followed = !std::isnan(fit.largest_residual_px);
  if (followed) {
    out << "the calibration's residual reaches " << measure(fit.largest_residual_px) << " px, pixels lie "
        << measure(fit.median_off_residual_px) << " px (median) from it; ";
  }
  out << percent(fit.beyond_limit_share) << " beyond the " << measure(fit.epipolar_limit_px) << " px epipolar limit\n";
  // Ten times the limit is no calibration error a recalibration leaves behind: the rays belong to
  // another rig, or the codes to another scale.
  if (fit.median_epipolar_px > 10.0 * fit.epipolar_limit_px &&
      (!followed || fit.largest_residual_px > fit.residual_limit_px)) {
    out << "warning: the calibration does not fit this capture: the decoded rays miss each other (another rig's "
           "calibration, or patterns coded at a fraction of the projector's resolution: a code step?)\n";
  } else if (fit.beyond_limit_share > 0.5) {
    out << "warning: most decoded pixels lie beyond the epipolar limit: recalibrate, or loosen "
           "reconstruction.triangulation.max_epipolar_error\n";
  } else if (followed && fit.largest_residual_px > fit.epipolar_limit_px) {
    out << "note: the calibration is up to " << measure(fit.largest_residual_px)
        << " px off this capture's epipolar geometry (pixels are judged from that residual, "
           "reconstruction.triangulation.max_calibration_residual); depth is only as good as the calibration: "
           "recalibrate with board poses spread over the whole view and depth range\n";
  }
}

// Per stage, why pixels have no point and which settings govern it, largest first: where a real
// rig's capture loses its pixels.
void printRejections(const reconstruction::Reconstruction& result, std::ostream& out) {
  std::vector<std::size_t> statuses;
  for (std::size_t status = 1; status < result.counts.size(); ++status) {
    if (result.counts[status] > 0) statuses.push_back(status);
  }
  std::stable_sort(statuses.begin(), statuses.end(),
                   [&](std::size_t a, std::size_t b) { return result.counts[a] > result.counts[b]; });
  const double pixels = static_cast<double>(result.cloud.size());
  for (const std::size_t status : statuses) {
    const auto which = static_cast<reconstruction::PixelStatus>(status);
    const reconstruction::StatusOrigin origin = reconstruction::statusOrigin(which);
    out << "  " << origin.stage << ": " << reconstruction::statusName(which) << " " << result.counts[status] << " ("
        << percent(static_cast<double>(result.counts[status]) / pixels) << "): " << origin.settings << "\n";
  }
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
  if (result.points_along_stripes > 0) {
    std::cout << "of the points, " << result.points_along_stripes
              << " on dark surfaces read along their stripes: coarser, within half their run of codes "
                 "(decode.stripe_reach, decode.max_code_run_along_stripe)\n";
  }
  if (result.validPoints() < result.cloud.size()) {
    std::cout << "pixels without a point, by stage, with the settings that govern them:\n";
    printRejections(result, std::cout);
  }
  if (io::readCaptureMetadata(input.capture_dir).pattern_set.row_codes) {
    printCalibrationFit(result.calibration_fit, std::cout);
  } else {
    // A column alone always meets the camera ray.
    std::cout << "calibration check: none (the capture has no row codes to check the calibration against)\n";
  }
  io::writePointCloud(out, result.cloud);
  if (status_path) io::writeImageFile(*status_path, result.status);
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
