// binpick reconstruct --capture DIR [--calib FILE] [--config FILE] [--threads N]
//                     [--out cloud.ply] [--status status.png]
// Decodes a capture's pattern images and triangulates them into an organized point cloud in the
// camera frame (metres, with the white image as intensity). --status writes why each pixel has
// no point, as an 8-bit image of PixelStatus values (docs/reconstruction.md).
#include <opencv2/imgcodecs.hpp>

#include "arguments.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/geometry_io.hpp"
#include "capture_reconstruction.hpp"
#include "commands.hpp"

namespace binpick::cli {

int runReconstruct(const std::vector<std::string>& raw) {
  const Arguments args(raw, {"--capture", "--calib", "--config", "--threads", "--out", "--status"}, {});
  CaptureInput input;
  input.capture_dir = args.required("--capture");
  input.calibration = args.value("--calib");
  input.config = args.value("--config");
  input.threads = args.integer("--threads");
  const std::string out = args.value("--out").value_or("cloud.ply");
  const auto status_path = args.value("--status");
  const reconstruction::Reconstruction result = reconstructCaptureDirectory(input);
  io::writePointCloud(out, result.cloud);
  if (status_path && !cv::imwrite(*status_path, result.status)) {
    throw core::Error(*status_path + ": cannot write the status image");
  }
  return 0;
}

}  // namespace binpick::cli
