// MeasuredScene (the thinned, column-indexed cloud) and the tool's collision test against it.
#include "binpick/picking/tool_collision.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "binpick/core/error.hpp"
#include "rigid.hpp"
#include "tool_volume.hpp"

namespace binpick::picking {
namespace {

// Calibrated transforms come from files with a few decimals.
constexpr double kPoseTolerance = 1e-5;
// More columns than this (a cloud wider than 3 m at 3 mm) and the columns grow instead: bounded
// memory.
constexpr double kMaxCells = 1 << 20;
// Nor more than this along either side, however elongated the cloud: the cells stay bounded (at
// most kMaxCells + 2 kMaxColumns) and the column counts far inside an int.
constexpr double kMaxColumns = 1 << 14;
// Pixels sampled to estimate an organized cloud's point spacing.
constexpr int kSpacingSamples = 4000;
// Points sampled to find the bulk of the cloud in base xy (OutlierWindow).
constexpr std::size_t kBulkSamples = 4096;
// Metres beyond the bulk of the cloud that a point may lie, at the least, and still be indexed:
// further than any tool reaches past the bin, which lies within the bulk.
constexpr double kMinOutlierReach = 1.0;

// The median distance between horizontally neighbouring valid pixels; 0 when none are found.
double medianPixelSpacing(const io::PointCloud& cloud) {
  const std::size_t count = cloud.points.size();
  const std::size_t step = std::max<std::size_t>(1, count / kSpacingSamples);
  std::vector<float> spacings;
  for (std::size_t i = 0; i + 1 < count; i += step) {
    if ((i + 1) % static_cast<std::size_t>(cloud.width) == 0) continue;  // last column
    const Eigen::Vector3f& a = cloud.points[i];
    const Eigen::Vector3f& b = cloud.points[i + 1];
    if (a.allFinite() && b.allFinite()) spacings.push_back((a - b).norm());
  }
  if (spacings.empty()) return 0.0;
  auto middle = spacings.begin() + static_cast<std::ptrdiff_t>(spacings.size() / 2);
  std::nth_element(spacings.begin(), middle, spacings.end());
  return *middle;
}

// Pixel stride keeping strided neighbours about step / 2 apart: dense enough that thinning to
// `step` still sees every surface, sparse enough to transform only a fraction of 1.3 MP.
int pixelStride(const io::PointCloud& cloud, double step) {
  if (!cloud.isOrganized()) return 1;
  const double spacing = medianPixelSpacing(cloud);
  if (!(spacing > 0.0)) return 1;
  return std::max(1, static_cast<int>(std::floor(0.5 * step / spacing)));
}

// The base xy region the columns may cover: the 1st to 99th percentile of a sample of the points,
// grown by that spread (at least kMinOutlierReach) each side. A stray point of the reconstruction
// far beyond it (a mismatched stripe, a reflection) would otherwise stretch the grid: with the
// cells bounded, each would grow and the thinning coarsen with it. Empty when the cloud has no
// valid point.
struct OutlierWindow {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  bool holds(const Eigen::Vector3f& p) const {  // false for NaN
    return p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y();
  }
};

OutlierWindow outlierWindow(const io::PointCloud& cloud, const Eigen::Isometry3f& T_base_camera) {
  const std::size_t count = cloud.points.size();
  const std::size_t step = std::max<std::size_t>(1, count / kBulkSamples);
  std::array<std::vector<double>, 2> axes;
  for (std::size_t i = 0; i < count; i += step) {
    if (!cloud.points[i].allFinite()) continue;
    const Eigen::Vector3f p = T_base_camera * cloud.points[i];
    if (!p.allFinite()) continue;
    axes[0].push_back(p.x());
    axes[1].push_back(p.y());
  }
  OutlierWindow window;
  if (axes[0].empty()) return window;
  for (int a = 0; a < 2; ++a) {
    std::vector<double>& values = axes[static_cast<std::size_t>(a)];
    std::sort(values.begin(), values.end());
    // Symmetric ranks, so that a few samples leave out as many at each end.
    const std::size_t upper = static_cast<std::size_t>(std::floor(0.99 * static_cast<double>(values.size() - 1)));
    const double q_lo = std::min(values[values.size() - 1 - upper], values[upper]);
    const double q_hi = std::max(values[values.size() - 1 - upper], values[upper]);
    const double reach = std::max(q_hi - q_lo, kMinOutlierReach);
    window.lo[a] = q_lo - reach;
    window.hi[a] = q_hi + reach;
  }
  return window;
}

// Calls visit(base point) for every valid point of the strided cloud. Run once per pass of the
// indexing instead of keeping a transformed copy: a fresh megabyte costs more in page faults than
// transforming the points again.
template <typename Visit>
void forEachBasePoint(const io::PointCloud& cloud, const Eigen::Isometry3f& T_base_camera, int stride, Visit&& visit) {
  const auto visitValid = [&](const Eigen::Vector3f& p) {
    if (p.allFinite()) visit(T_base_camera * p);
  };
  if (stride == 1) {
    for (const Eigen::Vector3f& p : cloud.points) visitValid(p);
    return;
  }
  const auto width = static_cast<std::size_t>(cloud.width);
  for (int row = 0; row < cloud.height; row += stride) {
    const std::size_t row_start = static_cast<std::size_t>(row) * width;
    for (int column = 0; column < cloud.width; column += stride) {
      visitValid(cloud.points[row_start + static_cast<std::size_t>(column)]);
    }
  }
}

}  // namespace

void MeasuredSceneParams::validate() const {
  core::requireField(std::isfinite(thin_step) && thin_step >= 1e-4, "measured_scene", "thin_step", ">= 0.0001 m",
                     thin_step);
}

MeasuredScene::MeasuredScene(const io::PointCloud& cloud, const Eigen::Isometry3d& T_base_camera,
                             const MeasuredSceneParams& params) {
  params.validate();
  if (!isRigidPose(T_base_camera, kPoseTolerance))
    throw core::Error("measured scene: T_base_camera is not a rigid pose");
  const double step = params.thin_step;
  const int stride = pixelStride(cloud, step);
  const Eigen::Isometry3f transform = T_base_camera.cast<float>();
  const OutlierWindow window = outlierWindow(cloud, transform);
  // Every pass sees the same points: those inside the window. Usually that is all of them, and
  // the passes skip the test.
  bool outliers = false;
  const auto forEach = [&](auto&& visit) {
    if (!outliers) return forEachBasePoint(cloud, transform, stride, visit);
    forEachBasePoint(cloud, transform, stride, [&](const Eigen::Vector3f& p) {
      if (window.holds(p)) visit(p);
    });
  };

  // Pass 1: the grid over the points' xy extent, again without the outliers when there are any
  // (a point that went NaN in the base frame, past the float range, is one).
  Eigen::Vector2f lo, hi;
  bool nan = false;
  const auto findExtent = [&] {
    lo = Eigen::Vector2f::Constant(std::numeric_limits<float>::infinity());
    hi = -lo;
    forEach([&](const Eigen::Vector3f& p) {
      lo = lo.cwiseMin(p.head<2>());
      hi = hi.cwiseMax(p.head<2>());
      nan |= std::isnan(p.x()) || std::isnan(p.y());
    });
  };
  findExtent();
  const auto inWindow = [&](const Eigen::Vector2f& corner) { return window.holds({corner.x(), corner.y(), 0.0f}); };
  if (nan || (lo.x() <= hi.x() && !(inWindow(lo) && inWindow(hi)))) {
    outliers = true;
    findExtent();
  }
  if (!(lo.x() <= hi.x())) lo = hi = Eigen::Vector2f::Zero();  // no valid point
  // In double: the difference of two finite floats may not be a finite float.
  const Eigen::Vector2d extent = hi.cast<double>() - lo.cast<double>();
  cell_size_ = std::max({step, std::sqrt(extent.x() * extent.y() / kMaxCells), extent.maxCoeff() / kMaxColumns});
  origin_ = lo.cast<double>();
  columns_ = static_cast<int>(extent.x() / cell_size_) + 1;
  rows_ = static_cast<int>(extent.y() / cell_size_) + 1;
  const auto cellOf = [&](const Eigen::Vector3f& p) {
    const auto x = std::min(columns_ - 1, static_cast<int>((p.x() - origin_.x()) / cell_size_));
    const auto y = std::min(rows_ - 1, static_cast<int>((p.y() - origin_.y()) / cell_size_));
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(x);
  };

  // Passes 2 and 3: a counting sort into the columns.
  const std::size_t cells = static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_);
  cell_start_.assign(cells + 1, 0);
  forEach([&](const Eigen::Vector3f& p) { ++cell_start_[cellOf(p) + 1]; });
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  points_.resize(cell_start_[cells]);
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  forEach([&](const Eigen::Vector3f& p) { points_[fill[cellOf(p)]++] = p; });
  thinColumns(step);
}

