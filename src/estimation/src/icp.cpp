#include "icp.hpp"

#include <omp.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"
#include "kdtree.hpp"
#include "point_ops.hpp"

namespace binpick::estimation {
namespace {

constexpr float kDegToRad = static_cast<float>(M_PI / 180.0);

struct Correspondence {
  Eigen::Vector3f source;  // moved model point
  Eigen::Vector3f target;  // scene point
  Eigen::Vector3f normal;  // scene normal
};

// Gauss-Newton step of the point-to-plane cost with Huber weights; returns the increment as an
// isometry applied on the left. Rotations are taken about the correspondences' centroid (not the
// camera origin ~1 m away), and a little damping keeps directions that the points do not
// constrain (sliding along a lone plane) where they are instead of sending them anywhere.
// H is symmetric: per pair only its upper triangle is updated. The point-to-point term's
// Jacobian is J3 = [-[a]x | I] (a = source - centre), so its share of H, sum wd J3^T J3 =
// [[tr(S) I - S, [sum wd a]x], [-[sum wd a]x, sum wd I]] with S = sum wd a a^T, needs only those
// three sums per pair; a 6x6 product per pair was a third of ICP's time.
Eigen::Isometry3f solvePointToPlane(const std::vector<Correspondence>& pairs, float huber, float point_weight) {
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  for (const Correspondence& c : pairs) centre += c.source;
  centre /= static_cast<float>(std::max<std::size_t>(pairs.size(), 1));
  Eigen::Matrix<double, 6, 6> upper = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
  double point_w = 0.0;
  Eigen::Vector3d point_wa = Eigen::Vector3d::Zero();
  Eigen::Matrix3d point_waa = Eigen::Matrix3d::Zero();
  for (const Correspondence& c : pairs) {
    const double r = static_cast<double>((c.source - c.target).dot(c.normal));
    const double w = std::abs(r) <= huber ? 1.0 : huber / std::abs(r);
    Eigen::Matrix<double, 6, 1> J;
    J << (c.source - centre).cross(c.normal).cast<double>(), c.normal.cast<double>();
    upper.selfadjointView<Eigen::Upper>().rankUpdate(J, w);
    g += (w * r) * J;
    if (point_weight > 0.0f) {
      const Eigen::Vector3d a = (c.source - centre).cast<double>();
      const Eigen::Vector3d d = (c.source - c.target).cast<double>();
      const double wd = point_weight * (d.norm() <= huber ? 1.0 : huber / d.norm());
      point_w += wd;
      point_wa += wd * a;
      point_waa += wd * a * a.transpose();
      g.head<3>() += wd * a.cross(d);  // J3^T d = [a x d; d]
      g.tail<3>() += wd * d;
    }
  }
  Eigen::Matrix<double, 6, 6> H = upper.selfadjointView<Eigen::Upper>();
  Eigen::Matrix3d skew;
  skew << 0.0, -point_wa.z(), point_wa.y(), point_wa.z(), 0.0, -point_wa.x(), -point_wa.y(), point_wa.x(), 0.0;
  H.topLeftCorner<3, 3>() += point_waa.trace() * Eigen::Matrix3d::Identity() - point_waa;
  H.topRightCorner<3, 3>() += skew;
  H.bottomLeftCorner<3, 3>() -= skew;
  H.bottomRightCorner<3, 3>() += point_w * Eigen::Matrix3d::Identity();
  constexpr double kRelativeDamping = 1e-3;
  H.diagonal().array() += kRelativeDamping * H.trace() / 6.0 + 1e-12;
  const Eigen::Matrix<double, 6, 1> x = H.ldlt().solve(-g);
  Eigen::Isometry3f delta = Eigen::Isometry3f::Identity();
  if (!x.allFinite()) return delta;
  const Eigen::Vector3d omega = x.head<3>();
  if (omega.norm() > 1e-12) {
    delta.linear() = Eigen::AngleAxisd(omega.norm(), omega.normalized()).toRotationMatrix().cast<float>();
  }
  // p' = R (p - centre) + centre + t
  delta.translation() = centre - delta.linear() * centre + x.tail<3>().cast<float>();
  return delta;
}

}  // namespace

void IcpParams::validate() const {
  const char* owner = "detection.icp";
  const auto requirePositive = [owner](float value, const char* field) {
    core::requireField(value > 0.0f && std::isfinite(value), owner, field, "finite and positive", value);
  };
  core::requireField(max_iterations >= 0 && max_iterations <= 1000, owner, "max_iterations", "in [0, 1000]",
                     max_iterations);
  requirePositive(initial_max_distance_ratio, "initial_max_distance_ratio");
  requirePositive(final_max_distance_ratio, "final_max_distance_ratio");
  requirePositive(huber_ratio, "huber_ratio");
  core::requireField(point_weight >= 0.0f && point_weight <= 10.0f, owner, "point_weight", "in [0, 10]", point_weight);
  requirePositive(convergence_translation_ratio, "convergence_translation_ratio");
  requirePositive(convergence_rotation_deg, "convergence_rotation_deg");
  requirePositive(fit_distance_ratio, "fit_distance_ratio");
  core::requireField(max_normal_angle_deg > 0.0f && max_normal_angle_deg <= 180.0f, owner, "max_normal_angle_deg",
                     "in (0, 180]", max_normal_angle_deg);
}

std::vector<uint32_t> visibleModelPoints(const PreparedModel& model, const Eigen::Isometry3f& pose) {
  return visibleSurfacePoints(model.points, model.normals, model.step, model.centre, pose);
}

std::vector<uint32_t> visibleSurfacePoints(const std::vector<Eigen::Vector3f>& points,
                                           const std::vector<Eigen::Vector3f>& normals, float step,
                                           const Eigen::Vector3f& centre, const Eigen::Isometry3f& pose) {
  // Back faces first, then a z-buffer over viewing directions with cells about one step wide at
  // the part's distance: a point more than a step behind the nearest in its cell is hidden. The
  // part spans a few dozen cells each way, so the buffer is a small dense grid over its bounds.
  const float depth = std::max((pose * centre).z(), step);
  const float cell = step / depth;
  struct Facing {
    uint32_t index;
    float z;
    int64_t u, v;
  };
  std::vector<Facing> facing;
  facing.reserve(points.size());
  int64_t u_low = std::numeric_limits<int64_t>::max(), v_low = u_low, u_high = std::numeric_limits<int64_t>::min(),
          v_high = u_high;
  for (uint32_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector3f p = pose * points[k];
    if (!(p.z() > 0.0f) || (pose.linear() * normals[k]).dot(p) >= 0.0f) continue;
    const auto u = static_cast<int64_t>(std::floor(p.x() / p.z() / cell));
    const auto v = static_cast<int64_t>(std::floor(p.y() / p.z() / cell));
    facing.push_back({k, p.z(), u, v});
    u_low = std::min(u_low, u), u_high = std::max(u_high, u);
    v_low = std::min(v_low, v), v_high = std::max(v_high, v);
  }
  std::vector<uint32_t> visible;
  if (facing.empty()) return visible;
  // A part close to the camera plane could span many cells: the grid is bounded, the rest wraps.
  // Each point's cell is found once, with the wrap's divisions only where the part spans more than
  // the grid: run for every lookup, they took most of this function's time.
  constexpr int64_t kMaxSide = 4096;
  const bool wraps = u_high - u_low + 1 > kMaxSide || v_high - v_low + 1 > kMaxSide;
  const int64_t width = std::min(u_high - u_low + 1, kMaxSide), height = std::min(v_high - v_low + 1, kMaxSide);
  std::vector<float> nearest(static_cast<std::size_t>(width * height), std::numeric_limits<float>::infinity());
  std::vector<std::size_t> cell_of(facing.size());
  for (std::size_t i = 0; i < facing.size(); ++i) {
    const Facing& f = facing[i];
    const int64_t u = wraps ? (f.u - u_low) % width : f.u - u_low;
    const int64_t v = wraps ? (f.v - v_low) % height : f.v - v_low;
    cell_of[i] = static_cast<std::size_t>(v * width + u);
    nearest[cell_of[i]] = std::min(nearest[cell_of[i]], f.z);
  }
  visible.reserve(facing.size());
  for (std::size_t i = 0; i < facing.size(); ++i) {
    if (facing[i].z <= nearest[cell_of[i]] + step) visible.push_back(facing[i].index);
  }
  return visible;
}

// A few hundred searches are worth a second thread; inside a parallel region (a pick's twins
// refined side by side) the threads are taken already.
bool PoseRefiner::searchInParallel(std::size_t searches) const {
  constexpr std::size_t kMinSearchesToShare = 256;
  return threads_ > 1 && searches >= kMinSearchesToShare && !omp_in_parallel();
}

struct PoseRefiner::Index {
  explicit Index(const std::vector<Eigen::Vector3f>& points) : tree(points) {}
  KdTree tree;
};

PoseRefiner::PoseRefiner(const PreparedScene& scene, float step, IcpParams params, int threads)
    : scene_(scene),
      step_(step),
      params_(params),
      min_normal_cos_(static_cast<float>(std::cos(static_cast<double>(params.max_normal_angle_deg) * M_PI / 180.0))),
      threads_(core::resolveThreadCount(threads)),
      index_(std::make_unique<Index>(scene.points)) {
  params_.validate();
}

PoseRefiner::~PoseRefiner() = default;

std::vector<uint32_t> PoseRefiner::scenePointsNear(const PreparedModel& model, const Eigen::Isometry3f& pose,
                                                   float radius) const {
  std::vector<uint8_t> near(scene_.points.size(), 0);
  std::vector<uint32_t> found;
  for (const Eigen::Vector3f& m : model.points) {
    index_->tree.withinRadius(pose * m, radius, found);
    for (uint32_t s : found) near[s] = 1;
  }
  std::vector<uint32_t> indices;
  for (uint32_t s = 0; s < near.size(); ++s) {
    if (near[s]) indices.push_back(s);
  }
  return indices;
}

IcpResult PoseRefiner::refine(const PreparedModel& model, const Eigen::Isometry3f& initial) const {
  return refine(model, initial, params_.max_iterations);
}

IcpResult PoseRefiner::refine(const PreparedModel& model, const Eigen::Isometry3f& initial, int max_iterations) const {
  IcpResult result;
  result.T_camera_model = initial;
  if (scene_.points.empty()) return result;
  std::vector<uint32_t> sources;
  struct Slot {
    Eigen::Vector3f source;
    int scene;  // -1: no correspondence
  };
  std::vector<Slot> slots;
  std::vector<Correspondence> pairs;
  const float huber = params_.huber_ratio * step_;
  for (int it = 0; it < max_iterations; ++it) {
    const Eigen::Isometry3f& pose = result.T_camera_model;
    if (params_.visible_points_only) {
      sources = visibleModelPoints(model, pose);
    } else {
      sources.resize(model.size());
      for (uint32_t k = 0; k < model.size(); ++k) sources[k] = k;
    }
    const float gate =
        (it < max_iterations / 3 ? params_.initial_max_distance_ratio : params_.final_max_distance_ratio) *
        step_;
    // Each source's scene point in its own slot, then the pairs in source order: the sums below
    // come out the same on any number of threads.
    slots.resize(sources.size());
#pragma omp parallel for num_threads(threads_) schedule(static) if (searchInParallel(sources.size()))
    for (std::size_t i = 0; i < sources.size(); ++i) {
      const uint32_t k = sources[i];
      const Eigen::Vector3f p = pose * model.points[k];
      const int s = index_->tree.nearestWithin(p, gate * gate).first;
      // A scene normal facing away from the moved model normal belongs to another surface.
      const bool paired = s >= 0 && scene_.normals[s].dot(pose.linear() * model.normals[k]) >= min_normal_cos_;
      slots[i] = {p, paired ? s : -1};
    }
    pairs.clear();
    for (const Slot& slot : slots) {
      if (slot.scene >= 0) pairs.push_back({slot.source, scene_.points[slot.scene], scene_.normals[slot.scene]});
    }
    if (pairs.size() < 6) break;
    const Eigen::Isometry3f delta = solvePointToPlane(pairs, huber, params_.point_weight);
    result.T_camera_model = delta * result.T_camera_model;
    result.iterations = it + 1;
    const float turn = Eigen::AngleAxisf(delta.linear()).angle();
    if (delta.translation().norm() < params_.convergence_translation_ratio * step_ &&
        turn < params_.convergence_rotation_deg * kDegToRad) {
      result.converged = true;
      break;
    }
  }
  orthonormalise(result.T_camera_model);

  // Final fit: residual and how much of what the camera should see of the part is there.
  result.fit = assess(model, result.T_camera_model);
  return result;
}

PoseFit PoseRefiner::assess(const PreparedModel& model, const Eigen::Isometry3f& pose) const {
  const std::vector<uint32_t> visible = visibleModelPoints(model, pose);
  const float fit_distance = params_.fit_distance_ratio * step_;
  PoseFit fit;
  fit.visible = static_cast<int>(visible.size());
  double squared = 0.0;
  for (uint32_t k : visible) {
    const Eigen::Vector3f p = pose * model.points[k];
    const auto s = index_->tree.nearestWithin(p, fit_distance * fit_distance).first;
    if (s < 0) continue;
    const float r = (p - scene_.points[s]).dot(scene_.normals[s]);
    squared += static_cast<double>(r) * r;
    ++fit.fitted;
  }
  fit.rmse = fit.fitted == 0 ? 0.0f : static_cast<float>(std::sqrt(squared / fit.fitted));
  return fit;
}

}  // namespace binpick::estimation
