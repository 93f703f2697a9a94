// Rig sequences: presets and the YAML description (rig_sequence.hpp).
#include "binpick/reconstruction/rig_sequence.hpp"

#include <algorithm>
#include <set>

#include "binpick/core/error.hpp"
#include "binpick/core/yaml_section.hpp"
#include "binpick/reconstruction/pattern_set.hpp"

namespace binpick::reconstruction {
namespace {

enum class Inverses { AfterEach, AfterAll, None };

struct GrayEntry {
  PatternAxis axis = PatternAxis::Columns;
  Inverses inverses = Inverses::AfterEach;
  bool msb_first = true;
};

std::string name(PatternKind kind, PatternAxis axis, int index) { return Pattern{kind, axis, index}.name(); }

void appendGray(std::vector<std::string>& patterns, const GrayEntry& entry, const io::PatternSetSpec& spec) {
  const int bits = grayCodeBitsOf(entry.axis, spec);
  std::vector<int> order(static_cast<std::size_t>(bits));
  for (int j = 0; j < bits; ++j) order[static_cast<std::size_t>(j)] = entry.msb_first ? j : bits - 1 - j;
  for (const int bit : order) {
    patterns.push_back(name(PatternKind::GrayBit, entry.axis, bit));
    if (entry.inverses == Inverses::AfterEach) patterns.push_back(name(PatternKind::GrayBitInverse, entry.axis, bit));
  }
  if (entry.inverses != Inverses::AfterAll) return;
  for (const int bit : order) patterns.push_back(name(PatternKind::GrayBitInverse, entry.axis, bit));
}

void appendPhase(std::vector<std::string>& patterns, PatternAxis axis, const io::PatternSetSpec& spec) {
  for (int step = 0; step < spec.phase_steps; ++step) patterns.push_back(name(PatternKind::PhaseStep, axis, step));
}

PatternAxis axisFromName(core::YamlSection& entry, const char* key, const std::string& text) {
  if (text == "columns") return PatternAxis::Columns;
  if (text == "rows") return PatternAxis::Rows;
  entry.fail(key, "must be columns or rows (got '" + text + "')");
}

GrayEntry readGrayEntry(core::YamlSection& entry) {
  GrayEntry gray;
  std::string axis, inverses = "after_each", order = "msb_first";
  entry.read("gray", axis);
  entry.read("inverses", inverses);
  entry.read("order", order);
  entry.finish();
  gray.axis = axisFromName(entry, "gray", axis);
  if (inverses == "after_each")
    gray.inverses = Inverses::AfterEach;
  else if (inverses == "after_all")
    gray.inverses = Inverses::AfterAll;
  else if (inverses == "none")
    gray.inverses = Inverses::None;
  else
    entry.fail("inverses", "must be after_each, after_all or none (got '" + inverses + "')");
  if (order != "msb_first" && order != "lsb_first") {
    entry.fail("order", "must be msb_first or lsb_first (got '" + order + "')");
  }
  gray.msb_first = order == "msb_first";
  return gray;
}

// One entry of `images`: a pattern name, or a {gray: AXIS, ...} / {phase: AXIS} group.
void appendEntry(std::vector<std::string>& patterns, const YAML::Node& node, std::size_t index,
                 const io::PatternSetSpec& spec, const std::string& origin) {
  const std::string path = "images[" + std::to_string(index) + "]";
  if (node.IsScalar()) {
    const std::string text = node.as<std::string>();
    if (!patternFromName(text)) {
      throw core::Error(origin + ": " + path + ": '" + text +
                        "' is no pattern name (white, black, gray_col_03, gray_col_03_inv, phase_row_1, ...)");
    }
    patterns.push_back(text);
    return;
  }
  core::YamlSection entry(node, path, origin);
  if (entry.has("gray")) return appendGray(patterns, readGrayEntry(entry), spec);
  if (!entry.has("phase")) entry.fail("gray", "or phase, or a pattern name, is needed");
  std::string axis;
  entry.read("phase", axis);
  entry.finish();
  if (spec.phase_steps == 0) entry.fail("phase", "needs the sequence's phase: {steps: N, period: P}");
  appendPhase(patterns, axisFromName(entry, "phase", axis), spec);
}

// The axes the names code; every name checked against the spec, none listed twice.
void deriveAxes(RigSequence& sequence, const std::string& origin) {
  std::set<std::string> seen;
  sequence.spec.column_codes = sequence.spec.row_codes = false;
  for (const std::string& text : sequence.patterns) {
    if (!seen.insert(text).second) throw core::Error(origin + ": '" + text + "' is listed twice");
    const Pattern pattern = *patternFromName(text);
    if (pattern.axis == PatternAxis::Columns) sequence.spec.column_codes = true;
    if (pattern.axis == PatternAxis::Rows) sequence.spec.row_codes = true;
    const bool gray = pattern.kind == PatternKind::GrayBit || pattern.kind == PatternKind::GrayBitInverse;
    const int limit = gray ? grayCodeBitsOf(pattern.axis, sequence.spec) : sequence.spec.phase_steps;
    if (pattern.axis != PatternAxis::None && pattern.index >= limit) {
      throw core::Error(origin + ": '" + text + "' is beyond the " + std::to_string(limit) +
                        (gray ? " Gray bits" : " phase steps") + " of the sequence");
    }
  }
  if (!sequence.spec.column_codes) throw core::Error(origin + ": no column codes; triangulation needs them");
}

}  // namespace

const std::vector<std::string>& sequencePresetNames() {
  static const std::vector<std::string> names = {"binpick", "opencv-graycode"};
  return names;
}

RigSequence presetSequence(const std::string& preset, const io::PatternSetSpec& spec) {
  RigSequence sequence;
  sequence.spec = spec;
  if (preset == "binpick") {
    sequence.patterns = patternNames(spec);
    return sequence;
  }
  if (preset != "opencv-graycode") {
    throw core::Error("unknown pattern sequence preset '" + preset + "' (use binpick or opencv-graycode)");
  }
  sequence.spec.column_codes = sequence.spec.row_codes = true;
  sequence.spec.phase_steps = 0;
  sequence.spec.validate();
  appendGray(sequence.patterns, {PatternAxis::Columns}, sequence.spec);
  appendGray(sequence.patterns, {PatternAxis::Rows}, sequence.spec);
  sequence.patterns.insert(sequence.patterns.end(), {"white", "black"});
  return sequence;
}

RigSequence parseRigSequence(const std::string& yaml_text, const std::string& origin) {
  core::YamlSection top(core::parseYaml(yaml_text, origin), "", origin);
  RigSequence sequence;
  io::PatternSetSpec& spec = sequence.spec;
  core::YamlSection projector = top.child("projector");
  projector.read("width", spec.projector_width);
  projector.read("height", spec.projector_height);
  projector.finish();
  if (!top.has("projector")) top.fail("projector", "is required: {width: W, height: H} in pixels");
  top.read("code_step", spec.code_step);
  top.read("gray_unit", spec.gray_unit);
  spec.phase_steps = 0;
  core::YamlSection phase = top.child("phase");
  phase.read("steps", spec.phase_steps);
  phase.read("period", spec.phase_period);
  phase.read("direction", spec.phase_direction);
  phase.read("offset_deg", spec.phase_offset_deg);
  phase.finish();
  core::validateSettings(origin, [&] { spec.validate(); });
  if (!top.has("images") || !top.node()["images"].IsSequence())
    top.fail("images", "must be a list, one entry per image");
  top.skip("images");
  top.finish();
  const YAML::Node images = top.node()["images"];
  for (std::size_t i = 0; i < images.size(); ++i) appendEntry(sequence.patterns, images[i], i, spec, origin);
  deriveAxes(sequence, origin);
  return sequence;
}

RigSequence readRigSequence(const std::string& path) { return parseRigSequence(core::readConfigFile(path), path); }

}  // namespace binpick::reconstruction
