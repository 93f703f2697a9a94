#pragma once
// What the camera saw along each line of sight: a coarse range image over viewing directions
// (x/z, y/z), each cell holding the smallest depth of the measured points in it. A pose whose model
// points lie well in front of that depth claims that the camera saw through the part: free space
// the sensor measured (scene-consistent verification, see detector.hpp). Built from every finite
// point, cropped or not (the floor and the walls were seen too); works for organized and
// unorganized clouds alike. Immutable after construction: thread-safe.
#include <Eigen/Core>
#include <limits>
#include <vector>

namespace binpick::estimation {

class LineOfSightMap {
 public:
  static constexpr float kUnseen = std::numeric_limits<float>::infinity();

  LineOfSightMap() = default;
  // `cell_size` is the side of a cell at `reference_depth` (model units); points at z <= 0 or not
  // finite are ignored.
  LineOfSightMap(const std::vector<Eigen::Vector3f>& points, float cell_size, float reference_depth);

  // The nearest measured depth along the direction of `p`, or kUnseen when nothing was measured
  // there (projector shadow, a hole, outside the image).
  float measuredDepth(const Eigen::Vector3f& p) const {
    if (!(p.z() > 0.0f)) return kUnseen;
    const float u = (p.x() / p.z() - origin_.x()) / cell_;
    const float v = (p.y() / p.z() - origin_.y()) / cell_;
    // Compared as floats before the cast: NaN and huge values never reach an index.
    if (!(u >= 0.0f && v >= 0.0f && u < static_cast<float>(width_) && v < static_cast<float>(height_))) return kUnseen;
    return depth_[static_cast<std::size_t>(v) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(u)];
  }

  // True when `p` lies more than `tolerance` in front of the measured surface along its line of
  // sight: the camera would have seen it there and saw something farther instead.
  bool seenThrough(const Eigen::Vector3f& p, float tolerance) const {
    const float measured = measuredDepth(p);
    return measured != kUnseen && p.z() + tolerance < measured;
  }

  // The same for a surface point with outward normal `n`, counted only where the camera would
  // have measured it: facing the camera within kMaxMeasuredAngleDeg. A grazing side wall lies on
  // the part's silhouette, over whatever is behind it, even at the true pose.
  static constexpr float kMaxMeasuredAngleDeg = 75.0f;
  bool seenThrough(const Eigen::Vector3f& p, const Eigen::Vector3f& n, float tolerance) const {
    return measurable(p, n) && seenThrough(p, tolerance);
  }
  // Whether the camera would measure a surface point at `p` with outward normal `n`: it faces the
  // camera within kMaxMeasuredAngleDeg.
  static bool measurable(const Eigen::Vector3f& p, const Eigen::Vector3f& n) {
    const float min_facing = 0.258819f;  // cos(kMaxMeasuredAngleDeg)
    return -n.dot(p) >= min_facing * p.norm();
  }

  bool empty() const { return depth_.empty(); }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  Eigen::Vector2f origin_ = Eigen::Vector2f::Zero();  // smallest (x/z, y/z)
  float cell_ = 1.0f;                                 // cell side in x/z units
  int width_ = 0, height_ = 0;
  std::vector<float> depth_;  // row-major, kUnseen where empty
};

}  // namespace binpick::estimation
