#pragma once
// Why a camera pixel has (or has no) 3D point. Every stage of reconstruction writes its verdict
// into one CV_8UC1 status image, so a user can see where and why the cloud has holes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

namespace binpick::reconstruction {

enum class PixelStatus : uint8_t {
  Valid = 0,
  // Decoding.
  Unlit,           // too little projector light: projector shadow, nothing seen, too dark
  Saturated,       // the sensor clipped the images needed to decode it
  UncertainCode,   // Gray-code bits that cannot be classified leave more than one candidate
  CodeOutOfRange,  // the code names a column/row outside the projector image
  PhaseMismatch,   // phase too weak, or it disagrees with the Gray code
  // Triangulation.
  Inconsistent,    // the decoded row does not lie on the column's epipolar curve
  NoIntersection,  // the camera ray and the projector's light do not meet in front of both
  // Filters.
  OutOfDepthRange,  // outside the configured depth range
  OutsideCrop,      // outside the configured crop box
  Speckle,          // part of a small isolated patch of points
  DepthEdge,        // stands off its neighbours' surface: a mixed pixel at a depth edge
};
constexpr std::size_t kPixelStatusCount = 12;

// "valid", "unlit", "saturated", ... (snake case, used in logs and JSON).
const char* statusName(PixelStatus status);

// The stage that gives a status and the `reconstruction:` settings that govern how many pixels
// get it (config/reconstruction.yaml), e.g. {"decode", "decode.min_contrast, decode.min_direct"}:
// what to look at when a real rig's capture loses pixels to it.
struct StatusOrigin {
  const char* stage;
  const char* settings;
};
StatusOrigin statusOrigin(PixelStatus status);

// How many pixels of a CV_8UC1 status image carry each status, indexed by the enum's value.
using StatusCounts = std::array<std::size_t, kPixelStatusCount>;
StatusCounts countStatuses(const cv::Mat& status);

}  // namespace binpick::reconstruction
