#pragma once
// The projected pattern sequence of a PatternSetSpec (binpick/io/capture.hpp): what the projector
// shows for each image of a capture, and in which order. The virtual cell renders it, acquisition
// triggers it and the decoder reads it, so all three agree by construction. Order:
//   white, black,
//   per coded axis (columns, then rows): Gray-code bits from the most significant, each followed
//   by its inverse, then the phase-shift steps (if any).
// That is binpick's own order; a capture may list its patterns in any order, and without white
// and black or without inverses (capture_completion: the decoder makes up what it lacks).
// Pure functions: thread-safe.
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "binpick/io/capture.hpp"

namespace binpick::reconstruction {

enum class PatternKind { White, Black, GrayBit, GrayBitInverse, PhaseStep };
enum class PatternAxis { None, Columns, Rows };

struct Pattern {
  PatternKind kind = PatternKind::White;
  PatternAxis axis = PatternAxis::None;
  int index = 0;  // Gray-code bit (0 = most significant) or phase step
  // "white", "black", "gray_col_03", "gray_col_03_inv", "phase_row_1", ...
  std::string name() const;
};

std::vector<Pattern> patternSequence(const io::PatternSetSpec& spec);
std::vector<std::string> patternNames(const io::PatternSetSpec& spec);
// The pattern a name stands for ("gray_row_04_inv"), or nullopt for a name no pattern has.
std::optional<Pattern> patternFromName(const std::string& name);

// Bits needed to give each of `size` projector columns (or rows) its own code: ceil(log2(size)).
int grayCodeBits(int size);
// The Gray bits a set projects along an axis: one word per PatternSetSpec::gray_unit.
int grayCodeBitsOf(PatternAxis axis, const io::PatternSetSpec& spec);
// The reflected binary Gray code of a column or row index, and its inverse.
inline unsigned grayCode(unsigned index) { return index ^ (index >> 1); }
inline unsigned grayDecode(unsigned code) {
  // Each binary bit is the xor of all Gray bits above it: fold the shifts in log2(32) steps.
  for (unsigned shift = 1; shift < 32; shift <<= 1) code ^= code >> shift;
  return code;
}

// theta_k, the shift of phase step k (io::PatternSetSpec::phase_direction, phase_offset_deg),
// radians: step k shows 1/2 + 1/2 cos(2 pi c / period - theta_k). Decoding weighs the steps by
// cos and sin of it, so the phase it finds is 2 pi c / period whichever way the steps run.
double phaseShift(const io::PatternSetSpec& spec, int step);

// Brightness in [0, 1] of the projector pixel at `pixel` (its column for a column pattern, its
// row for a row pattern, ignored for white and black), as an 8-bit projector shows it. Patterns
// code spec.code_step pixels per code (Gray bits count words of spec.gray_unit; the phase period
// is in pixels).
double patternBrightness(const Pattern& pattern, const io::PatternSetSpec& spec, int pixel);
// The projector image (projector_width x projector_height, CV_8UC1).
cv::Mat patternImage(const Pattern& pattern, const io::PatternSetSpec& spec);

}  // namespace binpick::reconstruction
