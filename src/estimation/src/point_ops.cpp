#include "point_ops.hpp"

#include "cell_key.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace binpick::estimation {
namespace {

// Open-addressing map from packed voxel coordinates to dense voxel ids (0, 1, 2, ...).
class VoxelIds {
 public:
  explicit VoxelIds(std::size_t expected) {
    std::size_t capacity = 16;
    while (capacity < expected) capacity *= 2;
    keys_.assign(capacity, kEmpty);
    ids_.resize(capacity);
  }
  uint32_t idOf(uint64_t key) {
    std::size_t slot = find(key);
    if (keys_[slot] == kEmpty) {
      if (2 * (count_ + 1) > keys_.size()) {  // keep the load under one half: probes stay short
        grow();
        slot = find(key);
      }
      keys_[slot] = key;
      ids_[slot] = count_++;
    }
    return ids_[slot];
  }
  uint32_t count() const { return count_; }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t{0};
  std::size_t find(uint64_t key) const {
    std::size_t slot = hash(key) & (keys_.size() - 1);
    while (keys_[slot] != kEmpty && keys_[slot] != key) slot = (slot + 1) & (keys_.size() - 1);
    return slot;
  }
  void grow() {
    std::vector<uint64_t> old_keys(keys_.size() * 2, kEmpty);
    std::vector<uint32_t> old_ids(ids_.size() * 2);
    old_keys.swap(keys_);
    old_ids.swap(ids_);
    for (std::size_t i = 0; i < old_keys.size(); ++i) {
      if (old_keys[i] == kEmpty) continue;
      const std::size_t slot = find(old_keys[i]);
      keys_[slot] = old_keys[i];
      ids_[slot] = old_ids[i];
    }
  }
  static uint64_t hash(uint64_t key) {  // splitmix64 finaliser: cheap and well mixed
    key ^= key >> 30;
    key *= 0xbf58476d1ce4e5b9ULL;
    key ^= key >> 27;
    key *= 0x94d049bb133111ebULL;
    return key ^ (key >> 31);
  }
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> ids_;
  uint32_t count_ = 0;
};

// Greedy clusters of one voxel's points by normal direction, each as a list of positions in
// `members`.
std::vector<std::vector<uint32_t>> clusterByNormal(const std::vector<uint32_t>& members,
                                                   const std::vector<Eigen::Vector3f>& normals, float cos_limit) {
  std::vector<std::vector<uint32_t>> clusters;
  for (uint32_t index : members) {
    auto it = std::find_if(clusters.begin(), clusters.end(), [&](const auto& cluster) {
      return normals[cluster.front()].dot(normals[index]) >= cos_limit;
    });
    if (it == clusters.end()) {
      clusters.push_back({index});
    } else {
      it->push_back(index);
    }
  }
  return clusters;
}

uint32_t nearestToCentroid(const std::vector<uint32_t>& members, const std::vector<Eigen::Vector3f>& points) {
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  for (uint32_t i : members) centroid += points[i];
  centroid /= static_cast<float>(members.size());
  return *std::min_element(members.begin(), members.end(), [&](uint32_t a, uint32_t b) {
    return (points[a] - centroid).squaredNorm() < (points[b] - centroid).squaredNorm();
  });
}

}  // namespace

float approximateDiameter(const std::vector<Eigen::Vector3f>& points) {
  if (points.size() < 2) return 0.0f;
  std::vector<uint32_t> candidates(points.size());
  for (uint32_t i = 0; i < candidates.size(); ++i) candidates[i] = i;
  if (points.size() > 3000) {
    Eigen::Vector3f lo = points[0], hi = points[0];
    for (const auto& p : points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    candidates = voxelSubsample(points, nullptr, (hi - lo).norm() / 150.0f, 0.0f);
  }
  float best_sq = 0.0f;
  for (std::size_t a = 0; a < candidates.size(); ++a) {
    for (std::size_t b = a + 1; b < candidates.size(); ++b) {
      best_sq = std::max(best_sq, (points[candidates[a]] - points[candidates[b]]).squaredNorm());
    }
  }
  return std::sqrt(best_sq);
}

std::vector<uint32_t> voxelSubsample(const std::vector<Eigen::Vector3f>& points,
                                     const std::vector<Eigen::Vector3f>* normals, float step, float cluster_angle) {
  if (points.empty()) return {};
  Eigen::Vector3f origin = points[0];
  for (const auto& p : points) origin = origin.cwiseMin(p);

  VoxelIds voxel_ids(points.size() / 4 + 16);
  std::vector<uint32_t> voxel_of(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    voxel_of[i] = voxel_ids.idOf(packCell(cellOf(points[i], origin, step)));

  // Counting sort of the points by voxel keeps this O(n) for million-point scenes.
  std::vector<uint32_t> start(voxel_ids.count() + 1, 0);
  for (uint32_t v : voxel_of) ++start[v + 1];
  for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<uint32_t> sorted(points.size());
  std::vector<uint32_t> cursor(start.begin(), start.end() - 1);
  for (uint32_t i = 0; i < points.size(); ++i) sorted[cursor[voxel_of[i]]++] = i;

  const bool cluster = normals != nullptr && cluster_angle > 0.0f;
  const float cos_limit = std::cos(cluster_angle);
  std::vector<uint32_t> kept;
  kept.reserve(voxel_ids.count());
  std::vector<uint32_t> members;
  for (uint32_t v = 0; v < voxel_ids.count(); ++v) {
    members.assign(sorted.begin() + start[v], sorted.begin() + start[v + 1]);
    if (!cluster) {
      kept.push_back(nearestToCentroid(members, points));
      continue;
    }
    for (const auto& group : clusterByNormal(members, *normals, cos_limit)) {
      kept.push_back(nearestToCentroid(group, points));
    }
  }
  std::sort(kept.begin(), kept.end());  // stable order, independent of hashing
  return kept;
}

void PlaneFit::add(const Eigen::Vector3f& p) {
  const Eigen::Vector3d q = p.cast<double>();
  sum_ += q;
  sum_outer_ += q * q.transpose();
  ++count_;
}

std::optional<Eigen::Vector3f> PlaneFit::normal(std::size_t min_neighbours) const {
  if (count_ < std::max<std::size_t>(min_neighbours, 3)) return std::nullopt;
  const Eigen::Vector3d mean = sum_ / static_cast<double>(count_);
  const Eigen::Matrix3d covariance = sum_outer_ / static_cast<double>(count_) - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(covariance);
  const Eigen::Vector3d eigenvalues = solver.eigenvalues();  // ascending
  // A line or a single point has two vanishing eigenvalues: no plane, no normal.
  if (!(eigenvalues[1] > 1e-12 * std::max(eigenvalues[2], 1e-30))) return std::nullopt;
  return solver.eigenvectors().col(0).normalized().cast<float>();
}

}  // namespace binpick::estimation
