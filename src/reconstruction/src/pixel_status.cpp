// Names and counts of the per-pixel reconstruction verdicts.
#include "binpick/reconstruction/pixel_status.hpp"

#include <array>

#include "binpick/core/error.hpp"

namespace binpick::reconstruction {
namespace {

// Indexed by the enum's value; the static_assert keeps the two in step.
constexpr const char* kNames[] = {
    "valid",        "unlit",           "saturated",          "uncertain_code", "code_out_of_range", "phase_mismatch",
    "inconsistent", "no_intersection", "out_of_depth_range", "outside_crop",   "speckle",           "depth_edge",
};
static_assert(sizeof(kNames) / sizeof(kNames[0]) == kPixelStatusCount);

constexpr StatusOrigin kOrigins[] = {
    {"", ""},
    {"decode",
     "decode.min_contrast, decode.min_direct, decode.projector_black_level, decode.stripe_reach, "
     "decode.max_code_run_along_stripe"},
    {"decode", "decode.max_saturated_fraction (the camera's exposure)"},
    {"decode",
     "decode.bit_margin, decode.min_bit_difference, decode.bit_noise_sigmas, decode.max_code_run_without_phase, "
     "decode.max_code_run_with_phase, decode.min_unwrap_neighbours, decode.stripe_reach, "
     "decode.max_code_run_along_stripe"},
    {"decode", "the projector size and code step of the capture's pattern set"},
    {"decode", "decode.min_phase_amplitude, decode.max_phase_gray_disagreement"},
    {"triangulation",
     "triangulation.max_epipolar_error, triangulation.max_calibration_residual, "
     "triangulation.column_when_row_inconsistent (and the calibration)"},
    {"triangulation", "the calibration (rays that meet behind a device or nowhere)"},
    {"filter", "filter.min_depth, filter.max_depth"},
    {"filter", "filter.crop"},
    {"filter", "filter.speckle_max_step, filter.speckle_min_pixels, filter.min_step_in_codes"},
    {"filter",
     "filter.edge_max_jump, filter.edge_min_support, filter.edge_side_reach, filter.min_step_in_codes, "
     "filter.median_reach, filter.median_max_pull"},
};
static_assert(sizeof(kOrigins) / sizeof(kOrigins[0]) == kPixelStatusCount);
static_assert(static_cast<std::size_t>(PixelStatus::DepthEdge) + 1 == kPixelStatusCount);

}  // namespace

const char* statusName(PixelStatus status) {
  const auto index = static_cast<std::size_t>(status);
  // A value cast in from a corrupt image must not index past the table.
  if (index >= kPixelStatusCount) return "unknown";
  return kNames[index];
}

StatusOrigin statusOrigin(PixelStatus status) {
  const auto index = static_cast<std::size_t>(status);
  if (index >= kPixelStatusCount) return {"", ""};
  return kOrigins[index];
}

StatusCounts countStatuses(const cv::Mat& status) {
  if (status.type() != CV_8UC1) {
    throw core::Error("countStatuses: the status image must be CV_8UC1 (got type " + std::to_string(status.type()) +
                      ")");
  }
  // A full byte histogram without a check per pixel, in four interleaved copies so that
  // increments of runs of equal values do not wait on each other; the check comes after.
  std::array<std::array<std::size_t, 256>, 4> histograms{};
  for (int y = 0; y < status.rows; ++y) {
    const uchar* row = status.ptr<uchar>(y);
    int x = 0;
    for (; x + 4 <= status.cols; x += 4) {
      ++histograms[0][row[x]];
      ++histograms[1][row[x + 1]];
      ++histograms[2][row[x + 2]];
      ++histograms[3][row[x + 3]];
    }
    for (; x < status.cols; ++x) ++histograms[0][row[x]];
  }
  StatusCounts counts{};
  for (std::size_t value = 0; value < 256; ++value) {
    const std::size_t count = histograms[0][value] + histograms[1][value] + histograms[2][value] + histograms[3][value];
    if (count == 0) continue;
    if (value >= kPixelStatusCount) {
      throw core::Error("countStatuses: " + std::to_string(count) + " pixels hold " + std::to_string(value) +
                        ", which is no PixelStatus");
    }
    counts[value] = count;
  }
  return counts;
}

}  // namespace binpick::reconstruction
