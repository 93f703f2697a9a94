// The camera ray table and the projector's undistortion tables.
#include "triangulation_tables.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace binpick::reconstruction::detail {
namespace {

// Grid spacing in projector pixels. Bilinear interpolation errs by about step^2 / 8 times the
// lens map's second derivative: for the virtual projector below 1e-5 pixel at 2 pixels, and
// still below 1e-3 pixel for lenses ten times as distorting.
constexpr double kStepPixels = 2.0;
// Decoded coordinates may lie a little outside the image (sub-pixel positions of the edge
// columns, a calibration that differs slightly from the one used to choose the patterns).
constexpr double kMarginPixels = 8.0;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int nodeCount(double span) { return static_cast<int>(std::ceil(span / kStepPixels)) + 1; }

// The epipolar label of the plane through the projector ray w (see EpipolarPencil).
double epipolarLabel(const EpipolarPencil& pencil, const Eigen::Vector3d& centre, const Eigen::Vector3d& w) {
  const Eigen::Vector3d n = centre.cross(w);
  return n.dot(pencil.e3) / n.dot(pencil.e2);
}

struct LabelRange {
  double min = 0.0, max = 0.0;
  double step = 0.0;  // about kStepPixels between neighbouring planes' image lines, or finer
  int nodes = 0;      // 0: the planes cannot be tabulated
};

// The labels of the planes that cross the margin-extended image, from a grid of samples: the
// label is monotonic across the image, so the border decides the range and the grid the step.
LabelRange labelRange(const io::LensIntrinsics& lens, const EpipolarPencil& pencil, const Eigen::Vector3d& centre) {
  constexpr int kSamples = 64;
  // Planes more than 89.9 degrees from the axis plane, or finer tables than this, mean the
  // epipole is in or near the image: no column's light crosses the planes cleanly.
  constexpr double kMaxLabel = 500.0;
  constexpr int kMaxNodes = 8192;
  const double x0 = -kMarginPixels, x1 = lens.width - 1 + kMarginPixels;
  const double y0 = -kMarginPixels, y1 = lens.height - 1 + kMarginPixels;
  LabelRange range;
  range.min = std::numeric_limits<double>::infinity();
  range.max = -range.min;
  double min_rate = range.min;  // label change per pixel, the slowest anywhere
  // NaN where the lens model has no inverse (not a real lens's image): such samples are skipped.
  auto label = [&](double x, double y) {
    const Eigen::Vector2d p = lens.undistort({(x - lens.cx) / lens.fx, (y - lens.cy) / lens.fy});
    return p.allFinite() ? epipolarLabel(pencil, centre, {p.x(), p.y(), 1.0}) : kNaN;
  };
  for (int j = 0; j <= kSamples; ++j) {
    for (int i = 0; i <= kSamples; ++i) {
      const double x = x0 + (x1 - x0) * i / kSamples, y = y0 + (y1 - y0) * j / kSamples;
      const double l = label(x, y);
      if (std::isnan(l)) continue;
      if (!(std::abs(l) <= kMaxLabel)) return {};
      range.min = std::min(range.min, l);
      range.max = std::max(range.max, l);
      const double rate = std::hypot(label(x + 1.0, y) - l, label(x, y + 1.0) - l);
      if (std::isfinite(rate)) min_rate = std::min(min_rate, rate);
    }
  }
  if (!(min_rate > 0.0) || !std::isfinite(min_rate)) return {};
  range.step = kStepPixels * min_rate;
  const double nodes = std::ceil((range.max - range.min) / range.step) + 3.0;
  if (nodes > kMaxNodes) return {};
  range.nodes = static_cast<int>(nodes);
  return range;
}

// Where the light of the column at distorted normalised x `target_x` crosses the plane with
// normal n: the point of the plane's image line whose distorted x is target_x, by Newton along
// the line. NaN where the line runs (almost) along the column or the lens model folds over.
Eigen::Vector2d crossColumn(const io::LensIntrinsics& lens, const Eigen::Vector3d& n, double target_x) {
  constexpr double kMinCrossing = 1e-3;  // sine of the angle between line and column
  constexpr double kH = 1e-7;
  const Eigen::Vector2d nan = Eigen::Vector2d::Constant(kNaN);
  const double nn = n.x() * n.x() + n.y() * n.y();
  if (!(nn > 0.0)) return nan;
  const Eigen::Vector2d origin = -n.z() * Eigen::Vector2d(n.x(), n.y()) / nn;
  Eigen::Vector2d along = Eigen::Vector2d(n.y(), -n.x()) / std::sqrt(nn);
  if (along.x() < 0.0) along = -along;
  if (along.x() < kMinCrossing) return nan;
  double s = (target_x - origin.x()) / along.x();
  for (int iteration = 0; iteration < 30; ++iteration) {
    const Eigen::Vector2d p = origin + s * along;
    const double residual = lens.distort(p).x() - target_x;
    if (std::abs(residual) < 1e-15) return p;
    const double slope = (lens.distort(p + kH * along).x() - lens.distort(p - kH * along).x()) / (2.0 * kH);
    if (!(slope > kMinCrossing)) return nan;
    s -= residual / slope;
  }
  const Eigen::Vector2d p = origin + s * along;
  return std::abs(lens.distort(p).x() - target_x) < 1e-12 ? p : nan;
}

LookupGrid<4> buildEpipolarGrid(const io::LensIntrinsics& lens, const EpipolarPencil& pencil,
                                const Eigen::Vector3d& centre, int threads) {
  if (!pencil.valid) return {};
  const LabelRange range = labelRange(lens, pencil, centre);
  if (range.nodes == 0) return {};
  LookupGrid<4> grid(-kMarginPixels, range.min - range.step, kStepPixels, range.step,
                     nodeCount(lens.width - 1 + 2 * kMarginPixels), range.nodes);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int j = 0; j < grid.ny(); ++j) {
    const Eigen::Vector3d n = pencil.e2 + grid.nodeY(j) * pencil.e3;
    for (int i = 0; i < grid.nx(); ++i) {
      const Eigen::Vector2d p = crossColumn(lens, n, (grid.nodeX(i) - lens.cx) / lens.fx);
      const double row = lens.fy * lens.distort(p).y() + lens.cy;  // NaN stays NaN
      float* node = grid.node(i, j);
      node[0] = static_cast<float>(p.x());
      node[1] = static_cast<float>(p.y());
      node[2] = static_cast<float>(row);
      node[3] = 0.0f;
    }
  }
  return grid;
}
}  // namespace

