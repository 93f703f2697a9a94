#pragma once
// Unwrapping the phase of a pixel whose Gray code is too uncertain to name the period, from its
// decoded neighbours. On dark surfaces the sensor noise leaves coarse Gray bits undecided far
// from their stripe edges while the phase still measures the position within the period; the
// neighbours on the same surface name the period (their columns lie within a few projector
// pixels of the pixel's). The certain bits must still agree, so a pixel across a depth edge from
// its neighbours is not given their period. Internal to the decoder.
#include <cstdint>
#include <vector>

#include "binpick/reconstruction/decoder.hpp"
#include "binpick/reconstruction/pixel_status.hpp"
#include "capture_layout.hpp"
#include "decode_plan.hpp"

namespace binpick::reconstruction::detail {

// A pixel the first pass left UncertainCode with a usable, unclipped phase.
struct UnwrapCandidate {
  std::size_t pixel = 0;      // row-major index
  float phase_offset = 0.0f;  // projector pixels within one period
  uint16_t code = 0;          // column Gray code as read, and its uncertain bits
  uint16_t uncertain = 0;
  float noise = 0.0f;  // DecodedCapture::column_noise, when estimated
  float row = 0.0f;    // the row's verdict, as resolveAxis gave it (rows present)
  PixelStatus row_status = PixelStatus::Valid;
};

// The candidate's column: the period instance of its phase nearest the median column of those of
// its 8 neighbours that the first pass decoded, when at least `min_neighbours` did, they span at
// most a quarter of a period, the instance lies within 0.5 + t.phase_tolerance of their median
// (as far as the phase may lie outside a Gray-code run of one column), and the code it names
// agrees with every certain bit whose stripe edge is farther than t.phase_tolerance from it. NaN
// otherwise.
float columnFromNeighbours(const UnwrapCandidate& candidate, const DecodedCapture& decoded, const AxisLayout& columns,
                           const DecodeThresholds& t, int min_neighbours);

// Decides every candidate on the first pass's columns, then writes the ones resolved (Valid, the
// column, the row as the first pass would have: NaN or its status when it did not decode).
void unwrapFromNeighbours(const std::vector<UnwrapCandidate>& candidates, const DecodePlan& plan, int min_neighbours,
                          int threads, DecodedCapture& decoded);

}  // namespace binpick::reconstruction::detail
