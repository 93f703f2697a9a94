#pragma once
// Whole-capture checks on a sample of pixels, before decoding: is there projector light at all,
// is the sensor saturated, and does every image show the pattern it claims to. Internal.
#include "binpick/io/capture.hpp"
#include "binpick/reconstruction/decoder.hpp"
#include "decode_plan.hpp"

namespace binpick::reconstruction::detail {

// Throws core::Error naming the images and what is wrong with them.
void checkCaptureLight(const io::Capture& capture, const DecodePlan& plan, const DecodeParams& params);

}  // namespace binpick::reconstruction::detail