LookupGrid<2> buildUndistortGrid(const io::LensIntrinsics& lens, int threads) {
  LookupGrid<2> grid(-kMarginPixels, -kMarginPixels, kStepPixels, kStepPixels,
                     nodeCount(lens.width - 1 + 2 * kMarginPixels), nodeCount(lens.height - 1 + 2 * kMarginPixels));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int j = 0; j < grid.ny(); ++j) {
    for (int i = 0; i < grid.nx(); ++i) {
      const Eigen::Vector2d p =
          lens.undistort({(grid.nodeX(i) - lens.cx) / lens.fx, (grid.nodeY(j) - lens.cy) / lens.fy});
      grid.node(i, j)[0] = static_cast<float>(p.x());
      grid.node(i, j)[1] = static_cast<float>(p.y());
    }
  }
  return grid;
}

CameraRays buildCameraRays(const io::LensIntrinsics& camera, int threads) {
  CameraRays rays;
  rays.width = camera.width;
  rays.height = camera.height;
  const std::size_t count = static_cast<std::size_t>(camera.width) * camera.height;
  rays.x.resize(count);
  rays.y.resize(count);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int row = 0; row < camera.height; ++row) {
    for (int col = 0; col < camera.width; ++col) {
      // NaN where the model has no inverse: such a pixel gets NoIntersection.
      const Eigen::Vector2d p = camera.undistort({(col - camera.cx) / camera.fx, (row - camera.cy) / camera.fy});
      const std::size_t i = static_cast<std::size_t>(row) * camera.width + col;
      rays.x[i] = static_cast<float>(p.x());
      rays.y[i] = static_cast<float>(p.y());
    }
  }
  return rays;
}

EpipolarPencil makeEpipolarPencil(const Eigen::Vector3d& camera_centre_in_projector) {
  const Eigen::Vector3d& c = camera_centre_in_projector;
  EpipolarPencil pencil;
  const Eigen::Vector3d axis_normal = c.cross(Eigen::Vector3d::UnitZ());
  if (!(axis_normal.norm() > 1e-6 * c.norm())) return pencil;
  pencil.e2 = axis_normal.normalized();
  pencil.e3 = c.normalized().cross(pencil.e2);
  pencil.valid = true;
  return pencil;
}

ProjectorTables buildProjectorTables(const io::LensIntrinsics& projector, const EpipolarPencil& pencil,
                                     const Eigen::Vector3d& camera_centre_in_projector, int threads) {
  ProjectorTables tables;
  tables.undistort = buildUndistortGrid(projector, threads);
  tables.epipolar = buildEpipolarGrid(projector, pencil, camera_centre_in_projector, threads);
  tables.min_column = tables.min_row = static_cast<float>(-kMarginPixels);
  tables.max_column = static_cast<float>(projector.width - 1 + kMarginPixels);
  tables.max_row = static_cast<float>(projector.height - 1 + kMarginPixels);
  return tables;
}

}  // namespace binpick::reconstruction::detail
