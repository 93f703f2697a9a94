#pragma once
// Reading the Gray code of pixels too dark, or too blurred, to read alone: along their stripes.
//
// A pixel whose bits drown in the sensor's noise (a black surface: a few counts of contrast; the
// finest bits of a defocused projector: a few percent of it) sees the same code as every pixel on
// its stripe, the curve where one projector column's light falls on the surface. Summing
// pattern - inverse over n pixels along that curve adds the signal n times and the noise sqrt(n)
// times. Only pixels that failed alone take part (a bright neighbour is not borrowed), and a bit
// is certain only where its sum clears bit_noise_sigmas times its own noise, so nothing is read
// that the light did not write. The finest bits, which blur and darkness erase first, may stay
// uncertain: the pixel is placed in the shortest run of codes that holds 95% of the likelihood
// their signs leave (each sign right with probability Phi(|sum| / sigma)), at the run's weighted
// mean, when that run is at most max_code_run_along_stripe codes: a coarser point than the
// others', at the precision its readable bits give, and judged as such downstream
// (DecodedCapture::stripe_run).
//
// The stripe's direction is searched per 16 x 16-pixel block: the one of 32 directions along
// which the finest bits' sums carry the most energy (across the stripes they cancel). Internal
// to the decoder.
#include "binpick/io/capture.hpp"
#include "binpick/reconstruction/decoder.hpp"
#include "decode_plan.hpp"

namespace binpick::reconstruction::detail {

// Decodes the Unlit and UncertainCode pixels with some contrast beyond the noise (and not
// clipped) along their stripes: those read become Valid (the row as keep_column_without_row
// says when it stays unread), with DecodedCapture::stripe_run set. Does nothing when an axis has phase images (the
// phase is the fine code there), when the capture's noise was not measured, or when params.stripe_reach is 0. The
// result does not depend on the thread count. Coordinates in codes, as decodeTile writes them.
void readAlongStripes(const io::Capture& capture, const DecodePlan& plan, const DecodeParams& params, int threads,
                      DecodedCapture& decoded);

}  // namespace binpick::reconstruction::detail
