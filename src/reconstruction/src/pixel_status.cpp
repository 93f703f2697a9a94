// Names and counts of the per-pixel reconstruction verdicts.
#include "binpick/reconstruction/pixel_status.hpp"

#include "binpick/io/error.hpp"

namespace binpick::reconstruction {
namespace {

// Indexed by the enum's value; the static_assert keeps the two in step.
constexpr const char* kNames[] = {
    "valid",           "unlit",        "saturated",       "uncertain_code",
    "code_out_of_range", "phase_mismatch", "inconsistent",  "no_intersection",
    "out_of_depth_range", "outside_crop",  "speckle",
};
static_assert(sizeof(kNames) / sizeof(kNames[0]) == kPixelStatusCount);
static_assert(static_cast<std::size_t>(PixelStatus::Speckle) + 1 == kPixelStatusCount);

}  // namespace

const char* statusName(PixelStatus status) {
  const auto index = static_cast<std::size_t>(status);
  // A value cast in from a corrupt image must not index past the table.
  if (index >= kPixelStatusCount) return "unknown";
  return kNames[index];
}

StatusCounts countStatuses(const cv::Mat& status) {
  if (status.type() != CV_8UC1) {
    throw Error("countStatuses: the status image must be CV_8UC1 (got type " +
                std::to_string(status.type()) + ")");
  }
  StatusCounts counts{};
  for (int y = 0; y < status.rows; ++y) {
    const uchar* row = status.ptr<uchar>(y);
    for (int x = 0; x < status.cols; ++x) {
      if (row[x] >= kPixelStatusCount) {
        throw Error("countStatuses: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                    ") holds " + std::to_string(row[x]) + ", which is no PixelStatus");
      }
      ++counts[row[x]];
    }
  }
  return counts;
}

}  // namespace binpick::reconstruction
