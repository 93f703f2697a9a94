// Mapping a capture's images onto its pattern set, with the checks that make the mapping safe.
#include "capture_layout.hpp"

#include <string>

#include "binpick/core/error.hpp"
#include "binpick/reconstruction/pattern_set.hpp"

namespace binpick::reconstruction::detail {
namespace {

std::string describe(const io::PatternSetSpec& spec) {
  std::string text = std::to_string(spec.projector_width) + "x" + std::to_string(spec.projector_height) + " projector";
  if (spec.column_codes) text += ", column codes";
  if (spec.row_codes) text += ", row codes";
  return text + ", " + std::to_string(spec.phase_steps) + " phase steps";
}

void checkNames(const io::CaptureMetadata& metadata, const std::vector<Pattern>& sequence) {
  const std::string set = "the pattern set (" + describe(metadata.pattern_set) + ")";
  if (metadata.patterns.size() != sequence.size()) {
    throw core::Error("capture: " + std::to_string(metadata.patterns.size()) + " patterns listed but " + set + " has " +
                      std::to_string(sequence.size()));
  }
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    if (metadata.patterns[i] == sequence[i].name()) continue;
    throw core::Error("capture: image " + std::to_string(i) + " is '" + metadata.patterns[i] + "' but " + set +
                      " expects '" + sequence[i].name() + "' there");
  }
}

void addPattern(CaptureLayout& layout, const Pattern& pattern, const io::PatternSetSpec& spec, int image) {
  if (pattern.kind == PatternKind::White) layout.white = image;
  if (pattern.kind == PatternKind::Black) layout.black = image;
  if (pattern.axis == PatternAxis::None) return;
  AxisLayout& axis = pattern.axis == PatternAxis::Columns ? layout.columns : layout.rows;
  axis.present = true;
  axis.size = pattern.axis == PatternAxis::Columns ? spec.projector_width : spec.projector_height;
  axis.phase_period = spec.phase_period;
  axis.gray_unit = spec.grayUnitCodes();
  if (pattern.kind == PatternKind::GrayBit) axis.bit_images.push_back(image);
  if (pattern.kind == PatternKind::GrayBitInverse) axis.inverse_images.push_back(image);
  if (pattern.kind == PatternKind::PhaseStep) axis.phase_images.push_back(image);
}

}  // namespace

CaptureLayout captureLayout(const io::Capture& capture) {
  const io::CaptureMetadata& metadata = capture.metadata;
  const std::vector<Pattern> sequence = patternSequence(metadata.pattern_set);  // validates the spec
  checkNames(metadata, sequence);  // the images themselves were checked by completeCapture
  if (!metadata.pattern_set.column_codes) {
    throw core::Error("capture: the pattern set has no column codes; triangulation needs the projector column");
  }
  CaptureLayout layout;
  layout.width = metadata.image_width;
  layout.height = metadata.image_height;
  layout.bit_depth = metadata.bit_depth;
  layout.pattern_set = metadata.pattern_set;
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    addPattern(layout, sequence[i], metadata.pattern_set, static_cast<int>(i));
  }
  return layout;
}

}  // namespace binpick::reconstruction::detail
