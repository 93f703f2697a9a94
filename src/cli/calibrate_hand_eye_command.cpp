// binpick calibrate hand-eye (--views DIR | --listen ...) --calib calib.yaml --setup SETUP
//                            --out hand_eye.yaml: `binpick calibrate hand-eye --help`.
// Robot poses from DIR/poses.txt, board poses from DIR/VIEW.png (docs/hand-eye.md); prints the
// views with their residuals and writes the result in binpickd's settings format. Bad input
// (a view without image, too few usable views, inverted poses, a poor fit) exits 1 naming it.
#include <iostream>

#include "arguments.hpp"
#include "binpick/calibration/hand_eye_file.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "board_options.hpp"
#include "calibrate_hand_eye.hpp"
#include "commands.hpp"
#include "hand_eye_report.hpp"

namespace binpick::cli {
namespace {

calibration::HandEyeParams solverParams(const Arguments& args) {
  calibration::HandEyeParams params;
  params.setup = calibration::handEyeSetupFromName(args.required("--setup"));
  if (const auto method = args.value("--method")) {
    params.method = calibration::handEyeMethodFromName(*method);
  }
  params.min_views = args.integer("--min-views").value_or(params.min_views);
  params.refine = args.flag("--refine");
  params.drop_outliers = args.flag("--drop-outliers");
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

int run(const Arguments& args) {
  if (args.flag("--listen")) return runGuidedSession(args);
  const auto views = args.value("--views");
  if (!views) throw missingOption("--views or --listen");
  return calibrateFromViews(args, *views);
}

}  // namespace

int calibrateFromViews(const Arguments& args, const std::string& views_directory) {
  const calibration::HandEyeParams params = solverParams(args);
  const calibration::BoardLayout layout = boardLayoutFromArguments(args);
  const std::string out = args.required("--out");
  const io::RigCalibration rig = io::readRigCalibration(args.required("--calib"));
  const std::vector<calibration::MeasuredView> views = measureViews(views_directory, layout, rig.camera);

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

void addCalibrateHandEyeCommand(CLI::App& calibrate, CommandTable& table) {
  CLI::App& command = table.add(calibrate, "hand-eye",
                                "Find the camera relative to the robot from robot poses and views of a board", run);
  addText(command, "--calib", "FILE", "The rig calibration (calib.yaml): the camera's lens")->required();
  addText(command, "--setup", "SETUP", "eye-to-hand (camera fixed) or eye-in-hand (on the flange)")->required();
  addText(command, "--out", "FILE", "Write the result here (hand_eye.yaml, for binpickd)")->required();
  CLI::Option* views = addText(command, "--views", "DIR", "The views: DIR/poses.txt and an image per view");
  CLI::Option* listen = addFlag(command, "--listen", "Guided: the robot sends its poses (POSE), views are taken");
  views->excludes(listen);
  addText(command, "--method", "NAME",
          "auto (default: the best fitting of the others, refined), shah, li, tsai, park, horaud, andreff or "
          "daniilidis");
  addInteger(command, "--min-views", "N", "Usable views needed (default 6)");
  addFlag(command, "--refine", "Refine both transforms after the closed-form solution (auto always does)");
  addFlag(command, "--drop-outliers", "Leave out views that disagree with the others, and name them");
  addBoardOptions(command);
  addGuidedSessionOptions(command, listen);
}

}  // namespace binpick::cli
