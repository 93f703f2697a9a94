#include "boundary.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "binpick/core/error.hpp"
#include "kdtree.hpp"
#include "point_ops.hpp"

namespace binpick::estimation {
namespace {

constexpr float kDegToRad = static_cast<float>(M_PI / 180.0);
constexpr int kMaxWindow = 40;               // pixels searched across a gap (shadow, lost steep wall)
constexpr std::size_t kMinLinePixels = 5;    // points needed to fit a line direction
constexpr float kMinCreaseCoherence = 0.9f;  // share of the crease directions' spread along their mean
constexpr std::size_t kPitchSamples = 1024;  // pixels sampled to measure the cloud's pixel pitch

// An organized cloud seen as an image.
class PixelGrid {
 public:
  explicit PixelGrid(const io::PointCloud& cloud) : cloud_(cloud), width_(cloud.width), height_(cloud.height) {}

  bool inside(int u, int v) const { return u >= 0 && v >= 0 && u < width_ && v < height_; }
  std::size_t index(int u, int v) const { return static_cast<std::size_t>(v) * width_ + u; }
  const Eigen::Vector3f& at(int u, int v) const { return cloud_.points[index(u, v)]; }
  int width() const { return width_; }
  int height() const { return height_; }

  // The median distance between horizontally adjacent valid pixels: converts metres into pixels.
  float typicalPitch() const {
    std::vector<float> pitches;
    // One more than an even share, so that the samples do not fall into one column.
    const std::size_t stride = cloud_.size() / kPitchSamples + 1;
    for (std::size_t i = 0; i + 1 < cloud_.size(); i += stride) {
      if (static_cast<int>(i % width_) + 1 >= width_) continue;
      const float d = (cloud_.points[i + 1] - cloud_.points[i]).norm();
      if (std::isfinite(d) && d > 0.0f) pitches.push_back(d);
    }
    if (pitches.empty()) return 0.0f;
    const auto middle = pitches.begin() + static_cast<std::ptrdiff_t>(pitches.size() / 2);
    std::nth_element(pitches.begin(), middle, pitches.end());
    return *middle;
  }

  // The near side of a depth discontinuity: along one of the four pixel directions, the first
  // valid pixel lies more than `jump` farther. Gaps are crossed (a projector shadow or a steep
  // wall the camera lost lies between a part's top and what is behind it); the far side of a gap
  // finds the near side nearer and is no boundary.
  bool isNearSideOfJump(int u, int v, float jump, int window) const {
    static constexpr int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
    const float z = at(u, v).z();
    for (int k = 0; k < 4; ++k) {
      for (int s = 1; s <= window; ++s) {
        const int nu = u + s * du[k], nv = v + s * dv[k];
        if (!inside(nu, nv)) break;
        const Eigen::Vector3f& q = at(nu, nv);
        if (!q.allFinite()) continue;
        if (q.z() - z > jump) return true;
        break;
      }
    }
    return false;
  }

 private:
  const io::PointCloud& cloud_;
  int width_, height_;
};

// Accumulates points around a centre; the line through them is their principal axis, when they
// spread along it `min_linearity` times more than across it (a corner has no line).
class LineFit {
 public:
  explicit LineFit(const Eigen::Vector3f& centre) : centre_(centre) {}
  void add(const Eigen::Vector3f& p) {
    const Eigen::Vector3d d = (p - centre_).cast<double>();
    sum_ += d, sum_outer_ += d * d.transpose(), ++count_;
  }
  std::optional<Eigen::Vector3f> direction(float min_linearity) const {
    if (count_ < kMinLinePixels) return std::nullopt;
    const Eigen::Vector3d mean = sum_ / static_cast<double>(count_);
    const Eigen::Matrix3d covariance = sum_outer_ / static_cast<double>(count_) - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    const Eigen::Vector3d spread = solver.eigenvalues();  // ascending
    if (!(spread(2) > 0.0) || spread(2) < min_linearity * spread(1)) return std::nullopt;
    return solver.eigenvectors().col(2).cast<float>().normalized();
  }

