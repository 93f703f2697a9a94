#pragma once
// Optional clean-up of an organized cloud after triangulation: a depth range, a crop box and the
// removal of small isolated patches (speckle: stray points from misdecoded pixels, usually at
// depth edges and on dark or glossy spots). Removed points become NaN and their pixels get the
// status that removed them. Stateless: thread-safe.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "binpick/io/point_cloud.hpp"

namespace binpick::reconstruction {

struct CloudFilterParams {
  // Camera z range, metres; 0 / infinity keep everything.
  double min_depth = 0.0;
  double max_depth = 1e9;
  // Axis-aligned box in the camera frame, metres; an empty box (the default) keeps everything.
  Eigen::AlignedBox3d crop;
  // Speckle removal: 4-connected neighbours belong to one patch when their camera z differs by
  // at most speckle_max_step; patches of fewer than speckle_min_pixels points are removed.
  // speckle_min_pixels = 0 turns it off.
  double speckle_max_step = 0.002;  // metres
  int speckle_min_pixels = 50;
  int threads = 0;        // 0: all cores
  void validate() const;  // throws core::Error naming the field
};

// `cloud` must be organized and `status` CV_8UC1 of its size (throws core::Error otherwise).
void filterCloud(io::PointCloud& cloud, cv::Mat& status, const CloudFilterParams& params);

}  // namespace binpick::reconstruction
