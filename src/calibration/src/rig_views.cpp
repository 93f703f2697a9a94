// A calibration view from a capture: decode it, find the board, then the projector's corners.
#include "binpick/calibration/rig_views.hpp"

#include <algorithm>
#include <chrono>
#include <functional>

#include "binpick/io/error.hpp"

namespace binpick::calibration {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void nested(const char* member, const std::function<void()>& validate) {
  try {
    validate();
  } catch (const Error& e) {
    throw Error(std::string("RigViewParams.") + member + ": " + e.what());
  }
}

// Checked before decoding: without both codes there are no projector corners at all, and the
// user must capture again with another pattern set, not change a setting.
void requireBothAxes(const Capture& capture, const std::string& name) {
  const PatternSetSpec& patterns = capture.metadata.pattern_set;
  if (!patterns.row_codes || !patterns.column_codes) {
    throw Error(name + ": the capture has no " + (patterns.row_codes ? "column" : "row") +
                " codes; calibrating the projector needs its columns and rows: capture the"
                " view again with the full pattern set (row_codes and column_codes)");
  }
}

const cv::Mat& whiteImage(const Capture& capture, const std::string& name) {
  const std::vector<std::string>& patterns = capture.metadata.patterns;
  const auto white = std::find(patterns.begin(), patterns.end(), "white");
  const auto index = static_cast<std::size_t>(white - patterns.begin());
  if (white == patterns.end() || index >= capture.images.size()) {
    throw Error(name + ": the capture has no white image to find the board in");
  }
  return capture.images[index];
}

}  // namespace

void RigViewParams::validate() const {
  nested("detection", [&] { detection.validate(); });
  nested("decode", [&] { decode.validate(); });
  nested("projector", [&] { projector.validate(); });
}

RigView measureRigView(const Capture& capture, const std::string& name, const BoardLayout& layout,
                       const RigViewParams& params) {
  params.validate();
  requireBothAxes(capture, name);
  RigView view;
  view.name = name;
  view.camera_width = capture.metadata.image_width;
  view.camera_height = capture.metadata.image_height;
  view.projector_width = capture.metadata.pattern_set.projector_width;
  view.projector_height = capture.metadata.pattern_set.projector_height;

  Clock::time_point start = Clock::now();
  view.board = detectBoard(whiteImage(capture, name), layout, params.detection);
  view.timings.detect = msSince(start);
  if (!view.board.found()) return view;  // no corners: decoding would be wasted

  start = Clock::now();
  reconstruction::DecodedCapture decoded;
  try {
    decoded = reconstruction::decodeCapture(capture, params.decode);
  } catch (const Error& e) {
    throw Error(name + ": " + e.what());
  }
  view.timings.decode = msSince(start);

  start = Clock::now();
  view.projector = findProjectorCorners(decoded, view.board, params.projector);
  view.timings.projector_corners = msSince(start);
  return view;
}

RigView readRigView(const std::string& directory, const BoardLayout& layout,
                    const RigViewParams& params) {
  // readCapture names the directory (or its file) in its errors.
  return measureRigView(readCapture(directory), directory, layout, params);
}

}  // namespace binpick::calibration
