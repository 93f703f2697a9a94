#include "line_of_sight.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "binpick/core/error.hpp"

namespace binpick::estimation {
namespace {

// A wide-angle or stray cloud must not make the map huge: past this many cells they grow.
constexpr double kMaxCells = 4.0e6;

bool inFront(const Eigen::Vector3f& p) { return p.allFinite() && p.z() > 0.0f; }

}  // namespace

LineOfSightMap::LineOfSightMap(const std::vector<Eigen::Vector3f>& points, float cell_size, float reference_depth) {
  if (!(cell_size > 0.0f) || !(reference_depth > 0.0f) || !std::isfinite(cell_size / reference_depth)) {
    throw core::Error("line of sight map: cell size and reference depth must be positive and finite");
  }
  Eigen::Vector2f low = Eigen::Vector2f::Constant(std::numeric_limits<float>::infinity());
  Eigen::Vector2f high = -low;
  for (const Eigen::Vector3f& p : points) {
    if (!inFront(p)) continue;
    const Eigen::Vector2f direction(p.x() / p.z(), p.y() / p.z());
    low = low.cwiseMin(direction);
    high = high.cwiseMax(direction);
  }
  if (!(low.allFinite() && high.allFinite())) return;  // nothing in front of the camera
  cell_ = cell_size / reference_depth;
  const Eigen::Vector2f extent = high - low;
  const double cells = (static_cast<double>(extent.x()) / cell_ + 1.0) * (static_cast<double>(extent.y()) / cell_ + 1.0);
  if (cells > kMaxCells) cell_ *= static_cast<float>(std::sqrt(cells / kMaxCells));
  origin_ = low;
  width_ = static_cast<int>(extent.x() / cell_) + 1;
  height_ = static_cast<int>(extent.y() / cell_) + 1;
  depth_.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), kUnseen);
  for (const Eigen::Vector3f& p : points) {
    if (!inFront(p)) continue;
    const auto u = std::min(static_cast<int>((p.x() / p.z() - origin_.x()) / cell_), width_ - 1);
    const auto v = std::min(static_cast<int>((p.y() / p.z() - origin_.y()) / cell_), height_ - 1);
    float& nearest = depth_[static_cast<std::size_t>(v) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(u)];
    nearest = std::min(nearest, p.z());
  }
}

}  // namespace binpick::estimation