 private:
  Eigen::Vector3f centre_;
  Eigen::Vector3d sum_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_outer_ = Eigen::Matrix3d::Zero();
  std::size_t count_ = 0;
};

// The direction of the boundary line through pixel (u0, v0): the principal axis of the boundary
// pixels within `radius`, or nothing at a corner or with too few pixels.
std::optional<Eigen::Vector3f> lineDirection(const PixelGrid& grid, const std::vector<uint8_t>& boundary, int u0,
                                             int v0, int half, float radius, float min_linearity) {
  const Eigen::Vector3f& centre = grid.at(u0, v0);
  LineFit line(centre);
  for (int v = std::max(0, v0 - half); v <= std::min(grid.height() - 1, v0 + half); ++v) {
    for (int u = std::max(0, u0 - half); u <= std::min(grid.width() - 1, u0 + half); ++u) {
      if (boundary[grid.index(u, v)] && (grid.at(u, v) - centre).squaredNorm() <= radius * radius)
        line.add(grid.at(u, v));
    }
  }
  return line.direction(min_linearity);
}

}  // namespace

void BoundaryParams::validate() const {
  const char* owner = "detection.boundary";
  core::requireField(depth_jump_ratio > 0.0f && depth_jump_ratio <= 10.0f, owner, "depth_jump_ratio", "in (0, 10]",
                     depth_jump_ratio);
  core::requireField(crease_angle_deg > 0.0f && crease_angle_deg < 180.0f, owner, "crease_angle_deg", "in (0, 180)",
                     crease_angle_deg);
  core::requireField(min_linearity >= 1.0f && min_linearity <= 100.0f, owner, "min_linearity", "in [1, 100]",
                     min_linearity);
}

BoundaryModel prepareBoundaryModel(const PreparedModel& model, const BoundaryParams& params) {
  params.validate();
  const std::vector<Eigen::Vector3f>& points = model.fine_points;
  const std::vector<Eigen::Vector3f>& normals = model.fine_normals;
  const KdTree tree(points);
  const float cos_crease = std::cos(params.crease_angle_deg * kDegToRad);
  BoundaryPoints candidates;
  std::vector<uint32_t> neighbours;
  for (std::size_t i = 0; i < points.size(); ++i) {
    tree.withinRadius(points[i], 0.75f * model.step, neighbours);
    // The neighbour turned most, on the convex side: behind this point's tangent plane. A concave
    // crease (the inside of an L) never bounds what the camera sees.
    int most_turned = -1;
    float lowest_cosine = cos_crease;
    for (uint32_t j : neighbours) {
      const float cosine = normals[i].dot(normals[j]);
      if (cosine < lowest_cosine && (points[j] - points[i]).dot(normals[i]) < 0.0f) {
        lowest_cosine = cosine, most_turned = static_cast<int>(j);
      }
    }
    if (most_turned < 0) continue;
    const Eigen::Vector3f along = normals[i].cross(normals[static_cast<std::size_t>(most_turned)]);
    if (!(along.norm() > 1e-3f)) continue;  // opposite normals (a thin wall's two sides): no line
    candidates.points.push_back(points[i]);
    candidates.directions.push_back(along.normalized());
  }
  // The crease's direction n_i x n_j, averaged without sign over the crease points within a step;
  // where they disagree, three faces meet and there is no line (as at the scene's corners).
  BoundaryModel boundary;
  const KdTree crease_tree(candidates.points);
  for (uint32_t k : voxelSubsample(candidates.points, nullptr, model.step, 0.0f)) {
    crease_tree.withinRadius(candidates.points[k], model.step, neighbours);
    Eigen::Matrix3f outer = Eigen::Matrix3f::Zero();
    for (uint32_t j : neighbours) outer += candidates.directions[j] * candidates.directions[j].transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> solver(outer);
    if (solver.eigenvalues()(2) < kMinCreaseCoherence * outer.trace()) continue;
    boundary.creases.points.push_back(candidates.points[k]);
    boundary.creases.directions.push_back(solver.eigenvectors().col(2).normalized());
  }
  boundary.table = PpfHashTable(model.points, model.normals, boundary.creases.points, boundary.creases.directions,
                                model.quantizer(), model.params.max_pairs_per_feature, model.referenceCount());
  return boundary;
}

BoundaryPoints sceneBoundaryPoints(const io::PointCloud& cloud, const std::optional<CropBox>& crop,
                                   const PreparedModel& model, const BoundaryParams& params, int threads) {
  params.validate();
  BoundaryPoints boundary;
  if (!cloud.isOrganized() || cloud.size() == 0) return boundary;
  const PixelGrid grid(cloud);
  const float pitch = grid.typicalPitch();
  if (!(pitch > 0.0f)) return boundary;
  const int gap_window = std::clamp(static_cast<int>(std::ceil(2.0f * model.step / pitch)), 1, kMaxWindow);
  const float jump = params.depth_jump_ratio * model.step;

  std::vector<uint8_t> is_boundary(cloud.size(), 0);
  const bool cropped = crop.has_value();
  const CropBox::Test inside = cropped ? crop->test() : CropBox::Test{};
#pragma omp parallel for num_threads(core::resolveThreadCount(threads)) schedule(static)
  for (int v = 0; v < grid.height(); ++v) {
    for (int u = 0; u < grid.width(); ++u) {
      const Eigen::Vector3f& p = grid.at(u, v);
      if (!p.allFinite() || (cropped && !inside.contains(p))) continue;
      if (grid.isNearSideOfJump(u, v, jump, gap_window)) is_boundary[grid.index(u, v)] = 1;
    }
  }
  std::vector<uint32_t> pixels;
  std::vector<Eigen::Vector3f> positions;
  for (uint32_t i = 0; i < is_boundary.size(); ++i) {
    if (is_boundary[i]) pixels.push_back(i), positions.push_back(cloud.points[i]);
  }
  const int line_window = std::clamp(static_cast<int>(std::ceil(model.step / pitch)), 1, kMaxWindow);
  for (uint32_t k : voxelSubsample(positions, nullptr, model.step, 0.0f)) {
    const auto u = static_cast<int>(pixels[k] % static_cast<uint32_t>(cloud.width));
    const auto v = static_cast<int>(pixels[k] / static_cast<uint32_t>(cloud.width));
    const auto direction = lineDirection(grid, is_boundary, u, v, line_window, model.step, params.min_linearity);
    if (!direction) continue;
    boundary.points.push_back(positions[k]);
    boundary.directions.push_back(*direction);
  }
  return boundary;
}

}  // namespace binpick::estimation
