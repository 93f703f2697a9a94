// A calibration view from a capture: decode it, find the board, then the projector's corners.
#include "binpick/calibration/rig_views.hpp"

#include <algorithm>
#include <functional>

#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"

namespace binpick::calibration {
namespace {

void nested(const char* member, const std::function<void()>& validate) {
  try {
    validate();
  } catch (const core::Error& e) {
    throw core::Error(std::string("RigViewParams.") + member + ": " + e.what());
  }
}

// Checked before decoding: without both codes there are no projector corners at all, and the
// user must capture again with another pattern set, not change a setting.
void requireBothAxes(const io::Capture& capture, const std::string& name) {
  const io::PatternSetSpec& patterns = capture.metadata.pattern_set;
  if (!patterns.row_codes || !patterns.column_codes) {
    throw core::Error(name + ": the capture has no " + (patterns.row_codes ? "column" : "row") +
                      " codes; calibrating the projector needs its columns and rows: capture the"
                      " view again with the full pattern set (row_codes and column_codes)");
  }
}

const cv::Mat& whiteImage(const io::Capture& capture, const std::string& name) {
  const std::vector<std::string>& patterns = capture.metadata.patterns;
  const auto white = std::find(patterns.begin(), patterns.end(), "white");
  const auto index = static_cast<std::size_t>(white - patterns.begin());
  if (white == patterns.end() || index >= capture.images.size()) {
    throw core::Error(name + ": the capture has no white image to find the board in");
  }
  return capture.images[index];
}

}  // namespace

void RigViewParams::validate() const {
  nested("detection", [&] { detection.validate(); });
  nested("decode", [&] { decode.validate(); });
  nested("projector", [&] { projector.validate(); });
}

RigView measureRigView(const io::Capture& capture, const std::string& name, const BoardLayout& layout,
                       const RigViewParams& params) {
  params.validate();
  requireBothAxes(capture, name);
  RigView view;
  view.name = name;
  view.camera_width = capture.metadata.image_width;
  view.camera_height = capture.metadata.image_height;
  view.projector_width = capture.metadata.pattern_set.projector_width;
  view.projector_height = capture.metadata.pattern_set.projector_height;

  core::Stopwatch stage;
  view.board = detectBoard(whiteImage(capture, name), layout, params.detection);
  view.timings.detect = stage.lapMs();
  if (!view.board.found()) return view;  // no corners: decoding would be wasted

  reconstruction::DecodedCapture decoded;
  try {
    decoded = reconstruction::decodeCapture(capture, params.decode);
  } catch (const core::Error& e) {
    throw core::Error(name + ": " + e.what());
  }
  view.timings.decode = stage.lapMs();

  view.projector = findProjectorCorners(decoded, view.board, params.projector);
  view.timings.projector_corners = stage.lapMs();
  return view;
}

RigView readRigView(const std::string& directory, const BoardLayout& layout, const RigViewParams& params) {
  // readCapture names the directory (or its file) in its errors.
  return measureRigView(io::readCapture(directory), directory, layout, params);
}

}  // namespace binpick::calibration
