// The decoder's per-row work. See decoder.hpp for the method; equations cite Moreno & Taubin,
// "Simple, Accurate, and Robust Projector-Camera Calibration" (3DIMPVT 2012), section 3.
// The tile loops are written without branches (0/1 integers, selects) and with restrict
// pointers so that the compiler vectorises them.
#include "row_decoder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "axis_resolution.hpp"
#include "fast_atan2.hpp"

namespace binpick::reconstruction::detail {
namespace {

// A run of consecutive pixels (in row-major order, across rows) of continuous images.
struct Tile {
  std::size_t offset = 0;  // first pixel
  int width = 0;           // pixels
};

template <typename Pixel>
const Pixel* imageRow(const Capture& capture, int image, const Tile& tile) {
  return capture.images[static_cast<std::size_t>(image)].ptr<Pixel>(0) + tile.offset;
}

// Counts (>= 0) in the classification's arithmetic: rounded for integers.
template <typename Work>
Work level(float counts) {
  if constexpr (std::is_integral_v<Work>) {
    return static_cast<Work>(static_cast<int>(counts + 0.5f));
  } else {
    return counts;
  }
}

// A margin (>= 0) in the classification's arithmetic: rounded up for integers, so that
// |p - q| >= margin means the same as in real numbers.
template <typename Work>
Work ceilingLevel(float counts) {
  if constexpr (std::is_integral_v<Work>) {
    const int whole = static_cast<int>(counts);
    return static_cast<Work>(whole + static_cast<int>(static_cast<float>(whole) < counts));
  } else {
    return counts;
  }
}

// Small loops with restrict arguments: the compiler vectorises these, not one loop doing it all.
template <typename Pixel, typename Work>
void addToBlack(const Pixel* __restrict black, const float* __restrict counts, Work* __restrict out, int width) {
  for (int x = 0; x < width; ++x) out[x] = level<Work>(static_cast<float>(black[x]) + counts[x]);
}

// The smallest |p - q| that classifies a bit: max(min_bit_difference, bit_margin * L_d).
template <typename Work>
void bitMargins(const float* __restrict direct, float least, float ratio, Work* __restrict out, int width) {
  for (int x = 0; x < width; ++x) out[x] = ceilingLevel<Work>(std::max(least, ratio * direct[x]));
}

// Whether every lit pixel of the tile is unclipped and lit more directly than globally, so that
// the simple rule classifies its bits exactly as the full rules would.
template <typename Work>
bool directLightOnly(const uint8_t* __restrict lit, const uint8_t* __restrict white_clipped,
                     const Work* __restrict direct_level, const Work* __restrict global_level, int width) {
  int exceptions = 0;
  for (int x = 0; x < width; ++x) {
    exceptions += lit[x] & (white_clipped[x] | static_cast<uint8_t>(direct_level[x] <= global_level[x]));
  }
  return exceptions == 0;
}

// L_max and L_min over the high-frequency images, then direct and global light (above black):
// L_d = (L_max - L_min) / (1 - b), L_g = 2 (L_min - b L_max) / (1 - b^2).
template <typename Pixel, typename Work>
void estimateLight(const Capture& capture, const DecodePlan& plan, const Tile& tile, RowScratch<Work>& s,
                   const RowOutput& out) {
  const int width = tile.width;
  float* __restrict high = s.brightest.data();
  float* __restrict low = s.darkest.data();
  std::fill(high, high + width, -std::numeric_limits<float>::infinity());
  std::fill(low, low + width, std::numeric_limits<float>::infinity());
  for (int image : plan.separation_images) {
    const Pixel* __restrict values = imageRow<Pixel>(capture, image, tile);
    for (int x = 0; x < width; ++x) {
      high[x] = std::max(high[x], static_cast<float>(values[x]));
      low[x] = std::min(low[x], static_cast<float>(values[x]));
    }
  }
  const Pixel* __restrict white = imageRow<Pixel>(capture, plan.layout.white, tile);
  const Pixel* __restrict black = imageRow<Pixel>(capture, plan.layout.black, tile);
  Work* __restrict direct_level = s.direct_level.data();
  Work* __restrict global_level = s.global_level.data();
  Work* __restrict margin = s.margin.data();
  uint8_t* __restrict lit = s.lit.data();
  uint8_t* __restrict white_clipped = s.white_clipped.data();
  float* __restrict intensity = out.intensity;
  // Locals, not reads through `plan`, so the compiler knows the stores cannot change them.
  const DecodeThresholds t = plan.thresholds;
  const float b = t.black_level;
  const float direct_scale = 1.0f / (1.0f - b);
  const float global_scale = 2.0f / (1.0f - b * b);
  const float to_unit = 1.0f / t.full_scale;
  // L_d into `high` and L_g into `low`, then the levels, margins and flags from them.
  for (int x = 0; x < width; ++x) {
    const float k = static_cast<float>(black[x]);
    const float direct = (high[x] - low[x]) * direct_scale;
    low[x] = std::max(0.0f, ((low[x] - k) - b * (high[x] - k)) * global_scale);
    high[x] = direct;
  }
  addToBlack<Pixel, Work>(black, high, direct_level, width);
  addToBlack<Pixel, Work>(black, low, global_level, width);
  bitMargins<Work>(high, t.min_bit_difference, t.bit_margin, margin, width);
  for (int x = 0; x < width; ++x) intensity[x] = static_cast<float>(white[x]) * to_unit;
  for (int x = 0; x < width; ++x) {
    const float k = static_cast<float>(black[x]);
    const float w = static_cast<float>(white[x]);
    lit[x] = static_cast<uint8_t>(static_cast<int>(w - k >= t.min_contrast) & static_cast<int>(high[x] >= t.min_direct));
    white_clipped[x] = static_cast<uint8_t>(w >= t.saturation);
  }
  s.direct_light_only = directLightOnly(lit, white_clipped, direct_level, global_level, width);
}

// One Gray bit against its inverse (raw p, q) for a tile, after Xu & Aliaga as used by Moreno &
// Taubin: where direct light dominates (L_d > L_g) the brighter one wins; where global light
// dominates, only p < L_d with q > L_g (off) or p > L_g with q < L_d (on) is trusted. Near-ties
// and pairs the sensor clipped are uncertain. (Levels include black: raw values compare
// directly.) Restrict parameters: the compiler vectorises this loop only when it is told.
template <typename Pixel, typename Work>
void classifyBit(const Pixel* __restrict pattern, const Pixel* __restrict inverse,
                 const Work* __restrict direct_level, const Work* __restrict global_level,
                 const Work* __restrict margin, Work clip, uint16_t* __restrict code,
                 uint16_t* __restrict uncertain, int width) {
  for (int x = 0; x < width; ++x) {
    const Work p = static_cast<Work>(pattern[x]);
    const Work q = static_cast<Work>(inverse[x]);
    const Work ld = direct_level[x];
    const Work lg = global_level[x];
    const Work difference = static_cast<Work>(p - q);
    const Work spread = difference < 0 ? static_cast<Work>(-difference) : difference;
    const uint16_t direct_dominates = ld > lg;
    const uint16_t brighter = p > q;
    const uint16_t on = static_cast<uint16_t>((p > lg) & (q < ld));
    const uint16_t off = static_cast<uint16_t>((p < ld) & (q > lg));
    const uint16_t value = static_cast<uint16_t>((direct_dominates & brighter) | ((1u - direct_dominates) & on));
    const uint16_t distinct = static_cast<uint16_t>((spread >= margin[x]) & ((p < clip) | (q < clip)));
    const uint16_t certain = static_cast<uint16_t>((direct_dominates | (on ^ off)) & distinct);
    code[x] = static_cast<uint16_t>((code[x] << 1) | value);
    uncertain[x] = static_cast<uint16_t>((uncertain[x] << 1) | (certain ^ 1u));
  }
}

// The same where every pixel that matters is lit mostly directly and unclipped (most tiles of a
// bin): the brighter of pattern and inverse wins, and near-ties are uncertain. A third of the
// work of the full rules.
template <typename Pixel, typename Work>
void classifyDirectBit(const Pixel* __restrict pattern, const Pixel* __restrict inverse,
                       const Work* __restrict margin, uint16_t* __restrict code, uint16_t* __restrict uncertain,
                       int width) {
  for (int x = 0; x < width; ++x) {
    const Work difference = static_cast<Work>(static_cast<Work>(pattern[x]) - static_cast<Work>(inverse[x]));
    const Work spread = difference < 0 ? static_cast<Work>(-difference) : difference;
    code[x] = static_cast<uint16_t>((code[x] << 1) | static_cast<uint16_t>(difference > 0));
    uncertain[x] = static_cast<uint16_t>((uncertain[x] << 1) | static_cast<uint16_t>(spread < margin[x]));
  }
}

template <typename Pixel, typename Work>
void classifyBits(const Capture& capture, const AxisLayout& axis, const Tile& tile, const Work clip,
                  RowScratch<Work>& s, AxisRow& row) {
  std::fill(row.code.begin(), row.code.begin() + tile.width, uint16_t{0});
  std::fill(row.uncertain.begin(), row.uncertain.begin() + tile.width, uint16_t{0});
  for (int bit = 0; bit < axis.bits(); ++bit) {
    const Pixel* pattern = imageRow<Pixel>(capture, axis.bit_images[bit], tile);
    const Pixel* inverse = imageRow<Pixel>(capture, axis.inverse_images[bit], tile);
    if (s.direct_light_only) {
      classifyDirectBit<Pixel, Work>(pattern, inverse, s.margin.data(), row.code.data(), row.uncertain.data(),
                                     tile.width);
    } else {
      classifyBit<Pixel, Work>(pattern, inverse, s.direct_level.data(), s.global_level.data(), s.margin.data(), clip,
                               row.code.data(), row.uncertain.data(), tile.width);
    }
  }
}

// N-step phase shift, I_k = A + B cos(phi - 2 pi k / N):
// phi = atan2(sum I_k sin(2 pi k/N), sum I_k cos(2 pi k/N)), B = 2/N |sum I_k e^(2 pi i k/N)|.
template <typename Pixel, typename Work>
void measurePhase(const Capture& capture, const DecodePlan& plan, const AxisLayout& axis, const Tile& tile,
                  RowScratch<Work>& s, AxisRow& row) {
  const int width = tile.width;
  float* __restrict sine_sum = row.phase_offset.data();
  float* __restrict cosine_sum = row.phase_amplitude.data();
  float* __restrict brightest = s.brightest.data();
  std::fill(sine_sum, sine_sum + width, 0.0f);
  std::fill(cosine_sum, cosine_sum + width, 0.0f);
  std::fill(brightest, brightest + width, 0.0f);
  for (std::size_t k = 0; k < axis.phase_images.size(); ++k) {
    const Pixel* __restrict values = imageRow<Pixel>(capture, axis.phase_images[k], tile);
    const float c = plan.phase.cosine[k];
    const float sn = plan.phase.sine[k];
    for (int x = 0; x < width; ++x) {
      const float v = static_cast<float>(values[x]);
      sine_sum[x] += v * sn;
      cosine_sum[x] += v * c;
      brightest[x] = std::max(brightest[x], v);
    }
  }
  const float clip = plan.thresholds.saturation;
  const float to_amplitude = 2.0f / static_cast<float>(axis.phase_images.size());
  const float to_pixels = static_cast<float>(axis.phase_period / (2.0 * M_PI));
  uint8_t* __restrict clipped = row.phase_clipped.data();
  for (int x = 0; x < width; ++x) {
    const float sn = sine_sum[x];
    const float cs = cosine_sum[x];
    sine_sum[x] = fastAtan2(sn, cs) * to_pixels;  // now the phase offset
    cosine_sum[x] = to_amplitude * std::sqrt(sn * sn + cs * cs);  // now the amplitude
    clipped[x] = static_cast<uint8_t>(brightest[x] >= clip);
  }
}

template <typename Pixel, typename Work>
void readAxis(const Capture& capture, const DecodePlan& plan, const AxisLayout& axis, const Tile& tile,
              RowScratch<Work>& s, AxisRow& row) {
  classifyBits<Pixel, Work>(capture, axis, tile, ceilingLevel<Work>(plan.thresholds.saturation), s, row);
  if (axis.hasPhase()) measurePhase<Pixel, Work>(capture, plan, axis, tile, s, row);
}

AxisSample sampleAt(const AxisRow& row, int x, bool with_phase) {
  AxisSample sample;
  sample.code = row.code[x];
  sample.uncertain = row.uncertain[x];
  if (with_phase) {
    sample.phase_offset = row.phase_offset[x];
    sample.phase_amplitude = row.phase_amplitude[x];
    sample.phase_clipped = row.phase_clipped[x] != 0;
  }
  return sample;
}

void resolveSimple(const AxisLayout& axis, const DecodeThresholds& t, AxisRow& row, int width) {
  const int longest = axis.hasPhase() ? t.max_run_with_phase : t.max_run_without_phase;
  resolveSimpleRuns(row.code.data(), row.uncertain.data(), longest, axis.size - 1, row.position.data(),
                    row.verdict.data(), width);
  if (!axis.hasPhase()) return;
  unwrapSimpleRuns(row.code.data(), row.uncertain.data(), row.phase_offset.data(), row.phase_amplitude.data(),
                   row.phase_clipped.data(), axis, t, row.position.data(), row.verdict.data(), width);
}

// The vectorised verdict where it decided, resolveAxis for the rest.
AxisVerdict verdictAt(const AxisRow& row, int x, const AxisLayout& axis, const DecodeThresholds& t) {
  if (row.verdict[x] != kNeedsFullResolution) {
    return {row.position[x], static_cast<PixelStatus>(row.verdict[x])};
  }
  return resolveAxis(sampleAt(row, x, axis.hasPhase()), axis, t);
}

// A code the sensor clipped is reported as Saturated rather than merely uncertain.
PixelStatus blame(PixelStatus status, bool white_clipped) {
  return status == PixelStatus::UncertainCode && white_clipped ? PixelStatus::Saturated : status;
}

template <typename Work>
void resolveTile(const DecodePlan& plan, const Tile& tile, RowScratch<Work>& s, const RowOutput& out) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const AxisLayout& columns = plan.layout.columns;
  const AxisLayout& rows = plan.layout.rows;
  resolveSimple(columns, plan.thresholds, s.columns, tile.width);
  if (rows.present) resolveSimple(rows, plan.thresholds, s.rows, tile.width);
  for (int x = 0; x < tile.width; ++x) {
    out.column[x] = nan;
    if (rows.present) out.row[x] = nan;
    if (!s.lit[x]) {
      out.status[x] = static_cast<uint8_t>(PixelStatus::Unlit);
      continue;
    }
    const AxisVerdict column = verdictAt(s.columns, x, columns, plan.thresholds);
    AxisVerdict row = column;
    if (column.status == PixelStatus::Valid && rows.present) row = verdictAt(s.rows, x, rows, plan.thresholds);
    const PixelStatus status = column.status != PixelStatus::Valid ? column.status : row.status;
    out.status[x] = static_cast<uint8_t>(blame(status, s.white_clipped[x] != 0));
    if (status != PixelStatus::Valid) continue;
    out.column[x] = column.position;
    if (rows.present) out.row[x] = row.position;
  }
}

void resizeAxis(AxisRow& row, int width) {
  row.code.resize(width);
  row.uncertain.resize(width);
  row.phase_offset.resize(width);
  row.phase_amplitude.resize(width);
  row.phase_clipped.resize(width);
  row.position.resize(width);
  row.verdict.resize(width);
}

}  // namespace

