// binpick calibrate rig (--sequence DIR | --views DIR... | (--camera ID | --fake-camera DIR)
//                        --record DIR ...) --out calib.yaml: `binpick calibrate rig --help`.
// Calibrates the camera and the projector from captures of a board at different poses, each with
// the full pattern set (docs/calibration.md), prints a table of the views and writes calib.yaml
// with the calibration's quality and date. --sequence takes every subdirectory holding a
// capture.json, in name order; the live path records each view to RECORD/view_NNN before use.
#include <iostream>

#include "arguments.hpp"
#include "binpick/calibration/rig_calibrator.hpp"
#include "binpick/core/error.hpp"
#include "board_options.hpp"
#include "calibrate_rig_report.hpp"
#include "calibrate_rig_views.hpp"
#include "commands.hpp"
#include "live_capture.hpp"

namespace binpick::cli {
namespace {

calibration::RigCalibrationParams calibrationParams(const Arguments& args) {
  calibration::RigCalibrationParams params;
  params.min_views = args.integer("--min-views").value_or(params.min_views);
  params.drop_outliers = args.flag("--drop-outliers");
  params.refine_intrinsics_in_stereo = !args.flag("--hold-intrinsics");
  params.outlier_factor = args.number("--outlier-factor").value_or(params.outlier_factor);
  params.outlier_floor_px = args.number("--outlier-floor-px").value_or(params.outlier_floor_px);
  if (const auto terms = args.value("--camera-distortion")) {
    params.camera_distortion = calibration::parseDistortionTerms(*terms, "--camera-distortion");
  }
  if (const auto terms = args.value("--projector-distortion")) {
    params.projector_distortion = calibration::parseDistortionTerms(*terms, "--projector-distortion");
  }
  params.validate();
  return params;
}

calibration::RigViewParams viewParams(const Arguments& args) {
  calibration::RigViewParams params;
  params.projector.half_window = args.integer("--corner-window").value_or(params.projector.half_window);
  params.validate();
  return params;
}

std::vector<calibration::RigView> gatherViews(const Arguments& args, const calibration::BoardLayout& layout,
                                              const calibration::RigViewParams& params, int min_views) {
  if (const auto views = args.values("--views"); !views.empty()) return readViews(views, layout, params);
  if (const auto sequence = args.value("--sequence")) {
    return readViews(sequenceCaptures(*sequence), layout, params);
  }
  const int count = args.integer("--count").value_or(std::max(min_views, 12));
  if (count < 1) throw core::Error("--count must be at least 1 (got " + std::to_string(count) + ")");
  return captureLiveViews(args, count, args.required("--record"), layout, params, std::cin);
}

// A chessboard of another size seen in a view (the board given in the other convention): what
// the user probably meant, for the error or a warning; empty when no view saw one.
std::string sizeHint(const Arguments& args, const std::vector<calibration::RigView>& views) {
  for (const calibration::RigView& view : views) {
    const std::string hint = boardSizeHint(args, view.board);
    if (!hint.empty()) return view.name + ": " + hint;
  }
  return "";
}

int run(const Arguments& args) {
  if (!args.value("--sequence") && !args.value("--views") && !args.value("--camera") && !args.value("--fake-camera")) {
    throw missingOption("--sequence, --views, --camera or --fake-camera");
  }
  const std::string out = args.required("--out");
  const calibration::BoardLayout layout = boardLayoutFromArguments(args);
  const calibration::RigCalibrationParams params = calibrationParams(args);
  const calibration::RigViewParams view_params = viewParams(args);

  const std::vector<calibration::RigView> views = gatherViews(args, layout, view_params, params.min_views);
  const std::string hint = sizeHint(args, views);
  calibration::RigCalibrationResult result;
  try {
    result = calibration::calibrateRig(views, layout, params);
  } catch (const core::Error& e) {
    if (hint.empty()) throw;
    throw core::Error(std::string(e.what()) + "; " + hint);
  }
  for (const std::string& warning : result.warnings) std::cerr << "warning: " << warning << "\n";
  if (!hint.empty()) std::cerr << "warning: " << hint << "\n";
  printRigReport(std::cout, result);
  io::writeRigCalibration(out, result.rig, result.quality);
  std::cout << "wrote " << out << "\n";
  return 0;
}

// CLI11 validators: an empty string accepts the value, anything else is the usage error's text.
// A calibration needs at least three board poses (cv::calibrateCamera's minimum for a lens).
std::string checkMinViews(const std::string& text) {
  try {
    if (parseInteger("--min-views", text) >= 3) return "";
  } catch (const core::Error&) {
    return "";  // not a number: the integer check says so
  }
  return "must be at least 3, not " + text + " (a lens needs three board poses)";
}

std::string checkDistortionTerms(const std::string& text) {
  try {
    calibration::parseDistortionTerms(text, "the terms");
    return "";
  } catch (const core::Error& e) {
    return e.what();
  }
}

}  // namespace

void addCalibrateRigCommand(CLI::App& calibrate, CommandTable& table) {
  CLI::App& command = table.add(calibrate, "rig", "Calibrate the camera and the projector from views of a board", run);
  addText(command, "--out", "FILE", "Write the calibration here (calib.yaml)")->required();
  CLI::Option* sequence = addText(command, "--sequence", "DIR", "Use every capture directory in DIR, in name order");
  CLI::Option* views = addText(command, "--views", "DIR", "Use these capture directories");
  views->expected(1, -1)->allow_extra_args();
  sequence->excludes(views);
  std::vector<CLI::Option*> live =
      addLiveCaptureOptions(command, "Take the views from a fake GigE camera serving DIR's captures in order");
  live.push_back(addText(command, "--record", "DIR", "Live: record each view to DIR/view_NNN (required)"));
  live.push_back(addInteger(command, "--count", "K", "Live: views to take (default: --min-views, at least 12)"));
  refuseTogether(live, {sequence, views});
  addBoardOptions(command);
  addInteger(command, "--min-views", "N", "Usable views needed, at least 3 (default 3; fewer than 8: a warning)")
      ->check(CLI::Validator(checkMinViews, ""));
  addFlag(command, "--drop-outliers", "Leave out views that fit much worse than the others");
  addFlag(command, "--hold-intrinsics", "Keep each device's own-solve intrinsics in the stereo step (not refined)");
  addNumber(command, "--outlier-factor", "F", "Outlier: RMS above F times the median view's (default 3)");
  addNumber(command, "--outlier-floor-px", "PX", "An RMS below PX is never an outlier (default 0.15)");
  addText(command, "--camera-distortion", "TERMS", "Camera distortion terms fitted (default k1,k2,p1,p2; add k3)")
      ->check(CLI::Validator(checkDistortionTerms, ""));
  addText(command, "--projector-distortion", "TERMS", "Projector distortion terms fitted (default k1,k2,p1,p2; add k3)")
      ->check(CLI::Validator(checkDistortionTerms, ""));
  addInteger(command, "--corner-window", "PX", "Half window for the projector's corners (default 40)");
}

}  // namespace binpick::cli
