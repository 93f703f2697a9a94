#pragma once
// Where each pattern of a capture's pattern set sits among its images, checked against the
// images themselves. Internal to the decoder.
#include <vector>

#include "binpick/io/capture.hpp"

namespace binpick::reconstruction::detail {

struct AxisLayout {
  bool present = false;
  int size = 0;                 // projector columns (or rows)
  std::vector<int> bit_images;  // image index of Gray bit j (most significant first)
  std::vector<int> inverse_images;
  std::vector<int> phase_images;  // one per phase step; empty without phase shift
  int phase_period = 0;           // projector pixels
  int gray_unit = 1;              // projector pixels per Gray-code word (PatternSetSpec::gray_unit)

  int bits() const { return static_cast<int>(bit_images.size()); }
  bool hasPhase() const { return !phase_images.empty(); }
  // Width in projector pixels of the stripes of Gray bit j: gray_unit 2^(bits - 1 - j).
  int stripeWidth(int bit) const { return gray_unit << (bits() - 1 - bit); }
};

struct CaptureLayout {
  int white = -1;
  int black = -1;
  AxisLayout columns;
  AxisLayout rows;
  int width = 0;  // camera image size
  int height = 0;
  int bit_depth = 8;
  io::PatternSetSpec pattern_set;  // the phase steps' shifts, among the rest
};

// For a capture in binpick's own order (completeCapture's, whose images it has checked). Throws
// core::Error when the pattern names are not the sequence the pattern set defines, or the set has
// no column codes (triangulation needs the projector column).
CaptureLayout captureLayout(const io::Capture& capture);

}  // namespace binpick::reconstruction::detail
