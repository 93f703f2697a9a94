#pragma once
// Whole-capture check, on a sample of well-lit pixels, that the images are in the order the
// metadata declares: a Gray pattern swapped with its own inverse, or phase-shift steps out of
// order, still add up to white + black (capture_light_check.hpp) but decode into wrong points.
// Internal.
#include "binpick/io/capture.hpp"
#include "binpick/reconstruction/decoder.hpp"
#include "decode_plan.hpp"

namespace binpick::reconstruction::detail {

// Where the phase and the Gray code of each sampled pixel agree, the images are in order. When
// they disagree on most pixels and swapping one Gray pattern with its inverse, or two phase
// steps, makes them agree, throws core::Error naming the two images. Captures without phase
// steps are not checked (nothing to compare the Gray code with).
void checkCaptureOrder(const io::Capture& capture, const DecodePlan& plan);

}  // namespace binpick::reconstruction::detail
