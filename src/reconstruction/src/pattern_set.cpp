// Gray-code + phase-shift pattern sequence.
#include "binpick/reconstruction/pattern_set.hpp"

#include <cmath>
#include <cstdio>
#include <optional>

#include "binpick/core/error.hpp"

namespace binpick::reconstruction {
namespace {

// Codes along the axis: the Gray code counts codes, not projector pixels (PatternSetSpec::code_step).
int axisSize(PatternAxis axis, const io::PatternSetSpec& spec) {
  return axis == PatternAxis::Rows ? spec.rowCodes() : spec.columnCodes();
}

void appendAxis(std::vector<Pattern>& sequence, PatternAxis axis, const io::PatternSetSpec& spec) {
  for (int bit = 0; bit < grayCodeBitsOf(axis, spec); ++bit) {
    sequence.push_back({PatternKind::GrayBit, axis, bit});
    sequence.push_back({PatternKind::GrayBitInverse, axis, bit});
  }
  for (int step = 0; step < spec.phase_steps; ++step) {
    sequence.push_back({PatternKind::PhaseStep, axis, step});
  }
}

// "03" -> 3; nullopt unless the text is one to three digits.
std::optional<int> smallNumber(const std::string& text) {
  if (text.empty() || text.size() > 3 || text.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return std::stoi(text);
}

// A projector drives 8-bit levels: the phase patterns it shows are quantised.
double eightBit(double brightness) { return std::round(255.0 * brightness) / 255.0; }

}  // namespace

std::string Pattern::name() const {
  if (kind == PatternKind::White) return "white";
  if (kind == PatternKind::Black) return "black";
  const char* axis_name = axis == PatternAxis::Rows ? "row" : "col";
  char text[48];
  if (kind == PatternKind::PhaseStep) {
    std::snprintf(text, sizeof text, "phase_%s_%d", axis_name, index);
  } else {
    std::snprintf(text, sizeof text, "gray_%s_%02d%s", axis_name, index,
                  kind == PatternKind::GrayBitInverse ? "_inv" : "");
  }
  return text;
}

std::vector<Pattern> patternSequence(const io::PatternSetSpec& spec) {
  spec.validate();
  std::vector<Pattern> sequence{{PatternKind::White, PatternAxis::None, 0}, {PatternKind::Black, PatternAxis::None, 0}};
  if (spec.column_codes) appendAxis(sequence, PatternAxis::Columns, spec);
  if (spec.row_codes) appendAxis(sequence, PatternAxis::Rows, spec);
  return sequence;
}

std::optional<Pattern> patternFromName(const std::string& name) {
  if (name == "white") return Pattern{PatternKind::White, PatternAxis::None, 0};
  if (name == "black") return Pattern{PatternKind::Black, PatternAxis::None, 0};
  const auto axisOf = [](const std::string& text) {
    return text == "col" ? PatternAxis::Columns : text == "row" ? PatternAxis::Rows : PatternAxis::None;
  };
  // gray_AXIS_BB[_inv] or phase_AXIS_K
  const bool gray = name.rfind("gray_", 0) == 0;
  const bool phase = name.rfind("phase_", 0) == 0;
  if (!gray && !phase) return std::nullopt;
  std::string rest = name.substr(gray ? 5 : 6);
  const bool inverse = gray && rest.size() > 4 && rest.compare(rest.size() - 4, 4, "_inv") == 0;
  if (inverse) rest.resize(rest.size() - 4);
  if (rest.size() < 5 || rest[3] != '_') return std::nullopt;
  const PatternAxis axis = axisOf(rest.substr(0, 3));
  const std::optional<int> index = smallNumber(rest.substr(4));
  if (axis == PatternAxis::None || !index) return std::nullopt;
  const PatternKind kind = phase     ? PatternKind::PhaseStep
                           : inverse ? PatternKind::GrayBitInverse
                                     : PatternKind::GrayBit;
  const Pattern pattern{kind, axis, *index};
  if (pattern.name() != name) return std::nullopt;  // one spelling per pattern: "gray_col_3" is not one
  return pattern;
}

std::vector<std::string> patternNames(const io::PatternSetSpec& spec) {
  std::vector<std::string> names;
  for (const Pattern& p : patternSequence(spec)) names.push_back(p.name());
  return names;
}

int grayCodeBits(int size) {
  int bits = 0;
  while ((1LL << bits) < size) ++bits;
  return bits;
}

int grayCodeBitsOf(PatternAxis axis, const io::PatternSetSpec& spec) {
  const int unit = spec.grayUnitCodes();
  return grayCodeBits((axisSize(axis, spec) + unit - 1) / unit);
}

double patternBrightness(const Pattern& pattern, const io::PatternSetSpec& spec, int pixel) {
  // Every pixel of a code's block shows the code's brightness.
  const int coordinate = pixel / spec.code_step;
  switch (pattern.kind) {
    case PatternKind::White: return 1.0;
    case PatternKind::Black: return 0.0;
    case PatternKind::GrayBit:
    case PatternKind::GrayBitInverse: {
      const int bits = grayCodeBitsOf(pattern.axis, spec);
      if (pattern.index < 0 || pattern.index >= bits) {
        throw core::Error("patternBrightness: Gray-code bit " + std::to_string(pattern.index) + " of " +
                          pattern.name() + " is outside [0, " + std::to_string(bits) + ")");
      }
      const auto word = static_cast<unsigned>(coordinate / spec.grayUnitCodes());
      const unsigned bit = (grayCode(word) >> (bits - 1 - pattern.index)) & 1u;
      return (pattern.kind == PatternKind::GrayBit) == (bit == 1u) ? 1.0 : 0.0;
    }
    case PatternKind::PhaseStep: {
      // I_k(c) = 1/2 + 1/2 cos(2 pi c / period - theta_k): the phase of pixel c is
      // 2 pi c / period, recovered from the N steps by their first Fourier coefficient.
      const double phase = 2.0 * M_PI * coordinate / (spec.phase_period / spec.code_step);
      const double shift = phaseShift(spec, pattern.index);
      return eightBit(0.5 + 0.5 * std::cos(phase - shift));
    }
  }
  throw core::Error("patternBrightness: unknown pattern kind");
}

double phaseShift(const io::PatternSetSpec& spec, int step) {
  return spec.phase_direction * 2.0 * M_PI * step / spec.phase_steps + spec.phase_offset_deg * M_PI / 180.0;
}

cv::Mat patternImage(const Pattern& pattern, const io::PatternSetSpec& spec) {
  spec.validate();
  cv::Mat image(spec.projector_height, spec.projector_width, CV_8UC1);
  const bool by_row = pattern.axis == PatternAxis::Rows;
  for (int row = 0; row < image.rows; ++row) {
    auto* pixels = image.ptr<uchar>(row);
    for (int col = 0; col < image.cols; ++col) {
      const double value = patternBrightness(pattern, spec, by_row ? row : col);
      pixels[col] = static_cast<uchar>(std::lround(255.0 * value));
    }
  }
  return image;
}

}  // namespace binpick::reconstruction