// Each column by height, keeping one point per `step` of it; compacted in place (the kept
// points of a column never lie after where its points started).
void MeasuredScene::thinColumns(double step) {
  const std::size_t cells = cell_start_.size() - 1;
  const auto by_height = [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) { return a.z() < b.z(); };
  std::size_t kept = 0;
  std::uint32_t begin = cell_start_[0];
  for (std::size_t c = 0; c < cells; ++c) {
    const std::uint32_t end = cell_start_[c + 1];
    std::sort(points_.begin() + begin, points_.begin() + end, by_height);
    float last_kept = -std::numeric_limits<float>::infinity();
    for (std::uint32_t i = begin; i < end; ++i) {
      if (points_[i].z() - last_kept < static_cast<float>(step)) continue;
      last_kept = points_[i].z();
      points_[kept++] = points_[i];
    }
    begin = end;
    cell_start_[c + 1] = static_cast<std::uint32_t>(kept);
  }
  points_.resize(kept);
  heights_.resize(kept);
  for (std::size_t i = 0; i < kept; ++i) heights_[i] = points_[i].z();
}

MeasuredScene::CellRange MeasuredScene::cellsUnder(double x_lo, double y_lo, double x_hi, double y_hi) const {
  const auto clip = [](double value, int count) {
    if (!(value >= 0.0)) return 0;  // below the grid (or NaN)
    return static_cast<int>(std::min(value, static_cast<double>(count - 1)));
  };
  CellRange range{clip((x_lo - origin_.x()) / cell_size_, columns_), clip((x_hi - origin_.x()) / cell_size_, columns_),
                  clip((y_lo - origin_.y()) / cell_size_, rows_), clip((y_hi - origin_.y()) / cell_size_, rows_)};
  // A box wholly outside the grid on one side clips onto its edge: make the range empty.
  if (x_hi < origin_.x() || y_hi < origin_.y() || x_lo > origin_.x() + columns_ * cell_size_ ||
      y_lo > origin_.y() + rows_ * cell_size_ || points_.empty()) {
    range.x0 = 1;
    range.x1 = 0;
  }
  return range;
}

