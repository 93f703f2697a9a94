// capture.json: CaptureMetadata as JSON, every key required and type-checked on reading.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"
#include "binpick/core/json_fields.hpp"
#include "binpick/io/capture.hpp"
#include "byte_io.hpp"
#include "capture_paths.hpp"

namespace binpick::io {
namespace {

using detail::fail;
using nlohmann::json;

constexpr int kFormatVersion = 1;
constexpr std::int64_t kMaxImagePixels = std::int64_t{1} << 28;  // 16384 x 16384

void require(bool ok, const char* field, const char* rule, int value) {
  core::requireField(ok, "PatternSetSpec", field, rule, value);
}

PatternSetSpec patternSetFrom(const json& object, const std::string& path) {
  if (!object.is_object()) fail(path, "'pattern_set' must be an object");
  PatternSetSpec spec;
  spec.projector_width = core::jsonField<int>(object, "projector_width", path);
  spec.projector_height = core::jsonField<int>(object, "projector_height", path);
  spec.column_codes = core::jsonField<bool>(object, "column_codes", path);
  spec.row_codes = core::jsonField<bool>(object, "row_codes", path);
  spec.phase_steps = core::jsonField<int>(object, "phase_steps", path);
  spec.phase_period = core::jsonField<int>(object, "phase_period", path);
  // Optional: captures written before it existed coded every projector pixel.
  if (object.contains("code_step")) spec.code_step = core::jsonField<int>(object, "code_step", path);
  if (object.contains("gray_unit")) spec.gray_unit = core::jsonField<int>(object, "gray_unit", path);
  if (object.contains("phase_direction")) spec.phase_direction = core::jsonField<int>(object, "phase_direction", path);
  if (object.contains("phase_offset_deg")) {
    spec.phase_offset_deg = core::jsonField<double>(object, "phase_offset_deg", path);
  }
  try {
    spec.validate();
  } catch (const core::Error& e) {
    fail(path, e.what());
  }
  return spec;
}

json toJson(const PatternSetSpec& spec) {
  json object = {{"projector_width", spec.projector_width}, {"projector_height", spec.projector_height},
                 {"column_codes", spec.column_codes},       {"row_codes", spec.row_codes},
                 {"phase_steps", spec.phase_steps},         {"phase_period", spec.phase_period}};
  // Written only when not binpick's own: older readers read the rest.
  if (spec.code_step != 1) object["code_step"] = spec.code_step;
  if (spec.gray_unit > spec.code_step) object["gray_unit"] = spec.gray_unit;
  if (spec.phase_direction != 1) object["phase_direction"] = spec.phase_direction;
  if (spec.phase_offset_deg != 0.0) object["phase_offset_deg"] = spec.phase_offset_deg;
  return object;
}

void checkConsistent(const CaptureMetadata& m, const std::string& path) {
  if (m.image_width <= 0 || m.image_height <= 0 || m.image_width > 65536 || m.image_height > 65536) {
    fail(path, "image_width and image_height must be in [1, 65536]");
  }
  // Each image is decoded whole: the size bounds what one allocation may take (512 MiB at 16 bits).
  if (static_cast<std::int64_t>(m.image_width) * m.image_height > kMaxImagePixels) {
    fail(path, "image_width x image_height must be at most " + std::to_string(kMaxImagePixels) + " pixels (got " +
                   std::to_string(m.image_width) + "x" + std::to_string(m.image_height) + ")");
  }
  if (m.bit_depth != 8 && m.bit_depth != 16) fail(path, "bit_depth must be 8 or 16");
  if (m.patterns.empty()) fail(path, "'patterns' is empty");
  if (m.patterns.size() != m.images.size()) {
    fail(path, "'patterns' and 'images' differ in length (" + std::to_string(m.patterns.size()) + " vs " +
                   std::to_string(m.images.size()) + ")");
  }
  if (!m.frame_times_ms.empty() && m.frame_times_ms.size() != m.patterns.size()) {
    fail(path, "'frame_times_ms' has " + std::to_string(m.frame_times_ms.size()) + " entries for " +
                   std::to_string(m.patterns.size()) + " patterns");
  }
  for (double time : m.frame_times_ms) {
    if (!std::isfinite(time)) fail(path, "'frame_times_ms' holds a value that is not finite");
  }
  for (const std::string& image : m.images) {
    if (!capture_detail::isPlainImageName(image)) {
      fail(path, "image name '" + image + "' must be images/<name>.png");
    }
  }
}

}  // namespace

void PatternSetSpec::validate() const {
  require(projector_width >= 2 && projector_width <= 65536, "projector_width", "in [2, 65536]", projector_width);
  require(projector_height >= 2 && projector_height <= 65536, "projector_height", "in [2, 65536]", projector_height);
  require(column_codes || row_codes, "column_codes", "true when row_codes is false", 0);
  require(phase_steps == 0 || (phase_steps >= 3 && phase_steps <= 64), "phase_steps", "0 or in [3, 64]", phase_steps);
  require(phase_period >= 4 && phase_period <= 65536, "phase_period", "in [4, 65536]", phase_period);
  require(code_step >= 1 && code_step <= 64 && code_step * 2 <= std::min(projector_width, projector_height),
          "code_step", "in [1, 64] and at most half the projector's size", code_step);
  require(phase_steps == 0 || phase_period % code_step == 0, "phase_period", "a multiple of code_step", phase_period);
  const bool words = gray_unit > code_step;
  require(gray_unit >= 0 && gray_unit <= 65536 && gray_unit % code_step == 0, "gray_unit",
          "0 or a multiple of code_step", gray_unit);
  require(!words || phase_steps > 0, "gray_unit", "code_step unless there are phase images", gray_unit);
  require(!words || gray_unit <= phase_period, "gray_unit", "at most phase_period", gray_unit);
  require(phase_direction == 1 || phase_direction == -1, "phase_direction", "1 or -1", phase_direction);
  core::requireField(phase_offset_deg >= 0.0 && phase_offset_deg < 360.0, "PatternSetSpec", "phase_offset_deg",
                     "in [0, 360)", phase_offset_deg);
}

CaptureMetadata readCaptureMetadata(const std::string& directory) {
  const std::string path = capture_detail::metadataPath(directory);
  const json document = core::readJsonFile(path);
  if (!document.is_object()) fail(path, "the document must be a JSON object");
  CaptureMetadata m;
  m.format_version = core::jsonField<int>(document, "format_version", path);
  if (m.format_version != kFormatVersion) {
    fail(path, "format_version " + std::to_string(m.format_version) +
                   " is not supported (this "
                   "build reads version " +
                   std::to_string(kFormatVersion) + ")");
  }
  m.source = core::jsonField<std::string>(document, "source", path);
  m.timestamp = core::jsonField<std::string>(document, "timestamp", path);
  m.image_width = core::jsonField<int>(document, "image_width", path);
  m.image_height = core::jsonField<int>(document, "image_height", path);
  m.bit_depth = core::jsonField<int>(document, "bit_depth", path);
  m.exposure_us = core::jsonField<double>(document, "exposure_us", path);
  m.gain_db = core::jsonField<double>(document, "gain_db", path);
  m.pattern_set = patternSetFrom(core::jsonField<json>(document, "pattern_set", path), path);
  m.patterns = core::jsonField<std::vector<std::string>>(document, "patterns", path);
  m.images = core::jsonField<std::vector<std::string>>(document, "images", path);
  if (document.contains("frame_times_ms")) {  // optional: recordings only
    m.frame_times_ms = core::jsonField<std::vector<double>>(document, "frame_times_ms", path);
  }
  checkConsistent(m, path);
  return m;
}

namespace capture_detail {

void checkMetadata(const CaptureMetadata& m, const std::string& path) {
  try {
    m.pattern_set.validate();
  } catch (const core::Error& e) {
    fail(path, e.what());
  }
  checkConsistent(m, path);
}

void writeCaptureMetadata(const std::string& directory, const CaptureMetadata& m) {
  const std::string path = capture_detail::metadataPath(directory);
  checkMetadata(m, path);
  json document = {{"format_version", m.format_version},
                   {"source", m.source},
                   {"timestamp", m.timestamp},
                   {"image_width", m.image_width},
                   {"image_height", m.image_height},
                   {"bit_depth", m.bit_depth},
                   {"exposure_us", m.exposure_us},
                   {"gain_db", m.gain_db},
                   {"pattern_set", toJson(m.pattern_set)},
                   {"patterns", m.patterns},
                   {"images", m.images}};
  if (!m.frame_times_ms.empty()) document["frame_times_ms"] = m.frame_times_ms;
  core::writeFileAtomically(path, document.dump(2) + "\n");
}

}  // namespace capture_detail

}  // namespace binpick::io
