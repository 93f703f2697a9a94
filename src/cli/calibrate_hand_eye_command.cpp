// binpick calibrate hand-eye --views DIR --calib calib.yaml --setup eye-to-hand|eye-in-hand
//                            [board options] [--method NAME] [--min-views N] [--refine]
//                            --out hand_eye.yaml
// Robot poses from DIR/poses.txt, board poses from DIR/VIEW.png (docs/hand-eye.md); prints the
// views with their residuals and writes the result in binpickd's settings format. Bad input
// (a view without image, too few usable views, inverted poses, a poor fit) exits 1 naming it.
#include <iostream>

#include "arguments.hpp"
#include "binpick/calibration/hand_eye_file.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "board_options.hpp"
#include "commands.hpp"
#include "hand_eye_report.hpp"

namespace binpick::cli {
namespace {

Arguments parseArguments(const std::vector<std::string>& raw) {
  std::set<std::string> valued = {"--views", "--calib", "--setup", "--method", "--min-views", "--out"};
  valued.insert(boardOptionNames().begin(), boardOptionNames().end());
  return Arguments(raw, valued, {"--refine"});
}

calibration::HandEyeParams solverParams(const Arguments& args) {
  calibration::HandEyeParams params;
  params.setup = calibration::handEyeSetupFromName(args.required("--setup"));
  if (const auto method = args.value("--method")) {
    params.method = calibration::handEyeMethodFromName(*method);
  }
  params.min_views = args.integer("--min-views").value_or(params.min_views);
  params.refine = args.flag("--refine");
  params.validate();
  return params;
}

std::vector<calibration::MeasuredView> measureViews(const std::string& directory,
                                                    const calibration::BoardLayout& layout,
                                                    const io::LensIntrinsics& camera) {
  std::vector<calibration::MeasuredView> views;
  for (const calibration::HandEyeViewFile& file : calibration::listHandEyeViews(directory)) {
    views.push_back(calibration::measureView(file, layout, camera));
  }
  return views;
}

}  // namespace

int runCalibrateHandEye(const std::vector<std::string>& raw) {
  const Arguments args = parseArguments(raw);
  const calibration::HandEyeParams params = solverParams(args);
  const calibration::BoardLayout layout = boardLayoutFromArguments(args);
  const std::string out = args.required("--out");
  const io::RigCalibration rig = io::readRigCalibration(args.required("--calib"));
  const std::vector<calibration::MeasuredView> views = measureViews(args.required("--views"), layout, rig.camera);

  calibration::HandEyeResult result;
  try {
    result = calibration::solveMeasuredViews(views, params);
  } catch (const core::Error&) {
    // The table shows which views were usable and why the others were not.
    printViewTable(std::cout, views, nullptr);
    printHandEyeWarnings(std::cerr, views, nullptr);
    throw;
  }
  printViewTable(std::cout, views, &result);
  printHandEyeResult(std::cout, result);
  printHandEyeWarnings(std::cerr, views, &result);
  if (!result.ok()) throw core::Error("hand-eye calibration failed, nothing written: " + result.failure);
  calibration::writeHandEyeFile(out, calibration::handEyeFileOf(result));
  std::cout << "wrote " << calibration::cameraTransformName(result.setup) << " to " << out << "\n";
  return 0;
}

}  // namespace binpick::cli