template <typename Work>
RowScratch<Work>::RowScratch() {
  const int width = kTilePixels;
  brightest.resize(width);
  darkest.resize(width);
  for (auto* buffer : {&direct_level, &global_level, &margin}) buffer->resize(width);
  lit.resize(width);
  white_clipped.resize(width);
  resizeAxis(columns, width);
  resizeAxis(rows, width);
}

template <typename Pixel>
void decodeTile(const Capture& capture, const DecodePlan& plan, std::size_t offset, int count,
                RowScratch<WorkType<Pixel>>& scratch, const RowOutput& out) {
  using Work = WorkType<Pixel>;
  const Tile tile{offset, count};
  RowOutput tile_out = out;
  tile_out.column += offset;
  if (tile_out.row != nullptr) tile_out.row += offset;
  tile_out.status += offset;
  tile_out.intensity += offset;
  estimateLight<Pixel, Work>(capture, plan, tile, scratch, tile_out);
  readAxis<Pixel, Work>(capture, plan, plan.layout.columns, tile, scratch, scratch.columns);
  if (plan.layout.rows.present) readAxis<Pixel, Work>(capture, plan, plan.layout.rows, tile, scratch, scratch.rows);
  resolveTile(plan, tile, scratch, tile_out);
}

template struct RowScratch<int16_t>;
template struct RowScratch<float>;
template void decodeTile<uint8_t>(const Capture&, const DecodePlan&, std::size_t, int, RowScratch<int16_t>&,
                                  const RowOutput&);
template void decodeTile<uint16_t>(const Capture&, const DecodePlan&, std::size_t, int, RowScratch<float>&,
                                   const RowOutput&);

}  // namespace binpick::reconstruction::detail
