// Phase unwrapping of uncertain Gray codes from the neighbours' columns (neighbour_unwrap.hpp).
#include "neighbour_unwrap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "binpick/reconstruction/pattern_set.hpp"

namespace binpick::reconstruction::detail {
namespace {

// Distance (projector pixels) from position x to the nearest stripe edge of the Gray bit of
// weight 2^b, in words of `unit` columns: that bit changes between columns c - 1 and c for
// c = unit 2^b (2m + 1).
float distanceToStripeEdge(float x, int b, int unit) {
  const float half = std::ldexp(static_cast<float>(unit), b);
  float r = std::fmod(x + 0.5f - half, 2.0f * half);
  if (r < 0.0f) r += 2.0f * half;
  return std::min(r, 2.0f * half - r);
}

// The certain bits of `code` name column c's Gray code, except bits whose edge is within
// `tolerance` of x (there the pixel may see either side).
bool certainBitsAgree(uint32_t code, uint32_t uncertain, unsigned column, float x, const AxisLayout& axis,
                      float tolerance) {
  const unsigned word = column / static_cast<unsigned>(axis.gray_unit);
  const uint32_t differing = (code ^ grayCode(word)) & ~uncertain;
  for (int b = 0; b < axis.bits(); ++b) {
    if (((differing >> b) & 1u) != 0 && distanceToStripeEdge(x, b, axis.gray_unit) > tolerance) return false;
  }
  return true;
}

// Columns of the 8 neighbours of `pixel` the first pass decoded; their count.
int decodedNeighbours(const DecodedCapture& decoded, std::size_t pixel, float* columns) {
  const int width = decoded.width, height = decoded.height;
  const int x = static_cast<int>(pixel % static_cast<std::size_t>(width));
  const int y = static_cast<int>(pixel / static_cast<std::size_t>(width));
  int count = 0;
  for (int v = std::max(0, y - 1); v <= std::min(height - 1, y + 1); ++v) {
    const float* column = decoded.column.ptr<float>(v);
    const uint8_t* status = decoded.status.ptr<uint8_t>(v);
    for (int u = std::max(0, x - 1); u <= std::min(width - 1, x + 1); ++u) {
      if ((u != x || v != y) && status[u] == static_cast<uint8_t>(PixelStatus::Valid)) columns[count++] = column[u];
    }
  }
  return count;
}

// An insertion sort, as std::sort does for so few values. Written out because GCC 12 cannot see
// that std::sort's branch for more than 16 values is never taken on the 8-float array, and warns
// (-Warray-bounds).
void sortFew(float* values, int count) {
  for (int i = 1; i < count; ++i) {
    const float value = values[i];
    int j = i;
    for (; j > 0 && value < values[j - 1]; --j) values[j] = values[j - 1];
    values[j] = value;
  }
}

}  // namespace

float columnFromNeighbours(const UnwrapCandidate& candidate, const DecodedCapture& decoded, const AxisLayout& columns,
                           const DecodeThresholds& t, int min_neighbours) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  float found[8] = {};
  const int count = decodedNeighbours(decoded, candidate.pixel, found);
  if (count < std::max(1, min_neighbours)) return nan;
  sortFew(found, count);
  const auto period = static_cast<float>(columns.phase_period);
  const float quarter = 0.25f * period;
  if (found[count - 1] - found[0] > quarter) return nan;  // not one smooth surface
  const float median = found[count / 2];
  const float x = candidate.phase_offset + period * std::round((median - candidate.phase_offset) / period);
  // As far from the neighbours as the phase may lie outside a Gray-code run of one column.
  if (std::fabs(x - median) > 0.5f + t.phase_tolerance || x < -0.5f || x > static_cast<float>(columns.size) - 0.5f)
    return nan;
  const auto column = static_cast<unsigned>(std::lround(x));
  if (!certainBitsAgree(candidate.code, candidate.uncertain, column, x, columns, t.phase_tolerance)) return nan;
  return x;
}

void unwrapFromNeighbours(const std::vector<UnwrapCandidate>& candidates, const DecodePlan& plan, int min_neighbours,
                          int threads, DecodedCapture& decoded) {
  std::vector<float> resolved(candidates.size());
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long i = 0; i < static_cast<long>(candidates.size()); ++i) {
    resolved[i] = columnFromNeighbours(candidates[i], decoded, plan.layout.columns, plan.thresholds, min_neighbours);
  }
  const bool rows = !decoded.row.empty();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!std::isfinite(resolved[i])) continue;
    const UnwrapCandidate& c = candidates[i];
    const bool row_valid = c.row_status == PixelStatus::Valid;
    PixelStatus status = PixelStatus::Valid;
    if (rows && !row_valid && !plan.thresholds.keep_column_without_row) status = c.row_status;
    decoded.status.ptr<uint8_t>(0)[c.pixel] = static_cast<uint8_t>(status);
    if (status != PixelStatus::Valid) continue;
    decoded.column.ptr<float>(0)[c.pixel] = resolved[i];
    if (!decoded.column_noise.empty()) decoded.column_noise.ptr<float>(0)[c.pixel] = c.noise;
    if (rows && row_valid) decoded.row.ptr<float>(0)[c.pixel] = c.row;
  }
}

}  // namespace binpick::reconstruction::detail
