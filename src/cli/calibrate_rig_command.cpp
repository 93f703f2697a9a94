// binpick calibrate rig (--sequence DIR | --views DIR... | (--camera ID | --fake-camera DIR)
//                        --record DIR [--count K] [live options])
//                       [--board charuco|chessboard] [--squares 9x7] [--square-mm 30]
//                       [--marker-mm 22] [--dictionary DICT_5X5_100] [--min-views 8]
//                       [--drop-outliers] [--outlier-factor 3] [--outlier-floor-px 0.5]
//                       [--corner-window 40] --out calib.yaml
// Calibrates the camera and the projector from captures of a board at different poses, each with
// the full pattern set (docs/calibration.md), prints a table of the views and writes calib.yaml
// with the calibration's quality and date. --sequence takes every subdirectory holding a
// capture.json, in name order; the live path records each view to RECORD/view_NNN before use.
#include <iostream>
#include <set>

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

// --views takes every value up to the next option; the rest goes to Arguments.
struct SplitArguments {
  std::vector<std::string> views;
  bool has_views = false;
  std::vector<std::string> rest;
};

SplitArguments splitViews(const std::vector<std::string>& raw) {
  SplitArguments split;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != "--views") {
      split.rest.push_back(raw[i]);
      continue;
    }
    if (split.has_views) throw core::Error("--views is given twice");
    split.has_views = true;
    while (i + 1 < raw.size() && raw[i + 1].rfind("--", 0) != 0) split.views.push_back(raw[++i]);
    if (split.views.empty()) throw core::Error("--views needs at least one capture directory");
  }
  return split;
}

Arguments parseArguments(const std::vector<std::string>& rest) {
  std::set<std::string> valued = liveCaptureOptionNames();
  const std::set<std::string>& board = boardOptionNames();
  valued.insert(board.begin(), board.end());
  valued.insert({"--sequence", "--record", "--count", "--min-views", "--outlier-factor", "--outlier-floor-px",
                 "--corner-window", "--out"});
  return Arguments(rest, valued, {"--drop-outliers"});
}

calibration::RigCalibrationParams calibrationParams(const Arguments& args) {
  calibration::RigCalibrationParams params;
  params.min_views = args.integer("--min-views").value_or(params.min_views);
  params.drop_outliers = args.flag("--drop-outliers");
  params.outlier_factor = args.number("--outlier-factor").value_or(params.outlier_factor);
  params.outlier_floor_px = args.number("--outlier-floor-px").value_or(params.outlier_floor_px);
  params.validate();
  return params;
}

calibration::RigViewParams viewParams(const Arguments& args) {
  calibration::RigViewParams params;
  params.projector.half_window = args.integer("--corner-window").value_or(params.projector.half_window);
  params.validate();
  return params;
}

// Exactly one source of views.
void requireOneSource(const Arguments& args, bool has_views) {
  const int sources = (args.value("--sequence") ? 1 : 0) + (has_views ? 1 : 0) + (args.value("--camera") ? 1 : 0) +
                      (args.value("--fake-camera") ? 1 : 0);
  if (sources != 1) {
    throw core::Error("give exactly one of --sequence DIR, --views DIR..., --camera ID or --fake-camera DIR");
  }
}

std::vector<calibration::RigView> gatherViews(const Arguments& args, const SplitArguments& split,
                                              const calibration::BoardLayout& layout,
                                              const calibration::RigViewParams& params, int min_views) {
  if (split.has_views) return readViews(split.views, layout, params);
  if (const auto sequence = args.value("--sequence")) {
    return readViews(sequenceCaptures(*sequence), layout, params);
  }
  const int count = args.integer("--count").value_or(std::max(min_views, 12));
  if (count < 1) throw core::Error("--count must be at least 1 (got " + std::to_string(count) + ")");
  return captureLiveViews(args, count, args.required("--record"), layout, params, std::cin);
}

}  // namespace

int runCalibrateRig(const std::vector<std::string>& raw) {
  const SplitArguments split = splitViews(raw);
  const Arguments args = parseArguments(split.rest);
  requireOneSource(args, split.has_views);
  const std::string out = args.required("--out");
  const calibration::BoardLayout layout = boardLayoutFromArguments(args);
  const calibration::RigCalibrationParams params = calibrationParams(args);
  const calibration::RigViewParams view_params = viewParams(args);

  const std::vector<calibration::RigView> views = gatherViews(args, split, layout, view_params, params.min_views);
  const calibration::RigCalibrationResult result = calibration::calibrateRig(views, layout, params);
  for (const std::string& warning : result.warnings) std::cerr << "warning: " << warning << "\n";
  printRigReport(std::cout, result);
  io::writeRigCalibration(out, result.rig, result.quality);
  std::cout << "wrote " << out << "\n";
  return 0;
}

}  // namespace binpick::cli
