// binpick reconstruct --capture DIR: `binpick reconstruct --help`.
// Decodes a capture's pattern images and triangulates them into an organized point cloud in the
// camera frame (metres, with the white image as intensity). --status writes why each pixel has
// no point, as an 8-bit image of PixelStatus values (docs/reconstruction.md). The summary (points,
// pixels without a point per reason, times, warnings) goes to stdout.
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "arguments.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/geometry_io.hpp"
#include "capture_reconstruction.hpp"
#include "commands.hpp"

namespace binpick::cli {
namespace {

int run(const Arguments& args) {
  CaptureInput input;
  input.capture_dir = args.required("--capture");
  input.calibration = args.value("--calib");
  input.config = args.value("--config");
  input.threads = args.integer("--threads");
  const std::string out = args.value("--out").value_or("cloud.ply");
  const auto status_path = args.value("--status");
  const reconstruction::Reconstruction result = reconstructCaptureDirectory(input, std::cout);
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