double MeasuredScene::shareCoveredAbove(const Eigen::Vector3d& point, double radius, double height) const {
  const CellRange cells = cellsUnder(point.x() - radius, point.y() - radius, point.x() + radius, point.y() + radius);
  const double limit = point.z() + height;
  int occupied = 0, covered = 0;
  for (int y = cells.y0; y <= cells.y1; ++y) {
    for (int x = cells.x0; x <= cells.x1; ++x) {
      const Eigen::Vector2d centre = origin_ + cell_size_ * Eigen::Vector2d(x + 0.5, y + 0.5);
      if ((centre - point.head<2>()).squaredNorm() > radius * radius) continue;
      const std::size_t cell =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(x);
      if (cell_start_[cell] == cell_start_[cell + 1]) continue;
      ++occupied;
      covered += heights_[cell_start_[cell + 1] - 1] > limit ? 1 : 0;  // the column's top
    }
  }
  return occupied == 0 ? 0.0 : static_cast<double>(covered) / occupied;
}

ToolContact toolCollision(const MeasuredScene& scene, const Eigen::Isometry3d& T_base_grasp,
                          const GripperParams& gripper, const ToolSweep& sweep) {
  const ToolVolume tool = toolVolume(gripper, sweep);
  Eigen::Vector3d lo, hi;
  const double cap = std::max(0.0, sweep.clearance_cap);
  baseBounds(tool, T_base_grasp, cap, lo, hi);
  const Eigen::Isometry3d T_grasp_base = T_base_grasp.inverse();
  double nearest = cap;
  bool collision = false;
  scene.visitBox(lo, hi, [&](const Eigen::Vector3f& base_point) {
    const Eigen::Vector3d p = T_grasp_base * base_point.cast<double>();
    for (int i = 0; i < tool.cylinder_count + tool.box_count; ++i) {
      bool counts = true;
      const auto box = static_cast<std::size_t>(i - tool.cylinder_count);
      const double distance = i < tool.cylinder_count
                                  ? cylinderDistance(tool.cylinders[static_cast<std::size_t>(i)], p, counts)
                                  : boxDistance(tool.boxes[box], p, counts);
      if (distance < 0.0) {
        collision = true;
        return false;
      }
      if (counts) nearest = std::min(nearest, distance);
    }
    if (tool.bent_body) {
      const double distance = bentBodyDistance(*tool.bent_body, p, nearest);
      if (distance < 0.0) {
        collision = true;
        return false;
      }
      nearest = std::min(nearest, distance);
    }
    return true;
  });
  if (collision) return {true, 0.0};
  return {false, nearest};
}

}  // namespace binpick::picking
