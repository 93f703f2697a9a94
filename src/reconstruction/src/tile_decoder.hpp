#pragma once
// Decoding a tile: a run of consecutive pixels of the (continuous) images. Loops over the whole
// tile for every image it needs (vectorised by the compiler), then a short per-pixel pass that
// turns bits and phase into a projector coordinate. Internal to the decoder; each thread owns its
// TileScratch.
#include <cstdint>
#include <type_traits>
#include <vector>

#include "binpick/io/capture.hpp"
#include "decode_plan.hpp"
#include "neighbour_unwrap.hpp"

namespace binpick::reconstruction::detail {

// The arithmetic of the bit classification: 16-bit integers for 8-bit images (exact, and twice
// the SIMD lanes of float), float for 16-bit images.
// Pixels per tile: long enough runs of each image for the hardware prefetcher to stream (a few
// kilobytes), short enough for the tile's per-pixel buffers to stay in the L2 cache.
constexpr int kTilePixels = 4096;

template <typename Pixel>
using WorkType = std::conditional_t<std::is_same_v<Pixel, uint8_t>, int16_t, float>;

// One coded axis (projector columns or projector rows) over a tile: one entry per pixel.
struct TileAxis {
  // Gray codes have at most 16 bits: projectors are at most 65536 pixels wide (PatternSetSpec).
  std::vector<uint16_t> code;       // the Gray code read, most significant bit first
  std::vector<uint16_t> uncertain;  // 1 for every bit that could not be classified
  std::vector<float> phase_offset;  // projector pixels, the position within one period
  std::vector<float> phase_amplitude;
  std::vector<uint8_t> phase_clipped;
  std::vector<float> position_noise;  // projector pixels (columns, when estimated)
  std::vector<float> position;        // resolveSimpleCodes' results
  std::vector<uint8_t> verdict;
};

template <typename Work>
struct TileScratch {
  std::vector<float> brightest;  // L_max, then the brightest phase image (clipping)
  std::vector<float> darkest;    // L_min
  // Raw counts a bit is compared with: black + L_d and black + L_g (Moreno & Taubin), and the
  // smallest pattern-inverse difference that classifies it.
  std::vector<Work> direct_level;
  std::vector<Work> global_level;
  std::vector<Work> margin;
  std::vector<uint8_t> lit;
  std::vector<uint8_t> white_clipped;
  bool direct_light_only = false;  // the tile's lit pixels need only the simple bit rule
  TileAxis columns;
  TileAxis rows;
  TileScratch();  // sized for one tile
};

struct TileOutput {  // pixel 0 of each output image
  float* column = nullptr;
  float* row = nullptr;  // projector rows; null when the capture has no row codes
  uint8_t* status = nullptr;
  float* intensity = nullptr;
  float* column_noise = nullptr;  // null when not estimated
  // Where the tile adds its UncertainCode pixels with a usable phase, for unwrapFromNeighbours;
  // null: not collected.
  std::vector<UnwrapCandidate>* candidates = nullptr;
};

// Decodes pixels [offset, offset + count) (row-major, count <= kTilePixels). Pixel is uint8_t or
// uint16_t, matching the capture's bit depth; every image must be continuous. `out` points at
// pixel 0 of the output images.
template <typename Pixel>
void decodeTile(const io::Capture& capture, const DecodePlan& plan, std::size_t offset, int count,
                TileScratch<WorkType<Pixel>>& scratch, const TileOutput& out);

}  // namespace binpick::reconstruction::detail
