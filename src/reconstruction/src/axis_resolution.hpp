#pragma once
// From the bits and phase read at one pixel to a projector column (or row). Internal; the
// per-pixel functions are inline because they run inside the decoder's tile loop.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "binpick/reconstruction/pattern_set.hpp"
#include "binpick/reconstruction/pixel_status.hpp"
#include "capture_layout.hpp"
#include "decode_plan.hpp"

namespace binpick::reconstruction::detail {

struct AxisSample {
  uint32_t code = 0;          // Gray code as read, most significant bit first
  uint32_t uncertain = 0;     // bits that could not be classified
  float phase_offset = 0.0f;  // projector pixels within one period, from the phase
  float phase_amplitude = 0.0f;
  bool phase_clipped = false;
};

struct AxisVerdict {
  float position = 0.0f;  // projector pixels, pixel centres at integers
  PixelStatus status = PixelStatus::Valid;
};

// Rounds to the nearest integer, halves up, for |value| < 2^20; written so that loops over it
// vectorise (an int conversion rather than a libm call).
inline float nearestWhole(float value) {
  constexpr float kShift = 1048576.0f;  // makes the argument positive: conversion truncates
  return static_cast<float>(static_cast<int>(value + 0.5f + kShift)) - kShift;
}

// More uncertain bits than this cannot leave a short run of columns: a pixel on a stripe edge
// of a run of n columns has about log2(n) uncertain bits.
constexpr int kMaxUncertainBits = 6;

struct CodeRun {
  unsigned first = 0;
  unsigned last = 0;
};

// Every column whose Gray code agrees with the certain bits: one per combination of the
// uncertain ones. Adjacent columns differ in exactly one Gray bit, so a pixel straddling a
// stripe edge leaves a run of two.
inline CodeRun candidateRun(uint32_t code, uint32_t uncertain) {
  if (uncertain == 0) {
    const unsigned column = grayDecode(code);
    return {column, column};
  }
  const uint32_t certain_bits = code & ~uncertain;
  CodeRun run{~0u, 0u};
  for (uint32_t subset = uncertain;; subset = (subset - 1) & uncertain) {
    const unsigned column = grayDecode(certain_bits | subset);
    run.first = std::min(run.first, column);
    run.last = std::max(run.last, column);
    if (subset == 0) break;
  }
  return run;
}

// The codes of a run of Gray-code words, AxisLayout::gray_unit codes each.
inline CodeRun codesOfWords(const CodeRun& words, const AxisLayout& axis) {
  const auto unit = static_cast<unsigned>(axis.gray_unit);
  return {words.first * unit, words.last * unit + unit - 1};
}

// The longest run of codes a pixel may leave. Words longer than half the setting (a
// complementary Gray code's half periods) leave two at a stripe edge, where the pixel sees either
// side: the phase then picks the instance nearest that edge, which is right while the phase errs
// by less than half a period.
inline int longestRun(const AxisLayout& axis, const DecodeThresholds& t) {
  if (!axis.hasPhase()) return t.max_run_without_phase;
  return std::max(t.max_run_with_phase, 2 * axis.gray_unit);
}

// The period instance of the phase's position closest to the run's centre; the true position
// lies within the run (columns first..last cover [first - 0.5, last + 0.5]).
inline AxisVerdict unwrapPhase(const AxisSample& sample, const CodeRun& run, const AxisLayout& axis,
                               const DecodeThresholds& t) {
  if (sample.phase_clipped) return {0.0f, PixelStatus::Saturated};
  if (!(sample.phase_amplitude >= t.min_phase_amplitude)) return {0.0f, PixelStatus::PhaseMismatch};
  const float period = static_cast<float>(axis.phase_period);
  const float centre = 0.5f * static_cast<float>(run.first + run.last);
  const float periods = nearestWhole((centre - sample.phase_offset) * (1.0f / period));
  const float position = sample.phase_offset + period * periods;
  const float low = static_cast<float>(run.first) - 0.5f - t.phase_tolerance;
  const float high = static_cast<float>(run.last) + 0.5f + t.phase_tolerance;
  if (!(position >= low && position <= high)) return {0.0f, PixelStatus::PhaseMismatch};
  return {position, PixelStatus::Valid};
}

inline AxisVerdict resolveAxis(const AxisSample& sample, const AxisLayout& axis, const DecodeThresholds& t) {
  if (__builtin_popcount(sample.uncertain) > kMaxUncertainBits) return {0.0f, PixelStatus::UncertainCode};
  CodeRun run = codesOfWords(candidateRun(sample.code, sample.uncertain), axis);
  if (run.last - run.first + 1 > static_cast<unsigned>(longestRun(axis, t))) {
    return {0.0f, PixelStatus::UncertainCode};
  }
  const unsigned size = static_cast<unsigned>(axis.size);
  if (run.first >= size) return {0.0f, PixelStatus::CodeOutOfRange};
  run.last = std::min(run.last, size - 1);  // codes past the edge were never projected
  if (!axis.hasPhase()) return {0.5f * static_cast<float>(run.first + run.last), PixelStatus::Valid};
  return unwrapPhase(sample, run, axis, t);
}

// Verdicts of resolveSimpleCodes: a PixelStatus, or this for a pixel resolveAxis must decide.
constexpr uint8_t kNeedsFullResolution = 255;

// resolveAxis for a whole tile at once, vectorised, for the common pixels: at most one uncertain
// bit (a stripe edge or none), a run no longer than longestRun, inside the projector. Writes the
// run's centre and a verdict per pixel: Valid for those pixels, kNeedsFullResolution for the
// others. Gives the same result as resolveAxis wherever it decides.
void resolveSimpleRuns(const uint16_t* __restrict code, const uint16_t* __restrict uncertain, const AxisLayout& axis,
                       const DecodeThresholds& t, float* __restrict centre, uint8_t* __restrict verdict, int width);
// unwrapPhase for the pixels resolveSimpleRuns decided: the centre becomes the unwrapped
// position, and their verdict Valid, PhaseMismatch or Saturated.
void unwrapSimpleRuns(const uint16_t* __restrict code, const uint16_t* __restrict uncertain,
                      const float* __restrict phase_offset, const float* __restrict phase_amplitude,
                      const uint8_t* __restrict phase_clipped, const AxisLayout& axis, const DecodeThresholds& t,
                      float* __restrict position, uint8_t* __restrict verdict, int width);

// grayDecode of a code of at most 16 bits, unrolled so that loops over it vectorise.
inline uint32_t grayDecode16(uint32_t code) {
  code ^= code >> 1;
  code ^= code >> 2;
  code ^= code >> 4;
  code ^= code >> 8;
  return code;
}

}  // namespace binpick::reconstruction::detail
