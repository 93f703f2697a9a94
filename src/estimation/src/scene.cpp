#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "binpick/core/error.hpp"
#include "kdtree.hpp"
#include "point_ops.hpp"

namespace binpick::estimation {
namespace {

// The normal's support reaches at least this many point spacings (a 3x3 pixel window), but never
// past this many subsampling steps: a normal over a wider patch no longer describes the point.
constexpr float kMinSupportInSpacings = 1.5f;
constexpr float kMaxSupportInSteps = 2.0f;

constexpr std::size_t kSpacingSamples = 256;  // points sampled to measure a cloud's spacing

float median(std::vector<float> values) {
  if (values.empty()) return 0.0f;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// The radius of a scene normal's neighbourhood in a cloud whose points lie `spacing` apart.
float normalSupport(float radius, float spacing, float step) {
  return std::max(radius, std::min(kMinSupportInSpacings * spacing, kMaxSupportInSteps * step));
}

// Full-resolution neighbours of a pixel found through the image grid: an organized cloud gives
// them without a search structure.
class OrganizedNeighbours {
 public:
  OrganizedNeighbours(const io::PointCloud& cloud, const SceneParams& params)
      : cloud_(cloud), max_half_(params.max_window_half_size) {}

  PlaneFit fit(uint32_t index, float radius) const {
    PlaneFit fit;
    const int u0 = static_cast<int>(index % static_cast<uint32_t>(cloud_.width));
    const int v0 = static_cast<int>(index / static_cast<uint32_t>(cloud_.width));
    const Eigen::Vector3f& centre = cloud_.points[index];
    const float pitch = pixelPitch(u0, v0);
    if (!(pitch > 0.0f)) return fit;
    const int half = std::clamp(static_cast<int>(std::ceil(radius / pitch)), 1, max_half_);
    const float radius_sq = radius * radius;
    for (int v = std::max(0, v0 - half); v <= std::min(cloud_.height - 1, v0 + half); ++v) {
      const Eigen::Vector3f* row = &cloud_.points[static_cast<std::size_t>(v) * cloud_.width];
      for (int u = std::max(0, u0 - half); u <= std::min(cloud_.width - 1, u0 + half); ++u) {
        // NaN fails the comparison, so invalid pixels drop out here too.
        if ((row[u] - centre).squaredNorm() <= radius_sq) fit.add(row[u]);
      }
    }
    return fit;
  }

  // The typical distance between adjacent pixels' points: the median over a sample of `indices`.
  float typicalPitch(const std::vector<uint32_t>& indices) const {
    std::vector<float> pitches;
    const std::size_t stride = std::max<std::size_t>(1, indices.size() / kSpacingSamples);
    for (std::size_t k = 0; k < indices.size(); k += stride) {
      const auto u = static_cast<int>(indices[k] % static_cast<uint32_t>(cloud_.width));
      const auto v = static_cast<int>(indices[k] / static_cast<uint32_t>(cloud_.width));
      const float pitch = pixelPitch(u, v);
      if (pitch > 0.0f) pitches.push_back(pitch);
    }
    return median(pitches);
  }

 private:
  // Distance between adjacent pixels' points: converts a metric radius into a pixel window.
  float pixelPitch(int u, int v) const {
    float best = std::numeric_limits<float>::infinity();
    const Eigen::Vector3f& p = at(u, v);
    const int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int nu = u + du[k], nv = v + dv[k];
      if (nu < 0 || nv < 0 || nu >= cloud_.width || nv >= cloud_.height) continue;
      const float d = (at(nu, nv) - p).norm();
      if (d < best) best = d;  // NaN neighbours never win
    }
    return std::isfinite(best) ? best : 0.0f;
  }
  const Eigen::Vector3f& at(int u, int v) const {
    return cloud_.points[static_cast<std::size_t>(v) * cloud_.width + u];
  }

  const io::PointCloud& cloud_;
  int max_half_;
};

// The typical distance between neighbouring points of an unorganized cloud: the median over a
// sample of kept points of the distance to their nearest other point.
float typicalSpacing(const KdTree& tree, const std::vector<uint32_t>& kept) {
  std::vector<float> spacing;
  const std::size_t stride = std::max<std::size_t>(1, kept.size() / kSpacingSamples);
  for (std::size_t k = 0; k < kept.size(); k += stride) {
    const float d = tree.nearestOtherSq(kept[k]);
    if (std::isfinite(d)) spacing.push_back(std::sqrt(d));
  }
  return median(spacing);
}

std::vector<uint32_t> validIndices(const io::PointCloud& cloud, const SceneParams& params) {
  std::vector<uint32_t> valid;
  valid.reserve(cloud.size());
  const bool cropped = params.crop.has_value();
  const CropBox::Test inside = cropped ? params.crop->test() : CropBox::Test{};
  for (uint32_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    if (!p.allFinite()) continue;
    if (cropped && !inside.contains(p)) continue;
    valid.push_back(i);
  }
  return valid;
}

// The depth a step is measured at: the median depth of the scene's points.
float medianDepth(const std::vector<Eigen::Vector3f>& points, const std::vector<uint32_t>& kept) {
  std::vector<float> depths(kept.size());
  for (std::size_t k = 0; k < kept.size(); ++k) depths[k] = points[kept[k]].z();
  return median(std::move(depths));
}

Eigen::Vector3f towardsCamera(const Eigen::Vector3f& n, const Eigen::Vector3f& p) {
  return n.dot(p) > 0.0f ? Eigen::Vector3f(-n) : n;
}

}  // namespace

bool CropBox::contains(const Eigen::Vector3f& p_camera) const { return test().contains(p_camera); }

void SceneParams::validate() const {
  const char* owner = "detection.scene";
  core::requireField(line_of_sight_cell_ratio >= 0.0f && line_of_sight_cell_ratio <= 10.0f, owner,
                     "line_of_sight_cell_ratio", "in [0, 10]", line_of_sight_cell_ratio);
  core::requireField(min_normal_neighbours >= 3, owner, "min_normal_neighbours", "at least 3", min_normal_neighbours);
  core::requireField(max_window_half_size >= 1 && max_window_half_size <= 50, owner, "max_window_half_size",
                     "in [1, 50]", max_window_half_size);
  if (crop) {
    core::requireField((crop->half_extents.array() > 0.0f).all() && crop->half_extents.allFinite(), owner,
                       "crop.half_extents", "finite and positive", crop->half_extents.transpose());
    core::requireField(crop->T_camera_box.matrix().allFinite(), owner, "crop.pose", "finite",
                       crop->T_camera_box.translation().transpose());
  }
}

PreparedScene prepareScene(const io::PointCloud& cloud, const PreparedModel& model, const SceneParams& params,
                           int threads) {
  params.validate();
  if (!cloud.isOrganized()) io::validateCloud(cloud, "scene cloud");
  const std::vector<uint32_t> valid = validIndices(cloud, params);
  PreparedScene scene;
  scene.valid_input_points = valid.size();
  if (valid.empty()) return scene;

  std::vector<Eigen::Vector3f> valid_points(valid.size());
  for (std::size_t k = 0; k < valid.size(); ++k) valid_points[k] = cloud.points[valid[k]];
  const std::vector<uint32_t> kept = voxelSubsample(valid_points, nullptr, model.step, 0.0f);
  const float depth = medianDepth(valid_points, kept);
  if (params.line_of_sight_cell_ratio > 0.0f && depth > 0.0f) {
    scene.line_of_sight = LineOfSightMap(cloud.points, params.line_of_sight_cell_ratio * model.step, depth);
  }

  // Section III-A: normals from the full-resolution neighbours of each kept point.
  const float radius = model.params.normal_radius_ratio * model.step;
  std::vector<std::optional<Eigen::Vector3f>> normals(kept.size());
  const auto min_neighbours = static_cast<std::size_t>(params.min_normal_neighbours);
  const int thread_count = core::resolveThreadCount(threads);
  if (cloud.isOrganized()) {
    const OrganizedNeighbours neighbours(cloud, params);
    std::vector<uint32_t> kept_pixels(kept.size());
    for (std::size_t k = 0; k < kept.size(); ++k) kept_pixels[k] = valid[kept[k]];
    const float support = normalSupport(radius, neighbours.typicalPitch(kept_pixels), model.step);
#pragma omp parallel for num_threads(thread_count) schedule(static)
    for (std::size_t k = 0; k < kept.size(); ++k) {
      normals[k] = neighbours.fit(kept_pixels[k], support).normal(min_neighbours);
    }
  } else {
    const KdTree tree(valid_points);
    const float support = normalSupport(radius, typicalSpacing(tree, kept), model.step);
#pragma omp parallel for num_threads(thread_count) schedule(static)
    for (std::size_t k = 0; k < kept.size(); ++k) {
      std::vector<uint32_t> found;
      tree.withinRadius(valid_points[kept[k]], support, found);
      PlaneFit fit;
      for (uint32_t j : found) fit.add(valid_points[j]);
      normals[k] = fit.normal(min_neighbours);
    }
  }
  for (std::size_t k = 0; k < kept.size(); ++k) {
    if (!normals[k]) {
      ++scene.without_normal;
      continue;
    }
    const Eigen::Vector3f& p = valid_points[kept[k]];
    scene.points.push_back(p);
    scene.normals.push_back(towardsCamera(*normals[k], p));
    scene.source_index.push_back(valid[kept[k]]);
  }
  return scene;
}

}  // namespace binpick::estimation
