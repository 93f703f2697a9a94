// The decoder's work on one tile: the vectorised passes (tile_kernels.hpp) over every image it
// needs, then the per-pixel resolution. See decoder.hpp for the method.
#include "tile_decoder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "axis_resolution.hpp"
#include "tile_kernels.hpp"

namespace binpick::reconstruction::detail {
namespace {

// A run of consecutive pixels (in row-major order, across image rows) of continuous images.
struct Tile {
  std::size_t offset = 0;  // first pixel
  int width = 0;           // pixels
};

template <typename Pixel>
const Pixel* imageTile(const io::Capture& capture, int image, const Tile& tile) {
  return capture.images[static_cast<std::size_t>(image)].ptr<Pixel>(0) + tile.offset;
}

// L_max and L_min over the high-frequency images, then direct and global light (above black):
// L_d = (L_max - L_min) / (1 - b), L_g = 2 (L_min - b L_max) / (1 - b^2).
template <typename Pixel, typename Work>
void estimateLight(const io::Capture& capture, const DecodePlan& plan, const Tile& tile, TileScratch<Work>& s,
                   const TileOutput& out) {
  const int width = tile.width;
  float* high = s.brightest.data();  // L_max, then L_d
  float* low = s.darkest.data();     // L_min, then L_g
  std::fill(high, high + width, -std::numeric_limits<float>::infinity());
  std::fill(low, low + width, std::numeric_limits<float>::infinity());
  for (int image : plan.separation_images) {
    widenRange<Pixel>(imageTile<Pixel>(capture, image, tile), high, low, width);
  }
  const Pixel* white = imageTile<Pixel>(capture, plan.layout.white, tile);
  const Pixel* black = imageTile<Pixel>(capture, plan.layout.black, tile);
  Work* direct_level = s.direct_level.data();
  Work* global_level = s.global_level.data();
  Work* margin = s.margin.data();
  uint8_t* lit = s.lit.data();
  uint8_t* white_clipped = s.white_clipped.data();
  float* intensity = out.intensity;
  const DecodeThresholds& t = plan.thresholds;
  // L_d into `high` and L_g into `low`, then the levels, margins and flags from them.
  separateLight<Pixel>(black, t.black_level, high, low, width);
  addToBlack<Pixel, Work>(black, high, direct_level, width);
  addToBlack<Pixel, Work>(black, low, global_level, width);
  bitMargins<Pixel, Work>(high, white, black, t, margin, width);
  flagPixels<Pixel>(white, black, high, t, intensity, lit, white_clipped, width);
  s.direct_light_only = directLightOnly(lit, white_clipped, direct_level, global_level, width);
}

template <typename Pixel, typename Work>
void classifyBits(const io::Capture& capture, const AxisLayout& axis, const Tile& tile, const Work clip,
                  TileScratch<Work>& s, TileAxis& buffers) {
  std::fill(buffers.code.begin(), buffers.code.begin() + tile.width, uint16_t{0});
  std::fill(buffers.uncertain.begin(), buffers.uncertain.begin() + tile.width, uint16_t{0});
  for (int bit = 0; bit < axis.bits(); ++bit) {
    const Pixel* pattern = imageTile<Pixel>(capture, axis.bit_images[bit], tile);
    const Pixel* inverse = imageTile<Pixel>(capture, axis.inverse_images[bit], tile);
    if (s.direct_light_only) {
      classifyDirectBit<Pixel, Work>(pattern, inverse, s.margin.data(), buffers.code.data(), buffers.uncertain.data(),
                                     tile.width);
    } else {
      classifyBit<Pixel, Work>(pattern, inverse, s.direct_level.data(), s.global_level.data(), s.margin.data(), clip,
                               buffers.code.data(), buffers.uncertain.data(), tile.width);
    }
  }
}

// N-step phase shift, I_k = A + B cos(phi - 2 pi k / N):
// phi = atan2(sum I_k sin(2 pi k/N), sum I_k cos(2 pi k/N)), B = 2/N |sum I_k e^(2 pi i k/N)|.
template <typename Pixel, typename Work>
void measurePhase(const io::Capture& capture, const DecodePlan& plan, const AxisLayout& axis, const Tile& tile,
                  TileScratch<Work>& s, TileAxis& buffers) {
  const int width = tile.width;
  float* sine_sum = buffers.phase_offset.data();  // the sums first, then the offset and amplitude
  float* cosine_sum = buffers.phase_amplitude.data();
  float* brightest = s.brightest.data();
  std::fill(sine_sum, sine_sum + width, 0.0f);
  std::fill(cosine_sum, cosine_sum + width, 0.0f);
  std::fill(brightest, brightest + width, 0.0f);
  for (std::size_t k = 0; k < axis.phase_images.size(); ++k) {
    accumulatePhase<Pixel>(imageTile<Pixel>(capture, axis.phase_images[k], tile), plan.phase.sine[k],
                           plan.phase.cosine[k], sine_sum, cosine_sum, brightest, width);
  }
  const float to_amplitude = 2.0f / static_cast<float>(axis.phase_images.size());
  const float to_pixels = static_cast<float>(axis.phase_period / (2.0 * M_PI));
  phaseFromSums(brightest, plan.thresholds.saturation, to_amplitude, to_pixels, sine_sum, cosine_sum,
                buffers.phase_clipped.data(), width);
}

// DecodedCapture::column_noise of the tile's pixels, from the amplitudes measurePhase left.
template <typename Pixel>
void estimateColumnNoise(const io::Capture& capture, const DecodePlan& plan, const Tile& tile, TileAxis& buffers) {
  const DecodeThresholds& t = plan.thresholds;
  phaseNoise<Pixel>(imageTile<Pixel>(capture, plan.layout.white, tile),
                    imageTile<Pixel>(capture, plan.layout.black, tile), buffers.phase_amplitude.data(),
                    t.column_noise_read, t.column_noise_gain, buffers.position_noise.data(), tile.width);
}

template <typename Pixel, typename Work>
void readAxis(const io::Capture& capture, const DecodePlan& plan, const AxisLayout& axis, const Tile& tile,
              TileScratch<Work>& s, TileAxis& buffers) {
  classifyBits<Pixel, Work>(capture, axis, tile, ceilingLevel<Work>(plan.thresholds.saturation), s, buffers);
  if (axis.hasPhase()) measurePhase<Pixel, Work>(capture, plan, axis, tile, s, buffers);
}

AxisSample sampleAt(const TileAxis& buffers, int x, bool with_phase) {
  AxisSample sample;
  sample.code = buffers.code[x];
  sample.uncertain = buffers.uncertain[x];
  if (with_phase) {
    sample.phase_offset = buffers.phase_offset[x];
    sample.phase_amplitude = buffers.phase_amplitude[x];
    sample.phase_clipped = buffers.phase_clipped[x] != 0;
  }
  return sample;
}

void resolveSimple(const AxisLayout& axis, const DecodeThresholds& t, TileAxis& buffers, int width) {
  resolveSimpleRuns(buffers.code.data(), buffers.uncertain.data(), axis, t, buffers.position.data(),
                    buffers.verdict.data(), width);
  if (!axis.hasPhase()) return;
  unwrapSimpleRuns(buffers.code.data(), buffers.uncertain.data(), buffers.phase_offset.data(),
                   buffers.phase_amplitude.data(), buffers.phase_clipped.data(), axis, t, buffers.position.data(),
                   buffers.verdict.data(), width);
}

// The vectorised verdict where it decided, resolveAxis for the rest.
AxisVerdict verdictAt(const TileAxis& buffers, int x, const AxisLayout& axis, const DecodeThresholds& t) {
  if (buffers.verdict[x] != kNeedsFullResolution) {
    return {buffers.position[x], static_cast<PixelStatus>(buffers.verdict[x])};
  }
  return resolveAxis(sampleAt(buffers, x, axis.hasPhase()), axis, t);
}

// The phase of a pixel some of whose steps the sensor clipped, from the others (at least three):
// least squares of I_k = A + C cos(t_k) + S sin(t_k) over the unclipped steps, phi = atan2(S, C).
// A highlight often clips only the brightest step or two. False when too few are left.
template <typename Pixel>
bool phaseFromUnclippedSteps(const io::Capture& capture, const DecodePlan& plan, const AxisLayout& axis,
                             std::size_t pixel, AxisSample& sample) {
  double m[3][3] = {}, v[3] = {};
  int used = 0;
  for (std::size_t k = 0; k < axis.phase_images.size(); ++k) {
    const float value =
        static_cast<float>(capture.images[static_cast<std::size_t>(axis.phase_images[k])].ptr<Pixel>(0)[pixel]);
    if (value >= plan.thresholds.saturation) continue;
    const double basis[3] = {1.0, plan.phase.cosine[k], plan.phase.sine[k]};
    for (int i = 0; i < 3; ++i) {
      v[i] += basis[i] * value;
      for (int j = 0; j < 3; ++j) m[i][j] += basis[i] * basis[j];
    }
    ++used;
  }
  if (used < 3) return false;
  const cv::Matx33d normal(m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]);
  cv::Vec3d solution;
  if (!cv::solve(normal, cv::Vec3d(v[0], v[1], v[2]), solution, cv::DECOMP_LU)) return false;
  const double to_pixels = axis.phase_period / (2.0 * M_PI);
  sample.phase_offset = static_cast<float>(std::atan2(solution[2], solution[1]) * to_pixels);
  sample.phase_amplitude = static_cast<float>(std::hypot(solution[1], solution[2]));
  sample.phase_clipped = false;
  return true;
}

// Without a phase, the Gray code alone when it leaves a run as short as a capture without phase
// would accept: its centre, to half a projector pixel.
AxisVerdict grayCodeAlone(const AxisSample& sample, const AxisLayout& axis, const DecodeThresholds& t) {
  if (__builtin_popcount(sample.uncertain) > kMaxUncertainBits) return {0.0f, PixelStatus::Saturated};
  const CodeRun run = codesOfWords(candidateRun(sample.code, sample.uncertain), axis);
  const auto size = static_cast<unsigned>(axis.size);
  if (run.last - run.first + 1 > static_cast<unsigned>(t.max_run_without_phase) || run.first >= size) {
    return {0.0f, PixelStatus::Saturated};
  }
  return {0.5f * static_cast<float>(run.first + std::min(run.last, size - 1)), PixelStatus::Valid};
}

// verdictAt, with a clipped phase recovered from the steps that were not clipped, or else the
// Gray code alone.
template <typename Pixel>
AxisVerdict verdictWithClipping(const io::Capture& capture, const DecodePlan& plan, const Tile& tile,
                                const TileAxis& buffers, int x, const AxisLayout& axis) {
  const AxisVerdict verdict = verdictAt(buffers, x, axis, plan.thresholds);
  if (verdict.status != PixelStatus::Saturated || !axis.hasPhase() || buffers.phase_clipped[x] == 0) return verdict;
  AxisSample sample = sampleAt(buffers, x, true);
  if (!phaseFromUnclippedSteps<Pixel>(capture, plan, axis, tile.offset + static_cast<std::size_t>(x), sample)) {
    return grayCodeAlone(sample, axis, plan.thresholds);
  }
  return resolveAxis(sample, axis, plan.thresholds);
}

// A phase that can be unwrapped by other means than the Gray code: measured, strong enough and
// unclipped.
bool usablePhase(const AxisLayout& axis, const TileAxis& buffers, int x, const DecodeThresholds& t) {
  return axis.hasPhase() && buffers.phase_clipped[x] == 0 && buffers.phase_amplitude[x] >= t.min_phase_amplitude;
}

UnwrapCandidate unwrapCandidate(const TileAxis& columns, int x, std::size_t tile_offset, const AxisVerdict& row,
                                bool rows_present) {
  UnwrapCandidate c;
  c.pixel = tile_offset + static_cast<std::size_t>(x);
  c.phase_offset = columns.phase_offset[x];
  c.code = columns.code[x];
  c.uncertain = columns.uncertain[x];
  c.noise = columns.position_noise[x];
  c.row = row.position;
  c.row_status = rows_present ? row.status : PixelStatus::Valid;
  return c;
}

// A code the sensor clipped is reported as Saturated rather than merely uncertain.
PixelStatus blame(PixelStatus status, bool white_clipped) {
  return status == PixelStatus::UncertainCode && white_clipped ? PixelStatus::Saturated : status;
}

template <typename Pixel, typename Work>
void resolveTile(const io::Capture& capture, const DecodePlan& plan, const Tile& tile, TileScratch<Work>& s,
                 const TileOutput& out) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const AxisLayout& columns = plan.layout.columns;
  const AxisLayout& rows = plan.layout.rows;
  resolveSimple(columns, plan.thresholds, s.columns, tile.width);
  if (rows.present) resolveSimple(rows, plan.thresholds, s.rows, tile.width);
  for (int x = 0; x < tile.width; ++x) {
    out.column[x] = nan;
    if (rows.present) out.row[x] = nan;
    if (out.column_noise != nullptr) out.column_noise[x] = nan;
    if (!s.lit[x]) {
      out.status[x] = static_cast<uint8_t>(PixelStatus::Unlit);
      continue;
    }
    const AxisVerdict column = verdictWithClipping<Pixel>(capture, plan, tile, s.columns, x, columns);
    const bool candidate = out.candidates != nullptr && column.status == PixelStatus::UncertainCode &&
                           s.white_clipped[x] == 0 && usablePhase(columns, s.columns, x, plan.thresholds);
    AxisVerdict row = column;
    if ((column.status == PixelStatus::Valid || candidate) && rows.present) {
      row = verdictWithClipping<Pixel>(capture, plan, tile, s.rows, x, rows);
    }
    if (candidate) out.candidates->push_back(unwrapCandidate(s.columns, x, tile.offset, row, rows.present));
    const bool column_alone = row.status != PixelStatus::Valid && plan.thresholds.keep_column_without_row;
    const PixelStatus status = column.status != PixelStatus::Valid ? column.status
                               : column_alone                      ? PixelStatus::Valid
                                                                   : row.status;
    out.status[x] = static_cast<uint8_t>(blame(status, s.white_clipped[x] != 0));
    if (status != PixelStatus::Valid) continue;
    out.column[x] = column.position;
    if (out.column_noise != nullptr) out.column_noise[x] = s.columns.position_noise[x];
    if (rows.present && row.status == PixelStatus::Valid) out.row[x] = row.position;
  }
}

