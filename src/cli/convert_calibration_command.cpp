// binpick convert-calibration --opencv-calib FILE --out calib.yaml: `binpick convert-calibration --help`.
// Reads a calibration another tool wrote with cv::FileStorage (XML, YAML or JSON: camera and
// projector matrices and distortion, R and T from the camera into the projector, or each
// device's board poses; io/opencv_calibration.hpp) and writes it as binpick's calib.yaml, in
// metres. One line on stdout says what was read, so that a wrong unit or a swapped size shows.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "arguments.hpp"
#include "binpick/io/opencv_calibration.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "commands.hpp"
#include "opencv_calibration_options.hpp"

namespace binpick::cli {
namespace {

std::string lensSummary(const char* device, const io::LensIntrinsics& lens) {
  char text[120];
  std::snprintf(text, sizeof text, "%s %dx%d (fx %.1f, fy %.1f, centre %.1f, %.1f)", device, lens.width, lens.height,
                lens.fx, lens.fy, lens.cx, lens.cy);
  return text;
}

// T is where the camera's centre sits in the projector's frame.
std::string poseSummary(const Eigen::Isometry3d& T_projector_camera) {
  const Eigen::Vector3d t = 1000.0 * T_projector_camera.translation();
  const double angle = Eigen::AngleAxisd(T_projector_camera.linear()).angle() * 180.0 / M_PI;
  char text[160];
  std::snprintf(text, sizeof text,
                "baseline %.1f mm (camera at %.1f, %.1f, %.1f mm in the projector's frame), turned %.1f degrees",
                t.norm(), t.x(), t.y(), t.z(), angle);
  return text;
}

int run(const Arguments& args) {
  const std::string input = args.required("--opencv-calib");
  const std::string out = args.required("--out");
  const io::RigCalibration rig = io::readOpenCvCalibration(input, openCvCalibrationOptionsFromArguments(args));
  io::writeRigCalibration(out, rig);
  std::cout << out << ": " << lensSummary("camera", rig.camera) << ", " << lensSummary("projector", rig.projector)
            << ", " << poseSummary(rig.T_projector_camera) << "\n";
  return 0;
}

}  // namespace

void addConvertCalibrationCommand(CLI::App& program, CommandTable& table) {
  CLI::App& command =
      table.add(program, "convert-calibration", "Write another tool's OpenCV calibration file as calib.yaml", run);
  addText(command, "--opencv-calib", "FILE",
          "cv::FileStorage XML/YAML/JSON with camera and projector intrinsics and R, T camera to projector")
      ->required();
  addText(command, "--projector", "WxH", "Projector resolution, when the file has none (e.g. 1920x1080)");
  addOpenCvCalibrationOptions(command);
  addText(command, "--out", "FILE", "Write calib.yaml here")->required();
}

}  // namespace binpick::cli