void resizeAxis(TileAxis& buffers, int width) {
  buffers.code.resize(width);
  buffers.uncertain.resize(width);
  buffers.phase_offset.resize(width);
  buffers.phase_amplitude.resize(width);
  buffers.phase_clipped.resize(width);
  buffers.position_noise.resize(width);
  buffers.position.resize(width);
  buffers.verdict.resize(width);
}

}  // namespace

template <typename Work>
TileScratch<Work>::TileScratch() {
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
void decodeTile(const io::Capture& capture, const DecodePlan& plan, std::size_t offset, int count,
                TileScratch<WorkType<Pixel>>& scratch, const TileOutput& out) {
  using Work = WorkType<Pixel>;
  const Tile tile{offset, count};
  TileOutput tile_out = out;
  tile_out.column += offset;
  if (tile_out.row != nullptr) tile_out.row += offset;
  if (tile_out.column_noise != nullptr) tile_out.column_noise += offset;
  tile_out.status += offset;
  tile_out.intensity += offset;
  estimateLight<Pixel, Work>(capture, plan, tile, scratch, tile_out);
  readAxis<Pixel, Work>(capture, plan, plan.layout.columns, tile, scratch, scratch.columns);
  if (out.column_noise != nullptr) estimateColumnNoise<Pixel>(capture, plan, tile, scratch.columns);
  if (plan.layout.rows.present) readAxis<Pixel, Work>(capture, plan, plan.layout.rows, tile, scratch, scratch.rows);
  resolveTile<Pixel, Work>(capture, plan, tile, scratch, tile_out);
}

template struct TileScratch<int16_t>;
template struct TileScratch<float>;
template void decodeTile<uint8_t>(const io::Capture&, const DecodePlan&, std::size_t, int, TileScratch<int16_t>&,
                                  const TileOutput&);
template void decodeTile<uint16_t>(const io::Capture&, const DecodePlan&, std::size_t, int, TileScratch<float>&,
                                   const TileOutput&);

}  // namespace binpick::reconstruction::detail
